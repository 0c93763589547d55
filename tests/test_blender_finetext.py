"""Text too fine for the band finishing tool, from Blender: a Text object's characters one by one
(operators/textcells.py), ``batch.py engrave`` reporting them in report.json's ``too_fine``, the
Engrave panel's lines fitting the sidebar in English and Japanese, the messages in Japanese.

The kanji are set in Blender's bundled Noto Sans CJK (its UI's Japanese fallback): no font file
is added to the repository.
"""
import contextlib
import io
import json
import os

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

import controller_rules  # noqa: E402
import rs274  # noqa: E402
import sidebar_fit as fit  # noqa: E402
from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from kezuri.operators import convert, panels, samples, textcells, translations  # noqa: E402
from kezuri.operators import engrave as engrave_shell  # noqa: E402
from kezuri.toolpath.engines import region as rg  # noqa: E402
from test_hostile_batch import BATCH, time_limit  # noqa: E402

CJK = os.path.join(bpy.utils.system_resource("DATAFILES"), "fonts", "Noto Sans CJK Regular.woff2")
JA = translations.TRANSLATIONS["ja_JP"]


def kanji_plate(scene, body: str = "鬱欅", height: float = 5.0):
    """A 40 x 24 x 10 mm plate with ``body`` in Noto Sans CJK, its kanji ``height`` mm tall
    (the Text's size set from the measured glyph), centred on the plate."""
    plate = bpy.data.objects.new("Plate", samples.box_mesh("Plate", -20, -12, -10, 20, 12, 0.0))
    scene.collection.objects.link(plate)
    data = bpy.data.curves.new("Name", "FONT")
    data.body = body
    data.font = bpy.data.fonts.load(CJK, check_existing=True)
    data.align_x, data.align_y = "CENTER", "CENTER"
    letters = bpy.data.objects.new("Name", data)
    letters.location.z = 0.05
    scene.collection.objects.link(letters)
    mesh = letters.to_mesh()
    z = np.array([v.co[1] for v in mesh.vertices])
    letters.to_mesh_clear()
    data.size = height / (z.max() - z.min())
    scene.kezuri.stock.plate = plate
    scene.kezuri.engrave.letters = letters
    return plate, letters


def test_a_text_objects_characters_come_one_by_one_where_they_stand(empty_scene):
    plate, letters = kanji_plate(empty_scene, "鬱 欅")
    depsgraph = bpy.context.evaluated_depsgraph_get()
    frame = convert.plate_from_object(plate, depsgraph, empty_scene, "CENTER").frame
    whole = convert.outlines_in_work(letters, depsgraph, frame)
    found = textcells.character_outlines(letters, depsgraph, frame, whole)
    assert [(c, i) for c, i, _ in found] == [("鬱", 0), ("欅", 2)]     # the space has no glyph
    first, second = (rg.from_loops(list(loops)) for _, _, loops in found)
    assert first.bounds()[2] < second.bounds()[0]                   # left to right, apart
    union = rg.from_loops(list(whole))
    assert abs((first + second).area() - union.area()) < 1e-3 * union.area()
    assert 4.9 < first.bounds()[3] - first.bounds()[1] < 5.1
    # an outline that is not this text's (a modifier changed it): no characters, not wrong ones
    assert textcells.character_outlines(letters, depsgraph, frame, [loop * 1.1 for loop in whole]) == []


def test_batch_engrave_names_the_5_mm_kanji_in_the_report(empty_scene, tmp_path):
    kanji_plate(empty_scene)
    blend = str(tmp_path / "name.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    out = tmp_path / "out"
    with time_limit(600), contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(["batch.py", "engrave", "--blend", blend, "--post", "linuxcnc", "--out", str(out)])
        except SystemExit as exit_:
            status = exit_.code
    assert status == 0
    report = json.loads((out / "report.json").read_text())
    too_fine = report["too_fine"]
    assert [(t["char"], t["index"], t["letters"]) for t in too_fine] == [("鬱", 0, "Name"), ("欅", 1, "Name")]
    for item in too_fine:
        assert item["height_mm"] == pytest.approx(5.0, abs=0.1)
        assert item["min_height_mm"] > 5.0 and 0 < item["narrowest_mm"] < 1.0 and item["missed_mm2"] > 0.5
        shown = f"'{item['char']}' (U+{ord(item['char']):04X}) of letters 'Name'"
        assert any(shown in w and f"at least {item['min_height_mm']:.1f} mm tall" in w for w in report["warnings"])
    # the program names them in its header's notes, and stays a program the readers accept
    text = (out / "engrave.ngc").read_text()
    notes = [line for line in text.splitlines() if line.startswith("(NOTE:") and "TOO BIG FOR" in line]
    assert [("U+9B31" in n, "U+6B05" in n) for n in notes] == [(True, False), (False, True)]
    assert controller_rules.check(text, "linuxcnc") == []
    if rs274.available():
        assert rs274.run(text)
    bpy.ops.wm.read_homefile(use_empty=True)


def test_the_engrave_panel_names_each_character_and_fits_the_sidebar(empty_scene, monkeypatch):
    props = empty_scene.kezuri.engrave
    found = [{"char": c, "index": k, "min_height_mm": h}
             for k, (c, h) in enumerate([("鬱", 61.5), ("欅", 70.2), (None, 123.4), ("W", None), ("a", 9.9),
                                         ("b", 8.8), ("c", 7.7), ("d", 6.6)])]
    props.too_fine = engrave_shell.too_fine_note(found)
    english = engrave_shell.too_fine_lines(props, japanese=False)
    assert english == ["'鬱': too fine, needs 61.5 mm", "'欅': too fine, needs 70.2 mm", "#3: too fine, needs 123.4 mm",
                       "'W': too fine at any size", "'a': too fine, needs 9.9 mm", "'b': too fine, needs 8.8 mm",
                       "and 2 more too fine"]
    japanese = engrave_shell.too_fine_lines(props, japanese=True)
    assert japanese[0] == "'鬱'：細かすぎ、61.5 mm 以上に" and japanese[-1] == "ほか 2 文字も細かすぎ"
    empty_scene.kezuri.job = "ENGRAVE"
    context = type("Context", (), {"scene": empty_scene, "active_object": None})()
    original = engrave_shell.too_fine_lines
    for language, table in (("en", None), ("ja", JA)):
        monkeypatch.setattr(engrave_shell, "too_fine_lines",
                            lambda p, japanese=None, ja=(language == "ja"): original(p, japanese=ja))
        texts = fit.all_texts([panels.KEZURI_PT_engrave], context, table)
        shown = [t for t in texts if "細かすぎ" in t.text or "too fine" in t.text]
        assert len(shown) == 7, language
        assert not fit.too_wide(shown), "\n".join(fit.too_wide(shown))
    props.too_fine = ""
    assert engrave_shell.too_fine_lines(props) == []


@pytest.mark.parametrize("english", [
    "the band finishing's 1 mm tool is too big for '鬱' (U+9B31) of letters 'Name': 8.16 mm^2 between its strokes is "
    "left uncut (gaps 0.08 mm wide); make it at least 61.5 mm tall (now 5.0 mm)",
    "the band finishing's 1 mm tool is too big for glyph 3 of letters 'Name': 0.40 mm^2 between its strokes is left "
    "uncut; no text up to 50 times as tall lets the tool in: use a smaller tool",
])
def test_the_warnings_come_out_in_japanese(english):
    japanese = translations.japanese_message(english)
    assert japanese is not None and "帯仕上げ" in japanese and "'Name'" in japanese
