#!/usr/bin/env bash
# The one command of a fresh machine: installs what is missing, builds, and
# bakes the default presets into out/. Extra arguments go to `skybake bake`
# (e.g. --force, --threads 2).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh bake  # what building the tool needs, not the tests' packages
# The tool only: tests and benchmarks are not needed to bake. A folder that
# scripts/test.sh configured keeps its tests (nothing to reconfigure).
if [ -f build/CMakeCache.txt ] && grep -q "^SKYBAKE_TESTS:BOOL=ON$" build/CMakeCache.txt; then
  ./scripts/build.sh skybake
else
  SKYBAKE_TOOL_ONLY=1 ./scripts/build.sh skybake
fi
./build/skybake bake presets/*.json presets/clouds/ -o out "$@"
