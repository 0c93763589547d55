"""The profile in the CAM tab's job list: a row of kind profile gets an empty ``shape`` slot and
``tabs`` in its other keys; with the Outline picked it plans and exports through the real operators
(the program read as text by the controller-rules reader, rs274 when installed)."""
import json
import re

import pytest

bpy = pytest.importorskip("bpy")

import controller_rules  # noqa: E402
import rs274  # noqa: E402
from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from kezuri.operators import samples  # noqa: E402


def test_a_profile_row_cuts_the_outline_out_with_its_tabs(empty_scene, tmp_path):
    scene = empty_scene
    samples.name_plate_cut_out(scene)
    scene.kezuri.machine.post = "linuxcnc"
    assert bpy.ops.kezuri.job_add(kind="engrave") == {"FINISHED"}
    assert bpy.ops.kezuri.job_add(kind="profile") == {"FINISHED"}
    row = scene.kezuri.job_list.rows[1]
    assert [(item.slot, item.object) for item in row.objects] == [("shape", None)]
    assert json.loads(row.extra) == {"tabs": []}
    row.objects[0].object = scene.objects["Outline"]
    row.extra = json.dumps({"tabs": [[0.0, -45.0], [0.0, 45.0]]})
    row.settings = json.dumps({"allowance": 0.3, "tab_width": 10.0})
    path = tmp_path / "plate.ngc"
    assert bpy.ops.kezuri.job_export(filepath=str(path), post="linuxcnc") == {"FINISHED"}
    text = path.read_text()
    assert re.findall(r"^T(\d+) M0?6", text, re.M) == ["2", "3", "2", "5"]
    assert controller_rules.check(text, "linuxcnc") == []
    profile = text[re.search(r"^T5 M0?6", text, re.M).start():]
    assert min(float(z) for z in re.findall(r"Z(-?\d+\.?\d*)", profile)) == pytest.approx(-20.3)
    assert "Z-17." in profile                     # over the tabs: 3 mm above the stock's bottom
    if rs274.available():
        kinds, points, _ = rs274.motion_endpoints(rs274.run(text, tools=(2, 3, 5)))
        assert points[:, 2].min() == pytest.approx(-20.3)
