"""Chamfer / deburr with a V-bit: the cut measured in the simulation against the closed forms
(depth = width / tan(theta / 2) for one flank), on a plate's outer edge and a milled hole's edge."""
import math

import numpy as np
import pytest

import controller_rules
import rs274
from kezuri.post.linuxcnc import LinuxCNCPost
from kezuri.toolpath import job as jobs
from kezuri.toolpath.ir.program import Program, Tool
from kezuri.toolpath.operations.chamfer import chamfer
from kezuri.toolpath.operations.chamfer.kind import ChamferGeometry
from kezuri.toolpath.operations.drill import drill
from kezuri.toolpath.operations.drill.helix import plan_helix
from kezuri.toolpath.simulate import BoxStock, simulate

PLATE = np.array([[0, 0], [40, 0], [40, 30], [0, 30]], float)


def column(result, x=None, y=None):
    """Heights across the stock along the row at ``y`` (or the column at ``x``), and the cell centres."""
    hf = result.heightfield
    if y is not None:
        j = int((y - hf.y0) / hf.cell_y)
        return hf.x0 + (np.arange(hf.heights.shape[0]) + 0.5) * hf.cell_x, hf.heights[:, j]
    i = int((x - hf.x0) / hf.cell_x)
    return hf.y0 + (np.arange(hf.heights.shape[1]) + 0.5) * hf.cell_y, hf.heights[i, :]


@pytest.mark.parametrize("settings", [chamfer.ChamferSettings(width=1.5), chamfer.ChamferSettings(width=0.0, depth=1.5),
                                      chamfer.ChamferSettings(width=2.0, tip_gap=0.0)])
def test_outer_edge_chamfer_width_and_depth(settings):
    assert chamfer.ChamferSettings(width=1.5).geometry()[:2] == pytest.approx((1.5, 1.5))   # 90 deg: 45 deg chamfer
    part = jobs.kind_of("chamfer").plan(jobs.Setup(), settings, ChamferGeometry((PLATE,)))
    op, = part.operations
    result = simulate([op], BoxStock(0, 0, -10, 40, 30, 0), cell=0.025)
    assert result.findings == []                    # no plunge of the V-bit: it ramps in along the edge
    width = settings.width or settings.depth        # a 90 deg bit: depth = width / tan(45 deg) = width
    for x, heights in (column(result, y=15.0), column(result, x=20.0)):
        near = np.minimum(x, x.max() + x.min() - x)  # distance from the nearer edge (cell centres)
        cut = heights < -1e-6
        # the flank: depth at a distance d from the edge is width - d, nothing beyond the width
        assert np.allclose(heights[cut], -(width - near[cut]), atol=1e-3)
        assert near[cut].max() == pytest.approx(width, abs=0.03)
    # the plate's corner: the bit's cone swings round it, the top corner stays inside the chamfer
    text = LinuxCNCPost().to_text(Program("chamfer", [op]))
    assert controller_rules.check(text, "linuxcnc") == []
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text, tools=[7]))
    assert points[:, 2].min() == pytest.approx(-(width + settings.tip_gap), abs=1e-4)


def test_hole_edge_chamfer_after_helix_milling():
    mill = drill.DrillSettings(helix=True, mill=Tool(5, "flat", 6.0, flute_length=25.0))
    hole = plan_helix([(10.0, 10.0)], [12.0], [-5.0], mill)
    t = np.linspace(0, 2 * np.pi, 96, endpoint=False)
    circle = np.column_stack([10 + 6 * np.cos(t), 10 + 6 * np.sin(t)])
    outline = np.array([[0, 0], [20, 0], [20, 20], [0, 20]], float)
    settings = chamfer.ChamferSettings(width=1.0, tip_gap=0.5)
    op = chamfer.plan([outline, circle], settings)          # the square's edge and the hole's
    result = simulate([hole, op], BoxStock(0, 0, -10, 20, 20, 0), cell=0.02)
    assert result.findings == []
    hf = result.heightfield
    # the hole's top: 12 + 2 x 1 mm wide; 0.5 mm down the chamfer: 12 + 2 x 0.5
    x = hf.x0 + (np.arange(hf.heights.shape[0]) + 0.5) * hf.cell_x
    y = hf.y0 + (np.arange(hf.heights.shape[1]) + 0.5) * hf.cell_y
    r = np.hypot(*np.meshgrid(x - 10, y - 10, indexing="ij"))
    ring = r < 8.5
    for level, diameter in ((-1e-6, 14.0), (-0.5, 13.0)):
        area = np.count_nonzero(ring & (hf.heights < level)) * hf.cell_x * hf.cell_y
        assert 2 * math.sqrt(area / math.pi) == pytest.approx(diameter, abs=0.03)


def test_chamfer_settings_refused_by_name():
    with pytest.raises(chamfer.ChamferError, match="needs a V-bit"):
        chamfer.ChamferSettings(tool=Tool(1, "flat", 6.0)).check()
    with pytest.raises(chamfer.ChamferError, match="give the width or the depth, one of them"):
        chamfer.ChamferSettings(width=1.0, depth=1.0).check()
    with pytest.raises(chamfer.ChamferError, match="needs the V-bit 12.4 mm wide at the top"):
        chamfer.ChamferSettings(width=6.0).check()
    with pytest.raises(chamfer.ChamferError, match="fewer than 3 distinct points"):
        chamfer.plan([[(0, 0), (1, 0)]])
