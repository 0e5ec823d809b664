#!/usr/bin/env bash
# The one test command: installs what is missing, builds everything (tool,
# tests, benchmarks), runs the whole test suite, then the sanitizer checks
# (scripts/sanitize.sh: the fuzz harnesses and an ASan + UBSan skybake under
# the hostile-input tests). `.ci/run` calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
(cd build && ctest --output-on-failure --parallel "$(nproc)" --timeout 900)
./scripts/sanitize.sh
