"""The router kinds' panels (issue 29): profile, pocket, drill and chamfer rows of the job list edited
with real properties (``scene.kezuri.<kind>``), planned with Generate Job, read back as job-file
settings; the planned moves checked against closed forms worked out here by hand."""
import json
import math
import os
import re

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from kezuri.operators import joblist, samples  # noqa: E402
from kezuri.toolpath.job import plan_job  # noqa: E402
# a drilling row's spindle speeds, feeds and peck, kept in the row whatever their value (the feeds a
# job file with a material computes where it leaves them out): DrillSettings' defaults
DRILL_FEEDS = {"rpm": 3000.0, "feed": 150.0, "peck": 3.0, "mill_rpm": 12000.0, "mill_feed": 800.0}


def planned_ops(scene):
    """The planned job's operations by the row's name: {row name: [Operation, ...]}."""
    planned = plan_job(joblist.build(scene)[0])
    found = {}
    for item in planned.planned:
        found.setdefault(item.operation.name, []).extend(item.part.operations)
    return found


def feed_points(op):
    kinds = np.asarray(op.kind)
    return np.asarray(op.xyz)[kinds != 0]      # every move's end but the rapids


def rounded_rect_distance(xy, hx, hy, r):
    """Signed distance (outside > 0) of points to a rectangle of half sizes hx, hy centred on the
    origin with corners rounded to radius r."""
    dx = np.maximum(np.abs(xy[:, 0]) - (hx - r), 0.0)
    dy = np.maximum(np.abs(xy[:, 1]) - (hy - r), 0.0)
    return np.hypot(dx, dy) - r


def clusters(points, gap):
    """Groups of the points, a point joining a group when within ``gap`` mm of one of its points."""
    groups = []
    for p in points:
        near = [g for g in groups if np.hypot(*(np.asarray(g) - p).T).min() <= gap]
        merged = [p] + [q for g in near for q in g]
        groups = [g for g in groups if not any(g is n for n in near)] + [merged]
    return groups


def add_row(scene, kind, name):
    assert bpy.ops.kezuri.job_add(kind=kind) == {"FINISHED"}
    listed = scene.kezuri.job_list
    row = listed.rows[listed.active]
    row.name = name
    return row


def slot(row, name, obj):
    item = next(i for i in row.objects if i.slot == name)
    item.object = obj


def test_profile_set_in_the_panel_plans_the_outline_offset_by_the_radius_with_its_tabs(empty_scene):
    scene = empty_scene
    _, _, outline = samples.name_plate_cut_out(scene)
    scene.kezuri.machine.post = "linuxcnc"
    row = add_row(scene, "profile", "cut out")
    slot(row, "shape", outline)
    props = scene.kezuri.profile                    # the selected row's settings, as the panel edits them
    props.diameter, props.tool_number, props.flute_length = 6.0, 5, 25.0
    props.tab_count, props.tab_width, props.tab_height, props.lead = 4, 8.0, 3.0, "none"
    props.step_down = 4.0
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    assert row.state in {"PLANNED", "FINDINGS"} and row.tools == "T5"
    # the defaults left out, but for the spindle speed, feeds and steps: what the panel shows is what runs
    # (a job file with a material computes the ones it leaves out)
    assert json.loads(row.settings) == {"lead": "none", "step_down": 4.0, "tab_count": 4,
                                        "rpm": 18000.0, "feed": 1500.0, "plunge_feed": 300.0}
    (op,) = planned_ops(scene)["cut out"]
    points = feed_points(op)
    floor = points[:, 2].min()
    assert floor == pytest.approx(-20.0 - 0.3, abs=1e-6)         # the 20 mm plate and the 0.3 mm breakthrough
    # the outline: 190 x 90 mm, corners 8 mm round; the 6 mm end mill's centre 3 mm outside it
    at_depth = points[points[:, 2] < floor + 1e-6]
    assert np.abs(rounded_rect_distance(at_depth[:, :2], 95.0, 45.0, 8.0) - 3.0).max() < 0.01
    # four tabs: where the tool stays at the tab's top, 3 mm above the stock's bottom (Z -20 + 3)
    tab_top = points[np.abs(points[:, 2] - (-20.0 + 3.0)) < 1e-6]
    angles = np.degrees(np.arctan2(tab_top[:, 1], tab_top[:, 0]))
    assert len(tab_top) >= 8 and len(set(np.floor((angles + 45.0) / 90.0).astype(int) % 4)) == 4   # on all 4 sides
    assert np.abs(rounded_rect_distance(tab_top[:, :2], 95.0, 45.0, 8.0) - 3.0).max() < 0.01
    # levels: 20.3 mm in 4 mm steps = 6 levels (20.3 / 4 = 5.075, rounded up), every step at most 4 mm
    assert math.ceil(20.3 / 4.0) == 6
    assert op.tool.diameter == 6.0 and op.tool.number == 5


def test_pocket_drill_and_chamfer_rows_take_their_settings_from_the_panel(empty_scene):
    scene = empty_scene
    plate, letters = samples.name_plate(scene)
    scene.kezuri.machine.post = "linuxcnc"
    pocket = add_row(scene, "pocket", "letters")          # its slots: the Engrave panel's letters, the plate
    assert {i.slot: i.object for i in pocket.objects} == {"region": letters, "plate": plate}
    props = scene.kezuri.pocket
    props.depth, props.diameter, props.stepover, props.step_down = 2.0, 3.0, 1.2, 2.0
    props.rest_diameter = 1.0           # rest machining; its tool number left at 0: the next one (T6)
    drill = add_row(scene, "drill", "holes")
    drill.extra = json.dumps({"holes": [[-90.0, -40.0], [90.0, 40.0]]})
    props = scene.kezuri.drill
    props.depth, props.peck, props.dwell, props.tool_number = 8.0, 0.0, 0.5, 4
    chamfer = add_row(scene, "chamfer", "edge")
    slot(chamfer, "edges", plate)
    scene.kezuri.chamfer.width = 1.5
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    rows = scene.kezuri.job_list.rows
    assert [(r.name, r.tools) for r in rows] == [("letters", "T5 T6"), ("holes", "T4"), ("edge", "T7")]
    assert json.loads(rows[0].settings) == {"depth": 2.0, "diameter": 3.0, "rest_diameter": 1.0, "stepover": 1.2,
                                            "step_down": 2.0, "rpm": 18000.0, "feed": 1200.0, "entry_feed": 400.0,
                                            "rest_rpm": 20000.0, "rest_feed": 500.0, "rest_step_down": 1.0,
                                            "rest_stepover": 0.8}
    assert json.loads(rows[1].settings) == {"depth": 8.0, "dwell": 0.5, **DRILL_FEEDS, "peck": 0.0}
    assert json.loads(rows[2].settings) == {"width": 1.5, "rpm": 16000.0, "feed": 1200.0, "plunge_feed": 300.0}
    ops = planned_ops(scene)
    rough, rest = ops["letters"]
    assert (rough.tool.diameter, rough.tool.number, rest.tool.diameter, rest.tool.number) == (3.0, 5, 1.0, 6)
    assert feed_points(rough)[:, 2].min() == pytest.approx(-2.0, abs=1e-9)
    (drilled,) = ops["holes"]
    bottoms = feed_points(drilled)
    assert bottoms[:, 2].min() == pytest.approx(-8.0, abs=1e-9)
    deepest = bottoms[np.abs(bottoms[:, 2] + 8.0) < 1e-9][:, :2]
    assert sorted(map(tuple, np.round(deepest, 6))) == [(-90.0, -40.0), (90.0, 40.0)]
    (edge,) = ops["edge"]
    # a 90 deg V-bit: depth = width / tan(45 deg) = 1.5 mm, the tip 0.2 mm (tip_gap) lower, its axis
    # 0.2 x tan(45 deg) = 0.2 mm outside the plate's 200 x 100 mm top edge
    points = feed_points(edge)
    tip = points[np.abs(points[:, 2] + 1.7) < 1e-9]
    assert points[:, 2].min() == pytest.approx(-1.7, abs=1e-9) and len(tip) > 4
    assert np.abs(rounded_rect_distance(tip[:, :2], 100.0, 50.0, 0.0) - 0.2).max() < 0.01


def test_a_row_shows_its_settings_in_the_panel_and_keeps_them_when_another_is_selected(empty_scene, tmp_path):
    scene = empty_scene
    samples.name_plate(scene)
    first = add_row(scene, "drill", "a")
    scene.kezuri.drill.depth = 6.0
    scene.kezuri.drill.retract = "r"
    second = add_row(scene, "drill", "b")             # selecting it reads "a" back, shows b's defaults
    assert json.loads(first.settings) == {"depth": 6.0, "retract": "r", **DRILL_FEEDS}
    assert (scene.kezuri.drill.depth, scene.kezuri.drill.retract) == (10.0, "initial")
    scene.kezuri.drill.helix = True
    scene.kezuri.job_list.active = 0
    assert json.loads(second.settings) == {"helix": True, **DRILL_FEEDS}
    assert (scene.kezuri.drill.depth, scene.kezuri.drill.retract, scene.kezuri.drill.helix) == (6.0, "r", False)
    scene.kezuri.job_list.active = 1
    first.settings = json.dumps({"retract": "sideways"})      # typed by hand: refused by name on showing it
    with pytest.raises(joblist.JobFileError, match=r"job list: 'a': settings.retract = 'sideways'"):
        joblist.show_row(scene, first)


def test_the_router_panels_show_for_their_rows_only(empty_scene):
    from kezuri.operators import panels

    scene = empty_scene
    samples.name_plate(scene)
    import types
    context = types.SimpleNamespace(scene=scene, active_object=None)
    for kind in ("profile", "pocket", "drill", "chamfer"):
        add_row(scene, kind, kind)
        shown = {c.bl_idname for c in panels.CLASSES if c.bl_idname.startswith("KEZURI_PT_joblist_")
                 and c.poll(context)}
        assert shown and all(name.startswith(f"KEZURI_PT_joblist_{kind}_") for name in shown), (kind, shown)


@pytest.mark.parametrize("language", ["en", "ja"])
def test_the_router_panels_fit_the_sidebar(empty_scene, language):
    """Every label, value and menu item of the four kinds' panels (all sub-panels open), in English
    and in Japanese, at Blender's default sidebar width (tests/sidebar_fit.py)."""
    import types

    import sidebar_fit as fit
    from kezuri.operators import panels, translations

    scene = empty_scene
    samples.name_plate(scene)
    context = types.SimpleNamespace(scene=scene, active_object=None)
    table = translations.TRANSLATIONS["ja_JP"] if language == "ja" else None
    for kind in ("profile", "pocket", "drill", "chamfer"):
        add_row(scene, kind, kind)
        classes = [c for c in panels.CLASSES if c.bl_idname.startswith("KEZURI_PT_joblist")]
        texts = fit.all_texts(classes, context, table)
        words = {t.text for t in texts}
        ja = translations.TRANSLATIONS["ja_JP"]
        tool = "Tool Number" if language == "en" else ja[("*", "Tool Number")]
        assert tool in words, kind                    # the kind's sub-panels were drawn
        assert not fit.too_wide(texts), "\n".join(fit.too_wide(texts))


# ----- the plate's own outline (no shape given) --------------------------------------------------------

SAMPLE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "samples", "jobs",
                      "nameplate-with-holes.toml")
CUT_OUT = '''
[[operations]]
kind = "profile"
name = "cut out"
{outline}
settings = {{ tool_number = 5, diameter = 6.0, flute_length = 25.0, tab_count = 4, lead = "none" }}
'''


def plate_cut(text, tmp_path):
    """The sample name-plate job with a profile appended, planned as batch plans it: the profile's
    feed points (x, y, z)."""
    from kezuri.operators import jobfile

    path = tmp_path / "job.toml"
    path.write_text(text)
    planned, _, _, _ = jobfile.plan_file(str(path))
    item = next(i for i in planned.planned if i.operation.name == "cut out")
    (op,) = item.part.operations
    return feed_points(op), planned


@pytest.mark.parametrize("outline", ["", 'outline = "plate"'])
def test_a_profile_without_a_shape_cuts_the_plate_out_offset_by_the_tool_radius_with_tabs(empty_scene, tmp_path,
                                                                                         outline):
    text = open(SAMPLE).read() + CUT_OUT.format(outline=outline)
    points, planned = plate_cut(text, tmp_path)
    # the sample's plate: 200 x 100 x 20 mm, work zero at its top centre; the 6 mm end mill's centre
    # runs 3 mm outside its rectangle (round corners of 3 mm), through to -20 - 0.3 (breakthrough)
    floor = points[:, 2].min()
    assert floor == pytest.approx(-20.3, abs=1e-6)
    at_depth = points[points[:, 2] < floor + 1e-6]
    assert len(at_depth) > 8
    assert np.abs(rounded_rect_distance(at_depth[:, :2], 100.0, 50.0, 0.0) - 3.0).max() < 0.01
    assert at_depth[:, 0].max() == pytest.approx(103.0, abs=0.01) and at_depth[:, 1].min() == pytest.approx(-53.0,
                                                                                                          abs=0.01)
    tabs = points[np.abs(points[:, 2] - (-20.0 + 3.0)) < 1e-6]      # the tabs' top: 3 mm above the bottom
    assert np.abs(rounded_rect_distance(tabs[:, :2], 100.0, 50.0, 0.0) - 3.0).max() < 0.01
    assert len(clusters(tabs[:, :2], 20.0)) == 4          # four tabs (each 8 mm + the 6 mm tool long)
    assert not [w for w in planned.warnings if "comes loose" in w]


def test_outline_takes_only_the_plate_and_not_beside_a_shape(empty_scene, tmp_path):
    from kezuri.operators.jobentry import JobFileError

    with pytest.raises(JobFileError, match=r"outline = 'Outline': the only outline a profile takes by name is "
                                           r"\"plate\""):
        plate_cut(open(SAMPLE).read() + CUT_OUT.format(outline='outline = "Outline"'), tmp_path)
    with pytest.raises(JobFileError, match="give objects.shape or outline = \"plate\", not both"):
        plate_cut(open(SAMPLE).read() + CUT_OUT.format(outline='outline = "plate"\nobjects = { shape = "Plate" }'),
                  tmp_path)


def test_a_new_profile_row_cuts_the_plate_out_with_four_tabs(empty_scene, tmp_path):
    scene = empty_scene
    samples.name_plate(scene)
    scene.kezuri.machine.post = "linuxcnc"
    row = add_row(scene, "profile", "cut out")
    assert scene.kezuri.profile.tab_count == 4 and row.objects[0].object is None
    scene.kezuri.profile.lead = "none"
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    (op,) = planned_ops(scene)["cut out"]
    points = feed_points(op)
    at_depth = points[points[:, 2] < points[:, 2].min() + 1e-6]
    assert np.abs(rounded_rect_distance(at_depth[:, :2], 100.0, 50.0, 0.0) - 3.0).max() < 0.01
    path = tmp_path / "cut.ngc"
    assert bpy.ops.kezuri.job_export(filepath=str(path), post="linuxcnc") == {"FINISHED"}
    text = path.read_text()
    assert "Z-20.3" in text and "Z-17." in text           # through, and over the tabs


def test_the_sample_plates_drilled_holes_chamfered_pass_the_gate_as_g3_arcs(empty_scene, tmp_path):
    """The name-plate job (engraving, four 5 mm holes drilled 12 mm deep) with the holes' edges
    chamfered 0.8 mm wide by the 90 deg V-bit: batch writes it (the gate clean over the whole job),
    the chamfer's moves are G3 circles of radius 2.5 - 0.2 tan(45 deg) = 2.3 mm, its tip at
    -(0.8 / tan(45 deg) + 0.2) = -1.0."""
    import contextlib
    import io

    import controller_rules
    import rs274
    from test_hostile_batch import BATCH

    holes = [[-90.0, -40.0, 5.0], [90.0, -40.0, 5.0], [90.0, 40.0, 5.0], [-90.0, 40.0, 5.0]]
    job = tmp_path / "chamfered.toml"
    job.write_text(open(SAMPLE).read() + '\n[[operations]]\nkind = "chamfer"\nname = "hole edges"\n'
                   f"holes = {json.dumps(holes)}\nsettings = {{ width = 0.8 }}\n")
    out = tmp_path / "out"
    with contextlib.redirect_stderr(io.StringIO()) as err, contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(["batch.py", "job", str(job), "--out", str(out)])
        except SystemExit as exit_:
            status = exit_.code
    assert status == 0, err.getvalue()[-2000:]
    text = open(json.loads(open(out / "report.json").read())["files"][0]).read()
    assert controller_rules.check(text, "linuxcnc") == []
    part = text[re.search(r"^T7 M0?6", text, re.M).start():]
    circles = re.findall(r"^G0?3 X(-?[\d.]+) Y(-?[\d.]+) Z(-?[\d.]+) I(-?[\d.]+) J(-?[\d.]+)", part, re.M) + \
        [(x, y, None, i, j) for x, y, i, j in re.findall(r"^G0?3 X(-?[\d.]+) Y(-?[\d.]+) I(-?[\d.]+) J(-?[\d.]+)",
                                                         part, re.M)]
    assert len(circles) >= 8
    for x, y, _, i, j in circles:
        assert math.hypot(float(i), float(j)) == pytest.approx(2.3, abs=1e-3)
        centre = (float(x) + float(i), float(y) + float(j))
        assert min(math.hypot(centre[0] - hx, centre[1] - hy) for hx, hy, _ in holes) < 1e-3
    if rs274.available():
        kinds, points, _ = rs274.motion_endpoints(rs274.run("G21 G90 G17\n" + part, tools=(7,)))
        assert points[:, 2].min() == pytest.approx(-1.0, abs=1e-4)
    assert os.path.exists(out / "setup-sheet.html")


def test_a_chamfer_row_chamfers_the_holes_of_a_curve_picked_in_its_holes_slot(empty_scene):
    """Circles of a curve (found as the drilling finds them: 6 mm across at X30 Y20 and X-30 Y20)."""
    scene = empty_scene
    samples.name_plate(scene)
    curve = bpy.data.curves.new("Holes", type="CURVE")
    for cx in (30.0, -30.0):
        spline = curve.splines.new("POLY")
        t = np.linspace(0.0, 2 * np.pi, 48, endpoint=False)
        spline.points.add(len(t) - 1)
        spline.points.foreach_set("co", np.column_stack([cx + 3.0 * np.cos(t), 20.0 + 3.0 * np.sin(t),
                                                         np.zeros_like(t), np.ones_like(t)]).ravel())
        spline.use_cyclic_u = True
    holes = bpy.data.objects.new("Holes", curve)
    scene.collection.objects.link(holes)
    row = add_row(scene, "chamfer", "hole edges")
    slot(row, "holes", holes)
    scene.kezuri.chamfer.width = 0.5
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    (op,) = planned_ops(scene)["hole edges"]
    arcs = np.isin(op.kind, (2, 3))
    centres = {(round(x, 3), round(y, 3)) for x, y in op.center[arcs, :2]}
    assert centres == {(30.0, 20.0), (-30.0, 20.0)}
    radii = np.hypot(op.xyz[arcs, 0] - op.center[arcs, 0], op.xyz[arcs, 1] - op.center[arcs, 1])
    # the circles' 48-gon fits a circle of radius ~3 mm; the axis 0.2 x tan(45 deg) inside it
    assert np.allclose(radii, radii[0]) and radii[0] == pytest.approx(3.0 - 0.2, abs=0.02)
    assert op.xyz[:, 2].min() == pytest.approx(-(0.5 + 0.2))


def test_the_panels_zero_values_mean_the_same_in_a_job_file(empty_scene, tmp_path):
    """depth = 0 is a cut through (as no depth), rest_diameter = 0 no rest machining: what the
    panel's default values write is what a job file means by them."""
    base = open(SAMPLE).read() + CUT_OUT.format(outline="")
    through, _ = plate_cut(base, tmp_path)
    zero, _ = plate_cut(base.replace("tab_count = 4,", "tab_count = 4, depth = 0,"), tmp_path)
    assert np.array_equal(through, zero)
    pocket = ('\n[[operations]]\nkind = "pocket"\nname = "letters"\nobjects = { region = "Letters" }\n'
              "settings = { depth = 1.0, diameter = 3.0, stepover = 1.2, rest_diameter = 0.0, rest_tool_number = 0 }\n")
    from kezuri.operators import jobfile
    path = tmp_path / "pocket.toml"
    path.write_text(open(SAMPLE).read() + pocket)
    planned, _, _, _ = jobfile.plan_file(str(path))
    item = next(i for i in planned.planned if i.operation.name == "letters")
    assert [op.tool.number for op in item.part.operations] == [5]          # no rest machining operation
