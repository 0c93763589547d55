"""STEP-NC workplans and rotary pockets as operation kinds of the job model: planned through
``plan_job`` on the built-in samples, they give the same operations as the workflow functions,
a cache returns what is unchanged and re-plans a changed setting, and a wrong settings type or a
machine of another family is refused naming the operation."""
import dataclasses
import os

import numpy as np
import pytest

from kezuri.toolpath import job as jobs
from kezuri.toolpath.ir import machine as machines
from kezuri.toolpath.ir.program import Tool
from kezuri.toolpath.operations.rotary import rotary
from kezuri.toolpath.operations.rotary.kind import RotaryGeometry, RotaryKind
from kezuri.toolpath.operations.stepnc import PocketSpec, load_workplan, pockets_to_part21, to_program
from kezuri.toolpath.operations.stepnc.kind import StepncGeometry, StepncKind, StepncSettings
from kezuri.toolpath.operations.stepnc.errors import StepNcError

FIXTURES = os.environ.get("KEZURI_FIXTURES", os.path.join(os.path.dirname(__file__), "fixtures"))
EX1 = os.path.join(FIXTURES, "iso14649", "ex1.stp")


def sample_plate() -> str:
    """The STEP-NC workflow's built-in sample (operators/stepnc.py sample_file): a 120 x 80 x 20 mm
    plate with a rectangular pocket 8 mm deep and an L-shaped one 5 mm deep."""
    pockets = [PocketSpec("POCKET1", ((10, 10), (50, 10), (50, 40), (10, 40)), 8.0),
               PocketSpec("POCKET2", ((65, 15), (110, 15), (110, 35), (85, 35), (85, 70), (65, 70)), 5.0)]
    return pockets_to_part21(((0, 0, -20), (120, 80, 0)), pockets, Tool(1, "flat", 6.0, flute_length=20.0),
                             name="KEZURI SAMPLE PLATE")


def one(kind, settings, geometry, machine=None, name="op"):
    return jobs.Job(jobs.Setup(name="plate", machine=machine), (jobs.JobOperation(kind, name, settings, geometry),))


def assert_same_operations(got, expected):
    assert len(got) == len(expected) > 0
    for a, b in zip(got, expected):
        assert a.name == b.name and a.tool == b.tool and a.spindle_rpm == b.spindle_rpm
        assert np.array_equal(a.kind, b.kind) and np.array_equal(a.xyz, b.xyz)
        assert np.array_equal(a.feed, b.feed, equal_nan=True)          # NaN: no feed on a rapid
        assert (a.center is None) == (b.center is None)
        if a.center is not None:
            assert np.array_equal(a.center, b.center, equal_nan=True)  # NaN: no arc centre on a line
        assert a.rotary.keys() == b.rotary.keys()
        for axis in a.rotary:
            assert np.array_equal(a.rotary[axis], b.rotary[axis], equal_nan=True)


def test_both_kinds_are_registered_with_their_machine_families():
    known = jobs.kinds()
    assert known["stepnc"] is StepncKind and known["rotary"] is RotaryKind
    assert StepncKind.families == ("milling",) and RotaryKind.families == ("cxz",)


# ----- STEP-NC -------------------------------------------------------------------------------------

def test_the_sample_workplan_plans_as_the_workflow_converts_it():
    text = sample_plate()
    planned = jobs.plan_job(one("stepnc", StepncSettings(), StepncGeometry(text)))
    part = planned.parts[0]
    expected = to_program(load_workplan(text), name="plate")
    assert_same_operations(part.operations, expected.operations)
    # rough and finish per pocket, in the workplan's order
    assert [op.source_id for op in part.operations] == [op.source_id for op in expected.operations]
    assert len(part.operations) == 4
    # the stock is the workpiece's BLOCK as the file gives it: 120 x 80 x 20, top at Z 0
    stock = part.stock
    assert (stock.x0, stock.y0, stock.z0, stock.x1, stock.y1, stock.z1) == (0, 0, -20, 120, 80, 0)
    assert part.design is None and part.skipped == ()
    assert list(part.warnings) == list(expected.notes)
    assert part.result.fixture_clearance == pytest.approx(0.01)     # no through hole: the bare margin
    # one part, so the job's program is the workplan's
    assert_same_operations(planned.program().operations, expected.operations)


def test_switched_off_workingsteps_are_skipped_by_name_and_reordering_follows_the_list():
    text = open(EX1, encoding="utf-8").read()
    order, enabled = (10, 12, 11, 14, 13), (10, 12, 14, 13)
    part = jobs.plan_job(one("stepnc", StepncSettings(order, enabled), StepncGeometry(text))).parts[0]
    expected = to_program(load_workplan(EX1), order=list(order), enabled=list(enabled), name="plate")
    assert_same_operations(part.operations, expected.operations)
    assert [op.source_id for op in part.operations] == [10, 12, 14, 13]
    assert [(s["id"], s["name"]) for s in part.skipped] == [(11, "WS DRILL HOLE1")]
    assert "switched off" in part.skipped[0]["reason"]


def test_the_cache_keeps_the_workplan_and_a_changed_order_replans_it():
    geometry, cache = StepncGeometry(open(EX1, encoding="utf-8").read()), {}
    first = jobs.plan_job(one("stepnc", StepncSettings(), geometry, name="workplan"), cache)
    assert first.replanned() == ["workplan"]
    again = jobs.plan_job(one("stepnc", StepncSettings(), geometry, name="workplan"), cache)
    assert again.replanned() == [] and again.parts[0] is first.parts[0]
    swapped = jobs.plan_job(one("stepnc", StepncSettings((10, 11, 12, 14, 13)), geometry, name="workplan"), cache)
    assert swapped.replanned() == ["workplan"]
    assert [op.source_id for op in swapped.parts[0].operations] == [10, 11, 12, 14, 13]


def test_a_workplan_with_nothing_to_cut_is_refused_with_the_reason():
    text = sample_plate()
    with pytest.raises(StepNcError, match="every workingstep is switched off"):
        jobs.plan_job(one("stepnc", StepncSettings(enabled=()), StepncGeometry(text)))
    empty = text.replace("CLOSED_POCKET(", "STEP(")   # no feature the reader supports: no workingstep left
    with pytest.raises(StepNcError, match="no workingstep can be machined"):
        jobs.plan_job(one("stepnc", StepncSettings(), StepncGeometry(empty)))


def test_stepnc_refuses_wrong_settings_and_a_rotary_table():
    geometry = StepncGeometry(sample_plate())
    with pytest.raises(jobs.JobError, match="operation 'plate pockets': settings must be StepncSettings"):
        jobs.plan_job(one("stepnc", rotary.RotarySettings(), geometry, name="plate pockets"))
    lathe = machines.preset("wood-lathe-cxz")
    with pytest.raises(jobs.JobError, match="operation 'plate pockets' .*runs on milling machines, not on the "
                                            "job's cxz machine"):
        jobs.plan_job(one("stepnc", StepncSettings(), geometry, machine=lathe, name="plate pockets"))
    # on a milling machine it plans
    assert jobs.plan_job(one("stepnc", StepncSettings(), geometry, machine=machines.preset("fanuc-vmc"))).parts


# ----- rotary pockets ------------------------------------------------------------------------------

def sample_rotary() -> RotaryGeometry:
    block, pockets = rotary.sample_job()
    return RotaryGeometry(block, tuple(pockets))


def test_the_bento_block_plans_as_the_workflow_plans_it():
    geometry = sample_rotary()
    settings = rotary.RotarySettings()
    part = jobs.plan_job(one("rotary", settings, geometry, machine=machines.preset("wood-lathe-cxz"))).parts[0]
    block, pockets = rotary.sample_job()
    expected = rotary.plan(block, pockets, settings, name="plate")
    assert_same_operations(part.operations, expected.program.operations)
    assert [op.name for op in part.operations] == [op.name for op in expected.program.operations]
    assert len(part.operations) == 3 and "c" in part.operations[0].rotary
    # the block, 105 x 105 x 30 mm, its top centre on the table's axis
    stock = part.stock
    assert (stock.x0, stock.y0, stock.z0, stock.x1, stock.y1, stock.z1) == (-52.5, -52.5, -30.0, 52.5, 52.5, 0.0)
    assert part.result.cycle_time_s == expected.cycle_time_s
    assert part.design is None and part.warnings == () and part.skipped == ()


def test_the_cache_keeps_the_pockets_and_a_changed_stepover_replans_them():
    geometry, cache = sample_rotary(), {}
    settings = rotary.RotarySettings()
    first = jobs.plan_job(one("rotary", settings, geometry, name="pockets"), cache)
    again = jobs.plan_job(one("rotary", rotary.RotarySettings(), sample_rotary(), name="pockets"), cache)
    assert first.replanned() == ["pockets"] and again.replanned() == []
    assert again.parts[0] is first.parts[0]
    finer = jobs.plan_job(one("rotary", dataclasses.replace(settings, stepover=0.8), geometry, name="pockets"), cache)
    assert finer.replanned() == ["pockets"]
    # a finer floor spiral pitch: more points on the flat floors
    assert len(finer.parts[0].operations[0]) > len(first.parts[0].operations[0])


def test_rotary_refuses_wrong_settings_and_a_milling_machine():
    geometry = sample_rotary()
    with pytest.raises(jobs.JobError, match="operation 'bento': settings must be RotarySettings, got StepncSettings"):
        jobs.plan_job(one("rotary", StepncSettings(), geometry, name="bento"))
    with pytest.raises(jobs.JobError, match="operation 'bento' .*runs on cxz machines, not on the job's milling"):
        jobs.plan_job(one("rotary", rotary.RotarySettings(), geometry, machine=machines.preset("grbl-router"),
                          name="bento"))
