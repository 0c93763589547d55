"""The export gate: a program the simulation finds fault with is not written unless the user
overrides it knowingly (batch --allow-findings, the panel's "Write Despite Findings"), and the
report says so.

The faulty job is a file written here in the ISO 14649 conventions of our own writer, with one
edit a hand-editing user or another generator makes: the pocket sits 10 mm below the top of its
BLOCK, so the rapids down to its retract plane (5 mm above the pocket) run through material."""
import json
import os

import numpy as np
import pytest

from kezuri.toolpath import simulate, stepnc
from kezuri.toolpath.program import Operation, Program, Tool
from kezuri.toolpath.stepnc.solids import stock_box

BOX = simulate.BoxStock(0.0, 0.0, -20.0, 40.0, 40.0, 0.0)


def raised_block_file(folder) -> str:
    pockets = [stepnc.PocketSpec("POCKET1", ((10, 10), (50, 10), (50, 40), (10, 40)), 8.0)]
    text = stepnc.pockets_to_part21(((0, 0, -20), (120, 80, 10)), pockets, Tool(1, "flat", 6.0, flute_length=20.0),
                                    name="RAISED BLOCK")
    placed = "('POCKET1',(30.,25.,10.))"
    assert text.count(placed) == 1
    path = os.path.join(str(folder), "raised.stp")
    with open(path, "w", encoding="ascii") as stream:
        stream.write(text.replace(placed, "('POCKET1',(30.,25.,0.))"))
    return path


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
    from kezuri.operators import convert, gate, stepnc as shell
    loaded = stepnc.load_workplan(raised_block_file(tmp_path))
    program = stepnc.to_program(loaded)
    setup = shell.simulation((loaded, program, convert.WorkFrame(1.0, (0.0, 0.0, 0.0))))
    assert setup.stock.z1 == pytest.approx(10.0)                   # the BLOCK's top, from the file
    with pytest.raises(gate.GateRefused) as refused:
        gate.check(setup)
    kinds = {f.kind for f in refused.value.findings}
    assert kinds == {"rapid_in_material"}
    # Each rapid down from the 20 mm security plane to Z 5 meets the block's top at Z 10: 5 mm in.
    assert max(f.depth_mm for f in refused.value.findings) == pytest.approx(5.0, abs=0.01)
    assert "rapid move 0 runs 5.000 mm into material" in str(refused.value)
    _, report = gate.check(setup, True)
    assert report["overridden"] and len(report["findings"]) == len(refused.value.findings)
    _, report = gate.check(setup, gate.signature(refused.value.findings))
    assert report["overridden"]
    with pytest.raises(gate.GateRefused):
        gate.check(setup, gate.signature(refused.value.findings[:1]))   # acknowledging some is not all


def test_batch_writes_nothing_and_exits_3_unless_allowed(tmp_path):
    from blender_helpers import run_batch
    path = raised_block_file(tmp_path)
    out = tmp_path / "refused"
    done = run_batch("stepnc", "--input", path, "--out", str(out))
    assert done.returncode == 3, done.stderr[-2000:]
    assert "not written: the simulation found" in done.stderr and "Traceback" not in done.stderr
    assert not (out / "stepnc.nc").exists() and not (out / "report.json").exists()
    out = tmp_path / "allowed"
    done = run_batch("stepnc", "--input", path, "--allow-findings", "--out", str(out))
    assert done.returncode == 0, done.stderr[-2000:]
    report = json.loads((out / "report.json").read_text())
    assert report["gate"]["overridden"] is True
    assert {f["kind"] for f in report["gate"]["findings"]} == {"rapid_in_material"}
    assert (out / "stepnc.nc").exists()


def test_the_panel_override_covers_the_findings_it_was_given(empty_scene, tmp_path):
    from kezuri.operators import stepnc as shell
    path = raised_block_file(tmp_path)
    shell.fill_workplan_list(empty_scene, path, stepnc.load_workplan(path))
    nc = str(tmp_path / "panel.nc")
    with pytest.raises(RuntimeError, match="not written: the simulation found 4 fault"):   # an ERROR report
        bpy.ops.kezuri.stepnc_export(filepath=nc, post="fanuc")
    assert not os.path.exists(nc)
    props = empty_scene.kezuri.simulation
    props.cell = 0.25                  # the override names moves, not positions: the gate's 0.1 mm check matches
    assert bpy.ops.kezuri.simulate(workflow="STEPNC") == {"FINISHED"}
    assert sum(f.blocking for f in props.findings) == 4
    props.allow_findings = True
    assert props.acknowledged.count("rapid_in_material") == 4
    assert bpy.ops.kezuri.stepnc_export(filepath=nc, post="fanuc") == {"FINISHED"}
    assert os.path.exists(nc)
    assert bpy.ops.kezuri.simulate(workflow="STEPNC") == {"FINISHED"}     # a new simulation: a new decision
    assert props.allow_findings is False and props.acknowledged == ""
