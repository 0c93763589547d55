"""The manifold engine along closed level loops of a ball (the rotary sample's finishing rings):
the removed volume against Pappus, and point by point against the true sweep."""
import math

import numpy as np
import pytest
from manifold3d import Manifold, OpType

from kezuri.toolpath import simulate as sim
from sweep_checks import depth_outside_ball_sweep, surface_samples
from kezuri.toolpath.ir.program import FEED, Operation, Tool
from kezuri.toolpath.simulate import sweep
from kezuri.toolpath.simulate.paths import Chain
from kezuri.toolpath.simulate.stock import stock_solid

BALL6 = Tool(2, "ball", 6.0)
BOX = (-30, -30, -20, 30, 30, 0)


def loop_op(points):
    points = np.asarray(points, float)
    n = len(points) - 1
    return Operation("loop", BALL6, 10000, np.full(n, FEED), points[1:], np.full(n, 500.0), start=points[0])


def circle(radius, z, n):
    angle = np.linspace(0, 2 * math.pi, n + 1)
    angle[-1] = 0.0                                   # closes exactly on its first point
    return np.column_stack([radius * np.cos(angle), radius * np.sin(angle), np.full(n + 1, z)])


def rounded_rectangle(width, height, corner, z, step=0.5):
    """A closed loop: straight sides, quarter circles of radius ``corner`` at the corners."""
    points = []
    for k, (cx, cy) in enumerate([(width / 2 - corner, height / 2 - corner), (corner - width / 2, height / 2 - corner),
                                  (corner - width / 2, corner - height / 2), (width / 2 - corner, corner - height / 2)]):
        angle = np.linspace(k * math.pi / 2, (k + 1) * math.pi / 2, max(2, math.ceil(corner * math.pi / 2 / step)) + 1)
        points.append(np.column_stack([cx + corner * np.cos(angle), cy + corner * np.sin(angle)]))
    ring = np.vstack(points)
    ring = np.vstack([ring, ring[:1]])
    return np.column_stack([ring, np.full(len(ring), z)])


def groove_section(r, depth):
    """The area of a ball end's section square to its path, ``depth`` deep (tip) under a flat
    top: a circular segment, or below the centre a half disc and the shank's rectangle."""
    if depth <= r:
        h = r - depth
        return r * r * math.acos(h / r) - h * math.sqrt(r * r - h * h)
    return math.pi * r * r / 2 + 2 * r * (depth - r)


@pytest.mark.parametrize("tolerance", [0.005, 0.01, 0.03, 0.05])
@pytest.mark.parametrize("depth", [2.0, 5.0])
def test_a_ball_groove_round_a_circle_is_pappus_within_a_thousandth(depth, tolerance):
    # the section is symmetric about the tip's vertical line, so its centroid runs on the
    # circle: volume = area * 2 pi R (Pappus); 360 chords of a 15 mm circle shorten the path by
    # 1.3e-5 of it, far inside the thousandth.  Measured (2 mm / 5 mm deep): -0.004 / -0.004 %
    # at 0.005 mm, +0.009 / -0.004 % at the default 0.03 mm, -0.03 / -0.04 % at 0.05 mm; before
    # the level tubes took the thinning's room on its side only (a section shrunk all round by
    # an eighth of the tolerance), -0.34 / -0.15 % at 0.03 mm and -0.57 / -0.26 % at 0.05 mm
    radius = 15.0
    result = sim.simulate(loop_op(circle(radius, -depth, 360)), BOX, engine="manifold", tolerance=tolerance)
    expected = 2 * math.pi * radius * groove_section(3.0, depth)
    assert result.removed_volume_mm3 == pytest.approx(expected, rel=1e-3)


LOOPS = {
    "circle of 6 mm in 90 chords": circle(6.0, -2.0, 90),
    "rounded rectangle 40 x 24, corners 5 mm": rounded_rectangle(40.0, 24.0, 5.0, -4.0),
    "rounded rectangle, corners 3.2 mm (just over the ball)": rounded_rectangle(30.0, 16.0, 3.2, -3.0, step=0.4),
}


@pytest.mark.parametrize("name", sorted(LOOPS))
def test_a_closed_ball_loop_lies_in_its_sweep_and_holds_the_shrunk_tools_sweep(name):
    # point by point: every point of the cut's surface below the top lies inside the true sweep
    # of the ball (and shank) along the loop, but for the corner polygon's allowance; and the
    # cut contains the sweep of the tool shrunk by the tolerance (exact hulls of it per move)
    tips, tolerance = LOOPS[name], 0.05
    stock = stock_solid(sim.as_stock(BOX), tolerance)
    chain = Chain(0, BALL6, tips, np.zeros(len(tips) - 1, int), np.zeros(len(tips) - 1, bool),
                  np.zeros(len(tips) - 1, bool), False)
    removed = stock - sweep.cut(stock, [chain], tolerance)
    samples = surface_samples(removed)
    below = samples[samples[:, 2] < BOX[5] - 1e-6]
    assert len(below) > 1000
    assert depth_outside_ball_sweep(below, tips, 3.0).max() < sweep.outside(BALL6, tolerance) + 1e-6
    shrunk = sweep.tool_points(BALL6, 0.005, 5.0, inset=tolerance)
    inner = Manifold.batch_boolean([Manifold.hull_points(sweep.placed(shrunk, tips[k:k + 2], None))
                                    for k in range(len(tips) - 1)], OpType.Add)
    assert ((inner ^ stock) - removed).volume() < 1e-6


def depth_outside_level_sweep(vertices, tips, tool):
    """How far each point lies outside the tool (ball, bull or V-bit, and its shank) swept along
    the level tip polyline: for a ball or bull, the distance from the disc of its corner centres
    less the corner radius, or beyond the shank; for a V-bit, horizontally beyond the cone."""
    r, rc = tool.radius, tool.corner_radius
    a, b = tips[:-1, :2], tips[1:, :2]
    worst = np.zeros(len(vertices))
    for start in range(0, len(vertices), 2000):
        v = vertices[start:start + 2000]
        d = b - a
        t = np.clip(np.einsum("vsk,sk->vs", v[:, None, :2] - a, d) / np.einsum("sk,sk->s", d, d), 0, 1)
        across = np.min(np.linalg.norm(v[:, None, :2] - (a + t[..., None] * d), axis=2), axis=1)
        up = v[:, 2] - tips[0, 2]
        if tool.shape.pointed:
            cone = across - np.minimum(up * tool.shape.tip_tan, r)
            worst[start:start + 2000] = np.where(up >= 0, cone, np.maximum(cone, -up))
        else:
            corner = np.hypot(np.maximum(across - (r - rc), 0.0), up - rc) - rc
            worst[start:start + 2000] = np.where(up >= rc, np.minimum(corner, across - r), corner)
    return worst


THINNED = {
    "15 mm circle in 360 chords": lambda: circle(15.0, -2.0, 360),
    "40 mm line, zigzag 0.001 mm in 201 moves": lambda: np.column_stack([
        np.linspace(-20.0, 20.0, 202), 0.001 * (-1.0) ** np.arange(202), np.full(202, -2.0)]),
    "S curve of two 8 mm arcs in 300 chords": lambda: np.vstack([
        np.column_stack([-8 + 8 * np.cos(np.linspace(math.pi, 0, 151)), 8 * np.sin(np.linspace(math.pi, 0, 151)),
                         np.full(151, -2.0)]),
        np.column_stack([8 - 8 * np.cos(np.linspace(0, math.pi, 151))[1:],
                         -8 * np.sin(np.linspace(0, math.pi, 151))[1:], np.full(150, -2.0)])]),
}
TOOLS = {"ball 6": BALL6, "bull 6 r1": Tool(3, "bull", 6.0, corner_radius=1.0), "V-bit 6 90 deg": Tool(4, "vbit", 6.0)}


@pytest.mark.parametrize("tool_name", sorted(TOOLS))
@pytest.mark.parametrize("name", sorted(THINNED))
def test_a_thinned_level_path_lies_in_its_sweep_and_holds_the_shrunk_tools_sweep(name, tool_name):
    # paths finer than the thinning's room (a sixteenth of the tolerance on a level path): the tubes follow chords over several moves, each ring's section moved in on the side
    # the dropped points lie (both sides along the zigzag, either side along the S), so every point
    # of the cut still lies in the true sweep but for the corner polygon's allowance (a V-bit's
    # cone has none), and the cut holds the sweep of the tool shrunk by the tolerance
    tips, tool, tolerance = THINNED[name](), TOOLS[tool_name], 0.05
    stock = stock_solid(sim.as_stock(BOX), tolerance)
    chain = Chain(0, tool, tips, np.zeros(len(tips) - 1, int), np.zeros(len(tips) - 1, bool),
                  np.zeros(len(tips) - 1, bool), False)
    removed = stock - sweep.cut(stock, [chain], tolerance)
    samples = surface_samples(removed, per_triangle=max(1, 4000 // removed.num_tri()))
    below = samples[samples[:, 2] < BOX[5] - 1e-6]
    assert len(below) > 1000
    assert depth_outside_level_sweep(below, tips, tool).max() < sweep.outside(tool, tolerance) + 1e-6
    if tool.shape.pointed:       # a cone shrunk by the tolerance is the cone raised by tolerance / sin(half angle)
        shrunk = sweep.tool_points(tool, 0.005, 5.0)
        lift = tolerance / math.sin(math.atan(tool.shape.tip_tan))
    else:
        shrunk, lift = sweep.tool_points(tool, 0.005, 5.0, inset=tolerance), 0.0
    inner = Manifold.batch_boolean([Manifold.hull_points(sweep.placed(shrunk, tips[k:k + 2] + [0, 0, lift], None))
                                    for k in range(len(tips) - 1)], OpType.Add)
    assert ((inner ^ stock) - removed).volume() < 1e-6


@pytest.mark.parametrize("tool_name", sorted(TOOLS))
def test_a_one_sided_ring_lies_in_the_tool_at_every_place_its_chords_allow(tool_name):
    # the rings' lemma itself, with the shifts far larger than a thinning makes (up to 0.2 mm):
    # a ring standing on the bisector of a vertex turning by d, where the true path strays up to
    # plus left and minus right of both chords, lies in the tool (the section's tool of
    # revolution) centred anywhere across either chord from -minus to plus
    tool = TOOLS[tool_name]
    section = sweep._section(sweep.tool_rings(tool, 0.025), tool.radius, 5.0)
    right = section[section[:, 0] >= 0]
    right = right[np.argsort(right[:, 1], kind="stable")]
    rng = np.random.default_rng(7)
    for _ in range(200):
        plus, minus = rng.uniform(0, 0.2, 2) * (rng.random(2) < 0.8)
        d = rng.uniform(0, 0.5) * rng.choice([-1, 1])
        ring = sweep._one_sided(section, np.array([plus]), np.array([minus]), np.array([math.cos(d / 2)]), 0.4)[0]
        for heading in (-d / 2, d / 2):             # the chords either side, seen from the bisector's frame
            normal = np.array([-math.sin(heading), math.cos(heading)])
            for a in np.linspace(-minus, plus, 7):
                across = np.linalg.norm(ring[:, :1] * [0.0, 1.0] - a * normal, axis=1)
                width = np.interp(ring[:, 1], right[:, 1], right[:, 0])
                assert np.all(across <= width + 1e-12)
                assert np.all(ring[:, 1] >= -1e-12)
