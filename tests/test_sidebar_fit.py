"""The CAM tab at Blender's default sidebar width: the job picker shows one workflow's panels,
and every label, value, menu item and list row fits, in English and in Japanese.

Widths are measured with ``blf.dimensions`` in Blender's UI font at 11 pt (tests/sidebar_fit.py
has the geometry and where each number comes from in Blender's source).  The model is checked
against what the real Blender 4.3 window showed at its default width (docs/screenshots of the
issue #21 run): the texts it cut there must come out too wide here, the ones it showed whole
must fit.
"""
import os
import types

import pytest

bpy = pytest.importorskip("bpy")

import sidebar_fit as fit  # noqa: E402
from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from kezuri.operators import panels, samples, translations, workflows  # noqa: E402
from kezuri.operators.stepnc import fill_workplan_list  # noqa: E402
from kezuri.toolpath.operations import stepnc  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
JA = translations.TRANSLATIONS["ja_JP"]
LANGUAGES = {"en": None, "ja": JA}


def test_font_is_blenders_ui_font_at_11_points():
    # "Unfold Twisted Quad" measured 113 px on the Blender 4.3 screenshot (its centred button text).
    assert abs(fit.text_width("Unfold Twisted Quad") - 113) <= 2
    # Japanese comes from the CJK fallback: full-width glyphs, 11 px each at 11 pt.
    assert fit.text_width("ニブリングピッチ") == pytest.approx(8 * 11, abs=2)


def test_layout_width_from_blenders_constants():
    assert fit.layout_width() == 280 - 20 - 2 * 8 - 2 * 8 == 228


def test_model_agrees_with_the_real_window():
    """Blender 4.3 at its default sidebar width, property split with decorators: "Sheet Thick..."
    and "Preferences Def..." were cut, "Nibbling Pitch", "Tool Diameter" and "Horizontal (YR)"
    were not, and "Corners from S..." was cut in a two-button row."""
    width = fit.layout_width()
    split = width - fit.UNIT                                   # the decorator column
    name_room = split * fit.SPLIT - fit.PAD
    menu_room = split * (1 - fit.SPLIT) - fit.PAD - fit.UNIT
    button_room = width / 2 - 2 * fit.PAD - fit.UNIT
    assert fit.text_width("Sheet Thickness") > name_room
    assert fit.text_width("Nibbling Pitch") <= name_room
    assert fit.text_width("Tool Diameter") <= name_room
    assert fit.text_width("Preferences Default") > menu_room
    assert fit.text_width("Horizontal (YR)") <= menu_room
    assert fit.text_width("Corners from Selected Face") > button_room
    assert fit.text_width("CDL") <= button_room


def test_job_picker_lists_the_workflow_table_once(empty_scene):
    keys = [item.identifier for item in empty_scene.kezuri.bl_rna.properties["job"].enum_items]
    assert keys == [w.key for w in workflows.WORKFLOWS if w.classes]
    assert len(keys) == len(set(keys))


def test_the_picked_job_is_saved_with_the_file(empty_scene, tmp_path):
    empty_scene.kezuri.job = "STEPNC"
    path = str(tmp_path / "job.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    empty_scene.kezuri.job = "CARVE"
    bpy.ops.wm.open_mainfile(filepath=path)
    assert bpy.context.scene.kezuri.job == "STEPNC"
    bpy.context.scene.kezuri.job = "ENGRAVE"


def shown_panels(scene, key):
    scene.kezuri.job = key
    context = types.SimpleNamespace(scene=scene, active_object=None)
    shown = set()
    for cls in panels.CLASSES:
        parent = getattr(cls, "bl_parent_id", "")
        if (not parent or parent in shown) and cls.poll(context):
            shown.add(cls.bl_idname)
    return shown


def test_each_job_shows_only_its_panels(empty_scene):
    own = {"ENGRAVE": "KEZURI_PT_engrave", "ROTARY": "KEZURI_PT_rotary", "STEPNC": "KEZURI_PT_stepnc",
           "TURNMILL": "KEZURI_PT_turnmill", "SHEET": "KEZURI_PT_sheet", "CARVE": "KEZURI_PT_carve"}
    for key, panel in own.items():
        shown = shown_panels(empty_scene, key)
        assert {"KEZURI_PT_job", "KEZURI_PT_machine", panel} <= shown
        assert not (set(own.values()) - {panel}) & shown, key
        has_simulation = workflows.workflow_of(key).simulation is not None
        assert ("KEZURI_PT_simulate" in shown) == has_simulation


def filled_scene(scene, tmp_path):
    """Every branch of the panels drawn: a workplan in the list, findings, a pocket selected."""
    samples.rotary_block(scene)
    path = os.path.join(HERE, "fixtures", "iso14649", "ex1.stp")
    fill_workplan_list(scene, path, stepnc.load_workplan(path))
    findings = scene.kezuri.simulation.findings
    for kind, move in (("gouge", 1234), ("rapid_in_material", 56), ("plunge", 7), ("spindle_stopped", 9999),
                       ("travel", 120)):
        finding = findings.add()
        finding.kind, finding.move, finding.blocking = kind, move, True
        finding.message = f"{kind}: a long message that only the tooltip shows in full, move {move}"
    pocket = next(o for o in scene.objects if o.kezuri_pocket.enabled)
    pocket.kezuri_pocket.bottom = "sphere"
    return types.SimpleNamespace(scene=scene, active_object=pocket)


@pytest.mark.parametrize("language", sorted(LANGUAGES))
def test_every_text_fits_the_default_sidebar(empty_scene, tmp_path, language):
    context = filled_scene(empty_scene, tmp_path)
    measured, failures = 0, []
    for key, *_ in workflows.job_items():
        empty_scene.kezuri.job = key
        texts = fit.all_texts(panels.CLASSES, context, LANGUAGES[language])
        measured += len(texts)
        failures += [f"{key}: {line}" for line in fit.too_wide(texts)]
    assert measured > 300
    assert not failures, "\n".join(failures)


def test_workingstep_rows_say_feature_operation_tool(empty_scene, tmp_path):
    context = filled_scene(empty_scene, tmp_path)
    steps = context.scene.kezuri.stepnc.steps
    rows = [(s.feature_name, s.step, s.tool) for s in steps]
    assert len(rows) == len({(s.ident) for s in steps}) >= 2
    # ex1.stp (ISO 14649-11 example 1): planar face, then pocket and holes; every row names its tool
    assert all(tool.startswith("T") and "Ø" in tool for _, _, tool in rows)
    assert {step for _, step, _ in rows} <= set(stepnc_words())
    assert len({row for row in rows}) == len(rows)      # no two rows read the same


def stepnc_words():
    from kezuri.operators.stepnc import STEP_WORDS
    return STEP_WORDS.values()


def test_a_text_too_wide_is_reported(empty_scene):
    """The check fails on truncation: a label made too long is caught with its place and width."""
    layout = fit.Layout()
    layout.label(text="Pockets: outline objects marked as pockets, on the stock")
    walk = fit.Walk(fit.Translator(None), None, fit.layout_width())
    walk.node(layout._node, fit.layout_width(), "test")
    problems = fit.too_wide(walk.texts)
    assert len(problems) == 1 and "has 220 px" in problems[0]


@pytest.mark.parametrize("language", sorted(LANGUAGES))
def test_the_machine_settings_fit_when_a_preset_is_picked(empty_scene, tmp_path, language):
    """Picking a machine preset shows its settings (travel, reach, retract, tool change, limits)."""
    context = filled_scene(empty_scene, tmp_path)
    machine = empty_scene.kezuri.machine
    machine.preset = "linuxcnc-manual"
    assert (machine.z_reach, machine.clearance_height, machine.retract) == (80.0, 20.0, "machine")  # filled in
    texts = fit.all_texts([panels.KEZURI_PT_machine], context, LANGUAGES[language])
    shown = {t.text for t in texts}
    for name in ("Travel X", "Z Reach", "Clearance Height", "Retract", "Machine Top Z", "Tool Change", "M6 Lifts Z",
                 "Max Spindle", "Max Feed"):
        assert (JA.get(("*", name), name) if language == "ja" else name) in shown, name
    assert not fit.too_wide(texts), "\n".join(fit.too_wide(texts))
    machine.preset = "POST"
