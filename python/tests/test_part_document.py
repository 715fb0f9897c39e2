# freeform.Part and TrimmedSurface without a CAD file (docs/python.md "CAD parts"): these run in
# every build, a module built without Open CASCADE (FREEFORM_BUILD_CAD=OFF) included, where parts
# come from documents and from trimmed surfaces built in Python. The facts are computed by hand:
# data/parts/plate.json is a 40 x 30 x 10 mm plate with a through hole of radius 6 mm.
import math
import pathlib

import numpy as np
import pytest

import freeform as ff

ROOT = pathlib.Path(__file__).resolve().parents[2]
PLATE = ROOT / "data" / "parts" / "plate.json"
CAD = (".step", ".stp", ".iges", ".igs", ".brep")


def mesh_volume(V, F):
    """The volume a closed, outward mesh encloses (the divergence theorem over its triangles)."""
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return float(np.sum(np.einsum("ij,ij->i", a, np.cross(b, c)))) / 6


def edge_counts(F):
    """Undirected edge -> number of triangles, and directed edges seen twice (orientation clashes):
    a consistently oriented closed mesh has every edge in two triangles and no clash."""
    directed = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    _, counts = np.unique(np.sort(directed, axis=1), axis=0, return_counts=True)
    _, directed_counts = np.unique(directed, axis=0, return_counts=True)
    return counts, int(np.sum(directed_counts > 1))


def test_formats_say_what_load_and_save_take(tmp_path):
    formats = ff.Part.formats
    assert ".json" in formats
    assert set(formats) in ({".json"}, set(CAD) | {".json"})
    plate = ff.Part.load(str(PLATE))
    if ".step" in formats:
        plate.save(str(tmp_path / "plate.step"))
        back = ff.Part.load(str(tmp_path / "plate.step"))
        assert (len(back.faces), len(back.edges)) == (len(plate.faces), len(plate.edges))
        return
    # Without Open CASCADE: every CAD file refused by name, and nothing written.
    for ext in CAD:
        path = tmp_path / ("plate" + ext)
        with pytest.raises(ff.Error, match="plate" + ext.replace(".", r"\.") + ".*without Open CASCADE"):
            plate.save(str(path))
        assert not path.exists()
        path.write_text("not read")
        with pytest.raises(ff.Error, match="without Open CASCADE"):
            ff.Part.load(str(path))


def test_the_plate_of_a_document_has_its_hand_computed_area_and_volume():
    part = ff.Part.load(str(PLATE))
    assert (len(part.faces), len(part.edges), len(part.vertices)) == (7, 15, 10)
    check = part.check()
    assert check["closed"] and check["open_edges"] == 0 and check["non_manifold_edges"] == 0
    lo, hi = part.bounds
    assert np.all(lo <= [0, 0, 0]) and np.all(hi >= [40, 30, 10])
    # Top and bottom 40 x 30 less the hole, four sides, the hole's wall.
    area = 2 * (40 * 30 - math.pi * 36) + 2 * 40 * 10 + 2 * 30 * 10 + 2 * math.pi * 6 * 10
    assert math.isclose(part.area, area, rel_tol=1e-9)
    volume = 40 * 30 * 10 - math.pi * 36 * 10
    for tolerance in (0.1, 0.01):
        V, F, r = part.tessellate(tolerance, report=True)
        counts, clashes = edge_counts(F)
        assert np.all(counts == 2) and clashes == 0
        assert r["watertight"] and r["certified"] and r["error_bound"] <= tolerance
        # Every mesh point within error_bound of the surface: the volumes differ by at most that
        # times the area.
        assert abs(mesh_volume(V, F) - volume) <= r["error_bound"] * area


def test_a_part_goes_through_a_document_file_unchanged(tmp_path):
    part = ff.Part.load(str(PLATE))
    path = tmp_path / "copy.json"
    report = part.save(str(path))
    assert report["valid"]
    back = ff.Part.load(str(path))
    assert len(back.faces) == len(part.faces)
    for a, b in zip(part.faces, back.faces):
        (u0, u1), (v0, v1) = a.domain
        uv = np.array([[u0 + (u1 - u0) * s, v0 + (v1 - v0) * (1 - s)] for s in np.linspace(0, 1, 5)])
        assert np.array_equal(a.points(uv), b.points(uv))
    # A lattice that moves the plate by (1, 2, 3) moves every face point by it (an affine lattice:
    # no degree rise).
    lat = ff.Lattice.fit(np.array([[-1, -1, -1], [41, 31, 11]], dtype=float), degree=(1, 1, 1))
    lat.control_points = lat.control_points + [1.0, 2.0, 3.0]
    moved, r = part.deform(lat)
    assert r["exact_faces"] == len(part.faces) and r["approximated_faces"] == []
    for a, b in zip(part.faces, moved.faces):
        (u0, u1), (v0, v1) = a.domain
        uv = np.array([[0.5 * (u0 + u1), 0.5 * (v0 + v1)]])
        assert np.allclose(b.points(uv), a.points(uv) + [1, 2, 3], rtol=0, atol=1e-12 * 50)


# ---------------------------------------------------------------- TrimmedSurface


def _plate():
    # A flat 2 x 3 patch, trimmed to the circle of radius 0.4 about (0.5, 0.5) of its parameters,
    # less the square hole [0.4, 0.6]^2 run backwards: area 6 (0.16 pi - 0.04) by hand.
    G = np.array([[[0, 0, 0], [0, 3, 0]], [[2, 0, 0], [2, 3, 0]]], dtype=float)
    surface = ff.NurbsSurface((1, 1), [0, 0, 1, 1], [0, 0, 1, 1], G)
    circle = ff.NurbsCurve.circle(center=[0.5, 0.5], radius=0.4)
    square = ff.NurbsCurve(1, [0, 0, 1, 2, 3, 4, 4], [[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6], [0.4, 0.4]])
    return ff.TrimmedSurface(surface, ((0, 1), (0, 1)), [[circle], [(square, 0, 4, True)]])


def test_a_trimmed_surface_built_in_python_has_the_area_computed_by_hand():
    t = _plate()
    assert isinstance(t, ff.Face)
    assert math.isclose(t.area, 6 * (0.16 * math.pi - 0.04), rel_tol=1e-9)
    assert list(t.classify([[0.5, 0.5], [0.5, 0.25], [0.05, 0.05]])) == [-1, 1, -1]
    assert np.array_equal(t.points([[0.5, 0.25]]), [[1.0, 0.75, 0.0]])
    trims = t.trims
    assert [len(loop) for loop in trims] == [1, 1]
    curve, first, last, reversed_ = trims[1][0]
    assert (first, last, reversed_) == (0, 4, True)
    assert np.array_equal(curve.control_points, [[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6], [0.4, 0.4]])
    # The certified mesh: every vertex inside or on the trims, its area the face's within the bound
    # (a flat face: the polygon's area misses the circle's segments only).
    V, F, r = t.tessellate(1e-3, report=True)
    assert r["certified"] and r["error_bound"] <= 1e-3
    uv = V[:, :2] / [2.0, 3.0]
    assert np.all(t.classify(uv) >= 0)
    a = 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1).sum()
    assert abs(a - t.area) < 2 * math.pi * 0.4 * 3 * 1e-3   # the circle's length (at most 3x) times the bound


def test_a_trimmed_surface_goes_through_a_document_and_a_lattice():
    t = _plate()
    doc = ff.Document()
    doc.add("plate", t)
    assert doc.type("plate") == "trimmed_surface"
    back = doc.object("plate")
    assert isinstance(back, ff.TrimmedSurface)
    uv = np.array([[0.3, 0.5], [0.5, 0.2], [0.7, 0.7]])
    assert np.array_equal(back.points(uv), t.points(uv))
    assert back.area == t.area
    # The document's trimmed square (a unit square less a circle of radius 1/4).
    square = ff.Document.load(str(ROOT / "data" / "parts" / "trimmed_square.json"))
    sq = square.object("square")
    assert math.isclose(sq.area, 1 - math.pi / 16, rel_tol=1e-9)
    # Through a general lattice: the exact composition equals the lattice applied to the points.
    lat = ff.Lattice.fit(np.array([[0, 0, -1], [2, 3, 1]], dtype=float), degree=(2, 2, 1))
    P = lat.control_points.copy()
    P[lat.index(1, 1, 1)] += [0.3, -0.2, 0.5]
    lat.control_points = P
    bent, report = t.deform(lat)
    assert isinstance(bent, ff.TrimmedSurface) and report["exact_faces"] == 1
    assert np.allclose(bent.points(uv), lat.deform(t.points(uv)), rtol=0, atol=1e-12 * 3)
    assert list(bent.classify(uv)) == list(t.classify(uv))   # the trims are kept
    with pytest.raises(ff.Error, match="expected a 2D NurbsCurve"):
        ff.TrimmedSurface(t.surface, None, [[ff.NurbsCurve.circle(center=[0, 0, 0], radius=1)]])
    with pytest.raises(ff.Error, match="knot domain"):
        ff.TrimmedSurface(t.surface, ((0, 2), (0, 1)))
