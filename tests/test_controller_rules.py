"""Every program every post writes for the built-in samples and the test jobs passes an independent
reader of the controls' rules (``controller_rules.py``), and that reader catches each rule."""
import os
import re

import numpy as np
import pytest

import controller_rules as rules
from kezuri import post
from kezuri.post import amada_punch, turnmill_xzc
from kezuri.toolpath.operations.carve import carve, carve_samples
from kezuri.toolpath.operations.engrave import engrave
from kezuri.toolpath.ir import machine
from kezuri.toolpath.operations.sheetmetal import nibbling, placement, unfold
from kezuri.toolpath.operations.rotary import rotary
from kezuri.toolpath.operations.turnmill import turnmill
from kezuri.toolpath.ir.program import Program
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program
from test_engrave import LETTERS, PLATE

EX1 = os.path.join(os.environ.get("KEZURI_FIXTURES", os.path.join(os.path.dirname(__file__), "fixtures")),
                   "iso14649", "ex1.stp")
PAPER_CORNERS = np.array([[0, 0, 0], [0, 30, 100], [100, 50, 100], [100, 40, 0]], float)


def max_f(text: str) -> float:
    return max(float(v) for v in re.findall(r"\bF([0-9.]+)", text))


@pytest.fixture(scope="module")
def programs():
    """(name, control, text) of every program."""
    out = []
    textured = engrave.plan(PLATE, LETTERS).program       # roughing carries its GougeTexture
    baked, _ = engrave.bake(textured)
    for name, control in (("fanuc", "fanuc-mill"), ("linuxcnc", "linuxcnc"), ("grbl", "grbl")):
        out.append((f"engrave {name}", control, post.milling_post(name).to_text(baked)))
    out.append(("engrave fanuc-macro", "fanuc-mill", post.milling_post("fanuc-macro").to_text(textured)))
    sample = rotary.plan(*rotary.sample_job()).program
    for name, control in (("linuxcnc", "linuxcnc-cxz"), ("fanuc", "fanuc-cxz")):
        out.append((f"rotary {name}", control, post.rotary_post(name).to_text(sample)))
    ex1 = to_program(load_workplan(EX1))
    for name, control in (("fanuc", "fanuc-mill"), ("linuxcnc", "linuxcnc"), ("grbl", "grbl")):
        out.append((f"stepnc {name}", control, post.milling_post(name).to_text(ex1)))
    v, f = carve_samples.wave_relief(cell=2.0)
    relief = carve.plan(v, f, carve.CarveSettings(scallop=0.05, step_down=4.0)).program
    for name, control in (("fanuc", "fanuc-mill"), ("linuxcnc", "linuxcnc"), ("grbl", "grbl")):
        out.append((f"carve {name}", control, post.milling_post(name).to_text(relief)))
    v, f, stock = turnmill.sample_part()
    plan = turnmill.plan(v, f, stock, name="sample").program
    out.append(("turnmill xzc", "turnmill-xzc", turnmill_xzc.TurnMillXZCPost().to_text(plan)))
    out.append(("turnmill linuxcnc", "turnmill-linuxcnc", turnmill_xzc.TurnMillLinuxCNCPost().to_text(plan)))
    quad = unfold.unfold_twisted_quad(PAPER_CORNERS, 5, "horizontal")
    out.append(("unfold punch", "amada-04p", punch_program(unfold.compensate_outline(quad.pattern.outline, 10.0))))
    for index, piece in enumerate(unfold.unfold_elbow(90.0, 150.0, 100.0, 5).pieces, start=1):
        out.append((f"elbow punch {index}", "amada-04p",
                    punch_program(unfold.compensate_outline(piece.outline, 10.0))))
    return out


def punch_program(contour, joints=2):
    """A turret-punch program as the sheet-metal workflows write it: placed on the Amada 04P
    preset's sheet, nibbled with merged lines and micro-joints."""
    profile = machine.preset("amada-04p")
    where = placement.place(contour, 10.0, profile)
    lines = nibbling.nibble(contour, 2.0, 10.0, joints=joints).moved(where.offset)
    return amada_punch.AmadaPunchPost().to_text(placement.program(where, lines, 302, 1.6, profile))


def clearance_of(name: str) -> float:
    """The height the safe-z rule counts as clear: the clearance height of the post's default
    machine (tests/controller_rules.py knows no posts; the caller gives it)."""
    for family in ("milling", "cxz"):
        try:
            return post.registry.default_machine(post.find(family, name.split()[-1])).clearance_z
        except post.UnknownPostError:
            continue
    return rules.DEFAULT_CLEARANCE


def test_every_program_passes_the_controller_rules(programs):
    assert len(programs) >= 20
    report = {name: rules.check(text, control, clearance_of(name))[:3] for name, control, text in programs}
    assert {name: found for name, found in report.items() if found} == {}
    # the rule ran: every milling and C-X-Z program lifts Z (a machine move or the clearance) before XY
    milling = [text for _, control, text in programs if control in rules.SAFE_Z_CONTROLS]
    assert len(milling) == 12            # engrave 4 posts, rotary 2, STEP-NC 3, carve 3


# The frames the GRBL and LinuxCNC posts wrote before issue 26 (hand-written here, from the engraving
# program): XY right after the load, Z lifted only after it.
OLD_GRBL = """G21 G17 G90 G94
(LOAD T2 6 MM BALL END MILL, ZERO Z ON THE PLATE TOP)
G00 G90 G54 X-100. Y-49.99 S6000 M03
G00 Z100.
G00 Z20.
Z2.
G01 Z-2. F300.
X-80. Z-2.6 F1200.
G00 Z20.
G00 Z100.
M05
G00 Z100.
(CHANGE TO T3 1 MM FLAT END MILL, ZERO Z ON THE PLATE TOP)
M00
G00 G90 G54 X-3.998 Y-0.188 S12000 M03
G00 Z100.
G00 Z20.
G01 Z-1. F300.
X3. F600.
G00 X10. Y10.
M05
M30
"""
OLD_LINUXCNC = """%
G21 G17 G40 G49 G80 G90 G94
G64 P0.01
M05
G49
T2 M06
G00 G90 G54 X-100. Y-49.99 S6000 M03
G43 H2
G00 Z100.
G00 Z20.
G01 Z-2. F300.
X-80. F1200.
G00 Z100.
M05
G49
M30
%
"""


def test_the_old_frames_are_caught_at_the_line_that_moves_xy():
    grbl = rules.check(OLD_GRBL, "grbl", 20.0)
    assert [(rule, line) for rule, line, _ in grbl] == [("safe-z", 3), ("safe-z", 15), ("safe-z", 20)]
    messages = {line: message for rule, line, message in grbl}
    assert "program start" in messages[3] and "X/Y" in messages[3]
    assert "pause (M00, line 14)" in messages[15]
    assert "program end" in messages[20]           # X10 Y10 after the last cut, at Z -1
    linuxcnc = rules.check(OLD_LINUXCNC, "linuxcnc", 20.0)
    assert [(rule, line) for rule, line, _ in linuxcnc] == [("safe-z", 7)]
    assert "M06, line 6" in linuxcnc[0][2]
    # a lift only to 5 mm is not enough when the caller says the clearance is 20 mm
    low = OLD_LINUXCNC.replace("T2 M06\n", "T2 M06\nG00 Z5.\n")
    assert [(r, line) for r, line, _ in rules.check(low, "linuxcnc", 20.0)] == [("safe-z", 8)]
    # and each old program passes once Z is lifted first
    fixed = OLD_LINUXCNC.replace("T2 M06\n", "T2 M06\nG53 G00 Z0.\n")
    assert rules.check(fixed, "linuxcnc", 20.0) == []
    grbl_fixed = (OLD_GRBL.replace("ZERO Z ON THE PLATE TOP)\nG00 G90", "ZERO Z ON THE PLATE TOP)\nG00 Z20.\nG00 G90")
                  .replace("M00\n", "M00\nG00 Z20.\n").replace("G00 X10. Y10.\n", "G00 Z20.\nX10. Y10.\n"))
    assert rules.check(grbl_fixed, "grbl", 20.0) == []


def test_a_fanuc_change_at_the_reference_position_leaves_z_there():
    assert rules.check(FANUC_GOOD, "fanuc-mill") == []
    # without the G28 before M06 the changer rule fires and Z is unknown at the XY move after it
    found = rules.check(bad(FANUC_GOOD, "G91 G28 Z0.\nG90\nG49\nT01", "G49\nT01"), "fanuc-mill")
    assert ("safe-z", 7) in [(r, line) for r, line, _ in found]


def test_inverse_time_feeds_stay_in_the_fanuc_range(programs):
    texts = {name: text for name, _, text in programs}
    # Before the short moves were merged: F16267657.718 (rotary, Fanuc) and F111311.551 (turn-mill).
    assert max_f(texts["rotary fanuc"]) <= 9000.0
    assert max_f(texts["turnmill xzc"]) <= 9000.0


def test_same_tool_is_not_changed_again(programs):
    texts = {name: text for name, _, text in programs}
    text = texts["stepnc fanuc"]
    changes = re.findall(r"^T(\d+) M06$", text, re.M)
    assert changes and all(a != b for a, b in zip(changes, changes[1:]))
    operations = len(re.findall(r"^\(OPERATION \d+:", text, re.M))
    assert len(changes) < operations                  # ISO 14649 Example 1 uses one tool twice in a row
    # Every operation still re-applies the offset of the tool in the spindle.
    assert len(re.findall(r"^G43 Z\S+ H\d+$", text, re.M)) == operations


FANUC_GOOD = """%
O0001 (T)
G21 G17 G40 G49 G80 G90
M05
G91 G28 Z0.
G90
G49
T01 M06
G00 G90 G54 X0. Y0. S1000 M03
G43 Z50. H01
G01 Z-1. F100.
G00 Z50.
M05
G91 G28 Z0.
G90
M30
%
"""


# The macro confined to cutting: G66.1 on the first raster block, G67 before the retract.
MACRO_GOOD = FANUC_GOOD.replace("G01 Z-1. F100.\nG00 Z50.\n", """G01 Z-1. F100.
G66.1 P7023 X100. F1200.
Y3.
X0.
G67
G00 Z50.
""")


def bad(text, old, new):
    assert old in text
    return text.replace(old, new, 1)


@pytest.mark.parametrize("control, text, rule", [
    ("fanuc-mill", bad(FANUC_GOOD, "O0001 (T)\n", ""), "frame"),
    ("fanuc-mill", bad(FANUC_GOOD, "M30\n", ""), "frame"),
    ("fanuc-mill", bad(FANUC_GOOD, "Z-1.", "Z-1"), "decimal"),
    ("fanuc-mill", bad(FANUC_GOOD, "X0.", "X123456.789"), "range"),
    ("fanuc-mill", bad(FANUC_GOOD, "X0.", "X0.1234"), "word"),
    ("fanuc-mill", bad(FANUC_GOOD, "S1000", "S123456"), "range"),
    ("fanuc-mill", bad(FANUC_GOOD, "H01", "H01 T100000"), "range"),
    ("fanuc-mill", bad(FANUC_GOOD, "G43 Z50. H01", "G43 Z50. H120"), "range"),
    ("fanuc-mill", bad(FANUC_GOOD, "G01 Z-1. F100.", "G93\nG01 Z-1. F16267657.718"), "feed"),
    ("fanuc-mill", bad(FANUC_GOOD, "G01 Z-1. F100.", "G93\nG01 Z-1. F10.\nZ-2."), "g93"),
    ("fanuc-mill", bad(FANUC_GOOD, "G01 Z-1. F100.", "G93\nG01 Z-1. F10"), "decimal"),
    ("fanuc-mill", bad(FANUC_GOOD, " S1000 M03", ""), "spindle"),
    ("fanuc-mill", bad(FANUC_GOOD, "M05\nG91 G28 Z0.\nG90\nG49\nT01", "M03\nG91 G28 Z0.\nG90\nG49\nT01"),
     "toolchange"),
    ("fanuc-mill", bad(FANUC_GOOD, "G91 G28 Z0.\nG90\nG49\nT01", "G49\nT01"), "toolchange"),
    ("fanuc-mill", bad(FANUC_GOOD, "G49\nT01", "G43 Z0. H01\nT01"), "toolchange"),
    ("fanuc-mill", bad(FANUC_GOOD, "G43 Z50. H01\n", "Z50.\n"), "toolchange"),
    ("fanuc-mill", bad(FANUC_GOOD, "G00 Z50.\nM05\n", "G00 Z50.\nM05\nG91 G28 Z0.\nG90\nG49\nT01 M06\n"),
     "toolchange"),
    ("fanuc-mill", bad(MACRO_GOOD, "G67\nG00 Z50.\n", "G00 Z50.\nG67\n"), "modalcall"),   # retract under G66.1
    ("fanuc-mill", bad(MACRO_GOOD, "X0.\nG67\n", "G00 X0.\nG67\n"), "modalcall"),      # reposition under it
    ("fanuc-mill", bad(MACRO_GOOD, "G67\nG00 Z50.\n", "G00 Z50.\n"), "modalcall"),      # never cancelled, M30
    ("fanuc-mill", bad(MACRO_GOOD, "G67\n", ""), "modalcall"),
    ("fanuc-mill", bad(MACRO_GOOD, "G67\n", "G67\nG67\n"), "modalcall"),              # G67 without G66.1
    ("fanuc-mill", bad(MACRO_GOOD, "Y3.\n", "G66.1 P7023 Y3.\n"), "modalcall"),        # nested
    ("fanuc-mill", bad(MACRO_GOOD, "G01 Z-1. F100.\n", "G01 Z-1. F100.\nG00 Z1.\n"), "modalcall"),  # made in G00
    ("fanuc-mill", bad(MACRO_GOOD, "Y3.\n", "Y3. M05\n"), "modalcall"),
    ("linuxcnc", "G21 G90\nT1 M06\nG43 H1\nS1000 M03\nG01 X1 F100\nM05\nG49\nT1 M06\nG43 H1\nM30\n", "toolchange"),
    ("linuxcnc", "G21 G90\nT1 M06\nG43 H1\nS1000 M03\nG93\nG01 X1 F10\nX2\nM30\n", "g93"),
    ("linuxcnc", "G21 G90\nT1 M06\nG43 H1\nS1000 M03\nG01 X1 F0\nM30\n", "feed"),
    ("linuxcnc", "%\nG21 G90\nM30\n", "frame"),
    ("grbl", "G21 G90\nS1000 M03\nG01 X1 F100\nT2 M06\nM30\n", "toolchange"),
    ("grbl", "G21 G90\nS1000 M03\nG01 X1 F100\nM00\nM30\n", "toolchange"),
    ("grbl", "G21 G90\nG43 H1\nM30\n", "toolchange"),
    ("grbl", "N10000000 G21 G90\nM30\n", "range"),
    ("turnmill-xzc", "%\nO0001\nG21 G18\nT0101\nM133 P4000\nG00 X89. Z2. C0.\nG93\nG01 X80. F10.\nG98\n"
     "M135\nM30\n%\n", "toolchange"),
    ("turnmill-xzc", "%\nO0001\nG21 G18\nG28 U0. W0.\nT0101\nM133 P4000\nG00 X89. Z2. C0.\nG93\n"
     "G01 X80. F10.\nG98\nG28 U0. W0.\nT0202\nM135\nM30\n%\n", "toolchange"),
    ("amada-04p", "N000 G92 X1000.00 Y1040.00\nN001 G72 X0.93 Y147.66\nG69 I20.29 J-5.32 P0.00 Q2.00 T302\n", "frame"),
    ("amada-04p", "N000 G92 X1000.00 Y1040.00\nN001 G72 X0.9 Y147.66\nG69 I20.29 J-5.32 P0.00 Q2.00 T302\nG50\n",
     "decimal"),
    ("amada-04p", "N000 G92 X1000.00 Y1040.00\nN1000 G72 X0.93 Y147.66\nG69 I20.29 J-5.32 P0.00 Q2.00 T302\nG50\n",
     "range"),
    ("amada-04p", "N000 G92 X1000.00 Y1040.00\nN001 G72 X0.93 Y147.66\nG69 I20.29 J-5.32 P0.00 Q2.00 T32\nG50\n",
     "range"),
    ("amada-04p", "N000 G92 X1000.00 Y1040.00\nN001 G72 X0.93 Y147.66\nG79 I20.29 J-5.32 P0.00 Q4.00 T302\nG50\n",
     "word"),
])
def test_the_checker_catches_each_rule(control, text, rule):
    found = rules.check(text, control)
    assert rule in {r for r, _, _ in found}, found


def test_the_good_hand_written_program_passes():
    assert rules.check(FANUC_GOOD, "fanuc-mill") == []
    assert rules.check(MACRO_GOOD, "fanuc-mill") == []
    assert rules.check("G21 G90\nT1 M06\nG53 G00 Z0\nG43 H1\nS1000 M03\nG93\nG01 X1 F10\nG94\nM05\nG49\n"
                       "M30\n", "linuxcnc") == []


def test_short_moves_are_merged_within_tolerance_and_the_rest_timed_at_the_floor():
    from kezuri.toolpath.ir.program import FEED, Operation, Tool, merge_short_moves
    tool = Tool(1, "flat", 6.0)
    # Along X: 10 mm, then 0.0004 mm (below the 0.001 mm increment), then 10 mm: the middle point goes.
    op = Operation("line", tool, 1000, [FEED] * 3, [[10, 0, 0], [10.0004, 0, 0], [20, 0, 0]], [600.0] * 3,
                   start=[0, 0, 0])
    merged = merge_short_moves(op, tolerance=0.01)
    assert merged.xyz.tolist() == [[10, 0, 0], [20, 0, 0]]
    # A 0.05 mm step at a right angle (0.05 mm off the merged chord, more than the tolerance): it stays.
    corner = Operation("corner", tool, 1000, [FEED] * 3, [[10, 0, 0], [10, 0.05, 0], [0, 0.05, 0]], [600.0] * 3,
                       start=[0, 0, 0])
    assert len(merge_short_moves(corner, tolerance=0.01)) == 3


def test_a_post_refuses_an_out_of_range_word_naming_operation_move_and_value():
    from kezuri.toolpath.ir.program import FEED, Operation, Tool
    op = Operation("fast", Tool(1, "flat", 6.0), 1000, [FEED, FEED], [[0, 0, -1], [100, 0, -1]],
                   [600.0, 300000.0], start=[0, 0, 5])
    with pytest.raises(post.PostError, match=r"operation 'fast', move 2: feed F \(mm/min\) 300000 is outside "
                                             r"the 0.001..240000"):
        post.milling_post("fanuc").to_text(Program("p", [op]))
    slow = op.replace(feed=np.array([600.0, 600.0]), xyz=np.array([[0, 0, -1], [200000, 0, -1]]))
    with pytest.raises(post.PostError, match=r"coordinate 200000 is outside the -99999.999..99999.999"):
        post.milling_post("fanuc").to_text(Program("p", [slow]))


def test_fanuc_orients_the_spindle_before_the_change_when_asked():
    from kezuri.post.fanuc import FanucPost
    baked, _ = engrave.bake(engrave.plan(PLATE, LETTERS).program)
    text = FanucPost(orient_spindle=True).to_text(baked)
    first = baked.operations[0].tool.number
    assert f"M05\nG91 G28 Z0.\nG90\nG49\nM19\nT{first:02d} M06\n" in text
    assert rules.check(text, "fanuc-mill") == []
    assert "M19" not in FanucPost().to_text(baked)
