# Pickling and copying (issue 26, item 2): every class pickles its defining fields and comes back
# equal bit for bit (the same arrays, byte for byte, and the same results of its calls); copy.copy
# and copy.deepcopy give independent objects. A MeshFile pickles the file as read (and a .gltf's
# external buffers) with its numbers as they are now, and reads it back from memory, not the disk.
import copy
import pickle

import numpy as np
import pytest

import freeform as ff
from conftest import ROOT, random_lattice

PROTOCOLS = sorted({2, pickle.DEFAULT_PROTOCOL, pickle.HIGHEST_PROTOCOL})


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def lattice_fields(lat):
    return [lat.degree, lat.origin, lat.axes, lat.control_points, lat.outside, lat.strength, lat.name]


def fields(obj):
    """What defines each object, and what its calls give (arrays compared byte for byte)."""
    rng = np.random.default_rng(5)
    if isinstance(obj, ff.Lattice):
        pts = rng.uniform(-1.5, 1.5, (50, 3))
        return lattice_fields(obj) + [obj.deform(pts), obj.det_j(pts), obj.weights(pts)]
    if isinstance(obj, ff.Binding):
        return [obj.size, obj.dtype]
    if isinstance(obj, ff.BezierCurve):
        return [obj.control_points, obj.evaluate(np.linspace(0, 1, 17))]
    if isinstance(obj, ff.Spline):
        return [obj.degree, obj.closed, obj.intervals, obj.control_points, obj.evaluate(np.linspace(0, obj.domain_end, 17))]
    if isinstance(obj, ff.Patch):
        return [obj.control_points, obj.evaluate(rng.uniform(0, 1, (9, 2)))]
    if isinstance(obj, ff.RationalBezierCurve):
        return [obj.homogeneous_points, obj.control_points, obj.weights, obj.evaluate(np.linspace(0, 1, 17))]
    if isinstance(obj, ff.NurbsCurve):
        a, b = obj.domain
        return [obj.degree, obj.knots, obj.homogeneous_points, obj.is_rational, obj.evaluate(np.linspace(a, b, 17))]
    if isinstance(obj, ff.RationalBezierSurface):
        return [obj.degree, obj.control_points, obj.weights, obj.evaluate(rng.uniform(0, 1, (9, 2)))]
    if isinstance(obj, ff.NurbsSurface):
        (u0, u1), (v0, v1) = obj.domain
        uv = np.column_stack([rng.uniform(u0, u1, 9), rng.uniform(v0, v1, 9)])
        return [obj.degree, obj.knots_u, obj.knots_v, obj.control_points, obj.weights, obj.is_rational, obj.evaluate(uv)]
    if isinstance(obj, ff.RationalLattice):
        pts = rng.uniform(-1.5, 1.5, (50, 3))
        return lattice_fields(obj.lattice) + [obj.weights, obj.strength, obj.deform(pts)]
    if isinstance(obj, ff.Document):
        out = [obj.names, [obj.type(n) for n in obj.names]]
        for n in obj.names:
            if obj.type(n) not in ("deboor_surface", "subdivision_surface"):
                out += fields(obj.object(n))
        return out
    raise AssertionError(type(obj))


def assert_same(a, b):
    fa, fb = fields(a), fields(b)
    assert len(fa) == len(fb)
    for x, y in zip(fa, fb):
        if isinstance(x, (np.ndarray, float)) and not isinstance(x, bool):
            assert same_bits(x, y), (x, y)
        else:
            assert x == y


def examples():
    lat = random_lattice(ff, degree=(2, 3, 1), seed=3, outside="keep")
    lat.strength = 0.7
    lat.name = "moved"
    lat.control_points[0] = [0.1, 1 / 3, np.nextafter(1.0, 2.0)]  # odd bits
    w = np.random.default_rng(2).uniform(0.5, 2.0, 24)
    knots = [0, 0, 0, 0.3, 0.7, 1, 1, 1]
    return {
        "Lattice": lat,
        "BezierCurve 2D": ff.BezierCurve(np.random.default_rng(1).normal(size=(4, 2))),
        "BezierCurve 3D": ff.BezierCurve(np.random.default_rng(1).normal(size=(6, 3))),
        "Spline": ff.Spline.interpolate(np.random.default_rng(4).normal(size=(7, 3)), end="natural"),
        "Spline closed 2D": ff.Spline.interpolate(np.random.default_rng(4).normal(size=(5, 2)), end="periodic"),
        "Patch": ff.Patch(np.random.default_rng(6).normal(size=(4, 3, 3))),
        "RationalBezierCurve": ff.RationalBezierCurve.circle_arc([0.5, 0.25], 1 / 3, 0.1, 2.0),
        "RationalBezierCurve 3D": ff.RationalBezierCurve(np.random.default_rng(8).normal(size=(4, 3)), [1, 1 / 3, 2.5, 0.7]),
        "NurbsCurve": ff.NurbsCurve(2, knots, np.random.default_rng(9).normal(size=(5, 3)), [1, 0.3, 1.7, 1 / 7, 1]),
        "NurbsCurve circle 2D": ff.NurbsCurve.circle([0.1, 0.2], 1 / 3),
        "RationalBezierSurface": ff.RationalBezierSurface(np.random.default_rng(3).normal(size=(3, 4, 3)),
                                                          np.random.default_rng(3).uniform(0.5, 2, (3, 4))),
        "NurbsSurface": ff.NurbsSurface.sphere([0.1, 0.2, 0.3], 1 / 3),
        "RationalLattice": ff.RationalLattice(lat, w),
        "Document": ff.Document.load(str(ROOT / "data" / "ffd_every_type.json")),
        "Document nurbs": ff.Document.load(str(ROOT / "examples" / "data" / "nurbs.json")),
    }


EXAMPLES = list(examples())


@pytest.mark.parametrize("name", EXAMPLES)
def test_pickle_round_trip_is_bit_for_bit(name):
    obj = examples()[name]
    for protocol in PROTOCOLS:
        back = pickle.loads(pickle.dumps(obj, protocol=protocol))
        assert type(back) is type(obj)
        assert back is not obj
        assert_same(obj, back)


@pytest.mark.parametrize("name", EXAMPLES)
def test_copy_and_deepcopy(name):
    obj = examples()[name]
    for c in (copy.copy(obj), copy.deepcopy(obj), copy.deepcopy([obj, obj])[0]):
        assert type(c) is type(obj) and c is not obj
        assert_same(obj, c)


def test_copies_are_independent():
    lat = random_lattice(ff)
    before = lat.control_points.copy()
    for c in (copy.copy(lat), copy.deepcopy(lat), pickle.loads(pickle.dumps(lat))):
        c.control_points += 1.0
        c.strength = 0.5
        np.testing.assert_array_equal(lat.control_points, before)
        assert lat.strength == 1.0
    doc = ff.Document.load(str(ROOT / "examples" / "data" / "demo.json"))
    d2 = copy.deepcopy(doc)
    d2.remove("arch")
    assert "arch" in doc and "arch" not in d2


def test_pickled_lattice_keeps_unsaved_edits_and_document_saves_the_same_bytes(tmp_path):
    lat = random_lattice(ff, seed=9)
    lat.control_points[5] = [1e-300, -0.0, 12345.678901234567]
    back = pickle.loads(pickle.dumps(lat))
    assert same_bits(back.control_points, lat.control_points)
    lat.save(str(tmp_path / "a.json"))
    back.save(str(tmp_path / "b.json"))
    assert (tmp_path / "a.json").read_bytes() == (tmp_path / "b.json").read_bytes()
    doc = ff.Document.load(str(ROOT / "data" / "ffd_every_type.json"))
    pickle.loads(pickle.dumps(doc)).save(str(tmp_path / "d1.json"))
    doc.save(str(tmp_path / "d0.json"))
    assert (tmp_path / "d0.json").read_bytes() == (tmp_path / "d1.json").read_bytes()


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_binding_round_trip_deforms_the_same(dtype):
    lat = random_lattice(ff, seed=4, outside="keep")
    pts = np.random.default_rng(1).uniform(-1.3, 1.3, (1000, 3)).astype(dtype)
    b = lat.bind(pts)
    moved = lat.copy()
    moved.control_points += 0.05
    for c in (pickle.loads(pickle.dumps(b)), copy.deepcopy(b), copy.copy(b)):
        assert c.size == 1000 and c.dtype == np.dtype(dtype)
        assert same_bits(c.deform(moved), b.deform(moved))
        assert same_bits(c.deform(moved), moved.deform(pts))
    # the frame travels too: a lattice with another frame is refused by the copy as by the original
    other = ff.Lattice(3, origin=[0, 0, 0], axes=np.eye(3))
    with pytest.raises(ff.Error, match="frame"):
        pickle.loads(pickle.dumps(b)).deform(other)


MESH_SAMPLES = ["cube.obj", "sphere.obj", "sphere.ply", "sphere.gltf", "sphere.glb", "sphere.off", "sphere.stl"]


@pytest.mark.parametrize("name", MESH_SAMPLES)
def test_mesh_file_pickles_from_memory_and_writes_the_same_file(name, tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    for f in (ROOT / "data" / "meshes").iterdir():          # the sample and its .bin / .mtl beside it
        (src / f.name).write_bytes(f.read_bytes())
    m = ff.MeshFile.read(str(src / name))
    assert m.file_bytes() == (src / name).read_bytes()
    lat = ff.Lattice(2, origin=[-1.5, -1.5, -1.5], axes=np.eye(3) * 3)
    lat.control_points[lat.index(1, 1, 2)] += [0.1, -0.2, 0.3]
    m.deform(lat)                                              # unsaved edits travel with the pickle
    for protocol in PROTOCOLS:
        data = pickle.dumps(m, protocol=protocol)
        for f in src.iterdir():                                # nothing of it is on the disk any more
            f.unlink()
        back = pickle.loads(data)
        for f in (ROOT / "data" / "meshes").iterdir():
            (src / f.name).write_bytes(f.read_bytes())
        assert back.path == m.path and back.format == m.format
        assert same_bits(back.positions, m.positions)
        assert same_bits(back.normals, m.normals)
        assert same_bits(back.tangents, m.tangents)
        assert back.normal_anchors == m.normal_anchors
        assert back.file_bytes() == m.file_bytes()
        assert back.companions == m.companions
        ext = name.rsplit(".", 1)[1]
        out = tmp_path / f"out.{ext}"                          # a .gltf's buffer goes beside it as out.bin
        m.write(str(out))
        written = out.read_bytes(), (tmp_path / "out.bin").read_bytes() if ext == "gltf" else b""
        out.unlink()
        back.write(str(out))
        assert out.read_bytes() == written[0]
        if ext == "gltf":
            assert back.companions == {"sphere.bin": (ROOT / "data" / "meshes" / "sphere.bin").read_bytes()}
            assert (tmp_path / "out.bin").read_bytes() == written[1]
    for c in (copy.copy(m), copy.deepcopy(m)):
        assert same_bits(c.positions, m.positions) and c.path == m.path
        c.positions[:] += 1.0
        assert not np.array_equal(c.positions, m.positions)


def test_mesh_file_read_bytes_and_its_errors():
    meshes = ROOT / "data" / "meshes"
    m = ff.MeshFile.read_bytes("in/memory.ply", (meshes / "sphere.ply").read_bytes())
    assert same_bits(m.positions, ff.MeshFile.read(str(meshes / "sphere.ply")).positions)
    assert m.path == "in/memory.ply" and m.companions == {}
    with pytest.raises(ff.Error, match=r"m\.gltf: buffer 0: the uri \"sphere\.bin\" names sphere\.bin, which is not among"):
        ff.MeshFile.read_bytes("m.gltf", (meshes / "sphere.gltf").read_bytes())
    g = ff.MeshFile.read_bytes("m.gltf", (meshes / "sphere.gltf").read_bytes(),
                               companions={"sphere.bin": (meshes / "sphere.bin").read_bytes()})
    assert same_bits(g.positions, ff.MeshFile.read(str(meshes / "sphere.gltf")).positions)
    with pytest.raises(ff.Error, match=r"cut\.stl: "):
        ff.MeshFile.read_bytes("cut.stl", (meshes / "sphere.stl").read_bytes()[:200])
    state = m.__getstate__()
    with pytest.raises(ff.Error, match="expected 6 fields"):
        ff.MeshFile.__new__(ff.MeshFile).__setstate__(state[:5])
    with pytest.raises(ff.Error, match=r"positions: expected 266 rows, got 3"):
        ff.MeshFile.__new__(ff.MeshFile).__setstate__((state[0], state[1], state[2], np.zeros((3, 3)), *state[4:]))


def test_corrupt_states_raise_freeform_error():
    state = ff.Lattice(2, origin=[0, 0, 0], axes=np.eye(3)).__getstate__()
    lat = ff.Lattice.__new__(ff.Lattice)
    with pytest.raises(ff.Error, match=r"axes: expected an array of shape \(3, 3\)"):
        lat.__setstate__((state[0], state[1], np.eye(3)[:, :2], *state[3:]))
    with pytest.raises(ff.Error, match="expected 7 fields"):
        ff.Lattice.__new__(ff.Lattice).__setstate__(state[:3])
