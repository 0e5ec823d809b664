#!/usr/bin/env bash
# End to end: a generated catalog baked through `skybake plan --emit ninja
# --edges product` (one edge per product) and ninja, against one local
# `skybake bake` of the same catalog. The default scene edges are
# ninja_scene_e2e.sh's.
#
#   tests/farm/ninja_e2e.sh [SKYBAKE]     (default: build/skybake)
#
# Checks:
#  1. `ninja -j 2` bakes the catalog; every output, stamp and manifest (less
#     times) is byte-identical to a local `skybake bake CAT/*.json`.
#  2. a second ninja run prints "no work to do"; `bake --only P` reads P's
#     current dependency from disk instead of computing it (when a product
#     with dependencies is registered).
#  3. touching a preset (or the atmosphere file Earth variants reference)
#     re-runs exactly its edges, but they change no stamp, no output byte and
#     no file time, and ninja is quiet again afterwards (restat);
#     editing a preset re-bakes just that scene, identical to a local re-bake;
#     deleting an output file re-runs its edge, which restores it.
#  4. a product made to fail (a folder squatting on its output path, so the
#     final rename fails) fails its edge: ninja exits non-zero and names it,
#     its dependents do not run (when a product with dependencies is
#     registered), and with -k 0 every independent edge still completes;
#     a whole-scene bake failing at its second product leaves stamps that
#     agree with the manifest.
#  5. concurrent `skybake bake` processes writing into one scene folder
#     (two presets of one scene with different outputs, the same output twice,
#     and --only of two products of one preset when a dependent product
#     exists) leave a manifest with every entry, valid files, no temporaries.
#  6. the --emit slurm script's array tasks, run here one by one, give the
#     same bytes; on an empty catalog it is refused or a no-op.
#
# Exit 0 pass, 1 fail, 77 skip (ninja missing). Paths contain a space and a
# '$' on purpose: the emitted file must quote and escape them.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
skybake="${1:-${SKYBAKE:-$repo/build/skybake}}"
skybake="$(cd "$(dirname "$skybake")" && pwd)/$(basename "$skybake")"
[ -x "$skybake" ] || { echo "ninja_e2e: no skybake executable at $skybake" >&2; exit 1; }
if ! command -v ninja >/dev/null; then
  echo "ninja_e2e: SKIP: ninja is not installed (apt-get install ninja-build)"
  exit 77
fi

T="$(mktemp -d "${TMPDIR:-/tmp}/skybake ninja e2e.XXXXXX")"
status=1
cleanup() {
  if [ "$status" -eq 0 ]; then rm -rf "$T"; else echo "ninja_e2e: FAILED; files kept in '$T'" >&2; fi
}
trap cleanup EXIT

fail() { echo "ninja_e2e: FAIL: $*" >&2; exit 1; }
ok() { echo "ok   $*"; }

. "$here/e2e_checks.sh"  # same_outputs, edges_run, find_dependent_product

# Name, size and modification time of every baked file and stamp.
snapshot() { (cd "$1" && find . -type f ! -name '.ninja_*' ! -name .skybake.lock -printf '%p %s %T@\n' | sort); }

run_ninja() {  # ninja args...; output in $nlog, exit code in $rc
  rc=0
  nlog="$(timeout 300 ninja "$@" 2>&1)" || rc=$?
}

cat="$T/catalog \$dir"  # '$' must reach ninja as "$$"
outd="$T/out \$dir"
ref="$T/ref"
# Small LUTs: the test is about the graph, not the numerics.
"$here/make_catalog.sh" -s 64x32 20 "$cat"
dep="$(find_dependent_product)"
if [ -n "$dep" ]; then
  # Three more scenes whose second product reads their transmittance.
  "$here/make_catalog.sh" -s 64x32 -i 20 -p "transmittance,$dep" 3 "$cat"
  dep_scene=earth_021
  echo "ninja_e2e: dependent product: $dep (scenes 20-22 request transmittance,$dep)"
else
  dep_scene=""
  echo "ninja_e2e: no registered product has dependencies yet: the dependent parts of checks 2b, 4, 4b and 5 are skipped"
fi
scenes=$(find "$cat" -maxdepth 1 -name '*.json' | wc -l)
nodes=$scenes  # one node per product: 20 scenes x 1 (+ 3 scenes x 2)
[ -z "$dep" ] || nodes=$((scenes + 3))

# 1. ninja bakes the catalog like one local bake.
"$skybake" plan "$cat" --emit ninja --edges product -o "$outd" --emit-file "$T/build.ninja"
[ "$(grep -c '^build .*: bake ' "$T/build.ninja")" -eq "$nodes" ] ||
  fail "build.ninja should have $nodes bake edges"
grep -q 'restat = 1' "$T/build.ninja" || fail "build.ninja: the bake rule has no restat"
t0=$(date +%s.%N)
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] || fail "ninja exited $rc:
$nlog"
[ "$(edges_run "$nlog")" -eq "$nodes" ] || fail "ninja ran $(edges_run "$nlog") edges, expected $nodes:
$nlog"
t1=$(date +%s.%N)
"$skybake" bake "$cat"/*.json -o "$ref" --threads 2 --quiet
t2=$(date +%s.%N)
same_outputs "$ref" "$outd"
ok "1. ninja -j 2 baked $nodes products of $scenes scenes ($(awk "BEGIN{printf \"%.2f\", $t1-$t0}") s; one bake process: $(awk "BEGIN{printf \"%.2f\", $t2-$t1}") s), byte-identical to a local bake"

# 2. Nothing to do the second time.
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] && grep -q 'no work to do' <<<"$nlog" || fail "second ninja run did work:
$nlog"
ok "2. second ninja run: no work to do"

# 2b. `bake --only DEP` reads its dependency from disk when it is current (the
#     dependency is its own farm node), instead of computing it again.
if [ -n "$dep" ]; then
  json="$("$skybake" bake "$cat/$dep_scene.json" --only "$dep" -o "$outd" --force --json)"
  json_list() { awk -v key="\"$1\": [" 'index($0, key) { on = 1; if ($0 ~ /\]/) on = 0; next } on && /\]/ { on = 0 } on { gsub(/[ ",]/, ""); print }' <<<"$json"; }
  json_list loaded | grep -qx transmittance && ! json_list computed | grep -qx transmittance ||
    fail "bake --only $dep recomputed its current dependency instead of reading it from disk:
computed: $(json_list computed | tr '\n' ' ') loaded: $(json_list loaded | tr '\n' ' ')"
  same_outputs "$ref" "$outd"
  ok "2b. bake --only $dep read the current transmittance from disk (and wrote the same bytes)"
else
  echo "skip 2b. bake --only reading a current dependency from disk: no dependent product registered yet"
fi

# 3. Touching inputs re-runs their edges as no-ops; restat keeps ninja quiet after.
before="$(snapshot "$outd")"
touch "$cat/mars_001.json"
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] || fail "ninja after touch exited $rc: $nlog"
[ "$(edges_run "$nlog")" -eq 1 ] && grep -q 'bake mars_001/transmittance' <<<"$nlog" ||
  fail "touching mars_001.json should re-run exactly its edge:
$nlog"
[ "$(snapshot "$outd")" = "$before" ] || fail "a no-op re-run changed files or stamps:
$(diff <(echo "$before") <(snapshot "$outd") || true)"
run_ninja -f "$T/build.ninja" -j 2
grep -q 'no work to do' <<<"$nlog" || fail "ninja not quiet after a restat no-op:
$nlog"
touch "$cat/atmospheres/earth.json"
earths=$(find "$cat" -maxdepth 1 -name 'earth_*.json' | wc -l)
earth_nodes=$earths
[ -z "$dep" ] || earth_nodes=$((earths + 1))  # earth_021 has two products
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] && [ "$(edges_run "$nlog")" -eq "$earth_nodes" ] ||
  fail "touching atmospheres/earth.json should re-run the $earth_nodes Earth edges:
$nlog"
[ "$(snapshot "$outd")" = "$before" ] || fail "a no-op re-run changed files or stamps"
run_ninja -f "$T/build.ninja" -j 2
grep -q 'no work to do' <<<"$nlog" || fail "ninja not quiet after restat no-ops: $nlog"
# A real change: only that scene's files and stamp change, like a local re-bake.
sed -i 's/"radius_km": 3386.19,/"radius_km": 3386.5,/' "$cat/mars_004.json"
grep -q '3386.5' "$cat/mars_004.json" || fail "could not edit mars_004.json"
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] && [ "$(edges_run "$nlog")" -eq 1 ] || fail "editing mars_004 should re-bake it only:
$nlog"
changed="$(diff <(echo "$before") <(snapshot "$outd") | grep '^>' | awk '{print $2}' | sort -u || true)"
grep -qv '^\./mars_004/' <<<"$changed" && fail "editing mars_004 changed other scenes: $changed"
grep -q '^\./mars_004/.stamps/transmittance.stamp$' <<<"$changed" || fail "mars_004's stamp did not change"
grep -q '^\./mars_004/transmittance.exr$' <<<"$changed" || fail "mars_004's EXR was not rewritten"
"$skybake" bake "$cat/mars_004.json" -o "$ref" --quiet
same_outputs "$ref" "$outd"
# A deleted output file: skybake finds it missing, so ninja must re-run its edge.
rm "$outd/tiny_planet_002/transmittance.dds"
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] && [ "$(edges_run "$nlog")" -eq 1 ] && grep -q 'bake tiny_planet_002/transmittance' <<<"$nlog" ||
  fail "deleting tiny_planet_002/transmittance.dds should re-run exactly its edge (are the files outputs of the edge?):
$nlog"
same_outputs "$ref" "$outd"
run_ninja -f "$T/build.ninja" -j 2
grep -q 'no work to do' <<<"$nlog" || fail "ninja not quiet after restoring a deleted file: $nlog"
ok "3. touch re-ran 1 and $earth_nodes edges as no-ops (stamps, bytes, times unchanged; then no work); an edit re-baked 1 scene, identical to a local re-bake; a deleted file was restored"

# 4. A failing product: its edge fails and is named, dependents do not run,
#    independent edges complete with -k 0. A part of the catalog, named by a
#    glob that skybake expands: scenes 0-5 and 20-22 (when they exist).
outf="$T/out fail"
entries=("$cat/*_00[0-5].json")
fnodes=6
if [ -n "$dep" ]; then entries+=("$cat/*_02[0-2].json"); fnodes=12; fi
"$skybake" plan "${entries[@]}" --emit ninja --edges product -o "$outf" --emit-file "$T/fail.ninja"
[ "$(grep -c '^build .*: bake ' "$T/fail.ninja")" -eq "$fnodes" ] || fail "fail.ninja should have $fnodes edges"
bad=${dep_scene:-earth_000}
mkdir -p "$outf/$bad/transmittance.exr"  # the rename onto it fails
run_ninja -f "$T/fail.ninja" -j 2 -k 0
[ "$rc" -ne 0 ] || fail "ninja succeeded although $bad/transmittance cannot be written:
$nlog"
grep -q "^FAILED: .*$bad/.stamps/transmittance.stamp" <<<"$nlog" || fail "ninja does not name the failed edge:
$nlog"
grep -q "skybake: error: .*$bad/transmittance.exr" <<<"$nlog" || fail "skybake's error is not reported:
$nlog"
[ ! -e "$outf/$bad/.stamps/transmittance.stamp" ] || fail "a failed product got a stamp"
expected_ok=$((fnodes - 1))
if [ -n "$dep" ]; then
  expected_ok=$((fnodes - 2))
  grep -q "bake $bad/$dep" <<<"$nlog" && fail "the dependent $bad/$dep ran after its input failed:
$nlog"
  [ ! -e "$outf/$bad/.stamps/$dep.stamp" ] && ! ls "$outf/$bad/$dep".* >/dev/null 2>&1 ||
    fail "the dependent $bad/$dep was baked"
fi
done_stamps=$(find "$outf" -path '*/.stamps/*.stamp' | wc -l)
[ "$done_stamps" -eq "$expected_ok" ] || fail "with -k 0, $done_stamps of the $expected_ok independent products completed:
$nlog"
for s in $(cd "$outf" && find . -path '*/.stamps/*.stamp' | sort); do
  cmp -s "$outf/$s" "$ref/$s" || fail "stamp $s differs from the local bake"
done
if [ -n "$dep" ]; then dep_note="its dependent $dep did not run, "; else dep_note="(no dependent product registered), "; fi
ok "4. failing $bad/transmittance: ninja exit $rc, edge named, ${dep_note}$expected_ok independent products completed with -k 0"

# 4b. A whole-scene bake (what a job-array task runs) whose second product
#     fails: every stamp left behind must name an output the manifest lists
#     as current, or ninja would skip a product skybake considers unbaked.
if [ -n "$dep" ]; then
  outp="$T/out partial"
  mkdir -p "$outp/$dep_scene/$dep.exr"
  prc=0
  "$skybake" bake "$cat/$dep_scene.json" -o "$outp" --quiet 2>/dev/null || prc=$?
  [ "$prc" -ne 0 ] || fail "a bake whose $dep output cannot be written succeeded"
  plan="$("$skybake" plan "$cat/$dep_scene.json" -o "$outp")"
  for s in "$outp/$dep_scene/.stamps/"*.stamp; do
    [ -e "$s" ] || continue
    name="$(basename "$s" .stamp)"
    grep -qE "^  $name +write .*up to date$" <<<"$plan" ||
      fail "after a failed bake, the stamp of $name exists but skybake does not find $name current:
$plan"
  done
  ok "4b. a whole-scene bake failing at $dep: exit $prc, its stamps and manifest agree"
fi

# 5. Concurrent bakes into one scene folder.
conc="$T/concurrent"
mkdir -p "$conc/presets"
sed -e 's/"name": "mars_001"/"name": "shared"/' \
  -e 's/{ "product": "transmittance",/{ "product": "transmittance", "name": "t_a",/' \
  "$cat/mars_001.json" >"$conc/presets/a.json"
sed -e 's/"name": "tiny_planet_002"/"name": "shared"/' \
  -e 's/{ "product": "transmittance",/{ "product": "transmittance", "name": "t_b",/' \
  "$cat/tiny_planet_002.json" >"$conc/presets/b.json"
grep -q t_a "$conc/presets/a.json" && grep -q t_b "$conc/presets/b.json" || fail "could not write the shared-scene presets"
# Sequential reference.
"$skybake" bake "$conc/presets/a.json" -o "$conc/ref" --quiet
"$skybake" bake "$conc/presets/b.json" -o "$conc/ref" --quiet
if [ -n "$dep" ]; then
  cp "$cat/$dep_scene.json" "$conc/presets/c.json"
  cp -r "$cat/atmospheres" "$conc/presets/"  # c.json (Earth) references atmospheres/earth.json
  "$skybake" bake "$conc/presets/c.json" -o "$conc/ref" --quiet
fi

wait_all() {  # pids...: every process exits 0
  local p r=0
  for p in "$@"; do wait "$p" || r=$?; done
  [ "$r" -eq 0 ] || fail "a concurrent bake exited $r (see above)"
}
check_current() {  # presets...: plan reads the manifest and finds every output current
  local plan written current
  plan="$("$skybake" plan "$@" -o "$conc/out")" || fail "plan of $* failed"
  written="$(grep -cE '^  [a-z_]+ +write ' <<<"$plan" || true)"
  current="$(grep -E '^  [a-z_]+ +write ' <<<"$plan" | grep -c 'up to date$' || true)"
  [ "$written" -ge 1 ] && [ "$current" -eq "$written" ] ||
    fail "after concurrent bakes, the outputs of $* are not all current (lost manifest entry?):
$plan
$(cat "$conc/out/"*/manifest.json 2>/dev/null)"
}
rounds=6
procs=4
[ -z "$dep" ] || procs=6
for ((r = 0; r < rounds; r++)); do
  pids=()
  "$skybake" bake "$conc/presets/a.json" -o "$conc/out" --force --threads 1 --quiet & pids+=($!)
  "$skybake" bake "$conc/presets/b.json" -o "$conc/out" --force --threads 1 --quiet & pids+=($!)
  "$skybake" bake "$conc/presets/a.json" -o "$conc/out" --force --threads 1 --quiet & pids+=($!)
  "$skybake" bake "$conc/presets/b.json" -o "$conc/out" --force --threads 1 --quiet & pids+=($!)
  if [ -n "$dep" ]; then
    "$skybake" bake "$conc/presets/c.json" --only transmittance -o "$conc/out" --force --threads 1 --quiet & pids+=($!)
    "$skybake" bake "$conc/presets/c.json" --only "$dep" -o "$conc/out" --force --threads 1 --quiet & pids+=($!)
  fi
  wait_all "${pids[@]}"
  grep -q '"name": "t_a"' "$conc/out/shared/manifest.json" && grep -q '"name": "t_b"' "$conc/out/shared/manifest.json" ||
    fail "round $r: the shared manifest lost an entry:
$(cat "$conc/out/shared/manifest.json")"
  # One plan each: two scenes of one name in one run are refused.
  check_current "$conc/presets/a.json"
  check_current "$conc/presets/b.json"
  [ -z "$dep" ] || check_current "$conc/presets/c.json"
  tmp="$(find "$conc/out" -name '*.tmp-*')"
  [ -z "$tmp" ] || fail "temporaries left behind: $tmp"
done
# Both presets of "shared" write shared/manifest.json with their own "preset"
# field; compare the files and stamps, and the manifest entries via plan above.
for f in $(cd "$conc/ref" && find . -type f ! -name manifest.json ! -name bake_log.json ! -name .skybake.lock | sort); do
  cmp -s "$conc/ref/$f" "$conc/out/$f" || fail "concurrent bakes: $f is not byte-identical to a sequential bake"
done
[ -z "$dep" ] || same_outputs "$conc/ref/${dep_scene}" "$conc/out/${dep_scene}"
ok "5. $rounds rounds of $procs concurrent bakes into one folder: manifest keeps every entry, files identical, no temporaries"

# 6. The --emit slurm job-array script, its tasks run here one by one (the
#    Slurm run itself is in slurm_e2e.sh), and on an empty catalog.
"$skybake" plan "$cat" --emit slurm --chunk 4 -o "$T/out slurm" --emit-file "$T/bake.sbatch" 2>/dev/null
tasks=$(((scenes + 3) / 4))
grep -q "^#SBATCH --array=0-$((tasks - 1))\$" "$T/bake.sbatch" || fail "bake.sbatch should have $tasks array tasks"
for ((i = 0; i < tasks; i++)); do
  (cd "$T" && SLURM_ARRAY_TASK_ID=$i bash "$T/bake.sbatch") || fail "array task $i failed"
done
same_outputs "$ref" "$T/out slurm"
mkdir -p "$T/empty catalog"
erc=0
"$skybake" plan "$T/empty catalog" --emit slurm -o "$T/out empty" --emit-file "$T/empty.sbatch" 2>/dev/null || erc=$?
if [ "$erc" -eq 0 ]; then
  (cd "$T" && SLURM_ARRAY_TASK_ID=0 bash "$T/empty.sbatch" >/dev/null 2>&1) ||
    fail "--emit slurm on an empty catalog wrote a job array whose task fails"
fi
ok "6. --emit slurm --chunk 4: $tasks array tasks run locally == local bake; empty catalog: $([ "$erc" -eq 0 ] && echo "no-op script" || echo "refused, exit $erc")"

status=0
echo "ninja_e2e: PASS"
