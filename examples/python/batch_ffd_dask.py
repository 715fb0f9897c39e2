#!/usr/bin/env python3
"""Free-form deformation of many meshes, or of one mesh through many lattices, on a Dask cluster
(docs/python.md, "Scaling out").

    # every mesh file of a folder through one lattice (as `freeform ffd MESH --lattice L -o OUT` each)
    PYTHONPATH=build/python python3 examples/python/batch_ffd_dask.py meshes IN_DIR LATTICE.json OUT_DIR

    # N random variants of one lattice (control points + N(0, sigma^2) noise, seeded per variant)
    PYTHONPATH=build/python python3 examples/python/batch_ffd_dask.py variants MESH LATTICE.json OUT_DIR --count 100

Without --scheduler the script starts a dask.distributed LocalCluster on this machine (--workers
processes, one thread each); with --scheduler tcp://host:8786 the same script sends the same tasks
to a running cluster. The lattice is shipped to the workers once (pickled: freeform objects pickle
their defining fields) and every task reads its mesh, deforms it and writes its result atomically
(a temporary file in OUT_DIR, then os.replace), so an interrupted run leaves whole files only, and a
rerun can skip what exists (--skip-existing). Paths must be visible to the workers under the same
names (one machine, or a shared file system), and every worker must be able to `import freeform`.

Prints one JSON line per result (the report of the deformation) after a progress bar.
"""
import argparse
import contextlib
import json
import os
import pathlib
import sys
import uuid

MESH_SUFFIXES = (".obj", ".ply", ".stl", ".off", ".glb")  # single-file formats (.gltf may have .bin buffers)


def atomic_write(path, write):
    """write(temporary_path), then os.replace onto path: readers see the old file or the whole new one."""
    path = pathlib.Path(path)
    tmp = path.with_name(f".{path.stem}.{uuid.uuid4().hex}.tmp{path.suffix}")  # the suffix picks the format
    try:
        write(str(tmp))
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def deform_file(mesh_path, lattice, out_path, normals="jacobian"):
    """One task: read the mesh losslessly, deform it (as `freeform ffd`), write it atomically."""
    import freeform as ff

    mesh = ff.MeshFile.read(str(mesh_path))
    report = mesh.deform(lattice, normals=normals, threads=1)  # one thread per task: the cluster parallelises
    atomic_write(out_path, mesh.write)
    report.pop("folds")
    return {"input": str(mesh_path), "output": str(out_path), **report}


def deform_variant(index, mesh_path, lattice, out_dir, sigma, seed):
    """One task: variant `index` of the lattice (its own random stream), the mesh through it, both written."""
    import numpy as np

    variant = lattice.copy()
    rng = np.random.default_rng([seed, index])
    variant.control_points += rng.normal(0.0, sigma, variant.control_points.shape)
    variant.name = f"variant_{index:05d}"
    out_dir = pathlib.Path(out_dir)
    suffix = pathlib.Path(mesh_path).suffix
    result = deform_file(mesh_path, variant, out_dir / f"variant-{index:05d}{suffix}")
    atomic_write(out_dir / f"variant-{index:05d}.lattice.json", variant.save)
    result["certificate"] = variant.certify()["verdict"]
    return result


def connect(args):
    from dask.distributed import Client, LocalCluster

    if args.scheduler:
        return Client(args.scheduler), None
    cluster = LocalCluster(n_workers=args.workers, processes=True, threads_per_worker=1, dashboard_address=None)
    return Client(cluster), cluster


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scheduler", help="address of a running dask scheduler (default: start a LocalCluster)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default 2)")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar")
    sub = ap.add_subparsers(dest="mode", required=True)
    m = sub.add_parser("meshes", help="every mesh file of a folder through one lattice")
    m.add_argument("input_dir")
    m.add_argument("lattice")
    m.add_argument("output_dir")
    m.add_argument("--normals", choices=["jacobian", "recompute"], default="jacobian")
    m.add_argument("--skip-existing", action="store_true", help="skip meshes whose output exists")
    v = sub.add_parser("variants", help="one mesh through N random variants of one lattice")
    v.add_argument("mesh")
    v.add_argument("lattice")
    v.add_argument("output_dir")
    v.add_argument("--count", type=int, default=10)
    v.add_argument("--sigma", type=float, default=0.02, help="standard deviation of the control-point noise")
    v.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)

    import freeform as ff
    from dask.distributed import progress

    lattice = ff.Lattice.load(args.lattice)
    out_dir = pathlib.Path(args.output_dir).resolve()
    out_dir.mkdir(parents=True, exist_ok=True)

    client, cluster = connect(args)
    try:
        shared = client.scatter(lattice, broadcast=True)  # pickled once, one copy per worker
        if args.mode == "meshes":
            inputs = sorted(p.resolve() for p in pathlib.Path(args.input_dir).iterdir()
                            if p.is_file() and p.suffix.lower() in MESH_SUFFIXES)
            jobs = [(p, out_dir / p.name) for p in inputs if not (args.skip_existing and (out_dir / p.name).exists())]
            futures = [client.submit(deform_file, src, shared, dst, args.normals, key=f"ffd-{dst.name}-{uuid.uuid4().hex}",
                                     pure=False) for src, dst in jobs]
        else:
            mesh = pathlib.Path(args.mesh).resolve()
            futures = client.map(deform_variant, range(args.count), mesh_path=mesh, lattice=shared, out_dir=out_dir,
                                 sigma=args.sigma, seed=args.seed, pure=False)
        if not args.no_progress:
            with contextlib.redirect_stdout(sys.stderr):  # the bar on stderr, the JSON lines on stdout
                progress(futures)
                print()
        for result in client.gather(futures):
            print(json.dumps(result))
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


if __name__ == "__main__":
    main()
