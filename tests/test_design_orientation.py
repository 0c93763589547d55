"""An inside-out design mesh (every normal pointing inward) is planned as the gate checks it
(issue 27, "Meshes"): the carving flips its faces by the gate's rule (a closed mesh's signed
volume; an open relief's projected area) and says so in the job's warnings and the program's
notes, and cuts what the same mesh with outward normals cuts."""
import numpy as np
import pytest

from kezuri.toolpath.engines import meshdata
from kezuri.toolpath.job import Job, JobOperation, Setup, plan_job
from kezuri.toolpath.operations.carve import carve, carve_samples
from kezuri.toolpath.operations.carve.kind import CarveGeometry
from kezuri.toolpath.simulate import BoxStock, checks

FLIP = "the design mesh was inside out (its normals pointed inward); its faces were flipped"


def planned(vertices, faces):
    settings = carve.CarveSettings(rough=False, steep_cleanup=False, scallop=0.05, sample_spacing=1.0)
    operation = JobOperation("carve", "carve", settings, CarveGeometry(vertices, faces))
    return plan_job(Job(Setup(name="relief"), (operation,))).parts[0]


def cutting_moves(part):
    return np.concatenate([op.xyz for op in part.operations])


def test_an_inside_out_closed_relief_is_flipped_with_a_warning_and_cut_as_the_right_one():
    vertices, faces = carve_samples.wave_relief(cell=2.0)
    right = planned(vertices, faces)
    wrong = planned(vertices, faces[:, ::-1].copy())
    assert FLIP not in right.warnings
    assert wrong.warnings[0] == FLIP and wrong.notes[0] == FLIP
    # the wave's flanks: 3 mm amplitude over a 60 mm wavelength slope up to atan(3 * 2 pi / 50) = 20.6 deg
    assert right.result.result.raster_slope_deg > 15.0
    assert wrong.result.result.raster_slope_deg == right.result.result.raster_slope_deg
    assert np.array_equal(cutting_moves(wrong), cutting_moves(right))


def test_planning_and_the_gate_read_the_orientation_alike():
    vertices, faces = carve_samples.wave_relief(cell=4.0)
    stock = BoxStock(*vertices.min(axis=0), *vertices.max(axis=0))
    for wound, expect_flip in ((faces, False), (faces[:, ::-1].copy(), True)):
        _, warnings = checks.check_design_mesh(type("D", (), {"vertices": vertices, "faces": wound})(), stock)
        assert bool(warnings) is expect_flip
        assert meshdata.inside_out(vertices, wound) is expect_flip


def test_an_open_relief_looking_down_is_inside_out():
    # a 10 x 10 mm square surface, two triangles: counter-clockwise from above looks up
    vertices = np.array([[0, 0, 0], [10, 0, 0], [10, 10, 1], [0, 10, 1]], float)
    up = np.array([[0, 1, 2], [0, 2, 3]])
    assert not meshdata.inside_out(vertices, up)
    assert meshdata.inside_out(vertices, up[:, ::-1])
    assert meshdata.signed_volume(*carve_samples.wave_relief(cell=4.0)) == pytest.approx(
        120 * 80 * 15 - 4 * 120 * 80, rel=0.02)       # 15 mm deep box less the 4 mm the mean top lies down
