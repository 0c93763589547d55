"""Hostile input to the core: every bad input is refused with a message naming it, never a
traceback, a hang or a silently wrong answer.  Every test that could hang runs under a time
limit (SIGALRM, or a subprocess with a timeout), so a hang fails instead of stalling CI."""
import contextlib
import math
import os
import re
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import trimesh

from kezuri.post import output
from kezuri.toolpath.simulate import ncread
from kezuri.toolpath.operations.sheetmetal import punch, unfold
from kezuri.toolpath import simulate as sim
from kezuri.toolpath.operations.turnmill import turnjoin
from kezuri.toolpath.operations.turnmill import turnmill as tm
from kezuri.toolpath.engines.meshdata import MeshInputError
from kezuri.toolpath.engines.meshfile import MeshFileError
from kezuri.toolpath.ir.errors import InputError
from kezuri.toolpath.ir.program import Tool
from kezuri.toolpath.operations.stepnc import part21

import rs274  # noqa: E402  (tests/rs274.py)

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
FLAT6 = Tool(1, "flat", 6.0)


@contextlib.contextmanager
def time_limit(seconds: int):
    """Fail (TimeoutError) when the block runs longer than ``seconds`` (checked between Python
    bytecodes: long numpy calls finish first)."""
    def expired(signum, frame):
        raise TimeoutError(f"took more than {seconds} s")
    previous = signal.signal(signal.SIGALRM, expired)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


def run_python(code: str, timeout: float) -> subprocess.CompletedProcess:
    """``code`` in a fresh interpreter with the package loaded as ``kezuri``; killed after ``timeout``."""
    prelude = ("import sys; sys.path.insert(0, %r); import conftest\n" % HERE)
    return subprocess.run([sys.executable, "-c", prelude + code], capture_output=True, text=True, timeout=timeout,
                          cwd=ROOT)


def refused_in_capped_memory(setup: str, call: str) -> str:
    """What a fresh interpreter prints running ``setup`` then ``call`` with its address space capped
    at 6 GB: 'REFUSED <message>' for an input error, 'PLANNED' when the call returned."""
    done = run_python("import resource; resource.setrlimit(resource.RLIMIT_AS, (6 << 30, 6 << 30))\n"
                      "from kezuri.toolpath.ir.errors import InputError\n" + setup +
                      f"try:\n    {call}\n    print('PLANNED')\n"
                      "except InputError as error:\n    print('REFUSED', error)\n", timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout


def read(text):
    with time_limit(20):
        return ncread.read_nc(text, FLAT6)


# ----- 1. the NC reader is strict like a control ------------------------------------------------

START = "G21 G90\nG0 X0 Y0 Z5 F300\n"        # F set before any cutting move, as a control needs


@pytest.mark.parametrize("line, reason", [
    ("G92 X0 Y0", "G92 sets a coordinate offset"),
    ("G68 X0 Y0 R30", "G68 rotates the coordinate system"),
    ("G38.2 Z-10 F50", "G38.2 probing moves are not simulated"),
    ("G84 X10 Y10 Z-5 R1 F100", "G84 canned cycles other than G81, G82 and G83 are not simulated"),
    ("G73 X10 Y10 Z-5 R1 Q1 F100", "G73 canned cycles other than G81, G82 and G83 are not simulated"),
    ("G83 X10 Y10 Z-5 R1 F100", "G83 needs a peck Q greater than 0"),
    ("G81 X10 Y10 Z-5 F100", "G81 needs its Z"),
    ("G81 X10 Y10 Z5 R1 F100", "the cycle's bottom Z5 lies above its R plane R1"),
    ("G91 G81 X10 Y10 Z-5 R1 F100", "a drilling cycle in incremental mode"),
    ("G81 X10 Y10 Z-5 R1 L3 F100", "the L word is not supported here"),
    ("G41 D1 X10", "G41 cutter radius compensation"),
    ("G18", "G18 selects another plane; only the XY plane"),
    ("G66.1 P7023", "G66.1 macro calls"),
    ("M98 P100", "M98 subprogram calls"),
    ("G12 X1", "G12 is not a code this reader knows"),
    ("M123", "M123 is not a code this reader knows"),
    ("G1 A10", "the A word is not supported"),
    ("G1 XNAN", "X is not followed by a number \\(found 'NAN'\\)"),
    ("G1 X-", "X- is not a number G-code can have"),
    ("G1 X1.2.3", "X1.2.3 is not a number G-code can have"),
    ("G1 X2E1", "X2E...: exponents are not allowed"),
    ("G1 X" + "9" * 400, "X9+ is out of range"),
    ("G1 X1 X2", "X is given twice"),
    ("G0 G1 X1", "G0 and G1 are both motions"),
    ("G1 X1 (open", "unbalanced or nested parenthesis"),
    ("G1 I5 X1", "I or J without an arc move"),
    ("G2 X10 Y0 R5", "R-format arcs are not supported"),
    ("G2 X10 Y0", "an arc needs I and J"),
    ("G2 X0 Y0 I0 J0", "the arc has no radius"),
    ("G90 G28 Z0", "G28 is followed only as G91 G28"),
    ("/G1 X1", "a block delete '/' is not followed"),
    ("G90 G91 X1", "G90 and G91 are in one modal group"),     # before: read as G91, LinuxCNC refuses it
    ("G21 G20 X1", "G20 and G21 are in one modal group"),
])
def test_the_reader_stops_at_what_it_cannot_follow_naming_the_line(line, reason):
    with pytest.raises(ncread.NCReadError, match=f"line 3: {reason}") as error:
        read(START + line + "\nG1 X20\n")
    assert repr(line if len(line) <= 120 else line[:117] + "...") in str(error.value)   # the line (its start)


@pytest.mark.parametrize("name, text, xyz", [
    # a UTF-8 kanji comment read as latin-1 holds U+0085 (工 of 工具 is E5 B7 A5, 具 is E5 85 B7), at
    # which str.splitlines broke the line: refused as an unbalanced parenthesis, line numbers shifted
    ("kanji comment", "G1 Z-1 F100 (工具 T1)\nX10\n".encode().decode("latin-1"), [[0, 0, -1], [10, 0, -1]]),
    ("form feed", "G1 Z-1 F100\n\x0c\nX10\n", [[0, 0, -1], [10, 0, -1]]),
    # the closing % ends the program (LinuxCNC; the end of the tape on a Fanuc): before, read on
    ("closing percent", "G1 Z-1 F100\nX10\n%\nG1 Z-30\n", [[0, 0, -1], [10, 0, -1]]),
    # a ; inside parentheses is comment text, not the start of a comment
    ("semicolon in parentheses", "G1 Z-1 F100 (rough; 2 passes)\nX10\n", [[0, 0, -1], [10, 0, -1]]),
    # spaces are nothing to a control: X 1 0 . 5 is X10.5 (before: refused)
    ("spaces in words", "G1 Z - 1 F100\nX 1 0 . 5\n", [[0, 0, -1], [10.5, 0, -1]]),
    ("CR LF", "G1 Z-1 F100\r\nX10\r\n", [[0, 0, -1], [10, 0, -1]]),
])
def test_legal_syntax_is_read_as_linuxcnc_reads_it(name, text, xyz):
    op, lines = read("%\nG21 G90\nG0 X0 Y0 Z5\n" + text)
    assert np.allclose(op.xyz, [[0, 0, 5], *xyz]), op.xyz
    assert lines == [3, 4, 5 + (name == "form feed")][:len(lines)], lines
    if rs274.available():
        calls = rs274.run("%\nG21 G90\nG0 X0 Y0 Z5\n" + text.encode("latin-1").decode("utf-8") + "\n%\n")
        _, points, _ = rs274.motion_endpoints(calls)
        assert np.allclose(points, [[0, 0, 5], *xyz]), points


def test_a_line_number_counts_only_real_line_breaks():
    with pytest.raises(ncread.NCReadError, match="line 6: the Q word"):
        read("G21 G90\nG0 X0 Y0 Z5\n(caf\x85 \x0c \x1c)\nG1 Z-1 F100\r\nX10\rG1 X11 Q1\n")


def test_a_refused_megabyte_line_is_quoted_short():
    with pytest.raises(ncread.NCReadError) as error:
        read(START + "G1 " + " ".join(["F100"] * 200000) + "\n")
    assert "line 3: F is given twice in 'G1 F100" in str(error.value) and len(str(error.value)) < 200


def test_a_canned_cycle_is_drilled_not_run_as_a_straight_feed():
    # Before 2026-11-27: G81 was ignored and its X, Y, Z cut as a G1 (1,651 mm^3 instead of a 132 mm^3
    # hole); then refused; now drilled as LinuxCNC drills it: over the hole, down to R, fed to Z, out.
    op, lines = read(START + "G1 Z1 F100\nG81 X10 Y10 Z-4 R1 F100\nG80\n")
    feeds = op.xyz[op.kind == 1]
    assert feeds.tolist() == [[0.0, 0.0, 1.0], [10.0, 10.0, -4.0]]      # the G1 Z1, then the hole alone
    assert op.xyz[-1].tolist() == [10.0, 10.0, 1.0] and lines[-1] == 4


@pytest.mark.parametrize("radius, error, refused", [
    (10.0, 0.02, False),     # under the absolute 0.028 mm
    (10.0, 0.03, True),      # over it, and 0.3 % of the radius
    (100.0, 0.05, False),    # over 0.028 mm, but only 0.05 % of the radius
    (5000.0, 2.7, False),    # 0.054 %, under 100 x 0.028 mm = 2.83 mm
    (5000.0, 2.9, True),     # over 100 x the absolute tolerance, whatever the radius
])
def test_arcs_are_held_to_linuxcncs_radius_tolerance(radius, error, refused):
    """LinuxCNC (interp_internal.hh, interp_arc.cc): refused when the radius at the end differs
    from the one at the start by more than 100 x 0.02*sqrt(2) mm, or by more than 0.02*sqrt(2) mm
    and 0.1 % of the radius."""
    end = radius + error    # start (r, 0), centre at the origin (I-r), end straight above it
    text = f"G21 G90\nG0 X{radius:.4f} Y0 Z0 F300\nG3 X0 Y{end:.4f} I{-radius:.4f} J0\n"
    if refused:
        with pytest.raises(ncread.NCReadError, match=rf"line 3: the arc's end lies {error:.4f} mm off its circle"):
            read(text)
    else:
        op, lines = read(text)
        assert lines == [2, 3] and np.allclose(op.center[1, :2], [0, 0])


def test_inch_arcs_use_the_inch_tolerance():
    # 0.002*sqrt(2) in = 0.0718 mm: 0.002 in off on a 1 in radius (0.2 %) is refused, 0.0015 in is not
    read("G20 G90\nG0 X1 Y0 Z0 F12\nG3 X0 Y1.0015 I-1 J0\n")
    with pytest.raises(ncread.NCReadError, match="line 3: the arc's end lies 0.0762 mm"):
        read("G20 G90\nG0 X1 Y0 Z0 F12\nG3 X0 Y1.003 I-1 J0\n")


def test_what_the_reader_sets_aside_is_listed_and_the_old_unpacking_still_works():
    text = ("%\nO1000\n(job)\nN10 G21 G90 G17 G54\nT1 M6\nS8000 M3\nM8\nG0 X0 Y0 Z5 ; over the start\n"
            "G1 Z-1 F200\nX10 (along)\nM9\nM5\nG91 G28 Z0\nM30\nG1 X1000\n")
    result = read(text)
    op, lines = result                         # the old (operation, lines) pair
    assert lines == [8, 9, 10] and result.operation is op and result.lines == lines
    assert np.allclose(op.xyz, [[0, 0, 5], [0, 0, -1], [10, 0, -1]])     # nothing read after M30
    ignored = {entry["code"]: entry for entry in result.ignored}
    assert ignored["comment"]["count"] == 3 and ignored["comment"]["first_line"] == 3
    assert ignored["M8"]["meaning"] == "coolant on" and ignored["M8"]["first_line"] == 7
    assert ignored["M6"]["count"] == 1 and ignored["F"]["count"] == 1
    assert "S" not in ignored and "M3" not in ignored and "M5" not in ignored    # followed: the spindle
    assert op.spindle_rpm == 8000 and op.spindle_cw and result.runs == [(op, lines)]
    assert ignored["G28"]["first_line"] == 13 and ignored["G54"]["count"] == 1
    assert [e["first_line"] for e in result.ignored] == sorted(e["first_line"] for e in result.ignored)


def test_our_own_posts_read_back_without_refusals():
    from kezuri import post
    from kezuri.toolpath.operations.engrave import engrave
    from test_engrave import LETTERS, PLATE
    baked, _ = engrave.bake(engrave.plan(PLATE, LETTERS).program)
    last = baked.operations[-1].xyz[-1]
    for name in ("linuxcnc", "fanuc", "grbl"):
        text = post.milling_post(name).to_text(baked)
        op, lines = read(text)
        # every motion block read (arcs, helical ones too, are one move each), to the program's end
        assert len(op) > 500, name
        assert len(op) >= len(re.findall(r"^(?:N\d+ )?G0?[0-3]\b", text, re.M)), name
        assert np.allclose(op.xyz[-1, :2], last[:2], atol=1e-3), name


def test_a_cell_too_coarse_to_mean_anything_is_refused_like_a_too_fine_one():
    op, _ = read(START + "G1 Z-2 F100\nX50\n")
    stock = (-10, -10, -10, 110, 10, 0)       # 20 mm across its smaller side: cells up to 5 mm
    with pytest.raises(sim.SimulationError, match=r"cell 1e\+09 mm is too coarse for a stock 20 mm across .*"
                                                  r"give a cell from 0.00548 to 5 mm"):
        sim.simulate([op], stock, cell=1e9)
    with pytest.raises(sim.SimulationError, match="use a coarser cell"):
        sim.simulate([op], stock, cell=1e-4)
    assert sim.simulate([op], stock, cell=5.0).removed_volume_mm3 > 0


# ----- hypothesis: random G-code lines ------------------------------------------------------------

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

WORDS = st.builds(lambda letter, number: letter + number,
                  st.sampled_from(list("GMXYZCIJKFSTHNPRQADE") + [" ", "(", ")", ";", "%", "/"]),
                  st.one_of(st.from_regex(r"[-+]?[0-9]{0,4}(\.[0-9]{0,4})?", fullmatch=True),
                            st.sampled_from(["NAN", "INF", "1.2.3", "2E1", "-", "", "00", "38.2", "81", "2", "3"])))
LINES = st.lists(WORDS, min_size=0, max_size=8).map(" ".join)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(LINES, min_size=1, max_size=6))
def test_random_gcode_reads_cleanly_or_names_the_line(lines):
    text = START + "\n".join(lines) + "\n"
    try:
        result = read(text)
    except ncread.NCReadError as error:
        message = str(error)
        assert message.startswith("line ") or message == "the NC file has no moves", message
        if message.startswith("line "):
            number = int(message.split(":")[0][5:])
            assert 1 <= number <= len(text.splitlines())
    else:
        op, numbers = result
        assert len(op) == len(numbers) and np.isfinite(op.xyz).all()


# ----- 2. design meshes are checked before they are trusted ---------------------------------------

BOX_STOCK = (0, 0, -10, 40, 40, 0)


def slot_op():
    return read("G21 G90\nG0 X5 Y20 Z5\nG1 Z-2 F100\nX35\nG0 Z5\n")[0]


def block(extents=(40, 40, 9), centre=(20, 20, -5.5)):
    return trimesh.creation.box(extents=extents, transform=trimesh.transformations.translation_matrix(centre))


def test_an_inside_out_design_is_flipped_and_said_so():
    normal = sim.simulate([slot_op()], BOX_STOCK, cell=0.5, design=block())
    flipped = block()
    flipped.faces = flipped.faces[:, ::-1]
    assert flipped.volume < 0
    repaired = sim.simulate([slot_op()], BOX_STOCK, cell=0.5, design=flipped, design_name="part.stl")
    assert repaired.warnings == ["design part.stl: the mesh was inside out (its normals pointed inward); its faces "
                                 "were flipped"]
    assert normal.warnings == []
    # the block's top is z = -1, the slot 2 deep: 1 mm gouged either way
    assert [f.depth_mm for f in repaired.findings_of("gouge")] == pytest.approx([1.0], abs=1e-3)
    assert [f.depth_mm for f in normal.findings_of("gouge")] == pytest.approx([1.0], abs=1e-3)


@pytest.mark.parametrize("make, message", [
    (lambda: trimesh.Trimesh(), "design part.stl: the mesh has no faces"),
    (lambda: trimesh.Trimesh(block().vertices, block().faces[1:], process=False),
     r"design part.stl: the mesh is not a closed solid: 3 edge\(s\) border only one face"),
    (lambda: trimesh.Trimesh(np.where(np.arange(24).reshape(8, 3) == 4, np.nan, block().vertices), block().faces,
                             process=False), "NaN or infinite vertex coordinates"),
    (lambda: block(centre=(200, 20, -5.5)), "does not overlap the stock"),
    (lambda: block(extents=(60, 40, 9)), r"the part stands 10.000 mm outside the stock"),
])
def test_bad_designs_are_refused_naming_the_mesh(make, message):
    with time_limit(60), pytest.raises(sim.SimulationError, match=message):
        sim.simulate([slot_op()], BOX_STOCK, cell=0.5, design=make(), design_name="part.stl")


def test_a_design_larger_than_the_stock_does_not_pass_silently():
    # Before: a design 2 mm larger all round measured a gouge volume hundreds of times the removed volume.
    big = block(extents=(44, 44, 14), centre=(20, 20, -5))
    with pytest.raises(sim.SimulationError, match="2.000 mm outside the stock"):
        sim.simulate([slot_op()], BOX_STOCK, engine="manifold", cell=0.5, design=big)


def test_random_bytes_as_a_design_file_are_refused_by_name(tmp_path):
    """Refused as the file is read (before: read as a mesh without faces, refused by the simulation)."""
    from kezuri.operators.ncfile import load_design
    path = tmp_path / "noise.stl"
    path.write_bytes(np.random.default_rng(7).bytes(3000))
    with pytest.raises(MeshFileError, match=f"--design {re.escape(str(path))}: (the mesh has no faces|not a readable)"):
        load_design(str(path))


# ----- 3. no hang, whatever the mesh or number ----------------------------------------------------

def _join_all_pairs(runs, surface, settings):
    """The old join, comparing every run with every other: the reference ordering."""
    remaining, passes = list(runs[1:]), [runs[0]]
    for _ in range(len(remaining)):
        end = passes[-1][-1]
        to_start = np.array([np.linalg.norm(r[0] - end) for r in remaining])
        to_end = np.array([np.linalg.norm(r[-1] - end) for r in remaining])
        i = int(np.argmin(np.minimum(to_start, to_end)))
        run = remaining.pop(i)
        if to_end[i] < to_start[i]:
            run = run[::-1]
        if min(to_start[i], to_end[i]) <= 4 * settings.pick_feed and turnjoin.link_clear(end, run[0], surface, settings):
            passes[-1] = np.vstack([passes[-1], run])
        else:
            passes.append(run)
    return passes


def test_the_grid_join_orders_runs_exactly_as_the_all_pairs_one():
    rng = np.random.default_rng(3)
    settings = tm.TurnMillSettings()
    far = tm.Triangles(np.array([[[500.0, 500, 500], [501, 500, 500], [500, 501, 500]]]))   # links always clear
    starts = np.vstack([rng.uniform(-30, 30, (300, 3)), rng.uniform(-300, 300, (20, 3))])   # some far away
    runs = [np.vstack([s, s + rng.normal(0, 2, 3), s + rng.normal(0, 4, 3)]) for s in starts]
    with time_limit(60):
        new = turnjoin.join_runs(runs, far, settings)
    old = _join_all_pairs(runs, far, settings)
    assert len(new) == len(old) and all(np.array_equal(a, b) for a, b in zip(new, old))


def test_join_progress_can_cancel():
    runs = [np.array([[float(i), 0, 0], [i + 0.5, 0, 0]]) for i in range(600)]
    far = tm.Triangles(np.array([[[500.0, 500, 500], [501, 500, 500], [500, 501, 500]]]))
    with pytest.raises(tm.TurnMillCancelled):
        turnjoin.join_runs(runs, far, tm.TurnMillSettings(), lambda fraction: False)


def test_turn_mill_on_a_plain_64_sided_cylinder_finishes():
    # Before: the all-pairs join took 40 s at 8 sections and more than 8 minutes at 64; the open
    # tube (no end caps) the same.
    done = run_python(
        "import time, numpy as np, trimesh\n"
        "from kezuri.toolpath.operations.turnmill import turnmill as tm\n"
        "m = trimesh.creation.cylinder(radius=20, height=40, sections=64)\n"
        "v = np.asarray(m.vertices)\n"
        "stock = tm.Stock(float(np.hypot(v[:, 0], v[:, 1]).max()), float(v[:, 2].min()), float(v[:, 2].max()))\n"
        "plan = tm.plan(v, m.faces, stock)\n"
        "print(sum(len(op) for op in plan.program.operations))\n"
        "tube = m.faces[np.abs(m.face_normals[:, 2]) < 0.5]\n"
        "print(sum(len(op) for op in tm.plan(v, tube, stock).program.operations))\n", timeout=240)
    assert done.returncode == 0, done.stderr[-2000:]
    closed, tube = (int(n) for n in done.stdout.split()[-2:])
    assert closed > 1000 and tube > 1000


@pytest.mark.parametrize("stock, named", [
    ("tm.Stock(1000.0, -60.0, 0.0)", "the radial roughing would need more than"),     # Stock Radius's top: > 60 s
    ("tm.Stock(42.5, -60.0, 10000.0)", "the axial roughing would need more than"),   # Stock Z Max's top: 24 GB, OOM
])
def test_a_stock_far_larger_than_the_part_is_refused_not_out_of_memory(stock, named):
    """Values inside the panel's ranges: the roughing copied the passes out to the stock, layer by
    layer, until the process ran out of memory (killed by the kernel at 24 GB) or of patience.
    Run in a child process with its address space capped at 6 GB, so a regression fails here."""
    printed = refused_in_capped_memory(
        "import numpy as np, trimesh\n"
        "from kezuri.toolpath.operations.turnmill import turnmill as tm\n"
        "m = trimesh.creation.cylinder(radius=12, height=60, sections=48)\n"
        "m.apply_translation((0, 0, -30))\n"
        "top = trimesh.creation.box(extents=(8, 8, 10)); top.apply_translation((0, 0, -5))\n"
        "m = m.difference(top)\n"
        f"stock = {stock}\n", "tm.plan(np.asarray(m.vertices), np.asarray(m.faces), stock)")
    assert "REFUSED" in printed and named in printed, printed[-1000:]


def test_a_finishing_layer_too_fine_to_hold_is_blamed_on_the_fineness_not_the_stock():
    # Tolerance 0.0001 mm on the turn-mill sample: over the limit before any roughing layer
    from kezuri.toolpath.operations.turnmill import turnjoin
    v = np.array([[0.0, 0.0, -10.0], [10.0, 0.0, 0.0], [0.0, 10.0, 0.0]])
    with pytest.raises(InputError, match="the radial finishing alone would need more than 5000000 tool positions"):
        turnjoin.count_positions([4_000_000, 0], 1_500_000, "radial", 0, 1.0, tm.Stock(42.5, -60.0, 0.0), v)
    total = [0, 4_000_000]
    turnjoin.count_positions(total, 900_000, "axial", 3, 1.0, tm.Stock(42.5, -60.0, 0.0), v)
    assert total == [0, 4_900_000]
    with pytest.raises(InputError, match=r"axial roughing .* \(4 layers of 1 mm so far\): the stock's end face Z 0"):
        turnjoin.count_positions(total, 200_000, "axial", 4, 1.0, tm.Stock(42.5, -60.0, 0.0), v)


def test_carving_through_a_metre_of_stock_at_the_finest_step_down_is_refused_not_out_of_memory():
    """Stock Above Design 1000 mm and Step Down 0.01 mm, both inside their ranges: 100,000 roughing
    levels ended in a MemoryError ("Kezuri internal error") after 25 s under a 6 GB cap."""
    printed = refused_in_capped_memory(
        "from kezuri.toolpath.operations.carve import carve, carve_samples\nv, f = carve_samples.wave_relief()\n",
        "carve.plan(v, f, carve.CarveSettings(step_down=0.01), stock_top=float(v[:, 2].max()) + 1000)")
    assert "REFUSED the roughing would need more than 10000000 moves" in printed, printed[-1000:]


def test_a_rotary_pocket_at_the_finest_spacing_and_step_down_is_refused_not_out_of_memory():
    """Spacing and Step Down both 0.01 mm (in range): 16.7 million points, a MemoryError in the C
    unwrapping ("Kezuri internal error")."""
    printed = refused_in_capped_memory(
        "from kezuri.toolpath.operations.rotary import rotary\nblock, pockets = rotary.sample_job()\n",
        "rotary.plan(block, [pockets[2]], rotary.RotarySettings(spacing=0.01, step_down=0.01))")
    assert "REFUSED pocket 'bowl': the toolpath would have" in printed, printed[-1000:]


def test_nan_vertices_are_refused_up_front():
    v, f, stock = tm.sample_part(48)
    v = v.copy()
    v[5, 1] = np.nan
    with time_limit(20), pytest.raises(MeshInputError, match="NaN or infinite vertex"):
        tm.plan(v, f, stock)


@pytest.mark.parametrize("pitch", ["0.00", "0.000001", "0.05"])
def test_a_zero_or_tiny_pitch_is_refused_before_punching(pitch):
    text = f"N000 G92 X1000.00 Y1040.00\nN001 G72 X0.00 Y0.00\nG69 I100.00 J0.00 P5.00 Q{pitch} T302\nG50\n"
    with time_limit(10), pytest.raises(punch.PunchError, match="line 3: .*(Q \\(pitch\\) > 0|below the 0.1 mm)"):
        punch.simulate_punching(text)


def test_unfold_divisions_are_bounded():
    quad = np.array([(0, 0, 0), (0, 30, 100), (100, 50, 100), (100, 40, 0)], float)
    with time_limit(10), pytest.raises(unfold.UnfoldError, match="from 1 to 1000, got 100000"):
        unfold.unfold_twisted_quad(quad, 100_000)


# ----- 4. tracebacks and partial output in the core -----------------------------------------------

def part21_text(data: str) -> str:
    return ("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
            f"FILE_SCHEMA(('X'));\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n")


def test_deeply_nested_part21_lists_are_refused_not_a_recursion_error():
    with time_limit(20), pytest.raises(part21.Part21Error, match="line 8, .*lists nested more than 100 deep"):
        part21.parse_part21(part21_text("#1=A(" + "(" * 5000 + "1" + ")" * 5000 + ");"))
    nested = part21.parse_part21(part21_text("#1=A(" + "(" * 99 + "1" + ")" * 99 + ");")).instances[1].params
    for _ in range(99):
        nested = nested[0]
    assert nested == [1]


@pytest.mark.parametrize("newline", ["\n", "\r\n", "\r"])
def test_part21_errors_count_lines_whatever_ends_them(newline):
    """A file with CR line ends was all one line: 'line 1, column 3929'."""
    text = part21_text("#1=A(1.,2.E);").replace("\n", newline)
    with time_limit(20), pytest.raises(part21.Part21Error, match=r"line 8, column 11 \(#1\)"):
        part21.parse_part21(text)


def test_stale_temporary_files_of_ours_are_cleaned_at_the_next_write(tmp_path):
    old = time.time() - 2 * 3600
    stale = tmp_path / ".kezuri-abc123_x.part"
    stale_png = tmp_path / ".kezuri-zz99yy00.part.png"
    fresh = tmp_path / ".kezuri-fresh000.part"            # a write still running
    theirs = tmp_path / ".kezuri-notours.tmp"
    mine = tmp_path / "notes.part"
    for path in (stale, stale_png, fresh, theirs, mine):
        path.write_text("x")
    for path in (stale, stale_png, theirs, mine):
        os.utime(path, (old, old))
    output.write_atomic(str(tmp_path / "job.nc"), "G0 X0\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == [".kezuri-fresh000.part", ".kezuri-notours.tmp",
                                                            "job.nc", "notes.part"]


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_an_unwritable_folder_is_an_output_error_naming_the_path(tmp_path):
    folder = tmp_path / "locked"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        with pytest.raises(output.OutputError, match=f"cannot write {folder}/job.nc: Permission denied"):
            output.write_atomic(str(folder / "job.nc"), "G0 X0\n")
        assert isinstance(output.OutputError("x"), InputError)
    finally:
        folder.chmod(0o700)
    assert list(folder.iterdir()) == []


def test_a_folder_that_cannot_be_made_is_an_output_error_naming_it(tmp_path):
    (tmp_path / "plain").write_text("a file, not a folder")
    with pytest.raises(output.OutputError, match=f"cannot write {tmp_path}/plain/job.nc: cannot make the folder "
                                                 f"{tmp_path}/plain"):
        output.write_atomic(str(tmp_path / "plain" / "job.nc"), "G0 X0\n")


def test_a_full_disk_is_an_output_error_and_leaves_nothing(tmp_path, monkeypatch):
    def full(fd):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(output.os, "fsync", full)
    with pytest.raises(output.OutputError, match=f"cannot write {tmp_path}/job.nc: No space left on device"):
        output.write_atomic(str(tmp_path / "job.nc"), "G0 X0\n")
    assert list(tmp_path.iterdir()) == []


def test_non_ascii_text_is_an_output_error_not_a_unicode_traceback(tmp_path):
    with pytest.raises(output.OutputError, match=r"the text is not ASCII \('é' at character 4\)"):
        output.write_atomic(str(tmp_path / "job.nc"), "(caf\u00e9)\n")
    assert list(tmp_path.iterdir()) == []


def test_atomic_path_renames_what_was_written_and_removes_a_failed_write(tmp_path):
    target = tmp_path / "preview.png"
    with output.atomic_path(str(target)) as temp:
        assert temp.endswith(".png") and os.path.dirname(temp) == str(tmp_path) and not os.path.exists(temp)
        with open(temp, "wb") as stream:
            stream.write(b"\x89PNG")
    assert target.read_bytes() == b"\x89PNG" and sorted(p.name for p in tmp_path.iterdir()) == ["preview.png"]
    with pytest.raises(output.OutputError, match="nothing was written"):
        with output.atomic_path(str(tmp_path / "other.png")):
            pass
    with pytest.raises(RuntimeError):
        with output.atomic_path(str(target)) as temp:
            open(temp, "wb").write(b"half")
            raise RuntimeError("render failed")
    assert target.read_bytes() == b"\x89PNG" and sorted(p.name for p in tmp_path.iterdir()) == ["preview.png"]


# ----- the batch command: what the reader set aside and what was repaired reach the report ---------

def test_batch_simulate_reports_what_it_ignored_and_repaired(tmp_path):
    import json

    from blender_helpers import run_batch
    nc = tmp_path / "slot.ngc"
    nc.write_text("(slot)\nG21 G90\nM8\nG0 X5 Y20 Z5\nG1 Z-2 F100\nX35\nG0 Z5\nM9\nM2\n")
    design = block()
    design.faces = design.faces[:, ::-1]                  # inside out
    design.export(str(tmp_path / "part.stl"))
    done = run_batch("simulate", "--nc", str(nc), "--tool", "flat:6", "--stock", "box:0,0,-10,40,40,0",
                     "--design", str(tmp_path / "part.stl"), "--cell", "0.5", "--out", str(tmp_path / "out"),
                     timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((tmp_path / "out" / "report.json").read_text())["simulation"]
    assert [(e["code"], e["first_line"]) for e in report["nc_ignored"]] == [("comment", 1), ("M8", 3), ("F", 5),
                                                                            ("M9", 8)]
    assert report["warnings"] == ["design part.stl: the mesh was inside out (its normals pointed inward); its faces "
                                  "were flipped"]
    assert report["max_gouge_mm"] == pytest.approx(1.0, abs=1e-3)      # the block's top is z = -1, the slot 2 deep
    bad = tmp_path / "bad.ngc"
    bad.write_text("G21 G90\nG0 X5 Y20 Z5\nG84 X10 Y10 Z-4 R1 F100\n")
    done = run_batch("simulate", "--nc", str(bad), "--tool", "flat:6", "--stock", "box:0,0,-10,40,40,0",
                     "--out", str(tmp_path / "out2"), timeout=300)
    assert done.returncode == 2 and "line 3: G84 canned cycles other than G81, G82 and G83 are not simulated" \
        in done.stderr
    assert "Traceback" not in done.stderr


# ----- 5. long work has a cancel point --------------------------------------------------------------

def nibbled_square(side: float, pitch: float) -> str:
    """One G69 per side of a side x side square, P5 punch: 4 x (side / pitch + 1) hits."""
    lines = ["N000 G92 X1000.00 Y1040.00", "N001 G72 X0.00 Y0.00"]
    for (x, y), angle in zip([(0, 0), (side, 0), (side, side), (0, side)], (0, 90, 180, 270)):
        lines.append(f"G72 X{x:.2f} Y{y:.2f}")
        lines.append(f"G69 I{side:.2f} J{angle:.2f} P0.00 Q{pitch:.2f} T302")
    return "\n".join(lines + ["G50"]) + "\n"


def test_punching_many_hits_reports_progress_and_can_be_cancelled():
    text = nibbled_square(200.0, 0.1)                     # 4 x 2001 hits
    hits = len(punch.read_amada(text).hits)
    assert hits == 4 * 2001
    calls = []

    def stop_at_second(fraction, text=""):
        calls.append(fraction)
        return len(calls) < 2

    started = time.perf_counter()
    with time_limit(20), pytest.raises(punch.PunchCancelled):
        punch.simulate_punching(text, punch_diameter=5.0, progress=stop_at_second)
    assert len(calls) == 2 and time.perf_counter() - started < 10
    seen = []
    with time_limit(120):
        result = punch.simulate_punching(text, punch_diameter=5.0, progress=lambda f, t="": seen.append(f))
    # a report before every batch of hits and one at the end, rising from 0 to 1
    assert len(seen) == math.ceil(hits / punch.DISC_BATCH) + 1 and seen == sorted(seen)
    assert seen[0] == 0.0 and seen[-1] == 1.0
    # the batched union is the same sheet: the hits 0.1 mm apart on a 200 mm square leave a
    # square part of side 200 - 5 = 195 (less its cusps, under 0.001 mm deep) and a frame
    assert result.part_separated and result.part_area_mm2 == pytest.approx(195.0 ** 2, rel=1e-4)


# ----- self-intersecting design meshes ------------------------------------------------------------

def two_boxes_unjoined():
    """Two closed 20 mm boxes overlapping by (13, 12, 11) mm, merged into one mesh without a boolean."""
    a = trimesh.creation.box(extents=(20, 20, 8), transform=trimesh.transformations.translation_matrix((12, 12, -6)))
    b = trimesh.creation.box(extents=(20, 20, 8), transform=trimesh.transformations.translation_matrix((19, 20, -5)))
    return trimesh.util.concatenate([a, b])


def bow_tie():
    """A figure-8 outline (5,5)-(35,35)-(35,5)-(5,35) extruded from z = -8 to -1: closed and
    consistently wound, but two side walls pass through each other along x = y = 20."""
    outline = np.array([(5, 5), (35, 35), (35, 5), (5, 35)], float)
    bottom = np.column_stack([outline, np.full(4, -8.0)])
    top = np.column_stack([outline, np.full(4, -1.0)])
    vertices = np.vstack([bottom, top])
    faces = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7)]           # caps (a fan on each)
    for k in range(4):
        n = (k + 1) % 4
        faces += [(k, n, 4 + n), (k, 4 + n, 4 + k)]
    return trimesh.Trimesh(vertices, np.array(faces), process=False)


def crossing_reference(mesh) -> set:
    """Every pair of faces without a common vertex whose triangles meet, by brute force (trimesh's
    own triangle-plane intersections are not used: each pair is cut by the other's plane here)."""
    tri = np.asarray(mesh.vertices)[mesh.faces]
    found = set()
    for i in range(len(tri)):
        for j in range(i + 1, len(tri)):
            if set(mesh.faces[i]) & set(mesh.faces[j]):
                continue
            if crosses(tri[i], tri[j]) or crosses(tri[j], tri[i]):
                found.add((i, j))
    return found


def crosses(t, u) -> bool:
    """Does an edge of triangle t pass through triangle u (barycentric test on u's plane)?"""
    n = np.cross(u[1] - u[0], u[2] - u[0])
    for k in range(3):
        p, q = t[k], t[(k + 1) % 3]
        dp, dq = np.dot(p - u[0], n), np.dot(q - u[0], n)
        if dp * dq >= 0:
            continue
        x = p + (q - p) * dp / (dp - dq)
        areas = [np.dot(np.cross(u[(m + 1) % 3] - u[m], x - u[m]), n) for m in range(3)]
        if min(areas) >= -1e-9 * np.dot(n, n):
            return True
    return False


@pytest.mark.parametrize("make, where", [(two_boxes_unjoined, None), (bow_tie, (20.0, 20.0))])
def test_a_self_intersecting_design_is_refused_naming_the_faces_and_a_place(make, where):
    from kezuri.toolpath.engines.selfcross import self_crossing
    mesh = make()
    stock = (0, 0, -10, 40, 40, 0)
    reference = crossing_reference(mesh)
    assert reference                                          # the mesh does cross itself
    with time_limit(20):
        found = self_crossing(mesh.vertices, mesh.faces)
    assert found.pairs == len(reference) and tuple(sorted(found.faces)) in reference
    # the place named lies on both faces of the pair named
    tri = np.asarray(mesh.vertices)[mesh.faces]
    for face in found.faces:
        n = np.cross(tri[face, 1] - tri[face, 0], tri[face, 2] - tri[face, 0])
        assert abs(np.dot(np.array(found.point) - tri[face, 0], n / np.linalg.norm(n))) < 1e-9
    if where is not None:                                    # the bow-tie's walls cross on x = y = 20
        assert found.point[:2] == pytest.approx(where)
    with time_limit(60), pytest.raises(sim.SimulationError, match=r"design part.stl: the mesh passes through "
                                                               r"itself \(\d+ pair\(s\) of faces cross, the first "
                                                               r"faces \d+ and \d+ at \("):
        sim.simulate([slot_op()], stock, cell=0.5, design=mesh, design_name="part.stl")


def test_closed_meshes_that_do_not_cross_themselves_pass():
    from kezuri.toolpath.engines.selfcross import self_crossing
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=15)
    torus = trimesh.creation.torus(major_radius=15, minor_radius=4)
    both = trimesh.util.concatenate([block(), trimesh.creation.box(extents=(5, 5, 5), transform=trimesh.transformations
                                                                   .translation_matrix((60, 0, 0)))])
    for mesh in (sphere, torus, both, block()):
        with time_limit(30):
            assert self_crossing(mesh.vertices, mesh.faces) is None
    assert crossing_reference(trimesh.creation.icosphere(subdivisions=1, radius=15)) == set()


# ----- the ball-clearance query: branch and bound in a tree, the same answers as brute force -------

def brute_nearest(points, tri, reach):
    """Every point against every triangle: the closest point by Ericson's regions written again
    here as a minimum over the face's interior projection, its three edges and its three corners."""
    best = np.full(len(points), np.inf)
    where = points.copy()
    for a, b, c in tri:
        n = np.cross(b - a, c - a)
        n = n / np.linalg.norm(n)
        candidates = []
        foot = points - np.outer((points - a) @ n, n)               # projection on the face's plane
        inside = np.ones(len(points), bool)
        for p, q in ((a, b), (b, c), (c, a)):
            inside &= np.cross(q - p, foot - p) @ n >= 0
        candidates.append(np.where(inside[:, None], foot, np.nan))
        for p, q in ((a, b), (b, c), (c, a)):
            t = np.clip((points - p) @ (q - p) / ((q - p) @ (q - p)), 0, 1)
            candidates.append(p + t[:, None] * (q - p))
        for candidate in candidates:
            d = np.linalg.norm(candidate - points, axis=1)
            better = np.nan_to_num(d, nan=np.inf) < best
            best[better], where[better] = d[better], candidate[better]
    within = best <= reach
    return np.where(within, best, np.inf), within, where


@pytest.mark.parametrize("seed", range(4))
def test_the_nearest_surface_point_is_the_brute_force_one(seed):
    from kezuri.toolpath.engines.meshrays import Triangles
    rng = np.random.default_rng(seed)
    mesh = trimesh.creation.icosphere(subdivisions=2, radius=20)
    vertices = mesh.vertices + rng.normal(0, 1.5, mesh.vertices.shape)        # a lumpy closed part
    tri = vertices[mesh.faces]
    # points on paths (as the planner asks: near the previous one) and scattered ones
    path = np.cumsum(rng.normal(0, 0.7, (400, 3)), axis=0) + (0, 0, 22)
    points = np.vstack([path, rng.uniform(-30, 30, (600, 3))])
    expected, within, where = brute_nearest(points, tri, 6.0)
    assert 100 < within.sum() < len(points)
    for kernel in ("auto", "numpy"):
        with time_limit(300):
            distance, closest = Triangles(tri, kernel=kernel).nearest(points, 6.0)
        assert np.abs(distance[within] - expected[within]).max() < 1e-9, kernel
        assert np.abs(closest[within] - where[within]).max() < 1e-9, kernel
        assert np.all(np.isinf(distance[~within])), kernel          # beyond reach is inf, as documented


@pytest.mark.parametrize("kernel", ["auto", "numpy"])
def test_a_ball_on_a_finely_split_surface_finds_the_same_nearest_point(kernel):
    """Also the numpy path (no numba): a triangle whose box is within reach but which lies beyond
    it, or a later batch's farther triangle, once overwrote the nearest distance."""
    from kezuri.toolpath.engines.meshrays import Triangles
    v, f, _ = tm.sample_part(48)
    dense_v, dense_f = trimesh.remesh.subdivide(*trimesh.remesh.subdivide(v, f))
    rng = np.random.default_rng(3)
    points = v[rng.integers(0, len(v), 2000)] + rng.normal(0, 3.0, (2000, 3))
    with time_limit(300):
        coarse = Triangles(v[f], kernel=kernel).nearest(points, 3.0)
        fine = Triangles(dense_v[dense_f], kernel=kernel).nearest(points, 3.0)
    assert np.isfinite(coarse[0]).sum() > 500
    assert np.array_equal(np.isfinite(coarse[0]), np.isfinite(fine[0]))
    finite = np.isfinite(coarse[0])
    assert np.abs(coarse[0][finite] - fine[0][finite]).max() < 1e-9


def test_the_self_crossing_search_is_a_cancel_point_of_the_simulation():
    sphere = trimesh.creation.icosphere(subdivisions=5, radius=4.0)
    sphere.apply_translation((20, 20, -5))
    calls = []

    def stop(fraction):
        calls.append(fraction)
        return False

    with time_limit(60), pytest.raises(sim.SimulationCancelled):
        sim.simulate([slot_op()], BOX_STOCK, cell=0.5, design=sphere, progress=stop)
    assert calls == [0.0]            # stopped at the first chunk of the design check, before any cutting


def test_a_g53_lift_is_followed_as_staying_put_and_other_g53_moves_are_refused():
    """The posts lift Z in machine coordinates (G53 G00 Z..) before XY after a start or a tool load:
    the reader takes the lift as the tool staying put (so an XY move after it is still checked at
    the height it had) and refuses a G53 move in X or Y, whose place it cannot know."""
    op, _ = read(START + "G00 Z5\nG53 G00 Z0\nG00 X10 Y10\nG01 Z-1 F100\n")
    assert op.xyz[:, 2].tolist()[:2] == [5.0, 5.0]          # the XY rapid at the height before the lift
    with pytest.raises(ncread.NCReadError, match="G53 moves in machine coordinates, which the reader does not know"):
        read(START + "G53 G00 X0 Y0\n")


@pytest.mark.parametrize("text, reason", [
    # a feed a control refuses (rs274: "Cannot do g1 with zero feed rate", "Negative f word used")
    ("G21 G90\nG0 X0 Y0 Z5\nG1 X10 F0\n", "line 3: a G1 move with F0 in effect since line 3"),
    ("G21 G90\nF0\nG0 X0 Y0 Z5\nG1 X10\n", "line 4: a G1 move with F0 in effect since line 2"),
    ("G21 G90\nG0 X0 Y0 Z5\nG1 X10\n", "line 3: a G1 move with no F word before it"),
    ("G21 G90\nG0 X0 Y0 Z5\nG1 X10 F-300\n", "line 3: F-300 is a negative feed"),
    ("G21 G93\nG0 X0 Y0 Z5\nG2 X10 Y0 I5 J0 F0\n", "line 3: a G2 move with F0"),
    # a dwell that cannot be, and a coordinate no machine reaches (300 digits, which overflowed the
    # simulation's sums and made the moves vanish)
    ("G21 G90\nG0 X0 Y0 Z5\nG4 P-5\n", "line 3: G4 P-5 is a negative dwell"),
    ("G21 G90\nG0 X" + "1" * 300 + " Y0 Z5\n", "line 2: X1.11111e\\+299 lies beyond the 100000 mm"),
    ("G20 G90\nG0 X0 Y0 Z5 F10\nG1 X4000\n", "line 3: X4000 lies beyond the 100000 mm"),   # 101.6 m in inches
    ("G21 G90\nG0 X0 Y0 Z5 F10\nG20 G1 X4000\n", "line 3: X4000 lies beyond the 100000 mm"),   # inches from this block on
])
def test_feeds_dwells_and_coordinates_a_control_refuses_are_refused(text, reason):
    with time_limit(10), pytest.raises(ncread.NCReadError, match=reason):
        read(text)
