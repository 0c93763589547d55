"""Every file a user hands the add-on, in every hostile CLASS, through every entry point that takes
one: batch's options and positional files (in-process, as tests/test_hostile_batch.py runs them),
the files a job file names, and the operators that import files (through real bpy).

The classes: a missing file; a folder; an empty file; binary garbage; a file cut short in the
middle; a UTF-8 byte-order mark, UTF-16 and Latin-1 text; a good file under a path with spaces and
Japanese characters (it must WORK); a path under a file (ENOTDIR: root is not stopped by permission
bits, so "unreadable" is a path no one can open); a symlink loop; a path too long for the file
system (ENAMETOOLONG); a file past the reader's size limit where there is one.

A refused case must end with exit status 2 (batch) or CANCELLED with an ERROR report (operator), a
message naming the file as the user typed it, no traceback, no "[Errno" text (the OS's words, not
ours), and nothing written."""
import contextlib
import io
import os
import shutil
import tempfile

import pytest

bpy = pytest.importorskip("bpy")
from test_hostile import time_limit  # noqa: E402
from test_hostile_batch import BATCH  # noqa: E402
from test_unfold import PAPER_CDL  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIXTURES = os.path.join(ROOT, "tests", "fixtures")
CASE_SECONDS = 120
COUNT = {"cases": 0}
JAPANESE = "部品 フォルダ"          # a folder name with a space and Japanese characters

# ----- good files of every format -------------------------------------------------------------------

with open(os.path.join(FIXTURES, "iso14649", "ex1.stp"), "rb") as _stream:
    STEP = _stream.read().replace(b"HEADER;", "HEADER;\n/* 切削 café */".encode(), 1)   # non-ASCII in a comment

CDL = PAPER_CDL.encode()                 # the seed paper's quad (tests/test_unfold.py)


def box_stl(lo, hi) -> bytes:
    """An ASCII STL of the box lo..hi (outward facets), written here, not by the code under test."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    lines = ["solid box"]
    for a, b, c, d in quads:
        for tri in ((a, b, c), (a, c, d)):
            lines.append("facet normal 0 0 0\n outer loop")
            lines += [f"  vertex {v[i][0]} {v[i][1]} {v[i][2]}" for i in tri]
            lines.append(" endloop\nendfacet")
    lines.append("endsolid box\n")
    return "\n".join(lines).encode()


def box_obj(lo, hi) -> bytes:
    """The box lo..hi as a Wavefront OBJ (quads, 1-based corners), with a comment in Japanese."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    quads = [(1, 4, 3, 2), (5, 6, 7, 8), (1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8)]
    return ("# 彫刻の箱 café\n" + "".join(f"v {x} {y} {z}\n" for x, y, z in v)
            + "".join("f " + " ".join(map(str, q)) + "\n" for q in quads)).encode()


OBJ = box_obj((-20, -20, -3), (20, 20, 0))
SURFACE = box_stl((-150, -100, -2), (150, 100, 0))
TURNED = box_stl((-10, -10, 0), (10, 10, 30))
CARVED = box_stl((-20, -20, -3), (20, 20, 0))
NC = b"%\n(a square, kanji comment: \xe5\x88\x87\xe5\x89\x8a caf\xc3\xa9)\nG21 G90 G17\nG0 Z5\nG0 X0 Y0\nG1 Z-1 F200\n" \
     b"G1 X10\nG1 Y10\nG1 X0\nG1 Y0\nG0 Z5\nM2\n%\n"
SVG = b'<?xml version="1.0" encoding="UTF-8"?>\n<svg xmlns="http://www.w3.org/2000/svg" width="60mm" ' \
      b'height="40mm" viewBox="0 0 60 40">\n  <!-- \xe7\xae\xb1 caf\xc3\xa9 -->\n  <rect x="10" y="10" width="40" ' \
      b'height="20"/>\n</svg>\n'


def dxf() -> bytes:
    pairs = [(0, "SECTION"), (2, "HEADER"), (9, "$ACADVER"), (1, "AC1009"), (9, "$INSUNITS"), (70, 4),
             (0, "ENDSEC"), (0, "SECTION"), (2, "ENTITIES")]
    for (x0, y0), (x1, y1) in (((0, 0), (40, 0)), ((40, 0), (40, 25)), ((40, 25), (0, 25)), ((0, 25), (0, 0))):
        pairs += [(0, "LINE"), (8, "CUT"), (10, x0), (20, y0), (30, 0.0), (11, x1), (21, y1), (31, 0.0)]
    pairs += [(0, "ENDSEC"), (0, "EOF")]
    return "".join(f"{code:>3}\n{value}\n" for code, value in pairs).encode()


DXF = dxf()
JOB = b"""# a drilling job (\xe7\xa9\xb4, caf\xc3\xa9)
[setup]
name = "holes"
stock = [-20.0, -20.0, -10.0, 20.0, 20.0, 0.0]
post = "linuxcnc"

[[operations]]
kind = "drill"
name = "{{name}}"
holes = [[-10.0, -10.0], [10.0, 10.0]]
settings = { tool_number = 4, diameter = 5.0, depth = 5.0, peck = 2.0, rpm = 3000, feed = 150 }
"""
BLEND_JOB = JOB.replace(b"stock = [-20.0, -20.0, -10.0, 20.0, 20.0, 0.0]", b'blend = "PATH"').replace(b"{{name}}", b"h")
ROWS = "name\nJosé\n鈴木\n".encode()
with open(os.path.join(FIXTURES, "tools", "kezuri-tools.toml"), "rb") as _stream:
    TOOLS = _stream.read()
with open(os.path.join(FIXTURES, "tools", "shop.tbl"), "rb") as _stream:
    TABLE = _stream.read()


def font() -> bytes:
    folder = bpy.utils.system_resource("DATAFILES", path="fonts")
    with open(os.path.join(folder, "DejaVuSansMono.woff2"), "rb") as stream:
        return stream.read()


def blend() -> bytes:
    """A .blend of an empty scene (its Sheet Metal settings at their defaults: a quad to unfold)."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "sheet.blend")
        bpy.ops.wm.save_as_mainfile(filepath=path, copy=True)
        with open(path, "rb") as stream:
            return stream.read()


# ----- entry points -----------------------------------------------------------------------------------
# name: (file name, good bytes or None (no good case here), a text format?, cut short is detectable?,
#        size limit or None, argv of the batch command for a path)

def job_file(tmp, path, line):
    """A job file beside the case that names ``path`` in an operation (the path as the user types it)."""
    job = os.path.join(tmp, "job.toml")
    with open(job, "w", encoding="utf-8") as stream:
        stream.write("[setup]\nname = \"j\"\nsample = \"name_plate\"\npost = \"linuxcnc\"\n\n[[operations]]\n"
                     + line.replace("PATH", path.replace("\\", "\\\\").replace('"', '\\"')) + "\n")
    return job


ENTRIES = {
    "stepnc --input": ("part.stp", STEP, True, True, None, lambda tmp, p: ["stepnc", "--input", p]),
    "unfold --cdl": ("quad.cdl", CDL, True, True, None, lambda tmp, p: ["unfold", "--cdl", p]),
    "turnmill --mesh": ("part.stl", TURNED, False, True, None,
                        lambda tmp, p: ["turnmill", "--mesh", p]),
    "carve --mesh": ("design.stl", CARVED, False, True, None, lambda tmp, p: ["carve", "--mesh", p]),
    "carve --mesh (.obj)": ("design.obj", OBJ, True, True, None, lambda tmp, p: ["carve", "--mesh", p]),
    "engrave --surface": ("surface.stl", SURFACE, False, True, None, lambda tmp, p: ["engrave", "--surface", p]),
    "simulate --nc": ("job.ngc", NC, True, False, None,
                      lambda tmp, p: ["simulate", "--nc", p, "--tool", "flat:3", "--stock", "box:-5,-5,-5,15,15,0"]),
    "simulate --design": ("part.stl", CARVED, False, True, None,
                          lambda tmp, p: ["simulate", "--nc", put(tmp, "ok.ngc", NC), "--tool", "flat:3",
                                          "--stock", "box:-20,-20,-5,20,20,0", "--design", p]),
    "profile --svg": ("design.svg", SVG, True, True, 100_000_000, lambda tmp, p: ["profile", "--svg", p]),
    "pocket --dxf": ("design.dxf", DXF, True, True, 100_000_000, lambda tmp, p: ["pocket", "--dxf", p]),
    "vcarve --font": ("font.woff2", font(), False, True, None,
                      lambda tmp, p: ["vcarve", "--text", "A", "--font", p]),
    "job FILE": ("job.toml", JOB.replace(b"{{name}}", b"holes"), True, True, None, lambda tmp, p: ["job", p]),
    "job TEMPLATE --each": ("template.toml", JOB, True, True, None,
                            lambda tmp, p: ["job", p, "--each", put(tmp, "rows.csv", ROWS)]),
    "job --each": ("rows.csv", ROWS, True, False, None,
                   lambda tmp, p: ["job", put(tmp, "template.toml", JOB), "--each", p]),
    "job: file = (stepnc)": ("part.stp", STEP, True, True, None,
                             lambda tmp, p: ["job", job_file(tmp, p, 'kind = "stepnc"\nname = "wp"\nfile = "PATH"')]),
    "job: design = (svg)": ("design.svg", SVG, True, True, 100_000_000,
                            lambda tmp, p: ["job", job_file(tmp, p, 'kind = "profile"\nname = "cut"\n'
                                                                    'design = { file = "PATH" }\n'
                                                                    'objects = { shape = "STEM" }'
                                                                    .replace("STEM", stem(p)))]),
    # its good .blend is read by unfold --blend below (a job needs a plate in it to run)
    "job: [setup] blend =": ("plate.blend", None, False, True, None,
                             lambda tmp, p: ["job", put(tmp, "job.toml", BLEND_JOB.replace(b"PATH", toml_path(p)))]),
    "unfold --blend": ("sheet.blend", blend(), False, True, None, lambda tmp, p: ["unfold", "--blend", p]),
    "tools import (.toml)": ("tools.toml", TOOLS, True, True, 20_000_000, lambda tmp, p: ["tools", "import", p, "--replace"]),
    "tools import (.tbl)": ("shop.tbl", TABLE, True, False, 20_000_000, lambda tmp, p: ["tools", "import", p, "--replace"]),
}


def stem(path: str) -> str:
    """The name of the object a design file's curves are made as (its file's name)."""
    return os.path.splitext(os.path.basename(path))[0]


def toml_path(path: str) -> bytes:
    return path.replace("\\", "\\\\").replace('"', '\\"').encode()


def put(folder, name, data: bytes) -> str:
    path = os.path.join(folder, name)
    with open(path, "wb") as stream:
        stream.write(data)
    return path


def run(tmp, argv) -> tuple:
    """(exit status, stderr, files written under --out) of batch.py with argv (tools: no --out)."""
    COUNT["cases"] += 1
    out = os.path.join(tmp, "out")
    tools = argv[0] == "tools"
    full = ["batch.py", *argv] + ([] if tools else ["--out", out])
    stderr = io.StringIO()
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(full)
        except SystemExit as exit_:
            status = exit_.code
    written = [os.path.join(b, f) for b, _, files in os.walk(out) for f in files]
    if status and os.path.exists(out):
        written.append(out)
    return status, stderr.getvalue(), written


CLASSES = ["missing", "folder", "empty", "garbage", "cut short", "bom", "utf-16", "latin-1", "japanese path",
           "under a file", "symlink loop", "too long", "huge"]
GARBAGE = bytes(range(256)) * 8 + b"\x00\xff\xfe" * 100


def latin1(data: bytes) -> bytes | None:
    """The file in ISO 8859-1 (Latin-1): 'é' and '°' one byte each, kanji as '?'; None when the
    file is ASCII (nothing to tell apart)."""
    text = data.decode("utf-8").encode("latin-1", errors="replace")
    return None if text == data else text


def make(tmp: str, spec: tuple, case: str):
    """(path as typed, expectation) for one class: 'refused', 'works' or 'works or refused' (None:
    the class does not apply to this entry's format)."""
    name, good, text, cut_detectable, limit, _ = spec
    stem, ext = os.path.splitext(name)
    if case == "missing":
        return os.path.join(tmp, f"none{ext}"), "refused"
    if case == "folder":
        path = os.path.join(tmp, f"folder{ext}")
        os.mkdir(path)
        return path, "refused"
    if case == "empty":
        return put(tmp, f"empty{ext}", b""), "refused"
    if case == "garbage":
        return put(tmp, f"garbage{ext}", GARBAGE), "refused"
    if case == "under a file":
        put(tmp, "file.txt", b"x")
        return os.path.join(tmp, "file.txt", f"x{ext}"), "refused"
    if case == "symlink loop":
        path = os.path.join(tmp, f"loop{ext}")
        os.symlink(path, path)
        return path, "refused"
    if case == "too long":
        return os.path.join(tmp, "d" * 300 + ext), "refused"
    if case == "huge":
        if limit is None:
            return None, None
        path = os.path.join(tmp, f"huge{ext}")
        with open(path, "wb") as stream:
            stream.truncate(limit + 1)          # sparse: no disk used
        return path, "refused"
    if good is None:
        return None, None
    if case == "cut short":
        return put(tmp, f"cut{ext}", good[:len(good) // 2 + 7]), "refused" if cut_detectable else "works or refused"
    if case == "japanese path":
        folder = os.path.join(tmp, JAPANESE)
        os.mkdir(folder)
        return put(folder, f"{stem} 1{ext}", good), "works"
    if not text:
        return None, None
    if case == "bom":
        return put(tmp, f"bom{ext}", b"\xef\xbb\xbf" + good), "works"
    if case == "utf-16":
        return put(tmp, f"utf16{ext}", good.decode("utf-8").encode("utf-16")), "works or refused"
    if case == "latin-1":
        if latin1(good) is None:
            return None, None
        return put(tmp, f"latin1{ext}", latin1(good)), "works or refused"
    raise AssertionError(case)


# what a refusal of each class says besides the file's name (the words, not the OS's errno text)
CLASS_WORDS = {"missing": "no such", "folder": "folder", "symlink loop": "loop", "too long": "too long",
               "under a file": "not a folder", "huge": "bytes"}


# the key of a job file that names the file (the Part 21 reader's own errors name the file's path)
JOB_KEYS = {"job: file = (stepnc)": "operation 1 ('wp'): file = ", "job: design = (svg)": "design.file = ",
            "job: [setup] blend =": "[setup] blend = "}


def check(status, message, written, path, case, expect, where):
    if expect == "works" or (expect == "works or refused" and status == 0):
        assert status == 0, (where, message[-3000:])
        return
    assert status == 2, (where, status, message[-3000:])
    assert "Traceback" not in message, (where, message[-3000:])
    assert "Errno" not in message, (where, message[-3000:])
    assert not written, (where, written)
    assert path in message, (where, path, message[-3000:])           # the file, as the user typed it
    assert CLASS_WORDS.get(case, "") in message, (where, CLASS_WORDS[case], message[-3000:])
    if case in ("utf-16", "latin-1"):        # refused: what is accepted, or where the text goes wrong
        assert "UTF-8" in message or "XML" in message, (where, message[-3000:])


@pytest.fixture
def library(tmp_path, monkeypatch):
    path = tmp_path / "library" / "tools.toml"
    monkeypatch.setenv("KEZURI_TOOL_LIBRARY", str(path))
    with contextlib.redirect_stdout(io.StringIO()):
        assert BATCH.main(["batch.py", "tools", "list"]) == 0      # the library as a first run makes it
    return path


@pytest.mark.parametrize("case", CLASSES)
@pytest.mark.parametrize("entry", list(ENTRIES))
def test_a_hostile_file_through_batch(entry, case, tmp_path, library, monkeypatch):
    tmp = tempfile.mkdtemp(prefix="kezuri-files-", dir=tmp_path)
    path, expect = make(tmp, ENTRIES[entry], case)
    if path is None:
        pytest.skip(f"{case} does not apply to {entry}")
    argv = ENTRIES[entry][5](tmp, path)
    before = library.read_bytes() if library.exists() else None
    status, message, written = run(tmp, argv)
    check(status, message, written, path, case, expect, (entry, case))
    key = JOB_KEYS.get(entry)
    if status and key and (entry != "job: file = (stepnc)" or case in CLASS_WORDS):
        assert key in message, (entry, case, message[-2000:])       # the job file's key, not a batch option
    if status and argv[0] == "tools":
        assert (library.read_bytes() if library.exists() else None) == before


# ----- the operators that import files, through bpy ----------------------------------------------------

OPERATORS = {
    "kezuri.import_stepnc": ("part.stp", STEP, True, True, None, lambda p: {"filepath": p}),
    "kezuri.import_design (svg)": ("design.svg", SVG, True, True, 100_000_000, lambda p: {"filepath": p}),
    "kezuri.import_design (dxf)": ("design.dxf", DXF, True, True, 100_000_000, lambda p: {"filepath": p}),
    "kezuri.import_cdl": ("quad.cdl", CDL, True, True, None, lambda p: {"filepath": p}),
    "kezuri.toollib_import": ("tools.toml", TOOLS, True, True, 20_000_000, lambda p: {"filepath": p, "replace": True}),
    "kezuri.job_load": ("job.toml", JOB.replace(b"{{name}}", b"holes"), True, True, None, lambda p: {"filepath": p}),
}


@pytest.fixture
def scene(library):
    import kezuri
    from kezuri.operators import samples
    if not hasattr(bpy.types.Scene, "kezuri"):
        kezuri.register()
    samples.clear_scene(bpy.context.scene)
    samples.set_millimetres(bpy.context.scene)
    bpy.context.window_manager.kezuri_tool_library.loaded = False
    return bpy.context.scene


@pytest.mark.parametrize("case", CLASSES)
@pytest.mark.parametrize("entry", list(OPERATORS))
def test_a_hostile_file_through_an_operator(entry, case, tmp_path, scene, library):
    tmp = tempfile.mkdtemp(prefix="kezuri-files-", dir=tmp_path)
    path, expect = make(tmp, OPERATORS[entry], case)
    if path is None:
        pytest.skip(f"{case} does not apply to {entry}")
    module, name = entry.split()[0].split(".")
    operator = getattr(getattr(bpy.ops, module), name)
    objects, tools = set(bpy.data.objects.keys()), library.read_bytes()
    files = sorted(os.listdir(tmp))
    stderr = io.StringIO()
    COUNT["cases"] += 1
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(stderr):
        try:
            result, message = operator(**OPERATORS[entry][5](path)), ""
        except RuntimeError as error:
            result, message = {"CANCELLED"}, str(error)
    if expect == "works" or (expect == "works or refused" and result == {"FINISHED"}):
        assert result == {"FINISHED"}, (entry, case, message)
        return
    written = sorted(set(os.listdir(tmp)) - set(files))
    status = 2 if result == {"CANCELLED"} and message.startswith("Error:") else result
    check(status, message + stderr.getvalue(), written, path, case, "refused", (entry, case))
    assert set(bpy.data.objects.keys()) == objects and library.read_bytes() == tools


@pytest.mark.parametrize("message, name, words", [
    ("--cdl parts/q.cdl: no such file", "--cdl parts/q.cdl", "ファイルがありません"),
    ("--svg 部品 1.svg: a folder, not a drawing file", "--svg 部品 1.svg", "図面ファイルではありません"),
    ("--nc loop.ngc: a symbolic link that leads round in a loop, to no file", "--nc loop.ngc", "循環"),
    ("job file j.toml: operation 1 ('wp'): file = 'p.stp': no such file (/w/p.stp)", "file = 'p.stp'",
     "ファイルがありません（/w/p.stp）"),
    ("--cdl q.cdl: CDL line 7: LINE record has 1 numbers, expected 13 or 14 (x1, y1, z1, x2, y2, z2, colour, "
     "type, ...)", "--cdl q.cdl", "CDL 7 行目"),
])
def test_a_file_error_comes_out_in_japanese_after_the_files_name(message, name, words):
    """The name the user gave the file stays as typed; the reason after it is translated (a reader's
    message under a file's name is matched after the name)."""
    from kezuri.operators.translations import japanese_message
    japanese = japanese_message(message)
    assert japanese is not None and name in japanese and words in japanese, japanese
    assert message.split(": ")[-1] not in japanese, japanese       # the reason is not left in English


def test_the_suite_counts_its_cases():
    """Counted when the whole module runs: the README states the number of cases."""
    if COUNT["cases"] < len(ENTRIES) * len(CLASSES) // 2:
        pytest.skip("run with the whole module to count")
    print(f"\n{COUNT['cases']} hostile file cases")
    assert COUNT["cases"] >= 250, COUNT


# ----- names the user gives where a file or a table entry is meant (material, machine, post, font) -----

NAMES = [
    (("engrave", "--material", "soft wood"), "--material 'soft wood'"),
    (("pocket", "--svg", "SVG", "--machine", "no-such-mill"), "no-such-mill"),
    (("pocket", "--svg", "SVG", "--post", "no-such-post"), "no-such-post"),
    (("vcarve", "--text", "A", "--font", "NoSuchFont.ttf"), "text.font = 'NoSuchFont.ttf': no such font file"),
    (("job", "JOB:machine = \"no-such-mill\""), "[setup] machine = 'no-such-mill' is not a machine preset"),
    (("job", "JOB:post = \"no-such-post\""), "no-such-post"),
]


@pytest.mark.parametrize("argv, named", NAMES)
def test_a_name_that_names_nothing_is_refused_by_name(argv, named, tmp_path):
    """--machine xx on a drawing command and machine = "xx" in a job file's [setup] ended in
    Blender's TypeError (a traceback): now refused naming the value and the presets."""
    tmp = str(tmp_path)
    args = []
    for arg in argv:
        if arg == "SVG":
            arg = put(tmp, "d.svg", SVG)
        elif arg.startswith("JOB:"):
            arg = put(tmp, "j.toml", JOB.replace(b"{{name}}", b"h").replace(b'post = "linuxcnc"', arg[4:].encode()))
        args.append(arg)
    status, message, written = run(tmp, args)
    assert status == 2 and "Traceback" not in message and not written, message[-3000:]
    assert named in message, message[-3000:]


@pytest.mark.parametrize("entry, size, seconds, named", [
    # before: the Part 21 tokenizer scanned all of it first (33 s and 6.5 GB for 50 MB of NULs)
    ("stepnc --input", 50_000_000, 10, "line 1, column 1: unexpected character U+0000"),
    # before: the NC reader stripped comments a character at a time (10 s and 830 MB for 50 MB)
    ("simulate --nc", 100_000_000, 8, "line 1 is 100000000 characters long"),
])
def test_a_big_binary_file_is_refused_in_seconds(entry, size, seconds, named, tmp_path):
    """A video or an archive picked by mistake: tens of MB of NULs (sparse, no disk used)."""
    tmp = str(tmp_path)
    path = os.path.join(tmp, "big" + os.path.splitext(ENTRIES[entry][0])[1])
    with open(path, "wb") as stream:
        stream.truncate(size)
    with time_limit(seconds):
        status, message, written = run(tmp, ENTRIES[entry][5](tmp, path))
    check(status, message, written, path, "garbage", "refused", entry)
    assert named in message, message[-2000:]
