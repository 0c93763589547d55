"""W2 rotary-table pockets (C-X-Z): geometry against analytic shapes, NC through LinuxCNC's rs274.

The checks on the written programs use rs274's canonical moves and this file's own
conversion (part point = machine point (X, 0) turned by +C about the axis), not the
module's helpers, so a sign or unwrapping mistake cannot cancel itself out.
"""
import math
import re

import numpy as np
import pytest

import rs274
from kezuri.post.gcode import PostError
from kezuri.post import rotary_post
from kezuri.post.rotary_cxz import FanucRotaryPost, LinuxCNCRotaryPost
from kezuri.toolpath.engines import region as rg
from kezuri.toolpath.operations.rotary import rotary, rotary_curves, rotary_pocket
from kezuri.toolpath.ir.program import RAPID, Operation, Program, Tool
from kezuri.toolpath.operations.rotary.rotary import Block, Pocket, RotaryError, RotarySettings

needs_rs274 = pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")

SETTINGS = RotarySettings()
R = SETTINGS.tool.radius


def rectangle(cx, cy, width, height):
    return np.array([[cx - width / 2, cy - height / 2], [cx + width / 2, cy - height / 2],
                     [cx + width / 2, cy + height / 2], [cx - width / 2, cy + height / 2]])


# Small analytic pockets: planes and a sphere the tests can write down independently.
SLANTED = Pocket("slanted box", rectangle(-15.0, 10.0, 40.0, 24.0), depth=8.0, wall_angle_deg=20.0)
VERTICAL = Pocket("vertical box", rectangle(12.0, -14.0, 30.0, 18.0), depth=6.0)
SPHERE = Pocket("square bowl", rectangle(20.0, 5.0, 30.0, 30.0), depth=6.0, bottom="sphere", sphere_radius=42.0)
AROUND_AXIS = Pocket("around the axis", rectangle(2.0, 1.0, 30.0, 20.0), depth=4.0)
SMALL_BLOCK = Block(80.0, 80.0, 20.0)


@pytest.fixture(scope="module")
def sample():
    return rotary.plan(*rotary.sample_job())


@pytest.fixture(scope="module")
def analytic():
    """Each analytic pocket planned on its own, with its LinuxCNC text."""
    jobs = {}
    for pocket in (SLANTED, VERTICAL, SPHERE, AROUND_AXIS):
        result = rotary.plan(SMALL_BLOCK, [pocket])
        jobs[pocket.name] = (result, LinuxCNCRotaryPost().to_text(result.program))
    return jobs


def machine_to_part(x, c):
    c = np.radians(c)
    return np.column_stack([x * np.cos(c), x * np.sin(c)])


def interpolated_tips(points, rotary_abc, kinds, samples=6):
    """Tool-tip positions in the part frame along every feed move, as the machine moves:
    X, C, Z linear between the canonical end points."""
    out = []
    for i in range(1, len(kinds)):
        if kinds[i] != "feed":
            continue
        t = np.linspace(0, 1, samples + 1)[:, None]
        x = points[i - 1, 0] + (points[i, 0] - points[i - 1, 0]) * t[:, 0]
        c = rotary_abc[i - 1, 2] + (rotary_abc[i, 2] - rotary_abc[i - 1, 2]) * t[:, 0]
        z = points[i - 1, 2] + (points[i, 2] - points[i - 1, 2]) * t[:, 0]
        out.append(np.column_stack([machine_to_part(x, c), z]))
    return np.vstack(out)


def canonical(text):
    return rs274.motion_endpoints(rs274.run(text))


def g1_blocks(text):
    """(start X C Z, end X C Z, F) of every G01 block, tracking modal words; each must carry F."""
    state = {"X": None, "C": None, "Z": None}
    mode, blocks = None, []
    for line in text.splitlines():
        if line.startswith("("):
            continue
        words = dict(re.findall(r"([GXCZF])(-?[\d.]+)", line))
        codes = re.findall(r"G(\d+)", line)
        if "00" in codes or "01" in codes:
            mode = "01" if "01" in codes else "00"
        start = dict(state)
        for axis in "XCZ":
            if axis in words:
                state[axis] = float(words[axis])
        if mode == "01" and any(axis in words for axis in "XCZ"):
            assert "F" in words, f"G93 cutting block without F: {line}"
            blocks.append(([start[a] for a in "XCZ"], [state[a] for a in "XCZ"], float(words["F"])))
    return blocks


def part_length(start, end, samples=2000):
    t = np.linspace(0, 1, samples + 1)
    x = start[0] + (end[0] - start[0]) * t
    c = start[1] + (end[1] - start[1]) * t
    z = start[2] + (end[2] - start[2]) * t
    pts = np.column_stack([machine_to_part(x, c), z])
    return float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())


def polygon_distance(loop, pts):
    """Unsigned distance from points to a closed polygon's edges (test's own)."""
    a = np.asarray(loop, float)
    b = np.roll(a, -1, axis=0)
    d = b - a
    best = np.full(len(pts), np.inf)
    for k in range(len(a)):
        t = np.clip(((pts - a[k]) @ d[k]) / (d[k] @ d[k]), 0, 1)
        best = np.minimum(best, np.linalg.norm(pts - (a[k] + t[:, None] * d[k]), axis=1))
    return best


# ----------------------------------------------------------------------------------------
# Cylindrical coordinates
# ----------------------------------------------------------------------------------------

def test_cylindrical_round_trip_including_near_180():
    rng = np.random.default_rng(7)
    pts = rng.uniform(-60, 60, size=(500, 2))
    eps = 1e-9
    special = np.array([[-10, 0], [10, eps], [10, -eps], [10, 0], [0, -10], [0, 10], [-0.001, 0], [35, 1e-7],
                        [35, -1e-7], [-35, 1e-7], [-35, -1e-7]], float)
    pts = np.vstack([pts, special])
    x_word, c = rotary.to_cylindrical(pts)
    assert np.all(x_word <= 0)
    assert np.all((c > -180 - 1e-12) & (c <= 180 + 1e-12))
    assert np.allclose(rotary.from_cylindrical(x_word, c), pts, atol=1e-9)
    # Shifting C by whole turns names the same point (C may run past 360).
    assert np.allclose(rotary.from_cylindrical(x_word, c + 720), pts, atol=1e-9)
    assert np.allclose(rotary.from_cylindrical(x_word, c - 360), pts, atol=1e-9)


def test_sign_convention():
    # (-R, 0) is C = 0; C is measured counter-clockwise (seen from +Z) from the -X axis.
    x_word, c = rotary.to_cylindrical([[-25, 0], [0, -25], [0, 25], [25, 0]])
    assert np.allclose(x_word, -25)
    assert np.allclose(c, [0, 90, -90, 180])
    # The part point under the tool at (X, 0) is that point turned by +C: the table itself
    # turned by -C, i.e. clockwise seen from the tool for +C.
    assert np.allclose(rotary.from_cylindrical(-25, 90), machine_to_part(np.array([-25.0]), np.array([90.0])))


def test_unwrap_keeps_neighbours_within_half_a_turn():
    angles = np.linspace(0, 4 * 360, 400)
    raw = (angles + 180) % 360 - 180
    radius = np.full(len(raw), 10.0)
    radius[50] = 0.0   # on the axis: keeps the previous C
    c = rotary.unwrap_c(raw, radius)
    assert np.max(np.abs(np.diff(c))) <= 180
    assert c[50] == c[49]
    mask = np.arange(len(c)) != 50
    assert np.allclose(c[mask], angles[mask])
    assert rotary.unwrap_c([170.0], [5.0], start_c=-540.0)[0] == pytest.approx(-550.0)


def test_c_is_continuous_over_the_whole_program(sample, analytic):
    programs = [sample.program] + [job[0].program for job in analytic.values()]
    for program in programs:
        c = np.concatenate([op.rotary["c"] for op in program.operations])
        assert np.max(np.abs(np.diff(c))) <= 180
        for op in program.operations:
            assert np.all(op.xyz[:, 0] <= 0) and np.all(op.xyz[:, 1] == 0)
    # Roughing circles around the axis turn the table many times: C runs past 360.
    c = analytic["around the axis"][0].program.operations[0].rotary["c"]
    assert c.max() - c.min() > 720


# ----------------------------------------------------------------------------------------
# The NC: rs274, inverse time
# ----------------------------------------------------------------------------------------

@needs_rs274
def test_rs274_accepts_every_program_and_sees_the_ir_points(sample, analytic):
    jobs = [(sample, LinuxCNCRotaryPost().to_text(sample.program))] + list(analytic.values())
    for result, text in jobs:
        kinds, points, abc = canonical(text)
        feed = [i for i, k in enumerate(kinds) if k == "feed"]
        got = np.column_stack([machine_to_part(points[feed, 0], abc[feed, 2]), points[feed, 2]])
        want = []
        for op in result.program.operations:
            last = (op.start[0], op.rotary["c"][0], op.start[2])
            for kind, (x, _, z), c in zip(op.kind, op.xyz, op.rotary["c"]):
                key = (round(x, 4), round(c, 4), round(z, 4))
                if key == tuple(round(v, 4) for v in last):
                    continue
                last = (x, c, z)
                if kind != RAPID:
                    want.append([*machine_to_part(np.array([x]), np.array([c]))[0], z])
        want = np.array(want)
        assert got.shape == want.shape
        assert np.max(np.abs(got - want)) < 1e-3


@needs_rs274
def test_inverse_time_f_is_path_length_over_speed(sample, analytic):
    table_deg_per_min = 360.0 * SETTINGS.max_table_rpm
    speeds = (SETTINGS.cutting_speed, SETTINGS.plunge_speed)
    for text in [LinuxCNCRotaryPost().to_text(sample.program), analytic["around the axis"][1]]:
        text_g93 = text.split("G93", 1)[1]
        assert "G94" in text_g93          # restored after the cutting
        limited = 0
        blocks = g1_blocks(text)
        assert blocks
        for start, end, f in blocks[::7]:
            length = part_length(start, end)
            minutes = 1.0 / f
            table_minutes = abs(end[1] - start[1]) / table_deg_per_min
            # A block takes its length at its speed (cutting or plunging), or the table's time for
            # its turn of C when that is longer.  The written end points are rounded to 1e-4 mm:
            # allow that much on the length.  No block is timed shorter than 1/9000 min (Fanuc's G93
            # F ends at 9999.999; the planner merges shorter moves where it can).
            errors = [abs(minutes - max(length / s, table_minutes, 1 / 9000)) * s
                      - 1e-3 * max(length, table_minutes * s) for s in speeds]
            assert min(errors) < 3e-4, (start, end, f)
            limited += table_minutes > length / SETTINGS.cutting_speed * 1.001 and \
                minutes == pytest.approx(table_minutes, rel=1e-3)
        assert limited < len(blocks[::7]) / 5


def test_move_lengths_are_part_frame_lengths():
    # A quarter turn at R = 20 and one mm down: a helix piece on the part, not 90 "mm".
    op = Operation("arc", SETTINGS.tool, 1000, [1, 1], [[-20, 0, -1], [-20, 0, -2]], [1200, 1200],
                   rotary={"c": [0.0, 90.0]}, start=[-20, 0, -1])
    lengths = rotary.move_lengths(op)
    assert lengths[0] == pytest.approx(0.0)
    assert lengths[1] == pytest.approx(math.hypot(math.pi / 2 * 20, 1.0), rel=1e-9)
    f = rotary.inverse_time_feed(op, max_table_rpm=1000)
    assert 1 / f[1] == pytest.approx(lengths[1] / 1200)


# ----------------------------------------------------------------------------------------
# Gouge: sampled ball centres (from rs274's moves) against the analytic pocket
# ----------------------------------------------------------------------------------------

def ball_centres(text):
    kinds, points, abc = canonical(text)
    tips = interpolated_tips(points, abc, kinds)
    return tips + np.array([0, 0, R])


@needs_rs274
def test_slanted_walls_and_flat_floor_are_never_cut(analytic):
    pocket = SLANTED
    centres = ball_centres(analytic[pocket.name][1])
    theta = math.radians(pocket.wall_angle_deg)
    (x0, y0), (x1, y1) = pocket.outline.min(axis=0), pocket.outline.max(axis=0)
    x, y, z = centres.T
    # Each wall plane leans out by tan(theta) towards the top; the ball must stay r off it
    # wherever it would touch it below the board top (a convex pocket: the half-spaces suffice).
    touching = z - R * math.sin(theta) <= 0
    for inward in (x - x0, x1 - x, y - y0, y1 - y):
        distance = (inward + z * math.tan(theta)) * math.cos(theta)
        assert np.all(distance[touching] >= R - 1e-6)
    assert np.all(z - R >= -pocket.depth - 1e-6)
    # And it reaches the design surface within the stand-off.
    assert np.min(z - R) == pytest.approx(-pocket.depth, abs=0.02)


@needs_rs274
def test_vertical_walls_and_flat_floor_are_never_cut(analytic, sample):
    pocket = VERTICAL
    centres = ball_centres(analytic[pocket.name][1])
    (x0, y0), (x1, y1) = pocket.outline.min(axis=0), pocket.outline.max(axis=0)
    x, y, z = centres.T
    below = z < R
    for inward in (x - x0, x1 - x, y - y0, y1 - y):
        assert np.all(inward[below] >= R - 1e-6)
    assert np.all(z - R >= -pocket.depth - 1e-6)
    # The sample's waisted (non-convex) pocket: distance to its outline polygon.
    peanut = next(p for p in sample.pockets if p.pocket.name == "peanut")
    op = peanut.operation
    tips = rotary.part_points(op)[op.kind != RAPID]
    inside = tips[:, 2] + R < R
    d = polygon_distance(peanut.pocket.outline, tips[inside, :2])
    assert np.all(d >= R - 1e-6)
    assert np.all(tips[:, 2] >= -peanut.pocket.depth - 1e-6)


@needs_rs274
def test_sphere_bowl_is_never_cut(analytic):
    pocket = SPHERE
    centres = ball_centres(analytic[pocket.name][1])
    rs = pocket.sphere_radius
    sphere_centre = np.array([20.0, 5.0, rs - pocket.depth])
    below = centres[:, 2] < R
    assert np.all(np.linalg.norm(centres[below] - sphere_centre, axis=1) <= rs - R + 1e-6)
    (x0, y0), (x1, y1) = pocket.outline.min(axis=0), pocket.outline.max(axis=0)
    x, y, _ = centres[below].T
    for inward in (x - x0, x1 - x, y - y0, y1 - y):
        assert np.all(inward >= R - 1e-6)
    # The bottom of the bowl is reached (the helix starts at the lowest point).
    assert np.min(centres[:, 2] - R) == pytest.approx(-pocket.depth, abs=0.02)


def test_reported_gouge_is_zero(sample, analytic):
    for report in sample.reports + [job[0].reports[0] for job in analytic.values()]:
        assert report["max_gouge_mm"] == 0.0


def crescent():
    a = np.linspace(0.3, 2 * np.pi - 0.3, 80)
    outer = np.column_stack([20 * np.cos(a), 20 * np.sin(a)])
    inner = np.column_stack([10 * np.cos(a[::-1]), 10 * np.sin(a[::-1])])
    return np.vstack([outer, inner]) + [5, 10]


def dumbbell():
    """Two 18 mm lobes joined by a neck narrower than the bit: the floor falls in two pieces."""
    t = np.linspace(0, 2 * np.pi, 100, endpoint=False)
    shape = (rg.CrossSection([np.column_stack([-15 + 9 * np.cos(t), 9 * np.sin(t)])])
             + rg.CrossSection([np.column_stack([15 + 9 * np.cos(t), 9 * np.sin(t)])])
             + rg.rectangle(-15, -2.5, 15, 2.5))
    return rg.loops(shape)[0] + [0, -30]


@needs_rs274
@pytest.mark.parametrize("outline, angle", [(crescent(), 0.0), (dumbbell(), 0.0), (dumbbell(), 10.0)])
def test_awkward_outlines_are_cut_without_gouge(outline, angle):
    # Centre off the floor (crescent), floor and walls in two pieces (dumbbell).
    pocket = Pocket("awkward", outline, 8.0, wall_angle_deg=angle)
    result = rotary.plan(Block(), [pocket])
    assert result.reports[0]["max_gouge_mm"] == 0.0
    kinds, points, abc = canonical(LinuxCNCRotaryPost().to_text(result.program))
    centres = interpolated_tips(points, abc, kinds, samples=3) + np.array([0, 0, R])
    below = centres[:, 2] - R * math.sin(math.radians(angle)) < 0
    need = R / math.cos(math.radians(angle)) - centres[below, 2] * math.tan(math.radians(angle))
    assert np.all(polygon_distance(outline, centres[below, :2]) >= need - 1e-6)
    assert np.all(rg.contains_points(rg.from_loops([outline]), centres[below, :2]))
    assert np.all(centres[:, 2] - R >= -8.0 - 1e-6)


def test_gouge_check_sees_a_gouge():
    result = rotary.plan(SMALL_BLOCK, [VERTICAL])
    op = result.program.operations[0]
    deeper = op.replace(xyz=op.xyz - np.array([0, 0, 0.3]))
    assert rotary.max_gouge(VERTICAL, deeper, SMALL_BLOCK) == pytest.approx(0.3, abs=1e-3)  # the floor was exact


def test_simulated_flat_floor_is_at_the_depth_and_not_gouged():
    # The floor spiral used to stand tolerance + ARC_TOLERANCE = 0.015 mm proud of the floor.
    from kezuri.toolpath import simulate as sim
    result = rotary.plan(SMALL_BLOCK, [VERTICAL])
    (x0, y0), (x1, y1) = VERTICAL.outline.min(axis=0), VERTICAL.outline.max(axis=0)

    def design(x, y):
        return np.where((x >= x0) & (x <= x1) & (y >= y0) & (y <= y1), -VERTICAL.depth, 0.0)
    found = sim.simulate(result.program, sim.BoxStock(-40, -40, -20, 40, 40, 0), cell=0.05, design=design)
    assert found.findings == []
    hf = found.heightfield
    x, y = np.meshgrid(hf.x(), hf.y(), indexing="ij")
    middle = (x > x0 + 2 * R) & (x < x1 - 2 * R) & (y > y0 + 2 * R) & (y < y1 - 2 * R)
    # The deepest point of the floor is the depth (the ball's tip runs on it), within 0.001 mm.
    assert hf.heights[middle].min() == pytest.approx(-VERTICAL.depth, abs=1e-3)
    # and nothing is below it anywhere
    assert hf.heights.min() >= -VERTICAL.depth - 1e-3
    # Between the spiral's turns the scallop of a ball at pitch P: r - sqrt(r^2 - (P/2)^2).
    scallop = R - math.sqrt(R * R - (SETTINGS.stepover / 2) ** 2)
    assert hf.heights[middle].max() <= -VERTICAL.depth + scallop + 0.02


def box_penetration(pocket, centres):
    """The test's own: how far balls cut into a pocket with vertical walls and a flat floor."""
    z = centres[:, 2]
    d = polygon_distance(pocket.outline, centres[:, :2])
    d = np.where(rg.contains_points(rg.from_loops([pocket.outline]), centres[:, :2]), d, -d)
    wall = np.where(z <= 0, R, np.sqrt(np.maximum(R * R - z * z, 0.0))) - d
    return np.maximum(np.where(z < R, wall, -np.inf), -pocket.depth - (z - R))


@pytest.mark.parametrize("turn, move", [(0.5, 0.0), (0.0, -0.3)])
def test_gouge_check_bounds_a_wall_gouge(turn, move):
    # Turning the table or moving X a little pushes the ball into the walls.  The check is a
    # bound, not a sample: never below what dense sampling of the machine's motion finds.
    op = rotary.plan(SMALL_BLOCK, [VERTICAL]).program.operations[0]
    moved = op.replace(xyz=op.xyz + [move, 0.0, 0.0], rotary={"c": op.rotary["c"] + turn})
    points = np.vstack([moved.start, moved.xyz])
    c = np.concatenate([moved.rotary["c"][:1], moved.rotary["c"]])
    kinds = ["rapid"] + ["rapid" if k == RAPID else "feed" for k in moved.kind]
    tips = interpolated_tips(points, np.column_stack([0 * c, 0 * c, c]), kinds, samples=100)
    dense = float(box_penetration(VERTICAL, tips + [0, 0, R]).max())
    assert dense > 0.1
    assert dense - 1e-9 <= rotary.max_gouge(VERTICAL, moved, SMALL_BLOCK) <= dense * 1.001 + 1e-4


@pytest.mark.parametrize("outline", [crescent(), dumbbell(), rectangle(0.0, 0.0, 30.0, 18.0)])
def test_outline_distance_is_exact(outline):
    loop = rg.validate_loop(outline, "test")
    region = rg.from_loops([loop])
    distance = rotary_pocket.OutlineDistance(loop, region, cap=4.0)
    pts = np.random.default_rng(7).uniform(loop.min(axis=0) - 5, loop.max(axis=0) + 5, (4000, 2))
    exact = polygon_distance(loop, pts) * np.where(rg.contains_points(region, pts), 1, -1)
    got = distance(pts)
    capped = got == 4.0
    assert np.allclose(got[~capped], exact[~capped], rtol=0, atol=1e-9)
    assert np.all(exact[capped] >= 4.0 - 1e-9)        # deep inside only "at least cap"


@pytest.mark.parametrize("outline", [crescent(), dumbbell()])
def test_curve_clipping_agrees_with_region(outline):
    region = rg.offset(rg.from_loops([outline]), -3.5)
    centre = np.array(rg.centroid(region))
    region = region.translate(tuple(-centre))
    boundary = rotary_curves.Boundary(region)
    phi = np.linspace(0, 2 * np.pi * 25, 20000)
    spiral = rotary_curves.by_arc_length(np.column_stack([phi * np.cos(phi), phi * np.sin(phi)]) / (2 * np.pi), 1.0)
    for curve in [rotary_curves.circle_points(radius, 1.0) for radius in (2.0, 6.5, 11.0, 17.0)] + [spiral]:
        ours, theirs = boundary.clip(curve), rg.clip_polyline(curve, region)
        assert len(ours) == len(theirs)
        assert all(a.shape == b.shape and np.allclose(a, b, rtol=0, atol=1e-12) for a, b in zip(ours, theirs))


# ----------------------------------------------------------------------------------------
# Roughing, finishing coverage, scallops
# ----------------------------------------------------------------------------------------

def test_roughing_circles_stay_inside_the_tool_offset_outline(sample):
    step = SETTINGS.roughing_stepover
    for path in sample.pockets:
        pocket = path.pocket
        theta = math.radians(pocket.wall_angle_deg)
        centre = np.array(path.report["centre"])
        assert path.roughing
        for tip_z, chain in path.roughing:
            assert np.allclose(chain[:, 2], tip_z)
            z = tip_z + R      # ball centre
            allowed = R / math.cos(theta) - z * math.tan(theta) + SETTINGS.allowance
            d = polygon_distance(pocket.outline, chain[:, :2])
            assert np.all(d >= allowed - 1e-6)
            free = d > allowed + 0.05
            if pocket.bottom == "flat":
                assert z - R >= -pocket.depth + SETTINGS.allowance - 1e-9
            else:
                s = np.array([*centre, pocket.sphere_radius - pocket.depth])
                gap = pocket.sphere_radius - R - SETTINGS.allowance - np.linalg.norm(
                    np.column_stack([chain[:, :2], chain[:, 2] + R]) - s, axis=1)
                assert np.all(gap >= -1e-6)
                free &= gap > 0.05
            # Away from the outline (and the bowl) the tool is on a circle about the pocket
            # centre, radius k * stepover.
            rings = np.linalg.norm(chain[free, :2] - centre, axis=1) / step
            assert np.allclose(rings, np.round(rings), atol=1e-6)
        depths = sorted({z for z, _ in path.roughing}, reverse=True)
        assert depths[0] >= -SETTINGS.step_down - 1e-9
        assert np.all(-np.diff(depths) <= SETTINGS.step_down + 1e-9)
        if pocket.bottom == "flat":
            # roughed down to the floor (less the allowance), so the floor spiral takes only that
            assert depths[-1] == pytest.approx(-pocket.depth + SETTINGS.allowance + SETTINGS.standoff, abs=1e-9)


def test_floor_spiral_covers_the_floor(sample):
    path = next(p for p in sample.pockets if p.pocket.name == "peanut")
    floor = np.vstack([c for c in path.bottom] + [path.wall[-1][1]])
    lo, hi = floor[:, :2].min(axis=0), floor[:, :2].max(axis=0)
    gx, gy = np.meshgrid(np.arange(lo[0], hi[0], 0.7), np.arange(lo[1], hi[1], 0.7))
    grid = np.column_stack([gx.ravel(), gy.ravel()])
    inside = polygon_distance(path.pocket.outline, grid) >= R + 0.1
    inside &= rg.contains_points(rg.from_loops([path.pocket.outline]), grid)
    grid = grid[inside]
    nearest = np.array([np.min(np.linalg.norm(floor[:, :2] - p, axis=1)) for p in grid])
    # Passes stepover apart, points spacing apart: nothing farther than half the diagonal.
    assert nearest.max() <= math.hypot(SETTINGS.stepover, SETTINGS.spacing) / 2 + 0.02
    assert np.allclose(np.vstack(path.bottom)[:, 2], -path.pocket.depth)    # on the floor, no stand-off
    assert np.allclose(path.wall[-1][1][:, 2], -path.pocket.depth + SETTINGS.standoff)


def test_bowl_helix_has_pitch_p_along_the_surface(sample):
    path = next(p for p in sample.pockets if p.pocket.name == "bowl")
    chain = path.bottom[0]
    centre = np.array([*path.report["centre"], path.pocket.sphere_radius - path.pocket.depth])
    v = np.column_stack([chain[:, :2], chain[:, 2] + R]) - centre
    psi = np.arccos(-v[:, 2] / np.linalg.norm(v, axis=1))
    phi = np.unwrap(np.arctan2(v[:, 1], v[:, 0]))
    on_helix = np.abs(np.linalg.norm(v, axis=1) - (path.pocket.sphere_radius - R - SETTINGS.standoff)) < 1e-6
    turns = (phi - phi[0]) / (2 * np.pi)
    arc = psi * path.pocket.sphere_radius
    # Past the first turns (where one alpha step spans a whole turn), before the rim clips it.
    middle = on_helix & (turns > 2) & (turns < 10)
    slope = np.polyfit(turns[middle], arc[middle], 1)[0]
    assert slope == pytest.approx(SETTINGS.stepover, rel=1e-4)
    steps = np.linalg.norm(np.diff(chain[middle], axis=0), axis=1)
    # alpha along the helix; the chords are a little shorter where the turns are tight.
    assert np.all((steps <= SETTINGS.spacing + 1e-9) & (steps > 0.99 * SETTINGS.spacing))


def numeric_scallop(r, step, surface_radius=None):
    """Highest point of the lower envelope of two neighbouring balls above the design surface."""
    if surface_radius is None:
        x = np.linspace(0, step, 20001)
        envelope = np.minimum(-np.sqrt(np.maximum(r * r - x ** 2, 0)), -np.sqrt(np.maximum(r * r - (x - step) ** 2, 0)))
        return float(envelope.max() + r)
    beta = step / surface_radius
    rho = surface_radius - r
    angles = np.linspace(0, beta, 20001)
    # Distance from the sphere centre to each ball surface along the ray at `angles`.
    reach = []
    for centre_angle in (0.0, beta):
        off = angles - centre_angle
        reach.append(rho * np.cos(off) + np.sqrt(r * r - (rho * np.sin(off)) ** 2))
    return float(surface_radius - np.max(reach, axis=0).min())


@pytest.mark.parametrize("r, step, surface", [(3, 1, None), (3, 0.5, None), (3, 2.5, None), (3, 1, 22.0),
                                              (3, 2, 10.0), (5, 1, 60.0)])
def test_scallop_closed_form(r, step, surface):
    expected = numeric_scallop(r, step, surface)
    got = rotary.scallop_height(r, step) if surface is None else rotary.scallop_height(r, step, surface)
    assert got == pytest.approx(expected, abs=1e-6)
    if surface is not None:
        assert got < rotary.scallop_height(r, step)    # a concave surface hugs the ball: a lower cusp


def test_sample_reports(sample):
    assert [r["name"] for r in sample.reports] == ["slanted tray", "peanut", "bowl"]
    assert [r["bottom"] for r in sample.reports] == ["flat", "flat", "sphere"]
    assert [r["wall_angle_deg"] for r in sample.reports] == [15.0, 0.0, 0.0]
    for report in sample.reports:
        assert set(report) >= {"name", "bottom", "wall_angle_deg", "outline", "points", "max_gouge_mm",
                               "scallop_mm", "cycle_time_s"}
        assert report["points"] > 100 and report["cycle_time_s"] > 0
        assert report["scallop_mm"] == pytest.approx(max(report["scallop_bottom_mm"], report["scallop_wall_mm"]))
    assert sample.reports[0]["scallop_bottom_mm"] == pytest.approx(rotary.scallop_height(R, 1.0), abs=1e-4)
    assert sample.reports[2]["scallop_bottom_mm"] == pytest.approx(rotary.scallop_height(R, 1.0, 22.0), abs=1e-4)
    assert sample.reports[2]["rim_wall_mm"] > 0          # a non-circular bowl has a rim
    # The paper cut its three pockets in 8 min 22 s; the estimate is of the same order.
    assert 4 * 60 < sample.cycle_time_s < 16 * 60
    block, pockets = rotary.sample_job()
    half = block.size_x / 2
    for pocket in pockets:
        assert np.all(np.abs(pocket.outline) < half - 5)


# ----------------------------------------------------------------------------------------
# Posts
# ----------------------------------------------------------------------------------------

def test_header_carries_the_cycle_time_and_output_is_deterministic(sample):
    for name in ("linuxcnc", "fanuc"):
        a = rotary_post(name).to_text(sample.program)
        b = rotary_post(name).to_text(sample.program)
        assert a == b
        match = re.search(r"ESTIMATED CYCLE TIME: (\d+) MIN (\d+) S", a)
        assert match and int(match.group(1)) * 60 + int(match.group(2)) == pytest.approx(sample.cycle_time_s, abs=1.5)
        assert len(g1_blocks(a)) > 1000
        assert a.count("\nG93\n") == len(sample.program.operations) == a.count("\nG94\n")


def test_fanuc_flavour():
    result = rotary.plan(SMALL_BLOCK, [VERTICAL])
    lines = FanucRotaryPost().to_text(result.program).splitlines()
    assert lines[0] == "%" and lines[1].startswith("O0001") and lines[-1] == "%"
    assert "T01 M06" in lines and "G43 Z50. H01" in lines
    assert lines[-5:-1] == ["M05", "G91 G28 Z0.", "G90", "M30"]
    assert not any(line.startswith("G64") for line in lines)
    assert not any(re.search(r"\bY", line) for line in lines if not line.startswith("("))
    for word in re.findall(r"\b[XCZF]-?[\d.]+", "\n".join(lines)):
        assert "." in word, word
    assert g1_blocks("\n".join(lines))      # every cutting block carries its F


def test_posts_refuse_what_they_cannot_write():
    op = Operation("flat", SETTINGS.tool, 1000, [0, 1], [[0, 0, 5], [1, 0, -1]], [np.nan, 500])
    with pytest.raises(PostError, match="C positions"):
        LinuxCNCRotaryPost().to_text(Program("p", [op]))
    positive = op.replace(rotary={"c": [0.0, 0.0]})
    with pytest.raises(PostError, match="negative side"):
        LinuxCNCRotaryPost().to_text(Program("p", [positive]))
    with pytest.raises(PostError, match="unknown post .heidenhain.; choose one of linuxcnc, fanuc"):
        rotary_post("heidenhain")


# ----------------------------------------------------------------------------------------
# Bad input
# ----------------------------------------------------------------------------------------

GOOD = rectangle(0.0, 20.0, 30.0, 20.0)


@pytest.mark.parametrize("pocket, settings, message", [
    (Pocket("open", GOOD[:2], 5.0), SETTINGS, "fewer than 3"),
    (Pocket("flat line", [[0, 0], [10, 0], [20, 0]], 5.0), SETTINGS, "no area"),
    (Pocket("nan", np.vstack([GOOD[:3], [[np.nan, 1.0]]]), 5.0), SETTINGS, "non-finite"),
    (Pocket("bow tie", [[0, 10], [20, 30], [20, 10], [0, 30], [-5, 20]], 5.0), SETTINGS, "crosses itself"),
    (Pocket("tiny", rectangle(10, 10, 5, 5), 3.0), SETTINGS, "does not fit"),
    (Pocket("closed in", GOOD, 20.0, wall_angle_deg=40.0), RotarySettings(tool=Tool(1, "ball", 6.0, flute_length=30)),
     "does not fit"),
    (Pocket("deep", GOOD, 26.0), RotarySettings(), "flute length"),
    (Pocket("nan depth", GOOD, float("nan")), SETTINGS, "finite"),
    (Pocket("zero depth", GOOD, 0.0), SETTINGS, "greater than zero"),
    (Pocket("through", GOOD, 30.0), RotarySettings(tool=Tool(1, "ball", 6.0, flute_length=40)), "through"),
    (Pocket("overhang", GOOD, 5.0, wall_angle_deg=-5), SETTINGS, "wall angle"),
    (Pocket("lathe", GOOD, 5.0, bottom="cone"), SETTINGS, "bottom"),
    (Pocket("small sphere", GOOD, 5.0, bottom="sphere", sphere_radius=10.0), SETTINGS, "smaller than the opening"),
    (Pocket("no sphere", GOOD, 5.0, bottom="sphere"), SETTINGS, "sphere radius"),
    (Pocket("slanted bowl", GOOD, 5.0, 10.0, bottom="sphere", sphere_radius=60.0), SETTINGS, "vertical rim"),
    (Pocket("outside", rectangle(50, 0, 20, 20), 5.0), SETTINGS, "outside"),
    (Pocket("fine", GOOD, 5.0), RotarySettings(spacing=0.0), "spacing"),
    (Pocket("fine", GOOD, 5.0), RotarySettings(spacing=-1.0), "spacing"),
    (Pocket("fine", GOOD, 5.0), RotarySettings(spacing=float("nan")), "spacing"),
    (Pocket("fine", GOOD, 5.0), RotarySettings(stepover=7.0), "wider than"),
    (Pocket("fine", GOOD, 5.0), RotarySettings(step_down=0.0), "step down"),
    (Pocket("fine", GOOD, 5.0), RotarySettings(cutting_speed=float("inf")), "cutting speed"),
    (Pocket("fine", GOOD, 5.0), RotarySettings(tool=Tool(1, "flat", 6.0)), "ball-nose"),
    (Pocket("fine", GOOD, 5.0), RotarySettings(clearance_z=-1.0), "clearance"),
])
def test_bad_input_raises_rotary_error(pocket, settings, message):
    with pytest.raises(RotaryError, match=message):
        rotary.plan(Block(), [pocket], settings)


def test_bad_job_raises_rotary_error():
    with pytest.raises(RotaryError, match="no pockets"):
        rotary.plan(Block(), [])
    with pytest.raises(RotaryError, match="overlap"):
        rotary.plan(Block(), [Pocket("a", GOOD, 5.0), Pocket("b", GOOD + 5, 5.0)])
    with pytest.raises(RotaryError, match="unique"):
        rotary.plan(Block(), [Pocket("a", GOOD, 5.0), Pocket("a", GOOD - 40, 5.0)])
    with pytest.raises(RotaryError, match="board"):
        rotary.plan(Block(105, float("nan"), 30), [Pocket("a", GOOD, 5.0)])
    assert issubclass(RotaryError, ValueError)


def test_board_sizes_read_from_blender_are_named_as_typed():
    """A board read from a scene in single precision (140.00000664964318 x 90.00000427477062 mm)
    is named 140 x 90 in the message, as the user typed it."""
    wide = GOOD * 3
    with pytest.raises(RotaryError, match=r"outside the 140 x 90 mm board"):
        rotary.plan(Block(140.00000664964318, 90.00000427477062, 30.000001), [Pocket("wide", wide, 5.0)])
    with pytest.raises(RotaryError, match=r"depth 30 mm goes through the 30 mm board"):
        rotary.plan(Block(140.00000664964318, 90.00000427477062, 30.000001), [Pocket("deep", GOOD, 30.000001)])
