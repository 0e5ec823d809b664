#!/usr/bin/env bash
# Peak memory of `info` and `check-tiling` on the largest outputs the shipped
# presets write, against their memory budget (--max-memory, default 1 GiB;
# docs/formats.md "Reading files skybake did not write"). Bakes every scene
# of presets/*.json into a scratch folder, takes the COUNT largest files
# (.exr, .dds, .ktx2, .vdb) and runs each command once per file under
# /usr/bin/time, printing a Markdown table of the peak resident set sizes
# (check-tiling exits 1 on a table that is not meant to tile).
#
#   bench/read_memory.sh [SKYBAKE]        (default: build/skybake)
#   env: COUNT (6), OUT (a fresh scratch folder; an existing bake is reused)
#
# Not a test: figures depend on the machine (allocator, thread count).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
exe="${1:-$repo/build/skybake}"
COUNT="${COUNT:-6}"
[ -x "$exe" ] || { echo "read_memory: $exe: not an executable" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "read_memory: needs /usr/bin/time (apt-get install time)" >&2; exit 2; }

if [ -n "${OUT:-}" ]; then
  out="$OUT"
else
  out="$(mktemp -d)"
  trap 'rm -rf "$out"' EXIT
fi
"$exe" bake "$repo"/presets/*.json -o "$out" -q >/dev/null

peak_mib() {  # command args...: the peak RSS in MiB, and the exit code
  local log rc
  log="$(mktemp)"
  set +e
  /usr/bin/time -f '%M' -o "$log" "$exe" "$@" >/dev/null 2>&1
  rc=$?
  set -e
  tail -n 1 "$log" | awk -v rc="$rc" '{ printf "%.1f (exit %d)", $1 / 1024, rc }'
  rm -f "$log"
}

echo "| file | bytes | info peak MiB | check-tiling peak MiB |"
echo "|---|---:|---:|---:|"
find "$out" -type f \( -name '*.exr' -o -name '*.dds' -o -name '*.ktx2' -o -name '*.vdb' \) \
    -printf '%s %p\n' | sort -n | tail -n "$COUNT" |
while read -r bytes file; do
  echo "| ${file#"$out"/} | $bytes | $(peak_mib info "$file") | $(peak_mib check-tiling "$file") |"
done
echo
echo "budget: 1024 MiB (--max-memory default); baseline: $(peak_mib --version) for --version"
