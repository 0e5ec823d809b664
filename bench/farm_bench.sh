#!/usr/bin/env bash
# Whole-command timings of the build-farm paths (docs/farm.md, "Figures"):
#
#  A. a catalog of PRESETS (100) generated presets, from an empty output folder:
#     local `ninja -j 2` over `plan --emit ninja` (one skybake process per
#     product) against one `skybake bake CAT/*.json --threads 2` process; and
#     the no-op re-runs (everything current) of both;
#  B. skybake's process start-up (`skybake --version`), the fixed cost of
#     every ninja edge;
#  C. the srun path, on the loopback cluster of tests/farm/slurm_e2e.sh (two
#     emulated one-CPU nodes; needs root or an installed Slurm): one
#     `srun -N1 -n1 -c1 --exact --quiet true` job step against `true`, and a
#     20-preset catalog through ninja + srun against local ninja (both -j 2,
#     inside one `salloc -N2 -n2`), giving the per-product overhead of srun.
#
#   bench/farm_bench.sh [--no-slurm] [SKYBAKE]      (default: build/skybake)
#   env: RUNS (3), PRESETS (100), CLUSTER_PRESETS (20)   (not SRUN_*: slurm_e2e.sh
#        clears SLURM_*/SRUN_* variables so an outer job cannot leak in)
#
# Uses hyperfine when installed (as root it installs it), else date +%s.%N.
# Prints a Markdown table; the machine is whatever runs it, so quote the
# figures with the machine (cores, load).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
self="$here/$(basename "${BASH_SOURCE[0]}")"
RUNS="${RUNS:-3}"
PRESETS="${PRESETS:-100}"
CLUSTER_PRESETS="${CLUSTER_PRESETS:-20}"

mode=main
slurm=1
case "${1:-}" in
  --inside-cluster) mode=cluster; shift ;;
  --inside-allocation) mode=allocation; shift ;;
  --no-slurm) slurm=0; shift ;;
esac
skybake="${1:-${SKYBAKE:-$repo/build/skybake}}"
skybake="$(cd "$(dirname "$skybake")" && pwd)/$(basename "$skybake")"
export SKYBAKE="$skybake"
[ -x "$skybake" ] || { echo "farm_bench: no skybake executable at $skybake" >&2; exit 1; }
command -v ninja >/dev/null || { echo "farm_bench: ninja is not installed" >&2; exit 1; }

if [ "$mode" = main ] && ! command -v hyperfine >/dev/null && [ "$(id -u)" -eq 0 ]; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends hyperfine >/dev/null 2>&1 ||
    echo "farm_bench: could not install hyperfine; timing with date" >&2
fi

# measure LABEL PREPARE COMMAND [RUNS]: prints "| LABEL | mean ± sd | min |", sets $mean.
measure() {
  local label="$1" prepare="$2" cmd="$3" runs="${4:-$RUNS}" csv i t0 t1 times=()
  if command -v hyperfine >/dev/null; then
    csv="$(mktemp)"
    # Its warnings (short commands, outliers) would break the table.
    hyperfine --style none --runs "$runs" --prepare "${prepare:-true}" --export-csv "$csv" "$cmd" \
      >/dev/null 2>"$csv.err" || { cat "$csv.err" >&2; return 1; }
    rm -f "$csv.err"
    read -r mean sd min < <(awk -F, 'NR == 2 { print $2, $3, $7 }' "$csv")
    rm -f "$csv"
  else
    for ((i = 0; i < runs; i++)); do
      bash -c "${prepare:-true}"
      t0=$(date +%s.%N)
      bash -c "$cmd" >/dev/null
      t1=$(date +%s.%N)
      times+=("$(awk "BEGIN { print $t1 - $t0 }")")
    done
    read -r mean sd min < <(printf '%s\n' "${times[@]}" |
      awk '{ s += $1; q += $1 * $1; if (NR == 1 || $1 < m) m = $1 } END { v = q / NR - (s / NR)^2; printf "%.6f %.6f %.6f\n", s / NR, (v > 0 ? sqrt(v) : 0), m }')
  fi
  printf '| %-58s | %8.3f s ± %6.3f | %8.3f s |\n' "$label" "$mean" "$sd" "$min"
}
ratio() { awk "BEGIN { printf \"%.3f\", $1 }"; }

header() {
  echo
  echo "| $1 | mean ± sd ($RUNS runs unless noted) | min |"
  echo "|---|---|---|"
}

if [ "$mode" = allocation ]; then
  # Inside `salloc -N2 -n2`, in the folder prepared by --inside-cluster.
  T="$PWD"
  header "srun path, inside salloc -N2 -n2 (2 emulated 1-CPU nodes)"
  measure "srun -N1 -n1 -c1 --exact --quiet true (one job step, 10 runs)" "" \
    "srun -N1 -n1 -c1 --exact --quiet true" 10
  step=$mean
  measure "true (10 runs)" "" "true" 10
  step=$(ratio "$step - $mean")
  measure "ninja -j 2, $CLUSTER_PRESETS presets, local edges" "rm -rf '$T/out_local'" \
    "ninja -f '$T/local.ninja' -j 2"
  local_ninja=$mean
  measure "ninja -j 2, $CLUSTER_PRESETS presets, edges via srun" "rm -rf '$T/out_srun'" \
    "ninja -f '$T/srun.ninja' -j 2"
  per=$(ratio "($mean - $local_ninja) / ($CLUSTER_PRESETS / 2)")
  echo
  echo "srun job step overhead: $step s; per product through ninja + srun (2 slots): $per s more than local ninja"
  exit 0
fi

if [ "$mode" = cluster ]; then
  # Inside tests/farm/slurm_e2e.sh --with-cluster: SLURM_CONF points at it.
  T="$(mktemp -d /tmp/skybake-farm-bench-srun.XXXXXX)"
  trap 'rm -rf "$T"' EXIT
  "$repo/tests/farm/make_catalog.sh" "$CLUSTER_PRESETS" "$T/catalog" >/dev/null
  "$skybake" plan "$T/catalog" --emit ninja -o "$T/out_local" --emit-file "$T/local.ninja" 2>/dev/null
  "$skybake" plan "$T/catalog" --emit ninja --launcher "srun -N1 -n1 -c1 --exact --quiet" \
    -o "$T/out_srun" --emit-file "$T/srun.ninja" 2>/dev/null
  measure "salloc -Q -N2 -n2 true (allocation round trip)" "" "salloc -Q -N2 -n2 true"
  (cd "$T" && salloc -Q -N2 -n2 "$self" --inside-allocation)
  # The two output folders must agree.
  for f in $(cd "$T/out_local" && find . -name '*.exr' -o -name '*.dds'); do
    cmp -s "$T/out_local/$f" "$T/out_srun/$f" || { echo "farm_bench: $f differs between local and srun" >&2; exit 1; }
  done
  exit 0
fi

# --- main: the 100-preset catalog, local -------------------------------------------
T="$(mktemp -d /tmp/skybake-farm-bench.XXXXXX)"
trap 'rm -rf "$T"' EXIT
cat="$T/catalog"
"$repo/tests/farm/make_catalog.sh" "$PRESETS" "$cat" >/dev/null
"$skybake" plan "$cat" --emit ninja -o "$T/out_ninja" --emit-file "$T/build.ninja" 2>/dev/null
edges=$(grep -c '^build .*: bake ' "$T/build.ninja")

echo "farm_bench: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(command -v hyperfine >/dev/null && echo hyperfine || echo date), skybake $("$skybake" --version | awk '{print $2}')"
header "$PRESETS presets ($edges products, transmittance 256x64 exr+dds), 2 cores"
measure "skybake --version (process start-up, 10 runs)" "" "'$skybake' --version" 10
startup=$mean
measure "ninja -j 2 (one process per product), from empty" "rm -rf '$T/out_ninja'" \
  "ninja -f '$T/build.ninja' -j 2"
ninja_full=$mean
measure "skybake bake CAT/*.json --threads 2, from empty" "rm -rf '$T/out_bake'" \
  "'$skybake' bake '$cat'/*.json -o '$T/out_bake' --threads 2 --quiet"
bake_full=$mean
measure "ninja -j 2, everything current (no-op)" "" "ninja -f '$T/build.ninja' -j 2"
measure "skybake bake CAT/*.json, everything current (no-op)" "" \
  "'$skybake' bake '$cat'/*.json -o '$T/out_bake' --threads 2 --quiet"
measure "skybake plan CAT --emit ninja (plan $PRESETS presets)" "" \
  "'$skybake' plan '$cat' --emit ninja -o '$T/out_ninja' --emit-file '$T/again.ninja'"
echo
echo "ninja / one process: $(ratio "$ninja_full / $bake_full")x; ninja cost per product over one process: $(ratio "($ninja_full - $bake_full) / ($edges / 2)") s per slot (start-up alone: $(ratio "$startup") s)"
for f in $(cd "$T/out_bake" && find . -name '*.exr' -o -name '*.dds'); do
  cmp -s "$T/out_bake/$f" "$T/out_ninja/$f" || { echo "farm_bench: $f differs between ninja and bake" >&2; exit 1; }
done

if [ "$slurm" -eq 1 ]; then
  rc=0
  "$repo/tests/farm/slurm_e2e.sh" --with-cluster "$self" --inside-cluster "$skybake" || rc=$?
  [ "$rc" -ne 77 ] || echo "farm_bench: no Slurm cluster here (skipped the srun part)"
  [ "$rc" -eq 0 ] || [ "$rc" -eq 77 ] || exit "$rc"
fi
