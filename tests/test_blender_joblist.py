"""The CAM tab's job list (issue 28, deliverables 3 and 4): the name-plate sample as a job of an
engraving and a drilling, planned, changed, exported, saved as a job file and run in batch.

Programs are read as text (tool changes by regex, drill depths from the Z words after the
drill's tool change); the batch run of the saved file is ``batch.py job`` in-process, as a user
runs it."""
import contextlib
import io
import json
import os
import re

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

import controller_rules  # noqa: E402
import sidebar_fit as fit  # noqa: E402
from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from test_hostile_batch import BATCH  # noqa: E402
from kezuri.operators import joblist, samples, translations  # noqa: E402
from kezuri.toolpath.job import plan_job  # noqa: E402

HOLES = [[-90.0, -40.0], [90.0, -40.0], [90.0, 40.0], [-90.0, 40.0]]
DRILL = {"tool_number": 4, "diameter": 5.0, "depth": 12.0, "peck": 3.0, "rpm": 3000, "feed": 150}


@pytest.fixture
def plate_job(empty_scene):
    """The name plate with an engraving (seed 7) and four mounting holes, linuxcnc post."""
    scene = empty_scene
    samples.name_plate(scene)
    scene.kezuri.machine.post = "linuxcnc"
    assert bpy.ops.kezuri.job_add(kind="engrave") == {"FINISHED"}
    assert bpy.ops.kezuri.job_add(kind="drill") == {"FINISHED"}
    rows = scene.kezuri.job_list.rows
    rows[1].name = "holes"
    rows[1].extra = json.dumps({"holes": HOLES})
    rows[1].settings = json.dumps(DRILL)
    scene.kezuri.job_list.active = 0          # the engraving's settings into the Engrave panel's group
    scene.kezuri.engrave.seed = 7             # edited in the panel: the row's
    return scene


def tool_changes(text: str) -> list:
    return [int(n) for n in re.findall(r"^T(\d+) M0?6", text, re.M)]


def drill_bottoms(text: str) -> float:
    """The lowest Z word after the drill's tool change (T4)."""
    part = text[re.search(r"^T4 M0?6", text, re.M).start():]
    return min(float(z) for z in re.findall(r"Z(-?\d+\.?\d*)", part))


def export(scene, path, capfd=None) -> tuple:
    """Export Job through the operator: (the NC text, what it reported)."""
    if capfd is not None:
        capfd.readouterr()
    assert bpy.ops.kezuri.job_export(filepath=str(path), post="linuxcnc") == {"FINISHED"}
    said = capfd.readouterr().out if capfd is not None else ""
    return open(path, encoding="utf-8").read(), said


def test_generate_plans_every_row_with_its_tools(plate_job):
    scene = plate_job
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    rows = scene.kezuri.job_list.rows
    assert [(r.name, r.state, r.tools) for r in rows] == [("engraving", "PLANNED", "T2 T3"), ("holes", "PLANNED", "T4")]
    assert rows[0].minutes > 1.0 and 0.0 < rows[1].minutes < rows[0].minutes
    assert json.loads(rows[0].settings) == {"seed": 7}             # the panel's edit is the row's
    shown = sorted(o.name for o in scene.objects if o.name.startswith(joblist.PREFIX)
                   and not o.name.endswith((" plunges", " links", " rapids")))     # the cuts, one per operation
    assert shown == ["Kezuri Job engraving: band finishing", "Kezuri Job engraving: burr contour",
                     "Kezuri Job engraving: roughing (gouge texture)"]
    drill = scene.objects["Kezuri Job holes: drill plunges"]      # a drill only plunges: no cut object
    xs = sorted({round(p.co.x) for spline in drill.data.splines for p in spline.points})
    assert xs[0] == -90 and xs[-1] == 90          # the holes where they were given (work = world here)


def test_changing_the_drill_stales_only_it_and_export_replans_only_it_as_batch_writes(plate_job, tmp_path, capfd):
    scene = plate_job
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    rows = scene.kezuri.job_list.rows
    scene.kezuri.job_list.active = 1
    scene.kezuri.drill.depth = 9.0              # edited in the drilling's panel (the shown row's settings)
    assert [joblist.shown_state(scene, r) for r in rows] == ["PLANNED", "STALE"]
    scene.kezuri.job_list.active = 0
    scene.kezuri.engrave.seed = 8               # the engraving edited in its panel: both stale (the chain)
    assert [joblist.shown_state(scene, r) for r in rows] == ["STALE", "STALE"]
    scene.kezuri.engrave.seed = 7
    assert [joblist.shown_state(scene, r) for r in rows] == ["PLANNED", "STALE"]
    job, _, _ = joblist.build(scene)
    assert joblist.stale_names(scene, job) == ["holes"]
    text, said = export(scene, tmp_path / "plate.ngc", capfd)
    assert "re-planned: holes" in said and "engraving" not in said.split("re-planned:")[1].splitlines()[0]
    assert drill_bottoms(text) == pytest.approx(-9.0)
    assert tool_changes(text) == [2, 3, 2, 4]
    assert controller_rules.check(text, "linuxcnc") == []
    assert [r.state for r in rows] == ["PLANNED", "PLANNED"]
    again, said = export(scene, tmp_path / "again.ngc", capfd)
    assert "nothing re-planned" in said and again == text

    # saved from the panel, run by batch.py job: the same program, byte for byte
    blend, toml = tmp_path / "plate.blend", tmp_path / "plate.toml"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    assert bpy.ops.kezuri.job_save(filepath=str(toml)) == {"FINISHED"}
    saved = open(toml, encoding="utf-8").read()
    assert 'blend = "plate.blend"' in saved and "depth = 9.0" in saved and "seed = 7" in saved
    out = tmp_path / "out"
    with contextlib.redirect_stderr(io.StringIO()) as err, contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(["batch.py", "job", str(toml), "--out", str(out)])
        except SystemExit as exit_:
            status = exit_.code
    assert status == 0, err.getvalue()[-2000:]
    report = json.loads(open(out / "report.json").read())
    batch_text = open(report["files"][0], "rb").read()
    assert batch_text == open(tmp_path / "plate.ngc", "rb").read()


def test_a_loaded_job_file_plans_as_the_file_in_batch(plate_job, tmp_path):
    """Load Job File: the sample job's rows, with their objects found by name, and the same program
    as ``batch.py job`` writes from that file."""
    scene = plate_job
    path = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "samples", "jobs",
                        "nameplate-with-holes.toml")
    assert bpy.ops.kezuri.job_load(filepath=path) == {"FINISHED"}
    rows = scene.kezuri.job_list.rows
    assert [(r.name, r.kind) for r in rows] == [("texture and letters", "engrave"), ("mounting holes", "drill")]
    assert {i.slot: i.object.name for i in rows[0].objects} == {"plate": "Plate", "letters": "Letters"}
    assert json.loads(rows[1].extra) == {"holes": HOLES} and json.loads(rows[1].settings)["depth"] == 12
    assert scene.kezuri.engrave.seed == 7         # the selected row's settings in its panel
    text, _ = export(scene, tmp_path / "loaded.ngc")
    assert tool_changes(text) == [2, 3, 2, 4] and drill_bottoms(text) == pytest.approx(-12.0)


def test_duplicate_and_reorder_change_the_programs_order(plate_job, tmp_path):
    scene = plate_job
    listed = scene.kezuri.job_list
    listed.active = 1
    assert bpy.ops.kezuri.job_duplicate() == {"FINISHED"}
    assert [r.name for r in listed.rows] == ["engraving", "holes", "holes 2"] and listed.active == 2
    listed.rows[2].settings = json.dumps({**DRILL, "tool_number": 5, "diameter": 3.0, "depth": 6.0})
    planned = plan_job(joblist.build(scene)[0])
    assert joblist.operation_rows(planned) == ["engraving"] * 3 + ["holes", "holes 2"]
    assert bpy.ops.kezuri.job_move(direction="UP") == {"FINISHED"}
    assert bpy.ops.kezuri.job_move(direction="UP") == {"FINISHED"}
    assert [r.name for r in listed.rows] == ["holes 2", "engraving", "holes"] and listed.active == 0
    text, _ = export(scene, tmp_path / "reordered.ngc")
    assert tool_changes(text) == [5, 2, 3, 2, 4]
    listed.rows[1].enabled = False              # switched off: left out of the program
    text, _ = export(scene, tmp_path / "off.ngc")
    assert tool_changes(text) == [5, 4]


def test_simulate_up_to_the_first_row_cuts_only_its_operations(plate_job):
    scene = plate_job
    assert bpy.ops.kezuri.job_simulate(upto=False) == {"FINISHED"}

    def deepest_at_holes() -> float:
        stock = next(o for o in scene.objects if o.name.startswith("Kezuri Simulated"))
        points = np.array([v.co[:] for v in stock.data.vertices])
        near = np.min([np.hypot(points[:, 0] - x, points[:, 1] - y) for x, y in HOLES], axis=0) < 1.0
        return float(points[near, 2].min())
    assert deepest_at_holes() == pytest.approx(-12.0, abs=0.2)
    whole = scene.kezuri.job_list.rows[1].state
    scene.kezuri.job_list.active = 0
    assert bpy.ops.kezuri.job_simulate(upto=True) == {"FINISHED"}
    assert -3.0 < deepest_at_holes() < 0.0        # only the engraving's texture: no hole
    assert whole in {"PLANNED", "FINDINGS"}


def test_errors_are_reported_not_raised_out_of_the_operators(plate_job, tmp_path):
    scene = plate_job
    if not bpy.data.filepath:            # (once a test has saved a .blend this session, it is saved)
        with pytest.raises(RuntimeError, match="save the .blend first"):
            bpy.ops.kezuri.job_save(filepath=str(tmp_path / "unsaved.toml"))
        assert not (tmp_path / "unsaved.toml").exists()
    scene.kezuri.job_list.rows[1].extra = json.dumps({"holes": []})
    with pytest.raises(RuntimeError, match="holes"):       # bpy.ops turns an ERROR report into RuntimeError
        bpy.ops.kezuri.job_generate()
    assert [r.state for r in scene.kezuri.job_list.rows] == ["NEW", "FAILED"]
    scene.kezuri.job_list.rows[1].settings = "{depth: 3"
    with pytest.raises(RuntimeError, match="settings is not JSON"):
        bpy.ops.kezuri.job_generate()
    bad = tmp_path / "bad.toml"
    bad.write_text('[[operations]]\nkind = "engrave"\nname = "a"\nobjects = { plate = "Plate" }\n\n'
                   '[[operations]]\nkind = "engrave"\nname = "b"\nobjects = { plate = "No Such Plate" }\n')
    with pytest.raises(RuntimeError, match="No Such Plate"):
        bpy.ops.kezuri.job_load(filepath=str(bad))
    assert [r.name for r in scene.kezuri.job_list.rows] == ["engraving", "holes"]     # the list as it was
    scene.kezuri.job_list.rows.clear()
    assert not bpy.ops.kezuri.job_generate.poll()


def test_remove_and_every_job_operator_that_changes_the_scene_can_be_undone(plate_job):
    """bpy.ops.ed.undo needs a window, which the bpy wheel has not (its poll fails): so this checks
    that every job-list operator that changes the scene pushes an undo step (UNDO in bl_options)."""
    scene = plate_job
    assert bpy.ops.kezuri.job_remove() == {"FINISHED"}
    assert [r.name for r in scene.kezuri.job_list.rows] == ["holes"]
    assert not bpy.ops.ed.undo.poll()
    for cls in joblist.CLASSES:
        if issubclass(cls, bpy.types.Operator):
            assert "UNDO" in cls.bl_options, cls.__name__


@pytest.mark.parametrize("language", ["en", "ja"])
def test_the_job_panel_fits_the_sidebar(plate_job, language):
    from kezuri.operators import panels

    scene = plate_job
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    import types
    context = types.SimpleNamespace(scene=scene, active_object=None)
    table = translations.TRANSLATIONS["ja_JP"] if language == "ja" else None
    for active in (0, 1):
        scene.kezuri.job_list.active = active
        classes = [c for c in panels.CLASSES if c.bl_idname.startswith("KEZURI_PT_joblist")]
        texts = fit.all_texts(classes, context, table)
        assert len(texts) > (20 if active == 0 else 5)
        assert not fit.too_wide(texts), "\n".join(fit.too_wide(texts))


def test_the_scene_material_flags_the_feeds_in_the_job_list_and_goes_into_the_saved_file(plate_job, tmp_path, capfd):
    """Machine & Stock's Material: Generate counts each row's feeds flags and reports them; the
    drill's 150 mm/min at 3000 rpm (0.025 mm per tooth) rubs in hardwood; the saved job file names the
    material; Export writes the program and reports the same warnings."""
    scene = plate_job
    scene.kezuri.stock.material = "hardwood"
    capfd.readouterr()
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    said = capfd.readouterr().out
    rows = scene.kezuri.job_list.rows
    assert rows[1].state == "FINDINGS" and rows[1].findings >= 1
    assert "feeds: operation" in said and "below the safe band" in said
    text, said = export(scene, tmp_path / "plate.ngc", capfd)
    assert tool_changes(text) and "below the safe band" in said
    scene.kezuri.stock.material = "NONE"
    capfd.readouterr()
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    assert "feeds: operation" not in capfd.readouterr().out and rows[1].findings == 0


def test_a_saved_job_file_names_the_material_and_loads_it_back(plate_job, tmp_path):
    scene = plate_job
    scene.kezuri.stock.material = "mdf"
    blend, toml = tmp_path / "plate.blend", tmp_path / "plate.toml"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    assert bpy.ops.kezuri.job_save(filepath=str(toml)) == {"FINISHED"}
    assert 'material = "mdf"' in toml.read_text(encoding="utf-8").splitlines()
    scene.kezuri.stock.material = "NONE"
    assert bpy.ops.kezuri.job_load(filepath=str(toml)) == {"FINISHED"}
    assert scene.kezuri.stock.material == "mdf"
