#!/usr/bin/env bash
# EXR compression side by side: every shipped preset given (default: Earth's
# atmosphere tables and the Horizon Zero Dawn noise set) is baked once per
# `exr_compression` (none, zip, zips, piz) with only its EXR outputs, on one
# thread, RUNS times; prints the EXR bytes and the median CPU time of the
# bake (user + sys, rusage) per compression. The bakers' work is the same in
# every row, so a row's CPU above the `none` row is what compressing cost.
#
#   bench/exr_compression_bench.sh [SKYBAKE]            (default: build/skybake)
#   env: RUNS (5), PRESETS ("presets/earth.json presets/clouds/horizon_zero_dawn.json"),
#        THREADS (1)
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
exe="${1:-$repo/build/skybake}"
RUNS="${RUNS:-5}"
THREADS="${THREADS:-1}"
PRESETS="${PRESETS:-presets/earth.json presets/clouds/horizon_zero_dawn.json}"
[ -x "$exe" ] || { echo "exr_compression_bench: $exe: not an executable" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

cd "$repo"
python3 - "$exe" "$RUNS" "$THREADS" "$work" $PRESETS <<'EOF'
import json, os, statistics, subprocess, sys

exe, runs, threads, work, presets = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5:]
compressions = ["none", "zip", "zips", "piz"]

def variant(preset, compression):
    d = json.load(open(preset))
    base = os.path.dirname(os.path.abspath(preset))
    d.pop("$schema", None)
    for key in ("planet", "atmosphere", "clouds"):  # references are relative to the preset
        if isinstance(d.get(key), str):
            d[key] = os.path.join(base, d[key])
    outputs = []
    for out in d["outputs"]:
        if "exr" in out.get("formats", ["exr"]):
            out = dict(out, formats=["exr"], exr_compression=compression)
            out.pop("dds_format", None)
            outputs.append(out)
    d["outputs"] = outputs
    path = os.path.join(work, f"{os.path.basename(preset)[:-5]}_{compression}.json")
    json.dump(d, open(path, "w"))
    return path

def bake(preset, out):
    p = subprocess.Popen([exe, "bake", "-q", "--force", "--threads", threads, preset, "-o", out],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, ru = os.wait4(p.pid, 0)
    err = p.stderr.read().decode(errors="replace")
    p.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"exr_compression_bench: {preset}: {err.strip()}")
    return ru.ru_utime + ru.ru_stime

print(f"runs: {runs}; threads: {threads}; median CPU of the bake (user+sys); load {os.getloadavg()[0]:.2f}\n")
print("| preset | exr_compression | EXR bytes | vs none | bake CPU ms | over none ms |")
print("|---|---|---|---|---|---|")
for preset in presets:
    variants = {c: variant(preset, c) for c in compressions}
    cpu = {c: [] for c in compressions}
    size = {}
    for r in range(runs):
        for c in compressions:  # interleaved: load affects every row alike
            out = os.path.join(work, f"out_{c}")
            cpu[c].append(bake(variants[c], out))
            size[c] = sum(os.path.getsize(os.path.join(dp, f)) for dp, _, fs in os.walk(out)
                          for f in fs if f.endswith(".exr"))
    base_cpu = statistics.median(cpu["none"])
    for c in compressions:
        m = statistics.median(cpu[c])
        print(f"| {os.path.relpath(preset)} | {c} | {size[c]} | {size[c] / size['none']:.3f} | "
              f"{m * 1e3:.0f} | {(m - base_cpu) * 1e3:+.0f} |")
EOF
