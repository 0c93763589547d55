"""V-carving from the shell, run in-process as a user runs it: the sample job
``samples/jobs/vcarve-sign.toml`` (Latin and kanji text, max depth 3 mm, a second tool for the
flat), ``batch.py vcarve --text ... --font ...`` and ``batch.py vcarve --svg FILE``; the programs
read back by LinuxCNC's rs274 and the controller-rules reader; bad entries refused by name."""
import json
import os

import numpy as np
import pytest

pytest.importorskip("bpy")
import controller_rules  # noqa: E402
import rs274  # noqa: E402
from test_batch_job import JOBS, run  # noqa: E402

SVG = """<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="30mm" viewBox="0 0 60 30">
  <rect x="5" y="5" width="50" height="8" fill="none" stroke="#000"/>
  <path d="M 10 18 L 30 28 L 50 18 Z" fill="none" stroke="#000"/>
</svg>
"""


def report_of(out):
    return json.loads(open(os.path.join(out, "report.json")).read())


@pytest.fixture(scope="module")
def sign_job():
    status, message, out = run("job", os.path.join(JOBS, "vcarve-sign.toml"))
    assert status == 0, message[-2000:]
    return out, report_of(out)


def test_the_sign_job_passes_the_gate_carved_to_its_max_depth(sign_job):
    """The sample sign at 3 mm max depth: its strokes (28 mm Latin, 60 mm kanji) are narrower than
    2 x 3 tan 30 deg = 3.46 mm but for slivers, so no clearing pass is needed and no letter is too
    fine; the slivers the 1 mm end mill cannot reach are reported with their ridge height.  (The
    clearing before the V-bit: test_vcarve.py's max-depth cases, test_blender_vcarve_panels.py.)"""
    out, report = sign_job
    assert report["gate"]["findings"] == [] and not report["gate"]["overridden"]
    assert [op["kind"] for op in report["job_operations"]] == ["vcarve", "vcarve"]
    assert report["job_operations"][0]["operations"] == ["latin"]
    assert not any(op.get("too_fine") for op in report["job_operations"])
    text = open(report["files"][0]).read()
    assert controller_rules.check(text, "linuxcnc") == []
    if rs274.available():
        kinds, points, _ = rs274.motion_endpoints(rs274.run(text, tools=(3, 4)))
        assert points[:, 2].min() == pytest.approx(-3.0, abs=1e-4)          # the max depth, not deeper
        # the kanji (below Y -5) and the Latin (above) both cut, within the 240 x 110 board
        cut = points[np.array(kinds) != "rapid"]
        low = cut[cut[:, 2] < -0.5]
        assert (low[:, 1] < -5).any() and (low[:, 1] > 5).any()
        assert np.abs(low[:, 0]).max() < 120 and np.abs(low[:, 1]).max() < 55


def test_batch_vcarve_text_in_a_japanese_font(tmp_path):
    status, message, out = run("vcarve", "--text", "削り", "--font", "Noto Sans CJK Regular.woff2",
                               "--text-size", "15", "--set", "angle=90", "--post", "linuxcnc", out=str(tmp_path / "out"))
    assert status == 0, message[-2000:]
    report = report_of(out)
    assert report["gate"]["findings"] == []
    assert 'text = { body = "削り", size = 15.0, font = "Noto Sans CJK Regular.woff2"' in report["job_file_text"]
    text = open(report["files"][0]).read()
    assert controller_rules.check(text, "linuxcnc") == []


def test_batch_vcarve_svg_with_a_max_depth(tmp_path):
    path = tmp_path / "sign.svg"
    path.write_text(SVG)
    status, message, out = run("vcarve", "--svg", str(path), "--set", "max_depth=2.0", "--post", "grbl",
                               out=str(tmp_path / "out"))
    assert status == 0, message[-2000:]
    report = report_of(out)
    assert report["gate"]["findings"] == []
    text = open(report["files"][0]).read()
    assert controller_rules.check(text, "grbl") == []


@pytest.mark.parametrize("argv, message", [
    (("--text", "A", "--font", "no-such-font.ttf"), r"text.font = 'no-such-font.ttf': no such font file"),
    (("--text", "   "), r"give the text to carve"),
    (("--text", "A", "--set", "angle=200"), r"tip angle must be from 1 to 179"),
    (("--text", "A", "--set", "depth=2"), r"settings.depth is not a V-carve setting"),
    (("--text", "Wide", "--text-size", "200"), r"set max_depth"),
])
def test_bad_vcarve_commands_are_refused_by_name(tmp_path, argv, message):
    import re
    status, stderr, out = run("vcarve", *argv, out=str(tmp_path / "out"))
    assert status != 0
    assert re.search(message, stderr), stderr[-2000:]
    assert not os.path.exists(os.path.join(out, "vcarve.ngc"))


def test_a_vcarve_row_of_the_job_list_carves_the_panels_letters(empty_scene):
    """The CAM tab's job list handles the new kind by itself: a V-carve row takes the letters and
    the plate, plans with its settings (JSON) and passes the gate."""
    import bpy

    from kezuri.operators import samples

    samples.name_plate(empty_scene)
    empty_scene.kezuri.machine.post = "linuxcnc"
    assert bpy.ops.kezuri.job_add(kind="vcarve") == {"FINISHED"}
    row = empty_scene.kezuri.job_list.rows[0]
    assert {item.slot: item.object.name for item in row.objects} == {"region": "Letters", "plate": "Plate"}
    row.settings = json.dumps({"angle": 90.0, "diameter": 12.7})
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    assert row.tools.startswith("T") and row.state == "PLANNED"


def test_mesh_faces_are_a_region(empty_scene):
    """A mesh object's faces (seen from above, in the plate's frame) are carved to their outline."""
    import bpy

    from kezuri.operators import samples
    from kezuri.operators import vcarve as shell
    from kezuri.operators.jobentry import JobEntry
    from kezuri.toolpath.engines import region as rg
    from kezuri.toolpath.job import Job, plan_job
    from kezuri.toolpath.simulate import simulate

    samples.name_plate(empty_scene)
    mesh = bpy.data.meshes.new("Badge")
    mesh.from_pydata([(-20, -10, 0.05), (20, -10, 0.05), (0, 15, 0.05), (0, -30, 0.05)], [], [(0, 1, 2), (1, 0, 3)])
    badge = bpy.data.objects.new("Badge", mesh)
    empty_scene.collection.objects.link(badge)
    entry = JobEntry("badge", "vcarve", True, {"region": badge}, {"angle": 90.0, "max_depth": 3.0}, {},
                     "operation 'badge'")
    depsgraph = bpy.context.evaluated_depsgraph_get()
    operation, setup, _ = shell.job_operation(empty_scene, depsgraph, entry, "linuxcnc")
    loops = operation.geometry.loops
    assert len(loops) == 1 and len(loops[0]) == 4                # the two triangles merged: a kite
    planned = plan_job(Job(setup, (operation,)))
    program, stock, limits = planned.simulation()
    sim = simulate(program, stock, cell=0.05, **limits)
    assert sim.findings == []
    hf = sim.heightfield
    x, y = np.meshgrid(hf.x(), hf.y(), indexing="ij")
    xy = np.column_stack([x.ravel(), y.ravel()])
    depth = (hf.top - np.maximum(hf.heights, hf.bottom)).ravel()
    kite = rg.from_loops(loops)
    inner = rg.contains_points(rg.offset(kite, -0.02), xy)
    outer = ~rg.contains_points(rg.offset(kite, 0.02), xy)
    assert not (inner & (depth <= 1e-6)).any() and not (outer & (depth > 1e-6)).any()
    assert depth.max() == pytest.approx(3.0, abs=1e-3)


@pytest.mark.parametrize("inlay, operations", [("female", ["vcarve"]), ("male", ["vcarve clearing", "vcarve"])])
def test_batch_inlay_halves_pass_the_gate(tmp_path, inlay, operations):
    status, message, out = run("vcarve", "--text", "欅", "--font", "Noto Sans CJK Regular.woff2", "--text-size", "40",
                               "--set", f"inlay={inlay}", "--set", "max_depth=3.0", "--set", "start_depth=1.5",
                               "--set", "glue_gap=0.1", "--post", "linuxcnc", out=str(tmp_path / "out"))
    assert status == 0, message[-2000:]
    report = report_of(out)
    assert report["gate"]["findings"] == []
    assert report["job_operations"][0]["operations"] == operations
    assert controller_rules.check(open(report["files"][0]).read(), "linuxcnc") == []
