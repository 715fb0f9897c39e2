# Curves, splines, patches, documents and mesh files from Python, checked against NumPy
# reimplementations, hand values, identities and the command-line tool.
import json
import shutil

import numpy as np
import pytest

import freeform as ff
from conftest import ROOT, bernstein, run_cli

ARCH = np.array([[0, 0], [1, 2], [3, 2], [4, 0]], dtype=float)


def test_curve_hand_values_and_bernstein_sum():
    c = ff.BezierCurve(ARCH)
    assert c.degree == 3 and c.dimension == 2
    np.testing.assert_allclose(c.evaluate([0.5]), [[2.0, 1.5]])  # README's hand value
    t = np.linspace(0, 1, 101)
    np.testing.assert_allclose(c.evaluate(t), bernstein(3, t) @ ARCH, atol=1e-14)
    np.testing.assert_allclose(c(t), c.evaluate(t))
    jet = c.derivatives([0.5], 2)
    assert jet.shape == (1, 3, 2)
    np.testing.assert_allclose(jet[0], [[2, 1.5], [4.5, 0], [0, -12]], atol=1e-14)  # docs/cli.md example


def test_curve_split_and_elevate_are_the_same_curve():
    rng = np.random.default_rng(2)
    c = ff.BezierCurve(rng.normal(size=(6, 3)))
    a, b = c.split(0.3)
    t = np.linspace(0, 1, 17)
    np.testing.assert_allclose(a.evaluate(t), c.evaluate(0.3 * t), atol=1e-13)
    np.testing.assert_allclose(b.evaluate(t), c.evaluate(0.3 + 0.7 * t), atol=1e-13)
    e = c.elevated(2)
    assert e.degree == 7
    np.testing.assert_allclose(e.evaluate(t), c.evaluate(t), atol=1e-13)
    # derivative by central differences
    h = 1e-6
    d = c.derivatives(t[1:-1], 1)[:, 1]
    np.testing.assert_allclose(d, (c.evaluate(t[1:-1] + h) - c.evaluate(t[1:-1] - h)) / (2 * h), rtol=1e-6, atol=1e-7)


def test_curve_bad_input():
    with pytest.raises(ff.Error, match=r"shape \(N, 2\) or \(N, 3\)"):
        ff.BezierCurve(np.zeros((3, 4)))
    with pytest.raises(ff.Error, match="not finite"):
        ff.BezierCurve([[0, 0], [np.nan, 1]])
    with pytest.raises(ff.Error, match="outside"):
        ff.BezierCurve(ARCH).evaluate([1.5])
    with pytest.raises(TypeError):
        ff.BezierCurve("abc")


def test_interpolating_spline_is_c2_and_passes_through_the_points():
    pts = np.array([[0, 0, 0], [1, 2, 0], [3, 3, 1], [4, 0, 2], [6, 1, 1]], dtype=float)
    s = ff.Spline.interpolate(pts)
    assert s.degree == 3 and s.segment_count == 4 and not s.closed
    np.testing.assert_allclose(s.evaluate(s.knots), pts, atol=1e-12)
    # chord-length parameters: the intervals are the distances between the points
    np.testing.assert_allclose(s.intervals, np.linalg.norm(np.diff(pts, axis=0), axis=1), rtol=1e-14)
    for joint in s.continuity()[1:-1]:
        assert joint["C"] >= 2
    # second derivatives agree from both sides of every interior knot; natural ends: f'' = 0
    eps = 1e-9
    for k in s.knots[1:-1]:
        left = s.derivatives([k - eps], 2)[0, 2]
        right = s.derivatives([k + eps], 2)[0, 2]
        np.testing.assert_allclose(left, right, atol=1e-5)
    np.testing.assert_allclose(s.derivatives([0.0, s.domain_end], 2)[:, 2], 0, atol=1e-12)


def test_spline_against_cli_interpolate(tmp_path):
    pts = [[0, 0], [1, 1], [2, 0], [3, 1]]
    src = tmp_path / "pts.json"
    src.write_text(json.dumps({"points": pts}))
    out = tmp_path / "s.json"
    run_cli("interpolate", src, "-o", out)
    doc = ff.Document.load(str(out))
    spline = doc.curve("interpolant")
    np.testing.assert_allclose(spline.control_points, ff.Spline.interpolate(np.array(pts, float)).control_points,
                               atol=1e-12)


def test_patch_against_tensor_bernstein_sum():
    rng = np.random.default_rng(3)
    P = rng.normal(size=(3, 4, 3))
    p = ff.Patch(P)
    assert p.degree == (2, 3)
    uv = rng.uniform(0, 1, (50, 2))
    expected = np.einsum("ni,nj,ijc->nc", bernstein(2, uv[:, 0]), bernstein(3, uv[:, 1]), P)
    np.testing.assert_allclose(p.evaluate(uv), expected, atol=1e-13)
    a, b = p.split_u(0.4)
    np.testing.assert_allclose(a.evaluate([[1.0, 0.3]]), p.evaluate([[0.4, 0.3]]), atol=1e-13)
    V, F, N = p.tessellate(4)
    assert V.shape == (25, 3) and F.shape == (32, 3) and N.shape == (25, 3)
    np.testing.assert_allclose(np.linalg.norm(N, axis=1), 1, atol=1e-12)


def test_document_evaluate_matches_cli():
    path = ROOT / "examples" / "data" / "demo.json"
    doc = ff.Document.load(str(path))
    assert doc.names == ["arch", "helix"] and doc.type("arch") == "bezier_curve" and "helix" in doc
    e = doc.evaluate("arch", [0.5], 2)
    cli = json.loads(run_cli("eval", path, "--object", "arch", "--at", "0.5", "--derivatives", "2"))
    np.testing.assert_array_equal(e["point"], cli["point"])
    np.testing.assert_array_equal(np.array(e["derivatives"]), np.array(cli["derivatives"]))
    with pytest.raises(ff.Error, match="arch"):
        doc.evaluate("arch", [2.0])
    with pytest.raises(ff.Error, match="nope"):
        doc.evaluate("nope", [0.5])


def test_document_tessellate_subdivision_and_deform(tmp_path):
    doc = ff.Document.load(str(ROOT / "data" / "cages" / "torus.json"))
    name = doc.names[0]
    V, F, N = doc.tessellate(name, segments=2)
    assert V.shape[1] == 3 and len(F) > 0
    e = doc.evaluate(name, [0, 0.5, 0.5], 1)
    assert e["face"] == 0 and len(e["point"]) == 3
    # the limit surface lies in the convex hull of the cage, so inside its bounding box
    cage = ff.MeshFile.read(str(ROOT / "data" / "cages" / "torus.obj")).positions
    lo, hi = cage.min(0) - 1e-12, cage.max(0) + 1e-12
    assert np.all((V >= lo) & (V <= hi)) and np.all((e["point"] >= lo) & (e["point"] <= hi))
    assert np.linalg.norm(e["derivatives"][0]) > 0
    lat = ff.Lattice.load(str(ROOT / "data" / "cages" / "bend_lattice.json"))
    report = doc.deform(lat)
    assert report["certificate"] in ("certified injective", "folds", "undecided")
    doc.save(str(tmp_path / "out.json"))
    assert ff.Document.load(str(tmp_path / "out.json")).names == doc.names


@pytest.mark.parametrize("name", ["cube.obj", "sphere.obj", "sphere.ply", "sphere.stl", "sphere.off",
                                  "sphere.gltf", "sphere.glb"])
def test_mesh_files_round_trip_bit_for_bit(tmp_path, name):
    src = ROOT / "data" / "meshes" / name
    for extra in ["cube.mtl", "sphere.bin"]:
        shutil.copy(ROOT / "data" / "meshes" / extra, tmp_path / extra)
    m = ff.MeshFile.read(str(src))
    assert m.format == name.split(".")[1]
    pos = m.positions
    assert pos.shape[1] == 3 and np.shares_memory(pos, m.positions)  # a view of the file's numbers
    out = tmp_path / name
    m.write(str(out))
    assert out.read_bytes() == src.read_bytes()
    # an edit through the view is written, and read back
    pos[0] += [0.25, 0.5, 0.125]
    m.write(str(out))
    # (STL and glTF store float32: the nearest float32 is written)
    np.testing.assert_allclose(ff.MeshFile.read(str(out)).positions[0], pos[0], rtol=1e-7)
    info = m.info()
    cli = json.loads(run_cli("info", src))
    assert info["positions"] == pos.shape[0]
    assert json.dumps(cli)  # the CLI reads the same file
    V, F, N = m.to_arrays()
    assert V.shape == pos.shape and len(F) == info["faces"]


def test_mesh_file_errors(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0\nf 1 2 3\n")
    with pytest.raises(ff.Error, match="bad.obj"):
        ff.MeshFile.read(str(bad))
    with pytest.raises(ff.Error):
        ff.MeshFile.read(str(tmp_path / "x.unknown"))


def test_clamped_interpolation_against_cli(tmp_path):
    pts = [[0, 0, 0], [1, 1, 0], [2, 0, 1], [3, 1, 1]]
    src = tmp_path / "pts.json"
    src.write_text(json.dumps({"points": pts}))
    out = tmp_path / "s.json"
    run_cli("interpolate", src, "-o", out, "--end", "clamped", "--start-derivative", "1,0,0",
            "--end-derivative", "0,2,0", "--param", "centripetal")
    cli = ff.Document.load(str(out)).curve("interpolant")
    s = ff.Spline.interpolate(pts, end="clamped", parametrization="centripetal", start_derivative=[1, 0, 0],
                              end_derivative=[0, 2, 0])
    np.testing.assert_allclose(s.control_points, cli.control_points, atol=1e-12)
    # the end derivatives are the ones asked for (by the Bézier end points: f'(0) = 3 (P1 - P0) / h0)
    np.testing.assert_allclose(s.derivatives([0.0, s.domain_end], 1)[:, 1], [[1, 0, 0], [0, 2, 0]], atol=1e-12)
    with pytest.raises(ff.Error, match="only with end='clamped'"):
        ff.Spline.interpolate(pts, start_derivative=[1, 0, 0])
    with pytest.raises(ff.Error, match="expected 3 numbers"):
        ff.Spline.interpolate(pts, end="clamped", start_derivative=[1, 0])


@pytest.mark.parametrize("name", ["cube.obj", "sphere.obj", "sphere.ply", "sphere.stl", "sphere.off",
                                  "sphere.gltf", "sphere.glb"])
def test_mesh_info_counts_equal_the_cli(tmp_path, name):
    for extra in ["cube.mtl", "sphere.bin"]:
        shutil.copy(ROOT / "data" / "meshes" / extra, tmp_path / extra)
    shutil.copy(ROOT / "data" / "meshes" / name, tmp_path / name)
    info = ff.MeshFile.read(str(tmp_path / name)).info()
    cli = json.loads(run_cli("info", tmp_path / name))
    for key in ["vertices", "edges", "faces", "boundary_edges", "boundary_loops", "components", "manifold", "closed",
                "euler", "genus"]:
        assert info[key] == cli[key], key
    assert info["euler"] == info["vertices"] - info["edges"] + info["faces"]


def test_subdivision_limit_evaluation_equals_the_cli():
    path = ROOT / "data" / "cages" / "torus.json"
    doc = ff.Document.load(str(path))
    name = doc.names[0]
    for face, u, v in [(0, 0.5, 0.5), (3, 0.25, 0.75), (7, 0.0, 1.0)]:
        e = doc.evaluate(name, [face, u, v], 1)
        out = json.loads(run_cli("eval", path, "--object", name, "--at", f"{face},{u},{v}", "--derivatives", 1))
        np.testing.assert_allclose(e["point"], out["point"], rtol=1e-15, atol=1e-15)
        np.testing.assert_allclose(e["normal"], out["normal"], rtol=1e-15, atol=1e-15)
        np.testing.assert_allclose(e["derivatives"][0], out["derivatives"]["u"], rtol=1e-15, atol=1e-15)
        np.testing.assert_allclose(e["derivatives"][1], out["derivatives"]["v"], rtol=1e-15, atol=1e-15)


def test_a_reader_warning_is_a_python_warning(tmp_path):
    # A PLY header line Blender 2.47 wrote is kept as a comment (docs/mesh-io.md); the library's
    # warning reaches Python as a UserWarning naming the file and the line, and nothing is printed.
    path = tmp_path / "blender.ply"
    path.write_text("ply\nformat ascii 1.0\nCreated by Blender3D 247 - www.blender.org\nelement vertex 3\n"
                    "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                    "property list uchar uint vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    with pytest.warns(UserWarning, match=r"blender\.ply.*unknown header line 'Created' kept as a comment") as record:
        mesh = ff.MeshFile.read(str(path))
    assert len(record) == 1
    assert mesh.positions.shape == (3, 3)


def test_kinds_table_describes_every_object_of_the_documents():
    # ff.kinds() is the library's kind table; each row's parameters, nature and operations are
    # checked against what the Document calls do with a real object of that kind.
    kinds = ff.kinds()
    table = {k["name"]: k for k in kinds}
    assert len(table) == len(kinds) == 13
    at = {"t": [0.0], "uv": [0.0, 0.0], "face_uv": [0, 0.5, 0.5], "stu": [0.5, 0.25, 0.75]}
    seen = set()
    for path in (ROOT / "data" / "ffd_every_type.json", ROOT / "examples" / "data" / "nurbs.json",
                 ROOT / "data" / "parts" / "plate.json", ROOT / "data" / "parts" / "trimmed_square.json"):
        doc = ff.Document.load(str(path))
        for o in json.loads(path.read_text())["objects"]:
            name = o["name"]
            k = table[doc.type(name)]
            assert k["name"] == o["type"]
            seen.add(k["name"])
            # A part's faces and a trimmed surface are NURBS (weights and knots where their
            # surfaces have them); a part is evaluated at FACE,U,V inside its face's box.
            trimmed = o["type"] in ("part", "trimmed_surface")
            surface = o["faces"][0] if o["type"] == "part" else o
            param = list(at[k["parameters"]])
            if trimmed:
                u0, u1, v0, v1 = surface["domain"]
                param = param[:-2] + [0.5 * (u0 + u1), 0.5 * (v0 + v1)]
                assert k["nature"] == ("brep" if o["type"] == "part" else "surface")
            assert k["rational"] == (trimmed or o["type"].startswith("rational") or o["type"].startswith("nurbs"))
            assert k["knots"] == ("knots" in surface)
            r = doc.evaluate(name, param)
            assert len(r["point"]) == (k["dimension"] or len(o["points"][0]))
            if trimmed:
                assert r["trim"] in ("inside", "outside", "boundary")
            with pytest.raises(ff.Error):
                doc.evaluate(name, param[:-1])
            if k["nature"] == "curve":
                doc.curve(name)
            else:
                with pytest.raises(ff.Error):
                    doc.curve(name)
            if "tessellate" in k["operations"]:
                positions, faces, _ = doc.tessellate(name, segments=2)
                assert len(positions) > 0 and len(faces) > 0
            else:
                with pytest.raises(ff.Error):
                    doc.tessellate(name, segments=2)
    assert seen == set(table)
