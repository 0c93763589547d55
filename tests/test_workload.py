"""Work estimates before planning (toolpath/workload.py): every operation kind counts what drives
its planning time and memory from its settings and the size of its geometry, and a job past a
limit is refused in well under a second, naming the operation, the settings with their values,
the estimate against the limit and the value that would do.  The built-in samples stay far below
every limit (a tenth of it at most).  Expected numbers are worked out by hand in the comments."""
import math
import re
import os
import time
from types import SimpleNamespace

import numpy as np
import pytest

from kezuri.toolpath import workload
from kezuri.toolpath.ir.program import Tool
from kezuri.toolpath.job import Job, JobError, JobOperation, Setup, estimate_job, plan_job
from kezuri.toolpath.operations.carve import carve, carve_samples
from kezuri.toolpath.operations.carve.kind import CarveGeometry
from kezuri.toolpath.operations.chamfer.chamfer import ChamferSettings
from kezuri.toolpath.operations.chamfer.kind import ChamferGeometry
from kezuri.toolpath.operations.drill.drill import DrillSettings
from kezuri.toolpath.operations.drill.kind import DrillGeometry
from kezuri.toolpath.operations.engrave.engrave import EngraveSettings
from kezuri.toolpath.operations.engrave.kind import EngraveGeometry
from kezuri.toolpath.operations.pocket.kind import PocketGeometry
from kezuri.toolpath.operations.pocket.pocket import PocketSettings
from kezuri.toolpath.operations.profile.kind import ProfileGeometry
from kezuri.toolpath.operations.profile.profile import ProfileSettings
from kezuri.toolpath.operations.rotary import rotary
from kezuri.toolpath.operations.rotary.kind import RotaryGeometry
from kezuri.toolpath.operations.turnmill import turnmill as tm
from kezuri.toolpath.operations.turnmill.kind import TurnMillGeometry
from kezuri.toolpath.ir.program import GougeTexture
from test_hostile import time_limit

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def square(side, x=0.0, y=0.0):
    h = side / 2
    return np.array([[x - h, y - h], [x + h, y - h], [x + h, y + h], [x - h, y + h]])


def refused(kind, settings, geometry, name="job") -> tuple:
    """The message of planning a job of one operation, and the seconds it took to refuse."""
    started = time.perf_counter()
    with time_limit(20), pytest.raises(workload.WorkloadError) as caught:
        plan_job(Job(Setup(name=name), (JobOperation(kind, kind, settings, geometry),)))
    return str(caught.value), time.perf_counter() - started


def test_counts_are_written_short_and_values_rounded_up():
    assert workload.count(41000) == "41,000"
    assert workload.count(4.1e9) == "4.1e9"
    assert workload.count(2e7) == "2e7"
    assert workload.at_least(0.01412) == "0.015"
    assert workload.at_least(0.8200001) == "0.83"
    assert workload.at_least(3.0) == "3"


def test_carve_finishing_too_fine_is_refused_before_any_dropping():
    v, f = carve_samples.wave_relief()           # 120 x 80 mm
    settings = carve.CarveSettings(scallop=0.0001, sample_spacing=0.01)
    message, seconds = refused("carve", settings, CarveGeometry(v, f, 2.0), "Relief")
    # the 3 mm ball at 0.0001 mm scallop steps 2 sqrt(2 * 1.5 * 0.0001 - 1e-8) = 0.03464 mm; the raster
    # covers 122.1 x 82.1 mm: 3526 lines of 8211 positions = 2.9e7, over 2e7
    assert message.startswith("carve 'Relief': the finishing raster at scallop 0.0001 mm and sample spacing 0.01 mm "
                              "is about 2.9e7 tool positions, over the 2e7 this machine can plan; "
                              "raise sample spacing to 0.015 mm or more"), message
    assert seconds < 10.0


def test_the_suggested_sample_spacing_is_under_the_limit():
    v, f = carve_samples.wave_relief()
    size = tuple(v.max(axis=0) - v.min(axis=0))
    settings = carve.CarveSettings(scallop=0.0001, sample_spacing=0.015)
    (finishing, roughing) = workload.carve("Relief", size, 2.0, settings)
    assert 1.5e7 < finishing.amount < 2e7


def test_carve_roughing_through_a_metre_of_stock_is_refused_up_front():
    v, f = carve_samples.wave_relief()
    message, seconds = refused("carve", carve.CarveSettings(step_down=0.01), CarveGeometry(v, f, 1000.0), "Relief")
    # 1000 mm / 0.01 mm = 100,000 levels; each clears 120 / 2.4 + 1 = 51 lines across the finishing raster,
    # of 80 / 0.5 + 1 = 161 positions (the 6 mm tool's 0.5 mm spacing): 8,211 a level, 8.2e8 in all
    assert "the roughing through 1000 mm of stock above the design at step down 0.01 mm (100,000 levels) is about " \
           "8.2e8 moves, over the 1e7 this machine can plan; raise step down to 0.83 mm or more" in message, message
    assert seconds < 10.0


def plate_geometry(letters=()):
    return EngraveGeometry(plate_outline=(square(200.0),), plate_thickness=10.0, letters=tuple(letters))


def test_engrave_gouges_at_a_tiny_stepover_are_refused():
    settings = EngraveSettings(stepover=0.001, texture=GougeTexture(spacing=0.1))
    message, seconds = refused("engrave", settings, plate_geometry(), "Sign")
    # 40,000 mm2 / 0.001 mm / 0.1 mm = 4e8 gouges
    assert message.startswith("engrave 'Sign': the gouge texture at stepover 0.001 mm and spacing 0.1 mm over "
                              "40000 mm2 is about 4e8 gouges, over the 2e6 this machine can plan; "
                              "raise stepover to 0.2 mm or more"), message
    assert seconds < 10.0


def test_engrave_band_rings_at_a_tiny_band_stepover_are_refused():
    settings = EngraveSettings(band_stepover=1e-5)
    message, _ = refused("engrave", settings, plate_geometry([("K", (square(20.0),))]), "Sign")
    # (4 - 1) mm / 1e-5 mm + 1 = 300,001 rings, 2 levels of 1 mm, round the 80 mm square: 4.8e7 mm
    assert "band stepover 1e-05 mm and band step down 1 mm (300,001 rings, 2 levels round 80 mm of letter " \
           "outlines) is about 4.8e7 mm of path, over the 1e7" in message, message


def test_pocket_path_at_a_tiny_stepover_is_refused():
    settings = PocketSettings(stepover=0.05, depth=5.0, step_down=2.0)
    message, _ = refused("pocket", settings, PocketGeometry((square(1000.0),), name="tray"))
    # 1e6 mm2 / 0.05 mm x 3 levels = 6e7 mm
    assert message.startswith("pocket 'tray': 1000000 mm2 at stepover 0.05 mm and step down 2 mm (3 levels) is about "
                              "6e7 mm of path, over the 1e7 this machine can plan; raise stepover to 0.3 mm"), message


def test_profile_path_round_a_ten_metre_panel_at_a_tiny_step_down_is_refused():
    settings = ProfileSettings(tool=Tool(1, "flat", 6.0, flute_length=30.0), step_down=0.01)
    message, _ = refused("profile", settings, ProfileGeometry((square(10000.0),), thickness=9.7, name="panel"))
    # 40,000 mm of outline x ceil(10 / 0.01) = 1000 levels (9.7 + 0.3 breakthrough) = 4e7 mm
    assert message.startswith("profile 'panel': 40000 mm of outline at step down 0.01 mm (1,000 levels) is about "
                              "4e7 mm of path, over the 1e7"), message


def test_chamfer_of_an_outline_of_millions_of_points_is_refused():
    t = np.linspace(0, 2 * math.pi, 2_500_000, endpoint=False)
    loop = np.column_stack([50 * np.cos(t), 50 * np.sin(t)])
    message, seconds = refused("chamfer", ChamferSettings(), ChamferGeometry((loop,)), "edge")
    assert "chamfer 'edge': the drawing is about 2.5e6 outline points, over the 2e6" in message, message
    assert seconds < 10.0


def grid_holes(n):
    side = math.ceil(math.sqrt(n))
    return tuple((10.0 * (k % side), 10.0 * (k // side)) for k in range(n))


def test_too_many_holes_to_order_are_refused_and_the_given_order_is_the_way_out():
    holes = grid_holes(25_000)
    message, seconds = refused("drill", DrillSettings(), DrillGeometry(holes), "rack")
    assert message.startswith("drill 'rack': the shortest order of its holes is about 25,000 holes to order, over the "
                              "20,000 this machine can plan; set the order to 'given'"), message
    assert seconds < 10.0
    (estimate,) = [e for _, found in estimate_job(Job(Setup(name="rack"), (
        JobOperation("drill", "drill", DrillSettings(order="given"), DrillGeometry(holes)),))) for e in found
        if e.key == "drill holes"]
    assert estimate.amount == 25_000 and not estimate.over


def test_pecks_too_fine_for_many_deep_holes_are_refused():
    settings = DrillSettings(tool=Tool(4, "drill", 5.0, flute_length=150.0), depth=100.0, peck=0.05, order="given")
    message, _ = refused("drill", settings, DrillGeometry(grid_holes(1000)), "rack")
    # 1000 holes x 100 / 0.05 = 2e6 pecks
    assert "1,000 holes 100 mm deep at peck 0.05 mm is about 2e6 pecks, over the 1e6" in message, message
    assert "raise peck to 0.1 mm or more" in message


def test_a_rotary_pocket_at_the_finest_spacing_is_refused_before_planning():
    block, pockets = rotary.sample_job()
    settings = rotary.RotarySettings(spacing=0.01, step_down=0.01)
    message, seconds = refused("rotary", settings, RotaryGeometry(block, (pockets[2],)))
    assert message.startswith("pocket 'bowl': the toolpath at a spacing of 0.01 mm and a step down of 0.01 mm is about ")
    assert "path points, over the 5e6 this machine can plan; raise spacing to" in message
    assert seconds < 10.0


def test_a_turn_mill_mesh_of_many_faces_at_a_fine_sample_spacing_is_refused():
    import trimesh
    sphere = trimesh.creation.icosphere(subdivisions=6, radius=20.0)       # 81,920 faces of ~0.06 mm2
    settings = tm.TurnMillSettings(sample_spacing=0.01)
    geometry = TurnMillGeometry(np.asarray(sphere.vertices), np.asarray(sphere.faces), tm.Stock(25.0, -25.0, 25.0))
    message, seconds = refused("turnmill", settings, geometry, "ball")
    # each face at k = 16 (the cap): 81,920 x 256 = 2.1e7 samples
    assert message.startswith("turn-mill 'ball': 81,920 faces at sample spacing 0.01 mm is about 2.1e7 "
                              "classification samples, over the 5e6"), message
    assert seconds < 10.0


def test_a_part21_file_past_200_mb_is_refused_by_its_size():
    with pytest.raises(workload.WorkloadError, match=r"the STEP-NC file 'x' is about 3e8 bytes, over the 2e8"):
        workload.stepnc("x", 300_000_000)


def test_in_a_job_of_several_operations_the_estimate_names_the_operation_before_any_planning():
    v, f = carve_samples.wave_relief()
    job = Job(Setup(name="sign"), (
        JobOperation("drill", "holes", DrillSettings(), DrillGeometry(((0.0, 0.0), (10.0, 0.0)))),
        JobOperation("carve", "relief", carve.CarveSettings(step_down=0.01), CarveGeometry(v, f, 1000.0))))
    started = time.perf_counter()
    with time_limit(20), pytest.raises(JobError, match=r"^operation 'relief': carve 'sign': the roughing"):
        plan_job(job)
    assert time.perf_counter() - started < 10.0


def far_below(estimates):
    for estimate in estimates:
        assert estimate.amount < estimate.limit.most / 10, (estimate.key, estimate.amount)
    return len(estimates)


def test_the_core_samples_are_far_below_every_limit():
    checked = 0
    for make in (carve_samples.wave_relief, carve_samples.domed_plate, carve_samples.steep_ridge,
                 carve_samples.walled_block, carve_samples.vertical_block):
        v, f = make()
        checked += far_below(workload.carve("sample", tuple(v.max(axis=0) - v.min(axis=0)), 5.0,
                                            carve.CarveSettings()))
    block, pockets = rotary.sample_job()
    for _, found in estimate_job(Job(Setup(), (JobOperation("rotary", "pockets", rotary.RotarySettings(),
                                                            RotaryGeometry(block, tuple(pockets))),))):
        checked += far_below(found)
    v, f, stock = tm.sample_part(192)
    for _, found in estimate_job(Job(Setup(), (JobOperation("turnmill", "part", tm.TurnMillSettings(),
                                                            TurnMillGeometry(v, f, stock)),))):
        checked += far_below(found)
    assert checked == 10 + 3 + 1


@pytest.mark.parametrize("name", sorted(n for n in os.listdir(os.path.join(ROOT, "samples", "jobs"))
                                        if n.endswith(".toml")))
def test_the_sample_jobs_are_far_below_every_limit(name):
    pytest.importorskip("bpy")
    import batch  # noqa: F401  (the package loaded as kezuri, registered)
    from kezuri.operators import jobfile
    from kezuri.operators.preferences import scene_post
    batch.load_extension()
    path = os.path.join(ROOT, "samples", "jobs", name)
    if os.path.exists(path[:-len(".toml")] + ".csv"):
        pytest.skip("a template: its rows fill it in")
    data = jobfile.read(path)
    setup_table = data.get("setup", {})
    scene = jobfile.scene_for(setup_table, path)
    post_name = setup_table.get("post") or scene_post(scene)
    jobfile.apply_setup(scene, setup_table, path)
    job, _, _ = jobfile.job_of(scene, jobfile.entries(data, scene, path), "sample", post_name, path)
    found = estimate_job(job)
    assert len(found) == len([op for op in job.operations if op.enabled])
    for _, estimates in found:
        far_below(estimates)


def test_batch_refuses_a_job_past_a_limit_with_exit_2_naming_the_operation_and_writes_nothing(tmp_path):
    pytest.importorskip("bpy")
    from test_batch_job import run
    text = open(os.path.join(ROOT, "samples", "jobs", "nameplate-with-holes.toml"), encoding="utf-8").read()
    text = text.replace("settings = { seed = 7 }", "settings = { seed = 7, stepover = 0.001, spacing = 0.1 }")
    assert "stepover = 0.001" in text
    job = tmp_path / "fine.toml"
    job.write_text(text, encoding="utf-8")
    started = time.perf_counter()
    status, message, out = run("job", str(job), out=str(tmp_path / "out"))
    assert status == 2, message[-2000:]
    assert "operation 'texture and letters': engrave 'nameplate': the gouge texture at stepover 0.001 mm and spacing " \
           "0.1 mm over" in message and "gouges, over the 2e6 this machine can plan; raise stepover to" in message, message
    assert "Traceback" not in message
    assert time.perf_counter() - started < 60
    assert not os.path.exists(out)


def test_every_refusal_comes_out_in_japanese_with_no_english_left():
    """Each part of a refusal (what, the quantity, the advice) has its own Japanese template: the
    whole message, and the same inside a job of several operations, keeps only names, numbers and
    units in Latin letters."""
    pytest.importorskip("bpy")
    from kezuri.operators import translations
    s = SimpleNamespace
    calls = [
        lambda: workload.carve("Relief", (120, 80, 14), 2.0, carve.CarveSettings(scallop=0.0001, sample_spacing=0.01)),
        lambda: workload.carve("Relief", (120, 80, 14), 1000.0, carve.CarveSettings(step_down=0.01)),
        lambda: workload.engrave("Sign", 40000.0, 0.0, EngraveSettings(stepover=0.001, texture=GougeTexture(spacing=0.1))),
        lambda: workload.engrave("Sign", 40000.0, 80.0, EngraveSettings(band_stepover=1e-5)),
        lambda: workload.pocket("tray", 1e6, 5.0, s(stepover=0.05, step_down=2.0)),
        lambda: workload.profile("panel", 40000.0, 10.0, s(step_down=0.01)),
        lambda: workload.chamfer("edge", 2_500_000),
        lambda: workload.drill("rack", 2_000_000, 10.0, s(order="given", peck=0.0)),
        lambda: workload.drill("rack", 25_000, 10.0, s(order="shortest", peck=0.0)),
        lambda: workload.drill("rack", 1000, 100.0, s(order="given", peck=0.05)),
        lambda: workload.rotary("bowl", 900.0, 110.0, 9.0, rotary.RotarySettings(spacing=0.01, step_down=0.01)),
        lambda: workload.stepnc("x", 300_000_000),
        lambda: workload.turnmill("ball", np.full(81920, 0.06), s(sample_spacing=0.01)),
    ]
    messages = []
    for call in calls:
        with pytest.raises(workload.WorkloadError) as caught:
            call()
        messages.append(str(caught.value))
    messages.append(f"operation 'relief': {messages[1]}")
    latin = re.compile(r"[A-Za-z]{3,}")
    for message in messages:
        japanese = translations.japanese_message(message)
        assert japanese is not None, message
        left = [word for word in latin.findall(japanese) if word not in ALLOWED_LATIN]
        assert not left, (message, japanese)


# names and words the messages keep as typed: object and file names, the order value 'given'
ALLOWED_LATIN = {"Relief", "Sign", "tray", "panel", "edge", "rack", "bowl", "ball", "relief", "given", "job", "STEP"}


def test_coincident_holes_among_many_are_found_in_a_moment_and_a_far_hole_is_refused():
    from kezuri.toolpath.operations.drill import drill
    holes = list(grid_holes(25_000)) + [(20.0004, 0.0003)]       # within a micron of hole 3 (20, 0)
    started = time.perf_counter()
    with time_limit(20), pytest.raises(drill.DrillError, match=r"^holes 3 and 25001 are the same point \[20.0, 0.0\]$"):
        drill.check_holes(holes)
    assert time.perf_counter() - started < 2.0          # every pair compared: 14 s
    assert len(drill.check_holes(grid_holes(25_000) + ((20.0008, 0.0008),))) == 25_001      # 1.1 micron apart
    with pytest.raises(drill.DrillError, match=r"hole 2 at \[1e\+200, 0.0\] lies beyond the 100000 mm"):
        drill.check_holes([(0.0, 0.0), (1e200, 0.0)])


def test_the_panel_refuses_a_carving_past_the_limit_before_planning(empty_scene):
    """Generate Carving with the finest scallop and sample spacing the panel allows (single
    precision: 9.99999974737875e-05 and 0.0099999998 are shown as typed)."""
    bpy = pytest.importorskip("bpy")
    from kezuri.operators import samples
    samples.set_millimetres(empty_scene)
    assert bpy.ops.kezuri.carve_sample(sample="wave") == {"FINISHED"}
    empty_scene.kezuri.carve.scallop = 0.0001
    empty_scene.kezuri.carve.sample_spacing = 0.01
    started = time.perf_counter()
    with time_limit(60), pytest.raises(RuntimeError, match=r"carve '[^']*': the finishing raster at scallop 0\.0001 mm "
                                                           r"and sample spacing 0\.01 mm is about 2\.\de7 tool positions, "
                                                           r"over the 2e7 this machine can plan; raise sample spacing"):
        bpy.ops.kezuri.carve_generate()
    assert time.perf_counter() - started < 10.0
