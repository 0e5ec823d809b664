"""The whole-command figures of the bench/ scripts: one process's CPU and wall
time, and the machine line printed with every table (figures depend on the
load, so the load goes with them)."""
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
