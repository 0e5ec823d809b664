#!/usr/bin/env bash
# The one command of a fresh machine: installs what is missing, builds, and
# bakes the default presets into out/. Extra arguments go to `skybake bake`
# (e.g. --force, --threads 2).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh skybake  # the tool only: tests and benchmarks are not needed to bake
./build/skybake bake presets/*.json presets/clouds/ -o out "$@"
