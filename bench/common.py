"""What the comparison scripts share: where the project, the shared data and the
release binary are, and running a command that must succeed."""
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("QMESH_DATA", os.path.join(os.path.dirname(ROOT), "shared", "data"))
Q = os.path.join(ROOT, "target", "release", "qmesh")
MEASURE = os.path.join(ROOT, "bench", "measure.py")


def sh(*cmd, cwd=None, timeout=None, env=None):
    """The stdout of `cmd` (run with `env` when given); exits with its stderr when it
    fails or outlives `timeout` s."""
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        sys.exit(f"failed: {' '.join(cmd[:2])} …\ntimed out after {timeout} s")
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stderr[-2000:]}")
    return r.stdout


GNU_TIME = "/usr/bin/time"


def timed(cmd, ok=(0,)):
    """Wall seconds, peak RSS bytes (GNU time, which forks cmd from its own small
    process) and stdout of one run of cmd; exits when its status is not in `ok`."""
    if not os.access(GNU_TIME, os.X_OK):
        sys.exit(f"{GNU_TIME} (GNU time, Debian package `time`) is needed for peak memory")
    with tempfile.NamedTemporaryFile("r") as report:
        t = time.perf_counter()
        done = subprocess.run([GNU_TIME, "-f", "%M", "-o", report.name, *cmd], capture_output=True, text=True)
        wall = time.perf_counter() - t
        if done.returncode not in ok:
            sys.exit(f"failed: {' '.join(cmd)}\n{done.stderr[-2000:]}")
        return wall, int(report.read().split()[-1]) * 1024, done.stdout


def median(measured, figure):
    """The median over the runs of `figure` of a command's report (bench/measure.py)."""
    return statistics.median(figure(o) for o in measured["outputs"])
