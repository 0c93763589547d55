"""batch.py as a user runs it: a separate process with the bpy wheel, files on disk."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import rs274

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def batch(*args, check=True):
    done = subprocess.run([sys.executable, os.path.join(ROOT, "batch.py"), *args], capture_output=True, text=True,
                          timeout=600, cwd=ROOT)
    if check:
        assert done.returncode == 0, done.stderr[-3000:]
    return done


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("batch")
    out = {}
    for key, args in {"a": ["--post", "linuxcnc", "--seed", "3"], "b": ["--post", "linuxcnc", "--seed", "3"],
                      "c": ["--post", "linuxcnc", "--seed", "4"], "macro": ["--post", "fanuc-macro"]}.items():
        folder = base / key
        batch("engrave", *args, "--out", str(folder))
        out[key] = folder
    return out


def test_engrave_writes_program_report_and_preview(runs):
    folder = runs["a"]
    report = json.loads((folder / "report.json").read_text())
    assert report["workflow"] == "engrave"
    assert report["files"] == [str(folder / "engrave.ngc")]
    png = (folder / "engrave.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000
    names = [op["name"] for op in report["operations"]]
    assert names == ["roughing (gouge texture)", "band finishing", "burr contour"]
    rough = report["operations"][0]
    assert rough["min_feed_z_mm"] == pytest.approx(-2.8) and rough["max_feed_z_mm"] == pytest.approx(-1.2)
    assert report["operations"][1]["min_feed_z_mm"] == pytest.approx(-2.0)
    depths = np.array(report["gouge_depths"])
    assert len(depths) > 100
    assert np.all((depths >= -2.8 - 1e-9) & (depths <= -1.2 + 1e-9))
    assert np.allclose(np.round((depths + 2) / 0.2) * 0.2 - 2, depths)
    assert np.max(np.abs(np.diff(depths))) <= 1.6 + 1e-9
    for op in report["operations"]:
        assert op["moves"] > 0 and op["feed_length_mm"] > 0 and op["cycle_time_s"] > 0


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")
def test_rs274_accepts_the_batch_program_and_sees_the_gouge_depths(runs):
    text = (runs["a"] / "engrave.ngc").read_text()
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text))
    feed_z = points[np.array(kinds) == "feed"][:, 2]
    report = json.loads((runs["a"] / "report.json").read_text())
    assert set(np.round(report["gouge_depths"], 3)) <= set(np.round(feed_z, 3))


def test_same_seed_same_program_other_seed_other_program(runs):
    a = (runs["a"] / "engrave.ngc").read_bytes()
    assert a == (runs["b"] / "engrave.ngc").read_bytes()
    assert a != (runs["c"] / "engrave.ngc").read_bytes()


def test_fanuc_macro_program(runs):
    text = (runs["macro"] / "engrave.nc").read_text()
    assert "G66.1 P7023" in text and "#3001" in text and "O7023" in text
    assert "GT5" not in text
    # The program as a control reads it: G66.1/G67 balanced and cancelled before every retract
    # (controller_rules), and on a strict Custom Macro B interpreter of a machine with every usual
    # axis the macro cuts G01 moves only, the rapids are the main program's, above the plate.
    import controller_rules
    from macrob import run_program
    assert controller_rules.check(text, "fanuc-mill") == []
    run = run_program(text, clock=iter(range(4096, 10**7, 16)), start=(0, 0, 100), axes="XYZABCUVW")
    assert run.ended_by == "M30" and run.clock_reads == 1
    assert all(m.kind == "feed" for m in run.moves if m.line != m.main_line)
    rapids = [m for m in run.moves if m.kind == "rapid"]
    assert rapids and all(m.line == m.main_line and m.z >= 2.0 - 1e-9 for m in rapids)
    feed_z = [m.z for m in run.moves if m.line != m.main_line]
    assert min(feed_z) >= -2.8 - 1e-9 and max(feed_z) <= -1.2 + 1e-9


def test_bad_input_exits_2_with_a_message_and_no_program(tmp_path):
    done = batch("engrave", "--blend", str(tmp_path / "missing.blend"), "--out", str(tmp_path / "o"), check=False)
    assert done.returncode == 2
    assert "missing.blend" in done.stderr and "Traceback" not in done.stderr
    assert not (tmp_path / "o" / "engrave.nc").exists()


def test_arguments_after_the_double_dash_when_run_by_blender():
    sys.path.insert(0, ROOT)
    try:
        import batch as batch_module
    finally:
        sys.path.remove(ROOT)
    blender_argv = ["blender", "-b", "plate.blend", "--python", "batch.py", "--", "engrave", "--out", "d"]
    assert batch_module.script_arguments(blender_argv) == ["engrave", "--out", "d"]
    assert batch_module.script_arguments(["batch.py", "demo", "--out", "d"]) == ["demo", "--out", "d"]
    args = batch_module.parser().parse_args(["rotary", "--post", "fanuc", "--out", "x"])
    assert (args.command, args.post, args.out) == ("rotary", "fanuc", "x")
