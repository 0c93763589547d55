"""The viewport's polylines of a path with arcs (program.walked, used by picture_jobs.role_paths):
every point of a walked arc lies on its circle (checked against the centre given, not the walk),
the angle steps are small, helices climb evenly, and straight moves are left as they are."""
import math

import numpy as np
import pytest

from kezuri.toolpath.ir.program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, Tool, walked

TOOL = Tool(1, "flat", 6.0)


def test_arcs_walked_on_their_circles_and_lines_kept():
    # a rapid, a line, a half circle CCW about (10, 0) radius 10, a helical quarter CW, a line
    kind = np.array([RAPID, FEED, ARC_CCW, ARC_CW, FEED])
    xyz = np.array([[0, 0, 5], [0, 0, -1], [20, 0, -1], [10, -10, -3], [0, -10, -3]], float)
    center = np.full((5, 3), np.nan)
    center[2] = [10, 0, -1]
    center[3] = [10, 0, -3]
    op = Operation("arcs", TOOL, 10000, kind, xyz, np.array([np.nan, 300, 600, 600, 600]), center=center,
                   start=np.array([0, 0, 20.0]))
    kinds, points = walked(op, arc_step=math.radians(5))
    assert len(points) == len(kinds) + 1 and np.array_equal(points[0], [0, 0, 20])
    assert list(kinds[:2]) == [RAPID, FEED] and np.array_equal(points[1:3], xyz[:2])
    half = points[3:3 + 36]                    # 180 / 5 pieces
    assert (kinds[2:2 + 36] == ARC_CCW).all()
    assert np.allclose(np.hypot(half[:, 0] - 10, half[:, 1]), 10.0) and np.allclose(half[:, 2], -1)
    assert half[:, 1].min() == pytest.approx(-10.0)         # CCW from (0,0) about (10,0) goes down through y = -10
    assert np.allclose(half[-1], [20, 0, -1])
    quarter = points[3 + 36:3 + 36 + 18]                    # 90 / 5 pieces, climbing -1 -> -3
    assert (kinds[2 + 36:2 + 36 + 18] == ARC_CW).all()
    assert np.allclose(np.hypot(quarter[:, 0] - 10, quarter[:, 1]), 10.0)
    assert np.allclose(np.diff(np.concatenate([[-1.0], quarter[:, 2]])), -2.0 / 18)
    assert np.allclose(points[-1], [0, -10, -3]) and kinds[-1] == FEED


def test_a_path_without_arcs_is_its_points():
    xyz = np.array([[1, 2, 3], [4, 5, 6]], float)
    op = Operation("lines", TOOL, 10000, np.array([RAPID, FEED]), xyz, np.array([np.nan, 100.0]),
                   start=np.array([0, 0, 0.0]))
    kinds, points = walked(op)
    assert list(kinds) == [RAPID, FEED] and np.array_equal(points, [[0, 0, 0], [1, 2, 3], [4, 5, 6]])
