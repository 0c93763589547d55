"""PLUNGE_HELIX at the file's angle: the helix drops pi * D * tan(angle) a turn, D the diameter of the
circle the tool centre runs on, so a 5 degree helix is cut at 5 degrees (it was cut at the axial depth
a turn: 9 degrees and more).  Checked on LinuxCNC's canonical output: every ARC_FEED that goes down
is measured (radius from its start and centre, sweep from its angles and rotation) and compared with
the closed form; the last turn is a part of one and the circle is completed at the depth.

The file is ex1.stp with HOLE1 milled by helical interpolation (a 10 mm end mill, entry PLUNGE_HELIX
5 degrees) and the pocket roughed with a PLUNGE_HELIX(radius 4, 5 degrees) entry."""
import math

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program
from test_stepnc import add_instances, ex1_text, replace_instance

ANGLE = 5.0

pytestmark = pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")


def helix_file() -> str:
    text = ex1_text().replace("#2= WORKPLAN('MAIN WORKPLAN',(#10,#11,#12,#13,#14),",
                              "#2= WORKPLAN('MAIN WORKPLAN',(#300,#13),")
    text = text.replace("#17= ROUND_HOLE('HOLE1 D=22MM',#4,(#20,#21),", "#17= ROUND_HOLE('HOLE1 D=22MM',#4,(#301),")
    text = replace_instance(text, 22, "#22= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH POCKET1',15.000,$,#39,#50,#41,"
                                      "$,#306,$,#51,6.500,5.000,1.000,0.500);")
    return add_instances(
        text,
        "#300= MACHINING_WORKINGSTEP('WS MILL HOLE1',#62,#17,#301,$);",
        "#301= BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'MILL HOLE1',10.000,$,#302,#50,#41,$,#305,$,$,5.0,$,$,$);",
        "#302= MILLING_CUTTING_TOOL('T2 10 mm end mill',#303,(#125),80.000,$,$);",
        "#303= ENDMILL(#304,4,.RIGHT.,.F.,$);", "#304= MILLING_TOOL_DIMENSION(10.000,$,$,35.0,0.0,$,$);",
        f"#305= PLUNGE_HELIX($,3.0,{ANGLE});", f"#306= PLUNGE_HELIX($,4.0,{ANGLE});")


def helical_arcs(calls):
    """(radius, sweep radians, drop mm) of every ARC_FEED that changes Z, from the canonical calls."""
    here, found = None, []
    for name, args in calls:
        if name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED"):
            here = np.array([float(v) for v in args[:3]])
        elif name == "ARC_FEED":
            x, y, cx, cy = (float(v) for v in args[:4])
            rotation, z = int(args[4]), float(args[5])
            a0 = math.atan2(here[1] - cy, here[0] - cx)
            a1 = math.atan2(y - cy, x - cx)
            sweep = (a1 - a0) % (2 * math.pi) if rotation > 0 else (a0 - a1) % (2 * math.pi)
            if sweep < 1e-9:
                sweep = 2 * math.pi
            sweep += 2 * math.pi * (abs(rotation) - 1)
            radius = math.hypot(here[0] - cx, here[1] - cy)
            if abs(z - here[2]) > 1e-9:
                found.append((radius, sweep, here[2] - z))
            here = np.array([x, y, z])
    return np.array(found)


def test_a_5_degree_helix_is_cut_at_5_degrees():
    program = to_program(load_workplan(helix_file()))
    assert [op.name for op in program.operations] == ["WS MILL HOLE1", "WS ROUGH POCKET1"]
    text = post.milling_post("linuxcnc").to_text(program)
    calls = rs274.run(text)
    arcs = helical_arcs(calls)
    radius, sweep, drop = arcs.T
    assert len(arcs) >= 20 and np.all(drop > 0)          # every helical arc goes down
    # the closed form: drop = R * sweep * tan(angle), i.e. pitch = pi * D * tan(angle) a turn
    np.testing.assert_allclose(drop, radius * sweep * math.tan(math.radians(ANGLE)), rtol=1e-3, atol=2e-4)
    # both helices are there: the hole's on its innermost circle (R 11 - 5 - 5 = 1) and the pocket's R 4
    assert set(np.round(radius, 3)) == {1.0, 4.0}
    # the hole: from 2 mm above its top (the approach gap) to 1 mm below its through bottom, Z 2 to Z -31,
    # all down the 1 mm helix: 33 / (2 pi 1 tan 5) = 60.0 turns (one turn per 5 mm layer was 9 degrees and more)
    hole = radius < 2
    assert drop[hole].sum() == pytest.approx(33.0, abs=1e-3)
    assert sweep[hole].sum() / (2 * math.pi) == pytest.approx(33.0 / (2 * math.pi * math.tan(math.radians(ANGLE))),
                                                              rel=1e-4)
