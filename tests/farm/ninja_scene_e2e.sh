#!/usr/bin/env bash
# End to end: `plan --emit ninja` with scene edges (the default: one edge and
# one `skybake bake PRESET` process per scene, all its products its outputs)
# run by real ninja, against one local `skybake bake` of the same catalog.
# The per-product emission (`--edges product`) is ninja_e2e.sh's.
#
#   tests/farm/ninja_scene_e2e.sh [SKYBAKE]     (default: build/skybake)
#
# The catalog: a copy of presets/earth.json (Earth's five default products)
# and five generated scenes of two products each (transmittance and the
# multiple-scattering table that reads it).
#
# Checks:
#  1. the file has one edge per scene, none with --only, none reading a
#     stamp; `ninja -j 2` bakes the catalog byte-identical to a local bake
#     (outputs, stamps, manifests).
#  2. a second ninja run prints "no work to do".
#  3. touching a preset re-runs its scene's edge only (the shared atmosphere
#     file: every Earth scene's), changing no byte, stamp or file time; ninja
#     is quiet after (restat).
#  4. changing one product's setting (Earth's sky-view size) re-runs one
#     edge that rewrites that product's files and stamp only, identical to a
#     local re-bake; deleting one file restores it and touches nothing else.
#  5. a product made to fail (a folder on its output path): ninja exits
#     non-zero naming the scene's edge; with -k 0 every other scene completes;
#     the failed scene's stamps agree with its manifest. Once the cause is
#     gone, ninja re-runs that edge only, which bakes only what was missing
#     (the products finished before the failure keep their file times) and
#     ends byte-identical to a local bake.
#  6. --chunk 2 gives one edge per two scenes and the same bytes; with
#     --max-parallel 1 (a ninja pool) no two of them run at once under -j 2
#     (.ninja_log's start and end times), and --emit-file creates its folder.
#
# Exit 0 pass, 1 fail, 77 skip (ninja missing). Paths contain a space and a
# '$' on purpose: the emitted file must quote and escape them.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
skybake="${1:-${SKYBAKE:-$repo/build/skybake}}"
skybake="$(cd "$(dirname "$skybake")" && pwd)/$(basename "$skybake")"
[ -x "$skybake" ] || { echo "ninja_scene_e2e: no skybake executable at $skybake" >&2; exit 1; }
if ! command -v ninja >/dev/null; then
  echo "ninja_scene_e2e: SKIP: ninja is not installed (apt-get install ninja-build)"
  exit 77
fi

T="$(mktemp -d "${TMPDIR:-/tmp}/skybake scene e2e.XXXXXX")"
status=1
cleanup() {
  if [ "$status" -eq 0 ]; then rm -rf "$T"; else echo "ninja_scene_e2e: FAILED; files kept in '$T'" >&2; fi
}
trap cleanup EXIT

fail() { echo "ninja_scene_e2e: FAIL: $*" >&2; exit 1; }
ok() { echo "ok   $*"; }

. "$here/e2e_checks.sh"  # same_outputs, edges_run

# Name, size and modification time of every baked file and stamp.
snapshot() { (cd "$1" && find . -type f ! -name '.ninja_*' ! -name .skybake.lock -printf '%p %s %T@\n' | sort); }
# The files (./scene/name) whose line differs between two snapshots.
changed() { diff <(echo "$1") <(echo "$2") | awk '/^[<>]/ { print $2 }' | sort -u || true; }

run_ninja() {  # ninja args...; output in $nlog, exit code in $rc
  rc=0
  nlog="$(timeout 300 ninja "$@" 2>&1)" || rc=$?
}

cat="$T/catalog \$dir"
outd="$T/out \$dir"
ref="$T/ref"
"$here/make_catalog.sh" -s 64x32 -p transmittance,multiscattering 5 "$cat" >/dev/null
cp "$repo/presets/earth.json" "$cat/earth.json"  # references atmospheres/earth.json, as there
scenes=6
earth_products="transmittance multiscattering skyview aerial_perspective sky_preview"

# 1. One edge per scene; ninja bakes the catalog like one local bake.
"$skybake" plan "$cat" --emit ninja -o "$outd" --emit-file "$T/build.ninja" 2>/dev/null
[ "$(grep -c '^build .*: bake ' "$T/build.ninja")" -eq "$scenes" ] ||
  fail "build.ninja should have $scenes bake edges (one per scene):
$(cat "$T/build.ninja")"
grep -q -- '--only' "$T/build.ninja" && fail "a scene edge bakes with --only"
grep '^build .*: bake ' "$T/build.ninja" | sed 's/^.*: bake //' | grep -q '\.stamp' &&
  fail "a scene edge reads a stamp (a scene's dependencies stay in its process)"
earth_edge="$(grep "^build .*: bake .*/earth.json " "$T/build.ninja")"
for p in $earth_products; do
  grep -q "earth/.stamps/$p.stamp .*|" <<<"$earth_edge" || fail "Earth's edge does not output $p's stamp"
done
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] || fail "ninja exited $rc:
$nlog"
[ "$(edges_run "$nlog")" -eq "$scenes" ] || fail "ninja ran $(edges_run "$nlog") edges, expected $scenes:
$nlog"
"$skybake" bake "$cat"/*.json -o "$ref" --threads 2 --quiet
same_outputs "$ref" "$outd"
ok "1. $scenes scene edges (Earth's has its 5 products' stamps); ninja -j 2 == one local bake, byte for byte"

# 2. Nothing to do the second time.
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] && grep -q 'no work to do' <<<"$nlog" || fail "second ninja run did work:
$nlog"
ok "2. second ninja run: no work to do"

# 3. Touch: the edges re-run as no-ops; restat keeps ninja quiet after.
before="$(snapshot "$outd")"
touch "$cat/earth.json"
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] && [ "$(edges_run "$nlog")" -eq 1 ] && grep -q 'bake earth$' <<<"$nlog" ||
  fail "touching earth.json should re-run Earth's edge only:
$nlog"
[ "$(snapshot "$outd")" = "$before" ] || fail "a no-op re-run changed files or stamps:
$(changed "$before" "$(snapshot "$outd")")"
run_ninja -f "$T/build.ninja" -j 2
grep -q 'no work to do' <<<"$nlog" || fail "ninja not quiet after a restat no-op:
$nlog"
touch "$cat/atmospheres/earth.json"  # earth, earth_000, earth_003
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] && [ "$(edges_run "$nlog")" -eq 3 ] ||
  fail "touching atmospheres/earth.json should re-run the 3 Earth scenes' edges:
$nlog"
[ "$(snapshot "$outd")" = "$before" ] || fail "a no-op re-run changed files or stamps"
run_ninja -f "$T/build.ninja" -j 2
grep -q 'no work to do' <<<"$nlog" || fail "ninja not quiet after restat no-ops: $nlog"
ok "3. touch re-ran 1, then 3 scene edges as no-ops (bytes, stamps, times unchanged; then no work)"

# 4. One product's input changes: its edge runs, only that product is rebaked.
sed -i 's/"product": "skyview", "size": \[192, 108\]/"product": "skyview", "size": [96, 54]/' "$cat/earth.json"
grep -q '"size": \[96, 54\]' "$cat/earth.json" || fail "could not edit earth.json's sky-view size"
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] && [ "$(edges_run "$nlog")" -eq 1 ] || fail "editing earth.json should run its edge only:
$nlog"
got="$(changed "$before" "$(snapshot "$outd")")"
want="$(printf '%s\n' ./earth/.stamps/skyview.stamp ./earth/bake_log.json ./earth/manifest.json \
  ./earth/skyview.dds ./earth/skyview.exr | sort)"
[ "$got" = "$want" ] || fail "a sky-view size change should rewrite sky-view's files, its stamp, the manifest and the bake log only; changed:
$got"
run_ninja -f "$T/build.ninja" -j 2
grep -q 'no work to do' <<<"$nlog" || fail "ninja not quiet after the re-bake: $nlog"
"$skybake" bake "$cat/earth.json" -o "$ref" --quiet
same_outputs "$ref" "$outd"
before="$(snapshot "$outd")"
rm "$outd/earth/aerial_perspective.dds"
run_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] && [ "$(edges_run "$nlog")" -eq 1 ] && grep -q 'bake earth$' <<<"$nlog" ||
  fail "deleting earth/aerial_perspective.dds should re-run Earth's edge only:
$nlog"
got="$(changed "$before" "$(snapshot "$outd")")"
want="$(printf '%s\n' ./earth/aerial_perspective.dds ./earth/aerial_perspective.exr \
  ./earth/bake_log.json ./earth/manifest.json | sort)"
[ "$got" = "$want" ] || fail "restoring aerial_perspective.dds should rewrite that product's files only; changed:
$got"
same_outputs "$ref" "$outd"
run_ninja -f "$T/build.ninja" -j 2
grep -q 'no work to do' <<<"$nlog" || fail "ninja not quiet after restoring a file: $nlog"
ok "4. a sky-view size edit rebaked sky-view alone (== local re-bake); a deleted file was restored alone"

# 5. A failing product fails its scene's edge; the other scenes go on (-k 0).
outf="$T/out fail"
"$skybake" plan "$cat" --emit ninja -o "$outf" --emit-file "$T/fail.ninja" 2>/dev/null
mkdir -p "$outf/earth/skyview.exr"  # the rename onto it fails
run_ninja -f "$T/fail.ninja" -j 2 -k 0
frc=$rc
[ "$frc" -ne 0 ] || fail "ninja succeeded although earth/skyview cannot be written:
$nlog"
grep -q "^FAILED: .*earth/.stamps/transmittance.stamp" <<<"$nlog" || fail "ninja does not name Earth's edge:
$nlog"
grep -q "skybake: error: .*earth/skyview.exr" <<<"$nlog" || fail "skybake's error is not reported:
$nlog"
for s in $(cd "$ref" && find . -path '*/.stamps/*.stamp' ! -path './earth/*' | sort); do
  cmp -s "$ref/$s" "$outf/$s" || fail "with -k 0, the other scenes' stamp $s is missing or differs"
done
[ ! -e "$outf/earth/.stamps/skyview.stamp" ] || fail "the failed product got a stamp"
plan="$("$skybake" plan "$cat/earth.json" -o "$outf")"
finished=""
for p in $earth_products; do
  if [ -e "$outf/earth/.stamps/$p.stamp" ]; then
    grep -qE "^  $p +write .*up to date$" <<<"$plan" ||
      fail "the stamp of earth/$p exists but skybake does not find it current:
$plan"
    finished="$finished $p"
  fi
done
grep -qw transmittance <<<"$finished" || fail "transmittance, baked before sky-view, has no stamp"
kept="$(cd "$outf" && find ./earth -name 'transmittance.*' -printf '%p %T@\n' | sort)"
rmdir "$outf/earth/skyview.exr"
run_ninja -f "$T/fail.ninja" -j 2
[ "$rc" -eq 0 ] && [ "$(edges_run "$nlog")" -eq 1 ] && grep -q 'bake earth$' <<<"$nlog" ||
  fail "after the fix, ninja should re-run Earth's edge only:
$nlog"
[ "$(cd "$outf" && find ./earth -name 'transmittance.*' -printf '%p %T@\n' | sort)" = "$kept" ] ||
  fail "the re-run baked transmittance again although it finished before the failure"
same_outputs "$ref" "$outf"
ok "5. failing earth/skyview: ninja exit $frc, Earth's edge named, the other $((scenes - 1)) scenes completed, stamps of [$finished ] agree with the manifest; after the fix 1 edge finished it, == local bake"

# 6. --chunk 2: one edge per two scenes, the same bytes; one at a time.
outc="$T/out chunk"
chunk_file="$T/new folder/chunk.ninja"
"$skybake" plan "$cat" --emit ninja --chunk 2 --max-parallel 1 -o "$outc" \
  --emit-file "$chunk_file" 2>/dev/null || fail "--emit-file into a folder not made yet failed"
[ "$(grep -c '^build .*: bake ' "$chunk_file")" -eq $((scenes / 2)) ] ||
  fail "chunk.ninja should have $((scenes / 2)) edges"
run_ninja -f "$chunk_file" -j 2
[ "$rc" -eq 0 ] && [ "$(edges_run "$nlog")" -eq $((scenes / 2)) ] || fail "ninja over chunks exited $rc:
$nlog"
same_outputs "$ref" "$outc"
# .ninja_log (v5): start and end in ms of each edge, one line per output of
# it. Sorted by start, an edge may not start before the previous one ended.
overlaps="$(grep -v '^#' "$outc/.ninja_log" | cut -f1,2 | sort -u -n |
  awk 'NR > 1 && $1 < end { n++ } { end = $2 } END { print n + 0 }')"
[ "$overlaps" -eq 0 ] || fail "--max-parallel 1: $overlaps edges ran beside another"
run_ninja -f "$chunk_file" -j 2
grep -q 'no work to do' <<<"$nlog" || fail "second ninja run over chunks did work: $nlog"
ok "6. --chunk 2 --max-parallel 1: $((scenes / 2)) edges one at a time == local bake; then no work"

status=0
echo "ninja_scene_e2e: PASS"
