"""The V-carve in the job list's panels (issue 30): a V-carve row's settings edited with real
properties (``scene.kezuri.vcarve``: V-bit, depth, clearing, inlay, feeds), planned with Generate
Job and exported; the planned depths checked against closed forms worked out here by hand."""
import json
import math
import re
import types

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from kezuri.operators import joblist, samples  # noqa: E402
from kezuri.toolpath.feeds import operationfeeds  # noqa: E402
from kezuri.toolpath.job import plan_job  # noqa: E402


def planned_ops(scene):
    """{row name: [Operation, ...]} of the job list's plan."""
    planned = plan_job(joblist.build(scene)[0])
    found = {}
    for item in planned.planned:
        found.setdefault(item.operation.name, []).extend(item.part.operations)
    return found, planned


def feed_points(op):
    return np.asarray(op.xyz)[np.asarray(op.kind) != 0]      # every move's end but the rapids


def z_at(points, xy):
    """The Z of the feed point nearest ``xy`` (which must be within 1 um of it)."""
    distance = np.hypot(points[:, 0] - xy[0], points[:, 1] - xy[1])
    assert distance.min() < 1e-3, (xy, distance.min())
    return points[int(np.argmin(distance)), 2]


def add_row(scene, name):
    assert bpy.ops.kezuri.job_add(kind="vcarve") == {"FINISHED"}
    listed = scene.kezuri.job_list
    row = listed.rows[listed.active]
    row.name = name
    return row


def rectangle(scene, name, x0, y0, x1, y1):
    """A mesh face (seen from above: the region), in the name plate's work frame (its top centre)."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(x0, y0, 0.0), (x1, y0, 0.0), (x1, y1, 0.0), (x0, y1, 0.0)], [], [(0, 1, 2, 3)])
    obj = bpy.data.objects.new(name, mesh)
    scene.collection.objects.link(obj)
    return obj


def region_slot(row, obj):
    next(item for item in row.objects if item.slot == "region").object = obj


@pytest.mark.parametrize("angle", [60.0, 90.0])
def test_a_strip_set_in_the_panel_is_w_over_2_tan_half_angle_deep(empty_scene, angle, tmp_path):
    """A 10 x 60 mm strip: the tip on its centre line 5 / tan(a/2) deep: 60 deg: 5 x sqrt(3) =
    8.6603 mm, 90 deg: 5 mm (the 12.7 mm V-bit's cone is 10 mm wide there)."""
    scene = empty_scene
    samples.name_plate(scene)
    scene.kezuri.machine.post = "linuxcnc"
    row = add_row(scene, "strip")
    region_slot(row, rectangle(scene, "Strip", -30.0, 10.0, 30.0, 20.0))
    props = scene.kezuri.vcarve                      # the selected row's settings, as the panel edits them
    props.angle, props.tool_number = angle, 7
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    assert row.state == "PLANNED" and row.tools == "T7"
    kept = json.loads(row.settings)          # what was set, and the speeds, feeds and steps a row always keeps
    assert kept["tool_number"] == 7 and kept.get("angle", 60.0) == angle
    assert set(kept) - {"angle", "tool_number"} <= set(operationfeeds.setting_names("vcarve"))
    ops, _ = planned_ops(scene)
    (op,) = ops["strip"]
    points = feed_points(op)
    expected = {60.0: 5.0 * math.sqrt(3.0), 90.0: 5.0}[angle]
    assert points[:, 2].min() == pytest.approx(-expected, abs=1e-3)
    deepest = points[points[:, 2] < -expected + 1e-3]
    assert np.abs(deepest[:, 1] - 15.0).max() < 1e-3                        # on the centre line
    # the centre line's deepest stretch: 60 - 2 x 5 mm long (the corners' bisectors meet 5 mm in)
    assert deepest[:, 0].min() == pytest.approx(-25.0, abs=0.02) and deepest[:, 0].max() == pytest.approx(25.0,
                                                                                                        abs=0.02)
    assert op.tool.number == 7 and op.tool.shape.tip_angle_deg == angle
    path = tmp_path / "strip.ngc"
    assert bpy.ops.kezuri.job_export(filepath=str(path), post="linuxcnc") == {"FINISHED"}
    words = [float(z) for z in re.findall(r"Z(-?[\d.]+)", path.read_text())]
    assert min(words) == pytest.approx(-expected, abs=1e-3)             # the program as written


def test_max_depth_and_the_clearing_end_mill_set_in_the_panel(empty_scene):
    """The 10 x 60 mm strip with the 90 deg V-bit held to 3 mm: the end mill (2 mm, T9, set in the
    Clearing panel) clears the strip shrunk by 3 x tan(45 deg) = 3 mm (4 x 54 mm) flat at Z -3, its
    centre 1 mm inside that; the V-bit runs that outline at Z -3 and goes no deeper."""
    scene = empty_scene
    samples.name_plate(scene)
    scene.kezuri.machine.post = "linuxcnc"
    row = add_row(scene, "strip")
    region_slot(row, rectangle(scene, "Strip", -30.0, 10.0, 30.0, 20.0))
    props = scene.kezuri.vcarve
    props.angle, props.max_depth = 90.0, 3.0
    props.clear_tool_number, props.clear_diameter, props.clear_step_down = 9, 2.0, 3.0
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    assert row.tools == "T9 T3"
    ops, _ = planned_ops(scene)
    clearing, vbit = ops["strip"]
    assert (clearing.tool.number, clearing.tool.diameter, vbit.tool.number) == (9, 2.0, 3)
    cleared = feed_points(clearing)
    assert cleared[:, 2].min() == pytest.approx(-3.0, abs=1e-9)
    floor = cleared[np.abs(cleared[:, 2] + 3.0) < 1e-9]
    assert np.abs(floor[:, 1] - 15.0).max() == pytest.approx(2.0 - 1.0, abs=0.01)
    assert np.abs(floor[:, 0]).max() == pytest.approx(27.0 - 1.0, abs=0.01)
    carved = feed_points(vbit)
    assert carved[:, 2].min() == pytest.approx(-3.0, abs=1e-9)
    at_max = carved[np.abs(carved[:, 2] + 3.0) < 1e-9]
    assert np.abs(at_max[:, 1] - 15.0).max() == pytest.approx(2.0, abs=0.01)
    assert np.abs(at_max[:, 0]).max() == pytest.approx(27.0, abs=0.01)


def test_an_inlay_plug_set_in_the_panel_starts_at_start_depth_plus_the_glue_gaps_share(empty_scene):
    """A male plug of a 10 x 20 mm rectangle, 90 deg V-bit, start depth 1.5 mm, glue gap 0.1 mm,
    3 mm high: the tip where the waste is 0 wide (its box's corners) at 1.5 + 0.1 / sin(45 deg) =
    1.6414 mm; the waste box the design grown by 2 x 3 x tan(45 deg) + 2 = 8 mm, cleared flat at
    Z -3.  The female pocket of the same design: the tip at 0 on the outline, its bottom at 2 mm."""
    scene = empty_scene
    samples.name_plate(scene)
    scene.kezuri.machine.post = "linuxcnc"
    design = rectangle(scene, "Design", 40.0, -10.0, 50.0, 10.0)
    male = add_row(scene, "plug")
    region_slot(male, design)
    props = scene.kezuri.vcarve
    props.angle, props.inlay, props.start_depth, props.glue_gap, props.max_depth = 90.0, "male", 1.5, 0.1, 3.0
    female = add_row(scene, "pocket")
    region_slot(female, design)
    kept = json.loads(male.settings)
    assert {key: kept[key] for key in ("angle", "inlay", "start_depth", "max_depth")} == \
        {"angle": 90.0, "inlay": "male", "start_depth": 1.5, "max_depth": 3.0}
    assert set(kept) - {"angle", "inlay", "start_depth", "max_depth"} <= set(operationfeeds.setting_names("vcarve"))
    props.angle, props.inlay, props.start_depth, props.max_depth = 90.0, "female", 1.5, 2.0
    male.enabled = False          # the two halves are cut from two boards: each planned on its own
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    ops, _ = planned_ops(scene)
    flat, pocket = ops["pocket"]                   # its flat bottom cleared by the end mill, then the V-bit
    assert feed_points(flat)[:, 2].min() == pytest.approx(-2.0, abs=1e-9)
    points = feed_points(pocket)
    assert points[:, 2].min() == pytest.approx(-2.0, abs=1e-9)
    for corner in ((40.0, -10.0), (50.0, -10.0), (50.0, 10.0), (40.0, 10.0)):      # the design's, at the top
        assert z_at(points, corner) == pytest.approx(0.0, abs=1e-3), corner
    male.enabled, female.enabled = True, False
    scene.kezuri.job_list.active = 0
    assert scene.kezuri.vcarve.inlay == "male" and scene.kezuri.vcarve.glue_gap == pytest.approx(0.1)
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    ops, _ = planned_ops(scene)
    clearing, plug = ops["plug"]
    points = feed_points(plug)
    shift = 1.5 + 0.1 / math.sin(math.radians(45.0))
    assert shift == pytest.approx(1.64142, abs=1e-5)
    for corner in ((32.0, -18.0), (58.0, -18.0), (58.0, 18.0), (32.0, 18.0)):       # the waste box's
        assert z_at(points, corner) == pytest.approx(-shift, abs=1e-3), corner
    assert points[:, 2].min() == pytest.approx(-3.0, abs=1e-9)
    assert np.abs(points[:, 0] - 45.0).max() == pytest.approx(5.0 + 8.0, abs=0.01)
    assert np.abs(points[:, 1]).max() == pytest.approx(10.0 + 8.0, abs=0.01)
    assert feed_points(clearing)[:, 2].min() == pytest.approx(-3.0, abs=1e-9)


def test_the_vcarve_panels_show_for_its_rows_only(empty_scene):
    from kezuri.operators import panels

    scene = empty_scene
    samples.name_plate(scene)
    context = types.SimpleNamespace(scene=scene, active_object=None)
    for kind in ("vcarve", "pocket", "vcarve"):
        assert bpy.ops.kezuri.job_add(kind=kind) == {"FINISHED"}
        shown = {c.bl_label for c in panels.CLASSES if c.bl_idname.startswith("KEZURI_PT_joblist_")
                 and c.poll(context)}
        if kind == "vcarve":
            assert shown == {"V-Bit", "Depth", "Clearing", "Inlay", "Feeds & Heights"}
        else:
            assert "V-Bit" not in shown and "Inlay" not in shown


@pytest.mark.parametrize("language", ["en", "ja"])
def test_the_vcarve_panels_fit_the_sidebar(empty_scene, language):
    """Every label, value and menu item of the V-carve's panels (all open), in English and in
    Japanese, at Blender's default sidebar width (tests/sidebar_fit.py)."""
    import sidebar_fit as fit
    from kezuri.operators import panels, translations

    scene = empty_scene
    samples.name_plate(scene)
    context = types.SimpleNamespace(scene=scene, active_object=None)
    table = translations.TRANSLATIONS["ja_JP"] if language == "ja" else None
    assert bpy.ops.kezuri.job_add(kind="vcarve") == {"FINISHED"}
    scene.kezuri.vcarve.inlay = "female"
    classes = [c for c in panels.CLASSES if c.bl_idname.startswith("KEZURI_PT_joblist")]
    texts = fit.all_texts(classes, context, table)
    words = {t.text for t in texts}
    ja = translations.TRANSLATIONS["ja_JP"]
    for label in ("Glue Gap", "Max Depth", "Mill Diameter", "Female"):
        assert (label if language == "en" else ja[("*", label)]) in words, label
    assert not fit.too_wide(texts), "\n".join(fit.too_wide(texts))
