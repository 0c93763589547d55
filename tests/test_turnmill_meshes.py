"""``batch.py turnmill --mesh FILE.stl`` runs to the end on real part meshes: a box, a hexagonal
bar, a spool whose flanges overhang its core, and a sculpted part (a revolved profile displaced
by smooth noise).  Each run must write the NC programs, the report and both pictures; LinuxCNC's
rs274 must accept the LinuxCNC programs, and the simulation of the program on the bar must find
no gouge and no rapid through the stock.  Batch's entry point is called in-process (Blender loaded
once), each part under a time limit."""
import contextlib
import importlib.util
import io
import json
import os

import numpy as np
import pytest
import trimesh

bpy = pytest.importorskip("bpy")
import rs274  # noqa: E402
from test_hostile import time_limit  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PART_SECONDS = 600


def load_batch():
    spec = importlib.util.spec_from_file_location("kezuri_batch_meshes", os.path.join(ROOT, "batch.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def outward(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    assert mesh.is_watertight, "the test part must be closed"
    if mesh.volume < 0:
        mesh.invert()
    return mesh


def box():
    return outward(trimesh.creation.box(extents=(40, 40, 40),
                                        transform=trimesh.transformations.translation_matrix((0, 0, -20))))


def hex_bar():
    return outward(trimesh.creation.cylinder(radius=15, height=60, sections=6,
                                             transform=trimesh.transformations.translation_matrix((0, 0, -30))))


def revolved(profile, sections=64) -> trimesh.Trimesh:
    """The closed solid of revolution of a (radius, z) profile running from the axis back to it."""
    return outward(trimesh.creation.revolve(np.asarray(profile, float), sections=sections))


SPOOL = [(0, -40), (20, -40), (20, -35), (9, -35), (9, -5), (20, -5), (20, 0), (0, 0)]


def spool():
    """Flanges of radius 20 at both ends, a core of radius 9 between: the inner flange faces look
    along Z at the core, and overhang it."""
    return revolved(SPOOL)


def sculpted():
    """A vase-like revolved profile; every vertex moved out along its radius by a smooth noise
    (a few random sinusoids in angle and height), so no two faces lie alike."""
    z = np.linspace(-50, 0, 26)
    radius = 14 + 5 * np.sin((z + 50) / 50 * np.pi) ** 2
    mesh = revolved([(0, -50), *zip(radius, z), (0, 0)], sections=72)
    rng = np.random.default_rng(18)
    v = mesh.vertices.copy()
    theta, height = np.arctan2(v[:, 1], v[:, 0]), v[:, 2]
    noise = sum(a * np.sin(k * theta + p) * np.cos(height / w + q)
                for a, k, p, w, q in zip(rng.uniform(0.2, 0.6, 4), (2, 3, 5, 7), rng.uniform(0, 6, 4),
                                         rng.uniform(4, 9, 4), rng.uniform(0, 6, 4)))
    rho = np.hypot(v[:, 0], v[:, 1])
    on_axis = rho < 1e-9
    scale = np.where(on_axis, 1.0, (rho + noise) / np.where(on_axis, 1.0, rho))
    v[:, :2] *= scale[:, None]
    return outward(trimesh.Trimesh(v, mesh.faces, process=False))


PARTS = {"box": box, "hex-bar": hex_bar, "spool": spool, "sculpted": sculpted}
# The spool was a known failure here (radial roughing cut the flange rim by 0.027 mm, the gate
# refused it) until runs got no two centres more than a stepover apart (test_turnmill_flange.py).
KNOWN: dict = {}


@pytest.fixture(scope="module")
def batch():
    return load_batch()


@pytest.mark.parametrize("name", [pytest.param(name, marks=pytest.mark.xfail(strict=True, reason=KNOWN[name]))
                                  if name in KNOWN else name for name in PARTS])
def test_turnmill_mesh_runs_to_the_end(batch, name, tmp_path):
    stl = tmp_path / f"{name}.stl"
    PARTS[name]().export(stl)
    out = tmp_path / "out"
    stderr = io.StringIO()
    with time_limit(PART_SECONDS), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        status = batch.main(["batch.py", "turnmill", "--mesh", str(stl), "--out", str(out)])
    assert status == 0, stderr.getvalue()[-3000:]
    assert "Traceback" not in stderr.getvalue()
    report = json.loads((out / "report.json").read_text())
    programs = [path for path in report["files"] if path.endswith(".ngc")]
    assert programs and all(os.path.getsize(path) > 1000 for path in report["files"])
    if rs274.available():
        for path in programs:
            calls = rs274.run(open(path).read())
            assert sum(1 for call, _ in calls if call in {"STRAIGHT_FEED", "ARC_FEED"}) > 50, path
    simulation = report["simulation"]
    assert simulation["gouges"] == [] and simulation["max_gouge_mm"] == 0, simulation["gouges"][:3]
    assert simulation["rapid_collisions"] == []
    assert simulation["removed_volume_mm3"] > 0
    assert report["operations"] and all(op["moves"] > 0 for op in report["operations"] if "moves" in op)
    assert os.path.getsize(report["preview"]) > 10000 and os.path.getsize(report["toolpaths_preview"]) > 10000
