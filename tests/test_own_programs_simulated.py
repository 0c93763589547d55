"""Our own programs, read back as text and simulated (``batch.py simulate --nc``): zero findings.

Every milling workflow's built-in sample is posted through every post of its family, and the NC
text is simulated by batch's own functions, in process (as a user runs ``batch.py simulate``).
A finding on a program the gate passed is a false alarm, and users who see false alarms learn to
ignore findings: each case expects none at all (no gouge, no rapid into material, no cut with the
spindle stopped, nothing below the stock).

What the reader cannot follow is done so:
* engrave ``fanuc-macro``: its texture is drawn by the controller macro O7023 under ``G66.1``
  (which the reader refuses by name); the program is run by the independent Custom Macro B
  interpreter (tests/macrob.py) with a clock, and the moves and spindle words it executes are
  written out as plain G-code (in execution order) and simulated like the others;
* each program is simulated with one tool (the reader's rule: ``--tool``), its first tool;
  the stock is the box the sample is cut from (see ``stock_of``).
The turn-mill (lathe X in diameter) and punch programs are not milling G-code: not read here.

Also here: the reader follows the spindle as LinuxCNC does (checked against ``rs274``'s
canonical calls), so a cut after ``M5``, after a tool change ``M6`` or before any ``M3`` is
named with its line, and ``S... M03`` on a positioning block is read as the spindle running.
"""
import contextlib
import importlib.util
import io
import json
import os

import numpy as np
import pytest

import rs274
from kezuri.toolpath.simulate import ncread
from kezuri.toolpath.ir.program import Tool
from macrob import run_program

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load_batch():
    spec = importlib.util.spec_from_file_location("kezuri_batch_own_programs", os.path.join(ROOT, "batch.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def batch():
    return load_batch()


def run(batch, *argv) -> dict:
    """batch.py <argv>, in process; its report."""
    out = argv[argv.index("--out") + 1]
    stderr = io.StringIO()
    with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        status = batch.main(["batch.py", *argv])
    assert status == 0, f"{argv}: {stderr.getvalue()[-3000:]}"
    return json.loads(open(os.path.join(out, "report.json")).read())


# The samples' stock, as their workflows define it (input to the check, not a result of it):
# the engraving plate 200 x 100 mm (operators/samples.py), the STEP-NC sample's 100 x 80 x 30 block
# (its Part 21 file), the rotary bento block; carve writes its stock into the report.
STOCKS = {"engrave": "box:-100,-50,-10,100,50,0", "stepnc": None, "rotary": None}
TOOLS = {"engrave": "ball:6", "carve": "flat:6", "stepnc": "flat:6", "rotary": "ball:6"}
# (the carve refuses fanuc-macro by name: it has no texture for the macro to draw; the curved-plate
# engraving, demo engrave-dome, is left out: its stock has a domed top, and --stock is a box or a bar)
CASES = ([("engrave", p, ()) for p in ("fanuc", "fanuc-macro", "linuxcnc", "grbl")]
         + [("carve", p, ()) for p in ("fanuc", "linuxcnc", "grbl")]
         + [("stepnc", p, ()) for p in ("fanuc", "linuxcnc", "grbl")]
         + [("rotary", p, ()) for p in ("fanuc", "linuxcnc")])


def stock_of(workflow: str, report: dict, text: str) -> str:
    if workflow == "carve":
        return "box:" + ",".join(f"{v:g}" for v in report["stock"])
    if STOCKS.get(workflow):
        return STOCKS[workflow]
    # the block's top is Z 0; around the cut area (what the program reaches, by rs274 or the text)
    op = ncread.read_nc(text, Tool(1, "flat", 6.0)).operation
    cutting = op.kind != 0
    xy = op.xyz[cutting, :2]
    reach = float(np.abs(xy).max()) + 10.0 if workflow == "rotary" else None
    if reach is not None:
        return f"box:{-reach:g},{-reach:g},-40,{reach:g},{reach:g},0"
    (x0, y0), (x1, y1) = xy.min(axis=0) - 5, xy.max(axis=0) + 5
    return f"box:{x0:g},{y0:g},{float(op.xyz[cutting, 2].min()) - 5:g},{x1:g},{y1:g},0"






def clock_16ms(start_ms: int, step_ms: float = 7.0):
    """#3001 as the paper's control shows it: real time in 16 ms steps."""
    t = float(start_ms)
    while True:
        yield int(t // 16) * 16
        t += step_ms


def macro_as_plain_gcode(text: str) -> str:
    """What a Custom Macro B control executes for ``text`` (moves and spindle words, in order),
    as plain G-code the reader follows."""
    done = run_program(text, clock=clock_16ms(64172), start=(0, 0, 100))
    timeline = [((e.line, 0, k), e) for k, e in enumerate(done.events) if e.kind in ("S", "M", "T")]
    timeline += [((m.main_line, 1, k), m) for k, m in enumerate(done.moves)]
    lines = ["G21 G90 G17"]
    for _, item in sorted(timeline, key=lambda pair: pair[0]):
        if hasattr(item, "x"):
            xyz = f"X{item.x:.4f} Y{item.y:.4f} Z{item.z:.4f}"
            if item.kind == "rapid":
                lines.append(f"G0 {xyz}")
            elif item.kind == "feed":
                lines.append(f"G1 {xyz} F{item.feed:g}")
            else:
                lines.append(f"G{2 if item.kind == 'cw' else 3} {xyz} I{item.i:.4f} J{item.j:.4f} F{item.feed:g}")
        elif item.kind == "S":
            lines.append(f"S{item.value:g}")
        elif item.kind == "T":
            lines.append(f"T{int(item.value)}")
        elif int(item.value) in (3, 4, 5, 6, 30):
            lines.append(f"M{int(item.value)}")
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("workflow, post_name, options", CASES,
                         ids=[f"{w}-{p}" for w, p, _ in CASES])
def test_our_own_programs_simulate_without_findings(batch, tmp_path, workflow, post_name, options):
    extra = ("--rotary", "c") if workflow == "rotary" else ()
    report = run(batch, workflow, "--post", post_name, *options, "--out", str(tmp_path / "job"))
    assert report["gate"]["findings"] == []
    nc = next(path for path in report["files"] if path.endswith((".nc", ".ngc")))
    text = open(nc).read()
    if "G66.1" in text:         # the controller macro: what the control executes, as plain G-code
        assert workflow == "engrave" and post_name == "fanuc-macro"
        nc = str(tmp_path / "executed.ngc")
        open(nc, "w").write(macro_as_plain_gcode(text))
    sim = run(batch, "simulate", "--nc", nc, "--tool", TOOLS[workflow], "--stock", stock_of(workflow, report, text),
              *extra, "--out", str(tmp_path / "sim"))["simulation"]
    assert sim["gouges"] == [] and sim["rapid_collisions"] == [] and sim["other_findings"] == [], \
        [f["message"] for f in sim["gouges"] + sim["rapid_collisions"] + sim["other_findings"]][:5]
    assert sim["removed_volume_mm3"] > 1000          # it did cut: the checks ran over real cuts


# ----- the reader follows the spindle as LinuxCNC does ---------------------------------------------

FLAT6 = Tool(1, "flat", 6.0)

SPINDLE_PROGRAM = ("G21 G90\n"             # 1
                   "G0 X5 Y5 Z5 S1000 M3\n"  # 2  positioning block starts the spindle
                   "G1 Z-1 F100\n"         # 3  cuts at 1000 rpm
                   "X10\n"                 # 4
                   "T2 M6\n"               # 5  the tool change stops it
                   "G0 X20 Y20\n"          # 6
                   "G1 Z-1\n"              # 7  cut, spindle stopped
                   "X25\n"                 # 8
                   "S2000 M4\n"            # 9  counter-clockwise, 2000
                   "X30\n"                 # 10
                   "M5\n"                  # 11
                   "X35\n"                 # 12 cut, spindle stopped
                   "M2\n")


def rs274_spindle_at_feeds(text: str) -> list:
    """Per STRAIGHT_FEED: the spindle rpm rs274 has running (0: stopped), from its canonical calls."""
    speed, running, out = 0.0, False, []
    for name, args in rs274.run(text):
        if name == "SET_SPINDLE_SPEED":
            speed = float(args[-1])
        elif name in ("START_SPINDLE_CLOCKWISE", "START_SPINDLE_COUNTERCLOCKWISE"):
            running = True
        elif name == "STOP_SPINDLE_TURNING":
            running = False
        elif name in ("STRAIGHT_FEED", "ARC_FEED"):
            out.append(speed if running else 0.0)
    return out


def test_the_reader_follows_the_spindle_like_linuxcnc():
    read = ncread.read_nc(SPINDLE_PROGRAM, FLAT6, "p.ngc")
    runs = [(op.spindle_rpm, op.spindle_cw, lines) for op, lines in read.runs]
    assert runs == [(1000.0, True, [2, 3, 4, 6]), (0.0, True, [7, 8]), (2000.0, False, [10]), (0.0, True, [12])]
    assert read.operation.spindle_rpm == 0.0                    # the whole program: its slowest cut
    assert not {"S", "M3", "M4", "M5"} & {e["code"] for e in read.ignored}
    if rs274.available():
        feeds = [run_op.spindle_rpm for run_op, lines in read.runs for k in np.flatnonzero(run_op.kind != 0)]
        assert feeds == rs274_spindle_at_feeds(SPINDLE_PROGRAM) == [1000, 1000, 0, 0, 2000, 0]


def test_a_cut_with_the_spindle_stopped_is_named_by_its_line(batch, tmp_path):
    nc = tmp_path / "p.ngc"
    nc.write_text(SPINDLE_PROGRAM)
    sim = run(batch, "simulate", "--nc", str(nc), "--tool", "flat:6", "--stock", "box:0,0,-10,40,40,0",
              "--out", str(tmp_path / "sim"))["simulation"]
    stopped = [(f["line"], f["message"]) for f in sim["other_findings"]]
    assert stopped == [(7, "p.ngc lines 7-8: move 0 cuts with the spindle at 0 rpm"),
                       (12, "p.ngc line 12: move 0 cuts with the spindle at 0 rpm")]


def test_a_program_that_never_starts_the_spindle_is_found():
    op, lines = ncread.read_nc("G21 G90\nG0 X5 Y5 Z5\nG1 Z-1 F100\nM2\n", FLAT6)
    assert op.spindle_rpm == 0.0 and lines == [2, 3]


@pytest.mark.parametrize("block, message", [("M3 M5", "M3 and M5 are in one modal group"),
                                            ("S-100 M3", "S-100 is not a spindle speed")])
def test_spindle_words_a_control_refuses_are_refused(block, message):
    with pytest.raises(ncread.NCReadError, match=f"line 2: {message}"):
        ncread.read_nc(f"G21 G90\n{block}\nG0 X0 Y0 Z5\n", FLAT6)
