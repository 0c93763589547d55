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

import numpy as np
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
    ("unfold", "--joints", 0, 8, True, False),
    ("elbow", "--joint-width", 0.05, 5.0, False, False),
    ("unfold", "--clamp-depth", 1.0, 1000.0, False, False),
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
    # the sheet, its clamps and the micro-joints (issue 26): malformed, or a part that fits nowhere
    (("unfold", "--clamps", "200,x"), "--clamps"), (("unfold", "--sheet-origin", "1,2,3"), "--sheet-origin"),
    (("unfold", "--sheet-size", "nan,100"), "--sheet-size"), (("elbow", "--sheet-size", "5,1e6"), "--sheet-size"),
    (("unfold", "--sheet-size", "300,150", "--clamps", "60,150,250"), "meets clamp 1 (dead zone X 20..100"),
    (("elbow", "--joints", "8"), "micro-joints: 8 joint(s) do not fit"),
    # files that are not what they claim
    (("stepnc", "--input", "missing.stp"), "missing.stp"),
    (("unfold", "--cdl", "missing.cdl"), "missing.cdl"),
    (("turnmill", "--mesh", "missing.stl"), "missing.stl"),
    # the elbow's DXF and SVG were written before a piece's punch program was refused: left behind
    (("elbow", "--diameter=1e6", "--bend-radius=1e6"), "piece 1 of --diameter = 1e+06 mm"),
    # (its curves merge into straight lines now: the 10 mm punch leaves no room for the micro-joints)
    (("elbow", "--diameter=0.1", "--bend-radius=0.1", "--angle=1", "--pieces=2"), "elbow piece 1 of 2: micro-joints"),
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


@pytest.mark.parametrize("out", ["", "  "])
def test_an_empty_output_folder_is_refused_not_taken_as_the_working_folder(tmp_path, out, monkeypatch):
    """--out "$OUT" with OUT unset: the elbow's files were written into the working folder."""
    monkeypatch.chdir(tmp_path)
    stderr = io.StringIO()
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        status = BATCH.main(["batch.py", "elbow", "--out", out])
    assert status == 2 and "--out is empty" in stderr.getvalue(), stderr.getvalue()
    assert list(tmp_path.iterdir()) == []


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


def box_stl(path, lo, hi) -> str:
    """A closed box from ``lo`` to ``hi`` (mm) as an ASCII STL, its normals outward."""
    import trimesh

    box = trimesh.creation.box(bounds=[lo, hi])
    path.write_bytes(box.export(file_type="stl"))
    return str(path)


@pytest.mark.parametrize("lo, hi, names", [
    # 5 m off the spindle axis: was planned as a 10 m bar (X10044) in 6 minutes with no word
    ((4980.0, -20.0, -60.0), (5020.0, 20.0, 0.0), ("off the spindle axis", "X 4980 to 5020 mm", "model it around")),
    ((5.0, 5.0, -30.0), (25.0, 25.0, 0.0), ("off the spindle axis", "X 5 to 25 mm")),
])
def test_a_turned_part_off_the_spindle_axis_is_refused_naming_where_it_lies(tmp_path, lo, hi, names):
    status, message, written = run("turnmill", "--mesh", box_stl(tmp_path / "part.stl", lo, hi))
    refused(status, message, written, "part.stl", *names)


def test_a_flat_turned_part_is_named_as_flat_along_the_axis(tmp_path):
    stl = tmp_path / "flat.stl"
    stl.write_text("solid p\nfacet normal 0 0 1\nouter loop\nvertex -10 -10 0\nvertex 10 -10 0\nvertex 10 10 0\n"
                   "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex -10 -10 0\nvertex 10 10 0\n"
                   "vertex -10 10 0\nendloop\nendfacet\nendsolid p\n")
    status, message, written = run("turnmill", "--mesh", str(stl))
    assert status == 2 and not written and "Traceback" not in message, message[-2000:]
    assert "stock z_min" not in message and "flat.stl" in message


SIMULATE_BOX = ("--tool", "flat:6", "--stock", "box:0,0,-10,40,40,0")


def test_an_empty_nc_file_is_refused_naming_it(tmp_path):
    empty = tmp_path / "empty.ngc"
    empty.write_text("")
    status, message, written = run("simulate", "--nc", str(empty), *SIMULATE_BOX)
    refused(status, message, written, f"--nc {empty}: the NC file has no moves")


def test_an_nc_file_in_utf8_with_kanji_comments_and_a_closing_percent_is_read(tmp_path):
    """UTF-8 工具 holds the byte 0x85 (U+0085 read as latin-1, a line break to str.splitlines):
    refused before as an unbalanced parenthesis; the moves after the closing % were cut too."""
    nc = tmp_path / "kanji.ngc"
    nc.write_bytes("%\r\n(荒削り 工具 T1)\r\nG21 G90\r\nG0 X5 Y5 Z5\r\nG1 Z-1 F100 (工具)\r\nX30\r\nG0 Z5\r\n"
                   "%\r\nG1 Z-9\r\n".encode("utf-8"))
    out = tmp_path / "out"
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
        status = BATCH.main(["batch.py", "simulate", "--nc", str(nc), *SIMULATE_BOX, "--out", str(out)])
    assert status == 0
    import json
    report = json.loads((out / "report.json").read_text())
    assert report["moves"] == 4 and report["simulation"]["removed_volume_mm3"] < 30 * 6 * 1.2, report


def stl(path, vertices):
    """An ASCII STL of the triangles (vertices as text, so 'nan' and 1e300 stay as written)."""
    facets = "".join("facet normal 0 0 1\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in tri) +
                     "endloop\nendfacet\n" for tri in vertices)
    path.write_text(f"solid t\n{facets}endsolid t\n")
    return str(path)


TETRA = [[(0, 0, 0), (40, 0, 0), (0, 30, 0)], [(0, 0, 0), (0, 30, 0), (0, 0, -10)],
         [(0, 0, 0), (0, 0, -10), (40, 0, 0)], [(40, 0, 0), (0, 0, -10), (0, 30, 0)]]


@pytest.mark.parametrize("command, scale, named", [
    # 1e300 mm: carve's raster over the design's box never ended (a hang); turnmill read it as "a face
    # uses the same vertex twice" (trimesh's merging rounded the corners together)
    ("carve", 1e300, "reaches 4e+301 mm"), ("turnmill", 1e300, "reaches 4e+301 mm"),
    ("engrave", 1e300, "reaches 4e+301 mm"), ("carve", 1e12, "reaches 4e+13 mm"), ("turnmill", 1e12, "reaches 4e+13 mm"),
    # a NaN corner: carve's loader dropped the face and said "needs (n, 3) vertices, got shape (2, 3)", naming no file
    ("carve", math.nan, "non-finite"), ("engrave", math.nan, "non-finite"), ("turnmill", math.nan, "NaN"),
])
def test_mesh_files_with_absurd_coordinates_are_refused_naming_the_file(tmp_path, command, scale, named):
    if math.isnan(scale):
        tris = [list(tri) for tri in TETRA]
        tris[0][1] = (math.nan, 0, 0)
    else:
        tris = [[(x * scale, y * scale, z * scale) for x, y, z in tri] for tri in TETRA]
    path = stl(tmp_path / "odd part.stl", tris)
    option = {"carve": "--mesh", "turnmill": "--mesh", "engrave": "--surface"}[command]
    status, message, written = run(command, option, path)
    refused(status, message, written, f"{option} {path}: ", named)


ORDER_CASES = [("13,13", "#13 is given more than once"), ("13,14,10,13", "#13 is given more than once"),
               ("13,,14", "instance ids separated by commas")]


@pytest.mark.parametrize("order, named", ORDER_CASES)
def test_an_order_naming_a_workingstep_twice_is_refused_not_rearranged(order, named):
    # before: the later mention moved it, so 13,14,10,13 cut 14, 10, 13; an empty item was dropped
    status, message, written = run("stepnc", "--input", EX1, "--order", order)
    refused(status, message, written, "--order", named)


EX1 = os.path.join(ROOT, "tests", "fixtures", "iso14649", "ex1.stp")
EX1_AP238 = os.path.join(ROOT, "tests", "fixtures", "iso14649", "ex1_ap238.stp")
MM = "#900=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));"


def conversion_unit(name, factor, base="#9002"):
    return (f"#900=(CONVERSION_BASED_UNIT('{name}',#9001)LENGTH_UNIT()NAMED_UNIT(#905));\n"
            f"#9001=LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE({factor}),{base});\n"
            "#9002=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));")


@pytest.mark.parametrize("source, old, new, named", [
    # a pocket 1.0E300 mm or 1.0E999 (inf) from the origin: a numpy traceback before
    (EX1, "(70.000, 70.000, 0.000)", "(70.000, 1.0E300, 0.000)", "#115 CARTESIAN_POINT: coordinates 1e+300"),
    (EX1, "(70.000, 70.000, 0.000)", "(70.000, 1.0E999, 0.000)", "#115 CARTESIAN_POINT: coordinates inf"),
    # a workingstep numbered past Blender's int: "bpy_struct ... not in 'int' range" traceback before
    (EX1, "(#10,#11,", "(#99999999999999999999999,#11,", "workingstep #99999999999999999999999"),
    # a negative pocket length was taken as its size without a word
    (EX1, "#121= TOLERANCED_LENGTH_MEASURE(80.000,#123);", "#121= TOLERANCED_LENGTH_MEASURE(-80.0,#123);",
     "#28 RECTANGULAR_CLOSED_PROFILE: profile_length -80 mm is negative"),
    # AP238 length units it could not convert were read as millimetres (a yard, a nanometre, kelvin ...)
    (EX1_AP238, MM, conversion_unit("FURLONG", "201168."), "is larger than 100000 mm"),
    (EX1_AP238, MM, conversion_unit("ZERO", "0."), "#900 CONVERSION_BASED_UNIT 'ZERO': a length unit of 0 mm"),
    (EX1_AP238, MM, conversion_unit("INCH", "25.4", base="#900"), "its conversion factor is given in itself"),
    (EX1_AP238, MM, MM.replace(".MILLI.", ".BOGUS."), "#900 SI_UNIT: BOGUS is not an SI prefix"),
    (EX1_AP238, MM, MM.replace(".MILLI.,.METRE.", "$,.KELVIN."), "#900 SI_UNIT: a length unit in KELVIN"),
    (EX1_AP238, MM, MM.replace(".MILLI.", ".NANO."), "stepover 1.71e-05 mm"),    # honoured: a part 0.1 um across
])
def test_part21_values_that_used_to_crash_or_pass_silently(tmp_path, source, old, new, named):
    text = open(source).read()
    assert old in text
    if new.startswith("(#9999"):
        text = text.replace("#10= MACHINING_WORKINGSTEP(", "#99999999999999999999999= MACHINING_WORKINGSTEP(")
    path = tmp_path / "changed.stp"
    path.write_text(text.replace(old, new, 1))
    status, message, written = run("stepnc", "--input", str(path))
    refused(status, message, written, named)


def test_an_inch_ap238_part_is_checked_by_the_gate_on_a_coarser_grid(tmp_path):
    """ex1 read in inches is 3.2 x 4.6 m: more cells than the gate's 0.1 mm grid may have.  It was
    refused, saying "use a coarser cell" (a setting stepnc does not have); so was a 1200 x 600 mm
    sign for engraving.  The gate now doubles its cell until the stock fits (0.8 mm here), and the
    report says which."""
    path = tmp_path / "inch.stp"
    path.write_text(open(EX1_AP238).read().replace(MM, conversion_unit("INCH", "25.4")))
    out = tmp_path / "out"
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
        status = BATCH.main(["batch.py", "stepnc", "--input", str(path), "--out", str(out),   # a machine that holds it
                             "--machine", "fanuc-vmc", "--travel", "6000", "6000", "2000", "--clearance-max", "1500"])
    assert status == 0
    import json
    assert json.loads((out / "report.json").read_text())["gate"]["cell_mm"] == 0.8


def test_a_stock_too_large_even_for_the_gates_coarsest_grid_says_it_is_the_gate(tmp_path):
    path = tmp_path / "far.stp"
    path.write_text(open(EX1).read().replace("(70.000, 70.000, 0.000)", "(90000.0, 90000.0, 0.000)"))
    status, message, written = run("stepnc", "--input", str(path))
    refused(status, message, written, "the export gate simulates every program before writing it, and cannot on "
                                      "this job's stock even at 1.6 mm")


def test_a_cell_of_1e_300_is_refused_in_a_message_a_person_can_read(tmp_path):
    nc = tmp_path / "slot.ngc"
    nc.write_text("G21 G90\nG0 X5 Y5 Z5\nG1 Z-1 F100\nX30\nG0 Z5\nM2\n")
    status, message, written = run("simulate", "--nc", str(nc), *SIMULATE_BOX, "--cell", "1e-300")
    refused(status, message, written, "a 1e-300 mm cell gives 4e+301 x 4e+301 cells")
    assert len(message) < 300, message


@pytest.mark.parametrize("tool, named", [
    ("flat:1e6", "diameter 1e+06 mm is outside the allowed range 0.1 <= diameter <= 100 mm"),   # ran before
    ("ball:1e-9", "diameter 1e-09 mm is outside"),                                               # ran before
    ("bull:200,60", "diameter 200 mm is outside"),
])
def test_simulate_tool_sizes_keep_to_the_one_table_of_ranges(tmp_path, tool, named):
    nc = tmp_path / "slot.ngc"
    nc.write_text("G21 G90\nG0 X5 Y5 Z5\nG1 Z-1 F100\nX30\nG0 Z5\nM2\n")
    status, message, written = run("simulate", "--nc", str(nc), "--tool", tool, "--stock", "box:0,0,-10,40,40,0")
    refused(status, message, written, f"--tool '{tool}'", named)


@pytest.mark.parametrize("command", ["engrave", "rotary"])
def test_a_blend_whose_unit_scale_puts_the_plate_past_100_m_is_refused_by_name(tmp_path, command):
    """Blender allows a unit scale up to 1e9 m per unit: the sample plate then lies 1e14 mm out,
    and Clipper raised "RuntimeError: Values exceed permitted range" (a traceback)."""
    BATCH.load_extension()
    from kezuri.operators import batchio, samples
    scene = batchio.open_blend(None)
    (samples.name_plate if command == "engrave" else samples.rotary_block)(scene)
    scene.unit_settings.scale_length = 1e9
    path = tmp_path / f"{command}-huge-units.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    status, message, written = run(command, "--blend", str(path))
    refused(status, message, written, "reaches 1e+14 mm" if command == "engrave" else "reaches 5.25e+13 mm",
            "unit scale of 1e+09 m per unit")


PAPER_CDL = ("LINE 0, 0, 0,\n0, 30, 100, 1, 1, 1,\n0, 0, 1, 1\nLINE 0, 30, 100,\n100, 50, 100, 1, 1,\n1, 0, 0, 1, 1\n"
             "LINE 100, 50, 100,\n100, 40, 0, 1, 1, 1,\n0, 0, 1, 1\nLINE 100, 40, 0,\n0, 0, 0, 1, 1, 1, 0,\n0, 1, 1\n")


@pytest.mark.parametrize("name, data, named", [
    # a CDL 1e12 mm across passed unchecked to the punch simulation ("more than 20000 hits ... pitches Q")
    ("huge.cdl", PAPER_CDL.replace("100,", "1e12,").encode(), "corner P2 (0, 30, 1e+12) is outside the allowed range"),
    # str.splitlines broke at the form feed: the bad record (line 10) was reported on line 11
    ("formfeed.cdl", PAPER_CDL.replace("1, 1, 1, 0,\n0, 1, 1", "1, 1, 1, 0,\n0, 1").replace("LINE 100, 50", "\x0cLINE 100, 50")
     .encode(), "CDL line 10: LINE record has 12 numbers"),
])
def test_cdl_files_are_read_by_their_own_lines_and_ranges(tmp_path, name, data, named):
    path = tmp_path / name
    path.write_bytes(data)
    status, message, written = run("unfold", "--cdl", str(path))
    refused(status, message, written, named)


def test_a_cdl_file_with_a_utf8_byte_order_mark_is_read(tmp_path):
    """The BOM, read as latin-1, glued itself to the first LINE word: 'found 3 LINE records'."""
    path = tmp_path / "bom.cdl"
    path.write_bytes(b"\xef\xbb\xbf" + PAPER_CDL.encode())
    out = tmp_path / "out"
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
        status = BATCH.main(["batch.py", "unfold", "--cdl", str(path), "--out", str(out)])
    assert status == 0 and (out / "unfold.nc").exists()


def test_corners_out_of_the_panels_range_are_refused_naming_the_option():
    status, message, written = run("unfold", "--corners", "0,0,0;0,30,100;100,50,100;1e6,40,0")
    refused(status, message, written, "--corners: corner P4 (1e+06, 40, 0) is outside the allowed range")


def test_a_1200_by_600_mm_sign_is_engraved_and_checked(tmp_path):
    """A sign board of 1200 x 600 mm (the sample at 6 mm per unit): the gate's 0.1 mm grid had more
    cells than it could hold, so nothing could be exported, from batch or the panel; then it was
    checked on 0.2 mm cells; now (72 M cells, about 1.5 GB at the peak) on the gate's own 0.1 mm."""
    BATCH.load_extension()
    from kezuri.operators import batchio, samples
    scene = batchio.open_blend(None)
    samples.name_plate(scene)
    scene.unit_settings.scale_length = 0.006
    blend = tmp_path / "sign.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    out = tmp_path / "out"
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
        status = BATCH.main(["batch.py", "engrave", "--blend", str(blend), "--post", "linuxcnc", "--out", str(out),
                             "--travel", "1400", "800", "150"])      # the preset's 600 x 400 mm would not hold it
    assert status == 0
    import json
    report = json.loads((out / "report.json").read_text())
    assert report["gate"]["cell_mm"] == 0.1 and report["gate"]["findings"] == []


def test_c_words_without_rotary_are_refused_not_dropped(tmp_path):
    """A program turning C, simulated without --rotary c: the C words were dropped silently and the
    report showed only the plunge (28 mm^3 instead of a half-turn groove)."""
    nc = tmp_path / "turns.ngc"
    nc.write_text("G21 G90\nG0 X-10 Y0 Z5 C0\nG1 Z-1 F100\nG1 C90\nG1 C180\nG0 Z5\nM2\n")
    status, message, written = run("simulate", "--nc", str(nc), "--tool", "flat:6", "--stock", "cylinder:20,10")
    refused(status, message, written, f"--nc {nc}: line 4 turns the C axis; give --rotary c")


def test_a_flat_design_with_no_stock_above_it_is_refused_naming_the_design(tmp_path):
    """A single flat square as the design: the gate said "stock box (0, 0, 0)..(40, 30, 0) encloses
    no volume", naming neither the design nor what to change."""
    path = tmp_path / "plane.obj"
    path.write_text("v 0 0 0\nv 40 0 0\nv 40 30 0\nv 0 30 0\nf 1 2 3\nf 1 3 4\n")
    status, message, written = run("carve", "--mesh", str(path))
    refused(status, message, written, "the design is flat (Z 0 mm everywhere)", "Stock Above in the Carve panel")


def test_a_relief_scaled_to_nothing_is_refused_before_planning(tmp_path):
    """A 40 mm dome scaled by 1e-9 (metres twice over): refused up front naming its size, not
    planned and then refused by the gate's grid."""
    import trimesh

    stl = tmp_path / "tiny.stl"
    dome = trimesh.creation.icosphere(subdivisions=2, radius=20.0)
    dome.apply_scale(1e-9)
    stl.write_bytes(dome.export(file_type="stl"))
    status, message, written = run("carve", "--mesh", str(stl))
    refused(status, message, written, "tiny.stl", "under 0.5 mm across", "other units")
    assert "roughing" not in message          # no planning progress before the refusal


def test_a_dense_turned_part_is_counted_not_listed_in_the_report(tmp_path):
    """A bar of 24,576 faces (a flat milled on it): report.json gives the count of each class and
    says the faces are not listed (a 790k-face bar wrote a 90 MB report), and the counts add up."""
    import json

    import manifold3d as m3
    import trimesh

    bar = m3.Manifold.cylinder(40, 15, 15, 256).translate((0, 0, -40)) - m3.Manifold.cube((20, 40, 20)).translate((10, -20, -30))
    mesh = bar.to_mesh()
    part = trimesh.Trimesh(np.asarray(mesh.vert_properties)[:, :3], np.asarray(mesh.tri_verts)).subdivide().subdivide()
    assert len(part.faces) > 20000
    stl = tmp_path / "bar.stl"
    stl.write_bytes(part.export(file_type="stl"))
    out = tmp_path / "out"
    with time_limit(240):
        status = BATCH.main(["batch.py", "turnmill", "--mesh", str(stl), "--post", "linuxcnc", "--out", str(out)])
    assert status == 0
    report = json.load(open(out / "report.json"))
    assert isinstance(report["faces"], str) and "counted" in report["faces"]
    assert sum(report["face_counts"].values()) == len(part.faces)
    assert report["face_counts"]["radial"] > 0 and os.path.getsize(out / "report.json") < 200_000


@pytest.mark.parametrize("text, named", [
    ("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=WORKPLAN(,;\nENDSEC;\nEND-ISO-10303-21;\n",
     ": line 5, column 13 (#1): expected a parameter value, found ','"),
    ("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=FOO(1.0);\nENDSEC;\nEND-ISO-10303-21;\n",
     ": an ISO 14649 file needs exactly one PROJECT, this one has 0"),
])
def test_an_error_in_a_stepnc_file_names_the_file_as_typed(tmp_path, monkeypatch, text, named):
    """The reader names the line, column and instance; the user also needs to know which file (a
    shop runs batches over folders of them), as given on the command line."""
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "plate 7.stp").write_text(text)
    monkeypatch.chdir(tmp_path)
    status, message, written = run("stepnc", "--input", os.path.join("parts", "plate 7.stp"))
    refused(status, message, written, os.path.join("parts", "plate 7.stp") + named)


def test_a_folder_given_as_the_stepnc_file_is_named_as_a_folder(tmp_path):
    folder = tmp_path / "plate.stp"
    folder.mkdir()
    status, message, written = run("stepnc", "--input", str(folder))
    refused(status, message, written, f"--input {folder}: a folder, not a file")
