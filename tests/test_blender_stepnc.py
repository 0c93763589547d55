"""W3 in Blender and batch: import ex1, reorder the workplan, export NC; pockets modelled in
Blender written as ISO 14649 and read back; batch reports and bad files."""
import json
import os

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

import rs274  # noqa: E402
from kezuri.operators import panels, samples  # noqa: E402
from kezuri.toolpath.operations import stepnc  # noqa: E402
from blender_helpers import draw_panel, run_batch  # noqa: E402

FIXTURES = os.environ.get("KEZURI_FIXTURES", os.path.join(os.path.dirname(__file__), "fixtures"))
EX1 = os.path.join(FIXTURES, "iso14649", "ex1.stp")



@pytest.fixture
def scene(empty_scene):
    scene = empty_scene
    return scene


def test_import_creates_features_and_the_workplan_list(scene):
    assert bpy.ops.kezuri.import_stepnc(filepath=EX1) == {"FINISHED"}
    steps = scene.kezuri.stepnc.steps
    assert [s.ident for s in steps] == [10, 11, 12, 13, 14]
    assert steps[3].name == "WS ROUGH POCKET1" and "ClosedPocket" in steps[3].feature
    names = {o.name for o in bpy.data.collections["Kezuri"].objects}
    assert {"Kezuri STEP-NC PLANAR FACE1", "Kezuri STEP-NC HOLE1 D=22MM", "Kezuri STEP-NC POCKET1"} <= names
    pocket = bpy.data.objects["Kezuri STEP-NC POCKET1"]
    z = [v.co.z for v in pocket.data.vertices]
    assert min(z) == pytest.approx(-30.0) and max(z) == pytest.approx(0.0)


def test_reordered_and_disabled_workingsteps_shape_the_nc(scene, tmp_path):
    bpy.ops.kezuri.import_stepnc(filepath=EX1)
    props = scene.kezuri.stepnc
    props.active_step = 4                                   # finishing of the pocket ...
    assert bpy.ops.kezuri.workingstep_move(direction="UP") == {"FINISHED"}
    assert [s.ident for s in props.steps] == [10, 11, 12, 14, 13]   # ... now before its roughing
    props.steps[1].enabled = False                          # no drilling
    path = tmp_path / "ex1.ngc"
    assert bpy.ops.kezuri.stepnc_export(filepath=str(path), post="linuxcnc") == {"FINISHED"}
    text = path.read_text()
    order = [line for line in text.splitlines() if line.startswith("(OPERATION ")]
    assert [o.split(": ", 1)[1].rstrip(")") for o in order] == ["WS FINISH PLANAR FACE1", "WS REAM HOLE1", "WS FINISH POCKET1",
                                                    "WS ROUGH POCKET1"]
    if rs274.available():
        rs274.run(text)
    # Finishing still cuts only what roughing leaves: the same moves in either order.
    loaded = stepnc.load_workplan(EX1)
    normal = {op.name: op for op in stepnc.to_program(loaded).operations}
    swapped = {op.name: op for op in stepnc.to_program(loaded, order=[10, 11, 12, 14, 13]).operations}
    # (the approach to the first floor layer, where the pocket's middle is still uncut, stops above the
    # material instead: test_stepnc.py::test_finishing_before_its_roughing_is_reported_not_replanned)
    early, planned = swapped["WS FINISH POCKET1"], normal["WS FINISH POCKET1"]
    assert np.array_equal(early.xyz[:, :2], planned.xyz[:, :2]) and np.array_equal(early.kind, planned.kind)
    assert np.count_nonzero(early.xyz[:, 2] != planned.xyz[:, 2]) == 1


def test_blender_pockets_written_as_iso14649_read_back_the_same(scene, tmp_path):
    plate = bpy.data.objects.new("Plate", samples.box_mesh("Plate", 0, 0, -20, 120, 80, 0))
    scene.collection.objects.link(plate)
    scene.kezuri.stock.plate = plate
    scene.kezuri.stock.origin = "CORNER"
    outlines = {"POCKET A": [(10, 10), (50, 10), (50, 40), (10, 40)],
                "POCKET B": [(65, 15), (110, 15), (110, 35), (85, 35), (85, 70), (65, 70)]}
    depths = {"POCKET A": 8.0, "POCKET B": 5.0}
    for name, outline in outlines.items():
        mesh = bpy.data.meshes.new(name)
        mesh.from_pydata([(x, y, 0) for x, y in outline], [], [list(range(len(outline)))])
        obj = bpy.data.objects.new(name, mesh)
        scene.collection.objects.link(obj)
        obj.kezuri_pocket.enabled = True
        obj.kezuri_pocket.depth = depths[name]
    path = tmp_path / "pockets.stp"
    assert bpy.ops.kezuri.export_stepnc(filepath=str(path)) == {"FINISHED"}
    loaded = stepnc.load_workplan(str(path))
    pockets = {}
    for step in loaded.workingsteps:
        feature = step.its_feature
        pockets[feature.its_id] = feature
    assert set(pockets) == set(outlines)
    for name, feature in pockets.items():
        assert feature.top_z - feature.bottom_z == pytest.approx(depths[name])
        got = np.asarray(feature.outline(), float)[:, :2]
        want = np.array(outlines[name], float)
        assert len(got) == len(want)
        for p in want:
            assert np.min(np.linalg.norm(got - p, axis=1)) < 1e-5     # Blender keeps vertices in float32
    assert len(loaded.workingsteps) == 4                    # rough + finish per pocket
    # Importing the written file gives that workplan in the panel.
    assert bpy.ops.kezuri.import_stepnc(filepath=str(path)) == {"FINISHED"}
    assert len(scene.kezuri.stepnc.steps) == 4


def test_export_without_import_is_a_clear_error(scene, tmp_path):
    with pytest.raises(RuntimeError):
        bpy.ops.kezuri.stepnc_export(filepath=str(tmp_path / "x.nc"))
    assert not (tmp_path / "x.nc").exists()


def test_stepnc_panel_lists_the_workplan(scene):
    bpy.ops.kezuri.import_stepnc(filepath=EX1)
    layout = draw_panel(panels.KEZURI_PT_stepnc, bpy.context)
    assert "steps" in layout.props
    assert {"kezuri.import_stepnc", "kezuri.stepnc_generate", "kezuri.stepnc_export",
            "kezuri.workingstep_move"} <= set(layout.operators)




def test_batch_stepnc_on_ex1(tmp_path):
    done = run_batch("stepnc", "--input", EX1, "--post", "linuxcnc", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((tmp_path / "report.json").read_text())
    assert [s["id"] for s in report["workingsteps"]] == [10, 11, 12, 13, 14]
    for step in report["workingsteps"]:
        assert step["moves"] > 0 and step["tool"] and step["feature"] and step["operation"]
    if rs274.available():
        kinds, points, _ = rs274.motion_endpoints(rs274.run((tmp_path / "stepnc.ngc").read_text()))
        floor = points[(np.array(kinds) == "feed") & np.isclose(points[:, 2], -30.0) & (points[:, 0] > 40)]  # not the hole
        # NIST's ex1.can cuts the pocket floor over x 54..86, y 39..101 at z = -30 (tool centre).
        assert floor[:, 0].min() == pytest.approx(54, abs=0.6) and floor[:, 0].max() == pytest.approx(86, abs=0.6)
        assert floor[:, 1].min() == pytest.approx(39, abs=0.6) and floor[:, 1].max() == pytest.approx(101, abs=0.6)


def test_batch_stepnc_order_option(tmp_path):
    done = run_batch("stepnc", "--input", EX1, "--order", "13,14,10", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((tmp_path / "report.json").read_text())
    assert [s["id"] for s in report["workingsteps"]] == [13, 14, 10]
    # the workingsteps left out are named, with why, in the report and the NC header
    assert [(s["id"], s["name"], s["reason"]) for s in report["skipped_workingsteps"]] == [
        (11, "WS DRILL HOLE1", "switched off (left out of the order to cut)"),
        (12, "WS REAM HOLE1", "switched off (left out of the order to cut)")]
    nc = (tmp_path / "stepnc.nc").read_text()
    assert "(NOTE: WORKINGSTEP #11 'WS DRILL HOLE1' SKIPPED: SWITCHED OFF [LEFT OUT OF THE ORDER TO CUT])" in nc
    assert "(NOTE: WORKINGSTEP #12 'WS REAM HOLE1' SKIPPED: SWITCHED OFF [LEFT OUT OF THE ORDER TO CUT])" in nc


def test_batch_stepnc_bad_file_names_the_line_and_writes_no_nc(tmp_path):
    text = open(EX1, encoding="latin-1").read().replace("#30= MILLING_TOOL_DIMENSION(18.000,",
                                                           "#30= MILLING_TOOL_DIMENSION(18.000,,")
    bad = tmp_path / "bad.stp"
    bad.write_text(text)
    done = run_batch("stepnc", "--input", str(bad), "--out", str(tmp_path / "out"))
    assert done.returncode == 2
    assert "line" in done.stderr and "#30" in done.stderr and "Traceback" not in done.stderr
    assert not list((tmp_path / "out").glob("stepnc.*"))


def test_batch_report_labels_each_operation_with_its_workingstep(tmp_path):
    """Finishing (#61) has no feedrate and is skipped: report.json lists rough (#60) and drill (#62)
    under their own names, the skip note once, one T number per distinct tool."""
    from test_stepnc_conventions import pocket_file

    source = tmp_path / "skipped.stp"
    source.write_text(pocket_file(finish_technology="#124", finish_tool="#122", hole=True))
    done = run_batch("stepnc", "--input", str(source), "--post", "linuxcnc", "--out", str(tmp_path / "out"))
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    assert [(s["id"], s["name"]) for s in report["workingsteps"]] == [(60, "WS ROUGH POCKET1"), (62, "WS DRILL HOLE1")]
    assert [s["tool"].split()[0] for s in report["workingsteps"]] == ["T1", "T2"]
    assert [op["name"] for op in report["operations"]] == ["WS ROUGH POCKET1", "WS DRILL HOLE1"]
    skipped = [w for w in report["warnings"] if "skipped" in w]
    assert len(skipped) == 1 and skipped[0].startswith("workingstep #61 'WS FINISH POCKET1' skipped")
    assert report["simulation"]["rapid_collisions"] == []


def test_batch_refusal_gives_the_reason_of_every_workingstep(tmp_path):
    from test_stepnc_conventions import pocket_file

    source = tmp_path / "unsupported.stp"
    source.write_text(pocket_file(rough="SIDE_ROUGH_MILLING", finish="SIDE_FINISH_MILLING"))
    done = run_batch("stepnc", "--input", str(source), "--out", str(tmp_path / "out"))
    assert done.returncode == 2
    assert "SIDE_ROUGH_MILLING #50 is not supported" in done.stderr
    assert "SIDE_FINISH_MILLING #51 is not supported" in done.stderr
    assert "switched off" not in done.stderr and "Traceback" not in done.stderr
    assert not list((tmp_path / "out").glob("stepnc.*"))
