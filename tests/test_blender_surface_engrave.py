"""The curved-plate engraving in the Blender shell (bpy wheel, background mode): the Plate
Surface in the Engrave panel, the operators on a cylindrical plate, and bad surfaces refused."""
import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

from blender_helpers import draw_panel  # noqa: E402
from kezuri.operators import engrave as shell  # noqa: E402
from kezuri.operators import panels, samples  # noqa: E402
from kezuri.toolpath.operations.engrave import surface_engrave as se  # noqa: E402

R = se.CYLINDER_RADIUS


@pytest.fixture
def scene(empty_scene):
    samples.name_plate(empty_scene)
    shell.add_surface(empty_scene, "cylinder")
    return empty_scene


def test_the_engrave_panel_shows_the_plate_surface(scene):
    assert "surface" in draw_panel(panels.KEZURI_PT_engrave, bpy.context).props


def test_generate_follows_the_cylinder_at_the_papers_depths(scene):
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    rough = bpy.data.objects["Kezuri Engrave roughing (gouge texture)"]
    points = shell.convert.curve_points(rough)
    # the 6 mm ball resting on the cylinder z = sqrt(R^2 - y^2) - R has its tip at
    # sqrt((R + 3)^2 - y^2) - R - 3 (closed form); the cuts lie 1.2..2.8 mm below that
    touch = np.sqrt((R + 3.0) ** 2 - points[:, 1] ** 2) - R - 3.0
    depth = points[:, 2] - touch
    cuts = depth < -0.5
    assert cuts.sum() > 1000
    assert depth[cuts].min() > -2.8 - 3e-3 and depth[cuts].max() < -1.2 + 3e-3
    assert np.ptp(points[cuts, 2]) > 7       # it is curved: the edges are far below the crown


def test_export_macro_program_on_the_cylinder(scene, tmp_path):
    path = tmp_path / "plate.nc"
    assert bpy.ops.kezuri.engrave_export(filepath=str(path), post="fanuc-macro") == {"FINISHED"}
    text = path.read_text()
    assert "G66.1 P7024" in text and "O7024" in text and " E1 Q1 R" in text and " B1 C" not in text


def test_a_surface_that_does_not_cover_the_plate_names_the_object(scene, tmp_path):
    small = shell.convert.mesh_object(scene, "Small Dome", *se.dome(-40, -20, 40, 20, -20),
                                      shell.convert.plate_from_object(scene.kezuri.stock.plate,
                                                                      bpy.context.evaluated_depsgraph_get(), scene,
                                                                      "CENTER").frame)
    scene.kezuri.engrave.surface = small
    path = tmp_path / "x.nc"
    with pytest.raises(RuntimeError, match="Small Dome.*does not cover the plate"):
        bpy.ops.kezuri.engrave_export(filepath=str(path), post="fanuc")
    assert not path.exists()


def test_batch_refuses_an_unknown_surface_and_writes_nothing(tmp_path):
    from blender_helpers import run_batch

    done = run_batch("engrave", "--surface", "sphere", "--out", str(tmp_path / "o"))
    assert done.returncode == 2 and "--surface sphere" in done.stderr and "Traceback" not in done.stderr
    assert not (tmp_path / "o" / "engrave.nc").exists()


def test_batch_on_the_cylinder_writes_the_program_and_the_design(tmp_path):
    import json

    import trimesh
    from blender_helpers import run_batch

    out = tmp_path / "o"
    done = run_batch("engrave", "--surface", "cylinder", "--post", "linuxcnc", "--out", str(out))
    assert done.returncode == 0, done.stderr[-2000:]
    report = json.loads((out / "report.json").read_text())
    assert report["gate"]["findings"] == [] and report["simulation"]["gouges"] == []
    assert report["files"] == [str(out / "engrave.ngc"), str(out / "design.stl")]
    design = trimesh.load(str(out / "design.stl"), force="mesh")
    assert design.is_watertight
    # the design is the cylinder lowered by the deepest cut (2.8 mm) with the letters up to it
    v = np.asarray(design.vertices)
    top = np.sqrt(R ** 2 - v[:, 1] ** 2) - R
    assert np.all(v[:, 2] <= top + 1e-3)
    assert np.any(np.abs(v[:, 2] - top) < 1e-3) and np.any(np.abs(v[:, 2] - (top - 2.8)) < 0.02)
