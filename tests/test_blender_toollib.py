"""The CAM tab's Tool Library panel: its operators on a library file of the test's own
(KEZURI_TOOL_LIBRARY), and every text of the panel fitting the default sidebar in English and
Japanese."""
import os
import types

import pytest

bpy = pytest.importorskip("bpy")

import sidebar_fit as fit  # noqa: E402
from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from kezuri.operators import toollib, translations  # noqa: E402
from kezuri.toolpath.tooling import formats, store  # noqa: E402

FIXTURES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fixtures", "tools")
JA = translations.TRANSLATIONS["ja_JP"]


@pytest.fixture
def library(tmp_path, monkeypatch, empty_scene):
    path = tmp_path / "tools.toml"
    monkeypatch.setenv("KEZURI_TOOL_LIBRARY", str(path))
    bpy.context.window_manager.kezuri_tool_library.loaded = False
    return path


def rows():
    return bpy.context.window_manager.kezuri_tool_library.tools


def fixture_library():
    """The library panel loaded with the Kezuri-format fixture: (its state, the tool numbers in row order)."""
    bpy.ops.kezuri.toollib_load()
    assert bpy.ops.kezuri.toollib_import(filepath=os.path.join(FIXTURES, "kezuri-tools.toml"),
                                         replace=True) == {"FINISHED"}
    return bpy.context.window_manager.kezuri_tool_library, [r.number for r in rows()]


def test_load_edit_save_add_remove(library):
    assert bpy.ops.kezuri.toollib_load() == {"FINISHED"}
    assert [r.number for r in rows()] == list(range(1, 12))
    state = bpy.context.window_manager.kezuri_tool_library
    state.index = 1
    row = rows()[1]
    assert (row.kind, row.diameter, row.stick_out) == ("ball", 6.0, 30.0)
    row.diameter, row.stick_out, row.vendor = 6.35, 27.5, "Example Tools"
    assert bpy.ops.kezuri.toollib_save() == {"FINISHED"}
    saved, _ = formats.read_path(str(library))
    t2 = saved.get(2)
    assert (t2.diameter, t2.corner_radius, t2.stick_out, t2.vendor) == (6.35, 3.175, 27.5, "Example Tools")
    assert os.path.exists(f"{library}.bak1")

    assert bpy.ops.kezuri.toollib_add() == {"FINISHED"}
    assert rows()[state.index].number == 12 and formats.read_path(str(library))[0].get(12).kind == "flat"
    assert bpy.ops.kezuri.toollib_remove() == {"FINISHED"}
    assert 12 not in formats.read_path(str(library))[0].numbers()


def test_a_row_that_is_no_tool_is_refused_and_nothing_written(library):
    bpy.ops.kezuri.toollib_load()
    before = library.read_text()
    row = rows()[0]
    row.kind, row.corner_radius = "bull", 4.0               # R4 on a 6 mm end mill
    with pytest.raises(RuntimeError, match=r"T1: corner_radius 4 mm must be above 0 and at most the radius 3"):
        bpy.ops.kezuri.toollib_save()
    assert library.read_text() == before


def test_import_and_export(library, tmp_path):
    bpy.ops.kezuri.toollib_load()
    with pytest.raises(RuntimeError, match="already in the library"):
        bpy.ops.kezuri.toollib_import(filepath=os.path.join(FIXTURES, "fusion-library.json"))
    assert bpy.ops.kezuri.toollib_import(filepath=os.path.join(FIXTURES, "fusion-library.json"),
                                         replace=True) == {"FINISHED"}
    assert [r.number for r in rows()] == [*range(1, 12), 14, 21]
    assert rows()[7].angle == pytest.approx(60.0) and rows()[7].name == "60 degree V groove"
    out = tmp_path / "shop.json"
    assert bpy.ops.kezuri.toollib_export(filepath=str(out)) == {"FINISHED"}
    assert formats.read_path(str(out))[0] == store.load(str(library))


@pytest.mark.parametrize("language", ["en", "ja"])
def test_every_text_of_the_panel_fits(library, language):
    bpy.ops.kezuri.toollib_load()
    bpy.ops.kezuri.toollib_import(filepath=os.path.join(FIXTURES, "kezuri-tools.toml"), replace=True)
    state = bpy.context.window_manager.kezuri_tool_library
    context = types.SimpleNamespace(scene=bpy.context.scene, window_manager=bpy.context.window_manager,
                                    active_object=None)
    table = JA if language == "ja" else None
    measured, failures = 0, []
    bpy.context.scene.kezuri.job = "ENGRAVE"              # its "Use for" buttons shown too
    for index, row in enumerate(rows()):                    # every kind's fields (bull: corner, V-bit: angle)
        state.index = index
        texts = fit.all_texts([toollib.KEZURI_PT_toollib], context, table)
        measured += len(texts)
        failures += fit.too_wide(texts)
    state.loaded, state.error = False, "x.toml: line 3: not TOML"
    failures += fit.too_wide(fit.all_texts([toollib.KEZURI_PT_toollib], context, table))
    state.error = ""
    assert measured > 200
    assert not failures, "\n".join(sorted(set(failures)))


def test_a_library_tool_goes_on_the_picked_jobs_panel(library):
    scene = bpy.context.scene
    state, numbers = fixture_library()
    scene.kezuri.job = "ENGRAVE"
    state.index = numbers.index(2)                          # 6 mm ball: the engraving's roughing ball
    assert bpy.ops.kezuri.toollib_use(slot="rough") == {"FINISHED"}
    state.index = numbers.index(3)                          # 1 mm flat: its band finishing
    assert bpy.ops.kezuri.toollib_use(slot="finish") == {"FINISHED"}
    engrave = scene.kezuri.engrave
    assert (engrave.rough_tool_number, engrave.rough_diameter) == (2, 6.0)
    assert (engrave.finish_tool_number, engrave.finish_diameter) == (3, 1.0)
    with pytest.raises(RuntimeError, match="the engrave's rough tool must be a ball end mill"):
        bpy.ops.kezuri.toollib_use(slot="rough")            # the 1 mm flat is no roughing ball
    scene.kezuri.job = "CARVE"
    state.index = numbers.index(14)                         # a bull nose: no carving slot takes it
    layout = fit.Layout()
    toollib.draw_library(layout, types.SimpleNamespace(scene=scene, window_manager=bpy.context.window_manager))
    walk = fit.Walk(fit.Translator(None), None, fit.layout_width())
    walk.node(layout._node, fit.layout_width(), "panel")
    assert not any("Use for" in t.text for t in walk.texts)
    state.index = numbers.index(2)
    assert bpy.ops.kezuri.toollib_use(slot="finish") == {"FINISHED"}
    assert (scene.kezuri.carve.finish_tool_number, scene.kezuri.carve.finish_diameter) == (2, 6.0)


def test_the_startup_read_loads_or_says_why(library):
    state = bpy.context.window_manager.kezuri_tool_library
    assert toollib.load_when_ready() is None and state.loaded and len(rows()) == 11
    library.write_text(library.read_text()[:-25])
    state.loaded = False
    toollib.load_when_ready()
    assert not state.loaded and "cannot be read, and is left as it is" in state.error


def test_the_library_lives_in_blenders_config_folder(monkeypatch, empty_scene):
    """Outside the extension's folder (removing the add-on keeps it); asking where it is writes nothing."""
    from kezuri.operators import toolstore

    monkeypatch.delenv("KEZURI_TOOL_LIBRARY", raising=False)
    path = toolstore.library_path()
    assert path == os.path.join(bpy.utils.user_resource("CONFIG"), "kezuri", "tools.toml")
    assert not os.path.dirname(os.path.abspath(toollib.__file__)) in path
    existed = os.path.exists(os.path.dirname(path))
    toolstore.stick_outs([{"tool_number": 2, "tool_kind": "ball", "tool_diameter_mm": 6.0}])
    assert os.path.exists(os.path.dirname(path)) == existed


def test_import_and_export_keep_the_edits_on_screen(library, tmp_path):
    bpy.ops.kezuri.toollib_load()
    rows()[4].stick_out = 36.0                              # T5 edited, not saved
    bpy.ops.kezuri.toollib_import(filepath=os.path.join(FIXTURES, "shop-inch.tbl"), units="inch", replace=True)
    saved = store.load(str(library))
    assert saved.get(1).diameter == pytest.approx(6.35) and saved.get(2).kind == "ball"    # the table's T1, T2
    assert saved.get(5).stick_out == 36.0 and rows()[4].stick_out == 36.0                # the edit kept
    rows()[4].stick_out = 37.5
    bpy.ops.kezuri.toollib_export(filepath=str(tmp_path / "out.toml"))
    assert formats.read_path(str(tmp_path / "out.toml"))[0].get(5).stick_out == 37.5    # as shown


def test_saving_keeps_the_numbers_of_the_rows_not_edited(library):
    """A row holds 6 digits (a float32 property): a tool not edited is saved as the file had it."""
    bpy.ops.kezuri.toollib_load()
    bpy.ops.kezuri.toollib_import(filepath=os.path.join(FIXTURES, "fusion-library.json"), replace=True)
    exact = store.load(str(library)).get(21).flute_length           # 0.75 in = 19.049999999999997 mm
    assert exact != 19.05
    rows()[0].stick_out = 31.0
    bpy.ops.kezuri.toollib_save()
    saved = store.load(str(library))
    assert saved.get(21).flute_length == exact and saved.get(1).stick_out == 31.0


def test_a_library_tool_goes_on_the_job_lists_selected_row(library):
    """A V-carve row in the job list takes the 30 deg engraver (T17) as its V-bit and the 1 mm flat
    (T3) as its clearing end mill: the row's panel group and its saved settings say so; the
    row buttons fit the sidebar in English and Japanese."""
    import json

    scene = bpy.context.scene
    state, numbers = fixture_library()
    scene.kezuri.job = "ENGRAVE"
    assert bpy.ops.kezuri.job_add(kind="vcarve") == {"FINISHED"}
    state.index = numbers.index(17)
    assert bpy.ops.kezuri.toollib_use(slot="tool", row=True) == {"FINISHED"}
    state.index = numbers.index(3)
    assert bpy.ops.kezuri.toollib_use(slot="clear", row=True) == {"FINISHED"}
    vcarve = scene.kezuri.vcarve
    assert (vcarve.tool_number, vcarve.angle, vcarve.clear_tool_number, vcarve.clear_diameter) == (17, 30.0, 3, 1.0)
    row = scene.kezuri.job_list.rows[scene.kezuri.job_list.active]
    saved = json.loads(row.settings)
    assert (saved["tool_number"], saved["angle"], saved["clear_tool_number"], saved["clear_diameter"]) == (17, 30.0, 3, 1.0)
    with pytest.raises(RuntimeError, match="must be a V-bit or engraver"):
        bpy.ops.kezuri.toollib_use(slot="tool", row=True)       # the 1 mm flat is no V-bit
    context = types.SimpleNamespace(scene=scene, window_manager=bpy.context.window_manager, active_object=None)
    for table in (None, JA):
        texts = fit.all_texts([toollib.KEZURI_PT_toollib], context, table)
        assert any("Use for Clearing" in t.text or "底の除去に使用" in t.text for t in texts)
        assert not fit.too_wide(texts)
