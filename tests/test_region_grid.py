"""region.grid_inside (the export gate's letter fill, by scan lines) against region.contains_points
(the even-odd test of each point, a different algorithm): the same answer for every grid point,
on random polygons with holes, vertices on grid lines and rows, and grids that start anywhere."""
import numpy as np
import pytest

from kezuri.toolpath.engines import region as rg


def random_region(rng):
    loops = []
    for _ in range(rng.integers(1, 4)):
        n = rng.integers(3, 14)
        centre, radius = rng.uniform(-5, 5, 2), rng.uniform(1, 4)
        angles = np.sort(rng.uniform(0, 2 * np.pi, n))
        r = radius * rng.uniform(0.3, 1, n)
        points = centre + np.column_stack([r * np.cos(angles), r * np.sin(angles)])
        if rng.random() < 0.5:          # vertices exactly on grid lines and rows
            points = np.round(points * 4) / 4
        loops.append(points)
    return rg.from_loops(loops, "test")


@pytest.mark.parametrize("seed", range(40))
def test_every_grid_point_as_the_point_test_says(seed):
    rng = np.random.default_rng(seed)
    try:
        area = random_region(rng)
    except rg.RegionError:
        pytest.skip("degenerate random polygon")
    xs = np.arange(-10, 10.001, 0.25) + rng.choice([0.0, 0.125, 1e-12])
    ys = np.arange(-9, 9.001, 0.25) + rng.choice([0.0, 0.125])
    got = rg.grid_inside(area, xs, ys, rows_per_block=int(rng.integers(1, 40)))
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    expected = rg.contains_points(area, np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape)
    assert got.shape == (len(xs), len(ys))
    assert (got == expected).all()


def test_a_square_with_a_hole_by_hand():
    outer = np.array([[0, 0], [4, 0], [4, 4], [0, 4]], float)
    hole = np.array([[1, 1], [3, 1], [3, 3], [1, 3]], float)
    xs = ys = np.arange(0.5, 4, 1.0)           # cell centres 0.5 1.5 2.5 3.5
    got = rg.grid_inside(rg.from_loops([outer, hole], "ring"), xs, ys)
    expected = np.ones((4, 4), bool)
    expected[1:3, 1:3] = False
    assert (got == expected).all()


def test_empty_inputs():
    square = rg.from_loops([np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)], "square")
    assert rg.grid_inside(square, np.zeros(0), np.arange(3.0)).shape == (0, 3)
    assert not rg.grid_inside(square, np.arange(5.0, 9.0), np.arange(5.0, 9.0)).any()
