"""batch.py writes the setup sheet beside report.json, all or nothing: batch's entry point called in
this process (as tests/test_batch_stop.py does), the sheet read back with html.parser and checked
against the NC program's own text and report.json."""
import contextlib
import io
import json
import os
import re

import pytest

pytest.importorskip("bpy")
from sheet_reader import read_sheet, seconds  # noqa: E402
from test_hostile_batch import BATCH  # noqa: E402  (batch.py loaded once for the in-process suites)


def run(*argv) -> tuple:
    stderr = io.StringIO()
    with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        status = BATCH.main(["batch.py", *argv])
    return status, stderr.getvalue()


@pytest.fixture(scope="module")
def engraving(tmp_path_factory):
    out = tmp_path_factory.mktemp("sheet") / "engrave"
    status, message = run("engrave", "--post", "linuxcnc", "--out", str(out))
    assert status == 0, message[-2000:]
    report = json.loads((out / "report.json").read_text())
    return out, report, read_sheet((out / "setup-sheet.html").read_text(encoding="utf-8"))


def test_the_sheet_is_written_and_listed(engraving):
    out, report, _ = engraving
    assert report["setup_sheet"] == str(out / "setup-sheet.html")
    assert "staging" not in report["setup_sheet"]


def test_every_tool_of_the_program_with_its_number_and_diameter(engraving):
    """The tools as the NC program's header lists them, e.g. (TOOL: T2 6 MM BALL END MILL [ROUGHING BALL])."""
    out, _, page = engraving
    text = (out / "engrave.ngc").read_text()
    listed = {int(n): float(d) for n, d in re.findall(r"^\(TOOL: T(\d+) ([\d.]+) MM ", text, re.M)}
    loaded = {int(n) for n in re.findall(r"^T(\d+) M0?6", text, re.M)}
    assert listed and set(listed) == loaded
    shown = {int(row["Tool"].lstrip("T")): float(row["Diameter (mm)"]) for row in page.rows("tools")}
    assert shown == listed


def test_operation_times_add_up_to_the_total(engraving):
    _, report, page = engraving
    ops = page.rows("operations")
    assert [o["Operation"] for o in ops] == [o["name"] for o in report["operations"]]
    times = [seconds(o["Time (h:mm:ss)"]) for o in ops]
    total = seconds(page.texts["total"].replace("Total", "").strip())
    assert abs(sum(times) - total) <= 0.5 * len(times) + 0.5          # each shown to the second
    assert abs(total - report["cycle_time_s"]) <= 0.5
    assert [abs(t - o["cycle_time_s"]) <= 0.5 for t, o in zip(times, report["operations"])] == [True] * len(ops)
    assert seconds(re.search(r"Total time(\d+:\d\d:\d\d)", page.texts["setup"]).group(1)) == total


def test_gate_program_and_pictures(engraving):
    out, report, page = engraving
    assert report["gate"]["findings"] == [] and page.attrs["gate"]["data-status"] == "passed"
    data = (out / "engrave.ngc").read_bytes()
    lines = len(data.splitlines())
    assert page.rows("programs") == [{"File": "engrave.ngc", "Size (bytes)": f"{len(data):,}", "Lines": f"{lines:,}"}]
    pictures = page.picture_bytes()
    assert pictures == [(out / "engrave-toolpaths.png").read_bytes(), (out / "engrave.png").read_bytes()]
    assert all(p[:8] == b"\x89PNG\r\n\x1a\n" for p in pictures)
    assert all(value.startswith("data:") for _, _, value in page.references())
    assert "X0 Y0 at the centre of the stock; Z0 on the stock top" in page.texts["setup"]
    assert "block 200 \u00d7 100 \u00d7 20 mm" in page.texts["setup"]       # the sample plate


def test_a_refused_run_writes_no_sheet_and_an_override_says_so(tmp_path):
    """Travel 150 mm for a 200 mm engraving: the gate refuses (exit 3, nothing written); with
    --allow-findings the sheet says the program was written despite the finding, and names it."""
    refused = tmp_path / "refused"
    status, message = run("engrave", "--post", "grbl", "--travel", "150", "400", "100", "--out", str(refused))
    assert status == 3, message[-2000:]
    assert not refused.exists() and os.listdir(tmp_path) == []
    allowed = tmp_path / "allowed"
    status, message = run("engrave", "--post", "grbl", "--travel", "150", "400", "100", "--allow-findings",
                          "--out", str(allowed))
    assert status == 0, message[-2000:]
    report = json.loads((allowed / "report.json").read_text())
    page = read_sheet((allowed / "setup-sheet.html").read_text(encoding="utf-8"))
    assert page.attrs["gate"]["data-status"] == "written despite findings"
    assert report["gate"]["overridden"] and report["gate"]["findings"]
    for finding in report["gate"]["findings"]:
        assert finding["message"] in page.texts["gate"]


def test_a_punching_job_without_a_program_gets_a_sheet_too(tmp_path):
    out = tmp_path / "unfold"
    status, message = run("unfold", "--out", str(out))
    assert status == 0, message[-2000:]
    report = json.loads((out / "report.json").read_text())
    page = read_sheet((out / "setup-sheet.html").read_text(encoding="utf-8"))
    data = (out / "unfold.nc").read_bytes()
    assert [(r["File"], r["Size (bytes)"]) for r in page.rows("programs")] == [("unfold.nc", f"{len(data):,}")]
    assert page.attrs["gate"]["data-status"] == "passed" and report["setup_sheet"] == str(out / "setup-sheet.html")
    width, height = report["sheet"]["sheet_mm"]
    assert f"sheet {width:g} \u00d7 {height:g} mm" in page.texts["setup"]
    assert page.picture_bytes() == [(out / "unfold.png").read_bytes()]


def test_the_turn_mill_sheet_names_every_program_it_wrote(tmp_path):
    """The turn-mill writes a program per post (default: all of them); the sheet's Post said '—'."""
    out = tmp_path / "turnmill"
    status, message = run("turnmill", "--post", "xzc", "--post", "cldata", "--out", str(out))
    assert status == 0, message[-2000:]
    written = sorted(p.suffix for p in out.iterdir() if p.suffix in (".nc", ".ngc", ".cls"))
    assert written == [".cls", ".nc"]
    page = read_sheet((out / "setup-sheet.html").read_text(encoding="utf-8"))
    assert re.search(r"PostTurn-Mill X-Z-C, APT CL DataWork offset", page.texts["setup"]), page.texts["setup"][:300]
