#!/usr/bin/env bash
# Configures and builds skybake (Release) into build/ (or $SKYBAKE_BUILD_DIR).
# Used by bake.sh and test.sh. Arguments are build targets (default: all).
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${SKYBAKE_BUILD_DIR:-build}"
configure=(-DCMAKE_BUILD_TYPE=Release)
if command -v ninja >/dev/null 2>&1; then configure+=(-G Ninja); fi
# ccache, where a developer installed it, shares objects between build folders.
if command -v ccache >/dev/null 2>&1; then configure+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
if [ ! -f "$dir/CMakeCache.txt" ]; then
  cmake -S . -B "$dir" "${configure[@]}"
fi
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$dir" --parallel "$(nproc)" "${targets[@]}"
