#!/usr/bin/env bash
# Configures and builds skybake (Release) into build/ (or $SKYBAKE_BUILD_DIR).
# Used by bake.sh and test.sh. Arguments are build targets (default: all).
# SKYBAKE_TOOL_ONLY=1 configures without the tests and benchmarks, so their
# packages need not be installed (scripts/bake.sh on a machine that only bakes).
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${SKYBAKE_BUILD_DIR:-build}"
if [ "${SKYBAKE_TOOL_ONLY:-0}" = 1 ]; then with_tests=OFF; else with_tests=ON; fi
configure=(-DCMAKE_BUILD_TYPE=Release -DSKYBAKE_TESTS=$with_tests -DSKYBAKE_BENCH=$with_tests)
if command -v ninja >/dev/null 2>&1; then configure+=(-G Ninja); fi
# ccache, where a developer installed it, shares objects between build folders.
if command -v ccache >/dev/null 2>&1; then configure+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
# Configured once; again only when the folder was configured the other way.
if [ ! -f "$dir/CMakeCache.txt" ] || ! grep -q "^SKYBAKE_TESTS:BOOL=$with_tests$" "$dir/CMakeCache.txt"; then
  cmake -S . -B "$dir" "${configure[@]}"
fi
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$dir" --parallel "$(nproc)" "${targets[@]}"
