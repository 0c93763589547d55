"""Text too fine for a V-carve's clearing end mill (issue 30): 5 mm kanji carved with a 60 deg
V-bit held to a max depth that leaves flat floors in the strokes, the floors to be cleared by a
3.175 mm end mill that fits none of them; ``batch.py job`` names the characters in the V-carve's
warnings and report.json's ``too_fine`` (the keys of engraving's), with the height at which the
end mill would fit.  Set in Blender's bundled Noto Sans CJK (no font file in the repository)."""
import contextlib
import io
import json
import math
import os

import pytest

bpy = pytest.importorskip("bpy")

from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from kezuri.operators import translations  # noqa: E402
from test_hostile_batch import BATCH  # noqa: E402

# Blender lays Noto Sans CJK's kanji out 1.6089 mm tall per 5 of the Text's size: 15.54 makes 欅 5.0 mm tall
JOB = '''
[setup]
name = "kanji"
stock = [-30.0, -15.0, -10.0, 30.0, 15.0, 0.0]
work_zero = "CENTER"
post = "linuxcnc"

[[operations]]
kind = "vcarve"
name = "kanji"
text = {{ body = "欅 削り", font = "Noto Sans CJK Regular.woff2", size = 15.54 }}
settings = {{ angle = 60.0, max_depth = {max_depth}, clear_diameter = 3.175 }}
'''
KEYS = {"operation", "letters", "char", "index", "missed_mm2", "narrowest_mm", "height_mm", "min_height_mm", "at"}


def run_job(tmp_path, max_depth):
    job = tmp_path / "kanji.toml"
    job.write_text(JOB.format(max_depth=max_depth), encoding="utf-8")
    out = tmp_path / "out"
    with contextlib.redirect_stderr(io.StringIO()) as err, contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(["batch.py", "job", str(job), "--out", str(out), "--allow-findings"])
        except SystemExit as exit_:
            status = exit_.code
    assert status == 0, err.getvalue()[-2000:]
    (operation,) = json.loads((out / "report.json").read_text())["job_operations"]
    return operation


def test_5_mm_kanji_too_fine_for_the_clearing_end_mill_are_named_with_a_height(empty_scene, tmp_path):
    """Max depth 0.3 mm: the V-bit's cone is 2 x 0.3 x tan(30 deg) = 0.346 mm wide there, so strokes
    wider than that get a flat floor, and the 3.175 mm end mill needs strokes 3.175 + 0.346 =
    3.521 mm wide to reach their floors: none of the 5 mm kanji's (about 0.3-0.5 mm) are."""
    operation = run_job(tmp_path, 0.3)
    found = operation["too_fine"]
    assert [(f["char"], f["index"]) for f in found][:2] == [("欅", 0), ("削", 2)]   # the space is no character
    need = 3.175 + 2 * 0.3 * math.tan(math.radians(30.0))
    assert need == pytest.approx(3.5214, abs=1e-4)
    for item in found:
        assert set(item) == KEYS and item["operation"] == "clearing" and item["letters"] == "text '欅 削り'"
        assert item["missed_mm2"] > 0.01
        assert 2 * 0.3 * math.tan(math.radians(30.0)) * 0.5 < item["narrowest_mm"] < need
        # the height at which the narrowest stroke is `need` wide (rounded up to 0.1 mm, checked there)
        assert item["min_height_mm"] >= item["height_mm"] * need / item["narrowest_mm"] - 0.1
        assert item["min_height_mm"] <= item["height_mm"] * need / item["narrowest_mm"] * 1.01 + 1.0
    assert found[0]["height_mm"] == pytest.approx(5.0, abs=0.05)
    lines = [w for w in operation["warnings"] if "too big for '欅' (U+6B05)" in w]
    assert len(lines) == 1 and f"make it at least {found[0]['min_height_mm']:.1f} mm tall (now 5.0 mm)" in lines[0]
    assert "the end mill needs 3.52 mm" in lines[0]
    japanese = translations.japanese_message(lines[0])
    assert japanese is not None and "除去加工の 3.175 mm エンドミル" in japanese and "'欅' (U+6B05)" in japanese


def test_no_flat_floor_no_too_fine(empty_scene, tmp_path):
    """Max depth 1 mm: the cone is 1.155 mm wide there, wider than every stroke of the 5 mm kanji,
    so the V-bit carves them all to a point: no floor, nothing named."""
    operation = run_job(tmp_path, 1.0)
    assert operation["too_fine"] == [] and operation["operations"] == ["kanji"]


def test_a_text_objects_characters_are_named_from_the_job_list(empty_scene):
    """A V-carve row of the job list on a Text object (its characters told one by one in the
    plate's frame): the same kanji, the same max depth, named in the planned part's result."""
    from kezuri.operators import joblist, samples
    from kezuri.toolpath.job import plan_job

    scene = empty_scene
    plate, _ = samples.name_plate(scene)
    data = bpy.data.curves.new("Name", "FONT")
    data.body = "欅 削り"
    data.font = bpy.data.fonts.load(os.path.join(bpy.utils.system_resource("DATAFILES"), "fonts",
                                                 "Noto Sans CJK Regular.woff2"), check_existing=True)
    data.size = 15.54
    name = bpy.data.objects.new("Name", data)
    scene.collection.objects.link(name)
    scene.kezuri.machine.post = "linuxcnc"
    assert bpy.ops.kezuri.job_add(kind="vcarve") == {"FINISHED"}
    row = scene.kezuri.job_list.rows[0]
    next(item for item in row.objects if item.slot == "region").object = name
    props = scene.kezuri.vcarve
    props.max_depth, props.clear_diameter = 0.3, 3.175
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    assert row.state == "FINDINGS"
    (item,) = plan_job(joblist.build(scene)[0]).planned
    found = item.part.result.too_fine
    assert [(f["char"], f["index"]) for f in found][:2] == [("欅", 0), ("削", 2)]
    assert all(f["letters"] == "object 'Name'" and set(f) == KEYS for f in found)
    assert any("too big for '欅' (U+6B05) of object 'Name'" in w for w in item.part.warnings)


def test_the_floor_corners_warning_comes_out_in_japanese(empty_scene):
    english = ("V-carve 'pocket': the T4 3.175 mm flat end mill (3.175 mm end mill) cannot reach 2 part(s) of the "
               "flat floor at max depth (X-0.00 Y-12.56, X1.00 Y2.00); the V-bit's tip traces them, ridges up to "
               "0.48 mm high may stand there")
    japanese = translations.japanese_message(english)
    assert japanese == ("V-carve 'pocket'：T4 3.175 mm flat end mill (3.175 mm end mill) は最大深さの平らな底のうち "
                        "2 か所（X-0.00 Y-12.56, X1.00 Y2.00）に届きません。V ビットの先端がなぞり、高さ 0.48 mm "
                        "までの山が残ることがあります")
