#!/usr/bin/env bash
# What a farm adds per product: a scene baked by one process against the same
# scene under ninja, one skybake process per product (`plan --emit ninja`),
# both on one thread and one slot, from an empty output folder. A ninja edge
# pays its own start-up, loads and hashes the preset, and reads the products
# it depends on back from disk; the difference over one process, divided by
# the products, is the per-product overhead. The `plan --emit ninja` itself
# is a separate row (a farm runs it once per catalog change, not per product).
#
#   bench/farm_overhead.sh [SKYBAKE]          (default: build/skybake)
#   env: RUNS (9), PRESETS ("presets/earth.json")
#
# Runs are interleaved (one process, then ninja, then again) so load affects
# both alike; medians of CPU (user + sys of the process tree, rusage) and wall.
# Not a test: figures depend on the machine and its load (printed with them).
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

def fresh(path):
    shutil.rmtree(path, ignore_errors=True)
    return path

print(f"runs per cell: {runs}; median CPU s (user+sys) / median wall s; {machine()}")
print()
print("| preset | products | one process | ninja -j 1, one process per product | plan --emit ninja "
      "| overhead per product (CPU) | overhead (CPU, % of one process) |")
print("|---|---|---|---|---|---|---|")
for preset in presets:
    out_one, out_ninja = os.path.join(work, "one"), os.path.join(work, "ninja")
    build = os.path.join(work, "build.ninja")
    emit = [exe, "plan", preset, "--emit", "ninja", "-o", out_ninja, "--emit-file", build,
            "--task-threads", "1"]
    subprocess.run(emit, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    products = sum(1 for line in open(build) if line.startswith("build ") and ": bake " in line)
    one, ninja, plan = [], [], []
    for _ in range(runs):
        one.append(timed([exe, "bake", "-q", preset, "-o", fresh(out_one), "--threads", "1"], "farm_overhead"))
        fresh(out_ninja)
        plan.append(timed(emit, "farm_overhead"))
        ninja.append(timed(["ninja", "-f", build, "-j", "1", "--quiet"], "farm_overhead"))
    med = lambda cells, k: statistics.median(c[k] for c in cells)
    c1, cn = med(one, 0), med(ninja, 0)
    cell = lambda cells: f"{med(cells, 0):.3f} / {med(cells, 1):.3f}"
    print(f"| {preset} | {products} | {cell(one)} | {cell(ninja)} | {cell(plan)} | "
          f"{(cn - c1) / products * 1000:.1f} ms | {100 * (cn - c1) / c1:.1f}% |")
EOF
