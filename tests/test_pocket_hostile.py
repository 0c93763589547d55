"""Hostile input to the pocket planner: random loops (open, degenerate, self-crossing, tiny, huge)
and random settings come back as a plan or as a PocketError naming the pocket, never as another
exception and never running long (each case time-limited, as in test_hostile)."""
import math

import numpy as np
import pytest

from kezuri.toolpath.ir.errors import InputError
from kezuri.toolpath.operations.pocket import pocket as pk
from test_hostile import time_limit

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

SECONDS = 20
coordinate = st.floats(min_value=-80, max_value=80, allow_nan=False, allow_infinity=False)
loop = st.lists(st.tuples(coordinate, coordinate), min_size=0, max_size=9)


def plan_or_refuse(loops, pocket_settings):
    with time_limit(SECONDS):
        try:
            return pk.plan(loops, pocket_settings, "hostile")
        except InputError as error:
            assert "pocket 'hostile'" in str(error), str(error)
            return None


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(loop, min_size=0, max_size=3))
def test_random_loops_are_planned_or_refused_by_name(loops):
    result = plan_or_refuse([np.array(points, float).reshape(-1, 2) for points in loops],
                            pk.PocketSettings(depth=1.0, step_down=1.0, stepover=3.0))
    if result is not None:
        op = result.operations[0]
        assert np.isfinite(op.xyz).all() and op.xyz[:, 2].min() >= -1.0 - 1e-9


number = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10, 10), st.just(0.0))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(stepover=number, depth=number, step_down=number, helix=number, ramp_angle=number, angle=number,
       strategy=st.sampled_from(["offset", "zigzag", "spiral"]))
def test_random_settings_are_planned_or_refused_by_name(stepover, depth, step_down, helix, ramp_angle, angle, strategy):
    square = np.array([[0, 0], [30, 0], [30, 30], [0, 30]], float)
    values = dict(stepover=stepover, depth=depth, step_down=step_down, helix_diameter=helix, ramp_angle=ramp_angle,
                  angle=angle, strategy=strategy)
    if all(isinstance(v, (int, float)) and math.isfinite(v) and v > 0 for v in (stepover, step_down)):
        values["stepover"] = max(stepover, 0.5)         # a tiny stepover is slow, not hostile
        values["step_down"] = max(step_down, 0.5)
    plan_or_refuse([square], pk.PocketSettings(**values))


@pytest.mark.parametrize("loops, message", [
    ([np.array([[0, 0], [40, 0], [40, 1e-7]], float)], r"loop 1 encloses no area"),
    ([np.array([[0, 0], [1e-3, 0], [1e-3, 1e-3], [0, 1e-3]], float)], r"encloses? no area|does not fit"),
    ([np.array([[0, 0], [20, 20], [20, 0], [0, 30]], float)], r"crosses itself at X"),
    ([np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)] * 2, r"enclose no area"),   # the same loop twice: even-odd
    ([], r"no closed loop"),
    ("not loops", r"loop 1"),
])
def test_named_hostile_regions(loops, message):
    with time_limit(SECONDS), pytest.raises(pk.PocketError, match=message):
        pk.plan(loops, pk.PocketSettings(), "hostile")
