# Scaling out on Dask (issue 26, item 2; docs/python.md "Scaling out"): a lattice shipped to two
# worker processes of a dask.distributed LocalCluster deforms chunks of points to the same bits as
# here, and examples/python/batch_ffd_dask.py, run against that cluster, writes the same bytes as
# `freeform ffd` for every mesh of a folder; a MeshFile (a .gltf with an external buffer) deformed
# on a worker comes back equal bit for bit. One cluster for the whole session (its start costs
# seconds on the 2-core CI machines).
import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

import freeform as ff
from conftest import ROOT, cli, random_lattice, run_cli

pytestmark = pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")
distributed = pytest.importorskip("dask.distributed")
cloudpickle = pytest.importorskip("cloudpickle")
# The workers cannot import this test module: send its functions by value.
cloudpickle.register_pickle_by_value(sys.modules[__name__])


@pytest.fixture(scope="session")
def dask_client():
    cluster = distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None)
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()


def deform_chunk(chunk, lattice):
    import os

    return lattice.deform(chunk, threads=1), lattice.report(chunk)["fold_count"], os.getpid()


def test_lattice_travels_to_worker_processes_and_back(dask_client):
    lat = random_lattice(ff, seed=12, scale=0.2, outside="extrapolate")
    lat.strength = 0.8
    pts = np.random.default_rng(3).uniform(-1.2, 1.2, (40_000, 3))
    chunks = np.array_split(pts, 8)
    futures = dask_client.map(deform_chunk, chunks, lattice=lat, pure=False)
    results = dask_client.gather(futures)
    got = np.concatenate([r[0] for r in results])
    here = lat.deform(pts, threads=1)
    assert got.dtype == here.dtype and got.tobytes() == here.tobytes()
    assert sum(r[1] for r in results) == lat.report(pts)["fold_count"]
    assert os.getpid() not in {r[2] for r in results}  # computed in the worker processes
    # and a lattice computed on a worker comes back whole
    back = dask_client.submit(lambda L: L.elevated(1, 0, 0), lat).result()
    assert back.degree == (4, 3, 3) and back.strength == lat.strength
    np.testing.assert_allclose(back.deform(pts[:100]), lat.deform(pts[:100]), rtol=0, atol=1e-12)


def deform_mesh(mesh, lattice):
    import os

    report = mesh.deform(lattice, threads=1)
    return mesh, report["vertices"], os.getpid()


def test_mesh_file_travels_to_a_worker_and_back(dask_client, tmp_path):
    # A .gltf with its buffer in a .bin beside it, read here from a folder that is gone before the
    # worker gets it: the pickle carries the file and its buffer, not the path.
    src = tmp_path / "src"
    src.mkdir()
    for name in ("sphere.gltf", "sphere.bin"):
        (src / name).write_bytes((ROOT / "data" / "meshes" / name).read_bytes())
    mesh = ff.MeshFile.read(str(src / "sphere.gltf"))
    shutil.rmtree(src)
    lat = random_lattice(ff, seed=4, scale=0.1)
    back, vertices, pid = dask_client.submit(deform_mesh, mesh, lat, pure=False).result()
    assert pid != os.getpid() and vertices == mesh.positions.shape[0]
    mesh.deform(lat, threads=1)
    assert back.positions.tobytes() == mesh.positions.tobytes()
    assert back.normals.tobytes() == mesh.normals.tobytes()
    mesh.write(str(tmp_path / "here.gltf"))
    written = (tmp_path / "here.gltf").read_bytes(), (tmp_path / "here.bin").read_bytes()
    back.write(str(tmp_path / "here.gltf"))
    assert (tmp_path / "here.gltf").read_bytes() == written[0]
    assert (tmp_path / "here.bin").read_bytes() == written[1]


def test_batch_example_writes_what_the_cli_writes(dask_client, tmp_path):
    cli()  # skips without the command-line tool
    src = tmp_path / "in"
    src.mkdir()
    for name in ["sphere.obj", "sphere.ply", "sphere.off", "sphere.stl", "sphere.glb", "cube.obj"]:
        shutil.copy(ROOT / "data" / "meshes" / name, src / name)
    shutil.copy(ROOT / "data" / "cages" / "torus.obj", src / "torus.obj")
    positions = ff.MeshFile.read(str(src / "sphere.obj")).positions
    lat = ff.Lattice.fit(positions, degree=(2, 3, 2), margin=0.3)
    lat.control_points[lat.index(2, 3, 1)] += [0.3, 0.2, -0.1]
    lat.control_points[lat.index(0, 1, 0)] -= [0.1, 0.0, 0.2]
    lat.save(str(tmp_path / "lat.json"))

    out = tmp_path / "out"
    r = subprocess.run([sys.executable, str(ROOT / "examples" / "python" / "batch_ffd_dask.py"),
                        "--scheduler", dask_client.scheduler.address, "meshes", str(src), str(tmp_path / "lat.json"),
                        str(out)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    lines = [json.loads(x) for x in r.stdout.splitlines() if x.startswith("{")]
    assert sorted(os.path.basename(x["output"]) for x in lines) == sorted(p.name for p in src.iterdir()
                                                                          if p.suffix != ".mtl")
    assert sorted(p.name for p in out.iterdir()) == sorted(os.path.basename(x["output"]) for x in lines)  # no temp left
    for entry in lines:
        name = os.path.basename(entry["output"])
        expected = tmp_path / f"cli-{name}"
        report = json.loads(run_cli("ffd", src / name, "--lattice", tmp_path / "lat.json", "-o", expected))
        assert (out / name).read_bytes() == expected.read_bytes(), name
        assert entry["vertices"] == report["vertices"] and entry["fold_count"] == report["fold_count"]


def test_batch_example_variants(dask_client, tmp_path):
    mesh = ROOT / "data" / "meshes" / "sphere.ply"
    lat = ff.Lattice.fit(ff.MeshFile.read(str(mesh)).positions, degree=2)
    lat.save(str(tmp_path / "lat.json"))
    out = tmp_path / "variants"
    r = subprocess.run([sys.executable, str(ROOT / "examples" / "python" / "batch_ffd_dask.py"), "--no-progress",
                        "--scheduler", dask_client.scheduler.address, "variants", str(mesh), str(tmp_path / "lat.json"),
                        str(out), "--count", "4", "--sigma", "0.05", "--seed", "7"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert len([x for x in r.stdout.splitlines() if x.startswith("{")]) == 4
    for i in range(4):
        # variant i: the lattice plus N(0, 0.05^2) noise from the stream (seed, i), recomputed here
        expected = lat.copy()
        expected.control_points += np.random.default_rng([7, i]).normal(0.0, 0.05, lat.control_points.shape)
        got = ff.Lattice.load(str(out / f"variant-{i:05d}.lattice.json"))
        np.testing.assert_array_equal(got.control_points, expected.control_points)
        m = ff.MeshFile.read(str(mesh))
        m.deform(expected)
        m.write(str(tmp_path / "here.ply"))
        assert (out / f"variant-{i:05d}.ply").read_bytes() == (tmp_path / "here.ply").read_bytes()
