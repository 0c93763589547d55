"""The export gate: a program the simulation finds fault with is not written unless the user
overrides it knowingly (batch --allow-findings, the panel's "Write Despite Findings"), and the
report says so.

The faulty job is NIST's ISO 14649 Example 1 with one attribute changed, as a user or another
generator would write it: the DRILLING of the through hole HOLE1 asks for an overcut_length of
12 mm, so the 20 mm drill goes 12 mm below the stock's bottom (the hole's depth plane, Z -30),
4 mm deeper than the point length and 2 mm of the through-hole rule: into the fixture."""
import json
import math
import os

import numpy as np
import pytest

from kezuri.toolpath import simulate
from kezuri.toolpath.operations import stepnc
from kezuri.toolpath.ir.program import Operation, Program, Tool
from kezuri.toolpath.operations.stepnc.solids import stock_box

BOX = simulate.BoxStock(0.0, 0.0, -20.0, 40.0, 40.0, 0.0)


FIXTURES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fixtures", "iso14649")
DRILLING = "#20= DRILLING($,$,'DRILL HOLE1',10.000,$,#44,#45,#41,$,"
OVERCUT = 12.0
DRILL_RADIUS = 10.0                           # HOLE1's 20 mm twist drill
POINT = DRILL_RADIUS * math.tan(math.radians(31.0)) + 2.0   # ex1 gives tool_top_angle 31: the workplan's rule


def overcut_file(folder) -> str:
    with open(os.path.join(FIXTURES, "ex1.stp"), encoding="latin-1") as stream:
        text = stream.read()
    assert text.count(DRILLING) == 1
    path = os.path.join(str(folder), "ex1-overcut.stp")
    with open(path, "w", encoding="latin-1") as stream:
        stream.write(text.replace(DRILLING, DRILLING[:-2] + f"{OVERCUT:.1f},"))
    return path


def planned_workplan(path):
    """A file's workplan as the shell plans it (a job of one STEP-NC operation), in the work frame."""
    from kezuri.operators import convert, stepnc as shell
    from kezuri.toolpath.engines.textfile import read_text
    from kezuri.toolpath.job import Job, JobOperation, Setup, plan_job
    from kezuri.toolpath.operations.stepnc.kind import StepncGeometry, StepncSettings
    job = Job(Setup(name=""), (JobOperation("stepnc", "stepnc", StepncSettings(), StepncGeometry(read_text(path))),))
    return shell.WorkplanJob(plan_job(job).parts[0], convert.WorkFrame(1.0, (0.0, 0.0, 0.0)))


def drill(depth: float, rpm: float = 3000.0) -> Operation:
    return Operation("drill", Tool(1, "drill", 8.0), rpm, [0, 1, 1, 0], [[20, 20, 5], [20, 20, 0], [20, 20, depth],
                                                                        [20, 20, 5]], [np.nan, 100, 100, np.nan])


def test_a_drill_through_the_fixture_is_found_as_deep_as_it_goes():
    found = simulate.blocking(simulate.simulate(Program("p", [drill(-25.0)]), BOX, cell=0.5).findings)
    assert [f.kind for f in found] == ["below_stock"]
    assert found[0].depth_mm == pytest.approx(5.0) and found[0].move == 2
    # A drill breaking through onto a spoil board by less than the clearance is fine.
    assert not simulate.simulate(Program("p", [drill(-25.0)]), BOX, cell=0.5, fixture_clearance=5.5).findings
    with pytest.raises(simulate.SimulationError, match="fixture clearance"):
        simulate.simulate(Program("p", [drill(-5.0)]), BOX, fixture_clearance=-1.0)


def test_cutting_with_the_spindle_stopped_is_found():
    found = simulate.simulate(Program("p", [drill(-5.0, rpm=0.0)]), BOX, cell=0.5).findings
    assert [(f.kind, f.move) for f in found] == [("spindle_stopped", 1)]
    assert found[0] in simulate.blocking(found)


bpy = pytest.importorskip("bpy")


def test_the_gate_refuses_and_an_override_must_name_the_findings(tmp_path):
    from kezuri.operators import gate, stepnc as shell
    setup = shell.simulation(planned_workplan(overcut_file(tmp_path)))
    assert setup.stock.z0 == pytest.approx(-30.0)                 # HOLE1's depth plane
    assert setup.extra["fixture_clearance"] == pytest.approx(POINT + 0.01, abs=1e-6)
    with pytest.raises(gate.GateRefused) as refused:
        gate.check(setup)
    found = refused.value.findings
    assert [f.kind for f in found] == ["below_stock"]
    assert found[0].depth_mm == pytest.approx(OVERCUT, abs=1e-6)
    assert "12.000 mm below the stock's bottom" in str(refused.value)
    _, report = gate.check(setup, True)
    assert report["overridden"] and len(report["findings"]) == 1
    _, report = gate.check(setup, gate.signature(found))
    assert report["overridden"]
    with pytest.raises(gate.GateRefused):
        gate.check(setup, "below_stock 0:0")                       # another move is not this one
    # The file without the overcut: the drill stops at the rule's breakthrough and the gate is quiet.
    _, report = gate.check(shell.simulation(planned_workplan(os.path.join(FIXTURES, "ex1.stp"))))
    assert report["findings"] == [] and not report["overridden"]


def test_batch_writes_nothing_and_exits_3_unless_allowed(tmp_path):
    from blender_helpers import run_batch
    path = overcut_file(tmp_path)
    out = tmp_path / "refused"
    done = run_batch("stepnc", "--input", path, "--out", str(out))
    assert done.returncode == 3, done.stderr[-2000:]
    assert "not written: the simulation found 1 fault" in done.stderr and "Traceback" not in done.stderr
    assert not out.exists() or not any(out.iterdir())
    out = tmp_path / "allowed"
    done = run_batch("stepnc", "--input", path, "--allow-findings", "--out", str(out))
    assert done.returncode == 0, done.stderr[-2000:]
    report = json.loads((out / "report.json").read_text())
    assert report["gate"]["overridden"] is True
    assert [(f["kind"], f["depth_mm"]) for f in report["gate"]["findings"]] == [("below_stock", OVERCUT)]
    assert (out / "stepnc.nc").exists()


def test_the_panel_override_covers_the_findings_it_was_given(empty_scene, tmp_path):
    from kezuri.operators import stepnc as shell
    path = overcut_file(tmp_path)
    shell.fill_workplan_list(empty_scene, path, stepnc.load_workplan(path))
    nc = str(tmp_path / "panel.nc")
    with pytest.raises(RuntimeError, match="not written: the simulation found 1 fault"):   # an ERROR report
        bpy.ops.kezuri.stepnc_export(filepath=nc, post="fanuc")
    assert not os.path.exists(nc)
    props = empty_scene.kezuri.simulation
    props.cell = 0.25                  # the override names moves, not positions: the gate's 0.1 mm check matches
    assert bpy.ops.kezuri.simulate(workflow="STEPNC") == {"FINISHED"}
    assert sum(f.blocking for f in props.findings) == 1
    props.allow_findings = True
    assert props.acknowledged.startswith("below_stock ")
    assert bpy.ops.kezuri.stepnc_export(filepath=nc, post="fanuc") == {"FINISHED"}
    assert os.path.exists(nc)
    assert bpy.ops.kezuri.simulate(workflow="STEPNC") == {"FINISHED"}     # a new simulation: a new decision
    assert props.allow_findings is False and props.acknowledged == ""


def test_the_gate_checks_every_move_against_the_machine_profile():
    """ISO 14649 Example 1 (a 100 x 60 mm plate) on machines too small for it: the gate names the
    axis, the program's extent and the machine's travel; the reach is checked against the highest
    Z written (the security plane and the frames' clearance height)."""
    from kezuri.operators import gate, stepnc as shell
    from kezuri.toolpath.ir import machine
    job = planned_workplan(os.path.join(FIXTURES, "ex1.stp"))
    program = job.program
    setup = shell.simulation(job)
    points = np.vstack([np.vstack([op.start, op.xyz]) for op in program.operations])
    heights = [max(op.safe_z, op.clearance_z) for op in program.operations]
    span = points.max(axis=0) - points.min(axis=0)
    top = max(points[:, 2].max(), *heights)
    router = machine.preset("grbl-router")
    _, report = gate.check(setup, machine=router)                  # fits: 800 x 800 x 100 mm, 60 mm reach
    assert report["findings"] == []
    small = router.replace(travel=(float(np.floor(span[0])) - 1.0, 800.0, 100.0))
    with pytest.raises(gate.GateRefused) as refused:
        gate.check(setup, machine=small)
    assert [f.kind for f in refused.value.findings] == ["travel"]
    assert f"spans {span[0]:.3f} mm along X" in str(refused.value)
    assert f"more than the {small.travel[0]:g} mm X travel of the machine 'Hobby router (GRBL)'" in str(refused.value)
    _, report = gate.check(setup, True, machine=small)
    assert report["overridden"] and report["findings"][0]["kind"] == "travel"
    # the frames lift to the clearance height (20 mm on the router): a reach below it is refused
    low = router.replace(clearance_max=top - 1.0, clearance_z=min(router.clearance_z, top - 1.0))
    found = gate.machine_findings(program, low)
    assert [f.kind for f in found] == ["travel"]
    assert f"lifts Z to {top:.3f} mm above the work zero, higher than the {top - 1.0:g} mm" in found[0].message
