"""Job files use the computed feeds (issue 31, item 3): with ``[setup] material``, a profile's,
pocket's, drilling's, chamfer's or V-carve's spindle speed, feeds and steps left out of its settings
come from the calculator for its tool, the kind and the machine; typed values win; report.json's
``feeds`` says per value whether it was computed or typed.  Without a material nothing changes.

The programs are read by LinuxCNC's rs274 (its canonical SET_SPINDLE_SPEED / SET_FEED_RATE calls
and feed moves).  Expected numbers are worked by hand from AST Tooling's hardwood row for a 1/4 in
cutter (.005 - .007 in per tooth) and wood's 600 - 1000 sfm with carbide (300 - 500 with HSS)."""
import json
import math
import os

import numpy as np
import pytest

pytest.importorskip("bpy")
import rs274  # noqa: E402
from test_batch_job import JOBS, run  # noqa: E402

from kezuri.toolpath.tooling import store  # noqa: E402
from kezuri.toolpath.tooling.library import LibraryTool  # noqa: E402

IN, FT = 25.4, 0.3048
RPM = round(800 * FT * 1000 / (math.pi * 6.35))           # 12223: 243.84 m/min at 1/4 in
FEED = round(RPM * 2 * 0.006 * IN)                         # 3726: the middle of .005 - .007 in per tooth
needs_rs274 = pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")


def job_text(material: str, settings: str, machine: str = "linuxcnc-manual") -> str:
    return ('[setup]\nname = "cut"\nstock = [0.0, 0.0, -12.0, 100.0, 50.0, 0.0]\npost = "linuxcnc"\n'
            f'machine = "{machine}"\n{material}\n\n[[operations]]\nkind = "profile"\nname = "cut out"\n'
            f'outline = "plate"\nsettings = {{ {settings} }}\n')


def run_job(tmp_path, text: str, name: str = "cut.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    status, message, out = run("job", str(path))
    assert status == 0, message[-2000:]
    report = json.load(open(os.path.join(out, "report.json")))
    return report, open(report["files"][0], encoding="utf-8").read()


def speeds_and_feeds(text: str, tools=(5,)) -> tuple:
    """(spindle speeds, feed rates other than 0) the program sets, as rs274 reads it; the Z levels
    of its feed moves below the top."""
    calls = rs274.run(text, tools=tools)
    speeds = {float(args[-1]) for name, args in calls if name == "SET_SPINDLE_SPEED" and float(args[-1]) > 0}
    feeds = {float(args[0]) for name, args in calls if name == "SET_FEED_RATE" and float(args[0]) > 0}
    kinds, points, _ = rs274.motion_endpoints(calls)
    flat = {round(float(b[2]), 3) for k, a, b in zip(kinds[1:], points[:-1], points[1:])
            if k != "rapid" and abs(a[2] - b[2]) < 1e-9 and np.hypot(*(b[:2] - a[:2])) > 1.0 and b[2] < -1e-6}
    return speeds, feeds, sorted(flat)


@pytest.fixture
def no_library(tmp_path, monkeypatch):
    monkeypatch.setenv("KEZURI_TOOL_LIBRARY", str(tmp_path / "none" / "tools.toml"))     # no file: assumed tools


@needs_rs274
def test_a_profile_in_hardwood_runs_at_the_computed_feeds_and_says_so(tmp_path, no_library):
    report, text = run_job(tmp_path, job_text('material = "hardwood"', "diameter = 6.35, tool_number = 5"))
    speeds, feeds, levels = speeds_and_feeds(text)
    assert speeds == {RPM}
    assert feeds == {FEED, round(FEED / 2)}                # cutting and plunging (Amana: feed / flutes)
    # through 12 mm + 0.3 breakthrough in steps of at most 1 x D (6.35 mm): 2 even levels (the default
    # 3 mm step would cut 5)
    assert levels == [-12.3, -6.15]
    (entry,) = report["feeds"]
    assert entry["values"] == {"rpm": {"value": RPM, "source": "computed"},
                               "feed": {"value": FEED, "source": "computed"},
                               "plunge_feed": {"value": round(FEED / 2), "source": "computed"},
                               "step_down": {"value": 6.35, "source": "computed"}}
    assert entry["values_chip_load_mm"] == pytest.approx(FEED / (RPM * 2), abs=1e-4)
    assert entry["chip_load_mm"] == pytest.approx(FEED / (RPM * 2), abs=1e-4) and entry["flags"] == []


@needs_rs274
def test_a_typed_feed_stays_typed_and_is_flagged_outside_the_band(tmp_path, no_library):
    report, text = run_job(tmp_path, job_text('material = "hardwood"', "diameter = 6.35, tool_number = 5, feed = 900"))
    speeds, feeds, _ = speeds_and_feeds(text)
    assert speeds == {RPM} and feeds == {900.0, 450.0}
    (entry,) = report["feeds"]
    assert entry["values"]["feed"] == {"value": 900, "source": "typed"}
    assert entry["values"]["rpm"] == {"value": RPM, "source": "computed"}
    assert entry["chip_load_mm"] == pytest.approx(900 / (RPM * 2), abs=1e-4)        # 0.0368 mm: rubs
    assert [f["kind"] for f in entry["flags"]] == ["rubbing"]
    assert entry["flags"][0]["band"] == [0.127, 0.178]
    assert any("below the safe band" in w for w in report["warnings"])


@needs_rs274
def test_the_machine_caps_the_computed_spindle_speed_and_feed(tmp_path, no_library):
    # the LinuxCNC tool-changer mill: 12000 rpm; 12000 x 2 x .1524 = 3658 mm/min is under its 10000
    report, text = run_job(tmp_path, job_text('material = "hardwood"', "diameter = 6.35, tool_number = 5",
                                              machine="linuxcnc-atc"))
    speeds, feeds, _ = speeds_and_feeds(text)
    assert speeds == {12000.0} and round(12000 * 2 * 0.006 * IN) in feeds
    # aluminium, 1/4 in carbide: 800 - 2200 sfm wants 45838 rpm; chip .001 - .0022 in
    report, text = run_job(tmp_path, job_text('material = "aluminium"', "diameter = 6.35, tool_number = 5",
                                              machine="linuxcnc-atc"), name="alu.toml")
    speeds, feeds, _ = speeds_and_feeds(text)
    assert round(1500 * FT * 1000 / (math.pi * 6.35)) > 12000 and speeds == {12000.0}
    assert round(12000 * 2 * 0.0016 * IN) in feeds


@needs_rs274
def test_the_tool_librarys_flutes_and_material_give_the_feeds(tmp_path, monkeypatch):
    path = tmp_path / "config" / "tools.toml"
    store.save(str(path), store.SEEDS.with_tool(LibraryTool(21, "flat", 6.35, flutes=3, material="hss",
                                                            flute_length=25.0)))
    monkeypatch.setenv("KEZURI_TOOL_LIBRARY", str(path))
    text = job_text('material = "hardwood"', "").replace("settings = {  }\n", "tool = 21\n")
    report, program = run_job(tmp_path, text)
    rpm = round(400 * FT * 1000 / (math.pi * 6.35))        # HSS: 300 - 500 sfm
    feed = round(rpm * 3 * 0.006 * IN)
    speeds, feeds, _ = speeds_and_feeds(program, tools=(21,))
    assert speeds == {rpm} and feeds == {feed, round(feed / 3)}
    (entry,) = report["feeds"]
    assert entry["flutes"] == 3 and entry["tool_material"] == "hss" and entry["assumed"] == []


@needs_rs274
def test_without_a_material_the_kinds_own_defaults_run(tmp_path, no_library):
    report, text = run_job(tmp_path, job_text("", "diameter = 6.35, tool_number = 5"))
    speeds, feeds, levels = speeds_and_feeds(text)
    assert speeds == {18000.0} and feeds == {1500.0, 300.0}      # ProfileSettings' rpm, feed, plunge feed
    assert levels == [-12.3, -9.84, -7.38, -4.92, -2.46]         # its 3 mm step: 5 even levels
    assert report["feeds"] == [] and report["material"] is None


SAMPLES = sorted(name for name in os.listdir(JOBS) if name.endswith(".toml")
                 and "material" not in open(os.path.join(JOBS, name), encoding="utf-8").read()
                 and "{{" not in open(os.path.join(JOBS, name), encoding="utf-8").read())


@pytest.mark.parametrize("name", SAMPLES)
def test_a_sample_job_without_material_plans_its_settings_as_typed(name):
    """Each sample job file without a material: every operation's settings are the ones its kind
    reads from the file as written, and the job records no computed feeds (the programs stay
    byte for byte as before: checked against the tree before this change, see the commit)."""
    import bpy

    from kezuri.operators import jobfile
    from kezuri.operators.preferences import scene_post
    from kezuri.operators.workflows import WORKFLOWS

    path = os.path.join(JOBS, name)
    data = jobfile.read(path)
    scene = jobfile.scene_for(data["setup"], path)
    post = data["setup"].get("post") or scene_post(scene)
    jobfile.apply_setup(scene, data["setup"], path)
    assert scene.kezuri.stock.material == "NONE"
    entries = jobfile.entries(data, scene, path)
    job, _, _ = jobfile.job_of(scene, entries, "sample", post, path)
    assert job.setup.feeds == () and job.setup.material == ""
    adapters = {w.kind: w for w in WORKFLOWS if w.kind and w.job_operation is not None}
    depsgraph = bpy.context.evaluated_depsgraph_get()
    for entry, operation in zip(entries, job.operations):
        own, _, _ = adapters[entry.kind].job_operation(scene, depsgraph, entry, post)
        assert repr(own.settings) == repr(operation.settings), entry.name
