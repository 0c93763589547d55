"""The punching simulation's scallop and gouge depths are distances from the punched part's
outline to the flat pattern (punch.simulate_punching).  They are measured one pattern segment at
a time over all the outline's points (the (points x segments x 2) block they were measured in was
the 60-piece elbow bench's largest cost); here the pieces of that elbow are measured again by
the plain block formula, written out in the test, and the numbers must be the same to the bit.
A program lying along X is punched turned a quarter (the booleans sweep along Y: the elbow's long
thin pieces cost 3.6-4.7x as much lying) and must give the same part as the same program turned
upright by the test."""
import dataclasses

import numpy as np
import pytest

from kezuri.post.amada_punch import AmadaPunchPost
from kezuri.toolpath.ir import machine
from kezuri.toolpath.operations.sheetmetal import nibbling, placement, punch, unfold


def block_distances(points, loop):
    """Each point's distance to the closed polyline: every point against every segment at once."""
    d = np.roll(loop, -1, axis=0) - loop
    p = points[:, None, :]
    t = np.clip(((p - loop) * d).sum(axis=2) / np.maximum((d * d).sum(axis=1), 1e-300), 0.0, 1.0)
    gap = p - (loop + t[..., None] * d)
    return np.sqrt((gap * gap).sum(axis=2).min(axis=1))


def elbow_piece(index, pieces=60, diameter=400.0, punch_diameter=10.0, pitch=2.0):
    """(NC text, flat pattern, micro-joints) of one piece, as bench/bench_punch.py makes them."""
    profile = machine.preset("amada-04p").replace(sheet_max=(2500.0, 1250.0))
    piece = unfold.unfold_elbow(90.0, 3000.0, diameter, pieces).pieces[index]
    outline = piece.outline - piece.outline.min(axis=0)
    contour = unfold.compensate_outline(outline, punch_diameter)
    where = placement.place(contour, punch_diameter, profile)
    lines = nibbling.nibble(contour, pitch, punch_diameter).moved(where.offset)
    text = AmadaPunchPost().to_text(placement.program(where, lines, 302, 1.6, profile))
    return text, outline + where.offset, lines.joints


@pytest.mark.parametrize("index", [0, 29, 59])
def test_an_elbow_pieces_scallop_is_the_block_formulas_to_the_bit(index):
    text, pattern, joints = elbow_piece(index)
    result = punch.simulate_punching(text, punch_diameter=10.0, pattern=pattern, joints=joints)
    assert result.part_separated is False and result.held_by_joints        # held by its two joints
    boundary = np.vstack(result.part_outline)
    gap = block_distances(boundary, pattern)
    assert result.max_gouge_mm == 0.0 and result.gouges == []
    # no point inside the pattern lies deeper than the 0.01 mm tolerance: the largest gap is the scallop
    # (a 10 mm punch at 2 mm pitch leaves 5 - sqrt(25 - 1) = 0.101 mm along a straight line, more where
    # the lines meet at an angle)
    assert result.max_scallop_mm == gap.max()
    assert 0.1 < result.max_scallop_mm < 0.5


def test_a_gouge_depth_is_the_block_formulas_to_the_bit():
    """A pattern 1 mm wider than the part punched: the hits along that side bite 1 mm into it."""
    text, pattern, joints = elbow_piece(29)
    wider = pattern.copy()
    wider[wider[:, 0] < wider[:, 0].min() + 1e-6, 0] -= 1.0        # the left end moved out by 1 mm
    result = punch.simulate_punching(text, punch_diameter=10.0, pattern=wider, joints=joints)
    boundary = np.vstack(result.part_outline)
    assert result.gouges and result.max_gouge_mm == pytest.approx(1.0, abs=0.02)
    assert result.max_gouge_mm in set(block_distances(boundary, wider).tolist())


def test_a_program_lying_along_x_is_punched_as_the_same_program_standing_along_y():
    """The simulation punches a program wider than it is tall turned a quarter (the booleans sweep
    along Y) and turns the results back: the piece as it lies and the same piece turned upright
    here (x, y -> -y, x, every line's direction + 90 degrees) give the same part, scallop, gouges
    and joints, turned."""
    text, pattern, joints = elbow_piece(29)
    wider = pattern.copy()
    wider[wider[:, 0] < wider[:, 0].min() + 1e-6, 0] -= 1.0        # a gouge along the left end, as above
    lying = punch.read_amada(text)
    assert np.ptp(lying.hits[:, 0]) > 10 * np.ptp(lying.hits[:, 1])           # 1257 mm along X, under 100 across

    def upright(points):
        points = np.asarray(points, float)
        return np.stack([-points[..., 1], points[..., 0]], axis=-1)
    standing = dataclasses.replace(lying, hits=upright(lying.hits), angles=lying.angles + 90.0)
    a = punch.simulate_punching(lying, punch_diameter=10.0, pattern=wider, joints=joints)
    b = punch.simulate_punching(standing, punch_diameter=10.0, pattern=upright(wider), joints=upright(joints))
    assert a.held_by_joints and b.held_by_joints and a.pieces == b.pieces and a.hits == b.hits
    assert a.part_area_mm2 == pytest.approx(b.part_area_mm2, rel=1e-12)
    assert a.removed_area_mm2 == pytest.approx(b.removed_area_mm2, rel=1e-12)
    assert a.max_scallop_mm == pytest.approx(b.max_scallop_mm, abs=1e-9)
    assert [(g.line, g.message[:30]) for g in a.gouges] == [(g.line, g.message[:30]) for g in b.gouges]
    assert [g.depth_mm for g in a.gouges] == pytest.approx([g.depth_mm for g in b.gouges], abs=1e-9)
    assert np.allclose(upright([g.xy for g in a.gouges]), [g.xy for g in b.gouges], atol=1e-9)
    assert a.joint_widths_mm == b.joint_widths_mm
    # the part as given back lies where the program punched it (not turned)
    (x0, y0), (x1, y1) = np.vstack(a.part_outline).min(axis=0), np.vstack(a.part_outline).max(axis=0)
    assert x1 - x0 > 1200 and y1 - y0 < 120
    assert np.allclose(a.part.bounds(), (x0, y0, x1, y1)) and a.sheet.bounds()[2] - a.sheet.bounds()[0] > 1200
    assert upright(np.vstack(a.part_outline)).min(axis=0) == pytest.approx(np.vstack(b.part_outline).min(axis=0), abs=1e-9)
