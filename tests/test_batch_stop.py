"""Every batch run can be stopped, and writes all its files or none.

In-process (batch's entry point called as a function): SIGINT and SIGTERM sent to this process
while a long job runs must end it within a couple of seconds with status 130 / 143, a message
saying so, and nothing on disk; a run that fails after some files were made (a folder in the way
of its report, a full disk) leaves --out as it was.  The full disk is a real one: a child process
whose file-size limit (RLIMIT_FSIZE) is smaller than the picture it writes."""
import contextlib
import importlib.util
import io
import os
import signal
import subprocess
import sys
import threading
import time

import pytest

bpy = pytest.importorskip("bpy")
from test_hostile import time_limit  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load_batch():
    spec = importlib.util.spec_from_file_location("kezuri_batch_stop", os.path.join(ROOT, "batch.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


BATCH = load_batch()


def everything_under(folder) -> list:
    return sorted(os.path.relpath(os.path.join(base, name), folder)
                  for base, dirs, files in os.walk(folder) for name in files + dirs)


def run(argv, *, signal_after=None, signum=None):
    """(status, stderr, seconds from the signal to the return) of ``batch.py argv``."""
    stderr = io.StringIO()
    sent = {}
    received_late = []

    def send():
        sent["at"] = time.perf_counter()
        os.kill(os.getpid(), signum)

    # If the run ended before the signal came, this handler (restored by batch after its run)
    # takes it, and the test fails on the status instead of pytest being interrupted.
    previous = signal.signal(signum, lambda *_: received_late.append(True)) if signum else None
    timer = threading.Timer(signal_after, send) if signum else None
    try:
        with time_limit(300), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            if timer:
                timer.start()
            status = BATCH.main(["batch.py", *argv])
            returned = time.perf_counter()
    finally:
        if timer:
            timer.cancel()
            timer.join()
            signal.signal(signum, previous)
    late = returned - sent["at"] if "at" in sent else None
    assert not received_late, "the run ended before the signal was sent: use a longer job"
    return status, stderr.getvalue(), late


@pytest.mark.parametrize("signum, status", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_stops_a_long_run_within_seconds_and_nothing_is_written(tmp_path, signum, status):
    out = tmp_path / "plate"
    code, message, late = run(["engrave", "--surface", "dome", "--out", str(out)], signal_after=4.0, signum=signum)
    assert code == status, message[-2000:]
    assert f"stopped by {signal.Signals(signum).name}" in message and "nothing was written" in message
    assert "Traceback" not in message
    assert late is not None and late < 3.0, f"stopped {late:.1f} s after the signal"
    assert everything_under(tmp_path) == []          # no --out folder, no staging folder left


def test_handlers_are_restored_after_the_run(tmp_path):
    before = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    code, message, _ = run(["unfold", "--out", str(tmp_path / "a")])
    assert code == 0, message
    assert (signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)) == before


def test_a_folder_in_the_way_of_the_report_leaves_out_as_it_was(tmp_path):
    out = tmp_path / "sheet"
    (out / "report.json").mkdir(parents=True)
    (out / "keep.txt").write_text("an earlier file\n")
    code, message, _ = run(["unfold", "--out", str(out)])
    assert code == 2, message
    assert str(out / "report.json") in message and "folder" in message
    assert ".kezuri-staging" not in message
    assert everything_under(tmp_path) == ["sheet", os.path.join("sheet", "keep.txt"),
                                          os.path.join("sheet", "report.json")]


def test_a_successful_run_reports_the_final_paths(tmp_path):
    out = tmp_path / "deep" / "er" / "sheet"
    code, message, _ = run(["unfold", "--out", str(out)])
    assert code == 0, message
    text = (out / "report.json").read_text()
    assert "staging" not in text and str(out / "unfold.nc") in text
    assert sorted(os.listdir(out)) == ["report.json", "setup-sheet.html", "unfold.dxf", "unfold.nc", "unfold.png",
                                       "unfold.svg"]
    assert os.listdir(tmp_path) == ["deep"]


def test_a_full_disk_leaves_out_as_it_was(tmp_path):
    """The NC program (about 1 kB) fits under the limit, the picture (about 17 kB) does not: the
    run must not leave the program without its picture and report."""
    out = tmp_path / "sheet"
    code = ("import resource, signal, sys, runpy\n"
            "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
            "resource.setrlimit(resource.RLIMIT_FSIZE, (8192, 8192))\n"
            f"sys.argv = ['batch.py', 'unfold', '--out', {str(out)!r}]\n"
            f"runpy.run_path({os.path.join(ROOT, 'batch.py')!r}, run_name='__main__')\n")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba-cache"))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, cwd=ROOT,
                          env=env)
    assert done.returncode == 2, done.stderr[-2000:]
    assert "File too large" in done.stderr and str(out) in done.stderr and "staging" not in done.stderr
    assert not out.exists()
    assert [name for name in os.listdir(tmp_path) if name.startswith(".kezuri")] == []



def test_a_signal_lost_in_a_finaliser_still_stops_the_run_before_anything_is_written(tmp_path):
    """The handler's Stopped is lost when the signal lands while Python runs a finaliser (a
    ``__del__``: "unraisable", seen once in a million-move simulate, which then wrote everything
    and exited 0).  Here a finaliser during the run takes the signal: the run goes on, but is
    stopped before its files are moved into --out: exit 130, nothing written."""
    class Finaliser:
        def __del__(self):
            os.kill(os.getpid(), signal.SIGINT)     # the handler runs here: its Stopped is unraisable
            time.sleep(0.05)

    original = BATCH.write_report

    def write_report(folder, report):
        Finaliser()                                  # made and dropped: __del__ runs at once
        return original(folder, report)

    BATCH.write_report = write_report
    try:
        out = tmp_path / "sheet"
        stderr = io.StringIO()
        with time_limit(120), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            code = BATCH.main(["batch.py", "unfold", "--out", str(out)])
    finally:
        BATCH.write_report = original
    assert code == 130, stderr.getvalue()[-2000:]
    assert "stopped by SIGINT" in stderr.getvalue() and "nothing was written" in stderr.getvalue()
    assert everything_under(tmp_path) == []
