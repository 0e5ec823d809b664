#!/usr/bin/env bash
# Builds the libFuzzer harnesses of fuzz/ (clang, ASan + UBSan, libFuzzer
# coverage) into build-fuzz/ and runs one for SECONDS:
#   scripts/fuzz.sh TARGET SECONDS [libFuzzer flags...]
# TARGET: preset_loader, dds_reader, exr_reader, vdb_reader, manifest_reader,
# ktx2_reader, ktx2_key_value, manifest_entry
# (the _fuzz suffix is optional), or all (each in turn for SECONDS).
# The corpus build-fuzz/corpus/TARGET keeps what earlier runs found; the
# seeds are fuzz/seeds/TARGET (committed, small), the shipped and bad presets
# and the small files fuzz_seeds writes with the project's writers. Findings
# (crash-*, leak-*, oom-*, timeout-*) are written to build-fuzz/findings/TARGET/;
# the exit status is non-zero when a run found one. The last lines give each
# run's executions and coverage (cov: edges, ft: features).
# Needs clang and the fuzzer runtime: apt-get install clang libclang-rt-14-dev.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
target="${1%_fuzz}"
seconds="$2"
shift 2
all=(preset_loader dds_reader exr_reader vdb_reader manifest_reader ktx2_reader ktx2_key_value
     manifest_entry)
if [ "$target" = all ]; then targets=("${all[@]}"); else targets=("$target"); fi
for t in "${targets[@]}"; do
  case " ${all[*]} " in *" $t "*) ;; *) echo "fuzz.sh: unknown target '$t' (one of ${all[*]}, all)" >&2; exit 2 ;; esac
done
if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz.sh: clang++ not found; apt-get install clang libclang-rt-14-dev" >&2
  exit 2
fi

dir=build-fuzz
if [ ! -f "$dir/CMakeCache.txt" ]; then
  configure=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKYBAKE_FUZZ=ON -DSKYBAKE_TESTS=OFF
             -DSKYBAKE_BENCH=OFF -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++)
  if command -v ninja >/dev/null 2>&1; then configure+=(-G Ninja); fi
  if command -v ccache >/dev/null 2>&1; then configure+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
  cmake -S . -B "$dir" "${configure[@]}"
fi
build=(--target fuzz_seeds --target skybake_vdb --target skybake_bc)  # VDB and BC are plugins
for t in "${targets[@]}"; do build+=(--target "${t}_fuzz"); done
cmake --build "$dir" --parallel "$(nproc)" "${build[@]}"

seeds="$dir/seeds"
rm -rf "$seeds" && "$dir/fuzz/fuzz_seeds" "$seeds"
mkdir -p "$seeds/preset_loader"
for f in presets/*.json presets/*/*.json tests/bad_presets/*.json tests/bad_presets/*/*.json; do
  cp "$f" "$seeds/preset_loader/$(echo "$f" | tr / _)"
done

status=0
summary=()
for t in "${targets[@]}"; do
  corpus="$dir/corpus/$t" findings="$dir/findings/$t"
  mkdir -p "$corpus" "$findings"
  extra=()
  [ -d "fuzz/seeds/$t" ] && extra+=("fuzz/seeds/$t")
  case "$t" in
    preset_loader) extra+=("$seeds/preset_loader"); dict=fuzz/json.dict ;;
    manifest_reader) extra+=("$seeds/manifest"); dict=fuzz/json.dict ;;
    ktx2_key_value | manifest_entry) extra+=("$seeds/$t"); dict=fuzz/json.dict ;;
    *) extra+=("$seeds/${t%_reader}"); dict= ;;
  esac
  flags=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2560 -malloc_limit_mb=2048
         -artifact_prefix="$findings/" -print_final_stats=1)
  [ -n "$dict" ] && flags+=(-dict="$dict")
  log="$dir/findings/$t.log"
  echo "== $t: ${seconds}s" >&2
  rc=0
  "$dir/fuzz/${t}_fuzz" "${flags[@]}" "$@" "$corpus" "${extra[@]}" >"$log" 2>&1 || rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  found=$(find "$findings" -maxdepth 1 -type f | wc -l)
  summary+=("$t: ${execs:-?} executions, cov ${cov:-?}, ft ${ft:-?}, corpus $(ls "$corpus" | wc -l), findings $found (exit $rc, log $log)")
  if [ "$rc" -ne 0 ] || [ "$found" -ne 0 ]; then status=1; tail -30 "$log" >&2; fi
done
printf '%s\n' "${summary[@]}"
exit "$status"
