#!/usr/bin/env bash
# Generates a catalog of N scene presets for the build-farm tests and benchmarks:
# variations of presets/earth.json, mars.json and tiny_planet.json (in turn),
# each with a distinct "name" (earth_000, mars_001, tiny_planet_002, ...) and
# slightly different physical parameters, so every scene has its own input hash.
#
#   tests/farm/make_catalog.sh [-p PRODUCT,...] [-s WxH] [-i FIRST] N DIR
#
#   -p  products each scene requests (default: transmittance). Products other
#       than transmittance get `{ "product": P }` (their defaults).
#   -s  transmittance size (default: the shipped presets' 256x64).
#   -i  index of the first preset (default 0): presets FIRST..FIRST+N-1, so
#       several calls can fill one folder with distinct scenes.
#
# The Earth variants reference DIR/atmospheres/earth.json (a copy of the
# shipped one), like presets/earth.json does: in a folder catalog that file is
# not a scene (it has no "outputs") and is skipped, and it is an input of every
# Earth variant. Existing files in DIR are overwritten; others are left alone.
set -euo pipefail

usage() {
  echo "usage: $0 [-p PRODUCT,...] [-s WxH] [-i FIRST] N DIR" >&2
  exit 2
}

products="transmittance"
size=""
first=0
while getopts "p:s:i:h" opt; do
  case "$opt" in
    p) products="$OPTARG" ;;
    s) size="$OPTARG" ;;
    i) first="$OPTARG" ;;
    *) usage ;;
  esac
done
shift $((OPTIND - 1))
[ $# -eq 2 ] || usage
count="$1"
dir="$2"
[[ "$count" =~ ^[0-9]+$ && "$first" =~ ^[0-9]+$ ]] || usage
if [ -n "$size" ] && ! [[ "$size" =~ ^[0-9]+x[0-9]+$ ]]; then usage; fi

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
mkdir -p "$dir/atmospheres"
cp "$repo/presets/atmospheres/earth.json" "$dir/atmospheres/earth.json"

# Decimal arithmetic (bash has integers only): num FORMAT EXPRESSION-IN-i.
num() { awk -v i="$3" "BEGIN { printf \"$1\", $2 }"; }

# The "outputs" array. $1: extra keys of the transmittance output (e.g. steps).
outputs() {
  local extra="$1" first=1 p tsize='[256, 64]'
  if [ -n "$size" ]; then tsize="[${size%x*}, ${size#*x}]"; fi
  printf '  "outputs": [\n'
  IFS=',' read -r -a list <<<"$products"
  for p in "${list[@]}"; do
    [ $first -eq 1 ] || printf ',\n'
    first=0
    if [ "$p" = transmittance ]; then
      printf '    { "product": "transmittance", "size": %s, "formats": ["exr", "dds"], "precision": "float"%s }' \
        "$tsize" "$extra"
    else
      printf '    { "product": "%s" }' "$p"
    fi
  done
  printf '\n  ]\n'
}

earth() {  # $1 index, $2 name
  cat <<EOF
{
  "name": "$2",
  "description": "Generated variation $1 of presets/earth.json (tests/farm/make_catalog.sh).",
  "planet": { "radius_km": $(num %.3f "6360 - i * 0.01" "$1"), "ground_albedo": [$(num %.3f "0.3 + (i % 7) * 0.01" "$1"), 0.3, 0.3] },
  "atmosphere": "atmospheres/earth.json",
$(outputs "")
}
EOF
}

mars() {
  cat <<EOF
{
  "name": "$2",
  "description": "Generated variation $1 of presets/mars.json (tests/farm/make_catalog.sh).",
  "planet": { "radius_km": 3386.19, "ground_albedo": [0.35, 0.22, 0.13] },
  "atmosphere": {
    "top_radius_km": $(num %.3f "3463.17 + i * 0.01" "$1"),
    "sun": { "illuminance": [0.4307, 0.4307, 0.4307], "angular_radius_rad": 0.003068 },
    "rayleigh": {
      "scattering_per_m": [19.918e-6, 13.57e-6, 5.75e-6],
      "density": { "exponential": { "scale_height_km": $(num %.3f "10.44 + (i % 5) * 0.1" "$1") } }
    },
    "mie": {
      "scattering_per_m": [53.618e-6, 53.618e-6, 53.618e-6],
      "absorption_per_m": [0.55309e-6, 0.55309e-6, 0.55309e-6],
      "phase": "cornette_shanks",
      "g": $(num %.3f "0.85 - (i % 3) * 0.01" "$1"),
      "density": { "exponential": { "scale_height_km": 3.095 } }
    }
  },
$(outputs "")
}
EOF
}

tiny_planet() {
  cat <<EOF
{
  "name": "$2",
  "description": "Generated variation $1 of presets/tiny_planet.json (tests/farm/make_catalog.sh).",
  "planet": { "radius_km": $(num %.3f "50 + i * 0.001" "$1"), "ground_albedo": [0.2, 0.3, 0.15] },
  "atmosphere": {
    "top_radius_km": $(num %.1f "80 + (i % 4)" "$1"),
    "rayleigh": {
      "scattering_per_m": [116.04e-6, 271.16e-6, 662.0e-6],
      "density": { "exponential": { "scale_height_km": 3 } }
    },
    "mie": {
      "scattering_per_m": [39.96e-6, 39.96e-6, 39.96e-6],
      "absorption_per_m": [4.44e-6, 4.44e-6, 4.44e-6],
      "g": $(num %.3f "0.75 + (i % 5) * 0.01" "$1"),
      "density": { "exponential": { "scale_height_km": 0.5 } }
    }
  },
$(outputs ', "steps": 64')
}
EOF
}

kinds=(earth mars tiny_planet)
for ((i = first; i < first + count; i++)); do
  kind="${kinds[i % 3]}"
  name="$(printf '%s_%03d' "$kind" "$i")"
  "$kind" "$i" "$name" >"$dir/$name.json"
done
echo "make_catalog: wrote $count scene presets ($products) to $dir"
