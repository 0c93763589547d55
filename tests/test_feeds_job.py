"""The feeds check before export, on a job file run in-process as ``batch.py job``: ``[setup] material``
checks each operation's spindle and feed against its tool's chip-load band (report.json ``feeds``,
warnings), the setup sheet shows each tool's chip load, a bad material is refused naming it, and
the program is written either way (feeds warn, they never refuse)."""
import json
import os

import pytest

pytest.importorskip("bpy")
from sheet_reader import read_sheet  # noqa: E402
from test_batch_job import run  # noqa: E402

from kezuri.toolpath.job import Setup, fingerprint, JobOperation  # noqa: E402

IN = 25.4


def job_text(material_line: str, rpm=3000, feed=150) -> str:
    return ('[setup]\nname = "holes"\nstock = [0.0, 0.0, -12.0, 100.0, 50.0, 0.0]\npost = "linuxcnc"\n'
            f'{material_line}\n\n[[operations]]\nkind = "drill"\nname = "holes"\nholes = [[10.0, 10.0], [90.0, 40.0]]\n'
            f'settings = {{ depth = 8.0, diameter = 5.0, rpm = {rpm}, feed = {feed}, tool_number = 4 }}\n')


@pytest.fixture(scope="module")
def hardwood_run(tmp_path_factory):
    job = tmp_path_factory.mktemp("feeds") / "holes.toml"
    job.write_text(job_text('material = "hardwood"'), encoding="utf-8")
    status, message, out = run("job", str(job))
    assert status == 0, message[-2000:]
    return out, json.loads(open(os.path.join(out, "report.json")).read())


def test_the_report_checks_each_operation_against_the_material(hardwood_run):
    out, report = hardwood_run
    assert report["material"] == "hardwood"
    (entry,) = report["feeds"]
    assert entry["checked"] and entry["tool_number"] == 4
    # a drill is fed per revolution: 150 mm/min at 3000 rpm = 0.05 mm/rev, whatever its flutes
    assert entry["spindle_rpm"] == 3000 and entry["feed_mm_min"] == 150
    assert entry["chip_load_mm"] == pytest.approx(0.05) and entry["chip_load_per"] == "revolution"
    # the US Navy manual's drilling feeds: a 5 mm (0.197 in) drill is in the 1/8 - 1/4 in row, .002 - .004 in/rev
    assert entry["band_mm"] == pytest.approx([round(0.002 * IN, 4), round(0.004 * IN, 4)])
    assert [f["kind"] for f in entry["flags"]] == ["rubbing"]
    assert any(w.startswith("feeds: operation") and "below the safe band" in w for w in report["warnings"])
    assert os.path.isfile(report["files"][0])            # written: feeds warn, they never refuse


def test_the_setup_sheet_shows_the_chip_load_each_tool_runs_at(hardwood_run):
    out, report = hardwood_run
    page = read_sheet(open(report["setup_sheet"], encoding="utf-8").read())
    (tool,) = page.rows("tools")
    assert tool["Tool"] == "T4" and tool["Chip load (mm)"] == "0.0500/rev"      # a drill: per revolution


def test_a_job_without_material_is_not_checked(tmp_path):
    job = tmp_path / "holes.toml"
    job.write_text(job_text(""), encoding="utf-8")
    status, message, out = run("job", str(job))
    assert status == 0, message[-2000:]
    report = json.loads(open(os.path.join(out, "report.json")).read())
    assert report["material"] is None and report["feeds"] == []
    assert not any(str(w).startswith("feeds:") for w in report["warnings"])


def test_feeds_inside_the_band_give_no_warning(tmp_path):
    job = tmp_path / "holes.toml"
    job.write_text(job_text('material = "hardwood"', rpm=5000, feed=400), encoding="utf-8")   # 0.08 mm/rev
    status, message, out = run("job", str(job))
    assert status == 0, message[-2000:]
    report = json.loads(open(os.path.join(out, "report.json")).read())
    assert report["feeds"][0]["flags"] == [] and report["feeds"][0]["chip_load_mm"] == pytest.approx(0.08)
    assert not any(str(w).startswith("feeds:") for w in report["warnings"])


@pytest.mark.parametrize("value", ['"oak"', '""x', "3", '"NONE "'])
def test_a_bad_material_is_refused_naming_it(tmp_path, value):
    job = tmp_path / "holes.toml"
    job.write_text(job_text(f"material = {value}"), encoding="utf-8")
    status, message, out = run("job", str(job))
    assert status == 2
    assert "material" in message


def test_the_material_does_not_change_a_plan_fingerprint():
    op = JobOperation("drill", "holes", None, None)
    assert fingerprint(Setup(material="hardwood"), op) == fingerprint(Setup(material=""), op)
    assert fingerprint(Setup(work_offset="G55"), op) != fingerprint(Setup(), op)
