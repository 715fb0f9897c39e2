# Issue 26, item 1: Lattice(..., axes=...) with a (3, 2) or (3, 1) array read past the array (a
# Matrix3d filled from a 3 x N block). Under valgrind (memcheck) the calls with wrong shapes must
# raise freeform.Error before any element is read: no invalid read in the module. Skipped only when
# valgrind is not installed (Debian: valgrind, scripts/install-deps.sh).
import os
import shutil
import subprocess
import sys

import pytest

import freeform as ff

SCRIPT = r"""
import numpy as np, freeform as ff
bad = [np.arange(1., 7).reshape(3, 2), np.arange(1., 4).reshape(3, 1), np.arange(1., 7).reshape(2, 3),
       np.arange(1., 10), np.arange(1., 7).reshape(3, 2)[:, ::2]]
for axes in bad:
    try:
        ff.Lattice(1, origin=[0, 0, 0], axes=axes)
    except ff.Error as e:
        assert "axes: expected an array of shape (3, 3)" in str(e), e
    else:
        raise SystemExit("accepted axes of shape %s" % (axes.shape,))
for origin in [[0, 0], np.zeros((1, 2))]:
    try:
        ff.Lattice(1, origin=origin, axes=np.eye(3))
    except ff.Error as e:
        assert "origin: expected an array of shape (3,)" in str(e), e
    else:
        raise SystemExit("accepted origin %r" % (origin,))
lat = ff.Lattice(1, origin=[0, 0, 0], axes=np.eye(3) * 2)
assert lat.axes.tolist() == (np.eye(3) * 2).tolist()
print("done")
"""


def test_bad_axes_read_nothing_under_valgrind():
    valgrind = shutil.which("valgrind")
    if not valgrind:
        pytest.skip("valgrind is not installed (scripts/install-deps.sh installs it)")
    env = dict(os.environ, PYTHONMALLOC="malloc", OPENBLAS_NUM_THREADS="1")
    module_dir = os.path.dirname(ff.__file__)
    env["PYTHONPATH"] = module_dir + os.pathsep + env.get("PYTHONPATH", "")
    r = subprocess.run([valgrind, "--tool=memcheck", "--error-exitcode=99", "--errors-for-leak-kinds=none",
                        "--leak-check=no", "--track-origins=no", "--undef-value-errors=no",
                        sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=300, env=env)
    assert "Invalid read" not in r.stderr, r.stderr[-4000:]
    assert r.returncode == 0, r.stderr[-4000:]
    assert r.stdout.strip() == "done"
