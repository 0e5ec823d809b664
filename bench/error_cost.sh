#!/usr/bin/env bash
# What the error measurement costs a bake (docs/decisions/error-records.md): each shipped scene preset (presets/*.json)
# and each case of presets/extreme/ is baked from an empty folder on one
# thread (so other processes' load affects both columns alike), and the
# bake_log.json times are summed per scene: bake_seconds (the bakers) against
# error_seconds (the measurement and tiling check of every written output).
# manifest.json holds no times; bake_log.json beside it does.
#
#   bench/error_cost.sh [SKYBAKE]        (default: build/skybake)
#   env: RUNS (1): bakes per scene, the median ratio is printed
#
# Prints a Markdown table, one row per scene, with each product's share.
# Not a test: figures depend on the machine and its load.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
exe="${1:-$repo/build/skybake}"
RUNS="${RUNS:-1}"
[ -x "$exe" ] || { echo "error_cost: $exe: not an executable" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

python3 - "$exe" "$RUNS" "$work" "$repo"/presets/*.json "$repo"/presets/extreme/*.json <<'PY'
import json, os, statistics, subprocess, sys

exe, runs, work, presets = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
print("| scene | bake s | error s | error / bake | largest shares (error s / bake s) |")
print("|---|---|---|---|---|")
total_bake = total_error = 0.0
for preset in presets:
    rows = []
    for run in range(runs):
        out = os.path.join(work, f"run{run}")
        subprocess.run([exe, "bake", preset, "-o", out, "--threads", "1", "-q", "--force"],
                       check=True, stderr=subprocess.DEVNULL)
        scene = json.load(open(preset))["name"]
        log = json.load(open(os.path.join(out, scene, "bake_log.json")))["outputs"]
        bake = sum(e["bake_seconds"] for e in log.values())
        error = sum(e.get("error_seconds", 0.0) for e in log.values())
        rows.append((error / bake if bake > 0 else 0.0, bake, error, log))
    ratio, bake, error, log = sorted(rows, key=lambda r: r[0])[len(rows) // 2]
    total_bake += bake
    total_error += error
    shares = sorted(((e.get("error_seconds", 0.0), e["bake_seconds"], name)
                     for name, e in log.items()), reverse=True)[:3]
    detail = ", ".join(f"{n} {es:.3f}/{bs:.3f}" for es, bs, n in shares if es > 0)
    print(f"| {scene} | {bake:.3f} | {error:.3f} | {100 * ratio:.1f}% | {detail} |")
print(f"| all | {total_bake:.3f} | {total_error:.3f} | "
      f"{100 * total_error / max(total_bake, 1e-9):.1f}% | |")
PY
