"""simulate --nc follows the drilling cycles G81, G82 and G83 (with G98/G99, G80) as LinuxCNC runs
them: the reader's moves against LinuxCNC's own interpreter (rs274's canonical calls), for every
cycle and retract mode, from above and from below the R plane."""
import numpy as np
import pytest

import rs274
from kezuri.toolpath.ir.program import Tool
from kezuri.toolpath.simulate import ncread

pytestmark = pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")
DRILL = Tool(1, "drill", 5.0)


def path(kinds, points) -> list:
    """(kind, x, y, z) of every move, zero-length moves dropped (rs274 and the reader may differ in
    whether a move that goes nowhere is written)."""
    out, last = [], None
    for kind, point in zip(kinds, np.round(np.asarray(points, float), 4)):
        here = tuple(point.tolist())
        if here != last:
            out.append((kind, *here))
        last = here
    return out


@pytest.mark.parametrize("cycle", ["G81", "G82 P0.5", "G83 Q2"])
@pytest.mark.parametrize("retract", ["G98", "G99"])
@pytest.mark.parametrize("start_z", [10.0, 0.5])      # above the R plane, and below it
def test_the_reader_drills_as_linuxcnc_does(cycle, retract, start_z):
    text = (f"G21 G90 G17\nG0 X0 Y0 Z{start_z:g}\nF150\n{retract} {cycle} X10 Y5 Z-7 R2\nX20 Y5\nY15\nG80\n"
            "G0 Z20\nM2\n")
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text))
    op, _ = ncread.read_nc(text, DRILL)
    theirs = path([0 if k == "rapid" else 1 for k in kinds], points)
    mine = path(op.kind.tolist(), op.xyz)
    # rs274 begins at its own origin; compare from the first move both have
    start = theirs.index(mine[0])
    assert mine == theirs[start:]
    bottoms = sorted({(x, y) for kind, x, y, z in mine if kind == 1 and z == -7.0})
    assert bottoms == [(10.0, 5.0), (20.0, 5.0), (20.0, 15.0)]
