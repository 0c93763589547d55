"""``batch.py job FILE.toml`` and its templates (``--each rows.csv``), run in-process as a user runs
them: job files written here in TOML, the programs read back as text by LinuxCNC's rs274 and the
controller-rules reader."""
import contextlib
import io
import json
import os
import re
import tempfile

import numpy as np
import pytest

pytest.importorskip("bpy")
import controller_rules  # noqa: E402
import rs274  # noqa: E402
from test_hostile import time_limit  # noqa: E402
from test_hostile_batch import BATCH  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
JOBS = os.path.join(ROOT, "samples", "jobs")
CASE_SECONDS = 300


def run(*argv, out=None) -> tuple:
    """(exit status, stderr, the --out folder) of ``batch.py <argv> --out <folder>``."""
    out = out or os.path.join(tempfile.mkdtemp(prefix="kezuri-job-"), "out")
    stderr = io.StringIO()
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(["batch.py", *argv, "--out", out])
        except SystemExit as exit_:
            status = exit_.code
    return status, stderr.getvalue(), out


@pytest.fixture(scope="module")
def sample_job():
    status, message, out = run("job", os.path.join(JOBS, "nameplate-with-holes.toml"))
    assert status == 0, message[-2000:]
    return out


def test_the_sample_job_is_one_program_with_its_three_tools_in_order(sample_job):
    report = json.loads(open(os.path.join(sample_job, "report.json")).read())
    assert report["files"] == [os.path.join(sample_job, "nameplate.ngc")]
    assert [op["name"] for op in report["job_operations"]] == ["texture and letters", "mounting holes"]
    assert report["gate"]["findings"] == [] and not report["gate"]["overridden"]
    text = open(report["files"][0]).read()
    assert re.findall(r"^T(\d+) M0?6", text, re.M) == ["2", "3", "2", "4"]
    assert controller_rules.check(text, "linuxcnc") == []


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")
def test_rs274_reads_the_job_and_the_drill_reaches_12_mm_at_the_four_corners(sample_job):
    text = open(os.path.join(sample_job, "nameplate.ngc")).read()
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text, tools=(2, 3, 4)))
    drilling = text[text.index("T4 M6") if "T4 M6" in text else text.index("T4 M06"):]
    kinds_d, points_d, _ = rs274.motion_endpoints(rs274.run(text[:0] + "G21 G90 G17\n" + drilling, tools=(4,)))
    bottoms = points_d[np.isclose(points_d[:, 2], -12.0)]
    assert sorted({(round(x, 3), round(y, 3)) for x, y, _ in bottoms}) == [(-90, -40), (-90, 40), (90, -40), (90, 40)]
    assert points[:, 2].min() == pytest.approx(-12.0)


def test_a_one_operation_job_writes_the_engrave_commands_program_byte_for_byte(tmp_path):
    job = tmp_path / "engrave.toml"
    job.write_text('[setup]\nname = "Scene"\nsample = "name_plate"\npost = "linuxcnc"\n\n'
                   '[[operations]]\nkind = "engrave"\nname = "engrave"\n'
                   'objects = { plate = "Plate", letters = "Letters" }\n', encoding="utf-8")
    status, message, out = run("job", str(job))
    assert status == 0, message[-2000:]
    status, message, direct = run("engrave", "--post", "linuxcnc")
    assert status == 0, message[-2000:]
    assert open(os.path.join(out, "Scene.ngc")).read() == open(os.path.join(direct, "engrave.ngc")).read()


def test_a_template_runs_every_row_into_its_folder_and_reports_the_bad_row(tmp_path):
    rows = tmp_path / "rows.csv"
    rows.write_text('name,seed\nAb,1\n"Q""\\\\",2\nCd,x\n', encoding="utf-8")       # Q"\\ and a seed 'x'
    status, message, out = run("job", os.path.join(JOBS, "nameplates.toml"), "--each", str(rows))
    assert status == 2, message[-2000:]
    summary = json.loads(open(os.path.join(out, "report.json")).read())
    assert [r["status"] for r in summary["rows"]] == ["written", "written", "bad input"]
    assert "row 3: column seed = 'x' is not a number" in summary["rows"][2]["message"]
    assert sorted(os.listdir(out)) == ["001-Ab", '002-Q', "report.json"]
    first = open(os.path.join(out, "001-Ab", "plate.nc")).read()
    second = open(os.path.join(out, '002-Q', "plate.nc")).read()
    assert first != second and first.startswith(("%", "(")) and "T4" in first
    for folder in ("001-Ab", "002-Q"):      # every row has its setup sheet, listed in its report
        row = json.loads(open(os.path.join(out, folder, "report.json")).read())
        assert row["setup_sheet"] == os.path.join(out, folder, "setup-sheet.html") and os.path.isfile(row["setup_sheet"])


def test_the_template_text_goes_in_as_typed():
    from kezuri.operators import jobfile, jobtemplate

    template = '[setup]\ntext = "Mr {{name}}"\n# {{nothing}} in a comment\n[[operations]]\nkind = "drill"\n' \
               'name = "{{name}}"\nsettings = { depth = {{depth}} }\n'
    text = jobtemplate.render(template, {"name": 'A "B" \\ C', "depth": "2.5"}, "row 1")
    data = jobfile.read("t.toml", text)
    assert data["setup"]["text"] == 'Mr A "B" \\ C'
    assert data["operations"][0]["name"] == 'A "B" \\ C'
    assert data["operations"][0]["settings"]["depth"] == 2.5
    with pytest.raises(jobfile.JobFileError, match=r"row 1: the job file's line 7 asks for \{\{depth\}\}"):
        jobtemplate.render(template, {"name": "x"}, "row 1")


BAD_JOBS = {
    "toml": ('[setup\nname = "x"\n', "not TOML"),
    "unknown table": ('[setup]\n[[operations]]\nkind = "drill"\nname = "a"\nholes = [[0.0, 0.0]]\n[extra]\n',
                      "unknown table 'extra'"),
    "no operations": ('[setup]\nname = "x"\n', "no [[operations]]"),
    "unknown setup key": ('[setup]\nmachin = "grbl-router"\n[[operations]]\nkind = "engrave"\nname = "a"\n',
                          "[setup] has an unknown key 'machin'"),
    "unknown kind": ('[[operations]]\nkind = "waterjet"\nname = "a"\n', "kind 'waterjet' is not one of"),
    "missing object": ('[[operations]]\nkind = "engrave"\nname = "a"\nobjects = { letters = "Name" }\n',
                       "objects.letters = 'Name' is not an object of the scene"),
    "unknown setting": ('[[operations]]\nkind = "engrave"\nname = "a"\nsettings = { sead = 3 }\n',
                        "settings.sead is not a setting of engrave"),
    "setting out of range": ('[[operations]]\nkind = "engrave"\nname = "a"\nsettings = { stepover = -1.0 }\n',
                             "Stepover"),
    "same names": ('[[operations]]\nkind = "engrave"\nname = "a"\n[[operations]]\nkind = "drill"\nname = "a"\n'
                   'holes = [[0.0, 0.0]]\n', "two operations are named 'a'"),
    "tool clash": ('[[operations]]\nkind = "engrave"\nname = "a"\n[[operations]]\nkind = "drill"\nname = "b"\n'
                   'holes = [[0.0, 0.0]]\nsettings = { tool_number = 3 }\n', "tool number 3 is the"),
    "drill without holes": ('[[operations]]\nkind = "engrave"\nname = "a"\n[[operations]]\nkind = "drill"\n'
                            'name = "b"\n', "no holes"),
    "hole not a number": ('[[operations]]\nkind = "engrave"\nname = "a"\n[[operations]]\nkind = "drill"\n'
                          'name = "b"\nholes = [[0.0, "x"]]\n', "holes must be"),
    "drill deeper than its flutes": ('[[operations]]\nkind = "engrave"\nname = "a"\n[[operations]]\nkind = "drill"\n'
                                     'name = "b"\nholes = [[0.0, 0.0]]\nsettings = { depth = 80.0 }\n',
                                     "deeper than"),
    "stock and sample": ('[setup]\nsample = "name_plate"\nstock = [0.0, 0.0, -5.0, 10.0, 10.0, 0.0]\n[[operations]]\n'
                         'kind = "drill"\nname = "b"\nholes = [[5.0, 5.0]]\n', "more than one of blend, sample and stock"),
    # a STEP-NC operation's file: named as typed in the job file, beside the entry that gives it
    "stepnc file missing": ('[[operations]]\nkind = "stepnc"\nname = "wp"\nfile = "parts/none.stp"\n',
                            "operation 1 ('wp'): file = 'parts/none.stp': no such file"),
    "stepnc file a folder": ('[[operations]]\nkind = "stepnc"\nname = "wp"\nfile = "."\n',
                             "operation 1 ('wp'): file = '.': a folder, not an ISO 14649 file"),
    "stepnc file bad": ('[[operations]]\nkind = "stepnc"\nname = "wp"\nfile = "bad.toml"\n',
                        "operation 1 ('wp'): file = 'bad.toml': line 1, column 1"),
    "stock upside down": ('[setup]\nstock = [0.0, 0.0, 5.0, 10.0, 10.0, 0.0]\n[[operations]]\nkind = "drill"\nname = "b"\n'
                          'holes = [[5.0, 5.0]]\n', "each lower corner value must lie below the upper one"),
}


@pytest.mark.parametrize("case", sorted(BAD_JOBS))
def test_a_bad_job_file_is_refused_by_name_and_nothing_is_written(tmp_path, case):
    text, words = BAD_JOBS[case]
    job = tmp_path / "bad.toml"
    job.write_text(text, encoding="utf-8")
    status, message, out = run("job", str(job))
    assert status == 2, message[-2000:]
    assert "Traceback" not in message
    assert words in message, message[-2000:]
    assert not os.path.exists(out)


def test_a_missing_job_file_and_bad_rows_files_are_named(tmp_path):
    status, message, out = run("job", str(tmp_path / "none.toml"))
    assert status == 2 and "none.toml: no such file" in message
    for text, words in (("", "empty"), ("name\n", "no rows"), ("a,a\n1,2\n", "names the column 'a' twice"),
                        ("a,b\n1\n", "line 2 has 1 values for 2 columns")):
        rows = tmp_path / "rows.csv"
        rows.write_text(text, encoding="utf-8")
        status, message, out = run("job", os.path.join(JOBS, "nameplates.toml"), "--each", str(rows))
        assert status == 2 and words in message, message[-1500:]
        assert not os.path.exists(out)


def test_rows_in_worker_processes_write_what_one_process_writes(tmp_path):
    rows = tmp_path / "rows.csv"
    rows.write_text("name,seed\nAb,1\n鈴木,3\n", encoding="utf-8")
    template = os.path.join(JOBS, "nameplates.toml")
    status, message, here = run("job", template, "--each", str(rows))
    assert status == 0, message[-2000:]
    status, message, workers = run("job", template, "--each", str(rows), "--jobs", "2")
    assert status == 0, message[-2000:]
    for folder in ("001-Ab", "002-鈴木"):
        assert open(os.path.join(here, folder, "plate.nc")).read() == open(os.path.join(workers, folder, "plate.nc")).read()
        row = json.loads(open(os.path.join(workers, folder, "report.json")).read())
        assert row["files"] == [os.path.join(workers, folder, "plate.nc")]


def header_named(text: str, name: str) -> str:
    """The program with its header's name line put back to ``name`` (the job's name is the only
    difference between a job of one operation and its workflow's command)."""
    first, rest = text.split("\n", 2)[:2], text.split("\n", 2)[2]
    return "\n".join([first[0], re.sub(r"KEZURI CAM - .*\)", f"KEZURI CAM - {name})", first[1]), rest])


@pytest.mark.parametrize("job, command, program, direct", [
    ("bento-pockets.toml", ("rotary", "--post", "linuxcnc"), "bento.ngc", "rotary.ngc"),
    ("ex1-workplan.toml", ("stepnc", "--input", os.path.join(ROOT, "tests", "fixtures", "iso14649", "ex1.stp"),
                           "--post", "linuxcnc"), "ex1.ngc", "stepnc.ngc"),
    ("turned-part.toml", ("turnmill",), "bar.ngc", "turnmill.ngc"),
])
def test_each_sample_job_writes_its_workflows_program(job, command, program, direct):
    """A job file of one operation writes what the workflow's own command writes, but for the name
    in the header (NC text compared line by line)."""
    status, message, out = run("job", os.path.join(JOBS, job))
    assert status == 0, message[-2000:]
    status, message, reference = run(*command)
    assert status == 0, message[-2000:]
    mine = open(os.path.join(out, program)).read()
    theirs = open(os.path.join(reference, direct)).read()
    assert header_named(mine, "SCENE") == theirs


def test_a_drilling_alone_drills_the_stock_the_setup_gives(tmp_path):
    """No operation gives the stock: the setup's (a box, work zero at its front-left top corner)."""
    job = tmp_path / "holes.toml"
    job.write_text('[setup]\nname = "holes"\nstock = [0.0, 0.0, -12.0, 100.0, 50.0, 0.0]\npost = "linuxcnc"\n\n'
                   '[[operations]]\nkind = "drill"\nname = "holes"\nholes = [[10.0, 10.0], [90.0, 40.0]]\n'
                   'settings = { depth = 8.0 }\n', encoding="utf-8")
    status, message, out = run("job", str(job))
    assert status == 0, message[-2000:]
    report = json.loads(open(os.path.join(out, "report.json")).read())
    assert report["gate"]["findings"] == []
    assert report["simulation"]["removed_volume_mm3"] > 0
