"""The whole-command figures of the bench/ scripts: one process's CPU and wall
time, the machine line printed with every table (figures depend on the
load, so the load goes with them), and presets made to bake from a scratch
folder."""
import json
import os
import subprocess
import sys
import tempfile
import time


def timed(argv, who, cwd=None):
    """(CPU s, wall s) of one command, run in `cwd` (default: this process's
    folder). CPU is user + sys from wait4's rusage: the process and every
    descendant it waited for (ninja's edges included). A failure exits,
    naming `who`, the command and what it printed on stderr."""
    with tempfile.TemporaryFile() as err:  # a file, not a pipe: no full-pipe stall
        t0 = time.perf_counter()
        p = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=err, cwd=cwd)
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
        if os.waitstatus_to_exitcode(status) != 0:
            err.seek(0)
            sys.exit(f"{who}: {' '.join(argv)} failed: {err.read().decode(errors='replace').strip()}")
    return ru.ru_utime + ru.ru_stime, wall


def machine():
    """'N CPUs, load a b c' (the 1, 5 and 15 minute load averages)."""
    return f"{os.cpu_count()} CPUs, load {' '.join(f'{x:.2f}' for x in os.getloadavg())}"


RESULT_COLUMNS = ["benchmark", "figure", "unit", "value", "commit", "machine", "command"]


def commit(repo):
    """The repository's HEAD commit, short, with '+dirty' when the tree has
    uncommitted changes; 'unknown' outside a git checkout."""
    try:
        head = subprocess.run(["git", "-C", repo, "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", repo, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + ("+dirty" if dirty else "")


def machine_description():
    """CPU model and count, and the load when measured (bench/results/README.md)."""
    model = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{model}; {machine()}"


def append_results(repo, name, command, rows):
    """Appends rows (benchmark, figure, unit, value) to bench/results/NAME.csv,
    with the commit, the machine and the command that measured them."""
    import csv
    path = os.path.join(repo, "bench", "results", name + ".csv")
    new = not os.path.exists(path)
    with open(path, "a", newline="") as f:
        w = csv.writer(f)
        if new:
            w.writerow(RESULT_COLUMNS)
        where, what = machine_description(), commit(repo)
        for benchmark, figure, unit, value in rows:
            w.writerow([benchmark, figure, unit, value, what, where, command])
    print(f"appended {len(rows)} rows to {path}")


def absolute_preset(preset):
    """The preset with its file references made absolute, so it bakes from elsewhere."""
    doc = json.load(open(preset))
    base = os.path.dirname(os.path.abspath(preset))
    for key in ("$schema", "planet", "atmosphere", "clouds"):
        if isinstance(doc.get(key), str):
            doc[key] = os.path.normpath(os.path.join(base, doc[key]))
    return doc
