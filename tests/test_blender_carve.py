"""Carving in Blender and batch: the panel, Generate/Export through the operators, the
Simulate operator's setup, and ``batch.py carve`` with the built-in design and an STL."""
import json

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

import rs274  # noqa: E402
from kezuri.operators import carve as shell  # noqa: E402
from kezuri.operators import panels  # noqa: E402
from kezuri.toolpath.operations.carve import carve_samples  # noqa: E402
from kezuri.toolpath import simulate as sim  # noqa: E402
from blender_helpers import draw_panel, run_batch  # noqa: E402


@pytest.fixture
def scene(empty_scene):
    assert bpy.ops.kezuri.carve_sample(sample="wave") == {"FINISHED"}
    props = empty_scene.kezuri.carve
    props.scallop = 0.05          # a coarser job keeps the test quick
    props.step_down = 4.0
    return empty_scene


def test_carve_panel(scene):
    layout = draw_panel(panels.KEZURI_PT_carve, bpy.context)
    assert {"design", "scallop", "raster_angle"} <= set(layout.props)
    assert {"kezuri.carve_sample", "kezuri.carve_generate", "kezuri.carve_export"} <= set(layout.operators)


def test_sample_is_the_design_in_millimetres(scene):
    design = scene.kezuri.carve.design
    vertices, faces = carve_samples.wave_relief()
    assert len(design.data.vertices) == len(vertices) and len(design.data.polygons) == len(faces)
    co = np.array([v.co for v in design.data.vertices]) * scene.unit_settings.scale_length * 1000
    assert co == pytest.approx(vertices, abs=1e-4)


def test_generate_export_and_simulate(scene, tmp_path):
    assert bpy.ops.kezuri.carve_generate() == {"FINISHED"}
    names = {o.name for o in bpy.data.collections["Kezuri"].objects}
    assert {"Kezuri Carve roughing", "Kezuri Carve finishing"} <= names
    path = tmp_path / "relief.ngc"
    assert bpy.ops.kezuri.carve_export(filepath=str(path), post="linuxcnc") == {"FINISHED"}
    if rs274.available():
        kinds, points, _ = rs274.motion_endpoints(rs274.run(path.read_text()))
        assert points[:, 2].min() >= -15.0 - 1e-6
    job = shell.run_carve(scene, bpy.context.evaluated_depsgraph_get())
    setup = shell.simulation(job)
    result = sim.simulate(setup.program, setup.stock, **setup.extra)
    assert result.findings == []
    assert bpy.ops.kezuri.simulate(workflow="CARVE") == {"FINISHED"}


def test_a_design_in_metres_gives_the_same_program(scene):
    mm_job = shell.run_carve(scene, bpy.context.evaluated_depsgraph_get())
    scene.unit_settings.scale_length = 1.0
    scene.kezuri.carve.design.scale = (0.001, 0.001, 0.001)
    bpy.context.view_layer.update()
    m_job = shell.run_carve(scene, bpy.context.evaluated_depsgraph_get())
    for a, b in zip(mm_job.result.program.operations, m_job.result.program.operations):
        assert len(a) == len(b) and np.allclose(a.xyz, b.xyz, atol=1e-6)


def test_no_design_is_a_clear_error(empty_scene):
    with pytest.raises(RuntimeError, match="design"):
        bpy.ops.kezuri.carve_generate()


def test_batch_carve_report(tmp_path):
    done = run_batch("carve", "--post", "linuxcnc", "--scallop", "0.04", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((tmp_path / "report.json").read_text())
    assert [(op["name"], op["tool_kind"]) for op in report["operations"]] == [("roughing", "flat"),
                                                                              ("finishing", "ball")]
    assert report["simulation"]["gouges"] == [] and report["simulation"]["rapid_collisions"] == []
    assert report["scallop"]["max_scallop_mm"] <= 0.04 + 1e-9
    for name in ("carve.ngc", "design.stl", "carve.png", "carve-toolpaths.png"):
        assert (tmp_path / name).stat().st_size > 1000
    if rs274.available():
        rs274.run((tmp_path / "carve.ngc").read_text())


def test_batch_carve_from_an_stl(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    vertices, faces = carve_samples.domed_plate(cell=2.0)
    stl = tmp_path / "dome.stl"
    trimesh.Trimesh(vertices, faces, process=False).export(str(stl))
    out = tmp_path / "out"
    done = run_batch("carve", "--mesh", str(stl), "--post", "fanuc", "--scallop", "0.05", "--angle", "45",
                     "--out", str(out))
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((out / "report.json").read_text())
    assert report["simulation"]["gouges"] == []
    assert report["stock"] == pytest.approx([-80, -30, -12, 80, 30, float(vertices[:, 2].max())], abs=1e-4)
    bad = run_batch("carve", "--mesh", str(tmp_path / "missing.stl"), "--out", str(out))
    assert bad.returncode == 2 and "missing.stl" in bad.stderr
