"""W6: the manifold engine's swept solids (toolpath/simulate/sweep.py) against closed forms and against the
true sweep of the tool, point by point."""
import math

import numpy as np
import pytest
from manifold3d import CrossSection, Manifold, OpType

from kezuri.toolpath import simulate as sim
from sweep_checks import depth_outside_ball_sweep, surface_samples
from kezuri.toolpath.simulate import sweep
from kezuri.toolpath.simulate.paths import Chain
from kezuri.toolpath.simulate.stock import stock_solid
from kezuri.toolpath.ir.program import FEED, Operation, Tool

BALL6 = Tool(2, "ball", 6.0)
FLAT6 = Tool(1, "flat", 6.0)
BOX = (-30, -30, -20, 30, 30, 0)


def chain(tool, points, radial=False):
    return Chain(0, tool, np.asarray(points, float), np.zeros(len(points) - 1, int),
                      np.zeros(len(points) - 1, bool), np.zeros(len(points) - 1, bool), radial)


def level_op(tool, points, name="op"):
    points = np.asarray(points, float)
    n = len(points) - 1
    return Operation(name, tool, 10000, np.full(n, FEED), points[1:], np.full(n, 500.0), start=points[0])


def circle(radius, z, n=400, turns=1.0):
    angle = np.linspace(0, 2 * math.pi * turns, n + 1)
    return np.column_stack([radius * np.cos(angle), radius * np.sin(angle), np.full(n + 1, z)])


def pieces_of(tool, points, tolerance=0.01, stock=None, radial=False):
    """The solids one chain is cut as, its level runs included."""
    stock = stock or stock_solid(sim.as_stock(BOX), tolerance)
    repeats = sweep.Repeats()
    makers = sweep._chain_pieces(chain(tool, points, radial=radial), tolerance, stock.bounding_box(),
                                 sweep.Floors([], tolerance), repeats)
    return [make() for make in makers + [m for made in repeats.kept() for m in made]]


def assert_the_ball_sweep(pieces, tips, tolerance, shank):
    """The 6 mm ball's pieces along the level ``tips``: every sampled surface point below the stock
    top within the engine's allowance of the exact sweep, and the sweep of the tool shrunk by the
    tolerance (exact hulls per move, its shank ``shank`` mm long) held inside them."""
    swept = Manifold.batch_boolean(pieces, OpType.Add)
    samples = surface_samples(swept)
    assert depth_outside_ball_sweep(samples[samples[:, 2] < BOX[5]], tips, 3.0).max() < sweep.outside(BALL6, tolerance) + 1e-6
    shrunk = sweep.tool_points(BALL6, 0.005, shank, inset=tolerance)
    inner = Manifold.batch_boolean([Manifold.hull_points(sweep.placed(shrunk, tips[k:k + 2], None))
                                    for k in range(len(tips) - 1)], OpType.Add)
    stock = stock_solid(sim.as_stock(BOX), tolerance)
    assert ((inner ^ stock) - swept).volume() < 1e-6


def test_ball_along_a_level_circle_is_pappus_of_its_section():
    # tip 2 mm deep on a 15 mm circle: the section in the stock is a circular segment of the ball
    r, depth, radius = 3.0, 2.0, 15.0
    op = level_op(BALL6, circle(radius, -depth, n=300))
    result = sim.simulate(op, BOX, engine="manifold", tolerance=0.01)
    segment = r * r * math.acos((r - depth) / r) - (r - depth) * math.sqrt(2 * r * depth - depth * depth)
    expected = 2 * math.pi * radius * segment
    assert result.removed_volume_mm3 <= expected * 1.001            # always material left
    assert result.removed_volume_mm3 == pytest.approx(expected, rel=0.01)


def ball_slot_volume(length, r, depth):
    """A straight ball-end slot cut ``depth`` deep (tip), ball centres ``length`` apart: the
    section (circular segment of the ball, and below the top the shank's rectangle when the
    centre is below it) times the length, plus the ball's ends (a spherical cap, or a half ball
    and the shank's cylinder)."""
    if depth <= r:
        h = r - depth
        segment = r * r * math.acos(h / r) - h * math.sqrt(r * r - h * h)
        return length * segment + math.pi * depth * depth * (3 * r - depth) / 3
    return (length * (math.pi * r * r / 2 + 2 * r * (depth - r))
            + 2 * math.pi * r ** 3 / 3 + math.pi * r * r * (depth - r))


@pytest.mark.parametrize("depth", [1.0, 3.0, 5.0])
@pytest.mark.parametrize("moves", [1, 4, 40])
def test_a_straight_ball_slot_is_its_closed_form_within_a_thousandth(depth, moves):
    # (it read 0.4 - 1.6 % low: inscribed polygons, and a tube's section shrunk to leave room
    # to thin a path that here needs none)
    tips = np.column_stack([np.linspace(-20, 20, moves + 1), np.zeros(moves + 1), np.full(moves + 1, -depth)])
    result = sim.simulate(level_op(BALL6, tips), BOX, engine="manifold")       # the default tolerance
    assert result.removed_volume_mm3 == pytest.approx(ball_slot_volume(40.0, 3.0, depth), rel=1e-3)


def test_every_piece_of_a_level_run_lies_within_its_bound_of_the_true_sweep():
    # a wave with a sharp corner in it: tubes, a corner wedge and the two end wedges
    x = np.linspace(-20, 0, 81)
    wave = np.column_stack([x, 3 * np.sin(x / 4), np.full_like(x, -2.0)])
    leg = np.column_stack([np.zeros(40), np.linspace(0, 15, 41)[1:], np.full(40, -2.0)])
    tips = np.vstack([wave, leg])
    pieces = pieces_of(BALL6, tips)
    assert len(pieces) < 20                   # tubes and wedges, not one hull per move
    vertices = np.vstack([np.asarray(p.to_mesh().vert_properties)[:, :3] for p in pieces])
    assert depth_outside_ball_sweep(vertices, tips, 3.0).max() < sweep.outside(BALL6, 0.01) + 1e-6
    # and together they fill it: the removed volume is the height field's (an independent method)
    stock = stock_solid(sim.as_stock(BOX), 0.01)
    removed = stock.volume() - (stock - Manifold.batch_boolean(pieces, OpType.Add)).volume()
    field = sim.simulate(level_op(BALL6, tips), BOX, cell=0.05)
    assert removed <= field.removed_volume_mm3 * 1.002
    assert removed == pytest.approx(field.removed_volume_mm3, rel=0.01)


@pytest.mark.parametrize("corners", [False, True])
def test_a_level_path_with_bends_corners_and_a_reversal_is_within_the_tolerance_of_its_sweep(corners):
    # a 5 mm circle in 1.2 mm chords (each vertex bends 14 degrees: on a level path the joints
    # may take half the tolerance, so the tubes run through the bends); or twice round it, then a
    # reversal, a square corner and a reversal: the pieces lie inside the exact sweep, and
    # contain the sweep of the tool shrunk by the tolerance, point for point (no fin of stock is
    # left standing where tubes meet)
    tolerance = 0.05
    if corners:
        corner = [[5.0, -4.0, -2.0], [9.0, -4.0, -2.0], [6.0, -4.0, -2.0]]
        tips = np.vstack([circle(5.0, -2.0, n=52, turns=2.0), corner])
    else:
        tips = circle(5.0, -2.0, n=26)
    pieces = pieces_of(BALL6, tips, tolerance=tolerance)
    assert len(pieces) <= (31 if corners else 16)    # tubes (breaking every 60 degrees), not hulls
    assert_the_ball_sweep(pieces, tips, tolerance, 5.0)


def test_a_layer_wholly_inside_a_deeper_ones_footprint_is_left_out():
    # flat 6 mm: three rings 6, 8, 10 at -5 clear the annulus 3..13 to the floor; a ring of 8 at -1
    # lies inside it, so it adds nothing
    deep = [circle(radius, -5.0) for radius in (6.0, 8.0, 10.0)]
    shallow = circle(8.0, -1.0)
    floors = sweep.Floors(sweep.level_runs([chain(FLAT6, ring) for ring in deep]), 0.05)
    assert floors.needed(shallow, FLAT6.radius) == []
    assert floors.needed(circle(12.0, -1.0), FLAT6.radius) == [(0, 400)]      # pokes out: kept
    ops = [level_op(FLAT6, ring, f"ring {i}") for i, ring in enumerate(deep + [shallow])]
    result = sim.simulate(ops, BOX, engine="manifold", tolerance=0.01)
    assert result.removed_volume_mm3 == pytest.approx(math.pi * (13 ** 2 - 3 ** 2) * 5.0, rel=0.01)


def test_a_staircase_of_short_moves_is_cut_as_hulls():
    steps = [[-10.0 + 0.5 * (k // 2 + k % 2), 0.5 * (k // 2), -1.0] for k in range(40)]
    steps = np.asarray(steps)
    section = sweep._section(sweep.tool_rings(BALL6, 0.025), 3.0, 5.0)
    assert sweep._tube_pieces(steps, section, 0.05) is None
    field, exact = (sim.simulate(level_op(BALL6, steps), BOX, engine=engine, tolerance=0.01, cell=0.05)
                    for engine in ("heightfield", "manifold"))
    assert exact.removed_volume_mm3 == pytest.approx(field.removed_volume_mm3, rel=0.01)


def test_a_level_staircase_on_a_grid_is_cut_along_its_rows():
    # eight diagonal stairs of 0.5 mm cells side by side, walked up and down (as the turn-mill
    # axial grid passes step): the rows across the stairs become one hull each, and every piece
    # still lies inside the exact sweep and fills it
    points = []
    for k in range(8):
        stair = [(0.5 * (k + m + s), 0.5 * m) for m in range(12) for s in (0, 1)]
        points += stair[::-1] if k % 2 else stair
    tips = np.array([(x - 6.0, y - 3.0, -1.0) for x, y in points])
    pieces = pieces_of(BALL6, tips, tolerance=0.05)
    assert len(pieces) < (len(tips) - 1) / 3
    for piece in pieces:
        assert depth_outside_ball_sweep(surface_samples(piece), tips, 3.0).max() < sweep.outside(BALL6, 0.05) + 1e-6
    stock = stock_solid(sim.as_stock(BOX), 0.05)
    removed = stock.volume() - (stock - Manifold.batch_boolean(pieces, OpType.Add)).volume()
    # a cut 1 mm deep is mostly surface: bound it between the height fields of the true ball and
    # of the ball shrunk by the tolerance (its sweep is the true sweep shrunk by the tolerance)
    field = sim.simulate(level_op(BALL6, tips), BOX, cell=0.05)
    shrunk = sim.simulate(level_op(Tool(2, "ball", 6.0 - 2 * 0.05), tips + [0, 0, 0.05]), BOX, cell=0.05)
    assert shrunk.removed_volume_mm3 < removed <= field.removed_volume_mm3 * 1.002


def grid_pocket_with_wall_arcs(overshoot, radius=4.5, cell=0.5, z=-1.0):
    """Level tips of a grid pocket in a circle (rows 0.5 mm apart, walked back and forth) that
    follows the wall between rows, as the turn-mill axial passes do: out to the wall, along it
    ``overshoot`` radians past the next row, back, and in to the next row."""
    tips = []
    previous = None
    for k, y in enumerate(np.arange(-8, 9) * cell):
        end = math.floor(math.sqrt(radius ** 2 - y ** 2) / cell) * cell
        xs = np.arange(-end, end + cell / 2, cell)[::(-1) ** k]
        start = math.atan2(y, xs[0])
        if previous is not None:
            ahead = np.sign(y) * (1 if math.cos(start) > 0 else -1)     # round the wall, away from the rows
            far = start + ahead * overshoot
            out = np.linspace(previous, far, max(2, int(abs(far - previous) / 0.02)))
            back = np.linspace(far, start, max(2, int(abs(far - start) / 0.02)))[1:]
            tips += [(radius * math.cos(a), radius * math.sin(a)) for a in np.concatenate([out, back])]
        tips += [(x, y) for x in xs]
        previous = math.atan2(y, xs[-1])
    tips = np.array([(x, y, z) for x, y in tips])
    return tips[np.concatenate([[True], np.any(np.abs(np.diff(tips, axis=0)) > 1e-9, axis=1)])]


def test_a_staircase_that_runs_back_along_its_wall_cuts_the_wall_once():
    # the same pocket with the wall arcs walked out and back: the way back lies on ground the
    # way out holds, so it adds almost no pieces; the pieces stay inside the exact sweep and fill
    # it to within the tolerance
    direct, doubled = grid_pocket_with_wall_arcs(0.0), grid_pocket_with_wall_arcs(0.3)
    pieces = pieces_of(BALL6, doubled, tolerance=0.05)
    extra_pieces = len(pieces) - len(pieces_of(BALL6, direct, tolerance=0.05))
    assert extra_pieces < (len(doubled) - len(direct)) / 10      # 300 more moves
    swept = Manifold.batch_boolean(pieces, OpType.Add)
    samples = surface_samples(swept, per_triangle=1)
    beyond = depth_outside_ball_sweep(samples[samples[:, 2] < BOX[5]], doubled, 3.0).max()   # in the stock
    assert beyond < sweep.outside(BALL6, 0.05) + 1e-6
    stock = stock_solid(sim.as_stock(BOX), 0.05)
    removed = stock.volume() - (stock - swept).volume()
    field = sim.simulate(level_op(BALL6, doubled), BOX, cell=0.05)
    shrunk = sim.simulate(level_op(Tool(2, "ball", 6.0 - 2 * 0.05), doubled + [0, 0, 0.05]), BOX, cell=0.05)
    assert shrunk.removed_volume_mm3 < removed <= field.removed_volume_mm3 * 1.002


def test_a_gentle_ramp_is_one_run_of_tubes_and_matches_the_height_field():
    # a ball spiralling down 1 mm per turn (about 0.6 degrees): within the slope allowance
    turns = np.linspace(0, 2, 801)
    tips = np.column_stack([15 * np.cos(2 * math.pi * turns), 15 * np.sin(2 * math.pi * turns), -1.0 - turns])
    assert sweep._gentle_runs(tips, sweep._max_slope(BALL6, 0.05 / 4)) == [(0, 800)]
    field, exact = (sim.simulate(level_op(BALL6, tips), BOX, engine=engine, tolerance=0.01, cell=0.05)
                    for engine in ("heightfield", "manifold"))
    assert exact.removed_volume_mm3 == pytest.approx(field.removed_volume_mm3, rel=0.01)


def radial_groove_volume(r, tip, bar):
    """A radial ball's full turn about C at tip radius ``tip`` on a bar: Pappus on the ball's inner
    half disc (centroid 4r/3pi nearer the axis than its centre) and the shank's band from the
    centre out to the bar's surface."""
    centre = tip + r
    half_disc = math.pi * r * r / 2 * 2 * math.pi * (centre - 4 * r / (3 * math.pi))
    band = 2 * r * math.pi * (bar ** 2 - centre ** 2)
    return half_disc + band


def test_a_radial_ball_turning_about_c_is_pappus_of_its_section():
    # radial ball, tip at radius 20 on a bar of radius 25, a full turn at z = -10
    r, tip, bar = 3.0, 20.0, 25.0
    angle = np.linspace(0, 2 * math.pi, 721)
    tips = np.column_stack([tip * np.cos(angle), tip * np.sin(angle), np.full(721, -10.0)])
    stock = stock_solid(sim.CylinderStock(radius=bar, height=30), 0.05)
    pieces = pieces_of(BALL6, tips, 0.05, stock, radial=True)
    assert len(pieces) <= 4                    # one tube and the tool at its ends
    removed = stock.volume() - (stock - Manifold.batch_boolean(pieces, OpType.Add)).volume()
    expected = radial_groove_volume(r, tip, bar)
    assert removed <= expected * 1.001
    assert removed == pytest.approx(expected, rel=0.01)


def test_a_ring_repeated_farther_from_the_c_axis_is_left_out():
    # roughing a groove ring by ring, 24 -> 20 at z = -10, and a half turn at 22 (which the full
    # ring at 20 covers): only the ring at 20 is cut, and the groove is its Pappus volume; a half
    # turn at 18 covers nothing and is kept
    angle = np.linspace(0, 2 * math.pi, 721)

    def ring(tip, turns=1.0, z=-10.0):
        a = angle * turns
        return np.column_stack([tip * np.cos(a), tip * np.sin(a), np.full(len(a), z)])

    stock = stock_solid(sim.CylinderStock(radius=25.0, height=30), 0.05)
    rings = [ring(24.0), ring(22.0, turns=0.5), ring(22.0), ring(20.0)]
    repeats = sweep.Repeats()
    for tips in rings + [ring(18.0, turns=0.5)]:
        assert sweep._chain_pieces(chain(BALL6, tips, radial=True), 0.05, stock.bounding_box(),
                                   sweep.Floors([], 0.05), repeats) == []
    assert len(repeats.kept()) == 2
    solid = sweep.cut(stock, [chain(BALL6, tips, radial=True) for tips in rings], 0.05)
    expected = radial_groove_volume(3.0, 20.0, 25.0)
    assert stock.volume() - solid.volume() == pytest.approx(expected, rel=0.01)
    assert stock.volume() - solid.volume() <= expected * 1.001


def test_a_slot_repeated_at_every_depth_is_cut_once_at_the_bottom():
    # a flat 6 mm slot 20 mm long, in four moves, at -1, -2 and -3 mm (a pocket with vertical
    # walls repeats its path at every depth): only the pass at -3 is cut, and the slot is
    # (L D + pi D^2 / 4) * depth
    line = np.column_stack([np.linspace(-10, 10, 5), np.zeros(5), np.zeros(5)])
    passes = [line + [0, 0, -depth] for depth in (1.0, 2.0, 3.0)]
    stock = stock_solid(sim.as_stock(BOX), 0.01)
    repeats = sweep.Repeats()
    for tips in passes:
        sweep._chain_pieces(chain(FLAT6, tips), 0.01, stock.bounding_box(), sweep.Floors([], 0.01), repeats)
    assert len(repeats.kept()) == 1
    result = sim.simulate([level_op(FLAT6, tips, f"pass {k}") for k, tips in enumerate(passes)], BOX,
                          engine="manifold", tolerance=0.01)
    expected = (20 * 6 + math.pi * 36 / 4) * 3
    assert result.removed_volume_mm3 == pytest.approx(expected, rel=0.01)
    assert result.removed_volume_mm3 <= expected * 1.001


def test_pocket_layers_on_the_side_of_a_bar_leave_out_the_ones_a_deeper_layer_covers():
    # a radial ball cutting a flat-floored pocket into the side of a bar: straight chords at
    # x = 22 (y +-8), 21 (y +-6) and 20 (y +-7), all at z = -15.  The chord at 20 lies nearer the
    # C axis than the one at 21 along every ray the latter crosses; the chord at 22 reaches
    # further round than the one at 20 and is kept.  Volumes: the radius map, an independent engine.
    from kezuri.toolpath.operations.turnmill import turnmill
    from kezuri.toolpath.ir.program import RAPID

    def chord(x, half_width, n=40):
        y = np.linspace(-half_width, half_width, n + 1)
        return np.column_stack([np.full(n + 1, x), y, np.full(n + 1, -15.0)])

    chords = [chord(22.0, 8.0), chord(21.0, 6.0), chord(20.0, 7.0)]
    repeats = sweep.Repeats()
    stock = stock_solid(sim.CylinderStock(radius=25.0, height=30), 0.05)
    for tips in chords:
        assert sweep._chain_pieces(chain(BALL6, tips, radial=True), 0.05, stock.bounding_box(),
                                   sweep.Floors([], 0.05), repeats) == []
    assert len(repeats.kept()) == 2

    def radial_op(tips, name):
        # in at the first point, along the chord, out: (X, Z, C) machine moves of a radial ball
        reach, angle = np.hypot(tips[:, 0], tips[:, 1]), np.degrees(np.arctan2(tips[:, 1], tips[:, 0]))
        x = np.concatenate([reach, [30.0]])
        c = np.concatenate([angle, angle[-1:]])
        kind = np.full(len(x), FEED)
        kind[-1] = RAPID
        xyz = np.column_stack([x, np.zeros(len(x)), np.full(len(x), -15.0)])
        return turnmill.TurnMillOperation(name, BALL6, 3000.0, kind, xyz, np.where(kind == RAPID, np.nan, 300.0),
                                          rotary={"c": c}, clearance_z=5.0, safe_z=5.0,
                                          start=np.array([30.0, 0.0, -15.0]), direction="radial")

    ops = [radial_op(tips, f"layer {k}") for k, tips in enumerate(chords)]
    bar = turnmill.Stock(25.0, -30.0, 0.0)
    field, exact = (sim.simulate(ops, bar, engine=engine, cell=0.05, tolerance=0.02)
                    for engine in ("heightfield", "manifold"))
    assert field.engine == "radiusmap"
    assert exact.removed_volume_mm3 == pytest.approx(field.removed_volume_mm3, rel=0.01)


def square_loop(side, z, step=1.0):
    """The square of this side about the origin, from (-side/2, -side/2) anticlockwise, in moves of ``step``."""
    h = side / 2
    corners = np.array([[-h, -h], [h, -h], [h, h], [-h, h], [-h, -h]])
    points = [corners[0]]
    for a, b in zip(corners[:-1], corners[1:]):
        n = int(round(np.linalg.norm(b - a) / step))
        points += [a + (b - a) * k / n for k in range(1, n + 1)]
    points = np.array(points)
    return np.column_stack([points, np.full(len(points), z)])


def test_a_ramp_entry_along_the_contour_it_then_cuts_deeper_adds_no_pieces():
    # a flat 6 mm ramps down at 3 degrees along a 20 mm square from the top to -2 mm, then cuts
    # the whole square at -2 (ending where its ramp ended): the ramp lies over the contour, on the
    # same vertical lines, so only its first and last move are cut (they hold the tool at the
    # ends); the groove is the square ring with round outer corners, 2 deep:
    # ((L + 2r)^2 - (4 - pi) r^2 - (L - 2r)^2) * 2
    loop = square_loop(20.0, -2.0)[:-1]
    ramp_moves = int(math.ceil(2.0 / math.tan(math.radians(3.0))))       # 1 mm moves
    ramp = np.vstack([loop, loop])[:ramp_moves + 1].copy()
    ramp[:, 2] = np.linspace(0.0, -2.0, ramp_moves + 1)
    contour = np.vstack([loop, loop])[ramp_moves:ramp_moves + len(loop) + 1]
    paths = sweep.LevelPaths()
    paths.add(FLAT6, contour)
    assert paths.covered(FLAT6, ramp).all()
    assert paths.needed(FLAT6, ramp) == [(0, 1), (ramp_moves - 1, ramp_moves)]
    assert not paths.covered(BALL6, ramp).any()                       # another tool: not held
    assert not paths.covered(FLAT6, ramp - [0, 0, 2.5]).any()          # below the contour: not held
    tips = np.vstack([ramp, contour[1:]])
    result = sim.simulate([level_op(FLAT6, tips)], BOX, engine="manifold", tolerance=0.01)
    expected = (26.0 ** 2 - (4 - math.pi) * 9.0 - 14.0 ** 2) * 2.0
    # material left only, at most the tolerance deep over both walls (outer 4 L + 2 pi r, inner 4 (L - 2r))
    walls = (4 * 20.0 + 2 * math.pi * 3.0 + 4 * 14.0) * 2.0
    assert expected - 0.01 * walls <= result.removed_volume_mm3 <= expected * 1.001


def test_a_flat_end_mills_level_run_is_one_prism_at_its_closed_form():
    # a flat 6 mm round a 10 mm circle 2 mm deep, in 400 chords: the shank's sweep is the path
    # offset by r, a prism; its facets lie inside within a quarter of the tolerance, so the groove
    # pi ((R + r)^2 - (R - r)^2) d is met from below within a thousandth (chords and facets)
    tips = circle(10.0, -2.0)
    pieces = pieces_of(FLAT6, tips, tolerance=0.01)
    assert len(pieces) == 1
    lo, hi = np.split(np.asarray(pieces[0].bounding_box()), 2)
    assert lo[2] == pytest.approx(-2.0) and hi[2] > BOX[5] and hi[0] == pytest.approx(13.0, abs=1e-3)
    result = sim.simulate(level_op(FLAT6, tips), BOX, engine="manifold", tolerance=0.01)
    expected = math.pi * (13.0 ** 2 - 7.0 ** 2) * 2.0
    assert expected * 0.999 < result.removed_volume_mm3 <= expected


def test_a_flat_end_mills_jagged_level_run_is_its_exact_sweep():
    # the staircase that other tools cut as hulls: for a flat end mill the prism is exact, so the
    # cut is the stairs' 2-D offset (an independent Clipper offset of each move's stadium) times
    # the depth, within the facets
    steps = np.asarray([[-10.0 + 0.5 * (k // 2 + k % 2), 0.5 * (k // 2), -1.5] for k in range(40)])
    pieces = pieces_of(FLAT6, steps, tolerance=0.01)
    assert len(pieces) == 1
    stadiums = [CrossSection.circle(3.0, 720).translate(list(a[:2])) + CrossSection.circle(3.0, 720).translate(list(b[:2]))
                for a, b in zip(steps[:-1], steps[1:])]
    hulls = CrossSection.batch_boolean([CrossSection.batch_hull([s]) for s in stadiums], OpType.Add)
    result = sim.simulate(level_op(FLAT6, steps), BOX, engine="manifold", tolerance=0.01)
    expected = hulls.area() * 1.5
    assert expected * 0.999 < result.removed_volume_mm3 <= expected * 1.0001


def test_a_ball_level_run_carries_its_end_in_tubes_and_its_shank_in_a_prism():
    # the tubes stop SHANK_OVERLAP (and a lift under half a millimetre) above the ball's equator;
    # one prism reaches from inside them to above the stock; together they lie inside the exact
    # sweep and hold the sweep of the tool shrunk by the tolerance
    tolerance = 0.05
    tips = circle(8.0, -4.0, n=120)
    pieces = pieces_of(BALL6, tips, tolerance=tolerance)
    tops = sorted(p.bounding_box()[5] for p in pieces)
    assert tops[-1] > BOX[5] and tops[-2] < -4.0 + 3.0 + sweep.SHANK_OVERLAP + 0.5 + 1e-9
    assert_the_ball_sweep(pieces, tips, tolerance, 8.0)


def test_the_moves_of_a_layer_that_a_deeper_layer_repeats_are_left_out():
    # a ball runs a 20 mm square at -3, then at -1.5 the same square with a detour out to the
    # side along one edge: only the detour is cut at -1.5 (its ends held by the deeper square),
    # and the cut is the same as with every move swept
    deep = square_loop(20.0, -3.0)
    loop = square_loop(20.0, -1.5)
    detour = np.array([[-2.0, -10.0], [-2.0, -14.0], [2.0, -14.0], [2.0, -10.0]])
    k = int(np.flatnonzero(np.all(np.isclose(loop[:, :2], [-2.0, -10.0]), axis=1))[0])
    upper = np.vstack([loop[:k], np.column_stack([detour, np.full(4, -1.5)]),
                       loop[np.flatnonzero(np.all(np.isclose(loop[:, :2], [2.0, -10.0]), axis=1))[0] + 1:]])
    paths = sweep.LevelPaths()
    paths.add(BALL6, deep)
    paths.add(BALL6, upper)
    assert paths.not_held_below(BALL6, upper) == [(k, k + 3)]
    assert paths.not_held_below(BALL6, deep) == [(0, len(deep) - 1)]          # never held by itself
    ops = [level_op(BALL6, deep, "deep"), level_op(BALL6, upper, "upper")]
    result = sim.simulate(ops, BOX, engine="manifold", tolerance=0.01)
    kept = sweep.LevelPaths.not_held_below
    try:
        sweep.LevelPaths.not_held_below = lambda self, tool, run: [(0, len(run) - 1)]
        every = sim.simulate(ops, BOX, engine="manifold", tolerance=0.01)
    finally:
        sweep.LevelPaths.not_held_below = kept
    assert result.removed_volume_mm3 == pytest.approx(every.removed_volume_mm3, rel=1e-4)
    field = sim.simulate(ops, BOX, cell=0.05)
    assert result.removed_volume_mm3 == pytest.approx(field.removed_volume_mm3, rel=0.01)


def test_shanks_at_one_height_are_one_prism_and_the_rings_cut_their_closed_form():
    # three overlapping rings of a flat 6 mm at -2 (footprints 3..9, 7..13, 11..17 mm round the
    # origin) and one at -1: two prisms, one per height; the -2 rings cut the annulus 3..17
    # (the -1 ring lies inside it and adds nothing)
    rings = [circle(radius, -2.0) for radius in (6.0, 10.0, 14.0)] + [circle(10.0, -1.0)]
    shanks = sweep.Shanks(0.01)
    for ring in rings:
        shanks.add(ring, 3.0, float(ring[0, 2]))
    prisms = [make() for make in shanks.pieces(BOX[5])]
    assert sorted(round(p.bounding_box()[2], 9) for p in prisms) == [-2.0, -1.0]
    ops = [level_op(FLAT6, ring, f"ring {k}") for k, ring in enumerate(rings)]
    result = sim.simulate(ops, (-40, -40, -20, 40, 40, 0), engine="manifold", tolerance=0.01)
    expected = math.pi * (17.0 ** 2 - 3.0 ** 2) * 2.0
    assert expected * 0.999 < result.removed_volume_mm3 <= expected
