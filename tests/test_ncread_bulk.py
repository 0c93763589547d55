"""The NC reader's bulk path (plain lines read as arrays, toolpath/simulate/ncplain.py) against the
same reader following every line one at a time (``read_nc(..., bulk=False)``, the code the bulk
path stands in for): on random programs mixing plain moves with everything else (comments, modes,
inch, incremental, cycles, spindle words, malformed words, errors), both give the same moves,
line numbers, ignored codes and spindle runs, or the same error message.  Small text pieces and
bulk windows make every boundary case (a run cut by a piece's end, a flagged line mid-run) occur."""
import math

import numpy as np
import pytest

from kezuri.toolpath.ir.program import Tool
from kezuri.toolpath.simulate import ncplain, ncread

FLAT6 = Tool(1, "flat", 6.0)


def number(rng, big=False):
    value = rng.choice([rng.uniform(-50, 50), rng.integers(-20, 20), 0.0, rng.uniform(-1, 1) * (1e7 if big else 1)])
    text = rng.choice([f"{value:.4f}", f"{value:g}", f"{value:.1f}"])
    if rng.random() < 0.05:
        text = text.lstrip("0") or "0"
    return text


def plain_line(rng):
    words = []
    if rng.random() < 0.1:
        words.append(f"N{rng.integers(1, 9999)}")
    if rng.random() < 0.4:
        words.append(rng.choice(["G0", "G1", "G00", "G01", "G1"]))
    for axis, p in (("X", 0.7), ("Y", 0.6), ("Z", 0.5), ("C", 0.03), ("I", 0.001), ("J", 0.001)):
        if rng.random() < p:
            words.append(axis + number(rng, big=rng.random() < 0.0005))
    if rng.random() < 0.1:
        words.append("F" + rng.choice(["100", "250.5", "+30", ".5", "0"], p=[0.3, 0.3, 0.2, 0.19, 0.01]))
    gap = rng.choice([" ", "", "  ", "\t"])
    return gap.join(words)


# lines that do not stop the reading (mostly), and lines that end it or are refused
SAFE = ["G21", "G20", "G90", "G91\nX1\nY-2.5 Z.5\nG90", "G17", "M3 S1000", "M4 S500", "M5", "S2000", "M6 T2", "(a comment)",
        "G1 X1 (move) Y2", "; note", "", "   ", "O1234", "G81 X5 Y5 Z-3 R2 F100", "G83 X1 Y1 Z-5 R1 Q2 F50",
        "G80", "G99", "G98", "x1 y2", "G1 X 1 0 Y2", "G4 P1", "G64 P0.01", "G0 X5 Y5 Z5 F1000", "G91 G28 Z0",
        "G53 G0 Z0", "T1", "N5 G1 X3 F200", "G43 H1", "G1 C30 F100\nG0 C0", "G1 F120"]
FATAL = ["%", "M30", "G91", "G3 X2 Y0 I1 J0", "X1.2.3", "X2E1", "F-5", "F0", "G1 X99999999", "G2 X10 Y0 I5 J0", "G1 X1 R2"]


def random_program(rng) -> str:
    lines = ["G21 G90", "G0 X0 Y0 Z5", "G1 F100"] if rng.random() < 0.9 else []
    for _ in range(rng.integers(5, 160)):
        draw = rng.random()
        lines.append(plain_line(rng) if draw < 0.8 else str(rng.choice(SAFE)) if draw < 0.995
                     else str(rng.choice(FATAL)))
    return rng.choice(["\n", "\r\n", "\r"]).join(lines) + rng.choice(["", "\n", "\nM2\n"])


def outcome(text, bulk):
    try:
        read = ncread.read_nc(text, FLAT6, "p.ngc", bulk=bulk)
    except ncread.NCReadError as error:
        return ("error", str(error))
    op, lines = read
    return ("ok", op, list(lines), read.ignored,
            [(run.name, run.spindle_rpm, run.spindle_cw, len(run), list(run_lines)) for run, run_lines in read.runs])


def assert_same(text):
    got, expected = outcome(text, True), outcome(text, False)
    assert got[0] == expected[0], (got[:2], expected[:2])
    if got[0] == "error":
        assert got[1] == expected[1]
        return
    a, b = got[1], expected[1]
    for name in ("kind", "xyz", "center", "feed", "start"):
        assert np.array_equal(getattr(a, name), getattr(b, name), equal_nan=True), name
    assert a.rotary.keys() == b.rotary.keys() and all(np.array_equal(a.rotary[k], b.rotary[k]) for k in a.rotary)
    assert (a.spindle_rpm, a.spindle_cw) == (b.spindle_rpm, b.spindle_cw)
    assert got[2:] == expected[2:]


@pytest.fixture
def small_pieces(monkeypatch):
    """Pieces of about 60 characters and bulk windows of a few lines."""
    monkeypatch.setattr(ncread, "CHUNK_CHARS", 60)
    monkeypatch.setattr(ncread, "BULK_LINES", 7)
    monkeypatch.setattr(ncread, "BULK_FIRST", 2)


@pytest.mark.parametrize("seed", range(300))
def test_random_programs_read_alike(seed, small_pieces):
    assert_same(random_program(np.random.default_rng(seed)))


@pytest.mark.parametrize("seed", range(20))
def test_random_programs_read_alike_in_one_piece(seed):
    assert_same(random_program(np.random.default_rng(1000 + seed)))


def arc_program(rng, inch: bool, off: float) -> str:
    """Half circles end to end, the end put ``off`` x the arc tolerance away from the circle."""
    tolerance = ncplain.ARC_TOLERANCE_INCH if inch else ncplain.ARC_TOLERANCE_MM
    lines = ["G20" if inch else "G21", "G90", "G0 X0 Y0 Z1", "G1 Z-1 F100"]
    x = 0.0
    for _ in range(rng.integers(3, 30)):
        r = float(rng.choice([0.00004, 0.002, 0.5, 3.0, 40.0, 900.0], p=[0.01, 0.19, 0.2, 0.2, 0.2, 0.2]))
        end = x + 2 * r + off * tolerance * rng.choice([1.0, -1.0])
        lines.append(f"{rng.choice(['G2', 'G3'])} X{end:.9f} Y0 I{r:.9f} J0")
        x = end
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("seed", range(40))
@pytest.mark.parametrize("off", [0.0, 0.5, 1.0, 1 - 1e-9, 1 + 1e-9, 2.0, 99.0, 100.0, 100 + 1e-7, 150.0])
def test_arcs_at_the_tolerances_edges_read_alike(seed, off, small_pieces):
    rng = np.random.default_rng(seed)
    assert_same(arc_program(rng, inch=bool(seed % 2), off=off))


def test_a_plain_program_by_hand():
    """Plain lines only: moves, line numbers and the F count as written, without the slow path."""
    text = "%\nG21 G90\nG0 X1 Y2 Z5\nG1 Z-1 F300\nX4\nY-2.5 F250\nG0 Z5\nM2\n%\n"
    op, lines = read = ncread.read_nc(text, FLAT6)
    assert op.kind.tolist() == [0, 1, 1, 1, 0]
    assert op.xyz.tolist() == [[1, 2, 5], [1, 2, -1], [4, 2, -1], [4, -2.5, -1], [4, -2.5, 5]]
    assert lines == [3, 4, 5, 6, 7] and lines[1:3] == [4, 5] and isinstance(lines[0], int)
    assert [e for e in read.ignored if e["code"] == "F"] == [{"code": "F", "meaning": "feed", "count": 2,
                                                                "first_line": 4}]


def test_incremental_sums_like_one_line_at_a_time():
    """G91 positions are summed in line order: 0.1 added ten thousand times is not 1000.0
    exactly, and the bulk path gives the same float as the line-at-a-time one."""
    text = "G21 G90\nG0 X0 Y0 Z1\nG91\n" + "X0.1\n" * 10_000 + "G90\n"
    op = ncread.read_nc(text, FLAT6).operation
    total = 0.0
    for _ in range(10_000):
        total += 0.1
    assert op.xyz[-1, 0] == total and total != 1000.0
    assert math.isclose(total, 1000.0, rel_tol=1e-9)
