#!/usr/bin/env python3
"""Free-form deformation from Python: 1,000,000 points (uniform in [-1, 1]^3, seed 7) through a
cubic lattice (4 x 4 x 4 control points, every one displaced), as benchmarks/bench_ffd.cpp does,
with

  - freeform.Lattice.deform (float64 and float32; it binds the points, i.e. computes their lattice
    coordinates, on every call, which the C++ benchmark's FfdBinding does once outside the loop),
  - Lattice.bind(points).deform(lat, out=...) (bound once, written into a preallocated array: what
    the C++ benchmark measures),
  - weights_matvec / weights_rmatvec (the matrix-free sensitivity products),
  - the fastest plain NumPy FFD we could write, measured in the same run: per chunk of points the
    lattice coordinates, per-axis Bernstein matrices, and the tensor sum as matrix products (BLAS):
    "W @ D" with the (chunk, 64) weight matrix W formed by broadcasting, and a two-stage form
    (s-t weights (chunk, 16) @ D (16, 12), then the u weights); the faster of the two is the
    baseline. The einsum(optimize=True) tensor sum PyGeM-style code writes is timed too, for
    reference (it is 4 to 5 times slower than the matrix products).

Prints one line per case (the median of --repeat runs after a warm-up, seconds and M points/s), the
speed-up over the NumPy baseline, and with --memory the peak memory per point of Lattice.deform
(a fresh process, 10^7 points by default: the growth of its peak resident set over the input).
Run from the repository root after building the module:

    PYTHONPATH=build/python python3 benchmarks/python/bench_ffd.py [--points N] [--repeat R] [--memory]

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


def numpy_einsum_ffd(points, origin, axes, control, rest, degree):
    """PyGeM-style vectorised FFD: lattice coordinates, per-axis Bernstein values, one einsum."""
    stu = np.clip((points - origin) @ np.linalg.inv(axes).T, 0.0, 1.0)
    k = np.arange(degree + 1)
    c = np.array([comb(degree, i) for i in k], dtype=np.float64)
    b = [c * stu[:, a, None] ** k * (1 - stu[:, a, None]) ** (degree - k) for a in range(3)]
    d = (control - rest).reshape(degree + 1, degree + 1, degree + 1, 3)
    return points + np.einsum("ni,nj,nk,ijkc->nc", b[0], b[1], b[2], d, optimize=True)


def _bernstein_chunk(stu, degree, coef, powers):
    """(3, n, degree+1) Bernstein values of the three lattice coordinates of a chunk."""
    x = stu.T[:, :, None]  # (3, n, 1)
    return coef * x ** powers * (1.0 - x) ** (degree - powers)


def numpy_wd_ffd(points, origin, axes, control, rest, degree, chunk=8192, out=None):
    """Chunked W @ D: W (chunk, K) = B_i(s) B_j(t) B_k(u) formed by broadcasting, D = P - R (K, 3)."""
    n1 = degree + 1
    dual = np.linalg.inv(axes).T
    powers = np.arange(n1, dtype=np.float64)
    coef = np.array([comb(degree, i) for i in range(n1)], dtype=np.float64)
    D = control - rest
    out = np.empty_like(points) if out is None else out
    for a in range(0, len(points), chunk):
        p = points[a:a + chunk]
        stu = np.clip((p - origin) @ dual, 0.0, 1.0)
        bs, bt, bu = _bernstein_chunk(stu, degree, coef, powers)
        W = (bs[:, :, None, None] * bt[:, None, :, None] * bu[:, None, None, :]).reshape(len(p), n1 ** 3)
        np.add(p, W @ D, out=out[a:a + chunk])
    return out


def numpy_two_stage_ffd(points, origin, axes, control, rest, degree, chunk=8192, out=None):
    """Chunked, in two matrix products: G = (B_i(s) B_j(t)) (chunk, 16) @ D (16, 4*3), then the sum
    over k of B_k(u) G_k: the same tensor sum with a third of the multiplications of forming W."""
    n1 = degree + 1
    dual = np.linalg.inv(axes).T
    powers = np.arange(n1, dtype=np.float64)
    coef = np.array([comb(degree, i) for i in range(n1)], dtype=np.float64)
    D = (control - rest).reshape(n1 * n1, n1 * 3)
    out = np.empty_like(points) if out is None else out
    for a in range(0, len(points), chunk):
        p = points[a:a + chunk]
        stu = np.clip((p - origin) @ dual, 0.0, 1.0)
        bs, bt, bu = _bernstein_chunk(stu, degree, coef, powers)
        G = ((bs[:, :, None] * bt[:, None, :]).reshape(len(p), n1 * n1) @ D).reshape(len(p), n1, 3)
        np.add(p, np.einsum("nk,nkc->nc", bu, G), out=out[a:a + chunk])
    return out


def peak_memory_per_point(points, threads):
    """Bytes per point by which Lattice.deform raises the peak resident set (VmHWM, reset just before
    the call, over VmRSS then), in a fresh process: the output array's 24 plus anything else."""
    import subprocess
    import sys

    code = f"""
import numpy as np, freeform as ff
def status(key):  # kB, from /proc/self/status: VmRSS (now), VmHWM (the peak so far)
    for line in open("/proc/self/status"):
        if line.startswith(key + ":"):
            return int(line.split()[1])
p = np.random.default_rng(7).uniform(-1, 1, ({points}, 3))
lat = ff.Lattice((3, 3, 3), origin=[-1.1, -1.1, -1.1], axes=np.eye(3) * 2.2)
lat.control_points += 0.01
lat.deform(p[:1000], threads={threads})
open("/proc/self/clear_refs", "w").write("5")  # reset VmHWM to the current resident set
before = status("VmRSS")
out = lat.deform(p, threads={threads})
print((status("VmHWM") - before) * 1024 / {points})
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(r.stdout.strip())


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
    ap.add_argument("--numpy-repeat", type=int, default=3)
    ap.add_argument("--threads", type=int, default=0, help="0: the library's default (hardware concurrency)")
    ap.add_argument("--memory", action="store_true", help="also measure Lattice.deform's peak memory per point")
    ap.add_argument("--memory-points", type=int, default=10_000_000)
    args = ap.parse_args()

    rng = np.random.default_rng(7)
    p64 = rng.uniform(-1, 1, (args.points, 3))
    p32 = p64.astype(np.float32)
    lat = make_lattice()
    g = rng.normal(size=p64.shape)
    dP = rng.normal(size=lat.control_points.shape)

    ref = numpy_einsum_ffd(p64, lat.origin, lat.axes, lat.control_points, lat.rest_points, 3)
    assert np.allclose(lat.deform(p64), ref, atol=1e-12), "freeform and NumPy disagree"
    for f in (numpy_wd_ffd, numpy_two_stage_ffd):
        assert np.allclose(f(p64, lat.origin, lat.axes, lat.control_points, lat.rest_points, 3), ref, atol=1e-12)

    n = args.points
    b64, b32 = lat.bind(p64), lat.bind(p32)
    o64, o32, onp = np.empty_like(p64), np.empty_like(p32), np.empty_like(p64)
    frame = (lat.origin, lat.axes, lat.control_points, lat.rest_points, 3)
    cases = [
        ("numpy W @ D", lambda: numpy_wd_ffd(p64, *frame, out=onp)),
        ("numpy two-stage", lambda: numpy_two_stage_ffd(p64, *frame, out=onp)),
        ("numpy einsum", lambda: numpy_einsum_ffd(p64, *frame)),
        ("ff.deform float64", lambda: lat.deform(p64, threads=args.threads)),
        ("ff.deform float32", lambda: lat.deform(p32, threads=args.threads)),
        ("ff.Binding float64", lambda: b64.deform(lat, threads=args.threads, out=o64)),
        ("ff.Binding float32", lambda: b32.deform(lat, threads=args.threads, out=o32)),
        ("ff.weights_matvec", lambda: lat.weights_matvec(p64, dP, threads=args.threads)),
        ("ff.weights_rmatvec", lambda: lat.weights_rmatvec(p64, g, threads=args.threads)),
    ]
    print(f"{n} points, cubic lattice, threads={args.threads or os.cpu_count()}, median of {args.repeat} "
          f"(NumPy: median of {args.numpy_repeat}) after a warm-up")
    results = {}
    for name, f in cases:
        repeat = args.numpy_repeat if name.startswith("numpy") else args.repeat
        t = median_time(f, repeat)
        results[name] = t
        print(f"{name:22s} {t * 1e3:9.2f} ms  {n / t / 1e6:8.2f} M points/s")
    best = min(("numpy W @ D", "numpy two-stage"), key=results.get)
    base = results[best]
    print(f"NumPy baseline: {best} ({base * 1e3:.1f} ms; einsum {results['numpy einsum'] / base:.1f}x slower)")
    for name in ("ff.deform float64", "ff.deform float32", "ff.Binding float64", "ff.Binding float32",
                 "ff.weights_matvec", "ff.weights_rmatvec"):
        print(f"speed-up of {name} over {best}: {base / results[name]:.1f}x")
    if args.memory:
        per_point = peak_memory_per_point(args.memory_points, args.threads)
        print(f"Lattice.deform peak memory over the input, {args.memory_points} float64 points: "
              f"{per_point:.1f} bytes per point (the output alone: 24)")


if __name__ == "__main__":
    main()
