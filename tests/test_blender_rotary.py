"""W2 in Blender and batch: pockets marked on objects, generate, export, the batch report."""
import json

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

import rs274  # noqa: E402
from kezuri.operators import panels, samples  # noqa: E402
from kezuri.operators import rotary as shell  # noqa: E402
from kezuri.toolpath.engines import region  # noqa: E402
from kezuri.toolpath.operations.rotary import rotary as core  # noqa: E402
from blender_helpers import draw_panel, run_batch  # noqa: E402




@pytest.fixture
def scene(empty_scene):
    scene = empty_scene
    samples.rotary_block(scene)
    return scene


def test_generate_shows_each_pocket_inside_its_outline(scene):
    assert bpy.ops.kezuri.rotary_generate() == {"FINISHED"}
    objects = {o.name: o for o in bpy.data.collections["Kezuri"].objects}
    block, pockets = core.sample_job()
    for pocket in pockets:
        obj = objects[f"Kezuri Rotary {pocket.name}"]
        points = shell.convert.curve_points(obj)
        cutting = points[points[:, 2] < -1e-6]
        outline = region.from_loops([pocket.outline])
        inside = region.contains_points(region.offset(outline, 0.01), cutting[:, :2])
        assert inside.all(), pocket.name
        assert cutting[:, 2].min() >= -pocket.depth - 1e-6


def test_rotary_export_passes_rs274(scene, tmp_path):
    path = tmp_path / "bento.ngc"
    assert bpy.ops.kezuri.rotary_export(filepath=str(path), post="linuxcnc") == {"FINISHED"}
    text = path.read_text()
    assert "G93" in text and "C" in text
    if rs274.available():
        kinds, points, rotary = rs274.motion_endpoints(rs274.run(text))
        assert np.all(points[:, 0] <= 1e-9)          # X only on the negative side of the centre
        assert np.max(np.abs(np.diff(rotary[:, 2]))) < 180


def test_pocket_settings_are_on_the_object_and_no_pockets_is_an_error(scene):
    for obj in scene.objects:
        obj.kezuri_pocket.enabled = False
    with pytest.raises(RuntimeError, match="no pockets"):
        bpy.ops.kezuri.rotary_generate()


def test_open_pocket_outline_is_refused(scene):
    curve = bpy.data.objects["peanut"].data
    curve.splines[0].use_cyclic_u = False
    with pytest.raises(RuntimeError, match="peanut.*open"):
        bpy.ops.kezuri.rotary_generate()


def test_mark_pocket_operator(scene):
    obj = bpy.data.objects["bowl"]
    obj.kezuri_pocket.enabled = False
    for o in scene.objects:
        o.select_set(o == obj)
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.kezuri.mark_pocket(enable=True) == {"FINISHED"}
    assert obj.kezuri_pocket.enabled


def test_rotary_panel_draws_pocket_settings_of_the_active_object(scene):
    bpy.context.view_layer.objects.active = bpy.data.objects["bowl"]
    layout = draw_panel(panels.KEZURI_PT_rotary, bpy.context)
    assert {"enabled", "depth", "wall_angle", "bottom", "sphere_radius", "post"} <= set(layout.props)
    assert {"kezuri.rotary_generate", "kezuri.rotary_export"} <= set(layout.operators)


def test_batch_rotary_report(tmp_path):
    done = run_batch("rotary", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["workflow"] == "rotary" and report["toolpath_seconds"] > 0
    assert sorted(p["name"] for p in report["pockets"]) == ["bowl", "peanut", "slanted tray"]
    for pocket in report["pockets"]:
        assert set(pocket) >= {"name", "bottom", "wall_angle_deg", "outline", "points", "max_gouge_mm", "scallop_mm",
                               "cycle_time_s"}
        assert pocket["max_gouge_mm"] == 0.0 and pocket["points"] > 100
    bottoms = {p["name"]: p["bottom"] for p in report["pockets"]}
    assert bottoms == {"bowl": "sphere", "peanut": "flat", "slanted tray": "flat"}
    # Same order of magnitude as the paper's 8 min 22 s for its three pockets.
    assert 4 * 60 < report["cycle_time_s"] < 16 * 60
    assert (tmp_path / "rotary.png").stat().st_size > 10_000
    if rs274.available():
        rs274.run((tmp_path / "rotary.ngc").read_text())
