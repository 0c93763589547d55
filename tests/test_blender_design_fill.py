"""The export gate's design heights (simulate/checks.DesignHeights: the letters' cells by scan
lines, a block of grid rows at a time) against brute force: every cell tested against every edge
of the letters, even-odd, in plain numpy, on the sample name plate's letters and on random
polygons with holes, and the gouge found over a block boundary as over the whole grid.

The rule for a cell centre (x, y) and an edge (x0, y0)-(x1, y1) (y0 != y1), the one the scan
lines follow: the edge crosses the cell's row when min(y0, y1) <= y < max(y0, y1) (so a vertex on
the row counts once, for the edge that leaves upward), at xi = x0 + (y - y0) (x1 - x0) / (y1 - y0);
the crossing counts when x < xi; a cell is inside with an odd count.  So a centre exactly on an
edge is inside when the region lies right of that edge (a square's left edge) and outside when
it lies left of it (the right edge); on a horizontal edge, inside on a bottom edge, outside on a top one."""
import numpy as np
import pytest

from blender_helpers import empty_scene  # noqa: F401
from kezuri.toolpath.engines import region as rg
from kezuri.toolpath.simulate import checks
from kezuri.toolpath.simulate.stock import HeightField


def brute_inside(loops, xs, ys) -> np.ndarray:
    """Every cell against every edge (the rule above): an (len(xs), len(ys)) bool grid."""
    edges = np.vstack([np.hstack([loop, np.roll(loop, -1, axis=0)]) for loop in loops])
    edges = edges[edges[:, 1] != edges[:, 3]]
    x0, y0, x1, y1 = (edges[:, k][None, :] for k in range(4))
    inside = np.zeros((len(xs), len(ys)), bool)
    for j, y in enumerate(ys):
        spans = (np.minimum(y0, y1) <= y) & (y < np.maximum(y0, y1))
        xi = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
        crossings = ((xs[:, None] < xi) & spans).sum(axis=1)
        inside[:, j] = crossings % 2 == 1
    return inside


def grid_over(x0, y0, x1, y1, cell):
    nx, ny = int(np.ceil((x1 - x0) / cell)), int(np.ceil((y1 - y0) / cell))
    return HeightField(x0, y0, (x1 - x0) / nx, (y1 - y0) / ny, np.zeros((nx, ny), np.float32), np.ones((nx, ny), bool),
                       0.0, -10.0)


def blocks(heights: checks.DesignHeights, rows: int) -> np.ndarray:
    nx = heights.hf.shape[0]
    return np.concatenate([heights.rows(i, min(i + rows, nx)) for i in range(0, nx, rows)])


def expected_heights(hf, floor, loops, z_min):
    """The design heights from the brute-force fill over the whole grid."""
    allowed = np.full(hf.shape, floor)
    allowed[brute_inside(loops, hf.x(), hf.y())] = max(floor, z_min)
    return allowed


def sample_letters():
    import bpy

    from kezuri.operators import convert, samples
    scene = bpy.context.scene
    plate_obj, letters_obj = samples.name_plate(scene)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    plate = convert.plate_from_object(plate_obj, depsgraph, scene)
    return plate, convert.outlines_in_work(letters_obj, depsgraph, plate.frame)


def test_the_sample_letters_cell_for_cell(empty_scene):  # noqa: F811
    from kezuri.toolpath.operations.engrave import engrave

    plate, letters = sample_letters()
    keep = rg.offset(rg.from_loops(list(letters), "letters"), -engrave.KEEP_MARGIN)
    loops = [np.asarray(loop, float) for loop in keep.to_polygons()]
    points = np.vstack(plate.outline)
    (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
    hf = grid_over(x0, y0, x1, y1, 0.25)
    heights = checks.design_heights(hf, -1.5, [loops])
    expected = expected_heights(hf, -1.5, loops, hf.top)
    assert heights.grid is None                      # no full grid kept for a floor and keep regions
    inside = expected == hf.top
    assert 0.05 < inside.mean() < 0.6                # the letters are there
    for rows in (1, 7, 256, hf.shape[0]):
        assert np.array_equal(blocks(heights, rows), expected), rows


def random_loops(rng):
    loops = []
    for _ in range(rng.integers(1, 5)):
        n = rng.integers(3, 16)
        centre, radius = rng.uniform(-6, 6, 2), rng.uniform(1, 5)
        angles = np.sort(rng.uniform(0, 2 * np.pi, n))
        r = radius * rng.uniform(0.3, 1, n)
        points = centre + np.column_stack([r * np.cos(angles), r * np.sin(angles)])
        if rng.random() < 0.5:          # vertices on cell centres' rows and columns
            points = np.round(points * 4) / 4 + 0.125
        loops.append(points)
    return loops


@pytest.mark.parametrize("seed", range(40))
def test_random_polygons_with_holes_cell_for_cell(seed):
    rng = np.random.default_rng(seed)
    loops = random_loops(rng)
    try:
        area = rg.from_loops(loops, "test")
    except rg.RegionError:
        pytest.skip("degenerate random polygon")
    keep = [np.asarray(loop, float) for loop in area.to_polygons()]
    hf = grid_over(-12, -11, 12, 11, 0.25)
    floor = float(rng.choice([-np.inf, -2.0]))
    heights = checks.design_heights(hf, None if floor == -np.inf else floor, [(keep, -0.5)])
    expected = expected_heights(hf, floor, keep, -0.5)
    for rows in (1, int(rng.integers(2, 30)), 1000):
        assert np.array_equal(blocks(heights, rows), expected), rows


def test_a_polygon_exactly_on_cell_centres_follows_the_stated_rule():
    """A square whose edges run through cell centres: its left and bottom edges' centres are
    inside, its right and top edges' are outside (x < xi; min <= y < max)."""
    hf = grid_over(0, 0, 4, 4, 1.0)                  # centres 0.5 .. 3.5
    square = np.array([[0.5, 0.5], [2.5, 0.5], [2.5, 2.5], [0.5, 2.5]])
    heights = checks.design_heights(hf, None, [(square, 1.0)])
    got = heights.rows(0, 4) == 1.0
    expected = np.zeros((4, 4), bool)
    expected[0:2, 0:2] = True                        # x in {0.5, 1.5}, y in {0.5, 1.5}
    assert np.array_equal(got, expected) and np.array_equal(brute_inside([square], hf.x(), hf.y()), expected)


def test_the_deepest_gouge_over_blocks_is_the_first_of_equals_as_over_the_grid(monkeypatch):
    """cut_findings compares a block of rows at a time: two cells gouged equally deep, in
    different blocks, report the first in grid order (row-major), as one argmax did."""
    from types import SimpleNamespace

    hf = grid_over(0, 0, 10, 10, 1.0)
    hf.heights[:] = 0.0
    hf.heights[2, 7] = hf.heights[8, 1] = -3.0        # 3 mm below the design floor of 0 ... equally deep
    monkeypatch.setattr(checks, "ROWS_PER_BLOCK", 3)
    found = {}

    def lowest(chains, grid, i, j, tolerance):
        found["cell"] = (i, j)
        return SimpleNamespace(move=[0], op_index=0), 0, 0.0

    monkeypatch.setattr(checks, "lowest_move", lowest)
    sim = SimpleNamespace(touches=[], hf=hf, tolerance=0.01)
    ops = [SimpleNamespace(name="op")]
    findings = checks.cut_findings(sim, [], ops, checks.design_heights(hf, 0.0, None))
    assert found["cell"] == (2, 7)
    assert len(findings) == 1 and "3.000 mm below" in findings[0].message and "2.0 mm^2" in findings[0].message
