#!/usr/bin/python3
"""The bake cost of sky_irradiance at its default size (32 sun zeniths x 16
altitudes) next to Earth's Hillaire set (transmittance, multiscattering,
skyview, aerial_perspective), whole commands, each RUNS times interleaved
(so load affects every row alike), each into a fresh output folder.

Rows:
  hillaire        presets/earth.json --only transmittance,multiscattering,skyview,aerial_perspective
  sky_irradiance  Earth, sky_irradiance with its default source (the converged
                  4D field, and a second field fine along the sun where the
                  sun is below the horizon) and its dependencies
                  (transmittance, multiscattering)
  sky_irradiance_psi_view  the same with twilight_source psi_ms_by_view
  sky_irradiance_field  the same with twilight_source converged_field (the
                  daylight field below the horizon too)
  sky_irradiance_psi_ms  the same with radiance_source multiscattering_table
  deps            the dependencies alone (transmittance, multiscattering)

Prints the median CPU (user + sys, rusage) and wall of each row, in seconds.

  bench/sky_irradiance_bench.py [SKYBAKE]   (default: build/skybake)
  env: RUNS (5), THREADS (0: all cores)

Not a test: figures depend on the machine and its load (printed with them).
"""
import json
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from process_timing import machine, timed  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def preset(folder, name, sky_outputs):
    with open(os.path.join(REPO, "presets", "earth.json"), encoding="utf-8") as f:
        p = json.load(f)
    p.pop("$schema", None)
    p["name"] = name
    p["atmosphere"] = os.path.join(REPO, "presets", p["atmosphere"])
    p["outputs"] = p["outputs"][:2] + sky_outputs
    path = os.path.join(folder, name + ".json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(p, f)
    return path


def main():
    exe = sys.argv[1] if len(sys.argv) > 1 else os.path.join(REPO, "build", "skybake")
    runs = int(os.environ.get("RUNS", "5"))
    threads = os.environ.get("THREADS", "0")
    work = tempfile.mkdtemp()
    field = preset(work, "si_field", [{"product": "sky_irradiance", "formats": ["exr"]}])
    psi_view = preset(work, "si_psi_view",
                      [{"product": "sky_irradiance", "formats": ["exr"],
                        "twilight_source": "psi_ms_by_view"}])
    field_only = preset(work, "si_field_only",
                        [{"product": "sky_irradiance", "formats": ["exr"],
                          "twilight_source": "converged_field"}])
    psi = preset(work, "si_psi", [{"product": "sky_irradiance", "formats": ["exr"],
                                   "radiance_source": "multiscattering_table"}])
    rows = {
        "hillaire": [os.path.join(REPO, "presets", "earth.json"), "--only",
                     "transmittance,multiscattering,skyview,aerial_perspective"],
        "sky_irradiance": [field],
        "sky_irradiance_psi_view": [psi_view],
        "sky_irradiance_field": [field_only],
        "sky_irradiance_psi_ms": [psi],
        "deps": [field, "--only", "transmittance,multiscattering"],
    }
    times = {k: [] for k in rows}
    for run in range(runs):
        for key, args in rows.items():
            out = os.path.join(work, f"out_{key}_{run}")
            times[key].append(timed([exe, "bake", *args, "-o", out, "-q", "-j", threads], key))
    print(f"sky_irradiance bench: {runs} runs, threads {threads}, {machine()}")
    print(f"{'row':24} {'CPU s':>8} {'wall s':>8}")
    for key, t in times.items():
        print(f"{key:24} {statistics.median(c for c, _ in t):8.3f} "
              f"{statistics.median(w for _, w in t):8.3f}")


if __name__ == "__main__":
    main()
