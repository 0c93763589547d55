"""Turn-mill and punching as operation kinds of the job model (issue 28, deliverable 1): planned
through ``plan_job`` on the built-in samples, each Part holds what the workflow's own functions
make, a cache returns the planned Part until a setting changes, and a job the kind cannot run
is refused naming the operation.

The references are the core's workflow functions called as the shell called them before the
kinds existed (classify, then plan; place, nibble, then move onto the sheet), and numbers
written here (the Amada 04P preset's sheet and G92 origin, the sample bar's size)."""
import dataclasses
import math

import numpy as np
import pytest
from manifold3d import Manifold

from kezuri.post import amada_punch
from kezuri.toolpath import job
from kezuri.toolpath.engines.meshrays import TrimeshRayEngine
from kezuri.toolpath.ir import machine
from kezuri.toolpath.operations.sheetmetal import nibbling, placement, punch, unfold
from kezuri.toolpath.ir.program import PunchOperation
from kezuri.toolpath.operations.sheetmetal.kind import PunchGeometry, PunchKind, PunchSettings
from kezuri.toolpath.operations.turnmill import turnmill as tm
from kezuri.toolpath.operations.turnmill.kind import TurnMillGeometry, TurnMillKind
from kezuri.toolpath.simulate import BoxStock, CylinderStock

SETTINGS = tm.TurnMillSettings(tolerance=0.05)        # coarser than the default: a quicker plan
TURNMILL = job.Setup(name="bar", machine=machine.preset("fanuc-0it-turnmill"))
PAPER_CORNERS = np.array([[0, 0, 0], [0, 30, 100], [100, 50, 100], [100, 40, 0]], float)
PUNCH = PunchSettings(station=302, tool_diameter=10.0, pitch=2.0, thickness=1.6, joints=2, joint_width=0.4)
PUNCHING = job.Setup(name="quad", post="amada-04p", machine=machine.preset("amada-04p"))
# The Amada 04P preset, written out: a 1270 x 1270 mm sheet, G92 origin X1000 Y1040.
SHEET = (1270.0, 1270.0)
ORIGIN = (1000.0, 1040.0)


def turnmill_job(settings=SETTINGS, geometry=None, setup=TURNMILL, name="turn-mill"):
    if geometry is None:
        geometry = TurnMillGeometry(*tm.sample_part(segments=96))
    return job.Job(setup, (job.JobOperation("turnmill", name, settings, geometry),))


def punch_job(settings=PUNCH, outline=None, setup=PUNCHING, name="punch"):
    if outline is None:
        outline = unfold.unfold_twisted_quad(PAPER_CORNERS, 5, "horizontal").pattern.outline
    return job.Job(setup, (job.JobOperation("punch", name, settings, PunchGeometry(outline)),))


@pytest.fixture(scope="module")
def turnmill_cache():
    cache = {}
    planned = job.plan_job(turnmill_job(), cache)
    return cache, planned


def same_operations(mine, theirs):
    assert [op.name for op in mine] == [op.name for op in theirs]
    for a, b in zip(mine, theirs):
        assert a.tool == b.tool and a.direction == b.direction and a.spindle_rpm == b.spindle_rpm
        assert np.array_equal(a.start, b.start)
        assert np.array_equal(a.kind, b.kind)
        assert np.array_equal(a.xyz, b.xyz) and np.array_equal(a.feed, b.feed, equal_nan=True)
        assert a.rotary.keys() == b.rotary.keys()
        assert all(np.array_equal(a.rotary[k], b.rotary[k]) for k in a.rotary)


# ----- registered --------------------------------------------------------------------------------

def test_both_kinds_are_registered_by_their_packages():
    known = job.kinds()
    assert known["turnmill"] is TurnMillKind and known["punch"] is PunchKind
    assert TurnMillKind.families == ("xzc",) and PunchKind.families == ("punch",)
    assert TurnMillKind.settings_type is tm.TurnMillSettings and PunchKind.settings_type is PunchSettings


# ----- turn-mill -------------------------------------------------------------------------------

def test_the_turnmill_part_is_what_classify_then_plan_make(turnmill_cache):
    _, planned = turnmill_cache
    part = planned.parts[0]
    v, f, stock = tm.sample_part(segments=96)
    engine = TrimeshRayEngine(v, f)
    labels = tm.classify_faces(v, f, engine, SETTINGS.sample_spacing)
    reference = tm.plan(v, f, stock, SETTINGS, engine, labels=labels, name="bar")
    same_operations(part.operations, reference.program.operations)
    assert [op.name for op in part.operations] == ["radial roughing", "radial finishing", "axial roughing",
                                                   "axial finishing"]
    outcome = part.result
    assert np.array_equal(outcome.plan.labels, labels)
    assert outcome.plan.program.name == "bar"                      # the setup's name
    assert outcome.rays == 2 * len(tm.face_samples(v[f], SETTINGS.sample_spacing)[0])
    # the bar: the sample's 85 mm bar from z -60 to the end face at 0, as a cylinder stock
    assert isinstance(part.stock, CylinderStock)
    assert (part.stock.radius, part.stock.height, part.stock.z_top) == (42.5, 60.0, 0.0)
    # the design layer is the part mesh the gate checks the cut against
    assert np.array_equal(part.design.design.vertices, v) and np.array_equal(part.design.design.faces, f)
    assert part.skipped == () and part.warnings == ()             # the sample's walls are all swept


def test_replanning_the_turnmill_job_returns_the_cached_part_and_a_changed_setting_replans(turnmill_cache):
    cache, first = turnmill_cache
    again = job.plan_job(turnmill_job(), cache)
    assert again.replanned() == [] and again.parts[0] is first.parts[0]
    faster = job.plan_job(turnmill_job(dataclasses.replace(SETTINGS, feed=650.0)), cache)
    assert faster.replanned() == ["turn-mill"]
    # the cutting moves at the new feed, the plunges at the plunge feed as before
    for before, after in zip(first.parts[0].operations, faster.parts[0].operations):
        assert set(np.unique(before.feed[before.kind != tm.RAPID])) == {150.0, 500.0}
        assert set(np.unique(after.feed[after.kind != tm.RAPID])) == {150.0, 650.0}


def hex_bar_with_hole():
    """A 30 mm hex bar 40 long (end face at z 0) with an 8 mm cross hole along Y at z -20: the
    hole's wall faces neither tool."""
    corner = 30.0 / math.sqrt(3.0)
    bar = Manifold.cylinder(40.0, corner, corner, 6).translate((0.0, 0.0, -40.0))
    hole = (Manifold.cylinder(4 * corner, 4.0, 4.0, 32).translate((0.0, 0.0, -2 * corner))
            .rotate((90.0, 0.0, 0.0)).translate((0.0, 0.0, -20.0)))
    mesh = (bar - hole).to_mesh64()
    v, f = np.array(mesh.vert_properties[:, :3], float), np.array(mesh.tri_verts, np.int64)
    return v, f, tm.Stock(float(np.hypot(v[:, 0], v[:, 1]).max()), -40.0, 0.0)


def test_the_faces_no_tool_reaches_are_the_parts_skipped_features_and_warnings():
    v, f, stock = hex_bar_with_hole()
    part = job.plan_job(turnmill_job(geometry=TurnMillGeometry(v, f, stock))).parts[0]
    assert len(part.skipped) == 1 and len(part.warnings) == 1
    tri = v[f]
    on_wall = np.all(np.abs(np.hypot(tri[..., 0], tri[..., 2] + 20.0) - 4.0) < 1e-6, axis=1)
    assert set(part.skipped[0].faces.tolist()) == set(np.flatnonzero(on_wall).tolist())
    assert part.warnings[0].startswith(f"not machined: {len(part.skipped[0].faces)} faces")


def test_a_turnmill_job_is_refused_naming_the_operation():
    with pytest.raises(job.JobError, match=r"operation 'OP10': settings must be TurnMillSettings, got PunchSettings"):
        job.plan_job(turnmill_job(settings=PUNCH, name="OP10"))
    milling = job.Setup(name="bar", machine=machine.preset("fanuc-vmc"))
    with pytest.raises(job.JobError, match=r"operation 'OP10' \(Turn-Mill\) runs on xzc machines, not on the "
                                           r"job's milling machine"):
        job.plan_job(turnmill_job(setup=milling, name="OP10"))


# ----- punching ------------------------------------------------------------------------------

def test_the_punch_part_is_what_place_and_nibble_make_on_the_sheet():
    outline = unfold.unfold_twisted_quad(PAPER_CORNERS, 5, "horizontal").pattern.outline
    part = job.plan_job(punch_job(outline=outline)).parts[0]
    profile = machine.preset("amada-04p")
    contour = unfold.compensate_outline(outline, 10.0)
    where = placement.place(contour, 10.0, profile)
    lines = nibbling.nibble(contour, 2.0, 10.0, joints=2, joint_width=0.4).moved(where.offset)
    (operation,) = part.operations
    assert isinstance(operation, PunchOperation)
    assert np.array_equal(operation.lines, lines.lines)
    assert (operation.station, operation.pitch, operation.thickness, operation.punch_diameter) == (302, 2.0, 1.6, 10.0)
    assert tuple(part.result.program.origin) == ORIGIN
    assert list(part.notes) == placement.describe(where) + ["micro-joints: 2 of 0.4 mm"]
    # every hit of every line lies on the tool-centre contour moved onto the sheet, in the sheet
    moved = contour + np.asarray(where.offset)
    segments = np.stack([moved, np.roll(moved, -1, axis=0)], axis=1)
    for point in operation.lines.reshape(-1, 2):
        a, b = segments[:, 0], segments[:, 1]
        t = np.clip(np.einsum("ij,ij->i", point - a, b - a) / np.einsum("ij,ij->i", b - a, b - a), 0, 1)
        assert np.min(np.hypot(*(a + t[:, None] * (b - a) - point).T)) < 1e-9
    assert np.all(operation.lines > 0) and np.all(operation.lines < SHEET[0])
    # the stock is the sheet, 1.6 mm thick below Z 0; nothing may be cut inside the pattern
    assert part.stock == BoxStock(0.0, 0.0, -1.6, SHEET[0], SHEET[1], 0.0)
    (region,) = part.design.keep_regions
    assert np.allclose(region[0], outline + np.asarray(where.offset))
    assert np.array_equal(part.result.contour, contour)
    # the program the post writes from it punches the part out, held by its two joints
    text = amada_punch.AmadaPunchPost().to_text(part.result.program)
    punched = punch.simulate_punching(text, punch_diameter=10.0, pattern=region[0], joints=part.result.nibbling.joints)
    assert punched.held_by_joints and not punched.part_separated and punched.gouges == []


def test_every_elbow_piece_plans_as_a_punch_job():
    for piece in unfold.unfold_elbow(90.0, 150.0, 100.0, 5).pieces:
        outline = piece.outline - piece.outline.min(axis=0)
        part = job.plan_job(punch_job(outline=outline)).parts[0]
        contour = unfold.compensate_outline(outline, 10.0)
        where = placement.place(contour, 10.0, machine.preset("amada-04p"))
        expected = nibbling.nibble(contour, 2.0, 10.0, joints=2, joint_width=0.4).moved(where.offset)
        assert np.array_equal(part.operations[0].lines, expected.lines)


def test_replanning_the_punch_job_returns_the_cached_part_and_a_changed_setting_replans():
    cache = {}
    first = job.plan_job(punch_job(), cache)
    again = job.plan_job(punch_job(), cache)
    assert first.replanned() == ["punch"] and again.replanned() == [] and again.parts[0] is first.parts[0]
    fewer = job.plan_job(punch_job(dataclasses.replace(PUNCH, joints=0)), cache)
    assert fewer.replanned() == ["punch"]
    assert len(first.parts[0].result.nibbling.joints) == 2 and len(fewer.parts[0].result.nibbling.joints) == 0
    assert fewer.parts[0].notes[-1] == "micro-joints: none, the part falls free at the last hits"


def test_a_punch_job_is_refused_naming_the_operation():
    with pytest.raises(job.JobError, match=r"operation 'blank': settings must be PunchSettings, got TurnMillSettings"):
        job.plan_job(punch_job(settings=SETTINGS, name="blank"))
    with pytest.raises(job.JobError, match=r"operation 'blank' \(Punching\) runs on punch machines, not on the "
                                           r"job's xzc machine"):
        job.plan_job(punch_job(setup=TURNMILL, name="blank"))


def test_a_pattern_with_too_many_hits_or_no_thickness_is_refused_by_name():
    outline = np.array([[0.0, 0.0], [1000.0, 0.0], [1000.0, 1000.0], [0.0, 1000.0]])
    with pytest.raises(punch.PunchError, match=r"pitch 0.1 mm: the flat pattern takes \d+ hits, more than the 20000"):
        job.plan_job(punch_job(dataclasses.replace(PUNCH, pitch=0.1), outline=outline))
    with pytest.raises(punch.PunchError, match=r"sheet thickness must be a finite number > 0 \(mm\), got 0.0"):
        job.plan_job(punch_job(dataclasses.replace(PUNCH, thickness=0.0)))
