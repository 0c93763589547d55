"""One tool library: the add-on preferences' old tool list (kept registered so old preference files
load) moves into tools.toml once, and the Engrave panel's Tool Library menu takes its tools from
tools.toml.  Real bpy: the preferences are the registered KezuriPreferences of an add-on entry, their
``tools`` filled as an old userpref.blend holds them; the file is read back by the library's reader."""
import os
import types

import pytest

bpy = pytest.importorskip("bpy")

import sidebar_fit as fit  # noqa: E402
from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from kezuri.operators import oldtools, preferences, toolmenu, translations  # noqa: E402
from kezuri.toolpath.tooling import formats, store  # noqa: E402
from kezuri.toolpath.tooling.library import LibraryTool, ToolLibrary  # noqa: E402

JA = translations.TRANSLATIONS["ja_JP"]


@pytest.fixture
def prefs(empty_scene, tmp_path, monkeypatch):
    """The extension's preferences as Blender gives them to an enabled add-on; removed afterwards
    (the other tests run with no add-on entry)."""
    monkeypatch.setenv("KEZURI_TOOL_LIBRARY", str(tmp_path / "tools.toml"))
    bpy.context.window_manager.kezuri_tool_library.loaded = False
    addons = bpy.context.preferences.addons
    addon = addons.new()
    addon.module = preferences.ADDON_ID
    yield addons[preferences.ADDON_ID].preferences
    addons.remove(addons[preferences.ADDON_ID])


def old_tool(prefs, name, number, kind, diameter, corner_radius=0.0, flute_length=20.0):
    tool = prefs.tools.add()          # as the old Add Tool left it: the fields typed, the others at their defaults
    tool.name, tool.number, tool.kind, tool.diameter = name, number, kind, diameter
    tool.corner_radius, tool.flute_length = corner_radius, flute_length
    return tool


SHOP = ToolLibrary([LibraryTool(1, "flat", 6.0, flute_length=22.0, name="shop 6 mm"),
                    LibraryTool(5, "ball", 3.0, flute_length=12.0, name="3 mm ball")])


def fill_old_list(prefs):
    old_tool(prefs, "8 mm ball", 17, "ball", 8.0, flute_length=25.0)        # new: moved
    old_tool(prefs, "Shop flat", 1, "flat", 6.35)                            # T1 is another tool: kept out
    old_tool(prefs, "3 mm ball", 5, "ball", 3.0, flute_length=12.0)          # the same tool: there already
    old_tool(prefs, "Bull", 20, "bull", 10.0, corner_radius=1.5, flute_length=30.0)
    old_tool(prefs, "V 90", 21, "vbit", 12.0, flute_length=10.0)             # the old list had no angle
    old_tool(prefs, "Broken", 22, "ball", 0.0)                               # no tool: named, not moved


def test_the_old_list_moves_into_the_library_once(prefs, tmp_path):
    path = tmp_path / "tools.toml"
    store.save(str(path), SHOP)
    fill_old_list(prefs)
    assert len(prefs.tools) == 6

    infos, warnings = oldtools.move_old_tools(prefs.tools, str(path))

    library, _ = formats.read_path(str(path))
    assert library == ToolLibrary([
        LibraryTool(1, "flat", 6.0, flute_length=22.0, name="shop 6 mm"),            # not overwritten
        LibraryTool(5, "ball", 3.0, flute_length=12.0, name="3 mm ball"),
        LibraryTool(17, "ball", 8.0, corner_radius=4.0, flute_length=25.0, name="8 mm ball"),
        LibraryTool(20, "bull", 10.0, corner_radius=1.5, flute_length=30.0, name="Bull"),
        LibraryTool(21, "vbit", 12.0, angle=90.0, flute_length=10.0, name="V 90")])
    assert len(prefs.tools) == 0
    assert infos == [f"Moved 3 tools (T17, T20, T21) from the add-on preferences into the tool library {path}; "
                     "1 were there already"]
    clash = [w for w in warnings if "T1 " in w]
    assert clash == ["The preferences' tool T1 6.35 mm flat end mill (Shop flat) was not moved: the tool library "
                     "has T1 as T1 6 mm flat end mill (shop 6 mm), which was kept"]
    broken = [w for w in warnings if "'Broken'" in w]
    assert len(broken) == 1 and "(T22, ball, diameter 0 mm" in broken[0] and "diameter 0.0 must be positive" \
        in broken[0]
    assert any("T21 'V 90': the preferences' list held no V-bit angle; it came in as 90°" in w for w in warnings)
    aside = tmp_path / oldtools.NOT_MOVED                   # nothing lost: the kept-out tool, whole
    assert formats.read_path(str(aside))[0] == ToolLibrary([LibraryTool(1, "flat", 6.35, name="Shop flat")])
    assert any(str(aside) in w for w in warnings)
    assert os.path.exists(f"{path}.bak1") and not os.path.exists(f"{path}.bak2")      # one write

    text, stamp = path.read_bytes(), path.stat().st_mtime_ns
    assert oldtools.move_old_tools(prefs.tools, str(path)) == ([], [])               # twice: nothing
    assert bpy.ops.kezuri.move_old_tools() == {"FINISHED"}
    assert path.read_bytes() == text and path.stat().st_mtime_ns == stamp
    assert not os.path.exists(f"{path}.bak2")


def test_the_operator_moves_them_into_a_first_library_over_the_presets(prefs, tmp_path):
    path = tmp_path / "tools.toml"
    old_tool(prefs, "Shop flat", 1, "flat", 6.35)
    old_tool(prefs, "8 mm ball", 17, "ball", 8.0)
    assert bpy.ops.kezuri.move_old_tools() == {"FINISHED"}
    library = store.load(str(path))
    assert library.numbers() == (*range(1, 12), 17)
    assert library.get(1) == LibraryTool(1, "flat", 6.35, name="Shop flat")        # the user's, not the preset
    assert library.get(2) == store.SEEDS.get(2)
    assert library.get(17) == LibraryTool(17, "ball", 8.0, corner_radius=4.0, name="8 mm ball")
    assert len(prefs.tools) == 0
    text = path.read_bytes()
    preferences.move_at_startup()                               # the start-up hook: nothing left to move
    assert path.read_bytes() == text


def test_an_unreadable_library_keeps_the_old_list(prefs, tmp_path):
    path = tmp_path / "tools.toml"
    path.write_text("format = \n")
    old_tool(prefs, "8 mm ball", 17, "ball", 8.0)
    assert bpy.ops.kezuri.move_old_tools() == {"CANCELLED"}     # a warning naming the file
    assert len(prefs.tools) == 1 and path.read_text() == "format = \n"


def test_the_engrave_menu_offers_the_librarys_balls_and_flats(prefs, tmp_path):
    offered = [(slot, tool.number) for slot, tool in toolmenu.offered(store.load(str(tmp_path / "tools.toml")))]
    assert offered == [("finish", 1), ("rough", 2), ("finish", 3), ("finish", 5), ("rough", 9)]   # the presets
    layout = fit.Layout()
    toolmenu.KEZURI_MT_library_tools.draw(types.SimpleNamespace(layout=layout), bpy.context)
    texts = [item[1] for item in layout._node.items]
    assert texts[:2] == ["Finishing: T1 6 mm flat end mill (6 mm roughing end mill)",
                         "Roughing: T2 6 mm ball end mill (6 mm ball end mill)"] and len(texts) == 5


def test_the_menus_operator_puts_a_library_tool_on_the_engraving(prefs, tmp_path):
    store.save(str(tmp_path / "tools.toml"), store.SEEDS.with_tool(LibraryTool(17, "ball", 8.0, name="8 mm ball")))
    engrave = bpy.context.scene.kezuri.engrave
    assert "UNDO" in toolmenu.KEZURI_OT_use_library_tool.bl_options
    assert bpy.ops.kezuri.use_library_tool(slot="rough", number=17) == {"FINISHED"}
    assert bpy.ops.kezuri.use_library_tool(slot="finish", number=3) == {"FINISHED"}
    assert (engrave.rough_tool_number, engrave.rough_diameter) == (17, 8.0)
    assert (engrave.finish_tool_number, engrave.finish_diameter) == (3, 1.0)
    with pytest.raises(RuntimeError, match=r"T7 12 mm 90° V-bit \(90° V-bit\); the engrave's rough tool must be a ball end mill"):
        bpy.ops.kezuri.use_library_tool(slot="rough", number=7)
    with pytest.raises(RuntimeError, match=r"no tool T40 in the tool library"):
        bpy.ops.kezuri.use_library_tool(slot="finish", number=40)
    assert (engrave.rough_tool_number, engrave.rough_diameter) == (17, 8.0)          # nothing taken
    assert (engrave.finish_tool_number, engrave.finish_diameter) == (3, 1.0)


def test_the_preferences_show_the_library_file_not_a_list(prefs, tmp_path):
    layout = fit.Layout()
    preferences.KezuriPreferences.draw(types.SimpleNamespace(layout=layout), bpy.context)
    drawn = []

    def walk(node):
        for item in node.items:
            if hasattr(item, "items"):             # a row, column or box
                walk(item)
            else:
                drawn.append(item)
    walk(layout._node)
    assert not [item for item in drawn if item[0] == "list"]
    labels = [item[1] for item in drawn if item[0] == "label"]
    assert str(tmp_path / "tools.toml") in labels
    assert "Edit it in the 3D Viewport's sidebar: CAM > Tool Library" in labels
    assert ("*", "Edit it in the 3D Viewport's sidebar: CAM > Tool Library") in JA


def run_check(mode, env):
    import json
    import subprocess
    import sys

    here = os.path.dirname(os.path.abspath(__file__))
    done = subprocess.run([sys.executable, os.path.join(here, "oldprefs_check.py"), mode], capture_output=True,
                          text=True, env=env, timeout=300)
    lines = [line for line in done.stdout.splitlines() if line.startswith("RESULT ")]
    assert done.returncode == 0 and lines, done.stdout[-2000:] + done.stderr[-3000:]
    return json.loads(lines[0][len("RESULT "):])


def test_an_old_userpref_file_moves_its_tools_on_load(tmp_path):
    """A real userpref.blend written with the old list: read back by a new Blender, moved, saved; a
    third start finds an empty list and leaves the library file as it was."""
    user = tmp_path / "user"
    (user / "scripts" / "addons").mkdir(parents=True)
    os.symlink(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), user / "scripts" / "addons" / "kezuri")
    library = tmp_path / "tools.toml"
    env = dict(os.environ, BLENDER_USER_RESOURCES=str(user), KEZURI_TOOL_LIBRARY=str(library))
    assert run_check("save", env)["save"] == ["FINISHED"]
    assert (user / "config" / "userpref.blend").exists()
    first = run_check("load", env)
    assert first["old_tools"] == [["8 mm ball", 17, "ball", 8.0, 0.0], ["Bull", 20, "bull", 10.0, 1.5],
                                  ["Shop flat", 1, "flat", 6.35, 0.0]]
    assert first["old_tools_after"] == 0
    moved = store.load(str(library))
    assert moved.numbers() == (*range(1, 12), 17, 20)                 # the presets less T1, and the moved ones
    assert moved.get(1) == LibraryTool(1, "flat", 6.35, name="Shop flat")
    assert moved.get(20) == LibraryTool(20, "bull", 10.0, corner_radius=1.5, name="Bull")
    text = library.read_bytes()
    second = run_check("load", env)
    assert second["old_tools"] == [] and second["old_tools_after"] == 0
    assert library.read_bytes() == text and not os.path.exists(f"{library}.bak1")
