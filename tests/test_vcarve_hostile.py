"""Hostile input to the V-carve planner: random loops (open, degenerate, self-crossing, tiny,
huge, touching) and random settings come back as a plan or as a VCarveError naming the V-carve,
never as another exception and never running long (each case time-limited, as in test_hostile).
A plan's moves are finite and never deeper than the planner's own deepest point or the max depth."""
import numpy as np
import pytest

from kezuri.toolpath.ir.errors import InputError
from kezuri.toolpath.operations.vcarve import vcarve as vc
from test_hostile import time_limit

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

SECONDS = 20
coordinate = st.floats(min_value=-40, max_value=40, allow_nan=False, allow_infinity=False)
loop = st.lists(st.tuples(coordinate, coordinate), min_size=0, max_size=9)


def plan_or_refuse(loops, carve_settings):
    with time_limit(SECONDS):
        try:
            return vc.plan(loops, carve_settings, "hostile")
        except InputError as error:
            assert "V-carve 'hostile'" in str(error) or "V-bit" in str(error), str(error)
            return None


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(loop, min_size=0, max_size=3), st.sampled_from([0.0, 1.0, 3.0]))
def test_random_loops_are_planned_or_refused_by_name(loops, max_depth):
    carve_settings = vc.VCarveSettings(tool=vc.vbit(3, 90.0, 12.7), max_depth=max_depth)
    result = plan_or_refuse([np.array(points, float).reshape(-1, 2) for points in loops], carve_settings)
    if result is not None:
        for op in result.operations:
            assert np.isfinite(op.xyz).all()
            assert op.xyz[:, 2].min() >= -(max_depth or result.deepest) - 1e-6


def test_touching_counters_and_slivers_are_carved():
    """Two squares meeting at a corner (touching contours) and a 10 um sliver beside them (thinner
    ones are refused by their number, by the pocket's loop rules the V-carve shares)."""
    a = np.array([[0, 0], [5, 0], [5, 5], [0, 5]], float)
    b = a + 5.0
    sliver = np.array([[6, 0], [12, 0], [12, 0.01], [6, 0.01]], float)
    result = plan_or_refuse([a, b, sliver], vc.VCarveSettings())
    assert result is not None and result.deepest == pytest.approx(2.5 / np.tan(np.radians(30)), abs=0.002)
