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
import controller_rules  # noqa: E402
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


def sphere():
    """A ball of radius 20 as 1,280 flat faces: every edge a convex crease the ball rounds."""
    return outward(trimesh.creation.icosphere(3, 20))


PARTS = {"box": box, "hex-bar": hex_bar, "spool": spool, "sculpted": sculpted, "sphere": sphere}
# The spool was a known failure here (radial roughing cut the flange rim by 0.027 mm, the gate
# refused it) until runs got no two centres more than a stepover apart (test_turnmill_flange.py);
# the faceted sphere (axial finishing cut its edges by 0.045 mm, then by 0.007 mm) until chords
# that dip towards the part were halved (test_every_chord_keeps_the_ball_off_a_faceted_sphere).
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
    part = np.asarray(trimesh.load(stl, force="mesh").vertices)
    radius, end_z = float(np.hypot(part[:, 0], part[:, 1]).max()), float(part[:, 2].max())
    for path in report["files"]:
        control = {".nc": "turnmill-xzc", ".ngc": "turnmill-linuxcnc"}.get(os.path.splitext(path)[1])
        if control:      # the frames stay clear of the bar (the lathe's frame rule)
            assert controller_rules.check_turret_frames(open(path).read(), control, radius, end_z) == [], path
    simulation = report["simulation"]
    assert simulation["gouges"] == [] and simulation["max_gouge_mm"] == 0, simulation["gouges"][:3]
    assert simulation["rapid_collisions"] == []
    assert simulation["removed_volume_mm3"] > 0
    assert report["operations"] and all(op["moves"] > 0 for op in report["operations"] if "moves" in op)
    assert os.path.getsize(report["preview"]) > 10000 and os.path.getsize(report["toolpaths_preview"]) > 10000


def point_triangle_distance(p, a, b, c):
    """Distance from each point p[i] to its triangle a[i], b[i], c[i] (rows paired; arrays
    broadcast): the closest point by the seven Voronoi regions of the triangle (Ericson,
    Real-Time Collision Detection 5.1.5), written here for the test."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = (ab * ap).sum(-1), (ac * ap).sum(-1)
    bp, cp = p - b, p - c
    d3, d4 = (ab * bp).sum(-1), (ac * bp).sum(-1)
    d5, d6 = (ab * cp).sum(-1), (ac * cp).sum(-1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = 1.0 / (va + vb + vc)
        face = a + ab * (vb * denom)[..., None] + ac * (vc * denom)[..., None]
        t_ab = np.clip(d1 / (d1 - d3), 0, 1)
        t_ac = np.clip(d2 / (d2 - d6), 0, 1)
        t_bc = np.clip((d4 - d3) / ((d4 - d3) + (d5 - d6)), 0, 1)
    inside = (va >= 0) & (vb >= 0) & (vc >= 0)
    best = np.where(inside, np.nan_to_num(np.linalg.norm(p - face, axis=-1), nan=np.inf), np.inf)
    for point in (a, b, c, a + ab * t_ab[..., None], a + ac * t_ac[..., None], b + (c - b) * t_bc[..., None]):
        best = np.minimum(best, np.nan_to_num(np.linalg.norm(p - point, axis=-1), nan=np.inf))
    return best


def distances_within(points, a, b, c, reach):
    """Distance from each point to the nearest triangle, exact where it is below ``reach`` (else
    at least ``reach``): a triangle whose centroid lies further than ``reach`` plus the triangle's
    own radius from the point cannot come nearer, so only the others are measured, all of them."""
    centroid = (a + b + c) / 3
    size = np.max([np.linalg.norm(x - centroid, axis=1) for x in (a, b, c)], axis=0)
    best = np.full(len(points), np.inf)
    for start in range(0, len(points), 4000):
        chunk = points[start:start + 4000]
        bound = np.linalg.norm(chunk[:, None, :] - centroid[None], axis=2) - size[None]
        point, tri = np.nonzero(bound < reach)
        found = np.full(len(chunk), np.inf)
        np.minimum.at(found, point, point_triangle_distance(chunk[point], a[tri], b[tri], c[tri]))
        best[start:start + 4000] = found
    return best


def test_every_chord_keeps_the_ball_off_a_faceted_sphere():
    """Each move of every operation on the faceted sphere, followed as the control moves (X, Z and
    C interpolated linearly), keeps the 6 mm ball's centre at least r - 1 micron from every face
    (the gate reports a cut 1 micron deep): measured by brute force over all 1,280 faces."""
    from kezuri.toolpath.ir import kinematics
    from kezuri.toolpath.operations.turnmill import turnmill
    from kezuri.toolpath.ir.program import RAPID
    mesh = sphere()
    v, f = np.asarray(mesh.vertices), np.asarray(mesh.faces)
    plan = turnmill.plan(v, f, turnmill.Stock(20.0, -20.0, 20.0))
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    checked = []
    for op in plan.program.operations:
        r = op.tool.diameter / 2
        t = np.linspace(0.0, 1.0, 6)[1:, None]
        xyz, turn = op.xyz, np.asarray(op.rotary["c"], float)
        cutting = np.flatnonzero(op.kind[1:] != RAPID) + 1      # the feed moves (a rapid retracts clear)
        machine = (xyz[cutting - 1, None, :] * (1 - t) + xyz[cutting, None, :] * t).reshape(-1, 3)
        angle = (turn[cutting - 1, None] * (1 - t[:, 0]) + turn[cutting, None] * t[:, 0]).reshape(-1)
        tips = kinematics.machine_to_part(machine, angle)
        centres = tips + (r * np.array([0.0, 0.0, 1.0]) if op.direction == "axial" else
                          r * np.column_stack([tips[:, :2] / np.linalg.norm(tips[:, :2], axis=1)[:, None],
                                               np.zeros(len(tips))]))
        # the faceted sphere lies inside the true one: a centre r or more from that is r from every face
        reach = np.linalg.norm(centres, axis=1)
        if op.name.endswith("finishing"):
            assert np.mean(reach < 20 + r + 0.5) > 0.5, op.name           # finishing runs on the surface
        near = reach < 20 + r
        if not near.any():
            continue
        gap = distances_within(centres[near], a, b, c, r)
        assert gap.min() >= r - 1e-3, (op.name, gap.min())
        checked.append(op.name)
    assert {"radial finishing", "axial finishing"} <= set(checked)
