# The examples run and do what they say (examples/python/).
import os
import re
import subprocess
import sys

import freeform as ff
from conftest import ROOT

EXAMPLES = ROOT / "examples" / "python"


def run(script, *args, **extra_env):
    env = dict(os.environ, MPLBACKEND="Agg", **extra_env)
    r = subprocess.run([sys.executable, str(EXAMPLES / script), *map(str, args)], capture_output=True, text=True,
                       env=env, timeout=60)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_deform_mesh(tmp_path):
    out = tmp_path / "deformed.obj"
    run("deform_mesh.py", ROOT / "data" / "meshes" / "sphere.obj", out)
    before = ff.MeshFile.read(str(ROOT / "data" / "meshes" / "sphere.obj"))
    after = ff.MeshFile.read(str(out))
    assert after.positions.shape == before.positions.shape
    assert after.positions[:, 2].max() > before.positions[:, 2].max() + 0.1  # the top was lifted
    # the lattice it saved reproduces the file's positions
    lat = ff.Lattice.load(str(out.with_suffix(".lattice.json")))
    assert abs(lat.deform(before.positions) - after.positions).max() < 1e-12


def test_spline_plot(tmp_path):
    text = run("spline_plot.py", tmp_path / "spline.png")
    assert text.count(": C2 G2") == 4
    assert (tmp_path / "spline.png").exists() or "plot skipped" in text


def test_shape_optimisation_reaches_the_target():
    text = run("shape_optimisation.py")
    m = re.search(r"final volume ([0-9.]+) \(target ([0-9.]+)\)", text)
    assert m and abs(float(m.group(1)) - float(m.group(2))) < 1e-5
    assert "certified injective" in text


def test_examples_write_outside_the_source_tree_by_default(tmp_path):
    # issue 26: deform_mesh.py and spline_plot.py wrote into the source tree's build/ by default
    run("deform_mesh.py", TMPDIR=str(tmp_path))
    assert (tmp_path / "freeform-examples" / "deformed-sphere.obj").exists()
    assert (tmp_path / "freeform-examples" / "deformed-sphere.lattice.json").exists()
    text = run("spline_plot.py", TMPDIR=str(tmp_path))
    assert (tmp_path / "freeform-examples" / "spline.png").exists() or "plot skipped" in text
    for script in ("deform_mesh.py", "spline_plot.py", "batch_ffd_dask.py"):
        assert '"build"' not in (EXAMPLES / script).read_text()
