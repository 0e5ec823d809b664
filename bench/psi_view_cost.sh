#!/usr/bin/env bash
# What the source by view costs to bake against the isotropic converged
# model (docs/decisions/psi-ms-by-view.md): for each scene, a preset holding
# only its transmittance and multiscattering outputs, the latter with
# "model": "converged", baked from an empty folder on one thread, then the
# same with "angular": "nu_zenith". Each bake runs RUNS times under
# /usr/bin/time; the minimum of each figure is kept (the machine is shared):
# the process's CPU seconds (user + sys) and wall seconds, both with the
# bake's error record, and the multiscattering bake's own wall seconds from
# bake_log.json (the error record left out).
#
#   bench/psi_view_cost.sh [SKYBAKE] [PRESET...]
#        (default: build/skybake; presets/{earth,mars,tiny_planet}.json)
#   env: RUNS (3)
#
# Prints a Markdown table. Not a test: figures depend on the machine and its load.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
exe="${1:-$repo/build/skybake}"
shift || true
presets=("$@")
if [ ${#presets[@]} -eq 0 ]; then presets=("$repo"/presets/{earth,mars,tiny_planet}.json); fi
RUNS="${RUNS:-3}"
[ -x "$exe" ] || { echo "psi_view_cost: $exe: not an executable" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

PYTHONPATH="$here" /usr/bin/python3 - "$exe" "$RUNS" "$work" "${presets[@]}" <<'PY'
import json, os, subprocess, sys

from process_timing import absolute_preset

exe, runs, work, presets = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]


def bake(path, name, out):
    """(cpu, wall, bake) seconds of one bake."""
    timing = os.path.join(work, "time.txt")
    subprocess.run(["/usr/bin/time", "-o", timing, "-f", "%U %S %e", exe, "bake", path, "-o",
                    out, "--threads", "1", "-q", "--force"], check=True,
                   stderr=subprocess.DEVNULL)
    user, system, wall = map(float, open(timing).read().split()[-3:])
    log = json.load(open(os.path.join(out, name, "bake_log.json")))["outputs"]
    entry = next(v for k, v in log.items() if "multiscattering" in k)
    return user + system, wall, entry["bake_seconds"]

print("| scene | converged: CPU s / wall s / bake s | by view: CPU s / wall s / bake s "
      "| by view / converged (CPU, bake) |")
print("|---|---|---|---|")
for preset in presets:
    doc = absolute_preset(preset)
    keep = [o for o in doc["outputs"] if o["product"] in ("transmittance", "multiscattering")]
    if not any(o["product"] == "multiscattering" for o in keep):
        keep.append({"product": "multiscattering", "size": [32, 32]})
    figures = {}
    for variant in ("converged", "view"):
        doc["outputs"] = [dict(o, formats=["exr"]) for o in keep]
        for o in doc["outputs"]:
            if o["product"] == "multiscattering":
                o.pop("directions", None)
                o.pop("direction_quadrature", None)
                o["model"] = "converged"
                if variant == "view":
                    o["angular"] = "nu_zenith"
        path = os.path.join(work, f"{doc['name']}_{variant}.json")
        json.dump(doc, open(path, "w"))
        runs_seen = [bake(path, doc["name"], os.path.join(work, f"out_{variant}_{run}"))
                     for run in range(runs)]
        figures[variant] = [min(r[i] for r in runs_seen) for i in range(3)]
    c, v = figures["converged"], figures["view"]
    print(f"| {doc['name']} | {c[0]:.2f} / {c[1]:.2f} / {c[2]:.2f} | "
          f"{v[0]:.2f} / {v[1]:.2f} / {v[2]:.2f} | {v[0] / c[0]:.2f}x, {v[2] / c[2]:.2f}x |")
PY
