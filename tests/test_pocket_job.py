"""A pocket in a job file, run through ``batch.py job`` in-process as a user runs it: the sample
``samples/jobs/sign-pockets.toml`` (the name plate's letters pocketed, the rest machined with a
1 mm end mill, then four holes drilled), read back by LinuxCNC's rs274 and the controller-rules
reader; and the job-file adapter's refusals of bad entries by name."""
import json
import os
import re

import numpy as np
import pytest

pytest.importorskip("bpy")
import controller_rules  # noqa: E402
import rs274  # noqa: E402
from test_batch_job import JOBS, run  # noqa: E402


@pytest.fixture(scope="module")
def sign_job():
    status, message, out = run("job", os.path.join(JOBS, "sign-pockets.toml"))
    assert status == 0, message[-2000:]
    return out, json.loads(open(os.path.join(out, "report.json")).read())


def test_the_sign_job_passes_the_gate_with_its_three_tools_in_order(sign_job):
    out, report = sign_job
    assert report["gate"]["findings"] == [] and not report["gate"]["overridden"]
    assert [op["kind"] for op in report["job_operations"]] == ["pocket", "drill"]
    assert report["job_operations"][0]["operations"] == ["letters", "letters rest"]
    text = open(report["files"][0]).read()
    assert re.findall(r"^T(\d+) M0?6", text, re.M) == ["5", "6", "4"]
    assert controller_rules.check(text, "linuxcnc") == []


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")
def test_rs274_reads_the_pockets_down_to_2_mm_and_no_end_mill_feeds_straight_down(sign_job):
    out, report = sign_job
    text = open(report["files"][0]).read()
    calls = rs274.run(text, tools=(4, 5, 6))
    drilling = next(k for k, (name, args) in enumerate(calls) if name == "COMMENT" and "OPERATION 3: DRILL" in str(args))
    kinds, points, _ = rs274.motion_endpoints(calls[:drilling])
    kinds = np.array(kinds)
    assert points[:, 2].min() == pytest.approx(-2.0)
    # every feed move that goes down runs sideways too, at most as steep as the 3 degree ramp
    previous = points[:-1]
    step = points[1:] - previous
    down = (kinds[1:] == "feed") & (step[:, 2] < -1e-6) & (previous[:, 2] < 1e-6)   # down into the plate
    run_xy = np.hypot(step[down, 0], step[down, 1])
    assert down.any() and np.all(-step[down, 2] <= run_xy * np.tan(np.radians(3.0)) + 1e-3)


@pytest.mark.parametrize("table, message", [
    ('objects = { plate = "Plate" }', r"no region"),
    ('objects = { region = "Letters", letters = "Plate" }', r"objects.letters: a pocket's objects are region, plate"),
    ('objects = { region = "Letters" }\nsettings = { stepover = 0.0 }', r"stepover must be more than 0"),
    ('objects = { region = "Letters" }\nsettings = { speed = 3 }', r"settings.speed is not a pocket setting"),
    ('objects = { region = "Letters" }\nsettings = { diameter = 30.0 }',
     r"the 30 mm end mill does not fit in the region"),
    ('objects = { region = "Letters" }\nsettings = { depth = 0 }', r"depth must be more than 0"),
    ('objects = { region = "Letters" }\nsettings = { strategy = 3 }', r"settings.strategy = 3 is not a word"),
])
def test_bad_pocket_entries_are_refused_by_name_and_nothing_is_written(tmp_path, table, message):
    job = tmp_path / "bad.toml"
    job.write_text('[setup]\nname = "bad"\nsample = "name_plate"\npost = "linuxcnc"\n\n'
                   f'[[operations]]\nkind = "pocket"\nname = "letters"\n{table}\n', encoding="utf-8")
    status, stderr, out = run("job", str(job))
    assert status != 0
    assert re.search(message, stderr), stderr[-1000:]
    assert "Traceback" not in stderr
    assert not os.path.exists(out) or not [f for f in os.listdir(out) if f.endswith(".ngc")]


def test_an_open_curve_is_refused_by_name(empty_scene):
    import bpy

    from kezuri.operators import pocket, samples
    from kezuri.operators.jobentry import JobEntry
    from kezuri.toolpath.ir.errors import InputError

    samples.name_plate(empty_scene)
    curve = bpy.data.curves.new("Open", type="CURVE")
    spline = curve.splines.new("POLY")
    spline.points.add(2)
    spline.points.foreach_set("co", [0, 0, 0, 1, 20, 0, 0, 1, 20, 20, 0, 1])
    obj = bpy.data.objects.new("Open", curve)
    empty_scene.collection.objects.link(obj)
    entry = JobEntry("logo", "pocket", True, {"region": obj}, {}, {}, "job file x: operation 1 ('logo')")
    with pytest.raises(InputError, match=r"'Open'.*open"):
        pocket.job_operation(empty_scene, bpy.context.evaluated_depsgraph_get(), entry, "linuxcnc")


def test_a_pocket_row_of_the_job_list_plans_the_letters_from_the_panels_objects(empty_scene):
    """The CAM tab's job list: a pocket row added in the name-plate scene takes the letters and the
    plate as its region and stock, and plans with its settings (JSON, as a job file keeps them)."""
    import bpy

    from kezuri.operators import samples

    samples.name_plate(empty_scene)
    empty_scene.kezuri.machine.post = "linuxcnc"
    assert bpy.ops.kezuri.job_add(kind="pocket") == {"FINISHED"}
    row = empty_scene.kezuri.job_list.rows[0]
    assert {item.slot: item.object.name for item in row.objects} == {"region": "Letters", "plate": "Plate"}
    row.settings = json.dumps({"diameter": 3.0, "depth": 1.5, "step_down": 1.5, "stepover": 1.2,
                               "helix_diameter": 1.5})
    assert bpy.ops.kezuri.job_generate() == {"FINISHED"}
    assert row.tools == "T5" and row.state in {"PLANNED", "FINDINGS"}      # FINDINGS: the helix notes
    assert row.minutes > 0
