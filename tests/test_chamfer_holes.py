"""Chamfers at round holes (issue 29): the V-bit along a circle inside each hole, G3 arcs.

Closed forms worked out here by hand: a V-bit of included angle theta (the library's 90 deg bit,
tan(theta / 2) = 1) chamfering a hole of radius R by ``width`` w with its tip ``tip_gap`` g below
the chamfer runs its axis on the circle rho = R - g tan(theta / 2), its tip at depth
w / tan(theta / 2) + g; the cut's edge at the top is at R + w, and d below the top at
R + w - d tan(theta / 2)."""
import math

import numpy as np
import pytest

import controller_rules
import rs274
from kezuri.post.fanuc import FanucPost
from kezuri.post.linuxcnc import LinuxCNCPost
from kezuri.toolpath import job as jobs
from kezuri.toolpath.ir.program import Program, Tool
from kezuri.toolpath.operations.chamfer import chamfer
from kezuri.toolpath.operations.chamfer.holes import plan_holes
from kezuri.toolpath.operations.chamfer.kind import ChamferGeometry
from kezuri.toolpath.operations.drill import drill
from kezuri.toolpath.operations.drill.helix import plan_helix
from kezuri.toolpath.simulate import BoxStock, simulate

HALF_TAN = math.tan(math.radians(90.0) / 2)      # the 90 deg V-bit: 1.0


def test_the_bit_runs_a_circle_of_the_closed_form_radius_as_g3_arcs():
    settings = chamfer.ChamferSettings(width=1.0, tip_gap=0.2)
    holes = ((10.0, 10.0, 6.0), (30.0, 10.0, 5.0))
    part = jobs.kind_of("chamfer").plan(jobs.Setup(), settings, ChamferGeometry((), 0.0, holes))
    (op,) = part.operations
    arcs = np.isin(op.kind, (2, 3))
    assert np.all(op.kind[arcs] == 3)                       # counter-clockwise: climb inside a hole
    tip = 1.0 / HALF_TAN + 0.2                              # 1.2 mm below the top
    for x, y, d in holes:
        mine = arcs & np.isclose(op.center[:, 0], x) & np.isclose(op.center[:, 1], y)
        rho = d / 2 - 0.2 * HALF_TAN                        # 2.8 and 2.3 mm
        ends = op.xyz[mine]
        assert np.allclose(np.hypot(ends[:, 0] - x, ends[:, 1] - y), rho, atol=1e-9)
        assert ends[-1, 2] == pytest.approx(-tip) and ends[-2, 2] == pytest.approx(-tip)   # a full circle at depth
        assert np.all(np.diff(ends[:, 2]) <= 1e-12)           # down the helix, never up
        # the helix from the approach gap (2 mm above the top): no steeper than 1 in 8 along the circle
        drops = -np.diff(np.concatenate([[2.0], ends[:, 2]]))
        assert drops.max() <= 2 * math.pi * rho / 8.0 + 1e-9
    for post, name in ((LinuxCNCPost(), "linuxcnc"), (FanucPost(), "fanuc-mill")):
        text = post.to_text(Program("holes", [op]))
        assert text.count("G03") + text.count("G3 ") >= int(arcs.sum()) - 1
        assert controller_rules.check(text, name) == [], name
    text = LinuxCNCPost().to_text(Program("holes", [op]))
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text, tools=[7]))
    assert kinds.count("ccw") == int(arcs.sum())
    assert points[:, 2].min() == pytest.approx(-1.2, abs=1e-4)


@pytest.mark.parametrize("width, tip_gap", [(1.0, 0.2), (1.5, 0.5)])
def test_the_cut_round_a_helix_milled_hole_is_the_asked_width(width, tip_gap):
    mill = drill.DrillSettings(helix=True, mill=Tool(5, "flat", 6.0, flute_length=25.0))
    hole = plan_helix([(10.0, 10.0)], [12.0], [-5.0], mill)
    settings = chamfer.ChamferSettings(width=width, tip_gap=tip_gap)
    op = plan_holes([(10.0, 10.0, 12.0)], settings)
    result = simulate([hole, op], BoxStock(0, 0, -10, 20, 20, 0), cell=0.02)
    assert result.findings == []                            # no plunge: the V-bit comes down on its helix
    hf = result.heightfield
    x = hf.x0 + (np.arange(hf.heights.shape[0]) + 0.5) * hf.cell_x
    y = hf.y0 + (np.arange(hf.heights.shape[1]) + 0.5) * hf.cell_y
    r = np.hypot(*np.meshgrid(x - 10, y - 10, indexing="ij"))
    ring = r < 9.5
    depth = width / HALF_TAN
    for level in (1e-6, depth / 2, depth - 0.05):
        area = np.count_nonzero(ring & (hf.heights < -level)) * hf.cell_x * hf.cell_y
        expected = 2 * (6.0 + width - level * HALF_TAN)      # the cut's diameter at that level
        assert 2 * math.sqrt(area / math.pi) == pytest.approx(expected, abs=0.03), level
    below = np.count_nonzero(ring & (hf.heights < -(depth + 0.05))) * hf.cell_x * hf.cell_y
    assert 2 * math.sqrt(below / math.pi) == pytest.approx(12.0, abs=0.03)     # the hole's wall below it


def test_holes_that_cannot_be_chamfered_are_refused_by_name():
    with pytest.raises(chamfer.ChamferError, match=r"the hole at X0 Y0 is 1 mm, narrower than the 1 mm chamfer"):
        plan_holes([(0.0, 0.0, 1.0)], chamfer.ChamferSettings(width=1.0))
    with pytest.raises(chamfer.ChamferError, match="past the centre; make tip_gap smaller"):
        plan_holes([(0.0, 0.0, 3.0)], chamfer.ChamferSettings(width=0.5, tip_gap=2.0))
    with pytest.raises(chamfer.ChamferError, match=r"holes\[1\] = \[1, 2\] is not \[x, y, diameter\]"):
        plan_holes([(0.0, 0.0, 5.0), [1, 2]], chamfer.ChamferSettings())
    with pytest.raises(chamfer.ChamferError, match="no holes"):
        plan_holes([], chamfer.ChamferSettings())
