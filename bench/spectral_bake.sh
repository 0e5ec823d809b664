#!/usr/bin/env bash
# The cost of a spectral bake (docs/decisions/spectral-tables.md): the same
# Earth (presets/earth_spectral.json, Bruneton's demo constants) baked at
# three wavelengths (the RGB coefficients, no "spectral"), at N = 15 and at
# N = 42, for the Hillaire set (transmittance, multiscattering, skyview,
# aerial_perspective) and for Bruneton's 4D table with its irradiance.
# Each command runs RUNS times (interleaved) under /usr/bin/time: median CPU
# (user + sys), median wall and median peak resident memory; the ratios to
# the RGB bake are printed, and everything is appended to
# bench/results/spectral_bake.csv.
#
#   bench/spectral_bake.sh [SKYBAKE]      (default: build/skybake; env RUNS, 3)
#
# Target: N = 15 at most 5x the RGB bake's CPU, with no more memory.
# Not a test: figures depend on the machine and its load (printed with them).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
exe="${1:-$repo/build/skybake}"
RUNS="${RUNS:-3}"
[ -x "$exe" ] || { echo "spectral_bake: $exe: not an executable" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

PYTHONPATH="$here" python3 - "$RUNS" "$repo" "$work" "$exe" <<'PY'
import json, os, shutil, statistics, subprocess, sys

from process_timing import append_results, machine

runs, repo, work, exe = int(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4]
base = json.load(open(os.path.join(repo, "presets/earth_spectral.json")))
base["atmosphere"] = os.path.join(repo, "presets/atmospheres/earth_spectral.json")
base.pop("$schema", None)

def preset(wavelengths):
    d = json.loads(json.dumps(base))
    if wavelengths == 3:
        d.pop("spectral")
    else:
        d["spectral"]["wavelengths"] = wavelengths
    path = os.path.join(work, f"earth_{wavelengths}.json")
    json.dump(d, open(path, "w"))
    return path

sets = {"hillaire": "transmittance,multiscattering,skyview,aerial_perspective",
        "bruneton4d": "scattering,irradiance"}
counts = [3, 15, 42]

def measure(argv):
    """(CPU s, wall s, peak RSS MiB) of one command under /usr/bin/time."""
    fmt = os.path.join(work, "time.txt")
    subprocess.run(["/usr/bin/time", "-o", fmt, "-f", "%U %S %e %M"] + argv, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    u, s, e, m = open(fmt).read().split()[-4:]
    return float(u) + float(s), float(e), float(m) / 1024.0

cells = {}
for _ in range(runs):
    for name, only in sets.items():
        for n in counts:
            out = os.path.join(work, "out")
            shutil.rmtree(out, ignore_errors=True)
            argv = [exe, "bake", preset(n), "--only", only, "-q", "-o", out]
            cells.setdefault((name, n), []).append(measure(argv))

print(f"runs per cell: {runs}; medians; {machine()}")
print("| set | wavelengths | CPU s | wall s | peak MiB | CPU / RGB | memory / RGB |")
print("|---|---|---|---|---|---|---|")
rows = []
for name in sets:
    rgb = [statistics.median(x[i] for x in cells[(name, 3)]) for i in range(3)]
    for n in counts:
        med = [statistics.median(x[i] for x in cells[(name, n)]) for i in range(3)]
        print(f"| {name} | {n} | {med[0]:.2f} | {med[1]:.2f} | {med[2]:.0f} | "
              f"{med[0] / rgb[0]:.2f}x | {med[2] / rgb[2]:.2f}x |")
        who = f"{name} at {n} wavelengths"
        rows += [(who, f"CPU (user + sys), median of {runs}", "s", f"{med[0]:.3f}"),
                 (who, f"wall, median of {runs}", "s", f"{med[1]:.3f}"),
                 (who, f"peak resident memory, median of {runs}", "MiB", f"{med[2]:.1f}"),
                 (who, "CPU / the RGB bake's", "x", f"{med[0] / rgb[0]:.2f}"),
                 (who, "peak memory / the RGB bake's", "x", f"{med[2] / rgb[2]:.2f}")]
append_results(repo, "spectral_bake", f"RUNS={runs} bench/spectral_bake.sh", rows)
PY
