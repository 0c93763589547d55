"""Converting big ISO 14649 files of explicit toolpaths (issue 32): the quick paths give what the
slow ones gave.

- the in-process stock's compiled column lowering equals its numpy loop (the reference) on the
  fixtures and a generated file, and both equal a brute-force distance test written here;
- a POLYLINE's points read at once equal the numbers of the file's text (read here by a regex),
  and every malformed point is still refused naming that point, as the point-by-point reader did;
- a FREEFORM trajectory's feed moves are the file's points moved to the pocket's placement;
- the model the shell read for the list is the plan's (one parse), the fingerprint the text's;
- the gate's height field marks the same cells as cut by each operation as with the whole grid.
"""
import math
import os
import re
import sys

import numpy as np
import pytest

from kezuri.toolpath.ir.program import FEED, RAPID, Operation, Tool
from kezuri.toolpath.operations.stepnc.inprocess import InProcessStock
from kezuri.toolpath.operations.stepnc.errors import StepNcError
from kezuri.toolpath.operations.stepnc.workplan import in_process_stock, load_workplan, to_program, workplan_from_text

HERE = os.path.dirname(os.path.abspath(__file__))
FIXTURES = os.path.join(HERE, "fixtures", "iso14649")
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "bench"))

import stepnc_bigfile  # noqa: E402  (bench/: the generator of the big file)
from test_stepnc_freeform import freeform_file  # noqa: E402


@pytest.fixture(scope="module")
def big_text():
    return stepnc_bigfile.explicit_toolpath_file(0.5)       # one pocket, 24,000 cutter locations


def sources(big_text):
    yield "ex1", os.path.join(FIXTURES, "ex1.stp")
    yield "ex1_ap238", os.path.join(FIXTURES, "ex1_ap238.stp")
    yield "freeform", freeform_file()
    yield "generated", big_text


def test_compiled_stock_equals_the_numpy_loop(big_text):
    pytest.importorskip("numba")
    for name, source in sources(big_text):
        model = load_workplan(source)
        program = to_program(model)
        heights = {}
        for kernel in ("numba", "numpy"):
            stock = in_process_stock(model)
            fresh = InProcessStock(0, 0, 1, 1, 0.0, kernel=kernel)
            stock.kernel = fresh.kernel
            for op in program.operations:
                stock.cut(op)
                stock.highest()
            heights[kernel] = stock.heights
        assert np.array_equal(heights["numba"], heights["numpy"]), name
        assert (heights["numba"] < heights["numba"].max()).sum() > 100, name     # it did cut


@pytest.mark.parametrize("kernel", ["numba", "numpy"])
def test_stock_against_brute_force(kernel):
    """Random feed moves of a 3 mm end mill over a 20 x 10 mm stock in 0.5 mm columns: a column
    goes down to the lowest upper end of the moves whose distance to its centre is at most the
    radius less the column's half-diagonal (distance by the closest point of the line, clamped)."""
    if kernel == "numba":
        pytest.importorskip("numba")
    rng = np.random.default_rng(7)
    xyz = np.column_stack([rng.uniform(-2, 22, 40), rng.uniform(-2, 12, 40), rng.uniform(-4, 1, 40)])
    kinds = [RAPID] + [FEED] * 39
    op = Operation("random", Tool(1, "flat", 3.0), 1000.0, kinds, xyz, [np.nan] + [500.0] * 39)
    stock = InProcessStock(0, 0, 20, 10, 0.0, cell=0.5, kernel=kernel)
    stock.cut(op)
    stock.highest()
    reach = 1.5 - 0.5 * math.sqrt(0.5)
    checked = 0
    for i in range(40):
        for j in range(20):
            cx, cy = 0.25 + 0.5 * i, 0.25 + 0.5 * j
            expected, near_edge = 0.0, False
            for k in range(1, 40):
                (ax, ay, az), (bx, by, bz) = xyz[k - 1], xyz[k]
                ux, uy = bx - ax, by - ay
                along = max(0.0, min(1.0, ((cx - ax) * ux + (cy - ay) * uy) / (ux * ux + uy * uy)))
                distance = math.hypot(ax + along * ux - cx, ay + along * uy - cy)
                near_edge |= abs(distance - reach) < 1e-9
                if distance <= reach:
                    expected = min(expected, max(az, bz))
            if not near_edge:
                assert stock.heights[i, j] == expected, (i, j)
                checked += 1
    assert checked > 700
    assert (stock.heights < 0).sum() > 100


def test_polyline_points_are_the_texts_numbers(big_text):
    """Every cutter location of the generated file, as the file writes it, is a feed move of the
    program, moved by the pocket's location (the toolpath is in the pocket's coordinates)."""
    polylines, points = [], []
    for line in big_text.splitlines():
        point = re.fullmatch(r"#\d+= CARTESIAN_POINT\('',\(([-0-9.]+),([-0-9.]+),([-0-9.]+)\)\);", line)
        if point:
            points.append(tuple(map(float, point.groups())))
        elif "= POLYLINE(" in line:
            polylines.append(points)
            points = []
    origin = np.array(re.search(r"'POCKET0: LOCATION',\(([-0-9.]+),([-0-9.]+),([-0-9.]+)\)",
                                big_text).groups(), float)
    assert len(polylines) > 20 and sum(map(len, polylines)) > 10000
    program = to_program(workplan_from_text(big_text))
    (op,) = program.operations
    feeds = op.xyz[op.kind == FEED]
    # the first point is entered (rapid above it, fed down); each polyline starts where the one
    # before it ended, and each of its later points is one feed move at the technology's feedrate 0.020 m/s = 1200 mm/min
    expected = np.vstack([np.array(p[1:]) for p in polylines]) + origin
    assert np.array_equal(feeds[-len(expected):], expected)
    assert np.array_equal(op.feed[op.kind == FEED][-len(expected):], np.full(len(expected), 1200.0))
    assert all(np.array_equal(a[-1], b[0]) for a, b in zip(polylines, polylines[1:]))


BAD_POINTS = [
    ("(1.0,2.0,.T.)", "#900 CARTESIAN_POINT: attribute coordinates must be 1 to 3 numbers, found [1.0, 2.0, True]"),
    ("(1.0,'2',3.0)", "#900 CARTESIAN_POINT: attribute coordinates must be 1 to 3 numbers, found [1.0, '2', 3.0]"),
    ("(1.0,2.0,3.0,4.0)", "#900 CARTESIAN_POINT: attribute coordinates must be 1 to 3 numbers, found "
                          "[1.0, 2.0, 3.0, 4.0]"),
    ("(1.0,2.0,1.0E999)", "#900 CARTESIAN_POINT: coordinates inf is not a coordinate (at most 100000 mm from the "
                          "origin)"),
    ("(1.0,2.0,1.0E300)", "#900 CARTESIAN_POINT: coordinates 1e+300 is not a coordinate (at most 100000 mm from "
                          "the origin)"),
    ("(1.0,2.0,-100001.0)", "#900 CARTESIAN_POINT: coordinates -100001 is not a coordinate (at most 100000 mm "
                            "from the origin)"),
    ("$", "#900 CARTESIAN_POINT: attribute coordinates is unset ($) but required"),
]


def _with_point(text: str, coordinates: str) -> str:
    """The freeform fixture with one point of a toolpath POLYLINE (#900) written as given."""
    polyline = re.search(r"#(\d+)= POLYLINE\('[^']*',\((#\d+),", text)
    first = polyline.group(2)
    text = text.replace(f"#{polyline.group(1)}= POLYLINE(", f"#{polyline.group(1)}= POLYLINE(", 1)
    text = re.sub(rf"(#{polyline.group(1)}= POLYLINE\('[^']*',\(){first},", rf"\1#900,{first},", text)
    return text.replace("ENDSEC;\nEND-ISO", f"#900= CARTESIAN_POINT('',{coordinates});\nENDSEC;\nEND-ISO")


@pytest.mark.parametrize("coordinates, message", BAD_POINTS)
def test_bad_points_are_named(coordinates, message):
    text = _with_point(freeform_file(), coordinates)
    with pytest.raises(StepNcError) as caught:
        workplan_from_text(text)
    assert str(caught.value) == message


def test_whole_numbers_and_short_points_read_as_before():
    """Integers are coordinates, one or two numbers are padded with zeros (the point-by-point rule)."""
    for coordinates, expected in (("(1,2,3)", (1.0, 2.0, 3.0)), ("(1.5,2.5)", (1.5, 2.5, 0.0))):
        model = workplan_from_text(_with_point(freeform_file(), coordinates))
        curves = [t.basiccurve for step in model.workingsteps for t in step.its_operation.its_toolpath
                  if type(t.basiccurve).__name__ == "Polyline"]
        assert any(c.points[0] == expected for c in curves), coordinates


def test_the_plan_takes_the_model_read_by_the_caller(big_text):
    """The shell reads the file for the workplan list and hands the model to the plan with the
    text: the plan does not read it again; the job's fingerprint is the text's either way."""
    from kezuri.toolpath.job import JobOperation, Setup, fingerprint
    from kezuri.toolpath.operations.stepnc.kind import StepncGeometry, StepncKind, StepncSettings

    text = freeform_file()
    model = workplan_from_text(text)
    given = StepncKind().plan(Setup(name="T"), StepncSettings(), StepncGeometry(text, model))
    fresh = StepncKind().plan(Setup(name="T"), StepncSettings(), StepncGeometry(text))
    assert given.result.loaded is model
    assert fresh.result.loaded is not model
    for a, b in zip(given.operations, fresh.operations):
        assert np.array_equal(a.xyz, b.xyz) and np.array_equal(a.kind, b.kind)
    assert StepncGeometry(text, model) == StepncGeometry(text)

    def operation(geometry):
        return JobOperation("stepnc", "stepnc", StepncSettings(), geometry)
    assert fingerprint(Setup(), operation(StepncGeometry(text, model))) == \
        fingerprint(Setup(), operation(StepncGeometry(text)))
    assert fingerprint(Setup(), operation(StepncGeometry(text))) != \
        fingerprint(Setup(), operation(StepncGeometry(text.replace("FREEFORM", "FREEFORM2", 1))))


def test_gate_marks_the_same_cells_as_the_whole_grid(big_text, monkeypatch):
    """The height field copies only the rows an operation can reach to find the cells it cut; the
    operation map equals the one made with the whole grid copied for every operation."""
    from kezuri.toolpath.simulate import heightfield
    from kezuri.toolpath.simulate.api import simulate
    from kezuri.toolpath.operations.stepnc.solids import stock_box

    for name, source in (("ex1", os.path.join(FIXTURES, "ex1.stp")), ("generated", big_text)):
        model = load_workplan(source)
        program = to_program(model)
        box = stock_box(model, program)
        maps = []
        for whole in (False, True):
            if whole:
                monkeypatch.setattr(heightfield.Simulation, "_rows",
                                    lambda self, chain: slice(0, self.hf.shape[0] * self.hf.shape[1]))
            result = simulate(program, box, cell=0.25)
            maps.append((result.heightfield.operation.copy(), result.heightfield.heights.copy()))
        assert np.array_equal(maps[0][0], maps[1][0]), name
        assert np.array_equal(maps[0][1], maps[1][1]), name
        assert len(np.unique(maps[0][0])) >= min(4, len(program.operations) + 1), name   # several operations cut
