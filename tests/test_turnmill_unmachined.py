"""Nothing skipped in silence: the faces neither turn-mill tool reaches are named in the plan, the
NC header, report.json, batch's stderr and the toolpath picture.

The test part is a hex bar with an 8 mm cross hole, built here with manifold3d: the flats are
radial faces and get paths; the hole's wall faces neither tool (its normals point at the hole's
axis, across the radial direction, and the +Z rays from its lower half hit its upper half).  Its
numbers are checked against the closed form of the faceted hole: a regular n-gon of radius r,
perimeter 2 n r sin(pi / n), swept across the bar from flat to flat (the across-flats width).
"""
import json
import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest
import trimesh
from manifold3d import Manifold

from kezuri.post import turnmill_xzc
from kezuri.toolpath.pictures import picture_jobs
from kezuri.toolpath.operations.turnmill import turnmill as tm

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
AF = 30.0              # across flats
LENGTH = 40.0
HOLE_D = 8.0
HOLE_Z = -20.0
SEGMENTS = 32          # the hole's polygon (a multiple of 4: vertices at 0, 90, 180, 270 degrees)
ORANGE = (250, 150, 20)


def hex_bar_with_hole():
    """Vertices, faces and stock of the hex bar (flats at y = +-AF/2), end face at z = 0, and the
    cross hole along Y at z = HOLE_Z."""
    corner = AF / math.sqrt(3.0)
    bar = Manifold.cylinder(LENGTH, corner, corner, 6).translate((0.0, 0.0, -LENGTH))
    hole = (Manifold.cylinder(4 * corner, HOLE_D / 2, HOLE_D / 2, SEGMENTS).translate((0.0, 0.0, -2 * corner))
            .rotate((90.0, 0.0, 0.0)).translate((0.0, 0.0, HOLE_Z)))
    mesh = (bar - hole).to_mesh64()
    v = np.array(mesh.vert_properties[:, :3], float)
    f = np.array(mesh.tri_verts, np.int64)
    return v, f, tm.Stock(float(np.hypot(v[:, 0], v[:, 1]).max()), -LENGTH, 0.0)


def hole_area() -> float:
    r = HOLE_D / 2
    return 2 * SEGMENTS * r * math.sin(math.pi / SEGMENTS) * AF


def on_hole_wall(v, f) -> np.ndarray:
    """Faces whose three corners lie on the hole's cylinder (distance HOLE_D/2 from its axis)."""
    tri = v[f]
    return np.all(np.abs(np.hypot(tri[..., 0], tri[..., 2] - HOLE_Z) - HOLE_D / 2) < 1e-6, axis=1)


@pytest.fixture(scope="module")
def hex_plan():
    v, f, stock = hex_bar_with_hole()
    return v, f, stock, tm.plan(v, f, stock, name="hex bar")


def test_the_hole_is_named_with_its_closed_form_numbers(hex_plan):
    v, f, stock, plan = hex_plan
    wall = np.flatnonzero(on_hole_wall(v, f))
    assert len(wall) == 2 * SEGMENTS
    assert np.all(plan.labels[wall] == tm.NEITHER)
    assert len(plan.skipped) == 1
    hole = plan.skipped[0]
    assert np.array_equal(np.sort(hole.faces), wall)
    assert hole.area == pytest.approx(hole_area(), rel=1e-9)            # 752.77 mm2
    r = HOLE_D / 2
    np.testing.assert_allclose(hole.lo, (-r, -AF / 2, HOLE_Z - r), atol=1e-9)
    np.testing.assert_allclose(hole.hi, (r, AF / 2, HOLE_Z + r), atol=1e-9)
    np.testing.assert_allclose(hole.radius, (AF / 2, math.hypot(AF / 2, r)), atol=1e-9)
    # the flats are planned: radial operations, and no flat face among the skipped
    assert {op.direction for op in plan.program.operations} == {"radial"}
    assert not np.isin(plan.radial_faces, wall).any()


def test_the_nc_header_names_the_hole(hex_plan):
    text = turnmill_xzc.TurnMillXZCPost().to_text(hex_plan[3].program)
    header = text[:text.index("G21")]
    notes = re.findall(r"\(NOTE: NOT MACHINED[^)]*\)", header)
    assert len(notes) == 2, notes
    total = re.search(r"NOT MACHINED: (\d+) FACES, ([0-9.]+) MM2 IN 1 FEATURES", notes[0])
    assert int(total.group(1)) == 2 * SEGMENTS
    assert float(total.group(2)) == pytest.approx(hole_area(), abs=0.05)
    where = re.search(r"Z ([-0-9.]+) TO ([-0-9.]+), X ([-0-9.]+) TO ([-0-9.]+), Y ([-0-9.]+) TO ([-0-9.]+)", notes[1])
    assert [float(g) for g in where.groups()] == [HOLE_Z - 4, HOLE_Z + 4, -4, 4, -AF / 2, AF / 2]
    assert max(len(line) for line in text.splitlines()) < 200


def test_a_face_left_out_of_the_selection_is_not_reported():
    v, f, stock = hex_bar_with_hole()
    plan = tm.plan(v, f, stock, reported=~on_hole_wall(v, f))
    assert plan.skipped == []
    assert not any("NOT MACHINED" in note.upper() for note in plan.program.notes)


def test_walls_the_ball_sweeps_are_not_reported():
    """The sample's NEITHER faces (groove shoulders, pocket walls) are cut by the ball's side as it
    runs along their floors: none of them is reported (no finding users learn to ignore)."""
    v, f, stock = tm.sample_part()
    plan = tm.plan(v, f, stock)
    assert np.count_nonzero(plan.labels == tm.NEITHER) > 700
    assert plan.skipped == []


def test_the_picture_draws_the_hole_in_its_own_colour_with_a_legend_entry(hex_plan):
    v, f, stock, plan = hex_plan
    ids = plan.skipped_faces()
    plain = picture_jobs.toolpath_picture(plan.program.operations, stock, [(v, f, picture_jobs.PART_COLOUR)])
    marked = picture_jobs.toolpath_picture(plan.program.operations, stock, [(v, f, picture_jobs.PART_COLOUR)],
                                           highlights=[(v, f[ids], ORANGE, "NOT MACHINED")])
    image, before = marked.image(), plain.image()
    legend = image[-picture_jobs.LEGEND:]
    assert np.all(legend == ORANGE, axis=2).sum() >= 28 * 5                # the swatch
    assert not np.all(before[-picture_jobs.LEGEND:] == ORANGE, axis=2).any()
    body = image[picture_jobs.HEADER:-picture_jobs.LEGEND].astype(float)
    # shaded orange: the colour times a shade, so R:G:B stays 250:150:20
    red, green, blue = body[..., 0], body[..., 1], body[..., 2]
    orange = (red > 60) & (np.abs(green / np.maximum(red, 1) - 0.6) < 0.02) & (np.abs(blue / np.maximum(red, 1) - 0.08) < 0.02)
    assert orange.sum() > 2000


def test_batch_names_the_hole_in_report_stderr_and_nc(tmp_path):
    v, f, _ = hex_bar_with_hole()
    stl = tmp_path / "hex.stl"
    trimesh.Trimesh(v, f, process=False).export(stl)
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, os.path.join(ROOT, "batch.py"), "turnmill", "--mesh", str(stl),
                          "--post", "xzc", "--out", str(out)], capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0, run.stderr
    report = json.loads((out / "report.json").read_text())
    missed = report["not_machined"]
    assert missed["faces"] == 2 * SEGMENTS
    assert missed["area_mm2"] == pytest.approx(hole_area(), abs=1e-3)
    assert missed["features"][0]["z"] == [HOLE_Z - 4, HOLE_Z + 4]
    assert "not machined: 64 faces, 752.8 mm2" in run.stderr
    assert any(w.startswith("not machined: 64 faces") for w in report["warnings"])
    assert "(NOTE: NOT MACHINED: 64 FACES, 752.8 MM2" in (out / "turnmill.nc").read_text()
    faces = [face["label"] for face in report["faces"]]
    assert faces.count("none") >= 2 * SEGMENTS
    # the program against the 0i-T's memory and block time, counted here from the text
    text = (out / "turnmill.nc").read_text()
    size_kb = len(text.encode()) / 1024
    short = 0
    inverse = False
    for line in text.splitlines():
        inverse = (inverse or " G93" in f" {line}") and not re.search(r"\bG9[48]\b", line)
        f = re.search(r"\bF([0-9.]+)", line)
        if inverse and f and line.startswith(("G01", "X", "Z", "C")) and 60000.0 / float(f.group(1)) < 7.5:
            short += 1
    assert short > 1000
    assert report["programs"]["xzc"] == {"size_kb": round(size_kb, 1), "memory_kb": 512.0, "short_blocks": short,
                                         "block_ms": 7.5}
    assert f"the turnmill-xzc program is {size_kb:,.1f} kB, larger than the 512 kB program memory" in run.stderr
    assert f"has {short:,} inverse-time blocks shorter than the 7.5 ms" in run.stderr
