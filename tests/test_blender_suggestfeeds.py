"""Suggest Feeds on the CAM tab's job list (issue 31, item 3): the selected row's spindle speed,
feeds and steps filled from the calculator for the scene's material, the chip load reported, and
refused naming the Material when none is set.  Expected numbers worked by hand from AST Tooling's
hardwood rows (1/8 in: .002 - .004, 1/4 in: .005 - .007 in per tooth; a 6 mm cutter reads between
them) and wood's 600 - 1000 sfm with carbide; Amana's V-groove chart .0024 in per tooth."""
import json
import math

import pytest

bpy = pytest.importorskip("bpy")

from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from kezuri.operators import samples, translations  # noqa: E402

IN, FT = 25.4, 0.3048
M_MIN = 800 * FT                                            # the middle of 600 - 1000 sfm


def hardwood_chip_mm(diameter_mm: float) -> float:
    """The middle of AST's hardwood band, read linearly between its 1/8 and 1/4 in rows."""
    t = (diameter_mm / IN - 0.125) / 0.125
    return ((0.002 + 0.003 * t) + (0.004 + 0.003 * t)) / 2 * IN


@pytest.fixture
def plate(empty_scene, tmp_path, monkeypatch):
    monkeypatch.setenv("KEZURI_TOOL_LIBRARY", str(tmp_path / "none" / "tools.toml"))    # no library: 2-flute carbide
    scene = empty_scene
    samples.name_plate(scene)
    scene.kezuri.machine.post = "linuxcnc"
    scene.kezuri.machine.preset = "linuxcnc-manual"           # 24000 rpm, 6000 mm/min
    assert bpy.ops.kezuri.job_add(kind="engrave") == {"FINISHED"}
    assert bpy.ops.kezuri.job_add(kind="profile") == {"FINISHED"}
    return scene


def test_suggest_feeds_fills_the_profile_row_and_reports_the_chip_load(plate, capfd):
    scene = plate
    listed = scene.kezuri.job_list
    listed.active = 1
    with pytest.raises(RuntimeError, match="Material"):            # no material: refused, naming it
        bpy.ops.kezuri.job_suggest_feeds()
    bpy.ops.kezuri.job_generate()                                  # the panel's values read back into the row
    assert json.loads(listed.rows[1].settings)["rpm"] == 18000      # the kind's default, kept as the row's own
    scene.kezuri.stock.material = "hardwood"
    capfd.readouterr()
    assert bpy.ops.kezuri.job_suggest_feeds() == {"FINISHED"}
    said = capfd.readouterr().out
    rpm = round(M_MIN * 1000 / (math.pi * 6.0))                    # the profile's 6 mm end mill: 12936 rpm
    feed = round(rpm * 2 * hardwood_chip_mm(6.0))                  # 0.1440 mm per tooth: 3726 mm/min
    settings = json.loads(listed.rows[1].settings)
    assert (settings["rpm"], settings["feed"], settings["plunge_feed"]) == (rpm, feed, round(feed / 2))
    assert settings["step_down"] == pytest.approx(6.0) and settings["tab_count"] == 4     # the row's own kept
    group = scene.kezuri.profile                                   # the panel shows the row's new values
    assert (group.rpm, group.feed, group.step_down) == (pytest.approx(rpm), pytest.approx(feed), pytest.approx(6.0))
    assert f"T5: {rpm} rpm, feed {feed} mm/min, chip load {feed / (rpm * 2):.4f} mm per tooth" in said
    # the values are now the row's own: Generate plans them and finds no feeds flag for it
    capfd.readouterr()
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    assert "feeds: operation 'profile'" not in capfd.readouterr().out


def test_suggest_feeds_fills_a_v_carve_rows_settings_and_is_not_offered_for_the_engraving(plate):
    scene = plate
    scene.kezuri.stock.material = "hardwood"
    listed = scene.kezuri.job_list
    listed.active = 0
    assert not bpy.ops.kezuri.job_suggest_feeds.poll()           # the paper's engraving keeps its values
    assert bpy.ops.kezuri.job_add(kind="vcarve") == {"FINISHED"}
    listed.active = 2
    listed.rows[2].settings = json.dumps({"rpm": 9000, "diameter": 12.7})
    assert bpy.ops.kezuri.job_suggest_feeds() == {"FINISHED"}
    settings = json.loads(listed.rows[2].settings)
    rpm = round(M_MIN * 1000 / (math.pi * 12.7))                  # 6112: suggest replaces the typed 9000
    feed = round(rpm * 2 * 0.0024 * IN)                            # Amana V-groove: 745 mm/min
    assert (settings["rpm"], settings["feed"], settings["entry_feed"]) == (rpm, feed, round(feed / 2))
    assert settings["clear_rpm"] == 24000                          # the 3.175 mm end mill, at the machine's top


def test_the_messages_are_in_japanese():
    ja = translations.japanese_message("Suggested feeds for 'cut' in Hardwood")
    assert ja is not None and "広葉樹" in ja and "'cut'" in ja
    ja = translations.japanese_message("T5: 12936 rpm, feed 3726 mm/min, chip load 0.1440 mm per tooth "
                                       "(band 0.1186 - 0.1694 mm)")
    assert ja == "T5：12936 rpm、送り 3726 mm/min、1刃送り 0.1440 mm（範囲 0.1186〜0.1694 mm）"
    table = translations.TRANSLATIONS["ja_JP"]
    assert table[("Operator", "Suggest Feeds")] == "送り・回転数を提案"
    ja = translations.japanese_message("job file a.toml: operation 2 ('cut'): feeds: flutes = 26: must be a whole "
                                       "number 1..20")
    assert ja is not None and "刃数" in ja and "1〜20" in ja
    ja = translations.japanese_message("T4: 13583 rpm, feed 1035 mm/min, feed per revolution 0.0762 mm "
                                       "(band 0.0508 - 0.1016 mm)")
    assert ja == "T4：13583 rpm、送り 1035 mm/min、1回転あたりの送り 0.0762 mm（範囲 0.0508〜0.1016 mm）"


def test_suggest_feeds_on_a_drilling_row_reports_the_feed_per_revolution(plate, capfd):
    scene = plate
    scene.kezuri.stock.material = "hardwood"
    assert bpy.ops.kezuri.job_add(kind="drill") == {"FINISHED"}
    scene.kezuri.job_list.active = 2
    capfd.readouterr()
    assert bpy.ops.kezuri.job_suggest_feeds() == {"FINISHED"}
    # 13583 rpm x 0.0762 mm/rev = 1035 mm/min (worked in the test above); 1035 / 13583 = 0.0762 mm/rev
    assert ("T4: 13583 rpm, feed 1035 mm/min, feed per revolution 0.0762 mm (band 0.0508 - 0.1016 mm)"
            in capfd.readouterr().out)


def test_a_row_added_or_loaded_with_a_material_starts_with_the_computed_feeds(plate, tmp_path):
    scene = plate
    scene.kezuri.stock.material = "hardwood"
    assert bpy.ops.kezuri.job_add(kind="drill") == {"FINISHED"}
    listed = scene.kezuri.job_list
    # the drilling's 5 mm drill, fed per revolution (issue 31 follow-up): wood's drill speed 300 - 400 sfm doubled
    # for carbide, 700 sfm = 213.36 m/min / (pi x 5 mm) = 13,582.9 -> 13583 rpm; the 1/8 - 1/4 in row's
    # .002 - .004 in/rev, middle .003 in = 0.0762 mm: 13583 x 0.0762 = 1035.0 -> 1035 mm/min
    rpm = round(700 * 0.3048 * 1000 / (math.pi * 5.0))
    feed = round(rpm * 0.003 * 25.4)
    assert (rpm, feed) == (13583, 1035)
    settings = json.loads(listed.rows[2].settings)
    assert (settings["rpm"], settings["feed"], settings["peck"]) == (rpm, feed, 5.0)
    assert scene.kezuri.drill.rpm == pytest.approx(rpm)            # the panel shows what runs
    # a job file that leaves them out: loaded, the rows hold what batch computes; a typed value stays
    job = tmp_path / "cut.toml"
    job.write_text('[setup]\nmaterial = "hardwood"\n\n[[operations]]\nkind = "profile"\nname = "cut"\n'
                   'settings = { diameter = 6.35, feed = 900 }\n', encoding="utf-8")
    scene.kezuri.stock.material = "NONE"
    assert bpy.ops.kezuri.job_load(filepath=str(job)) == {"FINISHED"}
    settings = json.loads(listed.rows[0].settings)
    assert settings["feed"] == 900 and settings["plunge_feed"] == 450           # typed, and its feed / flutes
    assert settings["rpm"] == round(M_MIN * 1000 / (math.pi * 6.35)) and settings["step_down"] == 6.35
