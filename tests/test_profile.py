"""Profile / cut-out, checked against closed forms on the simulated stock (the heightfield engine),
not against the planner: the cut-out part's outline (a rectangle, a circle) within 0.01 mm of the
design from the top of the cut to its bottom, each tab's remaining width and height, no straight
plunge of the end mill into material, holes cut before the outer outline, leads in the waste;
and hostile settings refused by name."""
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings as hsettings, strategies as st

from kezuri.toolpath import simulate as sim
from kezuri.toolpath.ir.errors import InputError
from kezuri.toolpath.ir.program import FEED, RAPID, Tool
from kezuri.toolpath.job import Job, JobOperation, Setup, plan_job
from kezuri.toolpath.operations.profile import profile as pf
from kezuri.toolpath.operations.profile.kind import ProfileGeometry
from test_hostile import time_limit

W, H = 60.0, 40.0              # the rectangle part, centred on the origin
THICK = 12.0
D = 6.0                        # the default tool: a 6 mm flat end mill, number 5
FLOOR = -THICK - 0.3           # through the stock and 0.3 mm into the spoil board
RECT = np.array([[-W / 2, -H / 2], [W / 2, -H / 2], [W / 2, H / 2], [-W / 2, H / 2]])


def circle(r, cx=0.0, cy=0.0, n=720):
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([cx + r * np.cos(a), cy + r * np.sin(a)])


def rect_distance(x, y):
    """Signed distance to the rectangle (negative inside), closed form."""
    dx, dy = np.abs(x) - W / 2, np.abs(y) - H / 2
    outside = np.hypot(np.maximum(dx, 0), np.maximum(dy, 0))
    return np.where((dx <= 0) & (dy <= 0), np.maximum(dx, dy), outside)


def cut(op, x0=-45.0, y0=-35.0, cell=0.1, side=45.0):
    stock = sim.BoxStock(x0, y0, -THICK, x0 + 2 * side, y0 + 2 * side - 20.0, 0.0)
    return sim.simulate([op], stock, cell=cell, no_plunge_tools=(op.tool.number,), fixture_clearance=0.3)


def grid(result):
    hf = result.heightfield
    gx, gy = np.meshgrid(hf.x(), hf.y(), indexing="ij")
    return gx, gy, hf.heights


def assert_outline(distance, heights, tabs_free=True, band=0.01):
    """Cells more than ``band`` inside the part stand to the top; cells more than ``band`` outside,
    within the kerf, are cut to the cut's bottom (the wall is vertical within the band)."""
    inside = distance < -band
    assert inside.sum() > 1000
    assert heights[inside].min() >= -1e-9, "the part was cut"
    kerf = (distance > band) & (distance < D - band)
    assert kerf.sum() > 1000
    if tabs_free:
        assert np.abs(heights[kerf] - FLOOR).max() < 1e-6


@pytest.mark.parametrize("allowance", [0.0, 0.3])
def test_a_rectangle_cut_out_is_within_a_hundredth_of_its_outline_top_to_bottom(allowance):
    op = pf.plan([RECT], pf.ProfileSettings(allowance=allowance), thickness=THICK).operation
    # two grids: one puts cell centres 0.009 mm inside the right and top edges and 0.009 mm outside
    # the left and bottom ones, the other the other way round
    for x0, y0 in ((-45.059, -35.059), (-45.041, -35.041)):
        result = cut(op, x0, y0)
        assert [f.kind for f in result.findings] == []
        gx, gy, heights = grid(result)
        distance = rect_distance(gx, gy)
        near = (np.abs(distance) > 0.008) & (np.abs(distance) < 0.01)
        assert near.sum() > 500               # the grids test the band itself
        assert_outline(distance, heights, band=0.008)


@pytest.mark.parametrize("side", ["outside", "inside"])
def test_a_circle_is_within_a_hundredth_of_its_outline(side):
    r = 20.0
    op = pf.plan([circle(r)], pf.ProfileSettings(side=side, allowance=0.25), thickness=THICK).operation
    result = cut(op, -40.0, -40.0, cell=0.1, side=40.0)
    assert [f.kind for f in result.findings] == []
    gx, gy, heights = grid(result)
    distance = np.hypot(gx, gy) - r
    if side == "inside":
        distance = -distance             # the part is outside the circle
    assert ((np.abs(distance) > 0.01) & (np.abs(distance) < 0.02)).sum() > 100
    assert_outline(distance, heights)


def test_tabs_keep_their_width_and_height_and_keep_off_the_corners():
    width, height = 8.0, 3.0
    settings = pf.ProfileSettings(tab_count=4, tab_width=width, tab_height=height, allowance=0.3)
    op = pf.plan([RECT], settings, thickness=THICK).operation
    cell = 0.05
    result = cut(op, -45.0, -35.0, cell=cell)
    assert [f.kind for f in result.findings] == []
    hf = result.heightfield
    xs, ys = hf.x(), hf.y()
    material = np.clip(hf.heights, hf.bottom, hf.top)
    tabs = []
    # the middle of the kerf, D / 2 off each straight edge, between the corners
    rows = [("y", -H / 2 - D / 2, W), ("y", H / 2 + D / 2, W), ("x", -W / 2 - D / 2, H), ("x", W / 2 + D / 2, H)]
    for axis, at, length in rows:
        if axis == "y":
            j = int(np.argmin(np.abs(ys - at)))
            line, along = material[:, j], xs
        else:
            i = int(np.argmin(np.abs(xs - at)))
            line, along = material[i, :], ys
        span = np.abs(along) <= length / 2
        standing = (line > hf.bottom + 1e-6) & span
        edges = np.flatnonzero(np.diff(np.concatenate([[0], standing.astype(int), [0]])))
        for start, stop in zip(edges[::2], edges[1::2]):
            piece = line[start:stop]
            top = piece.max()
            flat = np.sum(piece >= top - 1e-6) * cell
            tabs.append((top - hf.bottom, flat, along[start], along[stop - 1], length))
    assert len(tabs) == 4
    for tab_height, flat, lo, hi, length in tabs:
        assert tab_height == pytest.approx(height, abs=1e-6)
        assert flat == pytest.approx(width, abs=cell)
        assert hi - lo == pytest.approx(width + 2 * height, abs=2 * cell)     # 45-degree ends
        assert lo >= -length / 2 + D / 2 - cell and hi <= length / 2 - D / 2 + cell    # a tool radius off the corners


def test_triangular_tabs_are_ridges_of_their_width_and_height():
    settings = pf.ProfileSettings(tab_count=2, tab_width=8.0, tab_height=3.0, tab_shape="triangle")
    op = pf.plan([RECT], settings, thickness=THICK).operation
    result = cut(op, cell=0.05)
    assert [f.kind for f in result.findings] == []
    hf = result.heightfield
    material = np.clip(hf.heights, hf.bottom, hf.top)
    found = []
    for j in (int(np.argmin(np.abs(hf.y() + H / 2 + D / 2))), int(np.argmin(np.abs(hf.y() - H / 2 - D / 2)))):
        line = material[:, j] - hf.bottom
        standing = (line > 1e-6) & (np.abs(hf.x()) < W / 2)
        edges = np.flatnonzero(np.diff(np.concatenate([[0], standing.astype(int), [0]])))
        for start, stop in zip(edges[::2], edges[1::2]):
            found.append((line[start:stop].max(), (stop - start) * 0.05))
    for i in (int(np.argmin(np.abs(hf.x() + W / 2 + D / 2))), int(np.argmin(np.abs(hf.x() - W / 2 - D / 2)))):
        line = material[i, :] - hf.bottom
        standing = (line > 1e-6) & (np.abs(hf.y()) < H / 2)
        edges = np.flatnonzero(np.diff(np.concatenate([[0], standing.astype(int), [0]])))
        for start, stop in zip(edges[::2], edges[1::2]):
            found.append((line[start:stop].max(), (stop - start) * 0.05))
    assert len(found) == 2
    for peak, base in found:
        assert peak == pytest.approx(3.0, abs=0.05 * 0.75 + 1e-6)    # the apex falls 0.75 mm per mm
        assert base == pytest.approx(8.0, abs=0.1)


def test_no_straight_plunge_and_ramps_no_steeper_than_asked():
    op = pf.plan([RECT, circle(14.0, 10.0, 0.0, 180)], pf.ProfileSettings(tab_count=2, allowance=0.3),
                 thickness=THICK).operation
    result = cut(op)
    assert [f.kind for f in result.findings if f.kind == "plunge"] == []
    assert result.findings == []
    # every feed move going down into the stock (below the top) moves sideways at least 1 mm per
    # mm down (45 degrees, the tabs' ends), or starts above the top, or is the finishing pass's way
    # down inside the roughed kerf (checked by the simulation above: no plunge finding)
    a, b = op.start_points(), op.xyz
    down = (op.kind == FEED) & (b[:, 2] < a[:, 2] - 1e-9) & (a[:, 2] < -1e-9)
    run = np.hypot(*(b[down, :2] - a[down, :2]).T)
    drop = a[down, 2] - b[down, 2]
    assert np.all(run >= drop * (1 - 1e-6))


def test_holes_are_cut_before_the_outline_and_the_part_keeps_them():
    hole, square = circle(6.0, 12.0, 0.0, 180), np.array([[-20, -8], [-8, -8], [-8, 8], [-20, 8]], float)
    op = pf.plan([RECT, hole, square], pf.ProfileSettings(), thickness=THICK).operation
    cutting = np.flatnonzero((op.kind == FEED) & (op.xyz[:, 2] < -THICK))
    xy = op.xyz[cutting, :2]
    in_hole = np.hypot(xy[:, 0] - 12.0, xy[:, 1]) < 6.0
    in_square = (np.abs(xy[:, 0] + 14) < 6) & (np.abs(xy[:, 1]) < 8)
    outer = rect_distance(xy[:, 0], xy[:, 1]) > 0
    assert in_hole.any() and in_square.any() and outer.any()
    assert cutting[in_hole | in_square].max() < cutting[outer].min()
    result = cut(op)
    assert result.findings == []
    gx, gy, heights = grid(result)
    part = (rect_distance(gx, gy) < -0.01) & (np.hypot(gx - 12, gy) > 6.01) & \
        ~((np.abs(gx + 14) < 6.01) & (np.abs(gy) < 8.01))
    assert heights[part].min() >= -1e-9         # no lead, ramp or link marked the part


def test_climb_goes_clockwise_round_the_part_and_counter_clockwise_in_a_hole():
    for side, climb, clockwise in (("outside", True, True), ("outside", False, False), ("inside", True, False)):
        op = pf.plan([RECT], pf.ProfileSettings(side=side, climb=climb, lead="none"), thickness=THICK).operation
        deep = (op.kind == FEED) & np.isclose(op.xyz[:, 2], FLOOR)
        x, y = op.xyz[deep, 0], op.xyz[deep, 1]
        area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
        assert (area < 0) == clockwise, (side, climb)


def test_the_leads_lie_in_the_waste_and_away_from_the_tabs():
    for side in ("outside", "inside"):
        settings = pf.ProfileSettings(side=side, tab_count=3, allowance=0.3, lead_radius=4.0)
        plan = pf.plan([RECT], settings, thickness=THICK)
        op = plan.operation
        deep = op.xyz[(op.kind == FEED) & np.isclose(op.xyz[:, 2], FLOOR)]
        d = rect_distance(deep[:, 0], deep[:, 1])
        if side == "outside":
            assert d.min() >= D / 2 - 0.01 and d.max() > D / 2 + 3.0        # the lead reaches out into the waste
        else:
            assert d.max() <= -D / 2 + 0.01 and d.min() < -D / 2 - 3.0
        for tab in plan.tabs:      # no point of the path at the floor within a tab's reach of its centre
            assert np.hypot(*(deep[:, :2] - tab).T).min() > 8.0 / 2 + D / 2 - 1e-6


def test_the_job_kind_speaks_for_the_kerf_and_lets_the_tool_through_the_bottom():
    settings = pf.ProfileSettings(tab_count=4, allowance=0.3)
    geometry = ProfileGeometry((tuple(map(tuple, RECT.tolist())),), THICK, 0.0, "object 'Part'", "cut out")
    planned = plan_job(Job(Setup("part"), (JobOperation("profile", "cut out", settings, geometry),)))
    part = planned.parts[0]
    assert part.fixture_clearance == pytest.approx(0.3)
    program, stock, limits = planned.simulation()
    assert stock.z0 == -THICK and stock.x0 < -W / 2 - D
    result = sim.simulate(program, stock, cell=0.1, no_plunge_tools=(5,), **limits)
    assert result.findings == []
    # the same design catches a profile on the wrong side: the part's edge is cut through
    wrong = pf.plan([RECT], pf.ProfileSettings(side="inside"), thickness=THICK).operation
    result = sim.simulate([wrong], stock, cell=0.1, **limits)
    assert "gouge" in [f.kind for f in result.findings]


def test_a_through_cut_without_tabs_warns_that_the_part_comes_loose():
    plan = pf.plan([RECT], pf.ProfileSettings(), thickness=THICK, name="cut out")
    assert plan.warnings == ["profile 'cut out': no tabs and cut through: the part comes loose on the last pass"]
    assert pf.plan([RECT], pf.ProfileSettings(tab_count=2), thickness=THICK).warnings == []
    assert pf.plan([RECT], pf.ProfileSettings(depth=11.0), thickness=THICK).warnings == []     # an onion skin


def test_tab_positions_the_user_gives_are_snapped_to_the_contour():
    plan = pf.plan([RECT], pf.ProfileSettings(tabs=((0.0, -30.0), (0.0, 25.0))), thickness=THICK)
    assert sorted(map(tuple, np.round(plan.tabs, 6).tolist())) == [(0.0, -23.0), (0.0, 23.0)]
    with pytest.raises(pf.ProfileError, match=r"tabs\[0\] at \(30, -20\) sits within a tool radius of a corner"):
        pf.plan([RECT], pf.ProfileSettings(tabs=((30.0, -20.0),)), thickness=THICK)


# ----- hostile settings: refused by name, never a traceback -------------------------------------------

@pytest.mark.parametrize("changes, words", [
    (dict(tab_count=2, tab_width=200.0), "tab_width"),
    (dict(depth=-3.0), "depth"),
    (dict(step_down=0.0), "step_down"),
    (dict(step_down=float("nan")), "step_down"),
    (dict(depth=40.0), "depth"),
    (dict(side="left"), "side"),
    (dict(tab_count=2, tab_height=13.0), "tab_height"),
    (dict(tab_count=2, tab_shape="triangle", tab_width=2.0), "tab_width"),
    (dict(tool=Tool(5, "ball", 6.0)), "flat end mill"),
    (dict(tab_count=2, tab_spacing=10.0), "tab_count or tab_spacing"),
    (dict(ramp_angle=80.0), "ramp_angle"),
])
def test_bad_settings_are_refused_by_name(changes, words):
    with pytest.raises(pf.ProfileError, match=words.replace("(", r"\(")):
        pf.plan([RECT], pf.ProfileSettings(**changes), thickness=THICK)


def test_a_tool_wider_than_an_inside_contour_and_a_crossing_outline_are_refused_by_name():
    with pytest.raises(pf.ProfileError, match="6 mm flat end mill.*does not fit inside every contour of object 'Hole'"):
        pf.plan([circle(2.5)], pf.ProfileSettings(side="inside"), thickness=THICK, what="object 'Hole'")
    bow = np.array([[0, 0], [20, 20], [20, 0], [0, 30]], float)
    with pytest.raises(pf.ProfileError, match=r"object 'Bow': the outline crosses itself at \(12.00, 12.00\)"):
        pf.plan([bow], pf.ProfileSettings(), thickness=THICK, what="object 'Bow'")
    with pytest.raises(pf.ProfileError, match="closer together"):
        pf.plan([RECT, RECT + [62.0, 0.0]], pf.ProfileSettings(), thickness=THICK)
    with pytest.raises(pf.ProfileError, match="or a hole of it is narrower"):
        pf.plan([RECT, circle(2.0)], pf.ProfileSettings(), thickness=THICK)       # a 4 mm hole, a 6 mm tool


@hsettings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(depth=st.one_of(st.none(), st.floats(-50, 50)), step=st.floats(-2, 10), width=st.floats(-5, 400),
       height=st.floats(-2, 20), count=st.integers(0, 12), allowance=st.floats(-1, 3),
       lead=st.floats(-1, 30), side=st.sampled_from(pf.SIDES), shape=st.sampled_from(pf.TAB_SHAPES),
       scale=st.floats(0.5, 80))
def test_hostile_settings_plan_or_are_refused_never_a_traceback(depth, step, width, height, count, allowance, lead,
                                                                side, shape, scale):
    settings = pf.ProfileSettings(depth=depth, step_down=step, tab_width=width, tab_height=height, tab_count=count,
                                  allowance=allowance if side != "on" else 0.0, lead_radius=lead, side=side,
                                  tab_shape=shape)
    with time_limit(60):
        try:
            plan = pf.plan([circle(scale, n=90)], settings, thickness=THICK)
        except InputError as error:
            assert "profile" in str(error)
            return
    op = plan.operation
    assert np.isfinite(op.xyz).all() and op.xyz[:, 2].min() >= -THICK - 0.3 - 1e-9
    assert (op.kind == RAPID).any()


@pytest.mark.parametrize("side, lead, tab_shape, allowance", [
    ("inside", "arc", "flat", 0.3), ("inside", "line", "triangle", 0.0), ("on", "line", "flat", 0.0),
    ("outside", "none", "triangle", 0.5), ("outside", "line", "flat", 0.0),
])
def test_every_side_and_lead_passes_its_own_design_layer_without_a_plunge(side, lead, tab_shape, allowance):
    settings = pf.ProfileSettings(side=side, lead=lead, tab_shape=tab_shape, tab_count=2, allowance=allowance,
                                  climb=side != "on")
    geometry = ProfileGeometry((tuple(map(tuple, RECT.tolist())),), THICK, 0.0, "object 'Part'", "cut")
    planned = plan_job(Job(Setup("part"), (JobOperation("profile", "cut", settings, geometry),)))
    program, stock, limits = planned.simulation()
    result = sim.simulate(program, stock, cell=0.1, no_plunge_tools=(5,), **limits)
    assert result.findings == []
    gx, gy, heights = grid(result)
    distance = rect_distance(gx, gy)
    if side == "inside":
        distance = -distance
    elif side == "on":
        distance = distance + D / 2         # the tool's centre on the outline: the part loses a radius
    assert heights[distance < -0.01].min() >= -1e-9
