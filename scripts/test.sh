#!/usr/bin/env bash
# The one test command: installs what is missing, builds everything (tool,
# tests, benchmarks), then runs the test tiers (docs/testing.md) in order:
#   unit      every fast test, with a cut-down twin of each accuracy target
#   accuracy  the full-size targets against converged references and the path tracer
#   e2e       real GL on llvmpipe, ninja and a Slurm cluster on loopback
#   sanitize  the fuzz harnesses and an ASan + UBSan skybake under the
#             hostile-input tests (scripts/sanitize.sh)
# `.ci/run` calls exactly `./scripts/test.sh` (every tier).
#   scripts/test.sh                 every tier
#   scripts/test.sh unit            the inner loop
#   scripts/test.sh unit e2e        the tiers named, in that order
set -euo pipefail
cd "$(dirname "$0")/.."
tiers=("$@")
if [ ${#tiers[@]} -eq 0 ]; then tiers=(unit accuracy e2e sanitize); fi
for t in "${tiers[@]}"; do
  case "$t" in unit|accuracy|e2e|sanitize) ;;
    *) echo "test.sh: unknown tier '$t' (unit, accuracy, e2e or sanitize)" >&2; exit 2 ;;
  esac
done
./scripts/install-deps.sh
./scripts/build.sh
# The tests' scratch folders are named by process id, so each run starts
# with an empty one: kept, a developer's runs piled up 70 GB in a week.
rm -rf build/test_tmp
for t in "${tiers[@]}"; do
  echo "test.sh: tier $t"
  if [ "$t" = sanitize ]; then
    ./scripts/sanitize.sh
  else
    (cd build && ctest --output-on-failure --parallel "$(nproc)" --timeout 900 -L "^$t\$")
  fi
done
