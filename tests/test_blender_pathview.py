"""Toolpaths in the viewport in the pictures' colours per move kind (operators/pathview.py), run
in-process with the bpy wheel: after Generate every preview object is one operation's moves of
one kind, its material's viewport colour the legend's (the colour Blender's default Solid shading
shows), re-running Generate adds no material, and the scene's Show Rapids hides and shows the
rapid objects of every preview without planning again (and is undone as one property change).

Expected colours are decoded here from the legend's sRGB bytes (IEC 61966-2-1), not by the code
under test."""
import os

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

from blender_helpers import draw_panel  # noqa: E402
from kezuri.operators import convert, panels, pathview, samples  # noqa: E402
from kezuri.toolpath.pictures import legend  # noqa: E402

SUFFIX = {"cut": "", "plunge": " plunges", "link": " links", "rapid": " rapids"}


def decoded(rgb) -> tuple:
    c = np.asarray(rgb, float) / 255.0
    return tuple(np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)) + (1.0,)


@pytest.fixture
def scene(empty_scene):
    yield empty_scene
    bpy.context.scene.kezuri.show_rapids = True      # the switch is not in a group clear_scene resets


def preview(prefix: str) -> list:
    return [o for o in bpy.data.collections["Kezuri"].objects if o.name.startswith(prefix)]


def check_colours_by_kind(prefix: str) -> dict:
    """Every preview object has one move kind, in its name, its material and its colour:
    {kind: [objects]}."""
    by_kind = {}
    for obj in preview(prefix):
        kind = obj[pathview.KIND]
        by_kind.setdefault(kind, []).append(obj)
        assert obj.type == "CURVE" and obj.name.endswith(SUFFIX[kind]), obj.name
        assert [m.name for m in obj.data.materials] == [f"Kezuri {kind}"]
        want = decoded(legend.ROLE_COLOURS[kind])
        assert tuple(obj.data.materials[0].diffuse_color) == pytest.approx(want, abs=1e-6), kind
        assert tuple(obj.color) == pytest.approx(want, abs=1e-6), kind
    return by_kind


def splines(obj) -> list:
    """Each spline's points in world units (1 unit = 1 mm in these scenes)."""
    return [np.array([p.co[:3] for p in spline.points]) for spline in obj.data.splines]


def test_blenders_default_solid_shading_colours_by_material():
    # what the colours are made for: Solid shading, Color = Material, by default (Blender 5.0)
    assert bpy.types.View3DShading.bl_rna.properties["color_type"].default == "MATERIAL"
    assert bpy.context.scene.display.shading.color_type == "MATERIAL"


def test_engrave_preview_in_the_legends_colours(scene):
    samples.name_plate(scene)
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    by_kind = check_colours_by_kind("Kezuri Engrave")
    assert set(by_kind) == {"cut", "plunge", "link", "rapid"}
    assert {o.name for o in by_kind["cut"]} == {"Kezuri Engrave roughing (gouge texture)",
                                                "Kezuri Engrave band finishing", "Kezuri Engrave burr contour"}
    # the kinds as the moves are: cuts in the plate (top Z 0), plunges straight down from the 2 mm
    # approach gap, rapids (each run from where the tool was) ending nowhere below that gap
    cut_z = np.vstack([p for o in by_kind["cut"] for p in splines(o)])[:, 2]
    assert cut_z.max() <= 1e-4 and cut_z.min() == pytest.approx(-2.8, abs=1e-4)
    for obj in by_kind["plunge"]:
        for points in splines(obj):
            assert np.all(np.diff(points[:, 2]) < 0) and points[0, 2] == pytest.approx(2.0, abs=1e-4)
            assert np.ptp(points[:, :2], axis=0).max() < 1e-3
    assert min(p[1:, 2].min() for o in by_kind["rapid"] for p in splines(o)) == pytest.approx(2.0, abs=1e-4)
    # Generate again: the same objects and materials, none added
    names, materials = sorted(o.name for o in preview("Kezuri Engrave")), len(bpy.data.materials)
    kind_materials = [bpy.data.materials[f"Kezuri {kind}"].as_pointer() for kind in legend.ROLES]
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    assert sorted(o.name for o in preview("Kezuri Engrave")) == names
    assert len(bpy.data.materials) == materials
    assert [bpy.data.materials[f"Kezuri {kind}"].as_pointer() for kind in legend.ROLES] == kind_materials
    check_colours_by_kind("Kezuri Engrave")


def test_a_material_changed_by_hand_gets_the_legends_colour_back(scene):
    samples.name_plate(scene)
    material = bpy.data.materials.get("Kezuri cut") or bpy.data.materials.new("Kezuri cut")
    material.diffuse_color = (0.5, 0.5, 0.5, 1.0)
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    assert tuple(bpy.data.materials["Kezuri cut"].diffuse_color) == pytest.approx(decoded(legend.ROLE_COLOURS["cut"]))
    base = [n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED"][0].inputs["Base Color"]
    assert tuple(base.default_value) == pytest.approx(decoded(legend.ROLE_COLOURS["cut"]))   # Material Preview


def rotary_job(scene):
    samples.rotary_block(scene)
    assert bpy.ops.kezuri.rotary_generate() == {"FINISHED"}


def turnmill_job(scene):
    samples.turnmill_part(scene)
    assert bpy.ops.kezuri.turnmill_generate() == {"FINISHED"}


def stepnc_job(scene):
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fixtures", "iso14649", "ex1.stp")
    assert bpy.ops.kezuri.import_stepnc(filepath=path) == {"FINISHED"}
    assert bpy.ops.kezuri.stepnc_generate() == {"FINISHED"}


@pytest.mark.parametrize("prefix, job", [("Kezuri Rotary", rotary_job), ("Kezuri Turn-Mill", turnmill_job),
                                         ("Kezuri STEP-NC path", stepnc_job)])
def test_every_workflows_preview_is_coloured_by_move_kind(scene, prefix, job):
    job(scene)
    by_kind = check_colours_by_kind(prefix)
    assert {"cut", "rapid"} <= set(by_kind), sorted(by_kind)
    scene.kezuri.show_rapids = False
    assert hidden_by_kind(prefix).pop("rapid") == {True}
    if prefix == "Kezuri Rotary":
        # C-X-Z moves shown in the part's frame: the cuts spread over X and Y in the block
        # (in the machine's frame every point would have Y 0)
        cuts = np.vstack([p for o in by_kind["cut"] for p in splines(o)])
        assert np.ptp(cuts[:, 1]) > 10.0 and cuts[:, 2].max() <= 1e-4


def hidden_by_kind(prefix: str) -> dict:
    hidden = {}
    for obj in preview(prefix):
        hidden.setdefault(obj[pathview.KIND], set()).add(obj.hide_viewport)
    return hidden


def test_show_rapids_hides_and_shows_the_rapids_of_every_preview(scene):
    samples.name_plate(scene)
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    convert.remove_objects("Kezuri Carve")
    assert bpy.ops.kezuri.carve_sample(sample="wave") == {"FINISHED"}
    scene.kezuri.carve.scallop, scene.kezuri.carve.step_down = 0.05, 4.0      # a coarse job, quick
    assert bpy.ops.kezuri.carve_generate() == {"FINISHED"}
    by_kind = check_colours_by_kind("Kezuri Carve")
    assert {"cut", "rapid"} <= set(by_kind)
    objects = {o.name: o.as_pointer() for o in bpy.data.collections["Kezuri"].objects}
    assert hidden_by_kind("Kezuri Engrave")["rapid"] == {False} == hidden_by_kind("Kezuri Carve")["rapid"]
    scene.kezuri.show_rapids = False
    for prefix in ("Kezuri Engrave", "Kezuri Carve"):
        hidden = hidden_by_kind(prefix)
        assert hidden.pop("rapid") == {True} and set().union(*hidden.values()) == {False}, prefix
    # nothing planned again: the very same objects
    assert {o.name: o.as_pointer() for o in bpy.data.collections["Kezuri"].objects} == objects
    assert bpy.ops.kezuri.carve_generate() == {"FINISHED"}               # a new preview keeps to the switch
    assert hidden_by_kind("Kezuri Carve")["rapid"] == {True}
    scene.kezuri.show_rapids = True
    for prefix in ("Kezuri Engrave", "Kezuri Carve"):
        assert set().union(*hidden_by_kind(prefix).values()) == {False}, prefix


def test_show_rapids_is_undone_with_its_objects(scene):
    samples.name_plate(scene)
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    bpy.ops.ed.undo_push(message="preview")
    scene.kezuri.show_rapids = False
    bpy.ops.ed.undo_push(message="Show Rapids")
    assert hidden_by_kind("Kezuri Engrave")["rapid"] == {True}
    assert bpy.ops.ed.undo() == {"FINISHED"}
    assert bpy.context.scene.kezuri.show_rapids is True
    assert hidden_by_kind("Kezuri Engrave")["rapid"] == {False}
    assert bpy.ops.ed.redo() == {"FINISHED"}
    assert bpy.context.scene.kezuri.show_rapids is False
    assert hidden_by_kind("Kezuri Engrave")["rapid"] == {True}


def test_the_switch_is_under_the_job_picker_for_jobs_with_toolpaths(scene):
    for job, shown in (("ENGRAVE", True), ("CARVE", True), ("TURNMILL", True), ("SHEET", False)):
        scene.kezuri.job = job
        assert ("show_rapids" in draw_panel(panels.KEZURI_PT_job, bpy.context).props) is shown, job
    scene.kezuri.job = "ENGRAVE"
