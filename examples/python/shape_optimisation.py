#!/usr/bin/env python3
"""A tiny shape optimisation with the sensitivities (docs/python.md, "Sensitivities").

    PYTHONPATH=build/python python3 examples/python/shape_optimisation.py

Design variables: the control points P (K, 3) of a cubic lattice around a sphere mesh. Objective:
J(P) = (V(x(P)) - V_target)^2 with V the enclosed volume of the deformed mesh x = deform(points).
The chain rule gives dJ/dP = W^T (dJ/dx), computed without forming W by weights_rmatvec (the call
an adjoint solver makes); gradient descent moves the lattice until the volume reaches the target.
"""
import pathlib

import numpy as np

import freeform as ff

root = pathlib.Path(__file__).resolve().parents[2]
mesh = ff.MeshFile.read(str(root / "data" / "meshes" / "sphere.obj"))
points, faces, _ = mesh.to_arrays()
tris = np.array([[f[0], f[k], f[k + 1]] for f in faces for k in range(1, len(f) - 1)])


def volume_and_gradient(x):
    """V = 1/6 sum det(a, b, c) over the triangles, and dV/dx (N, 3)."""
    a, b, c = x[tris[:, 0]], x[tris[:, 1]], x[tris[:, 2]]
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
    g = np.zeros_like(x)
    np.add.at(g, tris[:, 0], np.cross(b, c) / 6)
    np.add.at(g, tris[:, 1], np.cross(c, a) / 6)
    np.add.at(g, tris[:, 2], np.cross(a, b) / 6)
    return volume, g


lat = ff.Lattice.fit(points, degree=(3, 3, 3))
v0, _ = volume_and_gradient(points)
target = 1.5 * v0
print(f"start volume {v0:.5f}, target {target:.5f}")
for step in range(50):
    x = lat.deform(points)
    v, dv_dx = volume_and_gradient(x)
    residual = v - target
    if abs(residual) < 1e-10 * target:
        break
    grad = lat.weights_rmatvec(points, 2 * residual * dv_dx)  # dJ/dP = W^T dJ/dx, (K, 3)
    # steepest descent with the step a Gauss-Newton model of J along -grad suggests
    dv_dP = grad / (2 * residual)
    lat.control_points -= 0.8 * residual * dv_dP / np.sum(dv_dP * dv_dP)
    print(f"step {step:2d}: volume {v:.6f}  |grad| {np.linalg.norm(grad):.3e}")
x = lat.deform(points)
print(f"final volume {volume_and_gradient(x)[0]:.6f} (target {target:.6f}); certificate:", lat.certify()["verdict"])
