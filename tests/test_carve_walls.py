"""The wall pass of relief carving: walls no raster finishes get waterlines at a Z step chosen
from the scallop asked for, and the raster's stepover stays the one the rest of the surface asks.

Checked on the built-in walled block (vertical walls, manifold3d booleans) and its height-map
twin (walls one 0.5 mm cell wide): the stepover against the closed form by hand, every wall-pass
point's distance to the design by brute force over every triangle, the wall's scallop measured by
ray-sphere intersection from the program's ball centres, the simulation, and rs274."""
import math

import numpy as np
import pytest

import rs274
from kezuri import post as posts
from kezuri.toolpath.operations.carve import carve, carve_samples
from kezuri.toolpath import simulate as sim
from kezuri.toolpath.ir.program import FEED

R = 1.5                  # the default finishing ball's radius
H = 0.02                 # the default scallop
FLAT = 2 * math.sqrt(H * (2 * R - H))          # a ball's stepover on level ground (and its Z step on a vertical wall)
TILT = math.radians(carve_samples.BLOCK["tilt_deg"])
TOL = carve.CarveSettings().tolerance                 # mm a path may stand off the dropped tool between points
TODAY_S = 1795.1         # the walls sample's cycle time before the wall pass (0bdb292: raster 0.232 mm + cleanup)


@pytest.fixture(scope="module")
def block():
    v, f = carve_samples.vertical_block()
    return v, f, carve.plan(v, f, carve.CarveSettings(rough=False))


def point_triangle_distance(points, tri):
    """Distance from each point (n, 3) to the nearest of the triangles (m, 3, 3), by hand: the
    plane where the foot falls inside, else the nearest edge."""
    best = np.full(len(points), np.inf)
    for start in range(0, len(tri), 64):
        t = tri[start:start + 64]
        a, b, c = t[:, 0], t[:, 1], t[:, 2]
        n = np.cross(b - a, c - a)
        n = n / np.linalg.norm(n, axis=1)[:, None]
        p = points[:, None, :]
        height = np.einsum("pmj,mj->pm", p - a, n)
        foot = p - height[..., None] * n
        inside = np.ones(height.shape, bool)
        for u, w in ((a, b), (b, c), (c, a)):
            inside &= np.einsum("pmj,mj->pm", np.cross(w - u, foot - u), n) >= 0
        d = np.where(inside, np.abs(height), np.inf)
        for u, w in ((a, b), (b, c), (c, a)):
            e = w - u
            s = np.clip(np.einsum("pmj,mj->pm", p - u, e) / np.einsum("mj,mj->m", e, e), 0, 1)
            d = np.minimum(d, np.linalg.norm(p - (u + s[..., None] * e), axis=2))
        best = np.minimum(best, d.min(axis=1))
    return best


def test_the_raster_keeps_the_stepover_of_the_sloped_top(block):
    v, f, result = block
    expected = 0.95 * FLAT * math.cos(TILT)           # no convex bend between faces the raster finishes
    assert result.stepover == pytest.approx(expected, rel=1e-5)     # (manifold3d's vertices are float32-exact)
    assert result.raster_slope_deg == pytest.approx(6.0, abs=1e-4)
    # the height-map twin's 87-degree walls: the old rule capped them at Max Slope (60 degrees)
    vh, fh = carve_samples.walled_block()
    twin = carve.plan(vh, fh, carve.CarveSettings(rough=False, steep_cleanup=False))
    assert twin.stepover == pytest.approx(expected, rel=1e-6)        # (a bend of 25 km between its facets)
    assert twin.stepover > 1.9 * 0.95 * FLAT * math.cos(math.radians(60.0))
    assert [op.name for op in twin.program.operations] == ["finishing", "wall pass"]


def test_the_wall_pass_steps_down_the_walls_at_the_scallop_asked(block):
    v, f, result = block
    assert [op.name for op in result.program.operations] == ["finishing", "wall pass"]
    walls = result.walls
    assert walls.shallowest_deg == pytest.approx(90.0, abs=1e-6)
    assert walls.z_step == pytest.approx(0.95 * FLAT, rel=1e-9)
    levels = np.array(walls.levels)
    assert levels[0] == pytest.approx(0.0 - R) and levels[-1] == pytest.approx(carve_samples.BLOCK["floor"])
    assert np.diff(levels).max() < 0 and -np.diff(levels).max() <= walls.z_step + 1e-9
    # the cusp between two ball contacts dz apart on a vertical wall
    step = -np.diff(levels).max()
    assert R - math.sqrt(R * R - step * step / 4) <= H
    op = result.program.operations[1]
    cutting = op.xyz[op.kind == FEED]
    assert set(np.round(cutting[:, 2], 6)) >= set(np.round(levels, 6))


def test_no_wall_pass_point_comes_nearer_the_design_than_the_ball(block):
    v, f, result = block
    op = result.program.operations[1]
    xyz = op.xyz
    feeds = np.flatnonzero(op.kind[1:] == FEED) + 1
    ends = xyz[feeds]
    mids = 0.5 * (xyz[feeds - 1] + xyz[feeds])
    centres = np.vstack([ends, mids]) + [0.0, 0.0, R]
    distance = point_triangle_distance(centres, v[f])
    # 0 gouges: no ball centre inside the design grown by r, but for the path's tolerance (a chord's sag)
    assert distance[:len(ends)].min() >= R - 1e-6
    assert distance.min() >= R - TOL
    # and the contours touch the walls: most centres stand within 1 um of the ball's radius
    assert np.mean(distance[:len(ends)] < R + 1e-3) > 0.9


def test_the_wall_scallop_measured_along_its_normal(block):
    v, f, result = block
    hx, hy = carve_samples.BLOCK["half"]
    x_wall = hx + carve_samples.BLOCK["corner"]       # the block's +x wall, a plane x = 28
    ys = np.arange(-5.0, 5.0001, 1.0)
    zs = np.arange(carve_samples.BLOCK["floor"] + R + 0.01, math.tan(TILT) * (-5 - 18) - 0.05, 0.005)
    # ball centres of every feed move near the wall, sampled 10 um apart
    found = []
    for op in result.program.operations:
        xyz = op.xyz
        for k in np.flatnonzero(op.kind[1:] == FEED) + 1:
            a, b = xyz[k - 1], xyz[k]
            if max(a[0], b[0]) < x_wall or min(a[0], b[0]) > x_wall + R + 0.1 or max(a[1], b[1]) < -5 - R \
                    or min(a[1], b[1]) > 5 + R:
                continue
            n = max(1, math.ceil(np.linalg.norm(b - a) / 0.01))
            found.append(a + np.outer(np.linspace(0, 1, n + 1), b - a))
    centres = np.vstack(found) + [0.0, 0.0, R]
    # material left along +x: the distance to the first ball the ray from the wall point enters
    left = []
    for y in ys:
        near = centres[np.abs(centres[:, 1] - y) <= R]
        p = np.column_stack([np.full(len(zs), x_wall), np.full(len(zs), y), zs])
        w = near[None, :, :] - p[:, None, :]
        bx = w[..., 0]
        disc = bx * bx - (np.einsum("pcj,pcj->pc", w, w) - R * R)
        left.append(np.where(disc >= 0, bx - np.sqrt(np.maximum(disc, 0)), np.inf).min(axis=1))
    left = np.concatenate(left)
    assert left.min() >= -TOL                         # nothing cut into the wall (but for the path's tolerance)
    assert left.max() <= H                            # the scallop asked, measured
    assert left.max() > 0.5 * H                       # (and it is a real scallop, not an empty test)


def test_the_simulation_finds_no_gouge_and_rs274_runs_it(block):
    from types import SimpleNamespace
    v, f, result = block
    design = SimpleNamespace(vertices=v, faces=f)
    simulated = sim.simulate(result.program, result.stock, design=design, cell=0.1)
    assert [x.message for x in simulated.findings] == []
    if rs274.available():
        writer = posts.create(("milling",), "linuxcnc")
        text = writer.to_text(result.program)
        kinds, points, _ = rs274.motion_endpoints(rs274.run(text))
        # the wall pass as the post writes it: its rounded stretches as arcs (tests/test_arcs_out.py
        # checks them against the polylines), every arc's end one of the planned points
        walls = writer.arcs_out(result.program).operations[1]
        assert "cw" in kinds or "ccw" in kinds
        found = 0
        for p in walls.xyz[::11]:
            while found < len(points) and not np.allclose(points[found], p, atol=6e-4):
                found += 1
            assert found < len(points), f"rs274 never reached {p}"


def test_the_walls_sample_is_far_faster_than_before():
    v, f = carve_samples.walled_block()
    result = carve.plan(v, f, carve.CarveSettings())
    assert result.walls is not None and result.walls.operation is not None
    assert result.program.cycle_time() < 0.75 * TODAY_S


def test_wall_pass_off_leaves_the_walls_with_a_warning(block):
    v, f, _ = block
    result = carve.plan(v, f, carve.CarveSettings(rough=False, wall_pass=False))
    assert [op.name for op in result.program.operations] == ["finishing"]
    assert any("Wall Pass is off" in w for w in result.warnings)


def test_batch_reports_the_wall_pass(tmp_path):
    import json
    import os
    import subprocess
    import sys
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    done = subprocess.run([sys.executable, os.path.join(root, "batch.py"), "carve", "--sample", "block", "--post",
                           "linuxcnc", "--out", str(tmp_path)], capture_output=True, text=True, timeout=600, cwd=root)
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((tmp_path / "report.json").read_text())
    walls = report["wall_pass"]
    summary = next(op for op in report["operations"] if op["name"] == "wall pass")
    assert walls["on"] and walls["moves"] == summary["moves"] > 1000
    assert walls["cycle_time_s"] == summary["cycle_time_s"] > 0
    assert walls["z_step_mm"] == pytest.approx(0.95 * FLAT, abs=1e-5) and walls["levels"] == 20
    step = walls["z_step_mm"]
    assert walls["scallop_closed_form_mm"] == pytest.approx(R - math.sqrt(R * R - step * step / 4), abs=1e-5)
    assert walls["scallop_closed_form_mm"] <= report["scallop"]["asked_mm"]
    assert report["gate"]["findings"] == []
    assert report["stepover_mm"] == pytest.approx(0.95 * FLAT * math.cos(TILT), rel=1e-4)
    if rs274.available():
        text = (tmp_path / "carve.ngc").read_text()
        kinds, points, _ = rs274.motion_endpoints(rs274.run(text))
        # the last wall level's tip height is reached by the interpreter
        assert np.any(np.abs(points[:, 2] - walls["tip_z_range_mm"][1]) < 1e-3)
