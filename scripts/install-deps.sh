#!/usr/bin/env bash
# Installs every Debian package skybake needs to build, test and bake.
# Safe to run twice: it asks apt only for what is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang-format
  libopenvdb-dev libopenvdb-tools libboost-iostreams-dev
  libopenimageio-dev openimageio-tools
  libopenexr-dev openexr libimath-dev
  libglm-dev nlohmann-json3-dev rapidjson-dev libcli11-dev libtbb-dev zlib1g-dev
  libfmt-dev libspdlog-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libnvtt-bin
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
