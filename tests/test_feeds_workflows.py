"""The single-workflow batch commands run the feeds check a job runs (issue 31, left item): with
``--material`` (or the scene's material), report.json gets ``feeds`` and each rubbing, overload or
beyond-the-machine flag a warning, the workflow's values unchanged (the seeds keep the paper's);
the router shorthands take ``--material`` into their job file, so a drilling's speeds and feeds
come from the drilling chart where left out.  Run in-process as a user runs them; programs read by
LinuxCNC's rs274 where it is installed.

Hand-worked: the drill shorthand's default drill (T4, 5 mm, its make unknown: carbide) in hardwood:
wood 300 - 400 sfm for HSS drills, doubled for carbide, the middle 700 sfm = 213.36 m/min;
213,360 / (pi x 5) = 13,582.9 -> 13583 rpm.  5 mm = 0.197 in: the 1/8 - 1/4 in row, .002 - .004 in
per revolution, the middle .003 in = 0.0762 mm; 13583 x 0.0762 = 1035.0 -> 1035 mm/min."""
import json
import os
import re

import pytest

pytest.importorskip("bpy")
import rs274  # noqa: E402
from test_batch_job import run  # noqa: E402
from test_batch_shorthand import SVG  # noqa: E402

IN = 25.4


@pytest.fixture(autouse=True)
def no_tool_library(tmp_path, monkeypatch):
    monkeypatch.setenv("KEZURI_TOOL_LIBRARY", str(tmp_path / "none" / "tools.toml"))     # no file: assumed tools


@pytest.fixture
def drawing(tmp_path):
    path = tmp_path / "plate.svg"
    path.write_text(SVG, encoding="utf-8")
    return str(path)


def report_of(out):
    return json.load(open(os.path.join(out, "report.json"), encoding="utf-8"))


def spindle_and_feeds(text: str) -> tuple:
    """The S and F words of a program (sorted sets of numbers)."""
    return (sorted({float(v) for v in re.findall(r"S(\d+(?:\.\d*)?)", text)}),
            sorted({float(v) for v in re.findall(r"F(\d+(?:\.\d*)?)", text)}))


def test_engrave_with_a_material_checks_the_papers_values_and_warns_without_changing_them():
    status, message, plain = run("engrave", "--post", "linuxcnc")
    assert status == 0, message[-2000:]
    status, message, checked = run("engrave", "--post", "linuxcnc", "--material", "hardwood")
    assert status == 0, message[-2000:]
    before, after = report_of(plain), report_of(checked)
    assert "feeds" not in before
    text_before = open(before["files"][0], encoding="utf-8").read()
    text_after = open(after["files"][0], encoding="utf-8").read()
    assert spindle_and_feeds(text_before) == spindle_and_feeds(text_after)       # the paper's values kept
    entries = after["feeds"]
    assert len(entries) == len(after["operations"]) and all(e["material"] == "hardwood" for e in entries)
    for entry in (e for e in entries if e["checked"]):
        # each entry's chip load is its own feed over rpm x flutes (2 assumed: no tool library)
        assert entry["chip_load_mm"] == pytest.approx(entry["feed_mm_min"] / (entry["spindle_rpm"] * 2), abs=1e-4)
        assert entry["assumed"] == ["flutes", "tool material"]
    flagged = [(e, f) for e in entries for f in e["flags"]]
    assert flagged, entries
    warnings = [w for w in after["warnings"] if w.startswith("feeds: ")]
    assert len(warnings) == len(flagged)
    for (entry, flag), warning in zip(flagged, warnings):
        assert entry["operation"] in warning and flag["message"] in warning and "hardwood" in warning


def test_engrave_refuses_an_unknown_material_naming_the_option_before_planning():
    status, message, out = run("engrave", "--post", "linuxcnc", "--material", "oak")
    assert status == 2 and "--material 'oak'" in message and "hardwood" in message
    assert not os.path.exists(os.path.join(out, "report.json"))


def test_the_drill_shorthand_in_hardwood_feeds_its_drill_per_revolution(drawing):
    status, message, out = run("drill", "--svg", drawing, "--post", "linuxcnc", "--material", "hardwood")
    assert status == 0, message[-2000:]
    report = report_of(out)
    assert 'material = "hardwood"' in report["job_file_text"]
    (entry,) = report["feeds"]
    assert entry["spindle_rpm"] == 13583 and entry["feed_mm_min"] == 1035
    assert entry["chip_load_per"] == "revolution" and entry["flags"] == []
    assert entry["band_mm"] == [round(0.002 * IN, 4), round(0.004 * IN, 4)]
    assert entry["values"]["rpm"] == {"value": 13583, "source": "computed"}
    text = open(report["files"][0], encoding="utf-8").read()
    if rs274.available():
        calls = rs274.run(text, tools=(4,))
        speeds = {float(a[-1]) for name, a in calls if name == "SET_SPINDLE_SPEED" and float(a[-1]) > 0}
        feeds = {float(a[0]) for name, a in calls if name == "SET_FEED_RATE" and float(a[0]) > 0}
        assert speeds == {13583.0} and 1035.0 in feeds


def test_the_drill_shorthand_keeps_typed_values_and_warns_when_a_drill_rubs(drawing):
    # the kind's own 3000 rpm and 150 mm/min: 0.05 mm per revolution, below .002 in (0.0508 mm)
    status, message, out = run("drill", "--svg", drawing, "--post", "linuxcnc", "--material", "hardwood",
                               "--set", "rpm=3000", "--set", "feed=150")
    assert status == 0, message[-2000:]
    report = report_of(out)
    (entry,) = report["feeds"]
    assert (entry["spindle_rpm"], entry["feed_mm_min"]) == (3000, 150)
    assert [f["kind"] for f in entry["flags"]] == ["rubbing"]
    assert entry["flags"][0]["value"] == pytest.approx(0.05)
    assert any(w.startswith("feeds: ") and "0.0500 mm per revolution" in w for w in report["warnings"])
    assert spindle_and_feeds(open(report["files"][0], encoding="utf-8").read())[0] == [3000.0]


def test_a_shorthand_refuses_an_unknown_material_naming_the_option(drawing):
    status, message, _ = run("profile", "--svg", drawing, "--material", "unobtainium")
    assert status == 2 and "--material 'unobtainium'" in message


@pytest.mark.parametrize("command", ["carve", "rotary"])
def test_carve_and_rotary_with_a_material_check_each_operation(command):
    status, message, out = run(command, "--material", "mdf")
    assert status == 0, message[-2000:]
    report = report_of(out)
    entries = report["feeds"]
    assert entries and all(e["material"] == "mdf" for e in entries)
    names = [op["name"] for op in report["operations"]]
    assert [e["operation"] for e in entries] == names
    flags = sum(len(e["flags"]) for e in entries)
    assert sum(w.startswith("feeds: ") for w in report["warnings"]) == flags
