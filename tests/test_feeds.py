"""Materials, feeds and speeds: the calculator against worked examples read off the cited charts (the
numbers here are the charts', typed from them, never the code's), the safe band and its flags, the
user's override flagged, hostile values refused with the value named, and ``batch.py feeds`` run
in-process."""
import contextlib
import io
import json
import math

import numpy as np
import pytest

from kezuri.toolpath.feeds import calculator, materials, programcheck
from kezuri.toolpath.ir import machine as machines
from kezuri.toolpath.ir.errors import InputError
from kezuri.toolpath.ir.program import FEED, RAPID, Operation, Tool

IN = 25.4          # mm per inch: the charts print inches


# ----- worked examples from the charts ------------------------------------------------------------------

def test_ast_hardwood_quarter_inch_band_and_the_amana_solid_wood_feeds_at_18000_rpm():
    """AST Tooling: hardwood, 1/4 in bit: chip load .005 - .007 in.  Amana's 2-flute solid-wood
    chart, 1/4 in at 18,000 rpm: 180 - 250 ipm for .005 - .007 in (180 = 18000 x 2 x .005)."""
    low, high, aim, note, source = calculator.band("hardwood", "flat", 0.25 * IN)
    assert (low, high) == pytest.approx((0.005 * IN, 0.007 * IN))
    assert note == "" and "asttooling.com" in source and "Hardwood" in source
    at_18000 = calculator.compute("flat", 0.25 * IN, "hardwood", 2, "profile", rpm=18000)
    assert at_18000.feed == pytest.approx(round(18000 * 2 * 0.006 * IN))        # mid band, 216 ipm
    for ipm in (180, 250):          # Amana's feed range for the same bit: inside the AST band
        found = calculator.check("flat", 0.25 * IN, "hardwood", 18000, ipm * IN, 2)
        assert found.flags == ()
    assert calculator.check("flat", 0.25 * IN, "hardwood", 18000, 100 * IN, 2).flags[0].kind == "rubbing"
    assert calculator.check("flat", 0.25 * IN, "hardwood", 18000, 300 * IN, 2).flags[0].kind == "overload"


@pytest.mark.parametrize("key, inch, low, high", [
    ("mdf", 0.5, 0.020, 0.025), ("mdf", 0.125, 0.004, 0.007), ("softwood", 0.375, 0.015, 0.017),
    ("plywood", 0.5, 0.018, 0.021), ("hdpe", 0.25, 0.006, 0.009), ("acrylic", 0.5, 0.010, 0.013),
    ("hardwood", 0.125, 0.002, 0.004), ("aluminium", 0.375, 0.0015, 0.0035), ("aluminium", 0.1875, 0.0008, 0.0018),
    ("brass", 0.25, 0.0005, 0.002), ("brass", 0.5, 0.002, 0.003)])
def test_every_material_reads_its_chart_row(key, inch, low, high):
    got = calculator.band(key, "flat", inch * IN)
    assert got[:2] == pytest.approx((low * IN, high * IN))
    assert materials.material(key).chip.source.count("http") == 1


def test_between_rows_the_band_is_interpolated_and_below_the_smallest_it_scales_with_the_diameter():
    # hardwood 1/8 in .002-.004, 1/4 in .005-.007: 3/16 in lies halfway
    low, high, *_ = calculator.band("hardwood", "flat", 0.1875 * IN)
    assert (low, high) == pytest.approx((0.0035 * IN, 0.0055 * IN))
    # a 1/16 in bit: half the 1/8 in row
    low, high, _, note, _ = calculator.band("hardwood", "flat", 0.0625 * IN)
    assert (low, high) == pytest.approx((0.001 * IN, 0.002 * IN)) and "scaled" in note
    low, high, _, note, _ = calculator.band("hardwood", "flat", 1.0 * IN)
    assert (low, high) == pytest.approx((0.017 * IN, 0.019 * IN)) and "largest" in note


def test_brass_reads_the_iti_chart_as_it_is_printed_up_to_a_diameter():
    """ITI: brass / soft bronze, end mills up to 1/4 in .0005 - .002, up to 1/2 in .002 - .003 in."""
    for inch, low, high in ((0.125, 0.0005, 0.002), (0.25, 0.0005, 0.002), (0.3, 0.002, 0.003), (0.5, 0.002, 0.003)):
        assert calculator.band("brass", "flat", inch * IN)[:2] == pytest.approx((low * IN, high * IN))


def test_aluminium_carbide_rpm_from_the_hit_surface_speed_and_hss_from_the_grizzly_table():
    """HIT: aluminium 6061 800 - 2200 sfm (aim: 1500); Grizzly / Machinery's Handbook: HSS in aluminium
    300 sfm.  rpm = sfm x 12 / (pi x D in)."""
    carbide = calculator.compute("flat", 0.25 * IN, "aluminium", 3, "pocket")
    assert carbide.rpm == pytest.approx(1500 * 12 / (math.pi * 0.25), abs=1)          # 22,918 rpm
    hss = calculator.compute("flat", 0.25 * IN, "aluminium", 3, "pocket", tool_material="hss")
    assert hss.rpm == pytest.approx(300 * 12 / (math.pi * 0.25), abs=1)              # 4,584 rpm
    # the chart's own rule of thumb, rpm = sfm x 3.82 / D: within 0.1 %
    assert hss.rpm == pytest.approx(300 * 3.82 / 0.25, rel=1e-3)
    assert "HSS" in hss.sources["surface_speed"] and "no HSS chart" in hss.sources["chip_load"]
    # feed = rpm x flutes x mid chip load (HIT 1/4 in: .001 - .0022 in)
    assert carbide.feed == pytest.approx(round(carbide.rpm * 3 * 0.0016 * IN))


def test_amana_v_groove_chip_loads_at_18000_rpm():
    """Amana carbide-tipped V-groove bits at 18,000 rpm: hardwood 90 ipm / .0024 in, MDF 180 ipm / .0048 in."""
    hard = calculator.compute("vbit", 12.7, "hardwood", 2, "vcarve", rpm=18000)
    assert hard.feed == pytest.approx(round(18000 * 2 * 0.0024 * IN))
    assert hard.feed == pytest.approx(90 * IN, rel=0.05)             # the chart's rounded 90 ipm
    mdf = calculator.compute("vbit", 12.7, "mdf", 2, "vcarve", rpm=18000)
    assert mdf.feed == pytest.approx(180 * IN, rel=0.05)
    assert hard.flags == () and mdf.flags == ()
    # the band of a V-bit is the chart's smallest (1/8 in) row: hardwood .002 - .004 in
    assert hard.band == pytest.approx((0.002 * IN, 0.004 * IN))
    assert "V-Groove" in hard.sources["chip_load"]
    assert hard.step_down is None and hard.step_over is None


def test_plunge_is_the_feed_over_the_flutes_and_steps_follow_the_operation_kind():
    result = calculator.compute("flat", 6.0, "mdf", 3, "pocket")
    assert result.plunge_feed == pytest.approx(round(result.feed / 3))        # Amana: ramp = IPM / flutes
    assert (result.step_down, result.step_over) == pytest.approx((3.0, 2.4))  # HIT: ADOC 50 %, RDOC 40 %
    assert calculator.compute("flat", 6.0, "mdf", 2, "profile").step_down == pytest.approx(6.0)   # 1 x D
    engrave = calculator.compute("ball", 6.0, "hardwood", 2, "engrave")
    assert engrave.step_over == pytest.approx(3.0)                            # the paper: 3 mm with a 6 mm ball
    carve = calculator.compute("ball", 6.0, "hardwood", 2, "carve")
    # a 0.05 mm scallop between passes of a 3 mm radius ball: 2 sqrt(h (D - h))
    assert carve.step_over == pytest.approx(2 * math.sqrt(0.05 * 5.95))
    drill = calculator.compute("drill", 5.0, "hardwood", 2, "drill")
    assert drill.plunge_feed == drill.feed and drill.step_down == pytest.approx(5.0)


# ----- drills: fed per revolution -------------------------------------------------------------------------

NAVY_IPR = [(0.125, 0.001, 0.002), (0.25, 0.002, 0.004), (0.5, 0.004, 0.007), (1.0, 0.007, 0.015)]


def test_a_quarter_inch_hss_drill_in_hardwood_from_the_drilling_charts_by_hand():
    """Worked by hand: wood 300 - 400 sfm for HSS drills (bestdrillbit.com), the middle 350 sfm x
    0.3048 = 106.68 m/min; 106,680 mm/min / (pi x 6.35 mm) = 5,347.6 -> 5348 rpm.  Feed per
    revolution for a 1/8 - 1/4 in drill .002 - .004 in (the US Navy manual), the middle .003 in =
    0.0762 mm; 5348 x 0.0762 = 407.5 -> 408 mm/min, and it plunges at that (not the end mill's
    3,726 mm/min of the router chart)."""
    result = calculator.compute("drill", 6.35, "hardwood", None, "drill", tool_material="hss")
    assert result.rpm == 5348 and result.feed == 408 and result.plunge_feed == 408
    assert result.per == "revolution" and result.chip_load == pytest.approx(408 / 5348)
    assert result.band == pytest.approx((0.002 * IN, 0.004 * IN)) and result.flags == ()
    assert "tpub.com" in result.sources["chip_load"] and "bestdrillbit" in result.sources["surface_speed"]
    assert result.as_dict()["chip_load_per"] == "revolution"
    end_mill = calculator.compute("flat", 6.35, "hardwood", 2, "drill")     # a helix-milled hole: the router chart
    assert (end_mill.rpm, end_mill.feed) == (12223, 3726)


def test_a_drills_feed_per_revolution_does_not_depend_on_its_flutes_and_harder_materials_take_the_low_end():
    one, two = (calculator.compute("drill", 10.0, "mdf", f, "drill", tool_material="hss") for f in (1, 2))
    assert (one.rpm, one.feed) == (two.rpm, two.feed)
    # 10 mm: the 1/4 - 1/2 in row, .004 - .007 in/rev; MDF (wood) the middle .0055 in
    assert one.feed == round(one.rpm * 0.0055 * IN)
    # aluminium, HSS: 200 - 300 fpm (Navy) -> 250 x 0.3048 = 76.2 m/min / (pi x 10) = 2425.5 -> 2426 rpm;
    # the row's low end .004 in = 0.1016 mm: 2426 x 0.1016 = 246.5 -> 246 mm/min
    alu = calculator.compute("drill", 10.0, "aluminium", None, "drill", tool_material="hss")
    assert (alu.rpm, alu.feed) == (2426, 246)
    # carbide: the HSS speed doubled (500 fpm): 152.4 m/min / (pi x 10) = 4851 rpm
    assert calculator.compute("drill", 10.0, "aluminium", None, "drill").rpm == 4851
    # plastics 150 - 250 sfm (MachinistPost), 200 x 0.3048 / (pi x 3.175 mm) = 6112 rpm; under 1/8 in .001 - .002
    small = calculator.compute("drill", 3.175, "acrylic", None, "drill", tool_material="hss")
    assert small.rpm == 6112 and small.feed == round(6112 * 0.0015 * IN)
    for inch, low, high in NAVY_IPR:
        band = calculator.band("hardwood", "drill", inch * IN)
        assert band[:2] == pytest.approx((low * IN, high * IN))


def test_a_drill_fed_like_an_end_mill_is_flagged_as_overload_per_revolution():
    found = calculator.check("drill", 6.35, "hardwood", 12223, 3726, 2, "hss")
    (flag,) = found.flags
    # 3726 / 12223 = 0.3048 mm per revolution against .002 - .004 in (0.0508 - 0.1016 mm)
    assert flag.kind == "overload" and flag.value == pytest.approx(0.3048, abs=1e-4)
    assert "0.3048 mm per revolution" in flag.message and "0.0508 - 0.1016" in flag.message
    slow = calculator.check("drill", 6.35, "hardwood", 5348, 100, 2, "hss")
    assert [f.kind for f in slow.flags] == ["rubbing"]                    # 0.0187 mm/rev


def test_every_material_has_drill_speeds_citing_a_source():
    for row in materials.table():
        assert set(row["drill_speed_sfm"]) == {"carbide", "hss"}
        assert all("http" in source for source in row["drill_speed_source"].values())
        assert "http" in row["drill_feed_source"]
        hss, carbide = row["drill_speed_sfm"]["hss"], row["drill_speed_sfm"]["carbide"]
        assert carbide == [2 * hss[0], 2 * hss[1]]


def test_the_calculator_takes_every_flute_count_the_tool_library_takes():
    from kezuri.toolpath.tooling import library
    assert library.MAX_FLUTES == calculator.MAX_FLUTES == 20
    assert calculator.compute("flat", 25.0, "mdf", 20).flutes == 20
    with pytest.raises(InputError, match="flutes = 21: must be a whole number 1..20"):
        calculator.compute("flat", 25.0, "mdf", 21)
    assert library.LibraryTool(1, "flat", 25.0, flutes=20).flutes == 20


# ----- the machine ----------------------------------------------------------------------------------------

def small_machine(spindle=10000.0, feed=1000.0):
    return machines.preset("fanuc-vmc").replace(name="small", label="small", max_spindle_rpm=spindle, max_feed=feed)


def test_the_machine_caps_the_spindle_and_the_feed_and_the_chip_load_it_then_gives_is_shown_and_flagged():
    result = calculator.compute("flat", 0.25 * IN, "mdf", 2, "profile", small_machine())
    assert result.rpm == 10000 and result.feed == 1000
    assert result.chip_load == pytest.approx(1000 / (10000 * 2))          # 0.05 mm
    assert [f.kind for f in result.flags] == ["rubbing"]                  # MDF 1/4 in: .012 - .015 in
    assert result.flags[0].band == pytest.approx((0.012 * IN, 0.015 * IN))
    assert any("capped" in n for n in result.notes)


def test_values_beyond_the_machine_are_flagged_with_the_number_and_the_machine_band():
    found = calculator.check("flat", 6.0, "hardwood", 30000, 20000, 2, machine=small_machine())
    kinds = {f.kind: f for f in found.flags}
    assert kinds["spindle above machine"].value == 30000 and kinds["spindle above machine"].band == (0.0, 10000.0)
    assert kinds["feed above machine"].value == 20000 and kinds["feed above machine"].band == (0.0, 1000.0)
    assert "30000" in kinds["spindle above machine"].message and "10000" in kinds["spindle above machine"].message


# ----- the user's override --------------------------------------------------------------------------------

def test_the_papers_engraving_values_are_kept_and_flagged_as_rubbing_in_hardwood():
    """The engraving workflow's 6 mm ball at S6000 (the paper) and 1200 mm/min: 0.1 mm per tooth with
    two flutes, below hardwood's band at 6 mm (the 1/8 - 1/4 in rows interpolated)."""
    result = calculator.compute("ball", 6.0, "hardwood", 2, "engrave", rpm=6000, feed=1200)
    assert result.rpm == 6000 and result.feed == 1200            # kept as given
    t = (6.0 / IN - 0.125) / 0.125
    low, high = (0.002 + t * 0.003) * IN, (0.004 + t * 0.003) * IN
    assert result.chip_load == pytest.approx(0.1)
    (flag,) = result.flags
    assert flag.kind == "rubbing" and flag.value == pytest.approx(0.1) and flag.band == pytest.approx((low, high))
    assert "0.1000" in flag.message and f"{low:.4f}" in flag.message and f"{high:.4f}" in flag.message
    heavy = calculator.compute("ball", 6.0, "hardwood", 2, "engrave", rpm=6000, feed=5000)
    assert [f.kind for f in heavy.flags] == ["overload"]


# ----- hostile values ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("args, named", [
    (("flat", 0, "hardwood"), "0"), (("flat", -3, "hardwood"), "-3"), (("flat", float("nan"), "hardwood"), "nan"),
    (("flat", float("inf"), "hardwood"), "inf"), (("flat", "6", "hardwood"), "'6'"), (("flat", True, "hardwood"), "True"),
    (("saw", 6, "hardwood"), "'saw'"), (("flat", 6, "oak"), "'oak'"), (("flat", 6, None), "None"),
    (("flat", 6, ""), "''")])
def test_hostile_tools_and_materials_are_refused_naming_the_value(args, named):
    with pytest.raises(InputError) as error:
        calculator.compute(*args)
    assert named in str(error.value)


@pytest.mark.parametrize("keywords, named", [
    ({"flutes": 0}, "flutes = 0"), ({"flutes": 2.5}, "flutes = 2.5"), ({"flutes": True}, "flutes = True"),
    ({"operation": "mill"}, "'mill'"), ({"tool_material": "steel"}, "'steel'"),
    ({"rpm": 0}, "spindle rpm = 0"), ({"rpm": float("nan")}, "nan"), ({"feed": -5}, "feed = -5"),
    ({"plunge_feed": 0}, "plunge feed = 0")])
def test_hostile_options_are_refused_naming_the_option_and_value(keywords, named):
    with pytest.raises(InputError) as error:
        calculator.compute("flat", 6.0, "hardwood", **keywords)
    assert named in str(error.value)


def test_every_material_row_cites_a_source_with_an_address():
    for row in materials.table():
        assert "http" in row["chip_source"]
        assert all("http" in source for source in row["speed_source"].values())
        assert set(row["surface_speed_sfm"]) == {"carbide", "hss"}
    assert "magnolia" in materials.material("hardwood").examples.lower()
    assert materials.material("Aluminum").key == "aluminium"


# ----- the check of a planned program -----------------------------------------------------------------------

def operation(name, tool, rpm, feeds):
    """Straight cuts along X at Z -1, each 10 mm long, at the given feeds; a plunge at 100 mm/min first."""
    n = len(feeds)
    xyz = np.array([[0, 0, 5], [0, 0, -1]] + [[10.0 * (i + 1), 0, -1] for i in range(n)], float)
    kind = np.array([RAPID, FEED] + [FEED] * n, np.int8)
    feed = np.array([np.nan, 100.0] + list(feeds), float)
    return Operation(name, tool, rpm, kind, xyz, feed)


def test_a_planned_program_is_checked_at_the_feed_that_carries_its_cutting_length():
    ball = Tool(2, "ball", 6.0)
    flat = Tool(3, "flat", 1.0)
    ops = [operation("rough", ball, 6000, [1200, 1200, 1200]), operation("band", flat, 12000, [600, 600])]
    entries = programcheck.check_program(ops, "hardwood")
    rough, band = entries
    assert rough["feed_mm_min"] == 1200 and rough["chip_load_mm"] == pytest.approx(0.1)   # not the 100 plunge
    assert [f["kind"] for f in rough["flags"]] == ["rubbing"]
    assert rough["assumed"] == ["flutes", "tool material"] and rough["flutes"] == 2
    # the 1 mm flat: 600 / (12000 x 2) = 0.025 mm; 1 mm is below the 1/8 in row: .002-.004 in x 1 / 3.175
    assert band["chip_load_mm"] == pytest.approx(0.025)
    assert band["band_mm"] == pytest.approx([round(0.002 * IN / 3.175, 4), round(0.004 * IN / 3.175, 4)])
    assert band["flags"] == []
    lines = programcheck.warnings(entries)
    assert len(lines) == 1 and lines[0].startswith("feeds: operation 'rough' (T2 6 mm ball end mill) in hardwood:")
    assert programcheck.chip_loads(entries) == {2: [0.1], 3: [0.025]}


def test_a_short_fast_link_is_checked_for_overload_too():
    ops = [operation("rough", Tool(2, "flat", 6.0), 18000, [5000, 5000, 5000, 20000])]
    (entry,) = programcheck.check_program(ops, "hardwood")
    assert entry["feed_mm_min"] == 5000 and entry["fastest_feed_mm_min"] == 20000
    assert [f["kind"] for f in entry["flags"]] == ["overload"]


# ----- batch.py feeds, in-process ------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def batch_module():
    from test_hostile_batch import BATCH
    return BATCH


def feeds_cli(batch_module, *argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            status = batch_module.main(["batch.py", "feeds", *argv])
        except SystemExit as exit_:
            status = exit_.code
    return status, out.getvalue(), err.getvalue()


def test_batch_feeds_prints_the_values_and_their_sources_as_json(batch_module):
    status, out, err = feeds_cli(batch_module, "--tool", "flat:6.35:2", "--material", "hardwood", "--operation",
                                 "profile", "--machine", "fanuc-vmc", "--rpm", "18000")
    assert status == 0, err
    result = json.loads(out)["feeds"]
    assert result["spindle_rpm"] == 18000 and result["feed_mm_min"] == pytest.approx(round(18000 * 2 * 0.006 * IN))
    assert result["band_mm"] == pytest.approx([round(0.005 * IN, 4), round(0.007 * IN, 4)])
    assert "asttooling.com" in result["sources"]["chip_load"] and result["flags"] == []
    assert json.loads(out)["machine"]["name"] == "fanuc-vmc"


def test_batch_feeds_flags_an_override_beyond_the_machine(batch_module):
    status, out, err = feeds_cli(batch_module, "--tool", "ball:6", "--material", "hardwood", "--rpm", "60000",
                                 "--machine", "linuxcnc-manual", "--tool-material", "hss")
    assert status == 0, err
    flags = json.loads(out)["feeds"]["flags"]
    top = machines.preset("linuxcnc-manual").max_spindle_rpm
    assert any(f["kind"] == "spindle above machine" and f["value"] == 60000 and f["band"][1] == top for f in flags)


@pytest.mark.parametrize("argv, named", [
    (["--tool", "flat:0", "--material", "hardwood"], "--tool 'flat:0'"),
    (["--tool", "flat:-6:2", "--material", "hardwood"], "--tool 'flat:-6:2'"),
    (["--tool", "flat:nan", "--material", "hardwood"], "--tool 'flat:nan'"),
    (["--tool", "saw:6", "--material", "hardwood"], "--tool 'saw:6'"),
    (["--tool", "flat", "--material", "hardwood"], "--tool 'flat'"),
    (["--tool", "flat:6:two", "--material", "hardwood"], "--tool 'flat:6:two'"),
    (["--tool", "flat:6", "--material", "oak"], "--material 'oak'"),
    (["--tool", "flat:6", "--material", "mdf", "--operation", "mill"], "--operation 'mill'"),
    (["--tool", "flat:6", "--material", "mdf", "--machine", "nope"], "--machine 'nope'"),
    (["--tool", "flat:6", "--material", "mdf", "--tool-material", "steel"], "--tool-material 'steel'"),
    (["--tool", "flat:6", "--material", "mdf", "--rpm", "nan"], "--rpm 'nan'"),
    (["--tool", "flat:6", "--material", "mdf", "--feed", "-1"], "--feed '-1'")])
def test_batch_feeds_exits_2_naming_the_option_and_the_value(batch_module, argv, named):
    status, out, err = feeds_cli(batch_module, *argv)
    assert status == 2 and out == ""
    assert named in err, err


def test_batch_feeds_without_a_material_is_an_argparse_error(batch_module):
    status, out, err = feeds_cli(batch_module, "--tool", "flat:6")
    assert status == 2 and "--material" in err
