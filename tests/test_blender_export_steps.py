"""Every Export operator runs its work in steps with Esc to cancel (issue 27): the export operators
are stepped operators; reading the scene writes nothing; the work (plan, the export gate, the file)
driven a step at a time by SteppedJob, as the modal operator drives it, writes the same program as
the operator run at once, and cancelled half way writes nothing.  STEP-NC's Generate is stepped too.

The window manager's modal loop itself needs a window (not in background mode): the Esc key is
SteppedOperator.modal calling SteppedJob.cancel, which these tests call."""
import os
import threading

import pytest

bpy = pytest.importorskip("bpy")

from kezuri.operators import carve as carve_shell  # noqa: E402
from kezuri.operators import common, exporting, joblist, samples, stepnc  # noqa: E402
from kezuri.operators import engrave as engrave_shell  # noqa: E402
from kezuri.operators import plancache  # noqa: E402
from kezuri.operators import rotary as rotary_shell  # noqa: E402
from kezuri.operators import turnmill as turnmill_shell  # noqa: E402
from kezuri.operators.workflows import WORKFLOWS  # noqa: E402

FIXTURES = os.environ.get("KEZURI_FIXTURES", os.path.join(os.path.dirname(__file__), "fixtures"))
EX1 = os.path.join(FIXTURES, "iso14649", "ex1.stp")


def export_classes() -> list:
    found = {cls for workflow in WORKFLOWS for cls in workflow.classes if issubclass(cls, exporting.NCExport)}
    return sorted(found | {joblist.KEZURI_OT_job_export}, key=lambda cls: cls.bl_idname)


def test_every_nc_export_and_every_generate_is_a_stepped_operator():
    exports = export_classes()
    assert {cls.bl_idname for cls in exports} >= {"kezuri.engrave_export", "kezuri.carve_export",
                                                  "kezuri.rotary_export", "kezuri.stepnc_export",
                                                  "kezuri.turnmill_export", "kezuri.job_export"}
    for cls in exports:
        assert issubclass(cls, common.SteppedOperator), cls.bl_idname
        assert "export_request" in vars(cls), f"{cls.bl_idname} implements its export in steps"
    generates = [cls for workflow in WORKFLOWS for cls in workflow.classes
                 if getattr(cls, "bl_idname", "").endswith("_generate")]
    generates.append(joblist.KEZURI_OT_job_generate)
    assert "kezuri.stepnc_generate" in {cls.bl_idname for cls in generates}
    for cls in generates:
        assert issubclass(cls, common.SteppedOperator), cls.bl_idname


def stepped(work) -> common.SteppedJob:
    job = common.SteppedJob(work, step_seconds=0.0)
    steps = 0
    while not job.step():
        steps += 1
    assert steps >= 3, "the work parked at its progress calls"
    return job


def cancelled_half_way(work) -> common.SteppedJob:
    job = common.SteppedJob(work, step_seconds=0.0)
    for _ in range(3):
        assert not job.step()
    assert 0.0 < job.fraction < 1.0
    job.cancel()
    assert job.done and job.cancelled and job.result() is None
    assert not any(t.name == "kezuri-job" and t.is_alive() for t in threading.enumerate())
    return job


def check_export(tmp_path, request, operator, post="linuxcnc"):
    """``request(path)`` the export's work; ``operator(path)`` the operator at once."""
    path = tmp_path / "stepped.nc"
    work = request(str(path))
    assert not path.exists()                      # reading the scene writes nothing
    cancelled_half_way(work)
    assert not path.exists() and os.listdir(tmp_path) == []
    done = stepped(request(str(path))).result()
    assert isinstance(done, exporting.Exported) and done.path == str(path)
    whole = tmp_path / "whole.nc"
    assert operator(str(whole)) == {"FINISHED"}
    assert path.read_text() == whole.read_text()


def test_engrave_export_in_steps(empty_scene, tmp_path):
    samples.name_plate(empty_scene)
    plancache.cache_of(empty_scene).clear()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    check_export(tmp_path, lambda path: engrave_shell.nc_export_request(empty_scene, depsgraph, "linuxcnc", path),
                 lambda path: bpy.ops.kezuri.engrave_export(filepath=path, post="linuxcnc"))


def test_carve_export_in_steps(empty_scene, tmp_path):
    samples.set_millimetres(empty_scene)
    assert bpy.ops.kezuri.carve_sample(sample="wave") == {"FINISHED"}
    plancache.cache_of(empty_scene).clear()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    check_export(tmp_path, lambda path: carve_shell.nc_export_request(empty_scene, depsgraph, "linuxcnc", path),
                 lambda path: bpy.ops.kezuri.carve_export(filepath=path, post="linuxcnc"))


def test_rotary_export_in_steps(empty_scene, tmp_path):
    samples.rotary_block(empty_scene)
    plancache.cache_of(empty_scene).clear()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    post = "linuxcnc"
    check_export(tmp_path, lambda path: rotary_shell.nc_export_request(empty_scene, depsgraph, post, path),
                 lambda path: bpy.ops.kezuri.rotary_export(filepath=path, post=post))


def test_turnmill_export_in_steps(empty_scene, tmp_path):
    samples.turnmill_part(empty_scene)
    plancache.cache_of(empty_scene).clear()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    post = "xzc"
    check_export(tmp_path, lambda path: turnmill_shell.nc_export_request(empty_scene, depsgraph, post, path),
                 lambda path: bpy.ops.kezuri.turnmill_export(filepath=path, post=post))


def test_stepnc_export_and_generate_in_steps(empty_scene, tmp_path):
    assert bpy.ops.kezuri.import_stepnc(filepath=EX1) == {"FINISHED"}
    check_export(tmp_path, lambda path: _stepnc_work(empty_scene, path),
                 lambda path: bpy.ops.kezuri.stepnc_export(filepath=path, post="linuxcnc"))
    planned = stepped(stepnc.stepnc_request(empty_scene, bpy.context.evaluated_depsgraph_get())).result()
    assert [op.name for op in planned.program.operations][:2] == ["WS FINISH PLANAR FACE1", "WS DRILL HOLE1"]
    assert bpy.ops.kezuri.stepnc_generate() == {"FINISHED"}


def _stepnc_work(scene, path):
    work = stepnc.export_nc_request(scene, "linuxcnc", path)
    return lambda progress=None: exporting.Exported(work(progress)[0])


def test_job_list_export_in_steps_records_the_rows_only_when_done(empty_scene, tmp_path):
    samples.name_plate(empty_scene)
    empty_scene.kezuri.machine.post = "linuxcnc"
    assert bpy.ops.kezuri.job_add(kind="engrave") == {"FINISHED"}
    plancache.cache_of(empty_scene).clear()
    rows = empty_scene.kezuri.job_list.rows
    before = [row.state for row in rows]
    path = tmp_path / "stepped.nc"
    cancelled_half_way(joblist.export_job_request(empty_scene, str(path), "linuxcnc"))
    assert os.listdir(tmp_path) == [] and [row.state for row in rows] == before
    done = stepped(joblist.export_job_request(empty_scene, str(path), "linuxcnc")).result()
    assert [row.state for row in rows] == before          # the scene is written on the main thread, after
    done.then(empty_scene)
    assert [row.state for row in rows] != before
    assert bpy.ops.kezuri.job_export(filepath=str(tmp_path / "whole.nc"), post="linuxcnc") == {"FINISHED"}
    assert path.read_text() == (tmp_path / "whole.nc").read_text()
