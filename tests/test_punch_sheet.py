"""Punching on the sheet (issue 26, deliverable 4): the part at positive sheet coordinates clear
of the clamps, micro-joints that hold it, collinear pieces merged, no hit twice.

The programs are read back as text: by the controller-rules checker (its own reading of the
04P words, given the sheet and the clamps' dead zones as numbers written here) and by the
punching simulation's reader."""
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import controller_rules as rules
from kezuri.post.amada_punch import AmadaPunchPost
from kezuri.toolpath.ir.program import PunchOperation, PunchProgram
from kezuri.toolpath.ir import machine
from kezuri.toolpath.operations.sheetmetal import nibbling, placement, punch, unfold

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PAPER_CORNERS = np.array([[0, 0, 0], [0, 30, 100], [100, 50, 100], [100, 40, 0]], float)
# The Amada 04P preset's sheet and clamps, written out by hand: clamps centred at X 200 and 700,
# each dead zone 80 wide and 50 deep from the clamped edge (Y 0); a 1270 x 1270 sheet.
SHEET = (1270.0, 1270.0)
ZONES = [(160.0, 0.0, 240.0, 50.0), (660.0, 0.0, 740.0, 50.0)]
PUNCH = dict(station=302, pitch=2.0, thickness=1.6)


def program(contour, joints=2, width=0.4, profile=None):
    profile = profile or machine.preset("amada-04p")
    where = placement.place(contour, 10.0, profile)
    lines = nibbling.nibble(contour, 2.0, 10.0, joints=joints, joint_width=width).moved(where.offset)
    text = AmadaPunchPost().to_text(placement.program(where, lines, PUNCH["station"], PUNCH["thickness"], profile))
    return text, lines, where


def written(nib):
    """The nibbled lines as a program of their own (G92 at the post's default origin, no notes)."""
    return AmadaPunchPost().to_text(PunchProgram("part", [nib.operation(PUNCH["station"], PUNCH["thickness"])]))


def quad_contour():
    quad = unfold.unfold_twisted_quad(PAPER_CORNERS, 5, "horizontal")
    return quad.pattern.outline, unfold.compensate_outline(quad.pattern.outline, 10.0)


def elbow_contours():
    out = []
    for piece in unfold.unfold_elbow(90.0, 150.0, 100.0, 5).pieces:
        outline = piece.outline - piece.outline.min(axis=0)
        out.append((outline, unfold.compensate_outline(outline, 10.0)))
    return out


# --- the checker's new rules ---------------------------------------------------------------

OLD = ("N000 G92 X1000.00 Y1040.00\nN001 G72 X-5.00 Y-5.57\nG69 I26.44 J6.13 P0.00 Q2.00 T302\n"
       "N002 G72 X21.29 Y-2.74\nG69 I20.87 J5.95 P0.00 Q2.00 T302\nG50\n")


def test_the_checker_finds_the_old_programs_faults():
    found = rules.check_punch(OLD, sheet=SHEET, clamp_zones=ZONES, punch_radius=5.0)
    kinds = {rule for rule, _, _ in found}
    assert "sheet" in kinds                        # Y-5.57: off the sheet
    assert "double hit" in kinds                   # X21.29 Y-2.74 ends line 3 and starts line 5
    assert any(rule == "sheet" and line == 3 for rule, line, _ in found)
    # the old per-segment writer on the paper's quad: every corner punched twice
    _, contour = quad_contour()
    old = AmadaPunchPost().to_text(PunchProgram("old", [PunchOperation("per segment", 302, 10.0, 2.0, 1.6,
                                                                       nibbling.segment_lines(contour))]))
    doubles = [f for f in rules.check_punch(old) if f[0] == "double hit"]
    assert len(doubles) == 12                      # 12 corners


def test_the_checker_sees_a_hit_in_a_clamp_zone_and_beyond_the_sheet():
    text = ("N000 G92 X1000.00 Y1040.00\nN001 G72 X150.00 Y20.00\nG69 I10.00 J0.00 P0.00 Q2.00 T302\n"
            "N002 G72 X1300.00 Y20.00\nG69 I4.00 J90.00 P0.00 Q2.00 T302\nG50\n")
    found = rules.check_punch(text, sheet=SHEET, clamp_zones=ZONES, punch_radius=5.0)
    clamp = [f for f in found if f[0] == "clamp"]
    # hits at X 150, 152 .. 160 on Y 20: with the 5 mm punch, X > 155 reaches clamp 1 (X 160..240)
    assert len(clamp) == 3 and all("clamp 1" in m for _, _, m in clamp)
    assert [f for f in found if f[0] == "sheet"] and all(line == 5 for r, line, _ in found if r == "sheet")
    assert rules.check_punch(text.replace("X150.00", "X100.00").replace("X1300.00", "X1200.00"), sheet=SHEET,
                             clamp_zones=ZONES, punch_radius=5.0) == []


def test_the_checker_reads_comments_and_the_offset_word():
    text = ("N000 G92 X1000.00 Y1040.00\n(PART AT X 10..20)\nN001 G72 X10.00 Y10.00\n"
            "G69 I4.00 J0.00 P10.00 Q2.00 T302\nG50\n")
    assert rules.check_punch(text) == []
    # P10: the hits run 5 mm to the left of the line (Y 15), P-10 to the right (Y 5)
    assert [(x, y) for _, x, y in rules._punch_hits(text)] == [(10.0, 15.0), (12.0, 15.0), (14.0, 15.0)]


def test_unfold_and_elbow_programs_pass_every_rule():
    outline, contour = quad_contour()
    texts = [program(contour)[0]] + [program(c)[0] for _, c in elbow_contours()]
    for text in texts:
        assert rules.check_punch(text, sheet=SHEET, clamp_zones=ZONES, punch_radius=5.0) == []
        assert rules.check(text, "amada-04p") == []


@pytest.fixture(scope="module")
def samples(tmp_path_factory):
    """The batch runs' programs, as a user gets them."""
    base = tmp_path_factory.mktemp("punch")
    out = {}
    for name in ("unfold", "elbow"):
        done = subprocess.run([sys.executable, os.path.join(ROOT, "batch.py"), name, "--out", str(base / name)],
                              capture_output=True, text=True, timeout=600, cwd=ROOT)
        assert done.returncode == 0, done.stderr[-2000:]
        out[name] = base / name
    return out


def test_the_batch_samples_pass_every_rule_and_say_where_the_part_sits(samples):
    files = sorted(samples["unfold"].glob("*.nc")) + sorted(samples["elbow"].glob("*.nc"))
    assert len(files) == 6
    for path in files:
        text = path.read_text()
        assert rules.check_punch(text, sheet=SHEET, clamp_zones=ZONES, punch_radius=5.0) == [], path
        assert text.startswith("N000 G92 X1000.00 Y1040.00\n(PART ON THE SHEET")
        assert "(CLAMP 1 DEAD ZONE X 160..240 Y 0..50)" in text and "(MICRO-JOINTS: 2 OF 0.4 MM)" in text
        hits = np.array([(x, y) for _, x, y in rules._punch_hits(text)])
        assert hits.min() >= 10.0 + 5.0 - 0.01     # the 10 mm margin plus the punch radius
    report = json.loads((samples["unfold"] / "report.json").read_text())
    part = report["sheet"]["parts"][0]
    assert part["where"] == "at the sheet corner" and part["joints"] == 2
    x0, y0, x1, y1 = part["hits_within"]
    assert (x0, y0) == (10.0, 10.0) and x1 < 160.0 - 10.0     # left of clamp 1's dead zone
    assert report["simulation"]["held_by_joints"] == [True] and report["gate"]["findings"] == []
    assert all(abs(w - 0.4) <= 0.02 for w in part["joint_webs_mm"])
    elbow = json.loads((samples["elbow"] / "report.json").read_text())
    assert elbow["simulation"]["held_by_joints"] == [True] * 5
    # the elbow pieces are 334 mm wide: not left of clamp 1 (X 160), so beside it
    assert {p["where"] for p in elbow["sheet"]["parts"]} == {"beside clamp 1"}
    assert all(p["hits_within"][0] == 250.0 for p in elbow["sheet"]["parts"])


# --- placement ---------------------------------------------------------------------------------

def test_the_part_goes_where_it_is_clear_of_the_clamps():
    square = np.array([[0, 0], [100, 0], [100, 100], [0, 100]], float)
    profile = machine.preset("amada-04p")
    where = placement.place(square - 500.0, 10.0, profile)
    # hits' discs from (10, 10): the contour's corner at 15, 15
    assert where.envelope == (10.0, 10.0, 120.0, 120.0)
    assert np.allclose(np.array(where.offset) + (-500.0, -500.0), (15.0, 15.0))
    wide = np.array([[0, 0], [300, 0], [300, 40], [0, 40]], float)
    beside = placement.place(wide, 10.0, profile)
    assert beside.where == "beside clamp 1" and beside.envelope[0] == 250.0       # 240 + the 10 mm margin
    long = np.array([[0, 0], [900, 0], [900, 40], [0, 40]], float)
    above = placement.place(long, 10.0, profile)
    assert above.where == "above the clamps" and above.envelope[1] == 60.0         # 50 deep + 10


def test_a_part_that_does_not_fit_is_refused_naming_the_clamp_and_its_size():
    big = np.array([[0, 0], [1200, 0], [1200, 1200], [0, 1200]], float)
    with pytest.raises(placement.PlacementError) as error:
        placement.place(big, 10.0, machine.preset("amada-04p"))
    message = str(error.value)
    assert "1210.0 x 1210.0 mm" in message and "clamp 1" in message and "X 160..240" in message
    no_sheet = machine.preset("amada-04p").replace(sheet_max=None)
    with pytest.raises(placement.PlacementError, match="sheet size"):
        placement.place(big, 10.0, no_sheet)


def test_the_profile_refuses_a_negative_margin():
    with pytest.raises(machine.MachineError, match="sheet margin"):
        machine.preset("amada-04p").replace(sheet_margin=-1.0)


# --- nibbling: merged lines, each hit once, joints ---------------------------------------------

def spacing_round(hits, closed=True):
    d = np.diff(np.vstack([hits, hits[:1]]) if closed else hits, axis=0)
    return np.hypot(d[:, 0], d[:, 1])


def test_collinear_pieces_are_one_line_and_no_hit_is_punched_twice():
    square = np.array([[0, 0], [25, 0], [50, 0], [50, 50], [50, 100], [0, 100], [0, 60]], float)
    nib = nibbling.nibble(square, 2.0, 10.0, joints=0)
    assert len(nib.corners) == 4 and nib.merged == 3 and len(nib.lines) == 4
    text = written(nib)
    read = punch.read_amada(text)
    hits = read.hits
    gaps = spacing_round(hits)
    # round the loop every hit once, the largest step at most the pitch, the smallest far from 0
    assert gaps.max() <= 2.0 + 0.01 and gaps.min() >= 1.0
    assert len(hits) == 300 / 2                    # 300 mm round at 2 mm: 150 hits, none twice
    # the elbow's square end: 48 collinear segments, one line
    outline, contour = elbow_contours()[0]
    nib = nibbling.nibble(contour, 2.0, 10.0, joints=0)
    assert nib.merged >= 48 - 1
    bottom = np.isclose(nib.lines[:, 0, 1], -5.0) & np.isclose(nib.lines[:, 1, 1], -5.0)
    assert np.sum(bottom) == 1 and nib.lines[bottom][0, 1, 0] - nib.lines[bottom][0, 0, 0] > 300


def test_a_corner_between_two_lines_shorter_than_the_pitch():
    # a 1 mm chamfer between two long edges: the short line keeps both its hits, the others stop short
    shape = np.array([[0, 0], [50, 0], [51, 1], [51, 50], [0, 50]], float)
    hits = punch.read_amada(written(nibbling.nibble(shape, 2.0, 10.0, joints=0))).hits
    gaps = spacing_round(hits)
    assert gaps.min() > 0.5 and gaps.max() <= 2.0 + 0.01
    two_short = np.array([[0, 0], [50, 0], [51, 0.5], [52, 2], [52, 50], [0, 50]], float)
    with pytest.raises(nibbling.NibblingError, match="punched twice"):
        nibbling.nibble(two_short, 2.0, 10.0, joints=0)


def test_micro_joints_leave_webs_of_their_width_off_the_corners():
    outline, contour = quad_contour()
    for width in (0.3, 0.5):
        text, lines, where = program(contour, joints=2, width=width)
        ends = lines.joints
        assert len(ends) == 2
        # centre to centre: the web plus one punch diameter
        assert np.allclose(np.hypot(*(ends[:, 1] - ends[:, 0]).T), width + 10.0)
        result = punch.simulate_punching(text, punch_diameter=10.0, pattern=outline + where.offset, joints=ends)
        assert result.held_by_joints and not result.part_separated
        assert all(abs(w - width) <= 0.02 for w in result.joint_widths_mm)     # the words' 0.01 mm
        # the part as it comes out is the pattern: no bite, scallops of nibbling only
        assert result.max_gouge_mm == 0.0 and result.max_scallop_mm < 0.2
        # the joints sit on the two longest edges (the quad's sides), at their middles
        mids = ends.mean(axis=1) - where.offset
        assert sorted(np.round(mids[:, 0]).tolist()) == [-5.0, 107.0]


def test_without_joints_the_part_falls_free_and_with_joints_that_do_not_hold_it_says_so():
    outline, contour = quad_contour()
    text, lines, where = program(contour, joints=0)
    free = punch.simulate_punching(text, punch_diameter=10.0, pattern=outline + where.offset)
    assert free.part_separated and not free.held_by_joints and free.joints == 0
    # joints given to the simulation that the program does not leave: the part falls free anyway
    _, joined, _ = program(contour, joints=2)
    fake = punch.simulate_punching(text, punch_diameter=10.0, pattern=outline + where.offset, joints=joined.joints)
    assert fake.part_separated and not fake.held_by_joints and fake.joints == 2
    # a part simulated without its joints' positions stays in the sheet (as a part with webs would)
    joined_text = program(contour, joints=2)[0]
    held = punch.simulate_punching(joined_text, punch_diameter=10.0, pattern=outline + where.offset)
    assert not held.part_separated and not held.held_by_joints


def test_joints_that_do_not_fit_are_refused():
    tiny = np.array([[0, 0], [20, 0], [20, 20], [0, 20]], float)
    with pytest.raises(nibbling.NibblingError, match="fewer joints"):
        nibbling.nibble(tiny, 2.0, 10.0, joints=2)
    for bad in (-1, 9, 1.5, True):
        with pytest.raises(nibbling.NibblingError, match="count"):
            nibbling.nibble(tiny, 2.0, 10.0, joints=bad)
    with pytest.raises(nibbling.NibblingError, match="width"):
        nibbling.nibble(tiny, 2.0, 10.0, joints=1, joint_width=math.nan)


def test_the_gate_takes_a_part_held_by_its_joints_and_refuses_joints_that_do_not_hold():
    from kezuri.operators import gate, sheetjobs
    outline, contour = quad_contour()
    text, lines, where = program(contour, joints=2)
    pattern = outline + where.offset
    held = punch.simulate_punching(text, punch_diameter=10.0, pattern=pattern, joints=lines.joints)
    assert sheetjobs.punch_gate([held], False)["findings"] == []
    free_text = program(contour, joints=0)[0]
    free = punch.simulate_punching(free_text, punch_diameter=10.0, pattern=pattern)
    assert sheetjobs.punch_gate([free], False)["findings"] == []            # as today: falls free, fine
    fake = punch.simulate_punching(free_text, punch_diameter=10.0, pattern=pattern, joints=lines.joints)
    with pytest.raises(gate.GateRefused, match="the part falls free: its 2 micro-joint"):
        sheetjobs.punch_gate([fake], False)
    unknown = punch.simulate_punching(text, punch_diameter=10.0, pattern=pattern)   # joints not said
    with pytest.raises(gate.GateRefused, match="the part stays in the sheet"):
        sheetjobs.punch_gate([unknown], False)
