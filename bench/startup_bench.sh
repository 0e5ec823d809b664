#!/usr/bin/env bash
# Whole-command start-up timings, side by side in one run: each command is run
# RUNS times per executable, interleaved (so load affects every column alike),
# and the median CPU time (user + sys of the process, from wait4's rusage,
# microsecond resolution) and median wall time are printed as a Markdown table.
#
#   bench/startup_bench.sh [SKYBAKE...]        (default: build/skybake)
#   env: RUNS (15), PRESET (presets/earth.json)
#
# Commands: `--version`; `validate PRESET`; `plan PRESET -o DIR --json`; and a
# small bake, `bake PRESET --only transmittance` into a fresh folder each run.
# Give several executables (e.g. before and after a change) to compare them in
# the same run. Not a test: figures depend on the machine and its load.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
RUNS="${RUNS:-15}"
PRESET="${PRESET:-$repo/presets/earth.json}"
exes=("$@")
[ ${#exes[@]} -gt 0 ] || exes=("$repo/build/skybake")
for exe in "${exes[@]}"; do
  [ -x "$exe" ] || { echo "startup_bench: $exe: not an executable" >&2; exit 2; }
done

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

PYTHONPATH="$here" python3 - "$RUNS" "$PRESET" "$work" "${exes[@]}" <<'EOF'
import os, statistics, sys

from process_timing import machine, timed

runs, preset, work, exes = int(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4:]
commands = [
    ("--version", lambda d: ["--version"]),
    ("validate", lambda d: ["validate", "-q", preset]),
    ("plan --json", lambda d: ["plan", preset, "-o", d, "--json"]),
    ("bake --only transmittance", lambda d: ["bake", "-q", preset, "--only", "transmittance", "-o", d]),
]

results = {}
counter = 0
for name, args in commands:
    for _ in range(runs):
        for exe in exes:
            counter += 1
            out = os.path.join(work, f"out{counter}")
            os.makedirs(out)
            results.setdefault((name, exe), []).append(timed([exe] + args(out), "startup_bench"))

print(f"runs per cell: {runs}; median CPU ms (user+sys) / median wall ms; {os.cpu_count()} CPUs, "
      f"{machine()}\n")
print("| command | " + " | ".join(exes) + " |")
print("|---|" + "---|" * len(exes))
for name, _ in commands:
    cells = []
    for exe in exes:
        r = results[(name, exe)]
        cpu = statistics.median(c for c, _ in r) * 1e3
        wall = statistics.median(w for _, w in r) * 1e3
        cells.append(f"{cpu:.1f} / {wall:.1f}")
    print(f"| {name} | " + " | ".join(cells) + " |")
EOF
