#!/usr/bin/env bash
# The skybake executable loads neither OpenImageIO nor OpenVDB nor libsquish
# (and the OpenMP runtime it needs) nor libhwy (whose initialiser calibrates a
# timer in every process) at start-up: none is among its DT_NEEDED
# entries nor anywhere in what the dynamic loader resolves (ldd); OpenVDB
# comes only with the VDB plugin beside it, libsquish with the
# block-compression plugin.
#   check_no_heavy_libraries.sh SKYBAKE
set -euo pipefail
exe="$1"
status=0
needed="$(readelf -d "$exe" | grep NEEDED || true)"
loaded="$(ldd "$exe")"
for lib in libOpenImageIO libopenvdb libsquish libgomp libhwy; do
  if grep -q "$lib" <<<"$needed$loaded"; then
    echo "check_no_heavy_libraries: $exe loads $lib at start-up:" >&2
    grep "$lib" <<<"$needed$loaded" >&2
    status=1
  fi
done
plugin="$(dirname "$exe")/libskybake_vdb.so"
if [ ! -f "$plugin" ]; then
  echo "check_no_heavy_libraries: no VDB plugin beside the executable: $plugin" >&2
  status=1
elif ! readelf -d "$plugin" | grep NEEDED | grep -q libopenvdb; then
  echo "check_no_heavy_libraries: $plugin does not link OpenVDB" >&2
  status=1
fi
bc_plugin="$(dirname "$exe")/libskybake_bc.so"
if [ ! -f "$bc_plugin" ]; then
  echo "check_no_heavy_libraries: no block-compression plugin beside the executable: $bc_plugin" >&2
  status=1
elif ! readelf -d "$bc_plugin" | grep NEEDED | grep -q libsquish; then
  echo "check_no_heavy_libraries: $bc_plugin does not link libsquish" >&2
  status=1
fi
[ $status -eq 0 ] && echo "check_no_heavy_libraries: $(wc -l <<<"$loaded") libraries, no OpenImageIO, no OpenVDB, no libsquish, no libhwy"
exit $status
