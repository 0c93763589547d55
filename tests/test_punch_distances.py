"""The punching simulation's scallop and gouge depths are distances from the punched part's
outline to the flat pattern (punch.simulate_punching).  They are measured one pattern segment at
a time over all the outline's points (the (points x segments x 2) block they were measured in was
the 60-piece elbow bench's largest cost); here the pieces of that elbow are measured again by
the plain block formula, written out in the test, and the numbers must be the same to the bit."""
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
