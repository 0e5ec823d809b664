#!/usr/bin/env bash
# The whole commands the speed targets are stated on, side by side in one run:
# each command is run RUNS times per executable, interleaved (so load affects
# every column alike), into a fresh output folder each time; prints the median
# CPU (user + sys of the process, rusage) and median wall, in seconds, and
# their minimums (on a shared machine the least disturbed run).
#
#   bench/commands.sh [SKYBAKE...]          (default: build/skybake)
#   env: RUNS (3), ONLY (space-separated row keys: version hillaire noise_all
#        noise_dds scattering4 scattering_tol)
#
# Give several executables (e.g. a build of main before and after a change;
# copy its libskybake_*.so plugins next to it) to compare them in one run.
# Each run appends its medians to bench/results/commands.csv, with the commit
# and the machine (bench/results/README.md).
# Rows (docs/decisions/speed-targets.md states the target of each):
#   version         skybake --version
#   hillaire        Earth's Hillaire set: transmittance, multiscattering,
#                   skyview, aerial_perspective (presets/earth.json --only)
#   noise_all       the Horizon Zero Dawn noise set, every format
#   noise_dds       the same, DDS only
#   scattering4     the 4D table 32x128x32x8 (single Mie), 4 orders, EXR
#   scattering_tol  the same at tolerance 1e-3
#
# With TILEABLE_VOLUME_NOISE=EXE (a build of Hillaire's TileableVolumeNoise
# generator, which is not a Debian package: the build used is described in
# docs/decisions/noise-set-speed.md), each
# run also times EXE in a fresh folder (it writes its volumes where it
# runs) and prints its medians and how many times the CPU of the first
# SKYBAKE's noise rows it takes.
# Not a test: figures depend on the machine and its load (printed with them).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
RUNS="${RUNS:-3}"
exes=("$@")
[ ${#exes[@]} -gt 0 ] || exes=("$repo/build/skybake")
for exe in "${exes[@]}"; do
  [ -x "$exe" ] || { echo "commands: $exe: not an executable" >&2; exit 2; }
done

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

[ -z "${TILEABLE_VOLUME_NOISE:-}" ] || [ -x "$TILEABLE_VOLUME_NOISE" ] ||
  { echo "commands: TILEABLE_VOLUME_NOISE=$TILEABLE_VOLUME_NOISE: not an executable" >&2; exit 2; }

PYTHONPATH="$here" python3 - "$RUNS" "$repo" "$work" "${ONLY:-}" "${TILEABLE_VOLUME_NOISE:-}" "${exes[@]}" <<'EOF'
import json, os, shutil, statistics, sys

from process_timing import append_results, machine, timed

runs, repo, work, only, other, exes = (int(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4].split(),
                                       sys.argv[5], sys.argv[6:])

def scene(name, outputs, atmosphere=True):
    d = {"name": name, "outputs": outputs}
    if atmosphere:
        d["planet"] = {"radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3]}
        d["atmosphere"] = os.path.join(repo, "presets/atmospheres/earth.json")
    path = os.path.join(work, name + ".json")
    json.dump(d, open(path, "w"))
    return path

def noise_set(formats):
    d = json.load(open(os.path.join(repo, "presets/clouds/horizon_zero_dawn.json")))
    for out in d["outputs"]:
        out["formats"] = [f for f in out["formats"] if f in formats]
    return scene("hzd_" + "_".join(formats), d["outputs"], atmosphere=False)

transmittance = {"product": "transmittance", "size": [256, 64], "formats": ["exr"]}
scattering = {"product": "scattering", "size": [32, 128, 32, 8], "formats": ["exr"]}
rows = {
    "version": ["--version"],
    "hillaire": ["bake", os.path.join(repo, "presets/earth.json"), "--only",
                 "transmittance,multiscattering,skyview,aerial_perspective"],
    "noise_all": ["bake", noise_set(["dds", "vdb", "exr", "png"])],
    "noise_dds": ["bake", noise_set(["dds"])],
    "scattering4": ["bake", scene("scattering4", [transmittance, dict(scattering, orders=4)])],
    "scattering_tol": ["bake", scene("scattering_tol", [transmittance, dict(scattering, tolerance=1e-3)])],
}
if only:
    rows = {k: v for k, v in rows.items() if k in only}

cells = {}
for _ in range(runs):
    for key, argv in rows.items():
        for exe in exes:
            out = os.path.join(work, "out")
            shutil.rmtree(out, ignore_errors=True)
            extra = ["-q", "-o", out] if argv[0] == "bake" else []
            cells.setdefault((key, exe), []).append(timed([exe] + argv + extra, "commands"))
    if other:
        folder = os.path.join(work, "other")
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)
        cells.setdefault(("other", other), []).append(timed([other], "commands", cwd=folder))

print(f"runs per cell: {runs}; median CPU s (user+sys) / median wall s (min / min); {machine()}")
print()
print("| command | " + " | ".join(exes) + " |")
print("|---|" + "---|" * len(exes))
for key in rows:
    line = []
    for exe in exes:
        c = cells[(key, exe)]
        line.append(f"{statistics.median(x[0] for x in c):.3f} / {statistics.median(x[1] for x in c):.3f}"
                    f" ({min(x[0] for x in c):.3f} / {min(x[1] for x in c):.3f})")
    print(f"| {key} | " + " | ".join(line) + " |")
results = []
for key in rows:
    for exe in exes:
        c = cells[(key, exe)]
        who = f"{key} ({os.path.relpath(exe, repo)})"
        results.append((who, f"CPU (user + sys), median of {runs}", "s", f"{statistics.median(x[0] for x in c):.3f}"))
        results.append((who, f"wall, median of {runs}", "s", f"{statistics.median(x[1] for x in c):.3f}"))
        results.append((who, f"CPU (user + sys), min of {runs}", "s", f"{min(x[0] for x in c):.3f}"))
        results.append((who, f"wall, min of {runs}", "s", f"{min(x[1] for x in c):.3f}"))
append_results(repo, "commands", "RUNS=%d ONLY=%r bench/commands.sh" % (runs, " ".join(only)), results)
if other:
    c = cells[("other", other)]
    cpu = statistics.median(x[0] for x in c)
    print()
    print(f"{other}: {cpu:.3f} / {statistics.median(x[1] for x in c):.3f}")
    for key in ("noise_all", "noise_dds"):
        if key in rows:
            mine = statistics.median(x[0] for x in cells[(key, exes[0])])
            print(f"  CPU against {key} of {exes[0]}: {cpu / mine:.0f}x")
EOF
