#!/usr/bin/env bash
# What a farm adds per product: a scene baked by one process against the same
# scene under ninja, for both ninja emissions of `plan --emit ninja`:
#   --edges product  one skybake process per product (`bake PRESET --only P`);
#                    each pays its own start-up, loads and hashes the preset,
#                    and reads the products it depends on back from disk;
#   --edges scene    (the default) one process per scene (`bake PRESET`), so
#                    what ninja adds is its own run, its log and the stamps.
# Everything on one thread and one slot, from an empty output folder. The
# difference over one process, divided by the products, is the per-product
# overhead. The `plan --emit ninja` itself is a separate column (a farm runs
# it once per catalog change, not per product).
#
#   bench/farm_overhead.sh [SKYBAKE]          (default: build/skybake)
#   env: RUNS (9), PRESETS ("presets/earth.json")
#
# Runs are interleaved (one process, then each ninja, then again) so load
# affects all alike; medians of CPU (user + sys of the process tree, rusage)
# and wall. Not a test: figures depend on the machine and its load (printed
# with them, before and after).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
exe="${1:-$repo/build/skybake}"
RUNS="${RUNS:-9}"
PRESETS="${PRESETS:-presets/earth.json}"
[ -x "$exe" ] || { echo "farm_overhead: $exe: not an executable" >&2; exit 2; }
command -v ninja >/dev/null || { echo "farm_overhead: ninja is not installed" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$repo"

PYTHONPATH="$here" python3 - "$exe" "$RUNS" "$work" $PRESETS <<'EOF'
import os, shutil, statistics, subprocess, sys

from process_timing import machine, timed

exe, runs, work, presets = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
EDGES = ("product", "scene")

def fresh(path):
    shutil.rmtree(path, ignore_errors=True)
    return path

def emit_command(preset, edges):
    out = os.path.join(work, f"ninja_{edges}")
    build = os.path.join(work, f"{edges}.ninja")
    return out, build, [exe, "plan", preset, "--emit", "ninja", "--edges", edges, "-o", out,
                        "--emit-file", build, "--task-threads", "1"]

def count_edges(build):
    return sum(1 for line in open(build) if line.startswith("build ") and ": bake " in line)

print(f"runs per cell: {runs}; median CPU s (user+sys) / median wall s; {machine()}")
print()
print("| preset | products | one process | ninja -j 1, --edges product | ninja -j 1, --edges scene "
      "| plan --emit ninja | overhead per product (CPU): product edges | scene edges "
      "| overhead (CPU, % of one process): product edges | scene edges |")
print("|---|---|---|---|---|---|---|---|---|---|")
for preset in presets:
    out_one = os.path.join(work, "one")
    products = None
    for edges in EDGES:
        _, build, emit = emit_command(preset, edges)
        subprocess.run(emit, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if edges == "product":
            products = count_edges(build)
    one, plan, ninja = [], [], {e: [] for e in EDGES}
    for _ in range(runs):
        one.append(timed([exe, "bake", "-q", preset, "-o", fresh(out_one), "--threads", "1"],
                         "farm_overhead"))
        for edges in EDGES:
            out, build, emit = emit_command(preset, edges)
            fresh(out)
            if edges == "scene":
                plan.append(timed(emit, "farm_overhead"))
            ninja[edges].append(timed(["ninja", "-f", build, "-j", "1", "--quiet"], "farm_overhead"))
    med = lambda cells, k: statistics.median(c[k] for c in cells)
    cell = lambda cells: f"{med(cells, 0):.3f} / {med(cells, 1):.3f}"
    c1 = med(one, 0)
    per = {e: (med(ninja[e], 0) - c1) / products * 1000 for e in EDGES}
    pct = {e: 100 * (med(ninja[e], 0) - c1) / c1 for e in EDGES}
    print(f"| {preset} | {products} | {cell(one)} | {cell(ninja['product'])} | "
          f"{cell(ninja['scene'])} | {cell(plan)} | {per['product']:.1f} ms | "
          f"{per['scene']:.1f} ms | {pct['product']:.1f}% | {pct['scene']:.1f}% |")
print()
print(f"after: {machine()}")
EOF
