"""W6 in Blender and batch: the carved stock of each job, its findings, and any NC file."""
import json

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

from kezuri.operators import panels, samples  # noqa: E402
from kezuri.toolpath.simulate import ncread  # noqa: E402
from kezuri.toolpath.ir.program import Tool  # noqa: E402
from blender_helpers import draw_panel, run_batch  # noqa: E402




@pytest.fixture
def scene(empty_scene):
    scene = empty_scene
    return scene


def test_simulated_name_plate_is_carved_around_untouched_letters(scene):
    samples.name_plate(scene)
    assert bpy.ops.kezuri.simulate(workflow="ENGRAVE") == {"FINISHED"}
    carved = next(o for o in bpy.data.collections["Kezuri"].objects if o.name.startswith("Kezuri Simulated"))
    z = np.array([v.co.z for v in carved.data.vertices])
    assert z.max() == pytest.approx(0.0, abs=1e-6)           # the letters stand at the plate top
    assert z.min() == pytest.approx(-20.0, abs=1e-6)         # the stock's bottom
    floor = z[(z < -0.5) & (z > -5)]
    assert floor.min() >= -2.8 - 0.05                        # nothing deeper than the deepest gouge
    assert len(scene.kezuri.simulation.findings) == 0


def test_rotary_simulation_has_no_findings(scene):
    samples.rotary_block(scene)
    assert bpy.ops.kezuri.simulate(workflow="ROTARY") == {"FINISHED"}
    assert len(scene.kezuri.simulation.findings) == 0


def test_turnmill_simulation_carves_the_bar(scene):
    """The sample bar after the radial and axial operations: the flat at x = 35 and the groove
    (floor radius 36) on its side, the pockets in its end face, and nothing found."""
    samples.turnmill_part(scene)
    assert bpy.ops.kezuri.simulate(workflow="TURNMILL") == {"FINISHED"}
    assert len(scene.kezuri.simulation.findings) == 0
    carved = next(o for o in bpy.data.collections["Kezuri"].objects if o.name.startswith("Kezuri Simulated"))
    v = np.array([tuple(carved.matrix_world @ p.co) for p in carved.data.vertices])
    rho = np.hypot(v[:, 0], v[:, 1])
    assert rho.max() == pytest.approx(42.5, abs=0.01)
    assert v[:, 2].min() == pytest.approx(-60.0, abs=1e-4) and v[:, 2].max() == pytest.approx(0.0, abs=1e-4)
    flat = (np.abs(v[:, 1]) < 5) & (v[:, 0] > 0) & (v[:, 2] < -32) & (v[:, 2] > -43)
    assert v[flat, 0].max() == pytest.approx(35.0, abs=0.1)
    groove = (v[:, 2] < -15.2) & (v[:, 2] > -16.8) & (np.abs(v[:, 0]) < 20) & (v[:, 1] > 0)
    assert rho[groove].max() == pytest.approx(36.0, abs=0.1)
    pocket = (np.abs(v[:, 0] - 20) < 6) & (np.abs(v[:, 1]) < 10)
    assert v[pocket, 2].min() == pytest.approx(-6.0, abs=0.05)


def test_exact_turnmill_simulation_can_go_to_a_child_process(scene):
    """From the panel the exact engine runs in a child process: the turn-mill job's call (the
    program, the bar, the part as the design) must travel there whole."""
    import pickle

    from kezuri.operators import simulate as shell
    samples.turnmill_part(scene)
    call = shell.simulation_request(scene, "TURNMILL", engine="manifold")
    kwargs = pickle.loads(pickle.dumps(call.kwargs))
    assert kwargs["engine"] == "manifold" and kwargs["stock"].radius == pytest.approx(42.5)
    assert [op.direction for op in kwargs["program_or_operations"].operations] == ["radial", "radial", "axial",
                                                                                   "axial"]
    assert len(kwargs["design"].faces) == len(call.kwargs["design"].faces) > 1000


def test_a_gouge_is_listed_and_framed(scene):
    """The name plate checked against a design 1 mm below the top: every cut deeper is a gouge."""
    from kezuri.operators import engrave, simview
    from kezuri.toolpath.operations.engrave import engrave as engrave_core
    from kezuri.toolpath import simulate as core
    samples.name_plate(scene)
    job = engrave.run_engrave(scene, bpy.context.evaluated_depsgraph_get())
    result = core.simulate(job.baked, engrave_core.plate_stock(job.plate.outline, 20.0), cell=0.25, design=-1.0)
    simview.store_findings(scene, simview.SimulationJob(result, job.plate.frame, "engrave"))
    findings = scene.kezuri.simulation.findings
    gouges = [f for f in findings if f.kind == "gouge"]
    assert gouges and max(f.depth_mm for f in result.findings_of("gouge")) == pytest.approx(1.8, abs=0.01)
    layout = draw_panel(panels.KEZURI_PT_simulate, bpy.context)
    assert "kezuri.frame_finding" in layout.operators
    assert bpy.ops.kezuri.frame_finding(index=0) == {"FINISHED"}
    assert tuple(scene.cursor.location) == pytest.approx(tuple(findings[0].location))


def test_nc_reader_follows_our_own_linuxcnc_program():
    text = "%\n(slot)\nG21 G90\nG0 X0 Y0 Z5\nG1 Z-2 F100\nX50\nG2 X60 Y10 I0 J10\nG91 G1 X5\nG90 G0 Z20\nM2\n%\n"
    op, lines = ncread.read_nc(text, Tool(1, "flat", 6.0))
    assert np.allclose(op.xyz, [[0, 0, 5], [0, 0, -2], [50, 0, -2], [60, 10, -2], [65, 10, -2], [65, 10, 20]])
    assert lines == [4, 5, 6, 7, 8, 9]
    assert np.allclose(op.center[3, :2], [50, 10])
    with pytest.raises(ncread.NCReadError, match="line 2"):
        ncread.read_nc("G0 X0\nG2 X10 Y0 R5\n", Tool(1, "flat", 6.0))


def test_batch_simulate_reports_the_nc_line_of_a_rapid_through_the_stock(tmp_path):
    nc = tmp_path / "slot.ngc"
    nc.write_text("G21 G90\nG0 X0 Y0 Z5\nG1 Z-2 F100\nX50\nG0 Z-1\nX100\nM2\n")
    done = run_batch("simulate", "--nc", str(nc), "--tool", "flat:6", "--stock", "box:-10,-10,-10,110,10,0", "--out", str(tmp_path / "out"))
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    simulation = report["simulation"]
    # The slot (flat 6 mm, 50 mm, 2 deep) plus the rapid's 1 mm deep trench: closed forms.
    slot = (50 * 6 + np.pi * 9) * 2
    trench = 50 * 6 * 1
    assert simulation["removed_volume_mm3"] == pytest.approx(slot + trench, rel=0.01)
    assert [r["line"] for r in simulation["rapid_collisions"]] == [6]
    assert (tmp_path / "out" / "simulated.stl").stat().st_size > 1000


def test_batch_engrave_report_has_the_simulation(tmp_path):
    done = run_batch("engrave", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr[-3000:]
    simulation = json.loads((tmp_path / "report.json").read_text())["simulation"]
    assert simulation["engine"] == "heightfield" and simulation["removed_volume_mm3"] > 1000
    assert simulation["gouges"] == [] and simulation["max_gouge_mm"] == 0 and simulation["rapid_collisions"] == []


def test_simulated_stock_is_coloured_by_depth_or_by_operation(scene):
    """The name plate's roughing, band and burr each colour their own surface; the panel's
    Colour switch changes which colours the viewport shows without simulating again."""
    from kezuri.operators import simview as shell
    samples.name_plate(scene)
    assert bpy.ops.kezuri.simulate(workflow="ENGRAVE") == {"FINISHED"}
    carved = next(o for o in bpy.data.collections["Kezuri"].objects if o.name.startswith("Kezuri Simulated"))
    attributes = carved.data.color_attributes
    assert attributes.active_color.name == "Kezuri depth"
    colours = np.empty(len(carved.data.vertices) * 4, np.float32)
    attributes["Kezuri operation"].data.foreach_get("color", colours)
    colours = colours.reshape(-1, 4)
    seen = {tuple(np.round(c, 3)) for c in colours}
    for index in range(3):                       # roughing, band finishing, burr contour
        assert tuple(np.round(shell.OPERATION_COLOURS[index], 3).astype(np.float32)) in seen
    scene.kezuri.simulation.colour_by = "OPERATION"
    assert attributes.active_color.name == "Kezuri operation"
