"""Long work in steps (issue #8): the UI operators run their work through SteppedJob, a step at
a time from a timer.  These tests drive SteppedJob the way the modal operator does, on the real
jobs of the sample scenes: the result is the same as in one go, the work only runs inside a
step, Esc (cancel) stops it without touching the scene, and errors reach the main thread."""
import threading
import time

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

from kezuri.operators import common, samples  # noqa: E402
from kezuri.operators import simulate as simulate_shell  # noqa: E402
from kezuri.operators import turnmill as turnmill_shell  # noqa: E402
from kezuri.toolpath.ir.errors import InputError  # noqa: E402


def run_in_steps(job: common.SteppedJob) -> int:
    steps = 0
    while not job.step():
        steps += 1
        assert steps < 100_000
    return steps


def kezuri_objects():
    collection = bpy.data.collections.get("Kezuri")
    return sorted(o.name for o in collection.objects) if collection else []


def test_stepped_simulation_matches_the_simulation_in_one_go(empty_scene):
    samples.rotary_block(empty_scene)
    whole = simulate_shell.simulate_job(empty_scene, "ROTARY", cell=0.25)
    job = common.SteppedJob(simulate_shell.simulation_request(empty_scene, "ROTARY", cell=0.25), step_seconds=0.0)
    steps = run_in_steps(job)
    stepped = job.result()
    assert steps >= 5                                   # parked at its progress calls, not run in one go
    assert job.fraction == pytest.approx(1.0)
    assert np.array_equal(stepped.result.heightfield.heights, whole.result.heightfield.heights)
    assert stepped.result.removed_volume_mm3 == pytest.approx(whole.result.removed_volume_mm3)


def test_work_runs_only_inside_a_step(empty_scene):
    from kezuri.operators import plancache
    samples.turnmill_part(empty_scene)
    plancache.cache_of(empty_scene).clear()         # a plan kept from an earlier test would finish at once
    request = turnmill_shell.turnmill_request(empty_scene, bpy.context.evaluated_depsgraph_get())
    job = common.SteppedJob(request, step_seconds=0.0)
    assert not job.step()
    seen = job.fraction
    time.sleep(0.3)                                     # the UI's idle time between timer events
    assert job.fraction == seen and not job.done
    run_in_steps(job)
    assert job.result().plan.program.operations


def test_cancel_stops_the_work_and_leaves_the_scene_as_it_was(empty_scene):
    samples.rotary_block(empty_scene)
    before = kezuri_objects()
    job = common.SteppedJob(simulate_shell.simulation_request(empty_scene, "ROTARY", cell=0.1), step_seconds=0.0)
    for _ in range(3):
        assert not job.step()
    assert 0.0 < job.fraction < 1.0
    job.cancel()
    assert job.done and job.cancelled and job.result() is None
    assert not any(t.name == "kezuri-job" and t.is_alive() for t in threading.enumerate())
    assert kezuri_objects() == before


def test_an_input_error_in_the_work_is_raised_on_the_main_thread():
    def compute(progress):
        progress(0.5, "half way")
        raise InputError("pocket 'A': the outline is open")

    job = common.SteppedJob(compute, step_seconds=0.0)
    run_in_steps(job)
    with pytest.raises(InputError, match="outline is open"):
        job.result()


def test_operators_read_the_scene_before_and_write_it_after(empty_scene):
    """prepare() adds nothing to the scene; running the operator directly still works in one go."""
    samples.rotary_block(empty_scene)
    before = kezuri_objects()
    operator_class = simulate_shell.KEZURI_OT_simulate
    assert issubclass(operator_class, common.SteppedOperator)
    simulate_shell.simulation_request(empty_scene, "ROTARY")
    assert kezuri_objects() == before
    assert bpy.ops.kezuri.simulate(workflow="ROTARY") == {"FINISHED"}
    assert any(name.startswith("Kezuri Simulated") for name in kezuri_objects())


def slot_program():
    from kezuri.toolpath.ir.program import FEED, Operation, Program, Tool
    xyz = np.array([[0.0, 0.0, -2.0], [40.0, 0.0, -2.0], [40.0, 20.0, -3.0], [0.0, 20.0, -1.0]])
    op = Operation("slots", Tool(1, "ball", 6.0), 10000, np.full(4, FEED), xyz, np.full(4, 600.0),
                   start=np.array([0.0, 0.0, 5.0]))
    return Program("slots", [op])


def test_manifold_simulation_runs_in_a_separate_process_with_the_same_result(empty_scene):
    """The manifold engine holds Python's GIL inside its booleans, so from the UI it runs in a
    child process; what comes back is the same solid as the simulation run here."""
    samples.rotary_block(empty_scene)
    assert isinstance(simulate_shell.simulation_request(empty_scene, "ROTARY", engine="manifold"), common.CoreCall)
    call = common.CoreCall("toolpath.simulate", "simulate",
                           {"program_or_operations": slot_program(), "stock": (-10, -10, -10, 50, 30, 0),
                            "engine": "manifold", "cell": 0.25, "chunk": 1})
    here = call()
    job = common.ProcessJob(call)
    while not job.step():
        time.sleep(0.01)
    there = job.result()
    assert there.engine == "manifold"
    assert 0.0 < job.fraction <= 1.0                     # progress came through the pipe
    assert there.removed_volume_mm3 == pytest.approx(here.removed_volume_mm3, rel=1e-6)
    assert there.solid.volume() == pytest.approx(here.solid.volume(), rel=1e-6)
    assert there.solid.num_tri() == here.solid.num_tri()
    assert [f.message for f in there.findings] == [f.message for f in here.findings]


def test_cancelling_the_process_ends_it_and_leaves_nothing(empty_scene):
    samples.rotary_block(empty_scene)
    before = kezuri_objects()
    job = common.ProcessJob(simulate_shell.simulation_request(empty_scene, "ROTARY", engine="manifold", cell=0.2))
    time.sleep(0.5)
    assert not job.step()
    job.cancel()
    assert job._process.poll() is not None and job.result() is None
    assert kezuri_objects() == before


def test_an_input_error_in_the_process_comes_back_as_itself():
    from kezuri.toolpath import simulate as core
    job = common.ProcessJob(common.CoreCall("toolpath.simulate", "simulate",
                                            {"program_or_operations": [], "stock": (0, 0, 0, 10, 10, 5),
                                             "cell": -1.0}))
    while not job.step():
        time.sleep(0.02)
    with pytest.raises(core.SimulationError, match="cell must be a positive number"):
        job.result()
