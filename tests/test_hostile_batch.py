"""Hostile input to every batch command, in-process (batch's entry point called as a function,
Blender loaded once): each case must end with exit status 2, a message naming the argument or the
value given, no traceback, and no file written; each case has a time limit, so a hang fails.

The numeric options are driven by Hypothesis with values outside what they mean (their ranges are
the scene properties' own limits, so batch and the panel agree), plus the concrete cases found by
hand: arguments that used to be silently clamped to another job, malformed lists, files that are
not what they claim to be."""
import contextlib
import importlib.util
import io
import math
import os
import tempfile

import pytest

bpy = pytest.importorskip("bpy")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from test_hostile import time_limit  # noqa: E402  (one SIGALRM limit for both hostile suites)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE_SECONDS = 120
COUNT = {"cases": 0}


def load_batch():
    spec = importlib.util.spec_from_file_location("kezuri_batch_hostile", os.path.join(ROOT, "batch.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


BATCH = load_batch()


def run(*argv) -> tuple:
    """(exit status, stderr, files written) of ``batch.py <argv> --out <fresh folder>``."""
    COUNT["cases"] += 1
    out = tempfile.mkdtemp(prefix="kezuri-hostile-")
    target = os.path.join(out, "job")
    stderr = io.StringIO()
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(["batch.py", *argv, "--out", target])
        except SystemExit as exit_:
            status = exit_.code
    # every file written, and the --out folder itself when a refused run made it (even empty)
    written = [os.path.join(base, f) for base, _, files in os.walk(out) for f in files]
    if status and os.path.exists(target):
        written.append(target)
    return status, stderr.getvalue(), written


def refused(status, message, written, *names):
    assert status == 2, message[-2000:]
    assert "Traceback" not in message, message[-3000:]
    assert not written, written
    for name in names:
        assert name in message, (name, message[-2000:])


# (command, option, lowest allowed, highest allowed, integer?, lowest excluded?)
NUMERIC = [
    ("elbow", "--diameter", 0.1, None, False, False),
    ("elbow", "--bend-radius", 0.1, None, False, False),
    ("elbow", "--angle", 1.0, 180.0, False, False),
    ("elbow", "--pieces", 2, 60, True, False),
    ("unfold", "--divisions", 1, 500, True, False),
    ("unfold", "--tool-diameter", 0.5, 114.3, False, False),
    ("unfold", "--thickness", 0.01, 12.7, False, False),
    ("unfold", "--pitch", 0.1, None, False, False),
    ("unfold", "--station", 1, 999, True, False),
    ("engrave", "--seed", 0, 2**31 - 1, True, False),
    ("simulate", "--cell", 0.0, None, False, True),
    ("carve", "--angle", -180.0, 180.0, False, False),
    ("carve", "--scallop", 0.0001, None, False, False),
]
SIMULATE_REQUIRED = ("--nc", "x.nc", "--tool", "ball:6", "--stock", "box:0,0,-10,10,10,0")


def allowed(text: str, lo, hi, integer: bool, lo_open: bool) -> bool:
    try:
        value = int(text) if integer else float(text)
    except ValueError:
        return False
    if not math.isfinite(value):
        return False
    return (lo is None or (value > lo if lo_open else value >= lo)) and (hi is None or value <= hi)


def outside(lo, hi, integer: bool):
    """Values a user may type that mean nothing for the option."""
    words = st.sampled_from(["nan", "NaN", "inf", "-inf", "1e999", "-1e999", "1.2.3", "2E1x", "x", "", " ", "1,5",
                             "0x10", "--", "½", "١٢", "1_000_000_000_000_000_000_000"])
    numbers = []
    if lo is not None:
        numbers.append(st.floats(max_value=lo, allow_nan=False).map(repr))
        numbers.append(st.integers(max_value=int(math.floor(lo))).map(str))
    if hi is not None:
        numbers.append(st.floats(min_value=hi, allow_nan=False).map(repr))
        numbers.append(st.integers(min_value=int(math.ceil(hi))).map(str))
    if integer:
        numbers.append(st.floats(allow_nan=False, allow_infinity=False).filter(lambda v: v != int(v)).map(repr))
    return st.one_of(words, st.text(max_size=12), *numbers)


@pytest.mark.parametrize("command, option, lo, hi, integer, lo_open", NUMERIC,
                         ids=[f"{c} {o}" for c, o, *_ in NUMERIC])
@settings(max_examples=45, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(data=st.data())
def test_numbers_that_mean_nothing_are_refused_by_name(command, option, lo, hi, integer, lo_open, data):
    value = data.draw(outside(lo, hi, integer).filter(lambda t: not allowed(t, lo, hi, integer, lo_open)))
    extra = SIMULATE_REQUIRED if command == "simulate" else ()
    status, message, written = run(command, *extra, f"{option}={value}")
    refused(status, message, written, option)


CONCRETE = [
    # silently clamped before: an elbow of 1 degree for 0, of 180 for 360 or inf; two pieces for 0
    (("elbow", "--angle=0"), "--angle"), (("elbow", "--angle=360"), "--angle"), (("elbow", "--angle=inf"), "--angle"),
    (("elbow", "--pieces=0"), "--pieces"), (("unfold", "--divisions=0"), "--divisions"),
    (("unfold", "--thickness=-1"), "--thickness"), (("unfold", "--station=99999"), "--station"),
    (("unfold", "--pitch=0"), "--pitch"), (("unfold", "--pitch=1e-6"), "--pitch"),
    (("unfold", "--thickness=inf"), "--thickness"), (("elbow", "--diameter=0"), "--diameter"),
    # malformed lists
    (("unfold", "--corners", "a,b,c"), "--corners"),
    (("unfold", "--corners", "0,0,0;0,30,100;100,50,100"), "--corners"),
    (("unfold", "--corners", "0,0,0;0,30,100;100,50,100;100,40,1.0E999"), "--corners"),
    (("stepnc", "--order", "1,x"), "--order"), (("stepnc", "--order", "999"), "--order"),
    (("simulate", "--nc", "missing.nc", "--tool", "ball:6", "--stock", "box:0,0,-10,10,10,0"), "missing.nc"),
    # unknown choices
    (("engrave", "--post", "heidenhain"), "--post"), (("rotary", "--post", "grbl"), "--post"),
    (("stepnc", "--post", "fanuc-macro"), "--post"), (("turnmill", "--engine", "embree"), "--engine"),
    # M19 asked of a post that does not write it (refused before any work, never left out)
    (("engrave", "--post", "linuxcnc", "--orient-spindle"), "--orient-spindle"),
    (("carve", "--post", "grbl", "--orient-spindle"), "--orient-spindle"),
    (("stepnc", "--post", "linuxcnc", "--orient-spindle"), "--orient-spindle"),
    # a turret punch job the machine cannot run: refused naming what the user gave, not the NC
    (("unfold", "--pitch", "12", "--tool-diameter", "10"), "--tool-diameter"),
    (("unfold", "--pitch", "10"), "--pitch = 10 mm must be less than --tool-diameter = 10 mm"),
    (("unfold", "--tool-diameter", "0"), "--tool-diameter"), (("unfold", "--tool-diameter", "500"), "--tool-diameter"),
    (("unfold", "--corners", "0,0,0;0,30000,100;50000,50000,100;50000,40,0"), "--corners"),
    (("unfold", "--corners", "0,0,0;0,3000,100;5000,5000,100;5000,40,0", "--pitch", "0.1"), "--pitch = 0.1 mm"),
    (("elbow", "--diameter", "20000", "--bend-radius", "30000"), "--diameter = 20000 mm"),
    # files that are not what they claim
    (("stepnc", "--input", "missing.stp"), "missing.stp"),
    (("unfold", "--cdl", "missing.cdl"), "missing.cdl"),
    (("turnmill", "--mesh", "missing.stl"), "missing.stl"),
]


@pytest.mark.parametrize("argv, name", CONCRETE, ids=[" ".join(a) for a, _ in CONCRETE])
def test_concrete_hostile_cases(argv, name):
    status, message, written = run(*argv)
    refused(status, message, written, name)


def test_a_file_that_is_not_a_blend_file(tmp_path):
    fake = tmp_path / "fake.blend"
    fake.write_bytes(os.urandom(2048))
    status, message, written = run("engrave", "--blend", str(fake))
    refused(status, message, written, "fake.blend")


def test_an_output_folder_that_is_a_file(tmp_path):
    blocker = tmp_path / "afile"
    blocker.write_text("x")
    stderr = io.StringIO()
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        status = BATCH.main(["batch.py", "elbow", "--out", str(blocker / "sub")])
    assert status == 2 and "Traceback" not in stderr.getvalue() and "afile" in stderr.getvalue()
    assert blocker.read_text() == "x"


@pytest.mark.parametrize("shape", ["file", "under a file", "read-only parent"])
def test_an_unusable_output_folder_is_named_before_any_work(tmp_path, shape):
    """--out is checked before the job: a file, a folder under a file, or a folder that would
    have to be made in a read-only one is refused naming --out and the path; nothing is made."""
    blocker = tmp_path / "afile"
    blocker.write_text("x")
    locked = tmp_path / "locked"
    locked.mkdir()
    out = {"file": blocker, "under a file": blocker / "sub", "read-only parent": locked / "job"}[shape]
    if shape == "read-only parent":
        locked.chmod(0o555)
        if os.access(locked, os.W_OK):
            pytest.skip("running as a user who may write anywhere (root)")
    stderr = io.StringIO()
    try:
        with time_limit(CASE_SECONDS), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            status = BATCH.main(["batch.py", "unfold", "--out", str(out)])
    finally:
        locked.chmod(0o755)
    message = stderr.getvalue()
    assert status == 2 and "Traceback" not in message, message
    assert "--out" in message and str(out) in message, message
    assert blocker.read_text() == "x" and sorted(p.name for p in tmp_path.iterdir()) == ["afile", "locked"]
    assert not list(locked.iterdir())


def test_the_suite_is_as_large_as_the_readme_says():
    """Counted when the whole module runs: the README states the number of hostile inputs."""
    if COUNT["cases"] < len(CONCRETE):
        pytest.skip("run with the whole module to count")
    assert COUNT["cases"] >= 500, COUNT


def test_a_part_mesh_with_a_nan_vertex_is_named(tmp_path):
    stl = tmp_path / "nan-part.stl"
    stl.write_text("solid p\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 10 0 0\nvertex nan 10 0\n"
                   "endloop\nendfacet\nendsolid p\n")
    status, message, written = run("turnmill", "--mesh", str(stl))
    refused(status, message, written, "finite")
