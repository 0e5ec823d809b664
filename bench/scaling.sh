#!/usr/bin/env bash
# How each product family's bake time grows with its texel count and with
# threads. For every family, one output is baked at three sizes (1x, 2x and 4x
# the texels) with --threads 1 and --threads 2, RUNS times, interleaved so load
# affects every cell alike. The time is the product's own bake_seconds from
# bake_log.json (the computation alone: no start-up, no writing, no error
# measurement, and its dependencies are separate entries). Prints:
#
#   - us per texel at each size (1 thread): flat along a row = linear cost;
#   - linearity: (time largest / time smallest) / (texels largest / texels
#     smallest); 1.00 = linear, above 1 = grows faster than the texels;
#   - the 1 -> 2 thread speed-up at the largest size (wall of the bake),
#     of the medians and of the fastest runs (on a shared machine the
#     fastest run of each is the one least slowed by other processes);
#   - the machine's ceiling: two CPU-bound processes against one, the most
#     any bake can show on it.
#
#   bench/scaling.sh [SKYBAKE]              (default: build/skybake)
#   env: RUNS (3), FAMILIES (space-separated subset of the names below)
#
# Not a test: figures depend on the machine and its load (printed with them).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
exe="${1:-$repo/build/skybake}"
RUNS="${RUNS:-3}"
[ -x "$exe" ] || { echo "scaling: $exe: not an executable" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

python3 - "$exe" "$RUNS" "$work" "$repo" "${FAMILIES:-}" <<'EOF'
import json, os, statistics, subprocess, sys

exe, runs, work, repo, only = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5].split()
atmosphere = os.path.join(repo, "presets/atmospheres/earth.json")
planet = {"radius_km": 6360, "ground_albedo": [0.3, 0.3, 0.3]}

# family: (extra output keys, three sizes: 1x, 2x, 4x the texels, or 1x, 4x,
# 16x / 1x, 8x, 64x where the product must be square or a cube, or a bake at
# 1x would be too short to time)
families = {
    # From Earth's default table up: a 256x64 table is a 6-9 ms bake, the
    # first loop of its process, whose speed-up measures how soon the other
    # vCPU wakes more than the bake (docs/decisions/speed-targets.md).
    "transmittance": ({}, [[256, 64], [512, 128], [1024, 256]]),
    "multiscattering": ({"directions": 64}, [[16, 16], [32, 16], [32, 32]]),
    "skyview": ({}, [[96, 54], [192, 54], [192, 108]]),
    # From the default 32^3 volume up (the sizes below it bake in 1-3 ms).
    "aerial_perspective": ({}, [[32, 32, 32], [64, 32, 32], [64, 64, 32]]),
    "scattering": ({"orders": 4}, [[16, 64, 16, 4], [32, 64, 16, 4], [32, 128, 16, 4]]),
    "scattering3d": ({"orders": 4}, [[16, 64, 16], [32, 64, 16], [32, 128, 16]]),
    "noise_shape": ({"perlin": {"period": 4, "octaves": 3}, "perlin_worley": {"period": 4, "octaves": 3},
                     "worley": [{"period": 2, "octaves": 3}, {"period": 4, "octaves": 3},
                                {"period": 8, "octaves": 2}]},  # periods that fit 32^3
                    [[32, 32, 32], [64, 64, 64], [128, 128, 128]]),  # cubes: 8x steps
    "noise_detail": ({"worley": [{"period": 2, "octaves": 2}, {"period": 2, "octaves": 3},
                                 {"period": 4, "octaves": 2}]}, [[32, 32, 32], [64, 64, 64], [128, 128, 128]]),
    "curl": ({}, [[64, 64], [128, 128], [256, 256]]),  # squares: 4x steps
    "weather": ({}, [[128, 128], [256, 256], [512, 512]]),
}
if only:
    families = {k: v for k, v in families.items() if k in only}

def preset(family, extra, size):
    out = {"product": family, "size": size, "formats": ["exr"]}
    out.update(extra)
    d = {"name": "scaling", "outputs": [out]}
    if family == "weather":
        d["clouds"] = os.path.join(repo, "presets/clouds/fair_weather_cumulus.json")
    if not family.startswith(("noise", "curl", "weather")):
        d["planet"] = planet
        d["atmosphere"] = atmosphere
    path = os.path.join(work, f"{family}_{'x'.join(map(str, size))}.json")
    json.dump(d, open(path, "w"))
    return path

def bake_seconds(path, threads, n):
    out = os.path.join(work, f"out{n}")
    subprocess.run(["rm", "-rf", out], check=True)
    subprocess.run([exe, "bake", "-q", path, "-o", out, "--threads", str(threads)], check=True,
                   stdout=subprocess.DEVNULL)
    log = json.load(open(os.path.join(out, "scaling", "bake_log.json")))
    return log["outputs"][family]["bake_seconds"]

# What two threads can give on this machine at all: two processes of a
# CPU-bound loop (no memory traffic, no synchronisation) against one. On a
# VM whose two vCPUs share a core or are stolen by other guests this is
# below 2, and no bake can scale past it.
import time
SPIN = [sys.executable, "-c", "s = 0\nfor i in range(3_000_000): s += i * i"]
def spin_wall(copies):
    start = time.perf_counter()
    procs = [subprocess.Popen(SPIN) for _ in range(copies)]
    for p in procs:
        p.wait()
    return time.perf_counter() - start
ceiling = []

cells = {}
n = 0
for _ in range(runs):
    ceiling.append(2 * spin_wall(1) / spin_wall(2))
    for family, (extra, sizes) in families.items():
        for i, size in enumerate(sizes):
            path = preset(family, extra, size)
            for threads in (1, 2):
                if threads == 2 and i != len(sizes) - 1:
                    continue
                n += 1
                cells.setdefault((family, i, threads), []).append(bake_seconds(path, threads, n))

load = open("/proc/loadavg").read().split()[:3]
print(f"runs per cell: {runs}; median bake_seconds; {os.cpu_count()} CPUs, load {' '.join(load)}")
print()
print("| family | sizes | us/texel, smallest | middle | largest | linearity | 1 -> 2 threads (largest) | fastest runs |")
print("|---|---|---|---|---|---|---|---|")
for family, (extra, sizes) in families.items():
    t = [statistics.median(cells[(family, i, 1)]) for i in range(3)]
    texels = [eval("*".join(map(str, s))) for s in sizes]
    per = [1e6 * t[i] / texels[i] for i in range(3)]
    t2 = statistics.median(cells[(family, 2, 2)])
    best = min(cells[(family, 2, 1)]) / min(cells[(family, 2, 2)])
    names = ", ".join("x".join(map(str, s)) for s in sizes)
    print(f"| {family} | {names} | {per[0]:.3g} | {per[1]:.3g} | {per[2]:.3g} | "
          f"{(t[2] / t[0]) / (texels[2] / texels[0]):.2f} | {t[2] / t2:.2f}x | {best:.2f}x |")
print()
print(f"machine ceiling (two CPU-bound processes against one, {runs} runs): median "
      f"{statistics.median(ceiling):.2f}x, best {max(ceiling):.2f}x")
EOF
