# freeform.Part, Face and Edge (docs/python.md "CAD parts", docs/cad.md) on the sample parts Debian
# ships (occt-misc): the counts Open CASCADE gives (TopExp::MapShapes: screw.step has 10 faces, 22
# edges, 14 vertices, one shell, one solid), face points against a NumPy Cox-de Boor evaluation of
# the exposed NURBS at the mapped parameters, the half-angle map against the circle's own geometry
# (equal angle steps give equal chords), the classification against a NumPy even-odd test of the
# certified boundary, and bad input.
import math
import pathlib

import numpy as np
import pytest

import freeform as ff
from test_nurbs import cox_de_boor
from test_part_document import edge_counts, mesh_volume

DATA = pathlib.Path("/usr/share/opencascade/data")
SCREW = DATA / "step" / "screw.step"

pytestmark = pytest.mark.skipif(".step" not in ff.Part.formats, reason="the module was built without Open CASCADE (test_part_document.py runs)")


def test_screw_counts_and_topology_as_open_cascade_gives_them():
    part = ff.Part.load(str(SCREW))
    assert (len(part.faces), len(part.edges), len(part.vertices)) == (10, 22, 14)
    assert part.shells == [list(range(10))] and part.solids == [[0]]
    assert part.units == "mm"
    check = part.check()
    assert check["closed"] and check["open_edges"] == 0 and check["non_manifold_edges"] == 0
    assert sorted(f.kind for f in part.faces) == ["cone"] * 2 + ["cylinder"] + ["plane"] * 4 + ["torus"] * 3
    lo, hi = part.bounds
    assert np.all(part.vertices >= lo - 1e-9) and np.all(part.vertices <= hi + 1e-9)
    # Every edge's ends are its vertices (within the edge's tolerance).
    for e in part.edges:
        if e.curve is None:
            continue
        a, b = e.range
        ends = e.points([a, b])
        v0, v1 = e.vertices
        assert np.linalg.norm(ends[0] - part.vertices[v0]) <= max(e.tolerance, 1e-7) * 10
        assert np.linalg.norm(ends[1] - part.vertices[v1]) <= max(e.tolerance, 1e-7) * 10


def nurbs_numpy(surface, st):
    (p, q), (nu, nv) = surface.degree, surface.count
    ku, kv = surface.knots_u, surface.knots_v
    # Cox-de Boor's half-open spans: keep the parameters off the last knot.
    s = np.minimum(st[:, 0], np.nextafter(ku[-1], -np.inf))
    t = np.minimum(st[:, 1], np.nextafter(kv[-1], -np.inf))
    Nu, Nv = cox_de_boor(ku, p, s), cox_de_boor(kv, q, t)
    P, w = surface.control_points, surface.weights
    num = np.einsum("ki,kj,ij,ijc->kc", Nu, Nv, w, P)
    den = np.einsum("ki,kj,ij->k", Nu, Nv, w)
    return num / den[:, None]


@pytest.mark.parametrize("name", ["step/screw.step", "step/linkrods.step", "iges/hammer.iges"])
def test_face_points_equal_numpy_nurbs_at_the_mapped_parameters(name):
    part = ff.Part.load(str(DATA / name))
    rng = np.random.default_rng(4)
    for face in part.faces:
        (u0, u1), (v0, v1) = face.domain
        uv = np.column_stack([rng.uniform(u0, u1, 50), rng.uniform(v0, v1, 50)])
        st = face.surface_parameters(uv)
        size = max(1.0, np.abs(part.bounds[0]).max(), np.abs(part.bounds[1]).max())
        np.testing.assert_allclose(face.points(uv), nurbs_numpy(face.surface, st), rtol=0, atol=1e-12 * size)
        np.testing.assert_allclose(face.surface.evaluate(st), face.points(uv), rtol=0, atol=1e-13 * size)


def test_half_angle_map_gives_equal_chords_for_equal_angles():
    # On a cylinder, cone or torus face the file's u is an angle: at fixed v, points at equal steps
    # of u are equally far apart (chord 2 r sin(step / 2)), which a wrong map would break.
    part = ff.Part.load(str(SCREW))
    checked = 0
    for face in part.faces:
        if face.kind not in ("cylinder", "cone", "torus"):
            continue
        (u0, u1), (v0, v1) = face.domain
        for v in np.linspace(v0, v1, 5):
            u = np.linspace(u0, u1, 41)
            p = face.points(np.column_stack([u, np.full_like(u, v)]))
            chords = np.linalg.norm(np.diff(p, axis=0), axis=1)
            if chords.max() < 1e-9:
                continue  # a degenerate circle (a cone's apex)
            np.testing.assert_allclose(chords, chords.mean(), rtol=1e-12)
            # The radius from the chord and the step equals the distance to the circle's centre,
            # the mean of the points of a full turn when the face is closed.
            r = chords.mean() / (2 * math.sin((u[1] - u[0]) / 2))
            if abs(u1 - u0 - 2 * math.pi) < 1e-9:
                centre = p[:-1].mean(axis=0)
                np.testing.assert_allclose(np.linalg.norm(p - centre, axis=1), r, rtol=1e-12)
            checked += 1
    assert checked >= 10


def even_odd(poly, pts):
    a, b = poly, np.roll(poly, -1, axis=0)
    inside = np.zeros(len(pts), dtype=bool)
    for (ax, ay), (bx, by) in zip(a, b):
        crosses = (ay > pts[:, 1]) != (by > pts[:, 1])
        with np.errstate(divide="ignore", invalid="ignore"):
            x = ax + (pts[:, 1] - ay) * (bx - ax) / (by - ay)
        inside ^= crosses & (x > pts[:, 0])
    return inside


def test_classification_equals_numpy_even_odd_on_the_certified_boundary():
    part = ff.Part.load(str(DATA / "step" / "linkrods.step"))
    rng = np.random.default_rng(9)
    for face in part.faces:
        (u0, u1), (v0, v1) = face.domain
        uv = np.column_stack([rng.uniform(u0, u1, 300), rng.uniform(v0, v1, 300)])
        inside = np.zeros(len(uv), dtype=bool)
        for k in range(len(face.loops)):
            inside ^= even_odd(face.boundary(k), uv)
        c = face.classify(uv)
        sure = c != 0
        assert sure.sum() > 250
        np.testing.assert_array_equal(c[sure] == 1, inside[sure])


def test_face_areas_equal_a_numpy_quadrature_of_the_area_element():
    # Face.area against NumPy's shoelace area of the certified boundary polygons: on the screw's
    # plane faces (orthonormal axes: parameter area is area) they differ by at most twice the
    # flatness times the polygons' perimeter. The part's area is the sum of its faces'.
    part = ff.Part.load(str(SCREW))
    planes = [f for f in part.faces if f.kind == "plane"]
    assert len(planes) == 4
    for f in planes:
        def shoelace(p):
            x, y = p[:, 0], p[:, 1]
            return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
        polygon = shoelace(f.boundary(0)) - sum(shoelace(f.boundary(k)) for k in range(1, len(f.loops)))
        perimeter = sum(np.linalg.norm(np.diff(np.vstack([b, b[:1]]), axis=0), axis=1).sum()
                        for b in (f.boundary(k) for k in range(len(f.loops))))
        assert abs(f.area - polygon) <= 2 * f.flatness * perimeter
        assert polygon > 0
    assert part.area == pytest.approx(sum(f.area for f in part.faces), rel=1e-14)


def test_bad_parts_raise_freeform_errors(tmp_path):
    with pytest.raises(ff.Error, match="missing.step: no such file"):
        ff.Part.load(str(tmp_path / "missing.step"))
    bad = tmp_path / "bad.igs"
    bad.write_text("not IGES at all\n")
    with pytest.raises(ff.Error, match="bad.igs"):
        ff.Part.load(str(bad))
    part = ff.Part.load(str(SCREW))
    with pytest.raises(ff.Error, match="loop 5 of"):
        part.faces[0].boundary(5)


def test_tessellate_gives_a_closed_mesh_whose_volume_holds_across_tolerances():
    part = ff.Part.load(str(SCREW))
    V, F = part.tessellate(0.5)
    assert V.shape[1] == 3 and F.shape[1] == 3 and F.dtype == np.int32
    assert F.min() == 0 and F.max() == len(V) - 1
    counts, clashes = edge_counts(F)
    assert np.all(counts == 2) and clashes == 0  # closed and consistently oriented
    V2, F2, report = part.tessellate(0.05, report=True)
    counts2, clashes2 = edge_counts(F2)
    assert np.all(counts2 == 2) and clashes2 == 0
    assert report["watertight"] and report["certified"] and report["error_bound"] <= 0.05
    assert report["triangles"] == len(F2) > len(F)
    assert len(report["triangle_faces"]) == len(F2)
    assert set(report["triangle_faces"].tolist()) == set(range(len(part.faces)))
    # Both meshes lie within their bounds of the part's surface: their volumes differ by at most
    # the two bounds times the part's area (Green's theorem over the trims, Part.area).
    _, _, coarse = part.tessellate(0.5, report=True)
    assert mesh_volume(V, F) > 0 and mesh_volume(V2, F2) > 0  # outward
    assert abs(mesh_volume(V, F) - mesh_volume(V2, F2)) <= (coarse["error_bound"] + report["error_bound"]) * part.area


def test_tessellate_refuses_a_bad_tolerance_and_a_mesh_over_the_limit():
    part = ff.Part.load(str(SCREW))
    for bad in (0.0, -1.0, math.inf, math.nan):
        with pytest.raises(ff.Error, match="tolerance"):
            part.tessellate(bad)
    with pytest.raises(ff.Error, match="exceed the limit of 100"):
        part.tessellate(1e-6, max_triangles=100)


def test_deform_moves_every_face_as_a_numpy_lattice_moves_its_points(tmp_path):
    from conftest import reference_deform

    part = ff.Part.load(str(SCREW))
    lo, hi = part.bounds
    lat = ff.Lattice.fit(np.array([lo, hi]), degree=2, margin=0.1)
    rng = np.random.default_rng(4)
    lat.control_points += rng.uniform(-1.0, 1.0, lat.control_points.shape)
    moved, report = part.deform(lat)
    assert report["faces"] == report["exact_faces"] == 10
    assert report["approximated_faces"] == [] and report["outside_faces"] == 0
    assert not report["affine"] and report["lipschitz"] > 1
    size = np.linalg.norm(np.subtract(hi, lo))
    for before, after in zip(part.faces, moved.faces):
        (u0, u1), (v0, v1) = before.domain
        uv = np.column_stack([rng.uniform(u0, u1, 20), rng.uniform(v0, v1, 20)])
        uv = uv[before.classify(uv) == 1]
        expected = reference_deform(lat, before.points(uv))
        assert np.max(np.linalg.norm(after.points(uv) - expected, axis=1)) < 1e-12 * size
    # Over degree 25 (a cubic lattice): reduced within the tolerance, and written as STEP that reads back.
    lat3 = ff.Lattice.fit(np.array([lo, hi]), degree=3, margin=0.1)
    lat3.control_points += rng.uniform(-1.0, 1.0, lat3.control_points.shape)
    capped, r3 = part.deform(lat3, max_degree=25, tolerance=1e-7)
    assert r3["max_degree"] <= 25 and r3["max_approximation_error"] <= 1e-7
    saved = capped.save(str(tmp_path / "screw.step"))
    assert saved["valid"]
    back = ff.Part.load(str(tmp_path / "screw.step"))
    assert (len(back.faces), len(back.edges), len(back.vertices)) == (10, 22, 14)
    assert back.check()["closed"]


def test_save_refuses_a_degree_over_25_and_a_bad_name_and_writes_nothing(tmp_path):
    part = ff.Part.load(str(SCREW))
    lo, hi = part.bounds
    lat = ff.Lattice.fit(np.array([lo, hi]), degree=3, margin=0.1)
    lat.control_points += np.random.default_rng(5).uniform(-1.0, 1.0, lat.control_points.shape)
    moved, report = part.deform(lat)
    assert report["max_degree"] > 25
    with pytest.raises(ff.Error, match="over Open CASCADE's 25"):
        moved.save(str(tmp_path / "x.step"))
    with pytest.raises(ff.Error, match="not a STEP"):
        part.save(str(tmp_path / "x.obj"))
    assert list(tmp_path.iterdir()) == []


def test_a_part_saved_as_brep_reads_back_with_its_counts_and_box(tmp_path):
    # Open CASCADE's own format (.brep): no unit, millimetres. The written screw has the STEP file's
    # 10 faces and 22 edges and its 14 vertices to the bit (17 digits written; the surfaces are
    # checked against Open CASCADE's projection in tests/test_cad_cli.cpp).
    part = ff.Part.load(str(SCREW))
    path = tmp_path / "screw.brep"
    report = part.save(str(path))
    assert report["valid"]
    back = ff.Part.load(str(path))
    assert (len(back.faces), len(back.edges), back.units) == (10, 22, "mm")
    assert back.vertices.shape == (14, 3)
    assert np.array_equal(np.unique(back.vertices, axis=0), np.unique(part.vertices, axis=0))
    # A sample part Debian ships in the format reads as well.
    nut = ff.Part.load(str(DATA / "occ" / "Pump_Nut.brep"))
    assert len(nut.faces) > 0 and nut.units == "mm"


def test_a_part_in_a_document_is_the_part_of_its_step_file(tmp_path):
    # Part.save(.json) writes a document of one part object; Document.object gives it back as a
    # Part whose faces evaluate to the STEP file's face points to the bit, and Document.evaluate
    # reports the trim class (inside the face) at a face's centre.
    part = ff.Part.load(str(SCREW))
    path = str(tmp_path / "screw.json")
    report = part.save(path)
    # screw.step has two gaps over their edges' tolerances already (`freeform info` says so too).
    assert part.check()["gaps_over_tolerance"] == 2 and report["valid"] is False
    doc = ff.Document.load(path)
    assert doc.names == ["screw"]
    assert doc.type("screw") == "part"
    again = doc.object("screw")
    assert isinstance(again, ff.Part)
    assert len(again.faces) == len(part.faces) == 10
    for a, b in zip(part.faces, again.faces):
        (u0, u1), (v0, v1) = a.domain
        uv = np.array([[u0 + (u1 - u0) * s, v0 + (v1 - v0) * (1 - s)] for s in np.linspace(0, 1, 7)])
        assert np.array_equal(a.points(uv), b.points(uv))
    inside = 0
    for i, face in enumerate(again.faces):
        (u0, u1), (v0, v1) = face.domain
        c = np.array([[0.5 * (u0 + u1), 0.5 * (v0 + v1)]])
        e = doc.evaluate("screw", [i, c[0, 0], c[0, 1]])
        assert np.allclose(e["point"], face.points(c)[0], rtol=0, atol=1e-12)
        assert e["trim"] in ("inside", "outside", "boundary")
        inside += e["trim"] == "inside"
    assert inside >= 3
    # Part.load of the document, and a document without a part: freeform.Error.
    assert len(ff.Part.load(path).edges) == 22
    with pytest.raises(ff.Error, match="has no part or trimmed_surface object"):
        ff.Part.load(str(pathlib.Path(__file__).resolve().parents[2] / "data" / "ffd_every_type.json"))


def test_a_part_deforms_through_a_rational_lattice_as_the_lattice_moves_its_points():
    # Part.deform and TrimmedSurface.deform take a RationalLattice as the library and the CLI do:
    # unit weights give the polynomial lattice's part bit for bit; a weight of 3 on the moved point
    # gives faces equal to RationalLattice.deform of the original face points (an independent,
    # point-wise computation) to 1e-12 of the part's size.
    part = ff.Part.load(str(SCREW))
    lo, hi = part.bounds
    lat = ff.Lattice.fit(np.array([lo, hi]), degree=(2, 2, 2))
    P = lat.control_points.copy()
    P[lat.index(1, 1, 1)] += 0.1 * (hi - lo)
    lat.control_points = P
    weights = np.ones(lat.point_count)
    exact, polynomial = part.deform(lat)
    unit, _ = part.deform(ff.RationalLattice(lat, weights))
    weights[lat.index(1, 1, 1)] = 3.0
    rl = ff.RationalLattice(lat, weights)
    bent, report = part.deform(rl)
    # Composed degrees (docs/cad.md): d (l+m+n) through the polynomial lattice, d (1+l+m+n) through
    # the rational one, d the part's largest degree.
    d = max([max(f.surface.degree) for f in part.faces] + [e.curve.degree for e in part.edges if e.curve is not None])
    assert (polynomial["max_degree"], report["max_degree"]) == (6 * d, 7 * d)
    assert report["exact_faces"] == 10
    size = float(np.linalg.norm(hi - lo))
    moved = 0.0
    for f, g, h in zip(part.faces, unit.faces, bent.faces):
        (u0, u1), (v0, v1) = f.domain
        uv = np.array([[u0 + (u1 - u0) * s, v0 + (v1 - v0) * (1 - s)] for s in np.linspace(0.1, 0.9, 5)])
        assert np.array_equal(g.points(uv), exact.faces[f.index].points(uv))
        assert np.max(np.abs(h.points(uv) - rl.deform(f.points(uv)))) <= 1e-12 * size
        moved = max(moved, float(np.max(np.abs(h.points(uv) - g.points(uv)))))
    assert moved > 1e-3 * size   # the weight changed the image
    with pytest.raises(TypeError, match="expected a Lattice or RationalLattice"):
        part.deform("lattice")
