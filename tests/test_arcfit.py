"""Arcs out (toolpath/ir/arcfit.py): polylines that follow circles become G2/G3 arcs.

Checked without the filter's own geometry: distances are measured here by brute force (point to
segment, point to arc by angle), the program is read back by LinuxCNC's rs274 (its ARC_FEED
centres and ends, not our IR), and known circles give back their centre and radius."""
import math

import numpy as np
import pytest

import rs274
from kezuri.post import create
from kezuri.toolpath.engines import region
from kezuri.toolpath.ir import arcfit
from kezuri.toolpath.ir.program import ARC_CCW, ARC_CW, FEED, RAPID, GougeTexture, Operation, Program, Tool

TOL = arcfit.DEFAULT_TOLERANCE
TOOL = Tool(1, "flat", 6.0)


def operation(points, z=-1.0, feed=800.0, start=None, kinds=None):
    points = np.asarray(points, float)
    xyz = np.column_stack([points, np.full(len(points), z)]) if points.shape[1] == 2 else points
    kinds = np.full(len(xyz), FEED) if kinds is None else kinds
    start = xyz[0] if start is None else start
    return Operation("test", TOOL, 10000, kinds, xyz, np.where(kinds == RAPID, np.nan, feed), start=start)


def arc_points(cx, cy, r, a0, sweep, count):
    t = a0 + np.linspace(0, sweep, count)
    return np.column_stack([cx + r * np.cos(t), cy + r * np.sin(t)])


def enough_points(r, sweep, tol=TOL):
    """Chords whose sagitta is a quarter of the tolerance."""
    step = 2 * math.acos(1 - tol / 4 / r) if r > tol / 4 else math.pi / 2
    return max(4, int(math.ceil(abs(sweep) / step)) + 1)


def sample_path(op, spacing=0.02):
    """Points along the operation's cutting path (arcs walked by angle), brute force."""
    out = []
    prev = op.start
    for kind, end, centre in zip(op.kind, op.xyz, op.center):
        if kind in (ARC_CW, ARC_CCW):
            a = math.atan2(prev[1] - centre[1], prev[0] - centre[0])
            b = math.atan2(end[1] - centre[1], end[0] - centre[0])
            r = math.hypot(prev[0] - centre[0], prev[1] - centre[1])
            sweep = (b - a) % (2 * math.pi) if kind == ARC_CCW else -((a - b) % (2 * math.pi))
            count = max(2, int(abs(sweep) * r / spacing) + 2)
            t = a + np.linspace(0, sweep, count)
            out.append(np.column_stack([centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)]))
        else:
            count = max(2, int(np.linalg.norm(end[:2] - prev[:2]) / spacing) + 2)
            out.append(prev[None, :2] + np.linspace(0, 1, count)[:, None] * (end[:2] - prev[:2]))
        prev = end
    return np.vstack(out)


def distance_to_polyline(points, vertices):
    a, b = vertices[:-1], vertices[1:]
    d = b - a
    length2 = np.maximum((d * d).sum(axis=1), 1e-300)
    best = np.full(len(points), np.inf)
    for start in range(0, len(points), 2000):
        p = points[start:start + 2000, None, :]
        t = np.clip(((p - a) * d).sum(axis=2) / length2, 0, 1)
        best[start:start + 2000] = np.linalg.norm(p - (a + t[..., None] * d), axis=2).min(axis=1)
    return best


def two_way_distance(before, after):
    old = np.vstack([before.start[None, :2], before.xyz[:, :2]])
    new_samples = sample_path(after)
    new_dense = sample_path(after, 0.002)
    return distance_to_polyline(new_samples, old).max(), distance_to_polyline(old, new_dense).max()


@pytest.mark.parametrize("seed", range(30))
def test_a_sampled_circle_comes_back_as_its_circle(seed):
    rng = np.random.default_rng(seed)
    cx, cy = rng.uniform(-200, 200, 2)
    r = float(rng.choice([rng.uniform(0.5, 5), rng.uniform(5, 500)]))
    sweep = rng.uniform(0.3, 6.0) * rng.choice([-1, 1])
    points = arc_points(cx, cy, r, rng.uniform(-math.pi, math.pi), sweep, enough_points(r, sweep))
    fitted = arcfit.fit_arcs(operation(points[1:], start=np.append(points[0], -1.0)))
    assert len(fitted) == 1
    assert fitted.kind[0] == (ARC_CCW if sweep > 0 else ARC_CW)
    assert np.allclose(fitted.center[0, :2], [cx, cy], atol=1e-6 * max(1, r))
    ends = np.linalg.norm(np.array([points[0], points[-1]]) - fitted.center[0, :2], axis=1)
    assert ends[0] == pytest.approx(ends[1], abs=1e-9) and ends[0] == pytest.approx(r, rel=1e-8)


def test_straight_lines_and_coarse_polygons_stay_lines():
    square = np.array([[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]], float)
    line = np.column_stack([np.linspace(0, 100, 50), np.linspace(0, 30, 50)])
    hexagon = arc_points(0, 0, 20, 0, 2 * math.pi, 7)          # chords far from any circle's tolerance
    for points in (square, line, hexagon):
        op = operation(points)
        assert arcfit.fit_arcs(op) is op


def test_an_even_ramp_along_a_circle_comes_back_as_a_helix():
    """A ramp entry along a rounded outline: Z falls evenly with the angle; the arcs that replace
    it end at the old heights and every old vertex lies within the tolerance of the helix at its
    angle (checked here by brute force, Z interpolated by angle as a control does)."""
    circle = arc_points(3, -2, 10, 0.3, math.pi, 200)
    ramp = np.column_stack([circle, np.linspace(0, -2, len(circle))])
    op = operation(ramp[1:], start=ramp[0])
    fitted = arcfit.fit_arcs(op)
    assert len(fitted) < 5 and np.isin(fitted.kind, (ARC_CCW,)).all()
    assert np.allclose(fitted.xyz[-1], ramp[-1])
    prev = ramp[0]
    for end, centre in zip(fitted.xyz, fitted.center):
        assert np.allclose(centre[:2], (3, -2), atol=1e-3)
        a = math.atan2(prev[1] + 2, prev[0] - 3)
        sweep = (math.atan2(end[1] + 2, end[0] - 3) - a) % (2 * math.pi)
        # the old vertices this arc spans: their angle from the start gives the helix's Z
        angles = (np.arctan2(ramp[:, 1] + 2, ramp[:, 0] - 3) - a) % (2 * math.pi)
        inside = angles <= sweep + 1e-9
        helix_z = prev[2] + (end[2] - prev[2]) * angles[inside] / sweep
        assert np.abs(ramp[inside, 2] - helix_z).max() <= TOL
        prev = end


def test_a_ramp_that_does_not_fall_evenly_stays_lines():
    circle = arc_points(0, 0, 10, 0, math.pi, 200)
    uneven = np.column_stack([circle, -2 * np.linspace(0, 1, len(circle)) ** 2])   # the slope changes at every move
    op = operation(uneven[1:], start=uneven[0])
    assert arcfit.fit_arcs(op) is op
    # a plunge (Z only) between two level circles splits them; each comes back as arcs, the plunge stays
    top = np.column_stack([circle, np.zeros(len(circle))])
    low = np.column_stack([circle[::-1], np.full(len(circle), -1.0)])
    path = np.vstack([top[1:], [[circle[-1, 0], circle[-1, 1], -1.0]], low[1:]])
    fitted = arcfit.fit_arcs(operation(path, start=top[0]))
    plunge = np.flatnonzero((fitted.kind == FEED) & np.isclose(fitted.xyz[:, 2], -1.0)
                            & np.isclose(fitted.xyz[:, 0], circle[-1, 0]) & np.isclose(fitted.xyz[:, 1], circle[-1, 1]))
    assert len(plunge) == 1 and np.isin(fitted.kind, (ARC_CW, ARC_CCW)).sum() >= 2


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")
def test_rs274_cuts_the_helix_down_the_ramp():
    circle = arc_points(0, 0, 8, 0, 1.5 * math.pi, 300)
    ramp = np.column_stack([circle, np.linspace(-0.5, -3.5, len(circle))])
    kinds = np.full(len(ramp), FEED)
    kinds[0] = RAPID
    op = Operation("ramp", TOOL, 12000, kinds, ramp, np.where(kinds == RAPID, np.nan, 600.0),
                   start=np.array([8.0, 0.0, 5.0]), safe_z=5.0, clearance_z=5.0)
    text = create("milling", "linuxcnc").to_text(Program("helix", [op]))
    arcs = [args for name, args in rs274.run(text) if name == "ARC_FEED"]
    assert 1 <= len(arcs) <= 3
    # ARC_FEED(end1, end2, c1, c2, turn, end3, ...): the last arc ends at the ramp's foot
    assert float(arcs[-1][5]) == pytest.approx(-3.5, abs=1e-4)
    assert [float(a[0]) for a in arcs][-1] == pytest.approx(circle[-1, 0], abs=1e-3)


def test_rapids_textures_and_other_arcs_are_left_alone():
    circle = arc_points(0, 0, 10, 0, math.pi, 200)
    textured = operation(circle).replace(texture=GougeTexture())
    assert arcfit.fit_arcs(textured) is textured
    rapids = operation(circle, kinds=np.full(len(circle), RAPID))
    assert arcfit.fit_arcs(rapids) is rapids
    feeds = np.where(np.arange(len(circle)) % 2, 800.0, 900.0)     # the feed changes at every move
    changing = Operation("f", TOOL, 10000, np.full(len(circle), FEED), np.column_stack([circle, -np.ones(len(circle))]),
                         feeds, start=np.array([10.0, 0, -1]))
    assert arcfit.fit_arcs(changing) is changing


@pytest.mark.parametrize("seed", range(12))
def test_offset_outlines_stay_within_the_tolerance_both_ways(seed):
    """Clipper's rounded offsets of random polygons: lines and arcs mixed, as the planners make them."""
    rng = np.random.default_rng(100 + seed)
    n = int(rng.integers(3, 9))
    angles = np.sort(rng.uniform(0, 2 * math.pi, n))
    radii = rng.uniform(10, 40, n)
    polygon = np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])
    grown = region.offset(region.from_loops([polygon], "test"), float(rng.uniform(1, 8)))
    loop = max((np.asarray(p) for p in grown.to_polygons()), key=len)
    loop = np.vstack([loop, loop[:1]])
    op = operation(loop[1:], start=np.append(loop[0], -1.0))
    fitted = arcfit.fit_arcs(op)
    assert len(fitted) < len(op) and np.isin(fitted.kind, (ARC_CW, ARC_CCW)).any()
    new_to_old, old_to_new = two_way_distance(op, fitted)
    assert new_to_old <= TOL + 1e-6 and old_to_new <= TOL + 1e-6
    assert np.allclose(fitted.xyz[-1], op.xyz[-1])
    assert fitted.feed_length() == pytest.approx(op.feed_length(), rel=2e-3)


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")
def test_rs274_cuts_the_arcs_on_the_old_path():
    t = np.linspace(0, 2 * math.pi, 12, endpoint=False)
    star = np.column_stack([30 * np.cos(t) * (1 + 0.3 * (np.arange(12) % 2)), 30 * np.sin(t) * (1 + 0.3 * (np.arange(12) % 2))])
    grown = region.offset(region.from_loops([star], "star"), 4.0)
    loop = max((np.asarray(p) for p in grown.to_polygons()), key=len)
    loop = np.vstack([loop, loop[:1]])
    xyz = np.column_stack([loop, np.full(len(loop), -1.0)])
    kinds = np.full(len(xyz), FEED)
    kinds[0] = RAPID
    op = Operation("outline", TOOL, 12000, kinds, xyz, np.where(kinds == RAPID, np.nan, 600.0),
                   start=np.array([loop[0, 0], loop[0, 1], 5.0]), safe_z=5.0, clearance_z=5.0)
    fitted = arcfit.fit_arcs(op)
    text = create("milling", "linuxcnc").to_text(Program("arcs", [fitted]))
    calls = rs274.run(text)
    arcs = [args for name, args in calls if name == "ARC_FEED"]
    assert len(arcs) >= 6                  # the six outer points rounded by the offset
    # every arc rs274 cuts: its ends at one radius, and its points within the tolerance of the old path
    old = loop
    kinds_read, points, _ = rs274.motion_endpoints(calls)
    prev = None
    for kind, end in zip(kinds_read, points):
        if kind in ("cw", "ccw") and prev is not None:
            args = next(a for a in arcs if np.allclose([float(a[0]), float(a[1])], end[:2]))
            centre = np.array([float(args[2]), float(args[3])])
            r0, r1 = np.linalg.norm(prev[:2] - centre), np.linalg.norm(end[:2] - centre)
            assert abs(r0 - r1) <= 2e-4           # the post's 4 decimals
            a = math.atan2(*(prev[:2] - centre)[::-1])
            b = math.atan2(*(end[:2] - centre)[::-1])
            sweep = (b - a) % (2 * math.pi) if kind == "ccw" else -((a - b) % (2 * math.pi))
            ts = a + np.linspace(0, sweep, 200)
            on_arc = centre + r0 * np.column_stack([np.cos(ts), np.sin(ts)])
            assert distance_to_polyline(on_arc, old).max() <= TOL + 2e-4
        prev = end
