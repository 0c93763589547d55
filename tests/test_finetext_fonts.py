"""Text too fine for the tool on real fonts: 5 mm kanji with the 1 mm band finishing tool of the
engraving are named, each with a smallest height above 5 mm, and pass at that height; a Latin
word 20 mm tall is not named.

The glyphs come from Blender's Text objects: Blender's own UI font for Latin and its bundled Noto
Sans CJK (datafiles/fonts, the UI's Japanese fallback) for the kanji, so no font is added to the
repository.  Heights are the glyph outlines' heights in mm (what the check reports).
"""
import os

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

from kezuri.toolpath.engines import finetext as ft  # noqa: E402
from kezuri.toolpath.engines import region as rg  # noqa: E402

CJK = os.path.join(bpy.utils.system_resource("DATAFILES"), "fonts", "Noto Sans CJK Regular.woff2")
BAND = 4.0          # the engraving's band width (EngraveSettings.band_width)
TOOL = 1.0          # the band finishing flat end mill (EngraveSettings.finish_tool)


def glyph_loops(character: str, height: float, x: float = 0.0, font_path: str | None = None) -> tuple:
    """The outline of one character as loops in mm, scaled so the glyph is ``height`` tall, its
    lower left corner at (x, 0)."""
    data = bpy.data.curves.new("glyph", "FONT")
    data.body = character
    if font_path:
        data.font = bpy.data.fonts.load(font_path, check_existing=True)
    obj = bpy.data.objects.new("glyph", data)
    mesh = obj.to_mesh()
    vertices = np.array([v.co[:2] for v in mesh.vertices], float)
    faces = [vertices[list(p.vertices)] for p in mesh.polygons]
    obj.to_mesh_clear()
    bpy.data.objects.remove(obj)
    region = rg.union_of_faces(faces, character)
    x0, y0, _, y1 = region.bounds()
    scale = height / (y1 - y0)
    return tuple((loop - [x0, y0]) * scale + [x, 0.0] for loop in rg.loops(region))


def engraved(text: str, height: float, font_path=None, spacing: float = 0.3):
    """Characters side by side, ``spacing`` x height apart, and the band the engraving cuts
    around them (the waste between and inside the strokes)."""
    characters, x = [], 0.0
    for index, character in enumerate(text):
        loops = glyph_loops(character, height, x, font_path)
        characters.append(ft.Character(character, index, loops))
        x = max(float(loop[:, 0].max()) for loop in loops) + spacing * height
    letters = rg.from_loops([loop for c in characters for loop in c.loops])
    return characters, rg.offset(letters, BAND) - letters


def test_the_cjk_font_is_there():
    assert os.path.isfile(CJK)


def test_a_latin_word_at_20_mm_with_the_1_mm_tool_is_not_named():
    characters, band = engraved("Watanabe", 20.0)
    assert ft.check(characters, band, TOOL) == []


@pytest.mark.parametrize("kanji", ["鬱", "欅"])
def test_5_mm_kanji_are_named_and_pass_at_the_height_named(kanji):
    characters, band = engraved(kanji, 5.0, CJK)
    found = ft.check(characters, band, TOOL)
    assert [(f.char, f.index) for f in found] == [(kanji, 0)]
    f = found[0]
    assert f.height_mm == pytest.approx(5.0)
    assert f.min_height_mm is not None and f.min_height_mm > 5.0
    assert 0 < f.narrowest_mm < TOOL
    assert f.missed_mm2 > 0.5            # strokes fused over whole square millimetres, not dust
    # drawn at the height named, the same character is reached everywhere
    characters, band = engraved(kanji, f.min_height_mm, CJK)
    assert ft.check(characters, band, TOOL) == []


def test_in_a_name_only_the_kanji_that_are_too_fine_are_named():
    characters, band = engraved("鬱山", 5.0, CJK)
    found = ft.check(characters, band, TOOL)
    assert [f.char for f in found] == ["鬱"]


def test_engraving_names_the_kanji_its_band_tool_fuses():
    """The engraving plan (raised letters, band finishing with the 1 mm flat end mill) reports each
    kanji of a 5 mm name in ``too_fine`` and in a warning that gives its smallest height."""
    from kezuri.toolpath.operations.engrave import engrave

    characters, _ = engraved("鬱欅", 5.0, CJK)
    loops = [loop for c in characters for loop in c.loops]
    plate = [np.array([[-8.0, -8.0], [20.0, -8.0], [20.0, 13.0], [-8.0, 13.0]])]
    given = [("Name", c.char, c.index, c.loops) for c in characters]
    result = engrave.plan(plate, [("Name", loops)], characters=given, texts={"Name": "鬱欅"})
    assert [(t["char"], t["index"], t["letters"], t["operation"]) for t in result.too_fine] == [
        ("鬱", 0, "Name", "band finishing"), ("欅", 1, "Name", "band finishing")]
    expected = {f.char: f for f in ft.check(characters, engrave.band_region(
        rg.from_loops(plate), rg.from_loops(loops), engrave.EngraveSettings()), 1.0)}
    for item in result.too_fine:
        assert item["min_height_mm"] == pytest.approx(expected[item["char"]].min_height_mm)
        assert item["min_height_mm"] > 5.0 and 0 < item["narrowest_mm"] < 1.0
    lines = [w for w in result.warnings if "too big for '鬱' (U+9B31) of letters 'Name'" in w]
    assert len(lines) == 1
    assert f"make it at least {result.too_fine[0]['min_height_mm']:.1f} mm tall (now 5.0 mm)" in lines[0]


def test_engraving_a_latin_name_at_20_mm_names_nothing():
    from kezuri.toolpath.operations.engrave import engrave

    characters, _ = engraved("Watanabe", 20.0)
    loops = [loop for c in characters for loop in c.loops]
    x1 = max(float(loop[:, 0].max()) for loop in loops)
    plate = [np.array([[-8.0, -8.0], [x1 + 8, -8.0], [x1 + 8, 28.0], [-8.0, 28.0]])]
    result = engrave.plan(plate, [("Name", loops)], texts={"Name": "Watanabe"})
    assert result.too_fine == []
    assert not [w for w in result.warnings if "too big for" in w]


def test_the_jobs_part_warnings_carry_the_characters_too_fine():
    """Through the job model (what the job list shows): the engraving's Part warns of each kanji."""
    from kezuri.toolpath import job as jobs
    from kezuri.toolpath.operations.engrave import engrave
    from kezuri.toolpath.operations.engrave.kind import EngraveGeometry

    characters, _ = engraved("鬱欅", 5.0, CJK)
    loops = tuple(loop for c in characters for loop in c.loops)
    plate = (np.array([[-8.0, -8.0], [20.0, -8.0], [20.0, 13.0], [-8.0, 13.0]]),)
    geometry = EngraveGeometry(plate, 10.0, (("Name", loops),), (("Name", "鬱欅"),),
                               characters=tuple(("Name", c.char, c.index, c.loops) for c in characters))
    planned = jobs.plan_job(jobs.Job(jobs.Setup(name="plate", post="linuxcnc"),
                                     (jobs.JobOperation("engrave", "name", engrave.EngraveSettings(), geometry),)))
    part = planned.parts[0]
    assert [t["char"] for t in part.result.result.too_fine] == ["鬱", "欅"]
    for kanji in ("'鬱' (U+9B31)", "'欅' (U+6B05)"):
        assert sum(kanji in w and "mm tall (now 5.0 mm)" in w for w in part.warnings) == 1
        assert sum(kanji in w for w in planned.warnings) == 1
