#!/usr/bin/env bash
# The layer map of docs/architecture.md ("Layer map"), checked on the sources:
# every `#include "<layer>/..."` in src/<layer>/ must name its own layer or
# one the map allows. Prints file:line and the broken rule for each
# violation and exits 1; exits 0 when the tree keeps the map.
#
# Usage: check_layers.sh SRC_DIR   (the src/ folder; ctest passes it)
set -euo pipefail

src="${1:?usage: check_layers.sh SRC_DIR}"
[ -d "$src" ] || { echo "check_layers: no such folder: $src" >&2; exit 2; }

# What each layer may include besides itself: the link graph of
# CMakeLists.txt, transitively closed. Keep in step with docs/architecture.md.
declare -A allowed=(
  [core]=""
  [atmosphere]="core"
  [verify]="core atmosphere"
  [reference]="core atmosphere verify"
  [noise]="core"
  [clouds]="core noise"
  [io]="core"
  [pipeline]="core atmosphere verify noise clouds io"
  [report]="core atmosphere verify reference noise clouds io pipeline"
  [farm]="core atmosphere verify noise clouds io pipeline"
  [cli]="core atmosphere verify reference noise clouds io pipeline report farm"
)

status=0
checked=0
for dir in "$src"/*/; do
  layer="$(basename "$dir")"
  if [ -z "${allowed[$layer]+set}" ]; then
    echo "$dir: folder '$layer' is not a layer of the map (add it to docs/architecture.md and this script)"
    status=1
    continue
  fi
  while IFS= read -r -d '' file; do
    line_no=0
    while IFS= read -r line || [ -n "$line" ]; do
      line_no=$((line_no + 1))
      # #include "target/...", also with spaces after # or before include.
      [[ "$line" =~ ^[[:space:]]*#[[:space:]]*include[[:space:]]*\"([^/\"]+)/ ]] || continue
      target="${BASH_REMATCH[1]}"
      checked=$((checked + 1))
      [ "$target" = "$layer" ] && continue
      if [ -z "${allowed[$target]+set}" ]; then
        echo "$file:$line_no: $layer includes \"$target/...\", which is not a layer of src/"
        status=1
        continue
      fi
      case " ${allowed[$layer]} " in
        *" $target "*) ;;
        *)
          echo "$file:$line_no: $layer may not include $target (rule: $layer may include" \
               "${allowed[$layer]:-only itself}${allowed[$layer]:+ and itself}; docs/architecture.md \"Layer map\")"
          status=1
          ;;
      esac
    done < "$file"
  done < <(find "$dir" -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) -print0 | sort -z)
done

if [ "$status" -eq 0 ]; then
  echo "layer map kept: $checked project includes checked"
fi
exit "$status"
