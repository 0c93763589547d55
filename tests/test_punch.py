"""W5 + W6: the turret-punch program read back and punched into the sheet: the part falls out,
the scallops are the nibbling cusps, and a hit that bites into the part names its NC line."""
import math

import numpy as np
import pytest

from kezuri.post import amada_punch
from kezuri.toolpath import punch, unfold

RECT = np.array([[0.0, 0.0], [40.0, 0.0], [40.0, 20.0], [0.0, 20.0]])
PAPER_QUAD = np.array([(0, 0, 0), (0, 30, 100), (100, 50, 100), (100, 40, 0)], float)


def program(lines):
    return "\n".join(["N000 G92 X1000.00 Y1040.00", *lines, "G50"]) + "\n"


def test_hits_are_spaced_evenly_with_both_ends():
    read = punch.read_amada(program(["N001 G72 X5.00 Y0.00", "G69 I10.00 J90.00 P0.00 Q2.00 T302"]))
    assert np.allclose(read.hits, [[5.0, y] for y in (0, 2, 4, 6, 8, 10)])
    assert read.lines.tolist() == [3] * 6 and read.stations.tolist() == [302] * 6
    assert read.punch_diameter is None and read.origin == (1000.0, 1040.0)
    # 10 mm at most 3 apart: four steps of 2.5
    read = punch.read_amada(program(["N001 G72 X0.00 Y0.00", "G69 I10.00 J0.00 P0.00 Q3.00 T302"]))
    assert np.allclose(read.hits[:, 0], [0, 2.5, 5, 7.5, 10])


@pytest.mark.parametrize("angle, direction", [(0, (1, 0)), (90, (0, 1)), (180, (-1, 0)), (-90, (0, -1)),
                                              (135, (-math.sqrt(0.5), math.sqrt(0.5)))])
def test_angle_quadrants(angle, direction):
    read = punch.read_amada(program(["N001 G72 X1.00 Y2.00", f"G69 I4.00 J{angle:.2f} P0.00 Q4.00 T302"]))
    assert np.allclose(read.hits[-1], np.array([1, 2]) + 4 * np.array(direction), atol=1e-9)


def test_offset_side_follows_the_sign_of_p():
    left = punch.read_amada(program(["N001 G72 X0.00 Y0.00", "G69 I10.00 J0.00 P6.00 Q2.00 T302"]))
    right = punch.read_amada(program(["N001 G72 X0.00 Y0.00", "G69 I10.00 J0.00 P-6.00 Q2.00 T302"]))
    assert np.allclose(left.hits[:, 1], 3.0) and np.allclose(right.hits[:, 1], -3.0)
    assert left.punch_diameter == right.punch_diameter == 6.0


def test_punching_line_reads_the_thickness():
    read = punch.read_amada(program(["N001 G72 X0.00 Y0.00", "G79 I12.00 J0.00 P0.00 Q4.00 D4.00 T302"]))
    assert read.thickness == 4.0 and len(read.hits) == 4


@pytest.mark.parametrize("lines, message", [
    (["G69 I10.00 J0.00 P0.00 Q2.00 T302"], "line 2: G69 before any G72"),
    (["N001 G72 X0.00 Y0.00", "G69 I10.00 J0.00 P0.00 T302"], "line 3: G69 needs I, J, P, Q, T"),
    (["N001 G72 X0.00 Y0.00", "G69 I10.00 J0.00 P0.00 Q0.00 T302"], "line 3: .*Q \\(pitch\\) > 0"),
    (["N001 G72 X0.00 Y0.00", "G69 I-1.00 J0.00 P0.00 Q2.00 T302"], "line 3: I \\(length\\)"),
    (["N001 G72 X0.00 Y0.00", "G01 X3.00"], "line 3: G01 is not a turret-punch code"),
    (["N001 G72 X0.00 Y0.00", "G69 I1.00 J0.00 P0.00 Q2.00 T302 ZZ"], "line 3: cannot read"),
])
def test_malformed_programs_name_the_line(lines, message):
    with pytest.raises(punch.PunchError, match=message):
        punch.read_amada(program(lines))


def test_program_end_is_required_and_final():
    with pytest.raises(punch.PunchError, match="no end"):
        punch.read_amada("N001 G72 X0.00 Y0.00\nG69 I1.00 J0.00 P0.00 Q1.00 T302\n")
    with pytest.raises(punch.PunchError, match="line 4: .*after the program end"):
        punch.read_amada("N001 G72 X0.00 Y0.00\nG69 I1.00 J0.00 P0.00 Q1.00 T302\nG50\nN002 G72 X1.00 Y1.00\n")


def rectangle_program(diameter, pitch, outline=RECT):
    return amada_punch.to_text(unfold.compensate_outline(outline, diameter), station=302, pitch=pitch, thickness=1.0)


def test_nibbled_rectangle_falls_out_with_nibbling_cusps():
    d, q = 2.0, 1.0
    result = punch.simulate_punching(rectangle_program(d, q), punch_diameter=d, pattern=RECT)
    assert result.part_separated and result.pieces == 2
    # The compensated rectangle is 42 x 22 round the hit centres: every side divides into 1 mm steps.
    cusp = 1.0 - math.sqrt(1.0 - 0.5 ** 2)
    assert result.max_scallop_mm == pytest.approx(cusp, abs=0.02)
    assert result.max_gouge_mm == 0.0 and result.gouges == []
    # material left only outside the pattern, at most a cusp deep along the perimeter
    assert 800.0 - 1e-6 <= result.part_area_mm2 <= 800.0 + 120.0 * cusp
    assert result.pattern_area_mm2 == pytest.approx(800.0)


def test_hits_further_apart_than_the_punch_leave_the_part_in_the_sheet():
    result = punch.simulate_punching(rectangle_program(2.0, 2.5), punch_diameter=2.0, pattern=RECT)
    assert not result.part_separated and result.pieces == 1


def test_a_hit_into_the_part_is_a_gouge_on_its_line():
    bigger = RECT + np.array([[-1.0, 0], [0, 0], [0, 0], [-1.0, 0]])   # the part should reach x = -1
    result = punch.simulate_punching(rectangle_program(2.0, 1.0), punch_diameter=2.0, pattern=bigger)
    assert result.max_gouge_mm == pytest.approx(1.0, abs=0.02)
    gouge = result.gouges[0]
    assert gouge.xy[0] == pytest.approx(0.0, abs=0.02)
    text = rectangle_program(2.0, 1.0).splitlines()
    # the nibbling line down the left side, from its reference point at x = -1
    assert text[gouge.line - 1].startswith("G69") and " J-90.00 " in text[gouge.line - 1]
    assert text[gouge.line - 2].split()[2] == "X-1.00"


@pytest.mark.parametrize("diameter, pitch", [(10.0, 2.0), (2.0, 1.0)])
def test_paper_quad_pattern_is_punched_out(diameter, pitch):
    pattern = unfold.unfold_twisted_quad(PAPER_QUAD, 5).pattern.outline
    text = amada_punch.to_text(unfold.compensate_outline(pattern, diameter), station=302, pitch=pitch, thickness=1.6)
    result = punch.simulate_punching(text, punch_diameter=diameter, pattern=pattern)
    assert result.part_separated and result.pieces == 2
    assert result.max_gouge_mm == 0.0
    assert result.max_scallop_mm <= punch.nibbling_scallop(diameter, pitch) + 0.03
    perimeter = np.sum(np.hypot(*np.diff(np.vstack([pattern, pattern[:1]]), axis=0).T))
    area = abs(unfold.signed_area(pattern))
    assert area <= result.part_area_mm2 <= area + perimeter * punch.nibbling_scallop(diameter, pitch)


def test_p0_needs_the_punch_diameter_and_p_must_agree():
    with pytest.raises(punch.PunchError, match="give the punch diameter"):
        punch.simulate_punching(rectangle_program(2.0, 1.0))
    text = program(["N001 G72 X0.00 Y0.00", "G69 I10.00 J0.00 P6.00 Q2.00 T302"])
    with pytest.raises(punch.PunchError, match="does not match"):
        punch.simulate_punching(text, punch_diameter=5.0)
    with pytest.raises(punch.PunchError, match="pattern"):
        punch.simulate_punching(text, pattern=[[0, 0], [1, 1]])


def test_scallop_closed_form():
    assert punch.nibbling_scallop(10.0, 2.0) == pytest.approx(5 - math.sqrt(24))
    assert punch.nibbling_scallop(2.0, 2.0) == pytest.approx(1.0)
