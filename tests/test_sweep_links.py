"""W6: the manifold engine's links between runs (toolpath/simulate/sweep.py): hulls of plunges and
ramps over ground deeper level runs cleared are left out (Floors.holds), so are moves another move
holds from below (a zigzag ramp's legs: repeats.without_repeated_moves), and moves of a few 1e-7 mm
(noise between two arcs) no longer split a level run (paths.without_short_moves).  What is left out
is checked against closed forms, the height field, and the sweep of the shrunk tool."""
import math

import numpy as np
import pytest

from manifold3d import Manifold, OpType

from kezuri.toolpath import simulate as sim
from kezuri.toolpath.ir.program import FEED, Operation, Tool
from kezuri.toolpath.simulate import sweep
from kezuri.toolpath.simulate.paths import Chain, without_short_moves
from kezuri.toolpath.simulate.stock import stock_solid

FLAT6 = Tool(1, "flat", 6.0)
BOX = (-30, -30, -20, 30, 30, 0)


def chain(tool, points):
    return Chain(0, tool, np.asarray(points, float), np.zeros(len(points) - 1, int),
                 np.zeros(len(points) - 1, bool), np.zeros(len(points) - 1, bool))


def op(points, name="op"):
    points = np.asarray(points, float)
    n = len(points) - 1
    return Operation(name, FLAT6, 10000, np.full(n, FEED), points[1:], np.full(n, 500.0), start=points[0])


def zigzag(z):
    """Rows y = -6, -3, 0, 3, 6 from x = -10 to 10, joined at alternate ends, at height z: a flat
    6 mm clears the rectangle [-13, 13] x [-9, 9] with corners rounded by 3 mm and a notch on
    each side where two rows end unjoined (see POCKET_AREA)."""
    points = []
    for k, y in enumerate((-6.0, -3.0, 0.0, 3.0, 6.0)):
        xs = np.linspace(-10, 10, 21) * (1 if k % 2 == 0 else -1)
        points += [[x, y, z] for x in xs]
    return np.array(points)


# each rounded corner leaves 9 - 9 pi / 4; each notch (3 mm deep, between two circles of 3 mm
# 3 mm apart) leaves 2 * integral over 0..1.5 of (3 - sqrt(9 - y^2)) dy
NOTCH = 2 * (4.5 - (1.5 * math.sqrt(6.75) + 9 * math.asin(0.5)) / 2)
POCKET_AREA = 26 * 18 - 4 * (9 - 9 * math.pi / 4) - 4 * NOTCH


def test_a_ramp_over_a_deeper_layers_floor_is_held_and_one_beside_it_is_not():
    deep = zigzag(-3.0)
    floors = sweep.Floors(sweep.level_runs([chain(FLAT6, deep)]), 0.05)
    inside = np.array([[-5.0, 0.0, 0.0], [5.0, 0.0, -1.5]])
    assert floors.holds(inside, 3.0)
    # the tool's circle at x = 10 + 0.1 pokes 0.1 mm out of the cleared end (x = 13)
    assert not floors.holds(np.array([[0.0, 0.0, 0.0], [10.1, 0.0, -1.5]]), 3.0)
    # nothing is cleared below the deep layer itself, nor below a point under it
    assert not floors.holds(inside - [0, 0, 1.5], 3.0)
    # a plunge straight down over the floor: the tool's circle
    assert floors.holds(np.array([[0.0, 0.0, 5.0], [0.0, 0.0, -1.0]]), 3.0)
    assert not floors.holds(np.array([[0.0, 7.0, 5.0], [0.0, 7.0, -1.0]]), 3.0)


def test_a_pocket_entered_by_ramps_over_its_floor_cuts_its_closed_form_without_the_ramps():
    # the upper layer at -1.5, ramped into over the middle; the lower at -3, entered by a plunge
    # beside the pocket (so it is cut): the ramp adds no piece, and the pocket is its closed form
    upper = np.vstack([[[-5.0, 0.0, 5.0], [-5.0, 0.0, 0.0], [5.0, 0.0, -1.5]], zigzag(-1.5)])
    lower = np.vstack([[[-10.0, -6.0, 5.0]], zigzag(-3.0)])
    chains = [chain(FLAT6, upper), chain(FLAT6, lower)]
    stock = stock_solid(sim.as_stock(BOX), 0.05)
    floors = sweep.Floors(sweep.level_runs(chains), 0.05)
    ramp = upper[:3]
    with_floors = sweep._hull_pieces(chains[0], ramp, None, sweep.tool_points(FLAT6, 0.05, 10.0), 10.0, 0.05,
                                     stock.bounding_box(), floors)
    without = sweep._hull_pieces(chains[0], ramp, None, sweep.tool_points(FLAT6, 0.05, 10.0), 10.0, 0.05,
                                 stock.bounding_box())
    # the plunge down to 0 is above the stock; the ramp lies over the floor at -3
    assert len(without) == 1 and len(with_floors) == 0
    result = sim.simulate([op(upper, "upper"), op(lower, "lower")], BOX, engine="manifold", tolerance=0.05)
    expected = POCKET_AREA * 3.0
    assert result.removed_volume_mm3 == pytest.approx(expected, rel=1e-3)
    assert result.removed_volume_mm3 <= expected * 1.001


def test_moves_of_a_few_tenths_of_a_micrometre_are_merged_into_the_next():
    rng = np.random.default_rng(3)
    path = np.cumsum(rng.normal(size=(60, 3)), axis=0)
    noisy = [path[0]]
    for point in path[1:]:
        noisy.append(point)
        for _ in range(rng.integers(0, 3)):
            noisy.append(noisy[-1] + rng.normal(size=3) * 2e-7)
    noisy = np.array(noisy)
    clean = without_short_moves(noisy, 1e-6)
    assert np.linalg.norm(np.diff(clean, axis=0), axis=1).min() >= 1e-6
    assert np.array_equal(clean[0], noisy[0]) and np.array_equal(clean[-1], noisy[-1])
    # every point left out lies within 1e-6 mm of a point kept
    distance = np.linalg.norm(noisy[:, None, :] - clean[None, :, :], axis=2).min(axis=1)
    assert distance.max() < 1e-6
    assert len(clean) == len(path)
    assert without_short_moves(path, 1e-6) is path


def test_a_level_loop_with_a_noise_move_is_one_run_and_cuts_what_the_clean_loop_cuts():
    angle = np.linspace(0, 2 * math.pi, 121)
    loop = np.column_stack([10 * np.cos(angle), 10 * np.sin(angle), np.full(121, -2.0)])
    noisy = np.insert(loop, 60, loop[60] + [1.2e-7, -0.8e-7, 0.0], axis=0)
    assert len(sweep._gentle_runs(noisy, 0.0)) == 2            # the noise move splits the loop
    assert sweep._gentle_runs(without_short_moves(noisy, sweep.SHORT_MOVE), 0.0) == [(0, 120)]
    clean, dirty = (sim.simulate(op(points), BOX, engine="manifold", tolerance=0.05).removed_volume_mm3
                    for points in (loop, noisy))
    # a 6 mm ring about r = 10: Pappus, 2 pi 10 * 6 * 2 mm deep
    assert dirty == pytest.approx(clean, rel=1e-9)
    assert clean == pytest.approx(2 * math.pi * 10 * 6 * 2, rel=2e-3)


def zigzag_ramp(legs=6, depth=3.0):
    """A flat 6 mm ramping down along y = 0 between x = -10 and 10, ``legs`` legs to ``depth``."""
    x = np.where(np.arange(legs + 1) % 2 == 0, -10.0, 10.0)
    return np.column_stack([x, np.zeros(legs + 1), -np.arange(legs + 1) * depth / legs])


def test_a_zigzag_ramp_cuts_only_its_last_leg_each_earlier_one_lies_over_a_later_one():
    from kezuri.toolpath.simulate.repeats import without_repeated_moves

    ramp = zigzag_ramp()
    # leg k (from x = +-10 at -k/2 to -(k+1)/2) lies over leg k + 2 at both ends; leg 5 over leg 6
    # (equal at x = -10, lower at 10): only the last leg is cut
    assert without_repeated_moves(ramp, [(0, 6)]) == [(5, 6)]
    # up the same legs: each leg lies over the one before it, and the first is cut
    assert without_repeated_moves(ramp[::-1].copy(), [(0, 6)]) == [(0, 1)]
    # moves outside the ranges given are neither cut nor holders
    assert without_repeated_moves(ramp, [(0, 4)]) == [(3, 4)]
    # a leg at the same heights twice: the first holds the second
    twice = np.array([[-10.0, 0, -1], [10.0, 0, -2], [-10.0, 0, -1], [10.0, 0, -2], [10.0, 0, -3]])
    assert without_repeated_moves(twice, [(0, 4)]) == [(0, 1), (3, 4)]
    # plunges and retracts on one vertical line: the one reaching lowest holds every other
    plunges = np.array([[0.0, 0, 5], [0.0, 0, -1], [0.0, 0, 5], [0.0, 0, -2], [0.0, 0, -4]])
    assert without_repeated_moves(plunges, [(0, 4)]) == [(3, 4)]
    # a holder is kept apart from the straight move after it (so it is cut as the whole tool,
    # never merged with it into a hull of a shrunk tool)
    back = np.array([[0.0, 0, 0], [10.0, 0, -1], [0.0, 0, -2], [-10.0, 0, -3]])
    assert without_repeated_moves(back, [(0, 3)]) == [(1, 2), (2, 3)]
    # nothing held: the ranges as given
    line = np.column_stack([np.linspace(0, 10, 6), np.zeros(6), -np.linspace(0, 1, 6)])
    assert without_repeated_moves(line, [(0, 2), (3, 5)]) == [(0, 2), (3, 5)]


def test_a_zigzag_ramp_into_a_slot_cuts_what_the_height_field_cuts():
    # the ramp alone: the sweep of its last leg (from -2.5 at x = -10 to -3 at 10) holds every
    # other; if it were left out, the slot would be half a millimetre shallower at one end (8 %)
    ramp = zigzag_ramp()
    stock = stock_solid(sim.as_stock(BOX), 0.05)
    floors, paths = sweep.Floors([], 0.05), sweep.LevelPaths()
    pieces = sweep._chain_pieces(chain(FLAT6, ramp), 0.05, stock.bounding_box(), floors, sweep.Repeats(), paths)
    assert len(pieces) == 1
    field, exact = (sim.simulate(op(ramp), BOX, engine=engine, tolerance=0.05, cell=0.05)
                    for engine in ("heightfield", "manifold"))
    assert exact.removed_volume_mm3 == pytest.approx(field.removed_volume_mm3, rel=0.005)
    # the slot's stadium (20 x 6 and two half discs) at least 2.5 and at most 3 mm deep
    stadium = 20 * 6 + math.pi * 9
    assert 2.5 * stadium < exact.removed_volume_mm3 < 3.0 * stadium


def shrunk_sweep(points, tolerance, shank=30.0):
    """The flat 6 mm shrunk by ``tolerance`` swept along every move (exact hulls per move)."""
    shrunk = sweep.tool_points(FLAT6, 0.005, shank, inset=tolerance)
    return Manifold.batch_boolean([Manifold.hull_points(sweep.placed(shrunk, points[k:k + 2], None))
                                   for k in range(len(points) - 1)], OpType.Add)


@pytest.mark.parametrize("case", ["zigzag", "pocket"])
def test_what_is_left_out_still_lies_in_the_cut(case):
    # the cut holds the sweep of the tool shrunk by the tolerance along every move, the moves
    # whose hulls were left out included
    stock = stock_solid(sim.as_stock(BOX), 0.05)
    if case == "zigzag":
        paths_ = [zigzag_ramp()]
    else:
        # a ramp beside the pocket (kept), a ramp over its floor (left out), the layers
        paths_ = [np.vstack([[[-20.0, -12.0, 5.0], [-20.0, -12.0, 0.0], [-20.0, 12.0, -1.0], [-5.0, 0.0, 0.0],
                              [5.0, 0.0, -1.5]], zigzag(-1.5)]),
                  np.vstack([[[-10.0, -6.0, 5.0]], zigzag(-3.0)])]
    solid = sweep.cut(stock, [chain(FLAT6, points) for points in paths_], 0.05)
    removed = stock - solid
    for points in paths_:
        inner = shrunk_sweep(points, 0.05) ^ stock
        assert (inner - removed).volume() < 1e-6
