#!/usr/bin/env bash
# The sanitizer part of the test command (scripts/test.sh runs it after the
# suite; docs/decisions/test-tiers.md):
#  1. every libFuzzer harness of fuzz/ (clang, ASan + UBSan) replays its seed
#     corpus and then makes a bounded, deterministic run (-seed=1, FUZZ_RUNS
#     executions, default 10000): the same inputs on every machine, so a
#     finding is reproducible and never depends on the machine's speed;
#  2. the executable built the same way (build-fuzz/skybake) runs the tests
#     that drive skybake on hostile and shipped inputs (SKYBAKE_TEST_EXE),
#     so any ASan or UBSan report fails them.
# Needs the normal build (build/, for the test executables) and clang with
# its runtime (clang, libclang-rt-14-dev; scripts/install-deps.sh).
#   scripts/sanitize.sh            all of it
#   FUZZ_RUNS=200000 scripts/sanitize.sh    a longer fuzzing run
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${FUZZ_RUNS:-10000}"

# A fresh corpus: what earlier local runs found is not part of the check.
rm -rf build-fuzz/corpus build-fuzz/findings
./scripts/fuzz.sh all 0 -runs="$runs" -seed=1

cmake --build build-fuzz --parallel "$(nproc)" --target skybake skybake_vdb skybake_bc

# An ASan or UBSan report exits 86 (an exit code skybake never uses), so no
# test that expects a given code can mistake a report for a refusal.
export ASAN_OPTIONS="exitcode=86:detect_leaks=1:allocator_may_return_null=0"
export UBSAN_OPTIONS="halt_on_error=1:exitcode=86:print_stacktrace=1"
export SKYBAKE_TEST_EXE="$PWD/build-fuzz/skybake"
cli='HostileJson.*:BadPresets.*:Validate*:CheckTiling*:CliErrors.*:CliBasics.*:PlanStrict.*'
cli+=':BakeCommand.EveryShippedPresetBakesFiniteFiles:ExtremeWarnings.ShippedPlanetsRaiseNone'
io='HostileDds.*:HostileExr.*:HostileVdb.*'
build/tests/skybake_cli_tests --gtest_filter="$cli" --gtest_brief=1
build/tests/skybake_io_tests --gtest_filter="$io" --gtest_brief=1
echo "sanitize: fuzz harnesses and the sanitizer build of skybake found nothing"
