#!/usr/bin/env bash
# What each Psi_ms model costs to bake (docs/reference.md "Converged
# Psi_ms"): for each scene, a preset holding only its transmittance and
# multiscattering outputs (same size, directions, steps and mapping) is
# baked from an empty folder on one thread with "model": "hillaire2020" and
# with "model": "converged", and bake_log.json gives each multiscattering
# bake's seconds (the error measurement is timed apart there, and left out).
#
#   bench/multiscattering_models.sh [SKYBAKE] [PRESET...]
#        (default: build/skybake; presets/{earth,mars,tiny_planet}.json and
#        presets/extreme/rayleigh_100x.json)
#   env: RUNS (1): bakes per model, the median is printed
#
# Prints a Markdown table. Not a test: figures depend on the machine and its load.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
exe="${1:-$repo/build/skybake}"
shift || true
presets=("$@")
if [ ${#presets[@]} -eq 0 ]; then
  presets=("$repo"/presets/{earth,mars,tiny_planet}.json "$repo"/presets/extreme/rayleigh_100x.json)
fi
RUNS="${RUNS:-1}"
[ -x "$exe" ] || { echo "multiscattering_models: $exe: not an executable" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

PYTHONPATH="$here" /usr/bin/python3 - "$exe" "$RUNS" "$work" "${presets[@]}" <<'PY'
import json, os, statistics, subprocess, sys

from process_timing import absolute_preset

exe, runs, work, presets = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]


print("| scene | hillaire2020 s | converged s | converged / hillaire |")
print("|---|---|---|---|")
for preset in presets:
    doc = absolute_preset(preset)
    keep = [o for o in doc["outputs"] if o["product"] in ("transmittance", "multiscattering")]
    if not any(o["product"] == "multiscattering" for o in keep):
        keep.append({"product": "multiscattering", "size": [32, 32]})
    seconds = {}
    for model in ("hillaire2020", "converged"):
        doc["outputs"] = [dict(o, formats=["exr"]) for o in keep]
        for o in doc["outputs"]:
            if o["product"] == "multiscattering":
                o["model"] = model
        path = os.path.join(work, f"{doc['name']}_{model}.json")
        json.dump(doc, open(path, "w"))
        times = []
        for run in range(runs):
            out = os.path.join(work, f"out_{model}_{run}")
            subprocess.run([exe, "bake", path, "-o", out, "--threads", "1", "-q", "--force"],
                           check=True, stderr=subprocess.DEVNULL)
            log = json.load(open(os.path.join(out, doc["name"], "bake_log.json")))["outputs"]
            entry = next(v for k, v in log.items() if "multiscattering" in k)
            times.append(entry["bake_seconds"])
        seconds[model] = statistics.median(times)
    print(f"| {doc['name']} | {seconds['hillaire2020']:.3f} | {seconds['converged']:.2f} | "
          f"{seconds['converged'] / seconds['hillaire2020']:.0f}x |")
PY
