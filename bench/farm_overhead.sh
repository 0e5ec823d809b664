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
# Runs are interleaved (one process and each ninja in a round, each round in
# another order) so load affects all alike; medians of CPU (user + sys of the process tree, rusage)
# and wall. The overhead is the median over rounds of (ninja - one process)
# CPU, as a percentage of the one process's median. Not a test: figures depend on the machine and its load (printed
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
lows = []
for preset in presets:
    out_one = os.path.join(work, "one")
    products = None
    for edges in EDGES:
        _, build, emit = emit_command(preset, edges)
        subprocess.run(emit, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if edges == "product":
            products = count_edges(build)
    one, plan, ninja = [], [], {e: [] for e in EDGES}
    def run_one():
        one.append(timed([exe, "bake", "-q", preset, "-o", fresh(out_one), "--threads", "1"],
                         "farm_overhead"))
    def run_ninja(edges):
        out, build, emit = emit_command(preset, edges)
        fresh(out)
        if edges == "scene":
            plan.append(timed(emit, "farm_overhead"))
        ninja[edges].append(timed(["ninja", "-f", build, "-j", "1", "--quiet"], "farm_overhead"))
    cells = [run_one, lambda: run_ninja("product"), lambda: run_ninja("scene")]
    for r in range(runs):  # each round in another order: none always runs first
        for k in range(len(cells)):
            cells[(r + k) % len(cells)]()
    med = lambda cells, k: statistics.median(c[k] for c in cells)
    cell = lambda cells: f"{med(cells, 0):.3f} / {med(cells, 1):.3f}"
    c1 = med(one, 0)
    # The overhead of a round is its ninja run less its one-process run: the
    # load drifts less within a round than across the runs.
    paired = {e: statistics.median(n[0] - o[0] for n, o in zip(ninja[e], one)) for e in EDGES}
    print(f"| {preset} | {products} | {cell(one)} | {cell(ninja['product'])} | "
          f"{cell(ninja['scene'])} | {cell(plan)} | "
          f"{paired['product'] / products * 1000:.1f} ms | {paired['scene'] / products * 1000:.1f} ms | "
          f"{100 * paired['product'] / c1:.1f}% | {100 * paired['scene'] / c1:.1f}% |")
    lows.append(f"| {preset} | {min(c[0] for c in one):.3f} | "
                f"{min(c[0] for c in ninja['product']):.3f} | {min(c[0] for c in ninja['scene']):.3f} |")
print()
print("Minimum CPU s of the same runs (less sensitive to load than the medians):")
print()
print("| preset | one process | ninja, --edges product | ninja, --edges scene |")
print("|---|---|---|---|")
print("\n".join(lows))
print()
print(f"after: {machine()}")
EOF
