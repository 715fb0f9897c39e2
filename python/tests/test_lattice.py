# freeform.Lattice against independent computations: a NumPy Bernstein tensor sum, finite
# differences for the sensitivities and det J, the command-line tool's outputs on the same files.
import json
import os
import subprocess

import numpy as np
import pytest

import freeform as ff
from conftest import ROOT, cli, reference_deform, reference_weights, random_lattice, run_cli

RNG = np.random.default_rng(5)
INSIDE = RNG.uniform(-1, 1, (200, 3)) * [1.0, 1.1, 0.85]
MIXED = RNG.uniform(-1.6, 1.6, (200, 3))  # many points outside the box


def test_rest_lattice_is_identity_bit_for_bit():
    lat = ff.Lattice.fit(INSIDE, degree=(2, 3, 1))
    assert lat.is_rest()
    assert np.array_equal(lat.deform(INSIDE), INSIDE)


@pytest.mark.parametrize("outside", ["clamp", "keep", "extrapolate"])
def test_deform_matches_numpy_bernstein_sum(outside):
    lat = random_lattice(ff, outside=outside)
    lat.strength = 0.7
    out = lat.deform(MIXED)
    assert out.dtype == np.float64 and out.shape == MIXED.shape
    np.testing.assert_allclose(out, reference_deform(lat, MIXED), rtol=0, atol=1e-13)


def test_float32_stays_float32():
    lat = random_lattice(ff)
    p32 = INSIDE.astype(np.float32)
    out = lat.deform(p32)
    assert out.dtype == np.float32
    np.testing.assert_allclose(out, reference_deform(lat, p32.astype(np.float64)), rtol=0, atol=2e-6)


def test_other_layouts_are_converted():
    lat = random_lattice(ff)
    expected = lat.deform(INSIDE)
    fortran = np.asfortranarray(INSIDE)
    np.testing.assert_array_equal(lat.deform(fortran), expected)
    strided = np.zeros((len(INSIDE), 6))
    strided[:, ::2] = INSIDE
    np.testing.assert_array_equal(lat.deform(strided[:, ::2]), expected)
    np.testing.assert_array_equal(lat.deform(INSIDE.tolist()), expected)
    ints = np.array([[0, 0, 0], [1, -1, 0]])
    np.testing.assert_allclose(lat.deform(ints), reference_deform(lat, ints), atol=1e-13)


def test_empty_input():
    lat = random_lattice(ff)
    assert lat.deform(np.zeros((0, 3))).shape == (0, 3)
    assert lat.weights(np.zeros((0, 3))).shape == (0, lat.point_count)


def test_control_points_are_a_writable_view():
    lat = random_lattice(ff)
    cp = lat.control_points
    assert cp.shape == (64, 3) and cp.dtype == np.float64
    assert np.shares_memory(cp, lat.control_points)  # the same buffer every time: no copy
    before = lat.deform(INSIDE)
    cp[lat.index(1, 2, 1)] += [0.3, 0, 0]  # edit in place ...
    after = lat.deform(INSIDE)  # ... the next call sees it
    np.testing.assert_allclose(after, reference_deform(lat, INSIDE), atol=1e-13)
    assert not np.allclose(before, after)
    # index order i*(m+1)*(n+1) + j*(n+1) + k
    lat2 = ff.Lattice((1, 2, 3), origin=[0, 0, 0], axes=np.eye(3))
    assert lat2.index(1, 2, 3) == 1 * 3 * 4 + 2 * 4 + 3
    np.testing.assert_allclose(lat2.rest_points[lat2.index(1, 2, 3)], [1, 1, 1])
    np.testing.assert_allclose(lat2.rest_points[lat2.index(0, 1, 2)], [0, 0.5, 2 / 3])


def test_weights_match_numpy_and_finite_differences():
    for outside in ["clamp", "keep", "extrapolate"]:
        lat = random_lattice(ff, degree=(3, 2, 2), outside=outside)
        lat.strength = 0.8
        W = lat.weights(MIXED)
        assert W.shape == (len(MIXED), lat.point_count)
        np.testing.assert_allclose(W, reference_weights(lat, MIXED), rtol=0, atol=1e-14)
        # central differences of deform with respect to every control point and coordinate
        h = 1e-3
        base = lat.control_points.copy()
        scale = np.abs(lat.deform(MIXED)).max()
        for q in range(0, lat.point_count, 5):
            for c in range(3):
                lat.control_points[:] = base
                lat.control_points[q, c] += h
                plus = lat.deform(MIXED)
                lat.control_points[:] = base
                lat.control_points[q, c] -= h
                minus = lat.deform(MIXED)
                fd = (plus - minus) / (2 * h)
                # the map is linear in P: only rounding is left, scaled by |p| / h
                np.testing.assert_allclose(fd[:, c], W[:, q], rtol=0, atol=1e-7 * max(1.0, scale / h * 1e-6))
                other = [a for a in range(3) if a != c]
                assert np.abs(fd[:, other]).max() < 1e-7
        lat.control_points[:] = base


def test_weights_finite_differences_relative():
    # 1e-7 relative on the entries that matter (W > 1e-3), points inside the box
    lat = random_lattice(ff)
    W = lat.weights(INSIDE)
    base = lat.control_points.copy()
    h = 1e-4
    for q in [0, 21, 42, 63]:
        lat.control_points[:] = base
        lat.control_points[q, 1] += h
        plus = lat.deform(INSIDE)
        lat.control_points[:] = base
        lat.control_points[q, 1] -= h
        minus = lat.deform(INSIDE)
        fd = (plus[:, 1] - minus[:, 1]) / (2 * h)
        big = W[:, q] > 1e-3
        assert big.sum() > 10
        np.testing.assert_allclose(fd[big], W[big, q], rtol=1e-7)
    lat.control_points[:] = base


def test_matrix_free_products():
    lat = random_lattice(ff, outside="keep")
    lat.strength = 1.3
    W = lat.weights(MIXED)
    dP = RNG.normal(size=(lat.point_count, 3))
    g = RNG.normal(size=MIXED.shape)
    np.testing.assert_allclose(lat.weights_matvec(MIXED, dP), W @ dP, rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(lat.weights_rmatvec(MIXED, g), W.T @ g, rtol=1e-12, atol=1e-12)
    # the thread count does not change the result
    big = RNG.uniform(-1, 1, (20000, 3))
    gb = RNG.normal(size=big.shape)
    assert np.array_equal(lat.weights_rmatvec(big, gb, threads=1), lat.weights_rmatvec(big, gb, threads=3))
    # W dP is the change of deform when the control points move by dP (linear in P)
    moved = lat.copy()
    moved.control_points += dP
    np.testing.assert_allclose(moved.deform(MIXED) - lat.deform(MIXED), lat.weights_matvec(MIXED, dP), atol=1e-12)


def finite_difference_jacobian(lat, p, h=1e-5):
    J = np.zeros((len(p), 3, 3))
    for c in range(3):
        e = np.zeros(3)
        e[c] = h
        J[:, :, c] = (lat.deform(p + e) - lat.deform(p - e)) / (2 * h)
    return J


def test_det_j_and_normals_against_finite_differences():
    lat = random_lattice(ff, scale=0.2)
    p = INSIDE * 0.9
    J = finite_difference_jacobian(lat, p)
    np.testing.assert_allclose(lat.det_j(p), np.linalg.det(J), rtol=1e-7)
    n = RNG.normal(size=p.shape)
    n /= np.linalg.norm(n, axis=1)[:, None]
    out, nn = lat.deform_normals(p, n)
    np.testing.assert_allclose(out, lat.deform(p), rtol=0, atol=1e-14)
    cof = np.linalg.det(J)[:, None, None] * np.linalg.inv(J).transpose(0, 2, 1)
    expected = np.einsum("pij,pj->pi", cof, n)
    expected /= np.linalg.norm(expected, axis=1)[:, None]
    np.testing.assert_allclose(nn, expected, atol=1e-7)


def test_certificate_and_report():
    lat = random_lattice(ff, scale=0.05)
    assert lat.certify()["verdict"] == "certified injective"
    # push the middle layer through its neighbours along x: the lattice folds
    folded = ff.Lattice((2, 1, 1), origin=[0, 0, 0], axes=np.eye(3))
    for j in range(2):
        for k in range(2):
            folded.control_points[folded.index(1, j, k), 0] = 2.0
    c = folded.certify()
    assert c["verdict"] == "folds"
    s, t, u = c["witness"]
    # det J at the witness, by finite differences of the map, is <= 0
    w = folded.origin + folded.axes @ np.array([s, t, u])
    w = np.clip(w, 1e-3, 1 - 1e-3)[None, :]
    assert np.linalg.det(finite_difference_jacobian(folded, w, 1e-6))[0] <= 1e-6
    r = folded.report(np.array([[0.1, 0.5, 0.5], [0.9, 0.5, 0.5], [2, 2, 2]]))
    assert r["vertices"] == 3 and r["outside"] == 1
    assert r["fold_count"] >= 1 and r["min_det_j"] <= 0


def test_direct_manipulation_hits_targets():
    lat = random_lattice(ff)
    p = INSIDE[:5]
    targets = lat.deform(p) + RNG.uniform(-0.05, 0.05, p.shape)
    r = lat.direct_manipulation(p, targets)
    assert r["rank"] == 5 and r["residual"] < 1e-10
    np.testing.assert_allclose(r["lattice"].deform(p), targets, atol=1e-10)
    np.testing.assert_allclose(r["lattice"].control_points - lat.control_points, r["change"], atol=1e-14)


def test_fit_load_save_and_cli_round_trip(tmp_path):
    mesh = ROOT / "data" / "meshes" / "sphere.obj"
    lat_json = tmp_path / "lat.json"
    run_cli("lattice", "--fit", mesh, "--degree", "2,3,2", "--margin", "0.1", "-o", lat_json)
    from_cli = ff.Lattice.load(str(lat_json))
    positions = ff.MeshFile.read(str(mesh)).positions
    fitted = ff.Lattice.fit(positions, degree=(2, 3, 2), margin=0.1)
    assert from_cli.degree == (2, 3, 2) and fitted.degree == (2, 3, 2)
    np.testing.assert_array_equal(from_cli.control_points, fitted.control_points)
    np.testing.assert_array_equal(from_cli.origin, fitted.origin)
    # bounding box by hand: margin 0.1 of the largest extent on every side
    lo, hi = positions.min(0), positions.max(0)
    pad = 0.1 * (hi - lo).max()
    np.testing.assert_allclose(fitted.origin, lo - pad, atol=1e-12)

    # deform in Python and through `freeform ffd` on the same lattice and mesh
    from_cli.control_points[from_cli.index(1, 2, 1)] += [0.2, -0.1, 0.3]
    from_cli.control_points[from_cli.index(0, 0, 0)] += [0.1, 0.1, 0.0]
    moved = tmp_path / "moved.json"
    from_cli.save(str(moved))
    out = tmp_path / "out.obj"
    report = json.loads(run_cli("ffd", mesh, "--lattice", moved, "-o", out))
    cli_positions = ff.MeshFile.read(str(out)).positions
    np.testing.assert_array_equal(from_cli.deform(positions), cli_positions)
    np.testing.assert_allclose(cli_positions, reference_deform(from_cli, positions), atol=1e-13)
    r = from_cli.report(positions)
    assert r["outside"] == report["outside"] and r["fold_count"] == report["fold_count"]
    assert r["min_det_j"] == pytest.approx(report["min_det_j"], rel=1e-12)
    assert from_cli.certify()["verdict"] == report["certificate"]["verdict"]

    # save -> load keeps everything bit for bit, and the file is a document the CLI reads
    again = ff.Lattice.load(str(moved))
    np.testing.assert_array_equal(again.control_points, from_cli.control_points)
    assert again.name == "lattice" and again.outside == "clamp"
    ev = json.loads(run_cli("eval", moved, "--object", "lattice", "--at", "0.25,0.5,0.75"))
    world = from_cli.origin + from_cli.axes @ np.array([0.25, 0.5, 0.75])
    np.testing.assert_allclose(from_cli.deform(world[None, :])[0], ev["point"], rtol=0, atol=1e-13)


def test_mesh_file_deform_matches_cli(tmp_path):
    mesh = ROOT / "data" / "meshes" / "sphere.ply"
    lat = ff.Lattice.fit(ff.MeshFile.read(str(mesh)).positions, degree=2)
    lat.control_points[lat.index(2, 1, 1)] += [0.4, 0.1, 0]
    lat.save(str(tmp_path / "lat.json"))
    run_cli("ffd", mesh, "--lattice", tmp_path / "lat.json", "-o", tmp_path / "cli.ply")
    m = ff.MeshFile.read(str(mesh))
    m.deform(lat)
    m.write(str(tmp_path / "py.ply"))
    assert (tmp_path / "py.ply").read_bytes() == (tmp_path / "cli.ply").read_bytes()


def test_bad_input_raises_with_a_clear_message(tmp_path):
    lat = random_lattice(ff)
    with pytest.raises(ff.Error, match=r"points: expected an array of shape \(N, 3\), got shape \(4, 2\)"):
        lat.deform(np.zeros((4, 2)))
    with pytest.raises(ff.Error, match=r"shape \(3,\)"):
        lat.deform(np.zeros(3))
    bad = INSIDE.copy()
    bad[7, 1] = np.nan
    with pytest.raises(ff.Error, match="points: row 7 is not finite"):
        lat.deform(bad)
    with pytest.raises(ff.Error, match="row 7 is not finite"):
        lat.weights(bad)
    with pytest.raises(TypeError, match="dtype"):
        lat.deform(np.array([["a", "b", "c"]]))
    with pytest.raises(TypeError, match="dtype"):
        lat.deform(np.zeros((2, 3), dtype=np.complex128))
    with pytest.raises(TypeError):
        lat.deform(None)
    with pytest.raises(ff.Error, match="dP: expected 64 rows"):
        lat.weights_matvec(INSIDE, np.zeros((3, 3)))
    with pytest.raises(ff.Error, match="g: 2 rows for 200 points"):
        lat.weights_rmatvec(INSIDE, np.zeros((2, 3)))
    with pytest.raises(ff.Error, match="outside"):
        lat.outside = "wrap"
    with pytest.raises(ff.Error):
        ff.Lattice.fit(INSIDE, degree=(0, 1, 1))
    with pytest.raises(ff.Error):
        ff.Lattice.fit(np.zeros((0, 3)))
    lat.control_points[3, 2] = np.inf
    with pytest.raises(ff.Error, match="control_points: row 3 is not finite"):
        lat.deform(INSIDE)
    # corrupt and missing files: the library's message names the file
    corrupt = tmp_path / "corrupt.json"
    corrupt.write_text('{"format": "freeform", "version": 1, "objects": [{"name": "l", "type": "lattice"')
    with pytest.raises(ff.Error, match="corrupt.json"):
        ff.Lattice.load(str(corrupt))
    with pytest.raises(ff.Error, match="missing.json"):
        ff.Lattice.load(str(tmp_path / "missing.json"))
    with pytest.raises(ff.Error, match="no lattice object"):
        ff.Lattice.load(str(ROOT / "examples" / "data" / "demo.json"))
    with pytest.raises(ff.Error, match="not a lattice"):
        ff.Lattice.load(str(ROOT / "examples" / "data" / "demo.json"), name="arch")
    assert issubclass(ff.Error, ValueError)


def test_repr_and_docstrings():
    lat = ff.Lattice.fit(INSIDE, degree=(1, 2, 3))
    assert repr(lat) == "Lattice(name='lattice', degree=(1, 2, 3), control_points=24, outside='clamp', strength=1)"
    assert "Bernstein" in ff.Lattice.__doc__ or "Bézier" in ff.Lattice.__doc__
    assert ff.Lattice.weights.__doc__ and ff.Lattice.deform.__doc__


def test_binding_reuses_coordinates_and_writes_into_out():
    lat = random_lattice(ff)
    for dtype in (np.float64, np.float32):
        p = MIXED.astype(dtype)
        b = lat.bind(p)
        assert b.size == len(p) and b.dtype == dtype
        lat.control_points[10] += [0.05, -0.02, 0.01]
        lat.strength = 0.5
        out = np.empty_like(p)
        res = b.deform(lat, out=out)
        assert np.shares_memory(res, out)  # written in place, no new array
        np.testing.assert_array_equal(out, lat.deform(p))
        with pytest.raises(ff.Error, match="out: expected"):
            b.deform(lat, out=np.empty((3, 3), dtype=dtype))
        other = ff.Lattice.fit(p, degree=2)
        with pytest.raises(ff.Error):
            b.deform(other)


def test_points_are_read_in_place_where_the_layout_allows():
    # docs/python.md "Arrays": float64 and float32 C-contiguous (N, 3) points are read without a copy
    # (the kernels get the caller's buffer); other layouts are converted once to float64.
    for dtype in (np.float64, np.float32):
        p = np.ascontiguousarray(INSIDE, dtype=dtype)
        seen = ff._points_as_read(p)
        assert seen.ctypes.data == p.ctypes.data and np.shares_memory(seen, p)
    for other in (np.asfortranarray(INSIDE), INSIDE.astype(np.int64), np.zeros((len(INSIDE), 6))[:, ::2]):
        seen = ff._points_as_read(other)
        assert not np.shares_memory(seen, other) and seen.dtype == np.float64 and seen.flags.c_contiguous


def test_results_do_not_depend_on_the_thread_count():
    # docs/python.md "Threads and the GIL": threads=0 is the hardware concurrency; the results are the same
    lat = random_lattice(ff)
    big = np.random.default_rng(5).uniform(-1.2, 1.2, (20_000, 3))
    ref = lat.deform(big, threads=1)
    for t in (0, 2, 3, 7):
        assert np.array_equal(lat.deform(big, threads=t), ref)
        assert np.array_equal(lat.det_j(big, threads=t), lat.det_j(big, threads=1))
    rl = ff.RationalLattice(lat, np.linspace(0.5, 2, lat.point_count))
    assert np.array_equal(rl.deform(big, threads=3), rl.deform(big, threads=1))


# ---------------------------------------------------------------- issue 26

@pytest.mark.parametrize("shape", [(3, 2), (3, 1), (2, 3), (9,), (3, 3, 1), (4, 3)])
def test_axes_of_a_wrong_shape_are_refused_by_name(shape):
    # before: a (3, 2) array filled the third column from past its end, or the error spoke of
    # linearly dependent edges, and (2, 3) said "expected (N, 3), got shape (3, 2)" (transposed)
    axes = np.arange(1.0, 1.0 + np.prod(shape)).reshape(shape)
    text = "(" + ", ".join(map(str, shape)) + ("," if len(shape) == 1 else "") + ")"
    with pytest.raises(ff.Error) as e:
        ff.Lattice(1, origin=[0, 0, 0], axes=axes)
    assert str(e.value) == f"axes: expected an array of shape (3, 3) (columns S, T, U), got shape {text}"


def test_origin_of_a_wrong_shape_is_refused_by_name():
    for origin, text in [([0, 0], "(2,)"), ([[0, 0, 0]], "(1, 3)"), (np.zeros(4), "(4,)")]:
        with pytest.raises(ff.Error) as e:
            ff.Lattice(1, origin=origin, axes=np.eye(3))
        assert str(e.value) == f"origin: expected an array of shape (3,), got shape {text}"
    with pytest.raises(ff.Error, match="origin: row 0 is not finite"):
        ff.Lattice(1, origin=[0, np.nan, 0], axes=np.eye(3))
    # a Fortran-order or integer frame is read as given (column c of axes is edge c)
    axes = np.asfortranarray([[2, 0, 1], [0, 3, 0], [0, 0, 4]])
    lat = ff.Lattice(1, origin=np.array([1, 2, 3], dtype=np.int32), axes=axes)
    np.testing.assert_array_equal(lat.axes, axes)
    np.testing.assert_array_equal(lat.origin, [1, 2, 3])
    np.testing.assert_array_equal(lat.rest_points[lat.index(1, 0, 0)], [3, 2, 3])  # origin + S


def test_index_is_bounds_checked_and_takes_keywords():
    lat = ff.Lattice((3, 2, 4), origin=[0, 0, 0], axes=np.eye(3))
    # (i*(m+1) + j)*(n+1) + k with m+1 = 3, n+1 = 5
    assert lat.index(1, 0, 0) == 15 and lat.index(0, 2, 4) == 14 and lat.index(3, 2, 4) == 59
    assert lat.index(i=1, j=2, k=0) == 25 and lat.index(k=3, j=1, i=2) == 38
    for bad, name in [((0, 3, 0), "j = 3"), ((-1, 0, 0), "i = -1"), ((4, 0, 0), "i = 4"), ((0, 0, 5), "k = 5")]:
        with pytest.raises(ff.Error, match=f"Lattice.index: {name} is outside"):
            lat.index(*bad)


def test_extrapolation_that_overflows_raises_instead_of_nan():
    lat = random_lattice(ff, outside="extrapolate")
    far = np.full((1, 3), 1e100)
    with pytest.raises(ff.Error, match=r"point row 0 is not finite: the deformation overflows float64 \(outside='extrapolate'"):
        lat.deform(far)
    with pytest.raises(ff.Error, match="overflows float32"):
        lat.deform(np.array([[0.0, 0.0, 0.0], [1e30, 1e30, 1e30]], dtype=np.float32))
    with pytest.raises(ff.Error, match="point row 1 is not finite"):
        lat.det_j(np.array([[0.0, 0.0, 0.0], [1e100, 0, 0]]))
    with pytest.raises(ff.Error, match="not finite"):
        lat.report(far)  # before: the NaN det J values were counted as folds
    with pytest.raises(ff.Error, match="not finite"):
        lat.bind(far).deform(lat)
    with pytest.raises(ff.Error, match="not finite"):
        lat.deform_normals(far, np.ones((1, 3)))
    # moderately far points still extrapolate, as the NumPy sum does
    near = np.array([[3.0, -2.5, 2.0], [10.0, 10.0, 10.0]])
    np.testing.assert_allclose(lat.deform(near), reference_deform(lat, near), rtol=1e-12)
    r = lat.report(near)
    assert r["vertices"] == 2 and r["outside"] == 2
    assert all(np.isfinite([r["min_det_j"], r["max_det_j"]]))


def test_mesh_file_deform_that_overflows_raises_and_keeps_the_file(tmp_path):
    lat = random_lattice(ff, outside="extrapolate")
    src = tmp_path / "far.obj"
    src.write_text("v 0 0 0\nv 1e100 1e100 1e100\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n")
    m = ff.MeshFile.read(str(src))
    before = m.positions.copy()
    for normals in ("jacobian", "recompute"):
        with pytest.raises(ff.Error, match=r"far\.obj: vertex 1 deforms to a position that is not finite \(the extrapolate policy"):
            m.deform(lat, normals=normals)
        np.testing.assert_array_equal(m.positions, before)  # before the fix: NaN positions, written as "nan"
    # the command line refuses the same file (one error line, exit 1) and writes nothing
    lat_path = tmp_path / "lat.json"
    out = tmp_path / "out.obj"
    lat.save(str(lat_path))
    r = subprocess.run([cli(), "ffd", str(src), "--lattice", str(lat_path), "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 1 and r.stdout == "" and not out.exists()
    assert r.stderr.startswith("error: ") and r.stderr.count("\n") == 1 and "vertex 1 deforms to a position that is not finite" in r.stderr


def test_document_deform_that_overflows_raises_and_keeps_the_document():
    lat = random_lattice(ff, outside="keep")
    doc = ff.Document()
    doc.add("near", ff.NurbsCurve.circle())
    doc.add("far", ff.NurbsCurve(2, [0, 0, 0, 1, 1, 1], np.full((3, 3), 1e100)))
    # refused by the composition itself ("BezierCurve: point 0 coordinate 0 is not finite") or by the
    # document layer's check of the result: either way naming the object, before anything changes
    with pytest.raises(ff.Error, match=r'object "far": .*not finite'):
        doc.deform(lat)
    np.testing.assert_array_equal(doc.object("far").control_points, np.full((3, 3), 1e100))  # before: inf
    np.testing.assert_array_equal(doc.object("near").control_points, ff.NurbsCurve.circle().control_points)


@pytest.mark.parametrize("bad", [2**40, -1, 1.5, True, "2", None])
def test_threads_must_be_a_count(bad):
    lat = random_lattice(ff)
    pts = np.random.default_rng(0).uniform(-1, 1, (1000, 3))
    calls = [lambda: lat.deform(pts, threads=bad), lambda: lat.det_j(pts, threads=bad),
             lambda: lat.deform_normals(pts, pts, threads=bad), lambda: lat.weights_matvec(pts, lat.control_points, threads=bad),
             lambda: lat.weights_rmatvec(pts, pts, threads=bad), lambda: lat.bind(pts).deform(lat, threads=bad),
             lambda: ff.RationalLattice(lat).deform(pts, threads=bad)]
    for call in calls:
        with pytest.raises(ff.Error) as e:
            call()
        message = str(e.value)
        assert message.startswith("threads: ") and len(message) < 120, message  # no dump of the points


def test_one_call_deform_equals_the_bound_kernel_across_chunks():
    # Lattice.deform binds and deforms chunk by chunk (no binding of all points): its results are the
    # bound kernel's, bit for bit, for sizes around the chunk length, both dtypes and every policy
    rng = np.random.default_rng(21)
    for outside in ("clamp", "keep", "extrapolate"):
        lat = random_lattice(ff, outside=outside, seed=2)
        lat.strength = 0.9
        for n in (0, 1, 2047, 2048, 2049, 4096 * 2 + 5):
            for dtype in (np.float64, np.float32):
                p = rng.uniform(-1.4, 1.4, (n, 3)).astype(dtype)
                out = lat.deform(p)
                assert out.dtype == dtype and out.shape == (n, 3)
                assert out.tobytes() == lat.bind(p).deform(lat).tobytes()


def test_strided_points_are_read_in_place_with_the_same_results():
    lat = random_lattice(ff, seed=8)
    base = np.random.default_rng(2).uniform(-1.2, 1.2, (6000, 6))
    for dtype in (np.float64, np.float32):
        b = base.astype(dtype)
        for view in (b[:, ::2], b[::2, 3:], np.asfortranarray(b[:, :3])):
            dense = np.ascontiguousarray(view)
            assert lat.deform(view).dtype == dtype
            assert lat.deform(view).tobytes() == lat.deform(dense).tobytes()
            assert lat.det_j(view).tobytes() == lat.det_j(dense).tobytes()
    bad = base[:, ::2].copy()
    bad[4321, 2] = np.inf
    with pytest.raises(ff.Error, match="points: row 4321 is not finite \\(inf\\)"):
        lat.deform(np.asfortranarray(bad))


def test_report_matches_a_numpy_count():
    lat = random_lattice(ff, seed=3, scale=0.6)  # strong enough to fold somewhere
    pts = np.random.default_rng(4).uniform(-1.5, 1.5, (20_000, 3))
    det = lat.det_j(pts)
    r = lat.report(pts)
    stu = np.linalg.solve(lat.axes, (pts - lat.origin).T).T
    assert r["vertices"] == len(pts)
    assert r["outside"] == int(np.sum(~np.all((stu >= 0) & (stu <= 1), axis=1)))
    assert r["folds"] == np.flatnonzero(det <= 0).tolist() and r["fold_count"] == len(r["folds"]) > 0
    assert r["min_det_j"] == det.min() and r["max_det_j"] == det.max()
    assert lat.report(np.zeros((0, 3))) == {"vertices": 0, "outside": 0, "min_det_j": 1.0, "max_det_j": 1.0,
                                            "fold_count": 0, "folds": []}


def test_deform_allocates_nothing_per_point_but_its_output():
    # issue 26: deform bound all points first (48 bytes per point of lattice coordinates, 458 MiB for
    # 10^7 points) besides its 24-byte output; now chunks. The peak resident set during one call of
    # 2e6 points, in a fresh process, grows by about the output only.
    import subprocess
    import sys

    if not os.access("/proc/self/clear_refs", os.W_OK):
        pytest.skip("needs Linux /proc/self/clear_refs to reset the peak resident set")
    code = """
import numpy as np, freeform as ff
def kb(key):
    return next(int(l.split()[1]) for l in open("/proc/self/status") if l.startswith(key + ":"))
p = np.random.default_rng(1).uniform(-1, 1, (2_000_000, 3))
lat = ff.Lattice(3, origin=[-1.1] * 3, axes=np.eye(3) * 2.2)
lat.control_points += 0.01
lat.deform(p[:10])
open("/proc/self/clear_refs", "w").write("5")
before = kb("VmRSS")
out = lat.deform(p, threads=2)
print((kb("VmHWM") - before) * 1024 / len(p))
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    per_point = float(r.stdout)
    assert 23 < per_point < 30, per_point  # the float64 output is 24; main needed 72
