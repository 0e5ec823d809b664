#!/usr/bin/env bash
# The Horizon Zero Dawn noise set (presets/clouds/horizon_zero_dawn.json)
# baked per format set, whole `skybake bake` processes side by side: each
# output restricted to one format (dds, vdb, exr, png) or all of them, at
# each thread count, RUNS times per executable, interleaved (so load affects
# every column alike), into a fresh output folder each time. Prints the
# median CPU (user + sys of the process, rusage) and median wall, in seconds,
# and the bytes each format set wrote.
#
#   bench/noise_set_bench.sh [SKYBAKE...]          (default: build/skybake)
#   env: RUNS (5), THREADS ("1 2"), SETS ("dds vdb exr png all")
#
# Give several executables (a build of main before and after a change, with
# its libskybake_*.so plugins next to it) to compare them in one run. The
# targets (docs/decisions/noise-set-speed.md): all formats at most
# 0.6 CPU s, DDS alone at most 0.3. Not a test: figures depend on the machine
# and its load (printed with them).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
RUNS="${RUNS:-5}"
THREADS="${THREADS:-1 2}"
SETS="${SETS:-dds vdb exr png all}"
exes=("$@")
[ ${#exes[@]} -gt 0 ] || exes=("$repo/build/skybake")
for exe in "${exes[@]}"; do
  [ -x "$exe" ] || { echo "noise_set_bench: $exe: not an executable" >&2; exit 2; }
done

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

PYTHONPATH="$here" python3 - "$RUNS" "$repo" "$work" "$THREADS" "$SETS" "${exes[@]}" <<'EOF'
import json, os, shutil, statistics, sys

from process_timing import machine, timed

runs, repo, work = int(sys.argv[1]), sys.argv[2], sys.argv[3]
threads, sets, exes = sys.argv[4].split(), sys.argv[5].split(), sys.argv[6:]

def preset(fmt):
    d = json.load(open(os.path.join(repo, "presets/clouds/horizon_zero_dawn.json")))
    d.pop("$schema", None)
    outputs = []
    for out in d["outputs"]:
        if fmt != "all":
            if fmt not in out["formats"]:
                continue
            out["formats"] = [fmt]
        outputs.append(out)
    d["outputs"] = outputs
    path = os.path.join(work, f"hzd_{fmt}.json")
    json.dump(d, open(path, "w"))
    return path

def bake(argv, out):
    """(CPU s, wall s, bytes of the files written) of one bake into a fresh `out`."""
    shutil.rmtree(out, ignore_errors=True)
    cpu, wall = timed(argv + ["-o", out], "noise_set_bench")
    size = sum(os.path.getsize(os.path.join(r, f)) for r, _, fs in os.walk(out) for f in fs
               if not f.endswith(".json") and not f.startswith("."))
    return cpu, wall, size

presets = {fmt: preset(fmt) for fmt in sets}
cells = {}
for _ in range(runs):
    for fmt in sets:
        for t in threads:
            for i, exe in enumerate(exes):
                argv = [exe, "bake", "-q", "--threads", t, presets[fmt]]
                out = os.path.join(work, f"out{i}")
                cells.setdefault((fmt, t, exe), []).append(bake(argv, out))

print(f"runs per cell: {runs}; median CPU s (user+sys) / median wall s / MB written; "
      f"{machine()}")
print()
print("| formats | threads | " + " | ".join(exes) + " |")
print("|---|---|" + "---|" * len(exes))
for fmt in sets:
    for t in threads:
        line = []
        for exe in exes:
            c = cells[(fmt, t, exe)]
            line.append(f"{statistics.median(x[0] for x in c):.3f} / "
                        f"{statistics.median(x[1] for x in c):.3f} / {c[-1][2] / 1e6:.1f}")
        print(f"| {fmt} | {t} | " + " | ".join(line) + " |")
EOF
