#!/usr/bin/env python3
"""Free-form deformation from Python: 1,000,000 points (uniform in [-1, 1]^3, seed 7) through a
cubic lattice (4 x 4 x 4 control points, every one displaced), as benchmarks/bench_ffd.cpp does,
with

  - freeform.Lattice.deform (float64 and float32; it binds the points, i.e. computes their lattice
    coordinates, on every call, which the C++ benchmark's FfdBinding does once outside the loop),
  - Lattice.bind(points).deform(lat, out=...) (bound once, written into a preallocated array: what
    the C++ benchmark measures),
  - weights_matvec / weights_rmatvec (the matrix-free sensitivity products),
  - the plain NumPy FFD measured in the same run: the vectorised Bernstein tensor sum PyGeM-style
    code does (per-axis Bernstein matrices, then an einsum over the 64 control points).

Prints one line per case (the median of --repeat runs after a warm-up, seconds and M points/s) and the speed-up over
NumPy. Run from the repository root after building the module:

    PYTHONPATH=build/python python3 benchmarks/python/bench_ffd.py [--points N] [--repeat R]

docs/performance.md has the figures and the C++ benchmark to compare with.
"""
import argparse
import os
import time
from math import comb

import numpy as np

import freeform as ff


def make_lattice(degree=3):
    lat = ff.Lattice((degree,) * 3, origin=[-1.1, -1.1, -1.1], axes=np.eye(3) * 2.2)
    rng = np.random.default_rng(11)
    lat.control_points += rng.uniform(-0.15, 0.15, lat.control_points.shape)
    return lat


def numpy_ffd(points, origin, axes, control, rest, degree):
    """PyGeM-style vectorised FFD: lattice coordinates, per-axis Bernstein values, tensor sum."""
    stu = np.clip((points - origin) @ np.linalg.inv(axes).T, 0.0, 1.0)
    k = np.arange(degree + 1)
    c = np.array([comb(degree, i) for i in k], dtype=np.float64)
    b = [c * stu[:, a, None] ** k * (1 - stu[:, a, None]) ** (degree - k) for a in range(3)]
    d = (control - rest).reshape(degree + 1, degree + 1, degree + 1, 3)
    return points + np.einsum("ni,nj,nk,ijkc->nc", b[0], b[1], b[2], d, optimize=True)


def median_time(f, repeat):
    """Median wall-clock seconds of repeat calls (after one warm-up call), as Google Benchmark's
    real_time median of the C++ benchmark."""
    f()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--threads", type=int, default=0, help="0: the library's default (hardware concurrency)")
    args = ap.parse_args()

    rng = np.random.default_rng(7)
    p64 = rng.uniform(-1, 1, (args.points, 3))
    p32 = p64.astype(np.float32)
    lat = make_lattice()
    g = rng.normal(size=p64.shape)
    dP = rng.normal(size=lat.control_points.shape)

    ref = numpy_ffd(p64, lat.origin, lat.axes, lat.control_points, lat.rest_points, 3)
    assert np.allclose(lat.deform(p64), ref, atol=1e-12), "freeform and NumPy disagree"

    n = args.points
    b64, b32 = lat.bind(p64), lat.bind(p32)
    o64, o32 = np.empty_like(p64), np.empty_like(p32)
    cases = [
        ("numpy_ffd float64", lambda: numpy_ffd(p64, lat.origin, lat.axes, lat.control_points, lat.rest_points, 3)),
        ("ff.deform float64", lambda: lat.deform(p64, threads=args.threads)),
        ("ff.deform float32", lambda: lat.deform(p32, threads=args.threads)),
        ("ff.Binding float64", lambda: b64.deform(lat, threads=args.threads, out=o64)),
        ("ff.Binding float32", lambda: b32.deform(lat, threads=args.threads, out=o32)),
        ("ff.weights_matvec", lambda: lat.weights_matvec(p64, dP, threads=args.threads)),
        ("ff.weights_rmatvec", lambda: lat.weights_rmatvec(p64, g, threads=args.threads)),
    ]
    print(f"{n} points, cubic lattice, threads={args.threads or os.cpu_count()}, median of {args.repeat} (NumPy: one timed run after a warm-up)")
    results = {}
    for name, f in cases:
        repeat = 1 if name.startswith("numpy") else args.repeat
        t = median_time(f, repeat)
        results[name] = t
        print(f"{name:22s} {t * 1e3:9.2f} ms  {n / t / 1e6:8.2f} M points/s")
    base = results["numpy_ffd float64"]
    for name in ("ff.deform float64", "ff.deform float32", "ff.Binding float64", "ff.Binding float32"):
        print(f"speed-up of {name} over numpy_ffd: {base / results[name]:.1f}x")


if __name__ == "__main__":
    main()
