#!/usr/bin/env bash
# Installs the Debian packages skybake needs. Safe to run twice: it asks apt
# only for what is missing.
#   scripts/install-deps.sh          to build, test and bake (scripts/test.sh)
#   scripts/install-deps.sh bake     to build the tool and bake (scripts/bake.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-all}"
case "$mode" in all|bake) ;; *) echo "install-deps: unknown mode '$mode' (all or bake)" >&2; exit 2 ;; esac

# What building `skybake` (and its VDB and BC plugins) needs.
packages=(
  build-essential cmake ninja-build pkg-config
  libopenvdb-dev libboost-iostreams-dev
  libopenexr-dev libimath-dev
  libglm-dev nlohmann-json3-dev rapidjson-dev libcli11-dev libtbb-dev zlib1g-dev
  libfmt-dev libspdlog-dev
  libsquish-dev libhwy-dev
  ccache
)
# What the tests, benchmarks and sanitizer checks add: test frameworks, the
# independent readers (OpenImageIO, OpenEXR's and OpenVDB's tools, nvtt,
# Pillow, Blender: docs/decisions/test-tiers.md), the shader
# compiler and a software GL, clang with its sanitizer and fuzzer runtime;
# Slurm and munge for the build-farm end-to-end test.
if [ "$mode" = all ]; then
  packages+=(
    clang-format libopenvdb-tools libopenimageio-dev openimageio-tools openexr
    libgtest-dev libgmock-dev libbenchmark-dev
    libnvtt-bin python3-pil blender
    glslang-tools libegl-dev libegl-mesa0 libgl1-mesa-dri libgles-dev
    clang libclang-rt-14-dev
    slurmctld slurmd slurm-client munge
  )
  # Node.js runs independent readers in some tests; a machine may already have
  # it from another source (whose npm conflicts with Debian's), so ask apt only
  # when there is no node at all.
  if ! command -v node >/dev/null 2>&1; then packages+=(nodejs npm); fi
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  echo "install-deps: installing ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The npm packages the tests read files with, pinned by tests/js/package-lock.json.
if [ "$mode" = all ] && { [ ! -d tests/js/node_modules ] || [ tests/js/package-lock.json -nt tests/js/node_modules ]; }; then
  echo "install-deps: npm packages for tests/js"
  (cd tests/js && npm ci --no-audit --no-fund --loglevel=error)
fi
