"""Pocketing, checked by cutting the program in the height-field simulation and comparing with
closed forms worked out here by hand (areas of rectangles, circles and L shapes, the corners a
round tool leaves), never with the planner's own regions."""
import math
import re

import numpy as np
import pytest

from kezuri.toolpath.ir.program import FEED
from kezuri.toolpath.job import Job, JobOperation, Setup, plan_job
from kezuri.toolpath.operations.pocket import pocket as pk
from kezuri.toolpath.operations.pocket.kind import PocketGeometry
from kezuri.toolpath.simulate import simulate

CELL = 0.1
DEPTH = 5.0
R6 = 3.0          # the default 6 mm end mill's radius


def circle(cx, cy, r, n=720, clockwise=False):
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    loop = np.column_stack([cx + r * np.cos(a), cy + r * np.sin(a)])
    return loop[::-1] if clockwise else loop


RECT = np.array([[0, 0], [60, 0], [60, 40], [0, 40]], float)
L_SHAPE = np.array([[0, 0], [50, 0], [50, 20], [20, 20], [20, 50], [0, 50]], float)
CORNER = (1 - math.pi / 4)      # what a round tool of radius 1 leaves in a square corner (mm^2)

# name: loops, settings, the area a 6 mm end mill clears (closed form), the perimeter (mm)
CASES = {
    "rectangle": ([RECT], pk.PocketSettings(), 60 * 40 - 4 * CORNER * R6 ** 2, 200.0),
    "circle": ([circle(0, 0, 20)], pk.PocketSettings(strategy="zigzag", angle=30.0), math.pi * 400, 2 * math.pi * 20),
    "island": ([RECT, circle(30, 20, 8)],
               pk.PocketSettings(finish_walls=True, wall_allowance=0.3, finish_floor=True, floor_allowance=0.2),
               60 * 40 - 4 * CORNER * R6 ** 2 - math.pi * 64, 200 + 2 * math.pi * 8),
    "L": ([L_SHAPE], pk.PocketSettings(strategy="zigzag", stepover=5.5), 50 * 20 + 20 * 30 - 5 * CORNER * R6 ** 2, 200.0),
    "L offset": ([L_SHAPE], pk.PocketSettings(stepover=2.0), 50 * 20 + 20 * 30 - 5 * CORNER * R6 ** 2, 200.0),
}


def planned(name, loops, settings):
    job = Job(Setup(name=name), (JobOperation("pocket", name, settings, PocketGeometry(tuple(loops), name)),))
    return plan_job(job)


def simulated(name, loops, settings):
    plan = planned(name, loops, settings)
    program, stock, limits = plan.simulation()
    numbers = tuple(op.tool.number for op in program.operations)
    return plan, program, simulate(program, stock, cell=CELL, no_plunge_tools=numbers, **limits)


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request):
    loops, settings, area, perimeter = CASES[request.param]
    plan, program, sim = simulated(request.param, loops, settings)
    return request.param, loops, settings, area, perimeter, program, sim


def test_removed_volume_is_the_area_times_the_depth(case):
    name, loops, settings, area, perimeter, _, sim = case
    hf = sim.heightfield
    removed = float(((hf.top - hf.heights) * hf.inside).sum() * hf.cell_x * hf.cell_y)
    rim = perimeter * CELL / 2 * DEPTH          # the cells the outline passes through, half cut on average
    assert removed == pytest.approx(area * DEPTH, abs=rim), name


def test_no_finding_no_plunge_and_no_gouge_of_islands_or_outside(case):
    """The gate's findings, with the end mills named as tools that cannot feed straight down and the
    pocket's design layer (floor at the depth, islands and the outside kept)."""
    name, *_, sim = case
    assert sim.findings == [], (name, [f.message for f in sim.findings[:3]])


def test_the_floor_is_flat_at_the_depth_and_the_walls_stand_on_the_outline(case):
    name, loops, settings, *_, sim = case
    hf = sim.heightfield
    gx, gy = np.meshgrid(hf.x(), hf.y(), indexing="ij")
    distance = SIGNED[name.split()[0]](gx, gy).ravel()         # > 0 inside the pocket
    z = hf.heights.ravel()
    margin = 0.01 + CELL
    assert np.all(z[distance < -margin] >= hf.top - 1e-9), f"{name}: cut outside the outline or into an island"
    # the floor: everywhere a tool disc fits, flat at the depth (within a micron)
    deep = distance > R6 + margin
    assert np.abs(z[deep] - (hf.top - DEPTH)).max() < 1e-6
    # the walls: cut to the floor right up to the outline (but in the corners)
    wall = (distance > margin) & (distance < 0.3)
    assert np.mean(z[wall] <= hf.top - DEPTH + 1e-6) > 0.9, name
    assert z.min() >= hf.top - DEPTH - 1e-6


def box_distance(x, y, x0, y0, x1, y1):
    """Signed distance to an axis-parallel rectangle's outline, > 0 inside."""
    inside = np.minimum.reduce([x - x0, x1 - x, y - y0, y1 - y])
    outside = np.hypot(np.maximum.reduce([x0 - x, 0 * x, x - x1]), np.maximum.reduce([y0 - y, 0 * y, y - y1]))
    return np.where(inside > 0, inside, -outside)


SIGNED = {
    "rectangle": lambda x, y: box_distance(x, y, 0, 0, 60, 40),
    "circle": lambda x, y: 20 - np.hypot(x, y),
    "island": lambda x, y: np.minimum(box_distance(x, y, 0, 0, 60, 40), np.hypot(x - 30, y - 20) - 8),
    # the union's distance is the larger of the two outside, at most the true one inside
    "L": lambda x, y: np.maximum(box_distance(x, y, 0, 0, 50, 20), box_distance(x, y, 0, 0, 20, 50)),
}


def test_offset_rings_run_from_the_inside_out_and_climb():
    """The first ring is the innermost; the outer wall's ring runs counter-clockwise and an
    island's clockwise (climb milling with a clockwise spindle)."""
    result = pk.plan([RECT, circle(30, 20, 8)], pk.PocketSettings(depth=1.0, step_down=1.0), "rings")
    op = result.operations[0]
    cutting = op.xyz[(op.kind == FEED) & np.isclose(op.xyz[:, 2], -1.0)]
    # the first cut is far from the outer wall, the last on the ring 3 mm from it
    assert min(cutting[0][0] - 0, 60 - cutting[0][0], cutting[0][1], 40 - cutting[0][1]) > 3.5
    turn = np.cross(np.diff(cutting[:, :2], axis=0)[:-1], np.diff(cutting[:, :2], axis=0)[1:])
    # along the outermost ring (3 mm from the walls) the tool turns left: counter-clockwise
    outer = (np.minimum.reduce([cutting[:, 0], 60 - cutting[:, 0], cutting[:, 1], 40 - cutting[:, 1]]) < 3.001)[1:-1]
    assert np.mean(turn[outer] > 0) > 0.9
    x, y = cutting[-1, :2]      # the last ring is one along a wall: 3 mm from the outline or the island
    assert min(abs(min(x, 60 - x, y, 40 - y) - 3.0), abs(math.hypot(x - 30, y - 20) - 11.0)) < 1e-3
    # round the island (11 mm from its centre) it turns right: clockwise
    near_island = (np.abs(np.hypot(cutting[:, 0] - 30, cutting[:, 1] - 20) - 11.0) < 1e-3)[1:-1]
    assert near_island.sum() > 50 and np.mean(turn[near_island] < 0) > 0.9


def test_rest_machining_clears_the_slots_and_the_small_tool_cuts_only_where_the_large_could_not():
    """A 30 mm square with two 3 mm slots: a 6 mm end mill cannot enter the slots, a 2 mm one
    clears them; the 2 mm tool's centre stays within its radius of what the 6 mm one left (the
    slots, and the square's corners beyond the 6 mm tool's radius)."""
    slots = np.array([[0, 0], [30, 0], [30, 5], [45, 5], [45, 8], [30, 8], [30, 20], [45, 20], [45, 23],
                      [30, 23], [30, 30], [0, 30]], float)
    settings = pk.PocketSettings(rest_tool=pk.end_mill(6, 2.0))
    plan, program, sim = simulated("slots", [slots], settings)
    assert [op.tool.diameter for op in program.operations] == [6.0, 2.0]
    assert sim.findings == [], [f.message for f in sim.findings[:3]]
    hf = sim.heightfield
    # every slot cell a 2 mm tool reaches (1 mm inside the slot ends and sides... the slot is 3 mm
    # wide, so its middle 1 mm band and more) is at the depth
    xs = hf.x()
    for y0 in (5.0, 20.0):
        j = int(np.argmin(np.abs(hf.y() - (y0 + 1.5))))
        along = (xs > 30.5) & (xs < 44.0)
        assert np.allclose(hf.heights[along, j], hf.top - DEPTH, atol=1e-6)
    removed = float(((hf.top - hf.heights) * hf.inside).sum() * hf.cell_x * hf.cell_y)
    area = 30 * 30 + 2 * 15 * 3 - 8 * CORNER * 1.0 ** 2       # the 2 mm tool leaves its radius in 8 corners
    assert removed == pytest.approx(area * DEPTH, abs=(30 * 4 + 4 * 15) * CELL / 2 * DEPTH)
    # the 2 mm tool's moves at depth: within 1 mm (+ 0.02) of the slots or of the square's corners
    # where the 6 mm tool left material (within 3 mm of two walls at a corner)
    rest = program.operations[1]
    cutting = rest.xyz[(rest.kind == FEED) & (rest.xyz[:, 2] < -1e-6)]
    x, y = cutting[:, 0], cutting[:, 1]
    in_slot = (x >= 30 - 1.02) & (((y >= 5 - 1.02) & (y <= 8 + 1.02)) | ((y >= 20 - 1.02) & (y <= 23 + 1.02)))
    corner_of = [(0, 0), (30, 0), (30, 30), (0, 30), (30, 5), (30, 8), (30, 20), (30, 23)]
    in_corner = np.zeros(len(x), bool)
    for cx, cy in corner_of:
        in_corner |= (np.abs(x - cx) <= 3.0 + 1.02) & (np.abs(y - cy) <= 3.0 + 1.02)
    assert np.all(in_slot | in_corner)
    assert in_slot.any() and in_corner.any()


def test_a_helix_that_does_not_fit_falls_back_to_a_ramp_along_the_path_and_says_so():
    narrow = np.array([[0, 0], [40, 0], [40, 8], [0, 8]], float)     # 2 mm of room for the 6 mm tool's centre
    result = pk.plan([narrow], pk.PocketSettings(helix_diameter=4.0), "slot")
    assert any("4 mm helix does not fit" in w and "ramped along the path" in w for w in result.warnings)


def test_where_neither_a_helix_nor_a_ramp_fits_the_pocket_is_refused_by_name():
    snug = circle(0, 0, 3.3)                  # a 0.3 mm circle of room for the tool centre: 1.9 mm round
    with pytest.raises(pk.PocketError, match=r"pocket 'logo': the 6 mm end mill's 4 mm helix does not fit in "
                                             r"the region at X-?\d+\.\d+ Y-?\d+\.\d+"):
        pk.plan([snug], pk.PocketSettings(), "logo")


@pytest.mark.parametrize("loops, settings, message", [
    ([np.array([[0, 0], [10, 0]], float)], pk.PocketSettings(), r"loop 1.*fewer than 3 distinct points"),
    ([circle(0, 0, 2.5)], pk.PocketSettings(), r"pocket 'p': the 6 mm end mill does not fit in the region"),
    ([RECT], pk.PocketSettings(stepover=0.0), r"stepover must be more than 0"),
    ([RECT], pk.PocketSettings(stepover=6.5), r"stepover 6.5 mm is more than the .*diameter"),
    ([RECT], pk.PocketSettings(depth=0.0), r"depth must be more than 0"),
    ([np.array([[0, 0], [10, 10], [10, 0], [0, 20]], float)], pk.PocketSettings(),
     r"loop 1 crosses itself at X6\.667 Y6\.667"),
    ([RECT], pk.PocketSettings(wall_allowance=0.3), r"wall_allowance 0.3 mm is left by roughing but finish_walls is off"),
    ([RECT], pk.PocketSettings(strategy="spiral"), r"strategy must be one of offset, zigzag"),
    ([RECT], pk.PocketSettings(ramp_angle=90.0), r"ramp_angle must be from 0.5 to 45 degrees"),
    ([RECT], pk.PocketSettings(rest_tool=pk.end_mill(6, 8.0)), r"rest_tool .* must be smaller"),
    ([np.array([[0, 0], [np.nan, 0], [1, 1]], float)], pk.PocketSettings(), r"non-finite"),
])
def test_bad_regions_and_settings_are_refused_by_name(loops, settings, message):
    with pytest.raises(pk.PocketError, match=message):
        pk.plan(loops, settings, "p")


def test_a_piece_no_entry_fits_is_left_uncut_with_a_note_while_the_rest_is_cut():
    """A rectangle and, apart from it, a circle only 0.3 mm wider than the tool's radius: the
    rectangle is pocketed, the circle's 1.9 mm path is too short to ramp on and is named."""
    loops = [RECT, circle(100, 0, 3.3)]
    result = pk.plan(loops, pk.PocketSettings(depth=2.0), "two")
    op = result.operations[0]
    assert op.xyz[:, 2].min() == pytest.approx(-2.0)
    assert np.all(op.xyz[op.xyz[:, 2] < 0, 0] < 61)                   # nothing cut in the circle
    assert any(re.search(r"cannot enter at X99\.[67]\d+ Y-?0\.\d+ \(a 1\.8\d mm path\): left uncut there", w)
               for w in result.warnings), result.warnings


@pytest.mark.parametrize("angle", [0.0, 45.0, 90.0, 137.5, -30.0])
def test_zigzag_at_any_angle_clears_the_rectangle_round_its_island(angle):
    loops = [RECT, circle(30, 20, 8)]
    _, program, sim = simulated(f"zigzag {angle:g}", loops, pk.PocketSettings(strategy="zigzag", angle=angle,
                                                                            stepover=4.0))
    assert sim.findings == [], [f.message for f in sim.findings[:3]]
    hf = sim.heightfield
    removed = float(((hf.top - hf.heights) * hf.inside).sum() * hf.cell_x * hf.cell_y)
    area = 60 * 40 - 4 * CORNER * R6 ** 2 - math.pi * 64
    assert removed == pytest.approx(area * DEPTH, abs=(200 + 2 * math.pi * 8) * CELL / 2 * DEPTH)
