# Shared helpers of the Python tests: the repository root, the command-line tool (FREEFORM_CLI,
# set by ctest; the test that needs it is skipped without it), a tick counter for the GIL tests and
# an independent NumPy FFD.
import os
import pathlib
import subprocess
import threading
import time
from math import comb

import numpy as np
import pytest

ROOT = pathlib.Path(os.environ.get("FREEFORM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def cli():
    path = os.environ.get("FREEFORM_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("FREEFORM_CLI (the freeform command-line tool) is not set")
    return path


def run_cli(*args):
    r = subprocess.run([cli(), *map(str, args)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout


def ticks_during(work):
    """Runs work() while another thread ticks every 0.5 ms; the number of ticks inside the call (a
    call that holds the GIL throughout lets the other thread tick not at all)."""
    ticks = []
    stop = threading.Event()

    def counter():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.0005)

    t = threading.Thread(target=counter)
    t.start()
    time.sleep(0.01)
    start = time.perf_counter()
    work()
    end = time.perf_counter()
    stop.set()
    t.join()
    return len([x for x in ticks if start < x < end])


def bernstein(d, x):
    """(len(x), d+1) Bernstein values, by the binomial formula (not the library's recurrence)."""
    x = np.asarray(x, dtype=np.float64)[:, None]
    i = np.arange(d + 1)[None, :]
    c = np.array([comb(d, k) for k in range(d + 1)], dtype=np.float64)[None, :]
    return c * x**i * (1 - x) ** (d - i)


def reference_weights(lat, points):
    """The (N, K) matrix strength * B_ijk(s,t,u) from the docs/ffd.md formulas in NumPy: lattice
    coordinates by solving X0 + A stu = p, then the outside policy."""
    points = np.asarray(points, dtype=np.float64)
    stu = np.linalg.solve(lat.axes, (points - lat.origin).T).T
    inside = np.all((stu >= 0) & (stu <= 1), axis=1)
    if lat.outside == "clamp":
        stu = np.clip(stu, 0, 1)
    l, m, n = lat.degree
    bs, bt, bu = bernstein(l, stu[:, 0]), bernstein(m, stu[:, 1]), bernstein(n, stu[:, 2])
    W = np.einsum("pi,pj,pk->pijk", bs, bt, bu).reshape(len(points), -1) * lat.strength
    if lat.outside == "keep":
        W[~inside] = 0
    return W


def reference_deform(lat, points):
    """p + W (P - R): the displacement form, independent of the library's kernels."""
    W = reference_weights(lat, points)
    return np.asarray(points, dtype=np.float64) + W @ (lat.control_points - lat.rest_points)


def random_lattice(ff, degree=(3, 3, 3), seed=1, scale=0.1, outside="clamp"):
    rng = np.random.default_rng(seed)
    lat = ff.Lattice(degree, origin=[-1.1, -1.2, -0.9], axes=np.diag([2.2, 2.4, 1.9]), outside=outside)
    lat.control_points += rng.uniform(-scale, scale, lat.control_points.shape)
    return lat
