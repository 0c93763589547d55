"""ISO 14649 files written by other tools: the conventions they differ in.

The Part 21 texts here are our own, written the way the ISO 14649-11 annex examples and NIST's
files are laid out (one instance a line, ``#n= ENTITY(...)``, tolerated lengths, placements named
after their feature).  The tests read the numbers they check from the text itself.
"""
import re

import numpy as np
import pytest

from kezuri.toolpath.ir.program import FEED
from kezuri.toolpath.simulate import BoxStock, simulate
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program

TOOL_DIAMETER = 10.0


def pocket_file(pocket_at=(75.0, 50.0), profile_at=None, block=True, size=(40.0, 24.0), finish_tool="#22",
                finish_technology="#24", rough_technology="#24", hole=False, rough="BOTTOM_AND_SIDE_ROUGH_MILLING",
                finish="BOTTOM_AND_SIDE_FINISH_MILLING", general=False) -> str:
    """A 120 x 80 x 30 plate with one rectangular closed pocket 8 deep, roughed and finished with a
    10 mm end mill (and with ``hole``, a 8 mm hole drilled 10 deep at (20, 20) afterwards).
    ``profile_at``: the location written in the profile's own placement (None: ``$``, the profile at
    the feature's zero point).  ``finish_tool``: #22, or #122, another instance of the same end mill
    (as generators write one per operation).  Technologies: #24 (0.01 m/s, 100 rev/s clockwise), #124
    (no feedrate), #125 (a spindle of 17544.63 "rev/s": an rpm), #126 (2 m/s at 100 rev/s)."""
    length, width = size
    profile_placement = "$" if profile_at is None else "#40"
    bounding = "#7" if block else "$"
    steps = "#60,#61,#62" if hole else "#60,#61"
    # ``general``: the same rectangle as a GENERAL_CLOSED_PROFILE of a closed POLYLINE
    half = (length / 2, width / 2)
    corners = "\n".join(f"#{71 + k}= CARTESIAN_POINT('POCKET1 CORNER {k + 1}',({sx * half[0]:.3f},{sy * half[1]:.3f},0.000));"
                        for k, (sx, sy) in enumerate(((-1, -1), (1, -1), (1, 1), (-1, 1))))
    profile = (f"#39= GENERAL_CLOSED_PROFILE({profile_placement},#70);\n#70= POLYLINE('POCKET1 OUTLINE',"
               f"(#71,#72,#73,#74,#71));\n{corners}" if general else
               f"#39= RECTANGULAR_CLOSED_PROFILE({profile_placement},#43,#44);")
    return f"""ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('KEZURI TEST: PLACEMENT CONVENTIONS'),'2;1');
FILE_NAME('conventions.stp','2026-11-25T00:00:00',('kezuri'),(''),'','','');
FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));
ENDSEC;
DATA;
#1= PROJECT('PLACEMENTS',#2,(#3),$,$,$);
#2= WORKPLAN('MAIN WORKPLAN',({steps}),$,#5,$);
#3= WORKPIECE('PLATE',$,0.01,$,$,{bounding},());
#4= AXIS2_PLACEMENT_3D('WORKPIECE ORIGIN',#10,#11,#12);
#5= SETUP('SETUP1',#4,#6,(#8));
#6= PLANE('SECURITY PLANE',#9);
#7= BLOCK('PLATE BLOCK',#13,120.000,80.000,30.000);
#8= WORKPIECE_SETUP(#3,#4,$,$,());
#9= AXIS2_PLACEMENT_3D('SECURITY PLANE',#14,#11,#12);
#10= CARTESIAN_POINT('ORIGIN',(0.000,0.000,0.000));
#11= DIRECTION('Z AXIS',(0.000,0.000,1.000));
#12= DIRECTION('X AXIS',(1.000,0.000,0.000));
#13= AXIS2_PLACEMENT_3D('BLOCK CORNER',#15,#11,#12);
#14= CARTESIAN_POINT('SECURITY PLANE',(0.000,0.000,50.000));
#15= CARTESIAN_POINT('BLOCK CORNER',(0.000,0.000,-30.000));
#20= ENDMILL(#21,4,.RIGHT.,.F.,$);
#21= MILLING_TOOL_DIMENSION({TOOL_DIAMETER:.3f},$,$,25.000,0.000,$,$);
#22= MILLING_CUTTING_TOOL('ENDMILL 10MM',#20,(#23),$,$,$);
#23= CUTTING_COMPONENT(25.000,$,$,$,$);
#24= MILLING_TECHNOLOGY(0.010,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);
#124= MILLING_TECHNOLOGY($,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);
#125= MILLING_TECHNOLOGY(0.010,.TCP.,$,-17544.630,$,.F.,.F.,.F.,$);
#126= MILLING_TECHNOLOGY(2.000,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);
#120= ENDMILL(#121,4,.RIGHT.,.F.,$);
#121= MILLING_TOOL_DIMENSION({TOOL_DIAMETER:.3f},$,$,25.000,0.000,$,$);
#122= MILLING_CUTTING_TOOL('ENDMILL 10MM',#120,(#123),$,$,$);
#123= CUTTING_COMPONENT(25.000,$,$,$,$);
#220= TWIST_DRILL(#221,2,.RIGHT.,.F.,$);
#221= MILLING_TOOL_DIMENSION(8.000,31.000,$,40.000,$,$,$);
#222= MILLING_CUTTING_TOOL('DRILL 8MM',#220,(#223),$,$,$);
#223= CUTTING_COMPONENT(40.000,$,$,$,$);
#224= MILLING_TECHNOLOGY(0.002,.TCP.,$,-20.000,$,.F.,.F.,.F.,$);
#230= ROUND_HOLE('HOLE1',#3,(#232),#233,#235,8.000,$,#238);
#232= DRILLING($,$,'DRILL HOLE1',5.000,$,#222,#224,#25,$,$,$,$,$,$);
#233= AXIS2_PLACEMENT_3D('HOLE1',#234,#11,#12);
#234= CARTESIAN_POINT('HOLE1',(20.000,20.000,0.000));
#235= PLANE('HOLE1 DEPTH',#236);
#236= AXIS2_PLACEMENT_3D('HOLE1 DEPTH',#237,#11,#12);
#237= CARTESIAN_POINT('HOLE1 DEPTH',(0.000,0.000,-10.000));
#238= FLAT_HOLE_BOTTOM();
#25= MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,());
#26= PLUNGE_TOOLAXIS($);
#27= BIDIRECTIONAL(0.500,.T.,$,.LEFT.,$);
#28= CONTOUR_PARALLEL(0.500,.T.,.CCW.,.CLIMB.);
#30= CLOSED_POCKET('POCKET1',#3,(#50,#51),#31,#35,(),$,#38,$,$,#39);
#31= AXIS2_PLACEMENT_3D('POCKET1',#32,#11,#12);
#32= CARTESIAN_POINT('POCKET1',({pocket_at[0]:.3f},{pocket_at[1]:.3f},0.000));
#35= PLANE('POCKET1 DEPTH',#36);
#36= AXIS2_PLACEMENT_3D('POCKET1 DEPTH',#37,#11,#12);
#37= CARTESIAN_POINT('POCKET1 DEPTH',(0.000,0.000,-8.000));
#38= PLANAR_POCKET_BOTTOM_CONDITION();
{profile}
#40= AXIS2_PLACEMENT_3D('POCKET1 PROFILE',#41,#11,#12);
#41= CARTESIAN_POINT('POCKET1 PROFILE',{_point(profile_at)});
#42= PLUS_MINUS_VALUE(0.010,0.010,3);
#43= TOLERANCED_LENGTH_MEASURE({width:.3f},#42);
#44= TOLERANCED_LENGTH_MEASURE({length:.3f},#42);
#50= {rough}($,$,'ROUGH POCKET1',10.000,$,#22,{rough_technology},#25,$,#26,$,#27,4.000,$,0.500,0.200);
#51= {finish}($,$,'FINISH POCKET1',10.000,$,{finish_tool},{finish_technology},#25,$,#26,$,#28,4.000,$,$,$);
#60= MACHINING_WORKINGSTEP('WS ROUGH POCKET1',#6,#30,#50,$);
#61= MACHINING_WORKINGSTEP('WS FINISH POCKET1',#6,#30,#51,$);
#62= MACHINING_WORKINGSTEP('WS DRILL HOLE1',#6,#230,#232,$);
ENDSEC;
END-ISO-10303-21;
"""


def _point(at) -> str:
    at = (0.0, 0.0, 0.0) if at is None else tuple(at) + (0.0,) * (3 - len(at))
    return "(" + ",".join(f"{v:.3f}" for v in at) + ")"


def numbers_from_text(text: str) -> dict:
    """The pocket's and the profile's locations, its sizes and the BLOCK, read by regular expressions."""
    def point(ident):
        found = re.search(rf"^#{ident}= CARTESIAN_POINT\('[^']*',\(([^)]*)\)\);", text, re.MULTILINE)
        return np.array([float(v) for v in found.group(1).split(",")])
    width = float(re.search(r"^#43= TOLERANCED_LENGTH_MEASURE\(([-\d.]+)", text, re.MULTILINE).group(1))
    length = float(re.search(r"^#44= TOLERANCED_LENGTH_MEASURE\(([-\d.]+)", text, re.MULTILINE).group(1))
    block = re.search(r"^#7= BLOCK\('[^']*',#13,([-\d.]+),([-\d.]+),([-\d.]+)\);", text, re.MULTILINE)
    corner = point(15)
    return {"pocket": point(32), "profile": point(41), "length": length, "width": width,
            "stock": (corner, corner + np.array([float(block.group(k)) for k in (1, 2, 3)]))}


def finishing_extent(program):
    """XY extent of the finishing operation's cutting moves: the tool centre R inside the walls."""
    finish = program.operations[1]
    cuts = finish.xyz[finish.kind == FEED]
    return cuts[:, :2].min(axis=0), cuts[:, :2].max(axis=0)


def test_the_standard_composition_is_kept():
    """Profile placement relative to the feature (ISO 14649-10): the pocket at (50, 40) with its
    profile 10 mm along x, so its centre is (60, 40); no warning."""
    text = pocket_file(pocket_at=(50.0, 40.0), profile_at=(10.0, 0.0))
    n = numbers_from_text(text)
    loaded = load_workplan(text)
    assert loaded.warnings == ()
    centre = n["pocket"][:2] + n["profile"][:2]
    low, high = finishing_extent(to_program(loaded))
    half = np.array([n["length"], n["width"]]) / 2 - TOOL_DIAMETER / 2
    np.testing.assert_allclose(low, centre - half, atol=0.01)
    np.testing.assert_allclose(high, centre + half, atol=0.01)


def test_pocket_placement_written_twice_is_read_once_with_a_warning():
    """The generator wrote the pocket's absolute placement (75, 50) again as the profile's.
    Composed, the pocket would sit at (150, 100), off the 120 x 80 stock; read once, it is cut at
    (75, 50), inside the stock, and the warning names the feature."""
    text = pocket_file(pocket_at=(75.0, 50.0), profile_at=(75.0, 50.0, 0.0))
    n = numbers_from_text(text)
    loaded = load_workplan(text)
    assert len(loaded.warnings) == 1
    warning = loaded.warnings[0]
    assert "#30 CLOSED_POCKET 'POCKET1'" in warning and "read as absolute" in warning and "BLOCK #7" in warning
    program = to_program(loaded)
    low, high = finishing_extent(program)
    half = np.array([n["length"], n["width"]]) / 2 - TOOL_DIAMETER / 2
    np.testing.assert_allclose(low, n["pocket"][:2] - half, atol=0.01)
    np.testing.assert_allclose(high, n["pocket"][:2] + half, atol=0.01)
    # every cut stays on the stock, and the simulation removes the pocket's volume (less corners)
    (x0, y0, z0), (x1, y1, z1) = n["stock"]
    for op in program.operations:
        cuts = op.xyz[op.kind == FEED]
        assert (cuts[:, 0] - TOOL_DIAMETER / 2 >= x0 - 1e-9).all() and (cuts[:, 0] + TOOL_DIAMETER / 2 <= x1).all()
        assert (cuts[:, 1] - TOOL_DIAMETER / 2 >= y0 - 1e-9).all() and (cuts[:, 1] + TOOL_DIAMETER / 2 <= y1).all()
    result = simulate(program, BoxStock(x0, y0, z0, x1, y1, z1), cell=0.25)
    assert result.findings == []
    corners = (4 - np.pi) * (TOOL_DIAMETER / 2) ** 2          # a square corner keeps R^2 (4 - pi) / 4 each
    expected = (n["length"] * n["width"] - corners) * 8.0
    assert result.removed_volume_mm3 == pytest.approx(expected, rel=0.01)


def test_repeated_placement_without_a_block():
    """No BLOCK to check against: a profile placement that repeats the feature's location is read
    once, with a warning saying so."""
    text = pocket_file(pocket_at=(75.0, 50.0), profile_at=(75.0, 50.0, 0.0), block=False)
    n = numbers_from_text(text)
    loaded = load_workplan(text)
    assert len(loaded.warnings) == 1 and "repeats the pocket's placement" in loaded.warnings[0]
    assert "no stock BLOCK" in loaded.warnings[0]
    low, high = finishing_extent(to_program(loaded))
    assert np.allclose((low + high) / 2, n["pocket"][:2], atol=0.01)


def test_pocket_off_the_stock_either_way_is_reported():
    """A pocket at (110, 70) with a profile offset (30, 0): off the stock composed (140, 70) and
    read absolute (30, 0 is the profile centre, the pocket then reaches below Y 0): cut as written,
    never silently."""
    text = pocket_file(pocket_at=(110.0, 70.0), profile_at=(30.0, 0.0))
    loaded = load_workplan(text)
    assert len(loaded.warnings) == 1
    assert "beyond the stock BLOCK #7" in loaded.warnings[0] and "cut as written" in loaded.warnings[0]


# --------------------------------------------------------------------------- tools, technology, reasons


def test_one_tool_number_per_distinct_tool():
    """Rough and finish name two instances (#22, #122) of the same 10 mm end mill: one T number;
    the drill is the second."""
    from kezuri import post

    loaded = load_workplan(pocket_file(finish_tool="#122", hole=True))
    program = to_program(loaded)
    assert [op.tool.number for op in program.operations] == [1, 1, 2]
    text = post.milling_post("linuxcnc").to_text(program)
    assert sorted(set(re.findall(r"\bT(\d+)\s*M0?6", text))) == ["1", "2"]


def test_a_workingstep_without_a_feed_is_skipped_with_its_reason():
    """Finishing (#61) names technology #124, which has no feedrate: it is skipped, the rest is
    cut, every operation carries its workingstep, and the reason is noted once."""
    loaded = load_workplan(pocket_file(finish_technology="#124", hole=True))
    program = to_program(loaded)
    assert [op.source_id for op in program.operations] == [60, 62]
    assert [op.name for op in program.operations] == ["WS ROUGH POCKET1", "WS DRILL HOLE1"]
    skipped = [note for note in program.notes if "skipped" in note]
    assert len(skipped) == 1
    assert "workingstep #61 'WS FINISH POCKET1' skipped: #124 MILLING_TECHNOLOGY: no positive feedrate" in skipped[0]


def test_rpm_written_where_the_standard_says_rev_per_second():
    """Technology #125 gives 17544.63 as the spindle; ISO 14649 reads rev/s (S1052678); the number is
    an rpm, as 2012-era files wrote it: S17545 is written, with a note."""
    from kezuri import post

    text = pocket_file(rough_technology="#125")
    written = float(re.search(r"^#125= MILLING_TECHNOLOGY\([^,]*,[^,]*,[^,]*,(-?[\d.]+)", text, re.MULTILINE).group(1))
    program = to_program(load_workplan(text))
    rough = program.operations[0]
    assert rough.spindle_rpm == pytest.approx(abs(written))
    assert abs(written) * 60 > 1e6                            # what the standard's unit would give
    notes = [note for note in program.notes if "rev/s" in note]
    assert len(notes) == 1 and "#125 MILLING_TECHNOLOGY" in notes[0] and "S1052678" in notes[0]
    assert "S17545" in post.milling_post("fanuc").to_text(program)


def test_feeds_the_tool_cannot_run_are_flagged():
    """2 m/s = 120000 mm/min at 6000 rpm with 4 teeth: 5 mm per tooth for a 10 mm end mill."""
    program = to_program(load_workplan(pocket_file(rough_technology="#126")))
    flagged = [note for note in program.notes if "#126 MILLING_TECHNOLOGY" in note]
    assert any("feed 120000 mm/min" in note for note in flagged)
    assert any("5 mm per tooth is too much for the 10 mm tool with 4 teeth" in note for note in flagged)
    assert all(note.startswith("workingstep #60 'WS ROUGH POCKET1'") for note in flagged)


def test_nothing_to_machine_lists_the_reason_of_every_workingstep():
    from kezuri.toolpath.operations.stepnc import nothing_to_machine

    loaded = load_workplan(pocket_file(rough="SIDE_ROUGH_MILLING", finish="SIDE_FINISH_MILLING"))
    assert loaded.workingsteps == ()
    reason = nothing_to_machine(loaded.warnings)
    assert "workingstep #60 'WS ROUGH POCKET1' skipped: SIDE_ROUGH_MILLING #50 is not supported" in reason
    assert "workingstep #61 'WS FINISH POCKET1' skipped: SIDE_FINISH_MILLING #51 is not supported" in reason
    assert "switched off" not in reason


def test_the_new_warnings_have_japanese_templates():
    """Every warning these files give comes out in Japanese (operators/translations.py)."""
    pytest.importorskip("bpy")
    from kezuri.operators import translations
    from kezuri.toolpath.operations.stepnc import nothing_to_machine

    files = [pocket_file(pocket_at=(75.0, 50.0), profile_at=(75.0, 50.0, 0.0)),
             pocket_file(pocket_at=(75.0, 50.0), profile_at=(75.0, 50.0, 0.0), block=False),
             pocket_file(pocket_at=(110.0, 70.0), profile_at=(30.0, 0.0))]
    messages = [warning for text in files for warning in load_workplan(text).warnings]
    for kwargs in ({"finish_technology": "#124"}, {"rough_technology": "#125"}, {"rough_technology": "#126"}):
        program = to_program(load_workplan(pocket_file(**kwargs)))
        messages += [note.split(": ", 1)[1] if note.startswith("workingstep #60") else note for note in program.notes]
    unsupported = load_workplan(pocket_file(rough="SIDE_ROUGH_MILLING", finish="SIDE_FINISH_MILLING"))
    messages.append(nothing_to_machine(unsupported.warnings))
    assert len(messages) >= 8
    for message in messages:
        japanese = translations.japanese_message(message)
        assert japanese is not None and re.search(r"[\u3040-\u30ff\u4e00-\u9fff]", japanese), message


def test_general_profile_placement_written_twice():
    """The same convention on a GENERAL_CLOSED_PROFILE: its POLYLINE's corners are relative to the
    profile's placement, which repeats the pocket's (75, 50)."""
    text = pocket_file(pocket_at=(75.0, 50.0), profile_at=(75.0, 50.0, 0.0), general=True)
    assert "GENERAL_CLOSED_PROFILE(#40,#70)" in text
    n = numbers_from_text(text)
    loaded = load_workplan(text)
    assert len(loaded.warnings) == 1 and "#30 CLOSED_POCKET 'POCKET1'" in loaded.warnings[0]
    low, high = finishing_extent(to_program(loaded))
    half = np.array([n["length"], n["width"]]) / 2 - TOOL_DIAMETER / 2
    np.testing.assert_allclose(low, n["pocket"][:2] - half, atol=0.01)
    np.testing.assert_allclose(high, n["pocket"][:2] + half, atol=0.01)
    # composed as the standard says when the profile sits at the feature's zero point: no warning
    plain = load_workplan(pocket_file(pocket_at=(75.0, 50.0), general=True))
    assert plain.warnings == ()
    low, high = finishing_extent(to_program(plain))
    np.testing.assert_allclose((low + high) / 2, n["pocket"][:2], atol=0.01)
