#!/usr/bin/env bash
# Installs every Debian package skybake needs to build, test and bake.
# Safe to run twice: it asks apt only for what is missing.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config clang-format
  libopenvdb-dev libopenvdb-tools libboost-iostreams-dev
  libopenimageio-dev openimageio-tools
  libopenexr-dev openexr libimath-dev
  libglm-dev nlohmann-json3-dev rapidjson-dev libcli11-dev libtbb-dev zlib1g-dev
  libfmt-dev libspdlog-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libnvtt-bin
  libsquish-dev
  glslang-tools libegl-dev libegl-mesa0 libgl1-mesa-dri libgles-dev
  python3-pil
)
# Node.js runs independent readers in some tests; a machine may already have
# it from another source (whose npm conflicts with Debian's), so ask apt only
# when there is no node at all.
if ! command -v node >/dev/null 2>&1; then packages+=(nodejs npm); fi

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
if [ ! -d tests/js/node_modules ] || [ tests/js/package-lock.json -nt tests/js/node_modules ]; then
  echo "install-deps: npm packages for tests/js"
  (cd tests/js && npm ci --no-audit --no-fund --loglevel=error)
fi
