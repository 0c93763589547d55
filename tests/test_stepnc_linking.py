"""Stock-aware linking (issue "Machine-ready programs", item 4): whatever order the workingsteps
are cut in, approaches stop above the material that is really left, and the simulation finds no
rapid in material.  The stock and the pockets are read from the Part 21 text by the tests (not by
our reader), and the G-code is judged as LinuxCNC's rs274 runs it.
"""
import itertools
import random
import re

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.toolpath.engines import region as rg
from kezuri.toolpath.ir.program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, Program, Tool
from kezuri.toolpath.simulate import BoxStock, simulate
from kezuri.toolpath.operations.stepnc.inprocess import InProcessStock
from kezuri.toolpath.operations.stepnc.workplan import APPROACH_GAP, load_workplan, pockets_to_part21, to_program
from kezuri.toolpath.operations.stepnc import PocketSpec

from test_stepnc import EX1

# The batch's built-in sample (operators/stepnc.py sample_file): a 120 x 80 x 20 plate, two pockets.
SAMPLE_POCKETS = [PocketSpec("POCKET1", ((10, 10), (50, 10), (50, 40), (10, 40)), 8.0),
                  PocketSpec("POCKET2", ((65, 15), (110, 15), (110, 35), (85, 35), (85, 70), (65, 70)), 5.0)]
SAMPLE_TOOL = Tool(1, "flat", 6.0, flute_length=20.0)


@pytest.fixture(scope="module")
def sample():
    text = pockets_to_part21(((0, 0, -20), (120, 80, 0)), SAMPLE_POCKETS, SAMPLE_TOOL, name="KEZURI SAMPLE PLATE")
    return text, load_workplan(text)


def block_from_text(text: str) -> BoxStock:
    """The BLOCK's corner and sizes, read from the text with regular expressions."""
    block = re.search(r"BLOCK\('[^']*',#(\d+),([-\d.E]+),([-\d.E]+),([-\d.E]+)\)", text)
    placement = re.search(rf"#{block.group(1)}=AXIS2_PLACEMENT_3D\('[^']*',#(\d+)", text)
    point = re.search(rf"#{placement.group(1)}=CARTESIAN_POINT\('[^']*',\(([^)]*)\)\)", text)
    x, y, z = (float(v) for v in point.group(1).split(","))
    dx, dy, dz = (float(block.group(k)) for k in (2, 3, 4))
    return BoxStock(x, y, z, x + dx, y + dy, z + dz)


def rapid_findings(program, stock, cell):
    result = simulate(program, stock, cell=cell)
    return [f for f in result.findings if f.kind == "rapid_in_material"], result.findings


def test_the_issue_order_on_the_sample(sample):
    """``--order 48,47,70,69`` (each pocket finished before it is roughed) rapided to Z-3.333 into
    uncut material; now the rapids stop APPROACH_GAP above the material and the rest is fed."""
    text, loaded = sample
    r1, f1, r2, f2 = (step.id for step in loaded.workingsteps)
    program = to_program(loaded, order=[f1, r1, f2, r2])
    stock = block_from_text(text)
    assert (stock.x0, stock.y0, stock.z0, stock.x1, stock.y1, stock.z1) == (0, 0, -20, 120, 80, 0)
    assert rapid_findings(program, stock, 0.25) == ([], [])
    # The first operation finishes pocket 1 with nothing cut: above the rough floor its rings sweep
    # the walls only (tool centres R + 0.5 from the wall), so the middle of the pocket, more than
    # 3 R + 0.5 from the walls (the outline from the spec), is uncut until the floor layers start
    # there.  Every rapid ending over it before the first feed over it ends above the stock top.
    first = program.operations[0]
    radius = SAMPLE_TOOL.radius
    middle = rg.offset(rg.from_loops([SAMPLE_POCKETS[0].outline]), -(3 * radius + 0.5))
    inside = rg.contains_points(middle, first.xyz[:, :2])
    first_feed = np.flatnonzero(inside & (first.kind == FEED))[0]
    rapids = np.flatnonzero(inside[:first_feed] & (first.kind[:first_feed] == RAPID))
    assert len(rapids)
    assert first.xyz[rapids, 2].min() == pytest.approx(stock.z1 + APPROACH_GAP)   # was -3.333 (issue)
    assert first.xyz[first_feed - 1, 2] == pytest.approx(stock.z1 + APPROACH_GAP)


@pytest.mark.parametrize("post_name", ["linuxcnc"])
@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")
def test_issue_order_as_rs274_runs_it(sample, post_name):
    """The G-code itself: rs274's moves rebuilt into one operation of the 6 mm end mill and
    simulated (ramps, polylines and the rounded corners' arcs, with the centres rs274 reads)."""
    text, loaded = sample
    r1, f1, r2, f2 = (step.id for step in loaded.workingsteps)
    program = to_program(loaded, order=[f1, r1, f2, r2])
    calls = rs274.run(post.milling_post(post_name).to_text(program))
    kinds, points, _ = rs274.motion_endpoints(calls)
    assert {"rapid", "feed"} <= set(kinds) <= {"rapid", "feed", "cw", "ccw"} and {"cw", "ccw"} & set(kinds)
    centres = [[float(a) for a in args[2:4]] + [float(args[5])] for name, args in calls if name == "ARC_FEED"]
    centre = np.full((len(kinds), 3), np.nan)
    centre[[k in ("cw", "ccw") for k in kinds]] = centres
    kind = np.array([{"rapid": RAPID, "feed": FEED, "cw": ARC_CW, "ccw": ARC_CCW}[k] for k in kinds])
    feed = np.where(kind == RAPID, np.nan, 500.0)
    replay = Operation("rs274", SAMPLE_TOOL, 10000.0, kind, points, feed, center=centre, start=points[0])
    assert rapid_findings(Program("rs274", [replay]), block_from_text(text), 0.25) == ([], [])


def test_every_order_of_the_sample_is_safe(sample):
    text, loaded = sample
    ids = [step.id for step in loaded.workingsteps]
    stock = block_from_text(text)
    for order in itertools.permutations(ids):
        rapids, findings = rapid_findings(to_program(loaded, order=list(order)), stock, 0.25)
        assert findings == [], (order, [(f.kind, f.operation, f.move, f.depth_mm) for f in findings])


def test_default_orders_are_unchanged_where_they_were_safe(sample):
    """In workplan order every approach stops where it did before: APPROACH_GAP above the layer
    cut before (the first layer: above the feature top), which the stock check agrees is safe."""
    _, loaded = sample
    for op, step in zip(to_program(loaded).operations, loaded.workingsteps):
        feature = step.its_feature
        starts = op.start_points()
        # a rapid straight down (same XY) that ends below the clearance plane ends an approach
        down = (op.kind == RAPID) & (op.xyz[:, 2] < op.clearance_z - 1e-9) & \
            (np.linalg.norm(op.xyz[:, :2] - starts[:, :2], axis=1) < 1e-9) & (starts[:, 2] > op.xyz[:, 2])
        cut_levels = sorted({round(z, 6) for z in op.xyz[op.kind == FEED, 2]} | {feature.top_z}, reverse=True)
        allowed = {round(z + APPROACH_GAP, 6) for z in cut_levels}
        assert {round(z, 6) for z in op.xyz[down, 2]} <= allowed


def test_random_orders_and_subsets_of_ex1_are_safe():
    """ex1 (planar face, drilling, reaming, pocket rough and finish; no BLOCK: the stock is the
    simulation's box around the cuts): random orders, some with workingsteps switched off."""
    from kezuri.toolpath.operations.stepnc.solids import stock_box

    loaded = load_workplan(EX1)
    ids = [step.id for step in loaded.workingsteps]
    rng = random.Random(19)
    full = to_program(loaded)
    stock = stock_box(loaded, full)     # the same box for every order: the complete program's
    checked = 0
    for _ in range(14):
        order = rng.sample(ids, len(ids))
        enabled = order if rng.random() < 0.6 else rng.sample(order, rng.randint(1, len(ids)))
        program = to_program(loaded, order=order, enabled=enabled)
        _, findings = rapid_findings(program, stock, 0.5)
        assert [f for f in findings if f.kind == "rapid_in_material"] == [], (order, enabled)
        checked += 1
    assert checked == 14


def test_in_process_stock_is_an_upper_bound():
    """A 10 mm flat end mill cutting a 40 mm slot 5 deep: under the slot the bound is the slot
    floor, near the rim of the cut it stays the top (the square of a column straddles the wall: the
    bound is exact up to two half-diagonals of a column, 2 x 0.177 mm)."""
    stock = InProcessStock(0, 0, 100, 50, 0.0)
    xyz = np.array([[20, 25, 5], [20, 25, -5], [60, 25, -5], [60, 25, 5]], float)
    op = Operation("slot", Tool(1, "flat", 10.0), 1000.0, [RAPID, FEED, FEED, FEED], xyz,
                   [np.nan, 100.0, 500.0, 500.0])
    stock.cut(op)
    assert stock.top_under(40, 25, 1.0) == -5.0          # well inside the slot
    assert stock.top_under(40, 25, 4.6) == -5.0          # within 2 x the half-diagonal of a column
    assert stock.top_under(40, 25, 5.5) == 0.0           # reaches the wall
    assert stock.top_under(80, 25, 3.0) == 0.0           # beyond the slot
    assert stock.top_under(200, 25, 3.0) == -np.inf      # off the stock
    assert stock.highest() == 0.0
