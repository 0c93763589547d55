"""The paper's weak point, checked by cutting: the sample's 20 mm axial pocket, machined by the
axial operations (polar X-C interpolation), simulated on a fine height field, is 20 mm wide."""
import numpy as np
import pytest

from kezuri.toolpath import simulate
from kezuri.toolpath.operations.turnmill import turnmill


def test_axial_pocket_is_machined_20_mm_wide():
    vertices, faces, stock = turnmill.sample_part()
    plan = turnmill.plan(vertices, faces, stock)
    axial = [op for op in plan.program.operations if op.direction == "axial"]
    assert axial
    # A thin strip across the pocket (x 10..30 at y = 0), on a 2 micron grid.
    strip = simulate.BoxStock(6.0, -0.2, -20.0, 34.0, 0.2, 0.0)
    result = simulate.simulate(axial, strip, cell=0.002)
    hf = result.heightfield
    row = hf.heights[:, hf.shape[1] // 2]
    cut = hf.x()[row < -1.0]
    width = cut.max() - cut.min() + hf.cell_x
    assert width == pytest.approx(20.0, abs=0.01)
    assert np.isclose(cut.min() - hf.cell_x / 2, 10.0, atol=0.01)
