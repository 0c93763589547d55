"""Every note the feeds calculator writes (how the band was read off the chart, what the machine
capped, what was given) comes out in Japanese: the calculator is run over every material, tool kind
and tool material, diameters below, between, on and above the charts' rows, a machine that caps the
spindle and the feed, one whose slowest spindle is raised to, and the user's own values; each note
is matched (a fixed message, or a template with its values put in) and no English word of the
note's text is left but its numbers."""
import re

import pytest

bpy = pytest.importorskip("bpy")

from kezuri.operators import translations  # noqa: E402
from kezuri.toolpath.feeds import calculator, materials  # noqa: E402
from kezuri.toolpath.ir import machine as machines  # noqa: E402

JA = translations.TRANSLATIONS["ja_JP"]
JAPANESE = re.compile(r"[\u3040-\u30ff\u3400-\u4dbf\u4e00-\u9fff]")
DIAMETERS = (0.8, 1.5, 3.175, 5.0, 6.35, 8.0, 12.7, 20.0, 40.0)      # mm: under, between, on, over the rows


def machines_to_try():
    vmc = machines.preset("fanuc-vmc")
    return (None, vmc.replace(name="small", label="small", max_spindle_rpm=10000.0, max_feed=1000.0),
            vmc.replace(name="slow", label="slow", min_spindle_rpm=30000.0, max_spindle_rpm=40000.0))


def every_note() -> set:
    notes = set()
    for material in materials.MATERIALS:
        for kind in calculator.TOOL_KINDS:
            for tool_material in materials.TOOL_MATERIALS:
                for diameter in DIAMETERS:
                    for machine in machines_to_try():
                        for flutes, given in ((None, {}), (2, {"rpm": 12000.0, "feed": 1500.0})):
                            found = calculator.compute(kind, diameter, material, flutes, "profile", machine,
                                                       tool_material, **given)
                            notes.update(found.notes)
    return notes


def japanese(note: str):
    return JA.get(("*", note)) or translations.japanese_message(note)


def test_the_runs_reach_every_kind_of_note():
    notes = every_note()
    for part in ("interpolated between", "below the chart's smallest", "above the chart's largest",
                 "the chart's row up to", "a V-bit cuts with its tip", "recommended: the V-groove", "feed per revolution",
                 "low end in a harder material", "flutes not given", "capped at the machine's", "raised to the machine",
                 "mm/min: feed per revolution", "mm/min: chip load per tooth",
                 "spindle speed as given", "feed as given"):
        assert any(part in note for note in notes), part


def test_every_note_comes_out_in_japanese():
    untranslated = []
    for note in sorted(every_note()):
        shown = japanese(note)
        # what is left in Latin letters: units, the tool kinds' letters (V), nothing of the English text
        left = set(re.findall(r"[A-Za-z]{3,}", shown or note)) - {"rpm", "min"}
        if not shown or not JAPANESE.search(shown) or left:
            untranslated.append(f"{note!r} -> {shown!r}")
    assert not untranslated, f"{len(untranslated)} feeds notes not in Japanese:\n" + "\n".join(untranslated)


def test_a_band_note_is_read_with_its_numbers():
    """A 5 mm drill is fed per revolution in the 1/8 - 1/4 in row of the drilling chart (an "up to"
    chart); a 4.5 mm router bit's band is interpolated between the chart's rows either side."""
    assert japanese("feed per revolution (the chart's row up to 6.35 mm)") == "1回転あたりの送り（表の 6.35 mm までの行）"
    assert japanese("interpolated between the chart's 3.18 and 6.35 mm rows") == "表の 3.18 mm と 6.35 mm の行の間を補間"
    assert japanese("below the chart's smallest diameter (3.18 mm): its band scaled by 1.5 / 3.18") == \
        "表の最小径（3.18 mm）未満のため、その範囲を 1.5 / 3.18 倍に縮小"
