"""W5 + W6: the turret-punch program read back and punched out of the sheet: the part falls out,
the scallops are the nibbling cusps, and a hit that bites into the part names its NC line.

Real manifold3d booleans throughout; the expected numbers come from closed forms worked out here."""
import math

import numpy as np
import pytest

from kezuri.post.amada_punch import AmadaPunchPost
from kezuri.toolpath.ir.program import PunchOperation, PunchProgram
from kezuri.toolpath.operations.sheetmetal import punch, unfold
from kezuri.toolpath.operations.sheetmetal.nibbling import offset_side, segment_lines

RECT = np.array([[0.0, 0.0], [40.0, 0.0], [40.0, 20.0], [0.0, 20.0]])
PAPER_QUAD = np.array([(0, 0, 0), (0, 30, 100), (100, 50, 100), (100, 40, 0)], float)


def program(lines, end="G50"):
    return "\n".join(["N000 G92 X1000.00 Y1040.00", *lines, end]) + "\n"


def one_line(move):
    return punch.read_amada(program(["N001 G72 X0.00 Y0.00", move]))


def segment_program(contour, diameter, pitch, compensation="none"):
    """One G72 + G69 per side of ``contour`` (station 302, 1 mm sheet), through the IR and the post."""
    op = PunchOperation("contour", 302, diameter, pitch, 1.0, segment_lines(contour), compensation)
    return AmadaPunchPost().to_text(PunchProgram("part", [op]))


def rectangle_program(diameter, pitch, outline=RECT):
    """P0: the rectangle compensated by the punch radius, one G72 + G69 per side."""
    return segment_program(unfold.compensate_outline(outline, diameter), diameter, pitch)


def cusp(diameter, spacing):
    """r - sqrt(r^2 - (s/2)^2), written out again so the test does not lean on the code under test."""
    r = diameter / 2
    return r - math.sqrt(r * r - spacing * spacing / 4)


def perimeter(outline):
    return float(np.sum(np.hypot(*np.diff(np.vstack([outline, outline[:1]]), axis=0).T)))


# ---------------------------------------------------------------- reader


def test_hits_are_spaced_evenly_with_both_ends():
    read = punch.read_amada(program(["N001 G72 X5.00 Y0.00", "G69 I10.00 J90.00 P0.00 Q2.00 T302"]))
    assert np.array_equal(read.hits, [[5.0, y] for y in (0.0, 2.0, 4.0, 6.0, 8.0, 10.0)])
    assert read.lines.tolist() == [3] * 6 and read.stations.tolist() == [302] * 6
    assert read.angles.tolist() == [90.0] * 6
    assert read.punch_diameter is None and read.thickness is None and read.origin == (1000.0, 1040.0)
    # 10 mm with hits at most 3 apart: ceil(10 / 3) = 4 steps of 2.5, both ends included
    assert np.allclose(one_line("G69 I10.00 J0.00 P0.00 Q3.00 T302").hits[:, 0], [0, 2.5, 5, 7.5, 10])
    # 0.7 / 0.1 is 6.999... in floating point: still 7 steps, not 8
    assert len(one_line("G69 I0.70 J0.00 P0.00 Q0.10 T302").hits) == 8
    assert one_line("G69 I0.00 J0.00 P0.00 Q2.00 T302").hits.tolist() == [[0.0, 0.0]]


def test_blank_lines_comments_and_a_g72_without_n_are_read():
    text = "(PART 1)\n\nN000 G92 X1000.00 Y1040.00\nG72 X1.00 Y2.00 (corner)\n" \
           "G69 I4.00 J0.00 P0.00 Q2.00 T302\n\nM30\n(end)\n"
    read = punch.read_amada(text)
    assert np.array_equal(read.hits, [[1.0, 2.0], [3.0, 2.0], [5.0, 2.0]])
    assert read.lines.tolist() == [5, 5, 5]


@pytest.mark.parametrize("angle, direction", [
    (0, (1, 0)), (90, (0, 1)), (180, (-1, 0)), (-90, (0, -1)), (270, (0, -1)),
    (135, (-math.sqrt(0.5), math.sqrt(0.5))), (-45, (math.sqrt(0.5), -math.sqrt(0.5))),
    (-150, (-math.sqrt(0.75), -0.5)), (30, (math.sqrt(0.75), 0.5))])
def test_angle_quadrants(angle, direction):
    read = punch.read_amada(program(["N001 G72 X1.00 Y2.00", f"G69 I4.00 J{angle:.2f} P0.00 Q4.00 T302"]))
    np.testing.assert_allclose(read.hits, [[1, 2], np.array([1, 2]) + 4 * np.array(direction)], atol=1e-12)


def test_offset_side_follows_the_sign_of_p():
    left = one_line("G69 I10.00 J0.00 P6.00 Q2.00 T302")
    right = one_line("G69 I10.00 J0.00 P-6.00 Q2.00 T302")
    assert np.array_equal(left.hits[:, 1], [3.0] * 6) and np.array_equal(right.hits[:, 1], [-3.0] * 6)
    assert left.punch_diameter == right.punch_diameter == 6.0
    up = one_line("G69 I10.00 J90.00 P6.00 Q2.00 T302")          # left of +Y travel is -X
    assert np.array_equal(up.hits[:, 0], [-3.0] * 6)


def test_punching_line_reads_the_thickness():
    read = one_line("G79 I12.00 J0.00 P0.00 Q4.00 D4.50 T101")
    assert read.thickness == 4.5 and len(read.hits) == 4 and read.stations.tolist() == [101] * 4


def test_reads_back_what_the_post_writes():
    contour = unfold.compensate_outline(RECT, 2.0)
    read = punch.read_amada(rectangle_program(2.0, 1.0))
    # 42 x 22 round the corners at 1 mm: 43 + 23 + 43 + 23 hits, the corners twice
    assert len(read.hits) == 132
    corners = read.hits[np.r_[0, 43, 66, 109]]
    assert np.array_equal(corners, contour)
    assert np.array_equal(np.unique(read.lines), [3, 5, 7, 9])


@pytest.mark.parametrize("lines, message", [
    (["G69 I10.00 J0.00 P0.00 Q2.00 T302"], "line 2: G69 before any G72 reference point"),
    (["N001 G72 X0.00 Y0.00", "(nibble)", "G69 I10.00 J0.00 P0.00 T302"],
     "line 4: G69 needs I, J, P, Q, T, got 'G69 I10.00 J0.00 P0.00 T302'"),
    (["N001 G72 X0.00 Y0.00", "G79 I10.00 J0.00 P0.00 Q5.00 T302"], "line 3: G79 needs I, J, P, Q, D, T"),
    (["N001 G72 X0.00", "G69 I10.00 J0.00 P0.00 Q2.00 T302"], "line 2: G72 needs X, Y"),
    (["N001 G72 X0.00 Y0.00", "G69 I10.00 J0.00 P0.00 Q0.00 T302"], r"line 3: I \(length\) must be >= 0 and Q"),
    (["N001 G72 X0.00 Y0.00", "G69 I10.00 J0.00 P0.00 Q-2.00 T302"], r"line 3: I \(length\) must be >= 0"),
    (["N001 G72 X0.00 Y0.00", "G69 I-1.00 J0.00 P0.00 Q2.00 T302"], r"line 3: I \(length\) must be >= 0"),
    (["N001 G72 X0.00 Y0.00", "G69 I" + "9" * 400 + " J0.00 P0.00 Q2.00 T302"], "line 3: a number is not finite"),
    (["N001 G72 X0.00 Y0.00", "G79 I10.00 J0.00 P0.00 Q5.00 D0.00 T302"], r"line 3: D \(thickness\) must be > 0"),
    (["N001 G72 X0.00 Y0.00", "G01 X3.00"], "line 3: G01 is not a turret-punch code"),
    (["N001 G72 X0.00 Y0.00", "G69.5 I1.00 J0.00 P0.00 Q2.00 T302"], "line 3: G69.5 is not a turret-punch code"),
    (["N001 G72 X0.00 Y0.00", "M02"], "line 3: M02 is not a turret-punch code"),
    (["N001 G72 X0.00 Y0.00", "G69 I1.00 J0.00 P0.00 Q2.00 T302 ZZ"], "line 3: cannot read"),
    (["N001 G72 X0.00 Y0.00", "G69 I1.00 J0.00 P0.00 Q2.00 T302.5"], "line 3: cannot read"),
    (["N001 G72 X0.00 Y0.00 (open comment"], "line 2: cannot read"),
    (["%", "N001 G72 X0.00 Y0.00"], "line 2: cannot read"),
    (["N001 G72 X0.00 Y0.00 G69"], "line 2: expected one G or M code"),
    (["N001 X0.00 Y0.00"], "line 2: expected one G or M code"),
    (["N001 G72 X0.00 X1.00 Y0.00"], "line 2: X given twice"),
    (["N001 G72 X0.00 Y0.00", "G69 I1.00 J0.00 P0.00 Q2.00 T302 X1.00"], "line 3: G69 needs"),
])
def test_malformed_programs_name_the_line(lines, message):
    with pytest.raises(punch.PunchError, match=message):
        punch.read_amada(program(lines))


def test_program_end_is_required_and_final():
    with pytest.raises(punch.PunchError, match=r"no end \(G50 or M30\)"):
        punch.read_amada("N001 G72 X0.00 Y0.00\nG69 I1.00 J0.00 P0.00 Q1.00 T302\n")
    with pytest.raises(punch.PunchError, match="line 4: 'N002 G72 X1.00 Y1.00' comes after the program end"):
        punch.read_amada("N001 G72 X0.00 Y0.00\nG69 I1.00 J0.00 P0.00 Q1.00 T302\nG50\nN002 G72 X1.00 Y1.00\n")
    with pytest.raises(punch.PunchError, match="line 3: G50 takes no words"):
        punch.read_amada("N001 G72 X0.00 Y0.00\nG69 I1.00 J0.00 P0.00 Q1.00 T302\nG50 X0.00\n")
    with pytest.raises(punch.PunchError, match="punches nothing"):
        punch.read_amada(program(["N001 G72 X0.00 Y0.00"]))
    with pytest.raises(punch.PunchError, match="different tool diameters"):
        punch.read_amada(program(["N001 G72 X0.00 Y0.00", "G69 I1.00 J0.00 P2.00 Q1.00 T302",
                                  "N002 G72 X1.00 Y0.00", "G69 I1.00 J0.00 P3.00 Q1.00 T302"]))
    with pytest.raises(punch.PunchError, match=r"line 3: the pitch Q0.001 is below the 0.1 mm"):
        one_line("G69 I1000.00 J0.00 P0.00 Q0.001 T302")
    with pytest.raises(punch.PunchError, match=r"line 3: the program has more than 20000 hits"):
        one_line("G69 I2000.10 J0.00 P0.00 Q0.10 T302")      # 20002 hits: 2000.1 / 0.1 steps, both ends
    with pytest.raises(punch.PunchError, match="must be text"):
        punch.read_amada(b"G50")


# ---------------------------------------------------------------- simulation


def test_nibbled_rectangle_falls_out_with_the_nibbling_cusps():
    # 4 mm punch, Q 2.05: the tool path is 44 x 24, so the hits are ceil(44 / 2.05) = 22 and
    # ceil(24 / 2.05) = 12 steps of exactly 2.0 mm, half the diameter (which also covers the corners).
    d, q, spacing = 4.0, 2.05, 2.0
    result = punch.simulate_punching(rectangle_program(d, q), punch_diameter=d, pattern=RECT)
    assert result.hits == 2 * (23 + 13)
    assert result.part_separated and result.pieces == 2
    expected = cusp(d, spacing)                                                  # 0.268, not 0.283 (Q)
    assert punch.nibbling_scallop(d, spacing) == pytest.approx(expected)
    assert result.max_scallop_mm == pytest.approx(expected, abs=1e-6)    # the cusps are exact (to the booleans' 1e-8)
    assert result.max_gouge_mm == 0.0 and result.gouges == []
    # the part is the pattern plus the cusps along the sides: at most a cusp deep along the perimeter
    assert 800.0 - 1e-6 <= result.part_area_mm2 <= 800.0 + perimeter(RECT) * expected
    assert result.pattern_area_mm2 == pytest.approx(800.0)
    # blank: hits from (-2, -2) to (42, 22), grown by r + margin (= d): 56 x 36
    assert result.removed_area_mm2 + result.part_area_mm2 + result.skeleton.area() == pytest.approx(56 * 36)
    assert len(result.part_outline) == 1 and result.part_outline[0].shape[1] == 2
    assert result.part.area() + result.skeleton.area() == pytest.approx(result.sheet.area())
    # a finer circle: the measured cusp closes in on the closed form (and leaves the one for Q)
    fine = punch.simulate_punching(rectangle_program(d, q), punch_diameter=d, pattern=RECT, tolerance=0.001)
    assert fine.max_scallop_mm == pytest.approx(expected, abs=0.0012)
    assert abs(fine.max_scallop_mm - cusp(d, q)) > 0.01


@pytest.mark.parametrize("pitch", [2.5, 2.0])
def test_hits_a_diameter_or_more_apart_leave_the_part_in_the_sheet(pitch):
    # 42 / 2.0 and 22 / 2.0 are whole: the 2 mm hits just touch and leave webs of no width
    result = punch.simulate_punching(rectangle_program(2.0, pitch), punch_diameter=2.0, pattern=RECT)
    assert not result.part_separated and result.pieces == 1
    assert result.max_scallop_mm is None and result.max_gouge_mm == 0.0
    assert result.part_area_mm2 == pytest.approx(result.sheet.area())


def test_a_hit_into_the_part_is_a_gouge_on_its_line():
    text = rectangle_program(2.0, 1.0)
    lines = text.splitlines()
    bigger = RECT + np.array([[-1.0, 0], [0, 0], [0, 0], [-1.0, 0]])   # the part should reach x = -1
    result = punch.simulate_punching(text, punch_diameter=2.0, pattern=bigger)
    assert result.part_separated
    assert result.max_gouge_mm == pytest.approx(1.0, abs=0.02)
    gouge = result.gouges[0]
    assert gouge.depth_mm == result.max_gouge_mm and gouge.xy[0] == pytest.approx(0.0, abs=0.02)
    # the nibbling line down the left side, from its reference point (-1, 21)
    assert lines[gouge.line - 1] == "G69 I22.00 J-90.00 P0.00 Q1.00 T302"
    assert lines[gouge.line - 2].endswith("G72 X-1.00 Y21.00")
    assert gouge.message.startswith(f"line {gouge.line}: a hit bites 1.000 mm into the part")
    # a pattern 1 mm larger all round: every side's line bites 1 mm, one finding per line
    everywhere = RECT + np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])
    result = punch.simulate_punching(text, punch_diameter=2.0, pattern=everywhere)
    assert sorted(g.line for g in result.gouges) == [3, 5, 7, 9]
    assert all(lines[g.line - 1].startswith("G69") for g in result.gouges)
    assert [g.depth_mm for g in result.gouges] == pytest.approx([1.0] * 4, abs=0.02)


def test_the_controller_offset_p_punches_the_same_part():
    # uncompensated rectangle with the offset done by the controller: P-4.00 (outside a CCW loop)
    text = segment_program(RECT, 4.0, 2.05, offset_side(RECT, "outside"))
    assert " P-4.00 " in text
    offset = punch.simulate_punching(text, pattern=RECT)
    compensated = punch.simulate_punching(rectangle_program(4.0, 2.05), punch_diameter=4.0, pattern=RECT)
    assert offset.punch_diameter == 4.0 and offset.part_separated and offset.max_gouge_mm == 0.0
    assert offset.part_area_mm2 == pytest.approx(compensated.part_area_mm2, abs=1e-6)
    assert offset.max_scallop_mm == pytest.approx(compensated.max_scallop_mm, abs=1e-9)
    assert punch.simulate_punching(text, punch_diameter=4.004, pattern=RECT).punch_diameter == 4.004
    with pytest.raises(punch.PunchError, match="punch diameter 5 does not match the program's P 4$"):
        punch.simulate_punching(text, punch_diameter=5.0)


def test_without_a_pattern_the_part_is_the_loose_piece():
    result = punch.simulate_punching(rectangle_program(2.0, 1.0), punch_diameter=2.0)
    assert result.part_separated and result.pieces == 2
    assert result.pattern_area_mm2 is None and result.max_scallop_mm is None and result.max_gouge_mm == 0.0
    assert 800.0 <= result.part_area_mm2 <= 800.0 + 120.0 * cusp(2.0, 1.0)


def test_paper_quad_is_punched_out():
    outline = unfold.unfold_twisted_quad(PAPER_QUAD, 5).pattern.outline
    text = segment_program(unfold.compensate_outline(outline, 2.0), 2.0, 2.0)
    result = punch.simulate_punching(text, punch_diameter=2.0, pattern=outline)
    assert result.part_separated and result.pieces == 2
    # the compensated path stops one radius from both edges at the (slightly) concave corners;
    # what is left is the 0.01 mm rounding of the NC words
    assert result.max_gouge_mm <= 0.02
    assert result.max_scallop_mm <= punch.nibbling_scallop(2.0, 2.0) + 0.01
    area = abs(unfold.signed_area(outline))
    assert area - 0.02 * perimeter(outline) <= result.part_area_mm2 <= area + perimeter(outline) * cusp(2.0, 2.0)
    assert result.seconds < 1.0


def test_bad_settings_are_rejected():
    text = rectangle_program(2.0, 1.0)
    with pytest.raises(punch.PunchError, match="give the punch diameter"):
        punch.simulate_punching(text)
    for diameter in (0.0, -2.0, float("nan"), "two", True):
        with pytest.raises(punch.PunchError, match="punch diameter must be a number > 0"):
            punch.simulate_punching(text, punch_diameter=diameter)
    for tolerance in (0.0, 0.6, float("inf")):
        with pytest.raises(punch.PunchError, match="tolerance must be > 0"):
            punch.simulate_punching(text, punch_diameter=2.0, tolerance=tolerance)
    with pytest.raises(punch.PunchError, match="margin must be a number > 0"):
        punch.simulate_punching(text, punch_diameter=2.0, margin=0.0)
    bad_patterns = [([[0, 0], [1, 1]], "fewer than 3 distinct points"),
                    ([[0, 0, 0], [1, 0, 0], [1, 1, 0]], r"list of \(x, y\) points"),
                    ([0, 1, 2], r"list of \(x, y\) points"),
                    ("square", r"list of \(x, y\) points"),
                    ([[0, 0], [1, np.nan], [1, 1]], "non-finite"),
                    ([[0, 0], [1, 0], [2, 0]], "encloses no area"),
                    (RECT + 500.0, "does not overlap")]
    for pattern, message in bad_patterns:
        with pytest.raises(punch.PunchError, match=message):
            punch.simulate_punching(text, punch_diameter=2.0, pattern=pattern)
    with pytest.raises(punch.PunchError, match="NC text or a PunchProgram"):
        punch.simulate_punching(42)
    empty = punch.PunchProgram(np.empty((0, 2)), np.empty(0, int), np.empty(0), np.empty(0, int), None, None, None)
    with pytest.raises(punch.PunchError, match="punches nothing"):
        punch.simulate_punching(empty, punch_diameter=2.0)
    with pytest.raises(punch.PunchError, match="line 3: G69 needs"):
        punch.simulate_punching(program(["N001 G72 X0.00 Y0.00", "G69 I1.00 J0.00 Q2.00 T302"]), punch_diameter=2.0)


def test_scallop_closed_form():
    assert punch.nibbling_scallop(10.0, 2.0) == pytest.approx(5 - math.sqrt(24))
    assert punch.nibbling_scallop(2.0, 1.0) == pytest.approx(1 - math.sqrt(0.75))
    assert punch.nibbling_scallop(2.0, 0.0) == 0.0
    assert punch.nibbling_scallop(2.0, 2.0) == punch.nibbling_scallop(2.0, 3.0) == 1.0
    with pytest.raises(punch.PunchError):
        punch.nibbling_scallop(0.0, 1.0)


def lens(r, p):
    """Area two discs of radius r, p apart (p < 2r), have in common."""
    return 2 * r * r * math.acos(p / (2 * r)) - (p / 2) * math.sqrt(4 * r * r - p * p)


@pytest.mark.parametrize("r, p, k, angle", [(2.0, 1.0, 20, 0.0), (5.0, 0.1, 300, 37.0), (1.0, 1.9, 7, -90.0),
                                            (25.0, 4.0, 40, 123.4)])
def test_a_line_of_hits_is_the_union_of_its_discs_in_closed_form(r, p, k, angle):
    """k + 1 discs of radius r, p apart along a line: each adds its disc less the lens it shares
    with the one before (the earlier ones meet it only inside that one), so the union has area
    (k + 1) pi r^2 - k lens(p).  The outline is inscribed (every corner on a circle, the chords
    within the tolerance of it) and its cusps are where neighbouring circles cross."""
    tolerance = 0.01
    u = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    centres = np.array([3.0, -7.0]) + np.arange(k + 1)[:, None] * p * u
    n = 4 * math.ceil(math.pi / math.acos(1 - tolerance / r) / 4)
    outline = punch._chain(centres, r, 2 * math.pi / n)
    on = np.abs(np.hypot(*(outline[:, None, :] - centres[None, :, :]).transpose(2, 0, 1)) - r).min(axis=1)
    assert on.max() < 1e-9                                            # every corner on a circle
    exact = (k + 1) * math.pi * r * r - k * lens(r, p)
    area = abs(unfold.signed_area(outline))
    assert unfold.signed_area(outline) > 0                            # counter-clockwise
    length = np.hypot(*np.diff(np.vstack([outline, outline[:1]]), axis=0).T).sum()
    assert exact - tolerance * length <= area <= exact + 1e-9
    # the cusps: each inner pair of neighbours crosses at p/2 along the line and sqrt(r^2 - p^2/4) aside
    v = np.array([-u[1], u[0]])
    cusps = (centres[:-1] + centres[1:]) / 2
    for side in (1, -1):
        want = cusps + side * math.sqrt(r * r - p * p / 4) * v
        assert np.abs(outline[:, None, :] - want[None, :, :]).sum(axis=2).min(axis=0).max() < 1e-9
    # a finer tolerance closes in on the closed form
    fine = punch._chain(centres, r, 2 * math.pi / (8 * n))
    assert abs(abs(unfold.signed_area(fine)) - exact) < abs(area - exact) / 10 + 1e-12


def test_hits_not_on_one_even_line_are_not_chained():
    assert punch._chain(np.array([[0.0, 0.0], [1.0, 0.0], [2.5, 0.0]]), 2.0, 0.1) is None     # uneven
    assert punch._chain(np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.1]]), 2.0, 0.1) is None     # bent
    assert punch._chain(np.array([[0.0, 0.0], [4.0, 0.0], [8.0, 0.0]]), 2.0, 0.1) is None     # a diameter apart
    assert punch._chain(np.array([[1.0, 1.0], [1.0, 1.0]]), 2.0, 0.1) is None                 # one place


def test_the_union_of_lines_is_the_union_of_every_hit():
    """A 40-sided outline nibbled at three pitches: the sheet left by the line unions is the
    sheet left by uniting every hit's own polygon (what the simulation did before), less only
    the slivers at the cusps that the hits' polygons missed (within the tolerance of the circles)."""
    from manifold3d import CrossSection, OpType
    angle = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    outline = np.column_stack([60 * np.cos(angle) * (1 + 0.2 * np.cos(3 * angle)), 45 * np.sin(angle)])
    for d, q in ((4.0, 0.5), (10.0, 3.0), (6.0, 5.9)):
        text = segment_program(unfold.compensate_outline(outline, d), d, q)
        program = punch.read_amada(text)
        r, tolerance = d / 2, 0.01
        n = 4 * math.ceil(math.pi / math.acos(1 - tolerance / r) / 4)
        disc = CrossSection.circle(r, n)
        each = CrossSection.batch_boolean([disc.rotate(float(a)).translate((float(x), float(y)))
                                           for (x, y), a in zip(program.hits, program.angles)], OpType.Add)
        lines = punch._discs(program, r, tolerance)
        assert (each - lines).area() < 1e-6                                # nothing of a hit is lost
        extra = (lines - each).area()
        assert 0 <= extra <= tolerance * 2 * len(program.hits) * q         # slivers along both sides
        result = punch.simulate_punching(text, punch_diameter=d, pattern=outline)
        assert result.part_separated and result.max_gouge_mm <= 0.011      # the NC words' 0.01 mm
