"""Inlays proven on the simulated stocks by booleans (manifold3d): the female (the V-carved pocket,
flat bottom at its max depth) and the male (the mirrored plug, start depth S, glue gap g, waste
cleared) are cut in the height-field simulation, their stocks made solids, the male turned over
(a half turn about the Y axis through the design's middle: mirrored back and upside down) and
pressed in until its depth S meets the pocket's top.  On walls at half the V-bit's angle a
from the vertical, lowering the plug by t closes the gap square to the walls by t sin(a): so

* lowered by (g - 0.05) / sin(a) it still meets nothing of the pocket's block (the gap is
  at least g - 0.05 everywhere), and
* lowered by (g + 0.05) / sin(a) it runs into the pocket's walls all along them: the boolean
  intersection's section half way down the walls lies within 0.1 mm of every point of the wall
  there (the gap is at most g + 0.05 along every wall).
"""
import math

import numpy as np
import pytest
from manifold3d import Manifold, Mesh

from kezuri.toolpath.engines import region as rg
from kezuri.toolpath.operations.pocket import pocket
from kezuri.toolpath.operations.vcarve import vcarve as vc
from kezuri.toolpath.simulate import simulate

CELL = 0.03
ANGLE = 60.0
S, GAP = 0.8, 0.1              # the plug's start depth and the glue gap (mm)
FEMALE_FLAT, MALE_HEIGHT = 2.0, 2.5
# an L with a round hole: convex and reflex corners, a curve, an island
L_SHAPE = np.array([[0, 0], [14, 0], [14, 5], [5, 5], [5, 12], [0, 12]], float)
HOLE = np.column_stack([2.5 + 1.2 * np.cos(np.linspace(0, 2 * np.pi, 96, endpoint=False)),
                        2.5 + 1.2 * np.sin(np.linspace(0, 2 * np.pi, 96, endpoint=False))])
DESIGN = [L_SHAPE, HOLE]


def solid(result, sim):
    vertices, faces = sim.mesh(max_cells=None)
    return Manifold(Mesh(vert_properties=np.asarray(vertices, np.float32), tri_verts=np.asarray(faces, np.uint32)))


def carved(settings):
    result = vc.plan(DESIGN, settings, name=settings.inlay)
    x0, y0, x1, y1 = result.carved.bounds()
    sim = simulate(result.operations, (x0 - 1, y0 - 1, -6.0, x1 + 1, y1 + 1, 0.0), cell=CELL)
    assert sim.findings == []
    return result, solid(result, sim)


@pytest.fixture(scope="module")
def stocks():
    tool = vc.vbit(3, ANGLE, 12.7)
    clear = pocket.end_mill(4, 1.0)
    female, female_solid = carved(vc.VCarveSettings(tool=tool, clear_tool=clear, inlay="female",
                                                    max_depth=FEMALE_FLAT, start_depth=S))
    male, male_solid = carved(vc.VCarveSettings(tool=tool, clear_tool=clear, inlay="male", max_depth=MALE_HEIGHT,
                                                start_depth=S, glue_gap=GAP))
    x0, _, x1, _ = rg.from_loops(DESIGN).bounds()
    # turned over about the Y axis through the design's middle, its depth S at the pocket's top:
    # (x, y, z) -> (x0 + x1 - x, y, -z - S)
    turned = male_solid.transform(np.array([[-1.0, 0, 0, x0 + x1], [0, 1.0, 0, 0], [0, 0, -1.0, -S]]))
    return female_solid, turned


def lowered(plug, t):
    return plug.translate((0.0, 0.0, -t))


def test_the_plug_meets_nothing_with_the_gap_less_0_05_closed(stocks):
    female, plug = stocks
    sin = math.sin(math.radians(ANGLE / 2))
    assert (female ^ plug).volume() < 1e-3                       # as pressed in: apart
    assert (female ^ lowered(plug, (GAP - 0.05) / sin)).volume() < 1e-3


def test_the_plug_runs_into_every_wall_with_the_gap_plus_0_05_closed(stocks):
    female, plug = stocks
    sin = math.sin(math.radians(ANGLE / 2))
    overlap = female ^ lowered(plug, (GAP + 0.05) / sin)
    assert overlap.volume() > 0
    depth = S / 2
    section = overlap.slice(-depth)
    # the pocket's wall at that depth: the design shrunk by depth x tan(a/2), sampled every 0.2 mm
    wall = rg.offset(rg.from_loops(DESIGN), -depth * math.tan(math.radians(ANGLE / 2)))
    points = []
    for loop in rg.loops(wall):
        closed = np.vstack([loop, loop[:1]])
        for a, b in zip(closed[:-1], closed[1:]):
            n = max(1, int(np.ceil(np.hypot(*(b - a)) / 0.2)))
            points.append(a + np.arange(n)[:, None] / n * (b - a))
    points = np.vstack(points)
    near = rg.contains_points(section.offset(0.1, rg.JoinType.Round, 2.0, 16), points)
    assert near.all(), f"{(~near).sum()} of {len(points)} wall points have no contact, e.g. {points[~near][:3]}"
