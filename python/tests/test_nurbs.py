# The rational and NURBS types from Python (docs/python.md, "Rational Bézier and NURBS"), checked
# against independent NumPy computations: the Cox-de Boor recursion, rational Bernstein sums, the
# circle and the sphere, central finite differences, identities of knot insertion / extraction /
# elevation, interpolation through its data, the command-line tool on the same documents, and the
# rational FFD formula of docs/nurbs.md.
import json
import math

import numpy as np
import pytest

import freeform as ff
from conftest import bernstein, run_cli, ticks_during


# ---------------------------------------------------------------- independent references

def cox_de_boor(knots, p, u):
    """(len(u), n+1) B-spline basis N_(i,p)(u) by the Cox-de Boor recursion (half-open spans, 0/0 = 0),
    in NumPy; u must lie in [u_p, u_(n+1)) (the right end is not special-cased)."""
    U = np.asarray(knots, dtype=np.float64)
    u = np.asarray(u, dtype=np.float64)[:, None]
    N = ((U[:-1][None, :] <= u) & (u < U[1:][None, :])).astype(np.float64)
    for k in range(1, p + 1):
        left_den = U[k:-1] - U[: -k - 1]
        right_den = U[k + 1:] - U[1:-k]
        with np.errstate(divide="ignore", invalid="ignore"):
            a = np.where(left_den > 0, (u - U[None, : -k - 1]) / left_den, 0.0)
            b = np.where(right_den > 0, (U[None, k + 1:] - u) / right_den, 0.0)
        N = a * N[:, :-1] + b * N[:, 1:]
    return N


def nurbs_reference(knots, p, points, weights, u):
    N = cox_de_boor(knots, p, u) * weights[None, :]
    return (N @ points) / N.sum(axis=1, keepdims=True)


def rational_bernstein(points, weights, t):
    B = bernstein(len(points) - 1, t) * weights[None, :]
    return (B @ points) / B.sum(axis=1, keepdims=True)


def random_knots(rng, p, count, clamped):
    """A random knot vector for `count` control points of degree p with repeated interior knots
    (multiplicity up to p) and, when not clamped, distinct random end knots."""
    interior = count - p - 1
    values = np.sort(rng.uniform(0.1, 0.9, max(interior, 1)))
    k = []
    while len(k) < interior:
        v = values[len(k) % len(values)]
        k.extend([v] * min(int(rng.integers(1, p + 1)), interior - len(k)))
    k = sorted(k)
    if clamped:
        return np.array([0.0] * (p + 1) + k + [1.0] * (p + 1))
    lo = np.sort(rng.uniform(-0.5, 0.0, p + 1))
    hi = np.sort(rng.uniform(1.0, 1.5, p + 1))
    return np.concatenate([lo, k, hi])


def interior_params(curve, n, rng):
    a, b = curve.domain
    u = np.sort(rng.uniform(a, b, n))
    knots = curve.knots
    return u[np.min(np.abs(u[:, None] - knots[None, :]), axis=1) > 1e-9]


# ---------------------------------------------------------------- evaluation

@pytest.mark.parametrize("p", [1, 2, 3, 4, 5])
@pytest.mark.parametrize("clamped", [True, False])
def test_nurbs_curve_equals_numpy_cox_de_boor(p, clamped):
    rng = np.random.default_rng(10 * p + clamped)
    for dim in (2, 3):
        count = p + 1 + int(rng.integers(0, 7))
        knots = random_knots(rng, p, count, clamped)
        P = rng.normal(size=(count, dim))
        w = rng.uniform(0.2, 3.0, count)
        c = ff.NurbsCurve(p, knots, P, w)
        assert c.degree == p and c.dimension == dim and c.control_count == count and c.is_rational
        np.testing.assert_array_equal(c.knots, knots)
        np.testing.assert_allclose(c.weights, w, rtol=1e-15)
        np.testing.assert_allclose(c.control_points, P, rtol=1e-14, atol=1e-15)
        assert c.domain == (knots[p], knots[count])
        u = interior_params(c, 200, rng)
        ref = nurbs_reference(knots, p, P, w, u)
        np.testing.assert_allclose(c.evaluate(u), ref, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(c.derivatives(u, 0)[:, 0], ref, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(c(u), ref, rtol=1e-12, atol=1e-12)
        # the polynomial B-spline (no weights) is the plain basis sum
        b = ff.NurbsCurve(p, knots, P)
        assert not b.is_rational
        np.testing.assert_allclose(b.evaluate(u), cox_de_boor(knots, p, u) @ P, rtol=1e-12, atol=1e-12)


def test_rational_bezier_curve_equals_numpy_rational_bernstein():
    rng = np.random.default_rng(3)
    for n in range(1, 8):
        for dim in (2, 3):
            P = rng.normal(size=(n + 1, dim))
            w = rng.uniform(0.1, 4.0, n + 1)
            c = ff.RationalBezierCurve(P, w)
            t = np.linspace(0, 1, 101)
            np.testing.assert_allclose(c.evaluate(t), rational_bernstein(P, w, t), rtol=1e-13, atol=1e-13)
            np.testing.assert_allclose(c.homogeneous_points, np.hstack([P * w[:, None], w[:, None]]), rtol=1e-15)
            assert c.degree == n and c.dimension == dim


def test_rational_bezier_surface_equals_numpy_tensor_sum():
    rng = np.random.default_rng(4)
    m, n = 3, 2
    P = rng.normal(size=(m + 1, n + 1, 3))
    w = rng.uniform(0.3, 2.5, (m + 1, n + 1))
    s = ff.RationalBezierSurface(P, w)
    assert s.degree == (m, n)
    np.testing.assert_allclose(s.control_points, P, rtol=1e-14)
    np.testing.assert_allclose(s.weights, w, rtol=1e-15)
    uv = rng.uniform(0, 1, (50, 2))
    Bu, Bv = bernstein(m, uv[:, 0]), bernstein(n, uv[:, 1])
    num = np.einsum("ki,kj,ij,ijc->kc", Bu, Bv, w, P)
    den = np.einsum("ki,kj,ij->k", Bu, Bv, w)
    np.testing.assert_allclose(s.evaluate(uv), num / den[:, None], rtol=1e-13, atol=1e-13)


def test_nurbs_surface_equals_numpy_tensor_cox_de_boor():
    rng = np.random.default_rng(5)
    p, q, nu, nv = 3, 2, 6, 5
    ku = random_knots(rng, p, nu, True)
    kv = random_knots(rng, q, nv, False)
    P = rng.normal(size=(nu, nv, 3))
    w = rng.uniform(0.3, 2.5, (nu, nv))
    s = ff.NurbsSurface((p, q), ku, kv, P, w)
    assert s.degree == (p, q) and s.count == (nu, nv) and s.is_rational
    np.testing.assert_allclose(s.control_points, P, rtol=1e-14, atol=1e-15)
    (u0, u1), (v0, v1) = s.domain
    uv = np.column_stack([rng.uniform(u0, u1, 80), rng.uniform(v0, v1, 80)])
    Nu, Nv = cox_de_boor(ku, p, uv[:, 0]), cox_de_boor(kv, q, uv[:, 1])
    num = np.einsum("ki,kj,ij,ijc->kc", Nu, Nv, w, P)
    den = np.einsum("ki,kj,ij->k", Nu, Nv, w)
    np.testing.assert_allclose(s.evaluate(uv), num / den[:, None], rtol=1e-12, atol=1e-12)
    # the grid batch path gives the same points
    us, vs = np.linspace(u0, u1, 7)[:-1], np.linspace(v0, v1, 5)[:-1]
    G = s.evaluate_grid(us, vs)
    assert G.shape == (6, 4, 3)
    pts = np.array([[a, b] for a in us for b in vs])
    np.testing.assert_allclose(G.reshape(-1, 3), s.evaluate(pts), rtol=1e-12, atol=1e-12)


# ---------------------------------------------------------------- conics

def test_circle_and_arcs_have_radius_one():
    t = np.linspace(0, 1, 2001)
    for center in ([0, 0], [0, 0, 0]):
        c = ff.NurbsCurve.circle(center, 1.0)
        r = np.linalg.norm(c.evaluate(t), axis=1)
        np.testing.assert_allclose(r, 1.0, rtol=0, atol=2e-15)
        # quarter points by hand: (1, 0), (0, 1), (-1, 0), (0, -1)
        np.testing.assert_allclose(c.evaluate([0, 0.25, 0.5, 0.75])[:, :2], [[1, 0], [0, 1], [-1, 0], [0, -1]], atol=1e-15)
        assert abs(c.arc_length(1e-12) - 2 * math.pi) < 1e-10
    for sweep in (0.3, 2.0, math.pi, -math.pi / 2):
        a = ff.RationalBezierCurve.circle_arc([0, 0], 1.0, 0.4, sweep)
        np.testing.assert_allclose(np.linalg.norm(a.evaluate(t), axis=1), 1.0, atol=2e-15)
        np.testing.assert_allclose(a.evaluate([1.0])[0], [math.cos(0.4 + sweep), math.sin(0.4 + sweep)], atol=1e-15)
        assert abs(a.arc_length(1e-12) - abs(sweep)) < 1e-10
    e = ff.RationalBezierCurve.ellipse_arc([1, 2], [2, 0], [0, 1], 0.0, 2.0)
    x = e.evaluate(t)
    np.testing.assert_allclose(((x[:, 0] - 1) / 2) ** 2 + (x[:, 1] - 2) ** 2, 1.0, atol=1e-14)


def test_sphere_has_radius_one_and_outward_normals():
    s = ff.NurbsSurface.sphere([0, 0, 0], 1.0)
    u = np.linspace(0, 1, 41)
    G = s.evaluate_grid(u, u)
    np.testing.assert_allclose(np.linalg.norm(G, axis=2), 1.0, atol=1e-14)
    uv = np.random.default_rng(6).uniform(0.01, 0.99, (100, 2))
    X = s.evaluate(uv)
    n = s.normal(uv)
    np.testing.assert_allclose(np.abs(np.sum(n * X, axis=1)), 1.0, atol=1e-12)


# ---------------------------------------------------------------- derivatives

def test_curve_derivatives_match_central_differences():
    rng = np.random.default_rng(7)
    knots = random_knots(rng, 4, 9, True)
    c = ff.NurbsCurve(4, knots, rng.normal(size=(9, 3)), rng.uniform(0.5, 2, 9))
    u = interior_params(c, 40, rng)
    u = u[np.min(np.abs(u[:, None] - knots[None, :]), axis=1) > 1e-3]
    h = 1e-5
    J = c.derivatives(u, 3)
    assert J.shape == (len(u), 4, 3)
    for k in (1, 2, 3):
        fd = (c.derivatives(u + h, k - 1)[:, k - 1] - c.derivatives(u - h, k - 1)[:, k - 1]) / (2 * h)
        np.testing.assert_allclose(J[:, k], fd, rtol=1e-5, atol=1e-5 * np.abs(J[:, k]).max())
    P, D = c.evaluate_with_derivative(u)
    np.testing.assert_allclose(P, J[:, 0], rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(D, J[:, 1], rtol=1e-10, atol=1e-10)
    r = ff.RationalBezierCurve(rng.normal(size=(5, 2)), rng.uniform(0.5, 2, 5))
    t = np.linspace(0.05, 0.95, 19)
    d = r.derivatives(t, 2)
    np.testing.assert_allclose(d[:, 1], (r.evaluate(t + h) - r.evaluate(t - h)) / (2 * h), rtol=1e-6, atol=1e-7)
    np.testing.assert_allclose(d[:, 2], (r.derivatives(t + h, 1)[:, 1] - r.derivatives(t - h, 1)[:, 1]) / (2 * h),
                               rtol=1e-5, atol=1e-5)


def test_surface_derivatives_match_central_differences():
    rng = np.random.default_rng(8)
    s = ff.NurbsSurface((3, 2), random_knots(rng, 3, 5, True), random_knots(rng, 2, 4, True),
                        rng.normal(size=(5, 4, 3)), rng.uniform(0.5, 2, (5, 4)))
    uv = rng.uniform(0.05, 0.95, (30, 2))
    ku, kv = s.knots_u, s.knots_v
    keep = (np.min(np.abs(uv[:, :1] - ku[None, :]), axis=1) > 1e-3) & (np.min(np.abs(uv[:, 1:] - kv[None, :]), axis=1) > 1e-3)
    uv = uv[keep]
    h = 1e-5
    J = s.derivatives(uv, 2)
    assert J.shape == (len(uv), 6, 3)
    du, dv = np.array([h, 0]), np.array([0, h])
    np.testing.assert_allclose(J[:, 1], (s.evaluate(uv + du) - s.evaluate(uv - du)) / (2 * h), rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(J[:, 2], (s.evaluate(uv + dv) - s.evaluate(uv - dv)) / (2 * h), rtol=1e-6, atol=1e-6)
    fuv = (s.partial(1, 0, uv + dv) - s.partial(1, 0, uv - dv)) / (2 * h)
    np.testing.assert_allclose(J[:, 4], fuv, rtol=1e-5, atol=1e-5)
    np.testing.assert_allclose(s.partial(0, 2, uv), J[:, 5], rtol=1e-14, atol=1e-13)
    G, Gu, Gv = s.evaluate_grid(uv[:3, 0], uv[:3, 1], derivatives=True)
    np.testing.assert_allclose(Gu[1, 2], s.partial(1, 0, [[uv[1, 0], uv[2, 1]]])[0], rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(Gv[2, 0], s.partial(0, 1, [[uv[2, 0], uv[0, 1]]])[0], rtol=1e-11, atol=1e-12)
    r = ff.RationalBezierSurface(rng.normal(size=(3, 4, 3)), rng.uniform(0.5, 2, (3, 4)))
    uv = rng.uniform(0.05, 0.95, (10, 2))
    np.testing.assert_allclose(r.partial(1, 0, uv), (r.evaluate(uv + du) - r.evaluate(uv - du)) / (2 * h), rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(r.derivatives(uv, 1)[:, 2], (r.evaluate(uv + dv) - r.evaluate(uv - dv)) / (2 * h),
                               rtol=1e-6, atol=1e-6)


# ---------------------------------------------------------------- knots, extraction, elevation

def test_knot_insertion_refinement_and_extraction_leave_the_curve_unchanged():
    rng = np.random.default_rng(9)
    knots = random_knots(rng, 3, 8, True)
    c = ff.NurbsCurve(3, knots, rng.normal(size=(8, 3)), rng.uniform(0.5, 2, 8))
    u = np.linspace(0, 1, 301)
    X = c.evaluate(u)
    k = c.insert_knot(0.37, 2)
    assert k.control_count == 10 and np.count_nonzero(k.knots == 0.37) == 2
    np.testing.assert_allclose(k.evaluate(u), X, atol=1e-13)
    r = c.refined([0.2, 0.5, 0.5, 0.77])
    assert r.control_count == 12
    np.testing.assert_allclose(r.evaluate(u), X, atol=1e-13)
    removed, err = k.remove_knot(0.37)
    assert err < 1e-12 and removed.control_count == 9
    np.testing.assert_allclose(removed.evaluate(u), X, atol=1e-12)
    pieces = c.bezier_pieces()
    br = c.breakpoints
    assert len(pieces) == len(br) - 1
    for piece, a, b in zip(pieces, br[:-1], br[1:]):
        s = np.linspace(0, 1, 21)
        np.testing.assert_allclose(piece.evaluate(s), c.evaluate(a + (b - a) * s), atol=1e-13)
    left, right = c.split(0.6)
    assert left.domain == (0.0, 0.6) and right.domain == (0.6, 1.0)
    np.testing.assert_allclose(left.evaluate(u * 0.6), c.evaluate(u * 0.6), atol=1e-13)
    np.testing.assert_allclose(right.evaluate(0.6 + 0.4 * u), c.evaluate(0.6 + 0.4 * u), atol=1e-13)
    np.testing.assert_allclose(c.reversed().evaluate(u), X[::-1], atol=1e-13)
    e = c.elevated(2)
    assert e.degree == 5
    np.testing.assert_allclose(e.evaluate(u), X, atol=1e-12)
    back, bound = e.reduced(1e-9)
    assert back.degree == 4 and bound < 1e-9
    np.testing.assert_allclose(back.evaluate(u), X, atol=1e-9)


def test_rational_bezier_operations_keep_the_curve():
    rng = np.random.default_rng(10)
    c = ff.RationalBezierCurve(rng.normal(size=(5, 3)), rng.uniform(0.3, 3, 5))
    t = np.linspace(0, 1, 51)
    a, b = c.split(0.3)
    np.testing.assert_allclose(a.evaluate(t), c.evaluate(0.3 * t), atol=1e-13)
    np.testing.assert_allclose(b.evaluate(t), c.evaluate(0.3 + 0.7 * t), atol=1e-13)
    np.testing.assert_allclose(c.elevated(3).evaluate(t), c.evaluate(t), atol=1e-13)
    np.testing.assert_allclose(c.reversed().evaluate(t), c.evaluate(1 - t), atol=1e-13)
    sf = c.standard_form()
    assert sf.weights[0] == 1 and sf.weights[-1] == 1
    # the Möbius reparametrisation: sf(s) = c(k s / ((1 - s) + k s)), k = (w_0 / w_n)^(1/n)
    w = c.weights
    k = (w[0] / w[-1]) ** (1 / 4)
    np.testing.assert_allclose(sf.evaluate(t), c.evaluate(k * t / ((1 - t) + k * t)), atol=1e-13)
    np.testing.assert_allclose(c.to_nurbs().evaluate(t), c.evaluate(t), atol=1e-14)
    np.testing.assert_allclose(ff.NurbsCurve.from_bezier(c).evaluate(t), c.evaluate(t), atol=1e-14)
    lo, hi = c.bounds()
    X = c.evaluate(np.linspace(0, 1, 10001))
    assert np.all(X >= lo - 1e-12) and np.all(X <= hi + 1e-12)
    np.testing.assert_allclose(X.min(axis=0), lo, atol=1e-6)  # tight: attained up to the sampling
    np.testing.assert_allclose(X.max(axis=0), hi, atol=1e-6)


def test_surface_refinement_and_extraction_leave_the_surface_unchanged():
    rng = np.random.default_rng(11)
    s = ff.NurbsSurface((2, 3), random_knots(rng, 2, 5, True), random_knots(rng, 3, 6, True),
                        rng.normal(size=(5, 6, 3)), rng.uniform(0.5, 2, (5, 6)))
    g = np.linspace(0, 1, 13)
    X = s.evaluate_grid(g, g)
    np.testing.assert_allclose(s.refined_u([0.3, 0.55]).evaluate_grid(g, g), X, atol=1e-13)
    np.testing.assert_allclose(s.insert_knot_v(0.45, 2).evaluate_grid(g, g), X, atol=1e-13)
    patches = s.bezier_patches()
    bu = np.unique(s.knots_u)
    bv = np.unique(s.knots_v)
    assert len(patches) == (len(bu) - 1) * (len(bv) - 1)
    loc = np.array([[0.2, 0.7], [0.9, 0.1], [0.5, 0.5]])
    for a in range(len(bu) - 1):
        for b in range(len(bv) - 1):
            p = patches[a * (len(bv) - 1) + b]
            glob = np.column_stack([bu[a] + (bu[a + 1] - bu[a]) * loc[:, 0], bv[b] + (bv[b + 1] - bv[b]) * loc[:, 1]])
            np.testing.assert_allclose(p.evaluate(loc), s.evaluate(glob), atol=1e-13)
    np.testing.assert_allclose(s.curve_at_v(0.4).evaluate(g), s.evaluate(np.column_stack([g, np.full_like(g, 0.4)])), atol=1e-13)
    np.testing.assert_allclose(s.curve_at_u(0.7).evaluate(g), s.evaluate(np.column_stack([np.full_like(g, 0.7), g])), atol=1e-13)
    r = patches[0]
    t = np.column_stack([g, g[::-1]])
    np.testing.assert_allclose(r.elevated(1, 2).evaluate(t), r.evaluate(t), atol=1e-13)
    np.testing.assert_allclose(r.transposed().evaluate(t[:, ::-1]), r.evaluate(t), atol=1e-14)
    a, b = r.split_u(0.4)
    np.testing.assert_allclose(a.evaluate(np.column_stack([g, g])), r.evaluate(np.column_stack([0.4 * g, g])), atol=1e-13)
    np.testing.assert_allclose(r.to_nurbs().evaluate(t), r.evaluate(t), atol=1e-14)
    # every tessellation vertex is a surface point: on the unit sphere, at radius 1
    V, F, N = ff.NurbsSurface.sphere().tessellate(segments=4)
    assert F.shape[1] == 3 and V.shape == N.shape and len(F) > 0
    np.testing.assert_allclose(np.linalg.norm(V, axis=1), 1.0, atol=1e-14)
    V, F, N = ff.NurbsSurface.sphere().tessellate(tolerance=1e-3)
    np.testing.assert_allclose(np.linalg.norm(V, axis=1), 1.0, atol=1e-14)
    V, F, N = r.tessellate(segments=3)
    assert len(V) == 16 and len(F) == 18


def test_continuity_report_at_every_knot():
    # C2 cubic B-spline, a double knot (C1) and a triple knot (C0) in one curve
    knots = [0, 0, 0, 0, 0.25, 0.5, 0.5, 0.75, 0.75, 0.75, 1, 1, 1, 1]
    rng = np.random.default_rng(12)
    c = ff.NurbsCurve(3, knots, rng.normal(size=(10, 2)))
    rep = c.continuity()
    assert [j["t"] for j in rep] == [0.25, 0.5, 0.75]
    assert [j["C"] for j in rep] == [2, 1, 0]
    # inserting a knot into a smooth curve changes nothing: the new knot is reported C2
    rep2 = c.insert_knot(0.125).continuity()
    assert rep2[0]["t"] == 0.125 and rep2[0]["C"] >= 2
    # the circle: C1 and G2 (curvature 1 on both sides) at the quarter knots
    circ = ff.NurbsCurve.circle()
    assert all(j["G"] == 2 for j in circ.continuity())


# ---------------------------------------------------------------- interpolation, approximation

def test_interpolation_passes_through_the_data_and_reproduces_polynomials():
    rng = np.random.default_rng(13)
    pts = np.cumsum(rng.uniform(0.2, 1.0, (9, 3)), axis=0)
    chord = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    chord /= chord[-1]
    for p in (1, 2, 3, 5):
        c = ff.interpolate_nurbs(pts, degree=p)
        assert c.degree == p and c.domain == (0.0, 1.0)
        np.testing.assert_allclose(c.evaluate(chord), pts, atol=1e-12)
    cen = np.concatenate([[0], np.cumsum(np.sqrt(np.linalg.norm(np.diff(pts, axis=0), axis=1)))])
    c = ff.interpolate_nurbs(pts, degree=4, parametrization="centripetal")
    np.testing.assert_allclose(c.evaluate(cen / cen[-1]), pts, atol=1e-12)
    # end derivatives (with respect to the normalised parameter)
    c = ff.interpolate_nurbs(pts, degree=3, start_derivative=[1, 0, 0], end_derivative=[0, 2, 0])
    assert c.control_count == len(pts) + 2
    np.testing.assert_allclose(c.evaluate(chord), pts, atol=1e-12)
    np.testing.assert_allclose(c.derivatives([0.0, 1.0], 1)[:, 1], [[1, 0, 0], [0, 2, 0]], atol=1e-11)
    # a cubic polynomial sampled at given parameters is reproduced everywhere
    poly = lambda t: np.column_stack([t, 2 * t**2 - t, t**3 - 0.5 * t])  # noqa: E731
    params = np.sort(np.concatenate([[0, 1], rng.uniform(0, 1, 8)]))
    c = ff.interpolate_nurbs(poly(params), degree=3, params=params)
    t = np.linspace(0, 1, 101)
    np.testing.assert_allclose(c.evaluate(t), poly(t), atol=1e-12)
    # least squares: ends interpolated, a cubic sampled densely is reproduced by any cubic B-spline space
    dense = np.linspace(0, 1, 40)
    a = ff.approximate_nurbs(poly(dense), 7, degree=3, params=dense)
    assert a.control_count == 7 and a.degree == 3
    np.testing.assert_allclose(a.evaluate([0, 1]), poly(np.array([0.0, 1.0])), atol=1e-13)
    np.testing.assert_allclose(a.evaluate(t), poly(t), atol=1e-11)


def test_from_spline_and_polynomial_conversion_keep_the_curve():
    pts = np.array([[0, 0], [1, 2], [3, 3], [4, 0], [6, 1]], dtype=float)
    s = ff.Spline.interpolate(pts)
    n = ff.NurbsCurve.from_spline(s)
    assert n.degree == 3 and n.domain == (0.0, s.domain_end) and not n.is_rational
    T = np.linspace(0, s.domain_end, 77)
    np.testing.assert_allclose(n.evaluate(T), s.evaluate(T), atol=1e-12)
    b = ff.BezierCurve([[0, 0, 0], [1, 2, 0], [3, 2, 1]])
    np.testing.assert_allclose(ff.NurbsCurve.from_bezier(b).evaluate(T / T[-1]), b.evaluate(T / T[-1]), atol=1e-14)
    patch = ff.Patch(np.random.default_rng(14).normal(size=(3, 4, 3)))
    uv = np.random.default_rng(15).uniform(0, 1, (20, 2))
    np.testing.assert_allclose(ff.NurbsSurface.from_bezier(patch).evaluate(uv), patch.evaluate(uv), atol=1e-14)


# ---------------------------------------------------------------- documents and the CLI

def nurbs_doc(tmp_path):
    doc = {"format": "freeform", "version": 1, "objects": [
        {"name": "circle", "type": "nurbs_curve", "degree": 2, "knots": [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4],
         "points": [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]],
         "weights": [1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1]},
        {"name": "wave", "type": "nurbs_curve", "degree": 3, "knots": [0, 0, 0, 0, 0.3, 0.3, 0.6, 1, 1, 1, 1],
         "points": [[0, 0, 0], [1, 2, 0], [2, -1, 1], [3, 0, 2], [4, 3, 0], [5, 1, 1], [6, 0, 0]],
         "weights": [1, 2, 0.5, 1, 3, 1, 1]},
        {"name": "arc", "type": "rational_bezier_curve", "points": [[1, 0], [1, 1], [0, 1]], "weights": [1, 0.5, 1]},
        {"name": "sheet", "type": "nurbs_surface", "degree": [2, 1], "knots": [[0, 0, 0, 0.5, 1, 1, 1], [0, 0, 2, 2]],
         "points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 1], [1, 1, 0]], [[2, 0, 0], [2, 1, 1]], [[3, 0, 0], [3, 1, 0]]],
         "weights": [[1, 1], [2, 1], [1, 0.5], [1, 1]]},
        {"name": "rpatch", "type": "rational_bezier_surface", "degree": [1, 2],
         "points": [[[0, 0, 0], [0, 1, 1], [0, 2, 0]], [[1, 0, 0], [1, 1, 2], [1, 2, 0]]],
         "weights": [[1, 2, 1], [1, 0.5, 1]]},
    ]}
    path = tmp_path / "nurbs.json"
    path.write_text(json.dumps(doc))
    return path


def test_document_objects_are_the_new_types_and_match_the_cli(tmp_path):
    path = nurbs_doc(tmp_path)
    doc = ff.Document.load(str(path))
    circle, wave, arc = doc.object("circle"), doc.object("wave"), doc.object("arc")
    assert isinstance(circle, ff.NurbsCurve) and isinstance(wave, ff.NurbsCurve)
    assert isinstance(arc, ff.RationalBezierCurve) and isinstance(doc.curve("arc"), ff.RationalBezierCurve)
    assert isinstance(doc.object("sheet"), ff.NurbsSurface)
    assert isinstance(doc.object("rpatch"), ff.RationalBezierSurface)
    # docs/format.md: the circle is at (0, 1) for T = 1 and at (-1, 0) for T = 2
    np.testing.assert_allclose(circle.evaluate([1, 2]), [[0, 1], [-1, 0]], atol=1e-15)
    for name, at in [("circle", 1.3), ("wave", 0.3), ("wave", 0.45), ("wave", 1.0), ("arc", 0.25)]:
        out = json.loads(run_cli("eval", path, "--object", name, "--at", at, "--derivatives", 2))
        jet = doc.object(name).derivatives([at], 2)[0]
        np.testing.assert_allclose(jet[0], out["point"], rtol=1e-14, atol=1e-15)
        np.testing.assert_allclose(jet[1:], out["derivatives"], rtol=1e-13, atol=1e-14)
        e = doc.evaluate(name, [at], 2)
        np.testing.assert_allclose(e["point"], out["point"], rtol=1e-15, atol=0)
    for name, at in [("sheet", (0.7, 1.5)), ("rpatch", (0.3, 0.6))]:
        out = json.loads(run_cli("eval", path, "--object", name, "--at", f"{at[0]},{at[1]}", "--derivatives", 1))
        s = doc.object(name)
        np.testing.assert_allclose(s.evaluate([at])[0], out["point"], rtol=1e-14, atol=1e-15)
        np.testing.assert_allclose(s.normal([at])[0], out["normal"], rtol=1e-13, atol=1e-14)
        np.testing.assert_allclose(s.partial(1, 0, [at])[0], out["derivatives"]["u"], rtol=1e-13, atol=1e-14)
        np.testing.assert_allclose(s.partial(0, 1, [at])[0], out["derivatives"]["v"], rtol=1e-13, atol=1e-14)
    # continuity of a nurbs_curve: the same report as `freeform continuity`
    out = json.loads(run_cli("continuity", path, "--object", "wave"))
    rep = wave.continuity()
    assert [(j["t"], j["C"], j["G"]) for j in out["joints"]] == [(j["t"], j["C"], j["G"]) for j in rep]
    np.testing.assert_allclose([j["jumps"] for j in out["joints"]], [j["jumps"] for j in rep], rtol=1e-15)


def test_documents_add_save_and_load_the_new_types(tmp_path):
    rng = np.random.default_rng(16)
    doc = ff.Document()
    c = ff.NurbsCurve(3, random_knots(rng, 3, 7, False), rng.normal(size=(7, 3)), rng.uniform(0.5, 2, 7))
    r = ff.RationalBezierCurve(rng.normal(size=(4, 2)), rng.uniform(0.5, 2, 4))
    s = ff.NurbsSurface.sphere([1, 2, 3], 2.0)
    p = ff.RationalBezierSurface(rng.normal(size=(2, 3, 3)), rng.uniform(0.5, 2, (2, 3)))
    for name, obj in [("c", c), ("r", r), ("s", s), ("p", p), ("b", ff.BezierCurve([[0, 0], [1, 1]]))]:
        doc.add(name, obj)
    with pytest.raises(ff.Error, match='"c" exists already'):
        doc.add("c", c)
    with pytest.raises(TypeError):
        doc.add("x", "not geometry")
    path = tmp_path / "out.json"
    doc.save(str(path))
    data = json.loads(path.read_text())
    assert [o["type"] for o in data["objects"]] == ["nurbs_curve", "rational_bezier_curve", "nurbs_surface",
                                                    "rational_bezier_surface", "bezier_curve"]
    np.testing.assert_array_equal(data["objects"][0]["knots"], c.knots)
    back = ff.Document.load(str(path))
    t = np.linspace(*c.domain, 31)
    np.testing.assert_array_equal(back.object("c").evaluate(t), c.evaluate(t))
    np.testing.assert_array_equal(back.object("r").weights, r.weights)
    uv = rng.uniform(0, 1, (10, 2))
    np.testing.assert_allclose(back.object("s").evaluate(uv), s.evaluate(uv), rtol=1e-15)
    np.testing.assert_allclose(back.object("p").evaluate(uv), p.evaluate(uv), rtol=1e-15)
    # the CLI reads what Python wrote
    out = json.loads(run_cli("eval", path, "--object", "c", "--at", t[7]))
    np.testing.assert_allclose(out["point"], c.evaluate([t[7]])[0], rtol=1e-15)
    # replace, convert (as `freeform convert --to`), remove
    back.replace("b", ff.NurbsCurve.circle())
    assert back.type("b") == "nurbs_curve"
    assert back.convert("p", "nurbs_surface") == "nurbs_surface"
    np.testing.assert_allclose(back.object("p").evaluate(uv), p.evaluate(uv), atol=1e-14)
    assert back.convert("p", "rational_bezier_surface") == "rational_bezier_surface"
    with pytest.raises(ff.Error, match="no single-object Bézier form"):
        back.convert("c", "rational_bezier_curve")
    with pytest.raises(ff.Error, match="converts to a nurbs_curve, not a nurbs_surface"):
        back.convert("r", "nurbs_surface")
    back.remove("c")
    assert "c" not in back and len(back) == 4


def test_document_object_refuses_types_without_a_python_object(tmp_path):
    path = tmp_path / "d.json"
    path.write_text(json.dumps({"format": "freeform", "version": 1, "objects": [{"name": "cage", "type": "subdivision_surface",
                                             "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
                                             "faces": [[0, 1, 2, 3]]}]}))
    doc = ff.Document.load(str(path))
    with pytest.raises(ff.Error, match='object "cage".*subdivision_surface has no Python object'):
        doc.object("cage")
    with pytest.raises(ff.Error, match=r"no object named \"nope\" \(objects: cage\)"):
        doc.object("nope")


# ---------------------------------------------------------------- rational FFD

def reference_rational_deform(lat, weights, points):
    """p + w_s N / D (docs/nurbs.md, "Rational FFD") in NumPy: N = sum w B (P - R), D = sum w B,
    with the clamp policy on the lattice coordinates."""
    points = np.asarray(points, dtype=np.float64)
    stu = np.clip(np.linalg.solve(lat.axes, (points - lat.origin).T).T, 0, 1)
    l, m, n = lat.degree
    B = np.einsum("pi,pj,pk->pijk", bernstein(l, stu[:, 0]), bernstein(m, stu[:, 1]), bernstein(n, stu[:, 2]))
    B = B.reshape(len(points), -1) * weights[None, :]
    N = B @ (lat.control_points - lat.rest_points)
    return points + lat.strength * N / B.sum(axis=1, keepdims=True)


def test_rational_lattice_deforms_points_and_curves_exactly():
    rng = np.random.default_rng(17)
    lat = ff.Lattice((2, 1, 2), origin=[-1.5, -1.5, -1.5], axes=np.eye(3) * 3)
    lat.control_points += rng.uniform(-0.2, 0.2, lat.control_points.shape)
    lat.strength = 0.8
    w = rng.uniform(0.5, 2.0, lat.point_count)
    rl = ff.RationalLattice(lat, w)
    assert not rl.is_polynomial and rl.strength == 0.8
    np.testing.assert_array_equal(rl.weights, w)
    pts = rng.uniform(-1.4, 1.4, (200, 3))
    np.testing.assert_allclose(rl.deform(pts), reference_rational_deform(lat, w, pts), rtol=1e-13, atol=1e-13)
    # unit weights: the polynomial FFD bit for bit
    np.testing.assert_array_equal(ff.RationalLattice(lat).deform(pts), lat.deform(pts))
    # Jacobian by central differences
    h = 1e-6
    J = rl.jacobian(pts[:5])
    for b in range(3):
        e = np.zeros(3)
        e[b] = h
        fd = (rl.deform(pts[:5] + e) - rl.deform(pts[:5] - e)) / (2 * h)
        np.testing.assert_allclose(J[:, :, b], fd, rtol=1e-6, atol=1e-7)
    # exact composition: the deformed curve is the deformed points of the curve
    c = ff.NurbsCurve(3, [0, 0, 0, 0, 0.4, 0.4, 1, 1, 1, 1], rng.uniform(-1, 1, (6, 3)), rng.uniform(0.5, 2, 6))
    t = np.linspace(0, 1, 57)
    dc = rl.deform_curve(c)
    assert isinstance(dc, ff.NurbsCurve) and dc.degree == 3 * (1 + 5)
    np.testing.assert_allclose(dc.evaluate(t), rl.deform(c.evaluate(t)), atol=1e-11)
    r = ff.RationalBezierCurve(rng.uniform(-1, 1, (3, 3)), [1, 0.6, 1.3])
    dr = rl.deform_curve(r)
    assert isinstance(dr, ff.RationalBezierCurve)
    np.testing.assert_allclose(dr.evaluate(t), rl.deform(r.evaluate(t)), atol=1e-11)
    # the polynomial lattice: a rational NURBS of degree d (l+m+n) (its denominator W^(l+m+n)), Bézier exactly
    pc = lat.deform_curve(c)
    assert isinstance(pc, ff.NurbsCurve) and pc.degree == 3 * 5
    np.testing.assert_allclose(pc.evaluate(t), lat.deform(c.evaluate(t)), atol=1e-11)
    b = ff.BezierCurve(rng.uniform(-1, 1, (4, 3)))
    db = lat.deform_curve(b)
    assert isinstance(db, ff.BezierCurve) and db.degree == 3 * 5
    np.testing.assert_allclose(db.evaluate(t), lat.deform(b.evaluate(t)), atol=1e-11)
    with pytest.raises(ff.Error, match="2D"):
        lat.deform_curve(ff.NurbsCurve.circle([0, 0]))
    with pytest.raises(TypeError):
        lat.deform_curve(ff.Patch(np.zeros((2, 2, 3))))
    with pytest.raises(ff.Error, match="weight"):
        ff.RationalLattice(lat, np.ones(3))
    with pytest.raises(ff.Error, match="weight"):
        ff.RationalLattice(lat, -np.ones(lat.point_count))


# ---------------------------------------------------------------- closest point, bounds

def test_closest_point_and_bounds():
    c = ff.NurbsCurve.circle([0, 0], 1.0)
    q = np.array([[2.0, 0.0], [0.0, -3.0], [-0.5, 0.5]])
    u, X, d = c.closest_point(q)
    np.testing.assert_allclose(X, q / np.linalg.norm(q, axis=1)[:, None], atol=1e-12)
    np.testing.assert_allclose(d, np.abs(np.linalg.norm(q, axis=1) - 1), atol=1e-12)
    np.testing.assert_allclose(c.evaluate(u), X, atol=1e-12)
    u1, x1, d1 = c.closest_point([2.0, 0.0])
    assert isinstance(u1, float) and abs(d1 - 1) < 1e-12
    lo, hi = c.bounds()
    np.testing.assert_allclose(lo, [-1, -1], atol=1e-14)
    np.testing.assert_allclose(hi, [1, 1], atol=1e-14)
    clo, chi = c.control_box()
    np.testing.assert_array_equal(clo, [-1, -1])


def test_closest_point_is_global_on_a_degree_4_rational_piece():
    # NurbsCurve::closestPoint once missed this (Newton from 8 samples per span); it now solves
    # for every stationary point of each span
    rng = np.random.default_rng(10)
    c = ff.RationalBezierCurve(rng.normal(size=(5, 3)), rng.uniform(0.3, 3, 5))
    q = c.evaluate([0.06])
    # refined (more spans, so more samples) it finds the point itself
    assert c.to_nurbs().refined(np.linspace(0.05, 0.95, 19)).closest_point(q)[2][0] < 1e-12
    assert c.closest_point(q)[2][0] < 1e-9


# ---------------------------------------------------------------- bad input

def test_bad_input_raises_clear_errors():
    P = np.zeros((4, 2))
    with pytest.raises(ff.Error, match=r"knot 3 \(0\.2.*less than knot 2.*must not decrease"):
        ff.NurbsCurve(2, [0, 0, 0.5, 0.2, 1, 1, 1], P)
    with pytest.raises(ff.Error, match="need 4 control points, got 5"):
        ff.NurbsCurve(2, [0, 0, 0, 0.5, 1, 1, 1], np.zeros((5, 2)))
    with pytest.raises(ff.Error, match="3 weights for 4 control points"):
        ff.NurbsCurve(2, [0, 0, 0, 0.5, 1, 1, 1], P, [1, 1, 1])
    with pytest.raises(ff.Error, match="weight 1 is not a positive finite number"):
        ff.NurbsCurve(2, [0, 0, 0, 0.5, 1, 1, 1], P, [1, 0, 1, 1])
    with pytest.raises(ff.Error, match="weight 2 is not a positive finite number"):
        ff.RationalBezierCurve(P, [1, 1, -1, 1])
    with pytest.raises(ff.Error, match="weight 0 is not a positive finite number"):
        ff.RationalBezierCurve(P, [np.nan, 1, 1, 1])
    with pytest.raises(ff.Error, match="2 weights for 4 control points"):
        ff.RationalBezierCurve(P, [1, 1])
    with pytest.raises(ff.Error, match="knot 4 is not finite"):
        ff.NurbsCurve(2, [0, 0, 0, 0.5, np.nan, 1, 1], P)
    with pytest.raises(ff.Error, match="row 1 is not finite"):
        ff.NurbsCurve(2, [0, 0, 0, 0.5, 1, 1, 1], [[0, 0], [np.nan, 0], [1, 1], [2, 0]])
    with pytest.raises(ff.Error, match=r"multiplicity 4, more than degree \+ 1 = 3"):
        ff.NurbsCurve(2, [0, 0, 0, 0.5, 0.5, 0.5, 0.5, 1, 1, 1], np.zeros((7, 2)))
    with pytest.raises(ff.Error, match=r"shape \(N, 2\) or \(N, 3\)"):
        ff.NurbsCurve(2, [0, 0, 0, 1, 1, 1], np.zeros((3, 4)))
    with pytest.raises(ff.Error, match=r"knots: expected a 1-D array"):
        ff.NurbsCurve(2, [[0, 0, 0, 1, 1, 1]], np.zeros((3, 2)))
    with pytest.raises(ff.Error, match=r"weights: expected a 1-D"):
        ff.RationalBezierCurve(P, np.ones((4, 1)))
    with pytest.raises(TypeError, match="dtype"):
        ff.NurbsCurve(2, np.array(["a"] * 6), np.zeros((3, 2)))
    with pytest.raises(TypeError, match="dtype"):
        ff.RationalBezierCurve(np.zeros((3, 2), dtype=complex), [1, 1, 1])
    with pytest.raises(TypeError):
        ff.NurbsCurve(2, [0, 0, 0, 1, 1, 1], "points")
    c = ff.NurbsCurve(2, [0, 0, 0, 0.5, 1, 1, 1], np.array([[0, 0], [1, 1], [2, 0], [3, 1]], dtype=float))
    with pytest.raises(ff.Error, match=r"parameter 1\.5 \(index 1\) outside \[0, 1\]"):
        c.evaluate([0.5, 1.5])
    with pytest.raises(ff.Error, match="index 0"):
        c.derivatives([np.nan], 1)
    with pytest.raises(ff.Error, match="order -1 is negative"):
        c.derivatives([0.5], -1)
    with pytest.raises(ff.Error, match="not inside the domain"):
        c.insert_knot(1.0)
    with pytest.raises(ff.Error, match="not inside the domain"):
        c.split(0.0)
    with pytest.raises(ff.Error, match=r"shape \(nu, nv, 3\)"):
        ff.NurbsSurface(1, [0, 0, 1, 1], [0, 0, 1, 1], np.zeros((2, 2, 2)))
    with pytest.raises(ff.Error, match=r"weights: expected a 2-D"):
        ff.NurbsSurface(1, [0, 0, 1, 1], [0, 0, 1, 1], np.zeros((2, 2, 3)), [1, 1, 1, 1])
    with pytest.raises(ff.Error, match=r"weight 3 \(point 1, 1\) is not a positive finite number"):
        ff.NurbsSurface(1, [0, 0, 1, 1], [0, 0, 1, 1], np.zeros((2, 2, 3)), [[1, 1], [1, 0]])
    with pytest.raises(ff.Error, match="knots in v"):
        ff.NurbsSurface(1, [0, 0, 1, 1], [0, 1, 0, 1], np.zeros((2, 2, 3)))
    with pytest.raises(ff.Error, match=r"grid of 2 x 2 points, got 2 x 3|need 2 x 2"):
        ff.NurbsSurface(1, [0, 0, 1, 1], [0, 0, 1, 1], np.zeros((2, 3, 3)))
    with pytest.raises(ff.Error, match="outside"):
        ff.NurbsSurface.sphere().evaluate([[0.5, 1.5]])
    with pytest.raises(ff.Error, match=r"shape \(N, 2\)"):
        ff.NurbsSurface.sphere().evaluate([0.5, 0.5])
    with pytest.raises(ff.Error, match="too few for degree"):
        ff.interpolate_nurbs(np.zeros((3, 2)) + np.arange(3)[:, None], degree=3)
    with pytest.raises(ff.Error, match="both end derivatives or neither"):
        ff.interpolate_nurbs(np.arange(12.0).reshape(6, 2), degree=3, start_derivative=[1, 0])
    with pytest.raises(ff.Error, match="parametrization"):
        ff.interpolate_nurbs(np.arange(12.0).reshape(6, 2), parametrization="arc")
    with pytest.raises(ff.Error, match="control points for 6 points"):
        ff.approximate_nurbs(np.arange(12.0).reshape(6, 2), 6)
    with pytest.raises(ff.Error, match="sweep"):
        ff.RationalBezierCurve.circle_arc([0, 0], 1.0, 0.0, 4.0)


def test_new_types_have_docstrings_and_reprs():
    for name in ["RationalBezierCurve", "NurbsCurve", "RationalBezierSurface", "NurbsSurface", "RationalLattice"]:
        cls = getattr(ff, name)
        assert cls.__doc__ and cls.__doc__.strip(), name
    for f in [ff.interpolate_nurbs, ff.approximate_nurbs, ff.NurbsCurve.insert_knot, ff.NurbsCurve.bezier_pieces,
              ff.NurbsSurface.evaluate_grid, ff.Lattice.deform_curve, ff.Document.object, ff.Document.add]:
        assert f.__doc__, f
    assert repr(ff.NurbsCurve.circle()) == "NurbsCurve(degree=2, control_count=9, dimension=2, rational=True)"
    assert repr(ff.NurbsSurface.sphere()) == "NurbsSurface(degree=(2, 2), count=(9, 5), rational=True)"


def test_gil_is_released_during_nurbs_evaluation():
    s = ff.NurbsSurface.sphere()
    u = np.linspace(0, 1, 1500)

    def work():
        for _ in range(3):
            s.evaluate_grid(u, u)

    # with the GIL held for the whole call the other thread could not tick during it
    assert ticks_during(work) >= 3


# ---------------------------------------------------------------- issue 26

def test_parameters_in_messages_show_the_problem():
    c = ff.BezierCurve([[0, 0], [1, 1], [2, 0]])
    with pytest.raises(ff.Error) as e:
        c.evaluate([0.5, 1 + 1e-9])
    assert str(e.value) == "BezierCurve.evaluate: parameter 1.000000001 (index 1) outside [0, 1]"
    tiny = ff.NurbsCurve(1, [0, 0, 1e-8, 1e-8], [[0, 0], [1, 0]])  # a domain of size 1e-8
    with pytest.raises(ff.Error) as e:
        tiny.evaluate([2e-8])
    assert str(e.value) == "NurbsCurve.evaluate: parameter 2e-08 (index 0) outside [0, 1e-08]"
    s = ff.NurbsSurface.sphere()
    with pytest.raises(ff.Error, match=r"uv row 0 \(0\.5, 1\.0000000000000002\) outside \[0, 1\] x \[0, 1\]"):
        s.evaluate([[0.5, np.nextafter(1.0, 2.0)]])


def test_reduced_and_other_operations_keep_a_polynomial_curve_polynomial():
    # a quadratic elevated to a cubic: reducing it gives the quadratic back, and weights of exactly 1
    knots = [0, 0, 0, 0.4, 1, 1, 1]
    pts = np.array([[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [2.0, -1.0, 1.0], [3.0, 0.5, -0.5]])
    quad = ff.NurbsCurve(2, knots, pts)
    cubic = quad.elevated()
    assert not cubic.is_rational and cubic.degree == 3
    red, err = cubic.reduced(1e-9)
    assert red.degree == 2 and not red.is_rational and err < 1e-12
    assert np.all(red.weights == 1.0)
    u = np.linspace(0, 1, 33)
    np.testing.assert_allclose(red.evaluate(u), quad.evaluate(u), atol=1e-12)
    # elevation doubled the knot 0.4; removing the extra one gives the quadratic's own points
    back, e = red.remove_knot(0.4)
    assert not back.is_rational and e < 1e-12 and back.knots.tolist() == knots
    np.testing.assert_allclose(back.control_points, pts, atol=1e-12)
    for other in (cubic.insert_knot(0.7), cubic.refined([0.2, 0.55]), cubic.remove_knot(0.4)[0], *cubic.split(0.3)):
        assert not other.is_rational
    # a rational curve stays rational
    circle = ff.NurbsCurve.circle([0.0, 0.0])
    assert circle.is_rational and circle.insert_knot(0.1).is_rational


def test_convert_to_the_kind_an_object_has_is_a_no_op():
    doc = ff.Document()
    doc.add("c", ff.NurbsCurve.circle([0.5, 0.25], 2.0))
    before = doc.object("c").homogeneous_points
    assert doc.convert("c", "nurbs_curve") == "nurbs_curve"  # before: "already a nurbs_curve" error
    assert doc.type("c") == "nurbs_curve"
    assert doc.object("c").homogeneous_points.tobytes() == before.tobytes()
    doc.add("p", ff.NurbsSurface.sphere())
    assert doc.convert("p", "nurbs_surface") == "nurbs_surface"
    with pytest.raises(ff.Error, match='object "c" is already a nurbs_curve'):
        doc.convert("c", "nurbs_surface")


def test_remove_knot_documents_that_it_can_raise():
    assert "freeform.Error" in ff.NurbsCurve.remove_knot.__doc__ and "weight" in ff.NurbsCurve.remove_knot.__doc__


def test_convert_a_polynomial_nurbs_curve_to_its_bezier_spline():
    # Document.convert takes the kind table's route (the document layer's convertObject), as
    # `freeform convert --to bezier_spline` does: a two-span quadratic B-spline becomes its Bezier
    # pieces. Knot 1 inserted once more (Boehm, alpha = (1 - 0) / (2 - 0)) puts the joint at
    # (P1 + P2) / 2 by hand.
    doc = ff.Document()
    pts = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [2.0, -1.0, 0.5], [3.0, 0.0, 1.0]]
    doc.add("bs", ff.NurbsCurve(2, [0, 0, 0, 1, 2, 2, 2], pts))
    assert doc.convert("bs", "bezier_spline") == "bezier_spline"
    assert doc.type("bs") == "bezier_spline"
    spline = doc.curve("bs")
    assert spline.degree == 2 and list(spline.intervals) == [1.0, 1.0]
    np.testing.assert_array_equal(spline.control_points[2], [1.5, 0.0, 0.25])
    np.testing.assert_array_equal(spline.control_points[3], pts[2])
    doc.add("bs2", ff.NurbsCurve(2, [0, 0, 0, 1, 2, 2, 2], pts))
    with pytest.raises(ff.Error, match="end condition"):
        doc.convert("bs2", "deboor_spline", end="open")
