"""What the comparison scripts share: where the project, the shared data and the
release binary are, and running a command that must succeed."""
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("QMESH_DATA", os.path.join(os.path.dirname(ROOT), "shared", "data"))
Q = os.path.join(ROOT, "target", "release", "qmesh")
MEASURE = os.path.join(ROOT, "bench", "measure.py")


def sh(*cmd, cwd=None, timeout=None):
    """The stdout of `cmd`; exits with its stderr when it fails or outlives `timeout` s."""
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, timeout=timeout)
    except subprocess.TimeoutExpired:
        sys.exit(f"failed: {' '.join(cmd[:2])} …\ntimed out after {timeout} s")
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stderr[-2000:]}")
    return r.stdout
