"""The feeds an operation takes from the calculator (issue 31, item 3: computed per operation and
used): for each tool of a profile, pocket, drilling, chamfer or V-carve, the spindle speed, feeds
and steps left out of its settings, the ones typed kept and flagged.

Expected values are worked here by hand from the charts' printed rows (inches per tooth at a
diameter in inches, surface feet per minute), as :mod:`toolpath.feeds.materials` cites them:
AST Tooling's hardwood chart, 1/8 in: .002 - .004, 1/4 in: .005 - .007 in per tooth; wood with
carbide 600 - 1000 sfm (Grizzly / Machinery's Handbook 300 - 500 sfm for HSS, doubled); Amana's
V-groove chart .0024 in per tooth; Amana's ramp-down = feed / flutes."""
import math

import pytest

from kezuri.toolpath.feeds import operationfeeds as of
from kezuri.toolpath.ir import machine as machines

IN, FT = 25.4, 0.3048
CARBIDE_WOOD_M_MIN = (600 + 1000) / 2 * FT        # the middle of the band, m/min
HSS_WOOD_M_MIN = (300 + 500) / 2 * FT


def rpm_for(diameter_mm, m_min=CARBIDE_WOOD_M_MIN):
    return round(m_min * 1000 / (math.pi * diameter_mm))


def by_setting(record):
    return {name: (v["value"], v["source"]) for name, v in record["values"].items()}


def test_a_quarter_inch_end_mill_profiling_hardwood_from_the_ast_chart_row():
    d = 6.35                                           # 1/4 in: the chart's row, no interpolation
    rpm = rpm_for(d)
    assert rpm == 12223                                # 243.84 m/min / (pi x 6.35 mm)
    chip = 0.006 * IN                                  # the middle of .005 - .007 in
    feed = round(rpm * 2 * chip)
    assert feed == 3726
    added, (record,) = of.operation_feeds("profile", {"diameter": d}, {"tool": of.ToolMake(5, "flat", d)},
                                          "hardwood", None)
    assert added == {"rpm": rpm, "feed": feed, "plunge_feed": round(feed / 2), "step_down": d}
    assert record["band_mm"] == [round(0.005 * IN, 4), round(0.007 * IN, 4)]
    assert record["chip_load_mm"] == pytest.approx(feed / (rpm * 2), abs=1e-4)
    assert record["flags"] == [] and record["tool"]["assumed"] == ["flutes", "tool material"]
    assert all(source == "computed" for _, source in by_setting(record).values())


def test_a_pocket_and_its_rest_end_mill_with_the_machine_capping_the_small_ones_spindle():
    machine = machines.preset("linuxcnc-manual")       # 24000 rpm, 6000 mm/min
    tools = {"tool": of.ToolMake(5, "flat", 6.35), "rest": of.ToolMake(6, "flat", 3.175)}
    added, (main, rest) = of.operation_feeds("pocket", {"rest_diameter": 3.175}, tools, "hardwood", machine)
    assert by_setting(main)["stepover"] == (pytest.approx(0.4 * 6.35), "computed")       # HITCARB roughing 40 %
    assert by_setting(main)["step_down"] == (pytest.approx(0.5 * 6.35), "computed")      # slotting ADOC 50 %
    assert added["entry_feed"] == round(added["feed"] / 2)
    # 1/8 in: 243.84 m/min wants 24446 rpm: the machine's 24000; chip .003 in (the middle of .002 - .004)
    assert rpm_for(3.175) == 24446
    assert added["rest_rpm"] == 24000
    assert added["rest_feed"] == round(24000 * 2 * 0.003 * IN)                          # 3658 mm/min
    assert added["rest_step_down"] == pytest.approx(1.5875, abs=6e-4)
    assert added["rest_stepover"] == pytest.approx(1.27)
    assert "rest_entry_feed" not in added
    assert any("capped at the machine's 24000 rpm" in note for note in rest["notes"])
    # without rest_diameter there is no rest end mill: nothing computed for it
    added, records = of.operation_feeds("pocket", {}, tools, "hardwood", machine)
    assert [r["slot"] for r in records] == ["tool"] and not any(k.startswith("rest_") for k in added)


def test_the_machines_feed_cap_is_applied_and_the_chip_load_it_then_gives_is_flagged():
    machine = machines.preset("linuxcnc-atc").replace(max_feed=2000.0)      # 12000 rpm, feed capped here
    added, (record,) = of.operation_feeds("profile", {}, {"tool": of.ToolMake(5, "flat", 6.35)}, "hardwood", machine)
    assert added["rpm"] == 12000 and added["feed"] == 2000                   # 12000 x 2 x .1524 = 3658 wanted
    assert record["chip_load_mm"] == pytest.approx(2000 / (12000 * 2), abs=1e-4)     # 0.0833 mm
    (flag,) = record["flags"]
    assert flag["kind"] == "rubbing" and flag["band"] == [0.127, 0.178]


def test_a_typed_feed_stays_typed_gives_the_plunge_and_is_flagged_outside_the_band():
    typed = {"feed": 900, "rpm": 12223}
    added, (record,) = of.operation_feeds("profile", typed, {"tool": of.ToolMake(5, "flat", 6.35)}, "hardwood", None)
    assert "feed" not in added and "rpm" not in added
    assert added["plunge_feed"] == 450                                  # Amana: feed / flutes, of the typed feed
    values = by_setting(record)
    assert values["feed"] == (900, "typed") and values["rpm"] == (12223, "typed")
    assert values["plunge_feed"] == (450, "computed")
    assert record["chip_load_mm"] == pytest.approx(900 / (12223 * 2), abs=1e-4)     # 0.0368 mm
    assert [f["kind"] for f in record["flags"]] == ["rubbing"]
    # a typed spindle speed alone: the feed is computed at it (chip .1524 mm)
    added, _ = of.operation_feeds("profile", {"rpm": 18000}, {"tool": of.ToolMake(5, "flat", 6.35)}, "hardwood", None)
    assert added["feed"] == round(18000 * 2 * 0.006 * IN)                            # 5486


def test_the_library_tools_flutes_and_hss_change_the_numbers():
    tool = of.ToolMake(5, "flat", 6.35, flutes=3, material="hss")
    added, (record,) = of.operation_feeds("profile", {}, {"tool": tool}, "hardwood", None)
    rpm = rpm_for(6.35, HSS_WOOD_M_MIN)
    assert added["rpm"] == rpm == 6112
    assert added["feed"] == round(rpm * 3 * 0.006 * IN)
    assert added["plunge_feed"] == round(added["feed"] / 3)
    assert record["tool"]["assumed"] == [] and record["tool"]["flutes"] == 3


def test_a_v_carve_aims_at_amanas_v_groove_chip_load_and_its_clearing_end_mill_at_the_chart():
    tools = {"tool": of.ToolMake(3, "vbit", 12.7), "clear": of.ToolMake(4, "flat", 3.175)}
    added, (vbit, clear) = of.operation_feeds("vcarve", {}, tools, "hardwood", machines.preset("linuxcnc-manual"))
    rpm = rpm_for(12.7)
    assert added["rpm"] == rpm == 6112
    assert added["feed"] == round(rpm * 2 * 0.0024 * IN)                 # 745 mm/min
    assert added["entry_feed"] == round(added["feed"] / 2)
    assert vbit["band_mm"] == [round(0.002 * IN, 4), round(0.004 * IN, 4)]     # the tip: the 1/8 in row
    assert "step_down" not in vbit["values"]                             # the geometry's depth
    assert added["clear_rpm"] == 24000 and added["clear_stepover"] == pytest.approx(1.27)


def test_a_drill_pecks_one_diameter_unless_it_dwells_and_its_helix_mill_only_when_switched_on():
    # the drill (make unknown: carbide) is fed per revolution (the Navy manual's 1/8 - 1/4 in row,
    # .002 - .004 in/rev, middle .003 in = 0.0762 mm) at wood's 300 - 400 sfm doubled for carbide:
    # 700 sfm = 213.36 m/min / (pi x 6.35 mm) = 10,695.3 -> 10695 rpm; x 0.0762 = 814.96 -> 815 mm/min
    tools = {"drill": of.ToolMake(4, "drill", 6.35), "mill": of.ToolMake(5, "flat", 6.35)}
    added, records = of.operation_feeds("drill", {}, tools, "hardwood", None)
    assert added == {"rpm": 10695, "feed": 815, "peck": 6.35} and [r["slot"] for r in records] == ["drill"]
    assert records[0]["band_mm"] == [round(0.002 * IN, 4), round(0.004 * IN, 4)]
    added, _ = of.operation_feeds("drill", {"dwell": 0.5, "peck": 0.0}, tools, "hardwood", None)
    assert "peck" not in added
    added, records = of.operation_feeds("drill", {"helix": True}, tools, "hardwood", None)
    # the helix end mill keeps the router chart: 12223 rpm x 2 x 0.1524 mm = 3726 mm/min
    assert added["mill_rpm"] == 12223 and added["mill_feed"] == 3726 and len(records) == 2


@pytest.mark.parametrize("kind", ["engrave", "carve", "rotary", "stepnc", "turnmill", "punch"])
def test_the_paper_kinds_and_the_others_keep_their_own_values(kind):
    assert of.operation_feeds(kind, {}, {"tool": of.ToolMake(2, "ball", 6.0)}, "hardwood", None) == ({}, [])


def test_a_typed_value_that_is_not_a_number_is_left_for_the_kind_to_refuse():
    tools = {"tool": of.ToolMake(5, "flat", 6.35)}
    for bad in (-1, 0, "fast", True, float("nan")):
        assert of.operation_feeds("profile", {"feed": bad}, tools, "hardwood", None) == ({}, [])
