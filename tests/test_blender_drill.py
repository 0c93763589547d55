"""Drilling and chamfering from a job file, with holes found in the scene: a curve object of
circles (32 to 128 points) and a mesh with a 64-segment cylindrical hole, beside the name plate
sample; run as ``batch.py job`` in process, the program read back by rs274 and the rules."""
import json
import os

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")
import controller_rules  # noqa: E402
import rs274  # noqa: E402
from test_batch_job import run  # noqa: E402

CIRCLES = [((-85.0, -38.0), 5.0, 32), ((85.0, -38.0), 5.0, 64), ((85.0, 38.0), 8.0, 128), ((-85.0, 38.0), 5.0, 48)]
MESH_HOLE = ((0.0, -38.0), 6.0)

JOB = """# holes found in the scene: the curve Mounting's circles, the mesh Bracket's hole
[setup]
name = "found"
blend = "found.blend"
post = "linuxcnc"
machine = "linuxcnc-manual"

[[operations]]
kind = "engrave"
name = "texture and letters"
objects = { plate = "Plate", letters = "Letters" }
settings = { seed = 7 }

[[operations]]
kind = "drill"
name = "mounting holes"
objects = { holes = "Mounting" }
settings = { tool_number = 4, diameter = 5.0, depth = 12.0, peck = 4.0, helix = true, mill_tool_number = 5, mill_diameter = 6.0 }

[[operations]]
kind = "drill"
name = "bracket hole"
objects = { holes = "Bracket" }
settings = { tool_number = 6, diameter = 6.0, peck = 0.0, retract = "r", spot = true, spot_tool_number = 8, spot_depth = 1.5 }

[[operations]]
kind = "chamfer"
name = "edge"
objects = { edges = "Plate" }
settings = { tool_number = 7, width = 1.0 }
"""


@pytest.fixture(scope="module")
def found_job(tmp_path_factory):
    import manifold3d as m3d

    import kezuri
    from kezuri.operators import samples
    if not hasattr(bpy.types.Scene, "kezuri"):
        kezuri.register()
    scene = bpy.context.scene
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    samples.name_plate(scene)
    curve = bpy.data.curves.new("Mounting", type="CURVE")
    for (x, y), d, count in CIRCLES:
        spline = curve.splines.new("POLY")
        spline.points.add(count - 1)
        t = np.linspace(0, 2 * np.pi, count, endpoint=False)
        spline.points.foreach_set("co", np.column_stack([x + d / 2 * np.cos(t), y + d / 2 * np.sin(t),
                                                         np.zeros(count), np.ones(count)]).ravel())
        spline.use_cyclic_u = True
    scene.collection.objects.link(bpy.data.objects.new("Mounting", curve))
    (x, y), d = MESH_HOLE
    solid = (m3d.Manifold.cube((20, 16, 20)).translate((x - 10, y - 8, -20))
             - m3d.Manifold.cylinder(24, d / 2, d / 2, 64).translate((x, y, -22))).to_mesh()
    mesh = bpy.data.meshes.new("Bracket")
    mesh.from_pydata(np.asarray(solid.vert_properties)[:, :3].tolist(), [], np.asarray(solid.tri_verts).tolist())
    scene.collection.objects.link(bpy.data.objects.new("Bracket", mesh))
    folder = tmp_path_factory.mktemp("found")
    bpy.ops.wm.save_as_mainfile(filepath=str(folder / "found.blend"))
    (folder / "found.toml").write_text(JOB, encoding="utf-8")
    status, message, out = run("job", str(folder / "found.toml"))
    assert status == 0, message[-3000:]
    return out


def test_holes_found_in_the_scene_are_drilled_and_milled(found_job):
    report = json.loads(open(os.path.join(found_job, "report.json")).read())
    assert report["gate"]["findings"] == [] and not report["gate"]["overridden"]
    text = open(report["files"][0]).read()
    assert controller_rules.check(text, "linuxcnc") == []
    # the curve's three 5 mm holes pecked 12 mm deep with G83 (a curve gives no depth: the setting's);
    # its 8 mm one helix-milled with the 6 mm end mill; the bracket's 6 mm hole through the 20 mm
    # plate (the mesh's hole reaches its bottom) with G81 G99: 0.5 mm beyond, and the point's length
    assert "G98 G83" in text and "G99 G81" in text and text.count("\nG80\n") == 3     # and the spot pass's
    assert "G99 G81 X0. Y-38. Z-1.5 R2." in text
    calls = rs274.run(text, tools=(2, 3, 4, 5, 6, 7, 8))
    kinds, points, _ = rs274.motion_endpoints(calls)
    feeds = points[[k == "feed" for k in kinds]]
    for (x, y), d, _ in CIRCLES:
        here = feeds[np.hypot(feeds[:, 0] - x, feeds[:, 1] - y) < 1e-3]
        if d == 5.0:
            assert here[:, 2].min() == pytest.approx(-12.0, abs=1e-4)
    helix = points[[k == "ccw" for k in kinds]]        # 14 mm from the R plane in 1 mm turns, and the floor
    (hx, hy), hd, _ = CIRCLES[2]
    on = np.abs(np.hypot(helix[:, 0] - hx, helix[:, 1] - hy) - (hd - 6.0) / 2) < 1e-3
    assert on.sum() == 15 and helix[on, 2].min() == pytest.approx(-12.0, abs=1e-4)
    (bx, by), bd = MESH_HOLE
    here = feeds[np.hypot(feeds[:, 0] - bx, feeds[:, 1] - by) < 1e-3]
    assert here[:, 2].min() == pytest.approx(-20.5 - 3.0 / np.tan(np.radians(59)), abs=1e-3)
    # the chamfer: the V-bit's tip 1.2 mm down (1 mm chamfer, 0.2 mm below it) round the plate
    assert "T7 M06" in text and points[:, 2][np.abs(np.abs(points[:, 0]) - 100.2) < 1e-3].min() == pytest.approx(-1.2)
