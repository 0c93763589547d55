"""The controller-macro program, executed by an independent Custom Macro B interpreter
(tests/macrob.py), cuts exactly what the baked program cuts for the same random digits."""
import numpy as np
import pytest

from kezuri import post
from kezuri.post.fanuc import macro_program
from kezuri.toolpath.operations.engrave import engrave
from macrob import MacroError, run_program
from test_engrave import LETTERS, PLATE


def path_points(moves):
    """End points in order, without zero-length moves (the macro may emit one at a row's end)."""
    points = []
    for move in moves:
        p = np.array(move.end, float)
        if points and np.allclose(points[-1], p, atol=1e-9):
            continue
        points.append(p)
    return np.array(points)


@pytest.fixture(scope="module")
def job():
    return engrave.plan(PLATE, LETTERS)


# The generator O7023 is documented to use (post/fanuc.py), modelled here with exact integers.
M, A = 32749, 2987


def seed_state(clock_ms: int) -> int:
    """FIX[frac(#3001 / M) * (M - 1)] + 1, in integers: r = #3001 mod M, frac = r / M."""
    return (clock_ms % M) * (M - 1) // M + 1


def model_digits(state: int):
    """Digits 0..9 of x <- A x mod M, digit = FIX[10 x / M]."""
    while True:
        state = A * state % M
        yield 10 * state // M


def clock_16ms(start_ms: int, step_ms: float = 7.0):
    """#3001 on the paper's control: real time advances, the clock shows it in 16 ms steps."""
    t = float(start_ms)
    while True:
        yield int(t // 16) * 16
        t += step_ms


@pytest.mark.parametrize("power_on_ms", [64172, 123456])
def test_macro_program_cuts_what_the_baked_program_cuts(job, power_on_ms):
    clock = clock_16ms(power_on_ms)
    first_read = int(power_on_ms // 16) * 16
    macro_text = post.milling_post("fanuc-macro").to_text(job.program)
    run = run_program(macro_text, clock=clock, start=(0, 0, 100))
    baked, depths = engrave.bake(job.program, digits=model_digits(seed_state(first_read)))
    baked_run = run_program(post.milling_post("fanuc").to_text(baked), start=(0, 0, 100))
    assert run.clock_reads == 1 and len(depths) > 100          # seeded once, then the generator
    macro_points, baked_points = path_points(run.moves), path_points(baked_run.moves)
    assert macro_points.shape == baked_points.shape
    assert np.max(np.abs(macro_points - baked_points)) < 1.5e-3   # both written to 0.001 mm
    # The depths the controller reached at each gouge are the baked depths, in order.
    rough_z = [m.z for m in run.moves if m.kind == "feed" and m.z is not None]
    assert set(np.round(depths, 3)) <= set(np.round(rough_z, 3))


def test_a_second_run_continues_the_sequence_without_reading_the_clock(job):
    macro_text = post.milling_post("fanuc-macro").to_text(job.program)
    first = run_program(macro_text, clock=iter([4096]), start=(0, 0, 100))
    state = first.var(115)
    assert 1 <= state < M and state == int(state)
    second = run_program(macro_text, clock=None, start=(0, 0, 100), variables={115: state})  # a read would raise
    assert second.clock_reads == 0
    baked, _ = engrave.bake(job.program, digits=model_digits(int(state)))
    baked_run = run_program(post.milling_post("fanuc").to_text(baked), start=(0, 0, 100))
    assert np.max(np.abs(path_points(second.moves) - path_points(baked_run.moves))) < 1.5e-3
    # a stale common variable that is not a generator state is replaced by a fresh seed
    stale = run_program(macro_text, clock=iter([4096]), start=(0, 0, 100), variables={115: 2.5})
    assert stale.clock_reads == 1 and stale.var(115) == first.var(115)


def test_digit_five_lands_on_the_base_depth(job):
    # Preset the generator so that the first draw is x = 16375: digit FIX[163750 / 32749] = 5.
    before = 16375 * pow(A, -1, M) % M
    assert A * before % M == 16375
    macro_text = post.milling_post("fanuc-macro").to_text(job.program)
    run = run_program(macro_text, start=(0, 0, 100), variables={115: before})
    band_starts = macro_text.splitlines().index("(OPERATION 2: BAND FINISHING)") + 1   # the gouges come before
    feed_z = [m.z for m in run.moves if m.kind == "feed" and m.z is not None and m.z < 0 and m.main_line < band_starts]
    # The first gouge is at -2.0 (the paper's GT5 would have sent digit 5 to -1.0).
    assert feed_z[0] == pytest.approx(-2.0)
    assert -1.0 not in np.round(feed_z, 3)


# ---------------------------------------------------------------- all nine depths on a real control

# The paper's rule with its values (base -2.0, quantum 0.2, amplitude 0.8): digits 1..4 -> -2.0 + 0.2 d,
# 6..9 -> -2.0 - 0.2 (d - 5), 0 and 5 -> -2.0.  A uniform digit therefore gives the base 2/10 of the
# gouges and each of the other eight depths 1/10.
PAPER_DEPTHS = {-2.0: 0.2, -1.8: 0.1, -1.6: 0.1, -1.4: 0.1, -1.2: 0.1, -2.2: 0.1, -2.4: 0.1, -2.6: 0.1, -2.8: 0.1}
# chi-square with 8 degrees of freedom (9 depths): P(X > 26.12) = 0.001 (standard table).
CHI2_8_999 = 26.12


def long_raster(rows: int, length: float = 2000.0) -> str:
    """A main program that sends `rows` X strokes of `length` mm through O7023 (one gouge per 20 mm)."""
    lines = ["%", "O0001", "G90 G21 G54", "G00 X0. Y0. Z5.", "G01 Z-2. F300."]
    for row in range(rows):
        stroke = f"X{length if row % 2 == 0 else 0.0:.1f} F1200."
        lines.append(f"G66.1 P7023 {stroke}" if row == 0 else stroke)
        lines.append(f"Y{row + 1:.1f}")
    lines += ["G67", "G00 Z5.", "M30"]
    return "\n".join(lines) + "\n" + macro_program(engrave.GougeTexture(), 3) + "%\n"


def gouge_depths(run, text):
    """Z of the gouge moves, in order: the moves made by O7023's block G01X#16Z#114F#9."""
    gouge_line = text.splitlines().index("G01X#16Z#114F#9") + 1
    return np.round([m.z for m in run.moves if m.line == gouge_line], 3)


def test_the_clock_digit_of_a_16ms_control_reaches_only_five_digits():
    # Why O7023 does not use the clock's last digit: 16 k ms always ends in an even digit.
    reads = clock_16ms(64172)
    assert {next(reads) % 10 for _ in range(10000)} == {0, 2, 4, 6, 8}


@pytest.mark.parametrize("power_on_ms", [0, 64172, 1_999_990_000])
def test_all_nine_depths_with_the_papers_frequencies(power_on_ms):
    text = long_raster(rows=60)        # 60 strokes x 100 gouges
    run = run_program(text, clock=clock_16ms(power_on_ms), start=(0, 0, 100), significant_digits=8)
    depths = gouge_depths(run, text)
    n = len(depths)
    assert n == 60 * 100 and run.clock_reads == 1
    values, counts = np.unique(depths, return_counts=True)
    assert set(values.tolist()) == set(PAPER_DEPTHS)            # all nine depths, nothing else
    observed = dict(zip(values.tolist(), counts.tolist()))
    expected = {d: p * n for d, p in PAPER_DEPTHS.items()}
    chi2 = sum((observed[d] - expected[d]) ** 2 / expected[d] for d in PAPER_DEPTHS)
    # A uniform random digit passes this with probability 0.999; a generator with a missing or
    # doubled digit gives chi2 in the hundreds (e.g. the clock digit's five: about 3000 here).
    assert chi2 < CHI2_8_999, (chi2, observed)
    # Successive gouges are independent: the 81 (depth, next depth) pairs against p_i p_j.
    pairs = {}
    for d0, d1 in zip(depths[:-1], depths[1:]):
        pairs[(d0, d1)] = pairs.get((d0, d1), 0) + 1
    m = n - 1
    chi2_pairs = sum((pairs.get((a, b), 0) - m * pa * pb) ** 2 / (m * pa * pb)
                     for a, pa in PAPER_DEPTHS.items() for b, pb in PAPER_DEPTHS.items())
    # 64 degrees of freedom: the 0.999 quantile is 104.7 (Wilson-Hilferty); 120 leaves room for
    # the not quite independent overlapping pairs.
    assert chi2_pairs < 120, chi2_pairs
    # The control's 8-digit arithmetic changes nothing in the generator: the run is the exact
    # sequence from its first state (found from the final #115 by stepping back n draws).
    final = run.var(115)
    assert final == int(final) and 1 <= final < M
    first_state = int(final) * pow(A, -n, M) % M
    if power_on_ms < 10_000_000:
        # a clock below 1e7 ms is seeded exactly (#3001 / 32749 keeps its fraction in 8 digits); a
        # larger clock loses digits of the fraction, which only changes which valid state is the seed
        assert first_state == seed_state(int(power_on_ms // 16) * 16)
    rule = {0: -2.0, 1: -1.8, 2: -1.6, 3: -1.4, 4: -1.2, 5: -2.0, 6: -2.2, 7: -2.4, 8: -2.6, 9: -2.8}
    digits = model_digits(first_state)
    np.testing.assert_array_equal(depths, [rule[next(digits)] for _ in range(n)])


def test_clock_digit_extraction_matches_the_paper_example():
    # The paper reads 64172 and extracts 2 -> depth -2 + 0.4 = -1.6.
    program = "%\nO0001\n#32=#3001\n#30=FIX[#32/10]*10\n#28=#32-#30\nM30\n%\n"
    run = run_program(program, clock=iter([64172]))
    assert run.var(28) == 2
    assert engrave.GougeTexture().depth(2) == pytest.approx(-1.6)


# ---------------------------------------------------------------- the macro confined to cutting

def runs_of_the_modal_call(text):
    """[(first line, last line)] of the G66.1 ... G67 runs of the main program (1-based)."""
    lines = text.split("O7023 (")[0].splitlines()
    runs, opened = [], None
    for number, line in enumerate(lines, 1):
        if line.startswith("G66.1"):
            assert opened is None, f"line {number}: G66.1 while one is in force"
            opened = number
        elif line == "G67":
            assert opened is not None, f"line {number}: G67 without G66.1"
            runs.append((opened, number - 1))
            opened = None
    assert opened is None, "G66.1 left modal at the program end"
    return runs, lines


def test_the_modal_call_spans_only_g01_raster_blocks(job):
    text = post.milling_post("fanuc-macro").to_text(job.program)
    runs, lines = runs_of_the_modal_call(text)
    assert len(runs) >= 3
    for first, last in runs:
        assert lines[first - 1].startswith("G66.1 P7023 X") and " F" in lines[first - 1]
        for line in lines[first - 1:last]:
            words = line.split()[2:] if line.startswith("G66.1") else line.split()
            # X and Y only (and F): no G code, no Z, no other address
            assert words and all(w[0] in "XYF" for w in words), line
        # the block before the call leaves G01 in force (the plunge)
        assert lines[first - 2].startswith("G01 Z")
        # after G67 the retract states its G code and Z
        assert lines[last + 1].startswith("G00 Z")


def test_the_new_program_on_a_strict_control(job):
    """Run on a machine with every usual axis (so no argument may be an axis address), the
    rapids and retracts are executed as programmed by the main program, above the plate, and
    the macro cuts only G01 moves, its gouges at the drawn depths in order."""
    power_on = 64172
    text = post.milling_post("fanuc-macro").to_text(job.program)
    run = run_program(text, clock=clock_16ms(power_on), start=(0, 0, 100), axes="XYZABCUVW")
    by_macro = [m for m in run.moves if m.line != m.main_line]
    by_main = [m for m in run.moves if m.line == m.main_line]
    assert by_macro and all(m.kind == "feed" for m in by_macro)
    assert all(m.kind != "rapid" for m in by_macro)
    rapids = [m for m in run.moves if m.kind == "rapid"]
    assert rapids and all(m.line == m.main_line for m in rapids)
    lines = text.splitlines()
    for m in rapids:
        block = lines[m.line - 1]
        for axis, value in zip("XYZ", m.end):        # the rapid ends where its block says
            word = next((w for w in block.split() if w[0] == axis), None)
            if word is not None:
                assert float(word[1:]) == pytest.approx(value, abs=1e-9), block
        moved_xy = abs(m.end[0] - m.start[0]) > 1e-9 or abs(m.end[1] - m.start[1]) > 1e-9
        # across the plate at the clearance height (20) or above; down only to 2 mm over the top
        assert m.z >= (20.0 if moved_xy else 2.0) - 1e-9, block
    # the retracts and plunges of the roughing are main-program blocks, never textured (the band
    # finishing after it ramps down in step-downs of its own)
    band = next(i for i, line in enumerate(lines, start=1) if line.startswith("(OPERATION 2:"))
    z_moves = [m for m in by_main if abs(m.end[2] - m.start[2]) > 1e-9 and m.kind == "feed" and m.line < band]
    assert z_moves and all(m.z == pytest.approx(-2.0) for m in z_moves if m.z < 0)
    # the gouges: made by O7023's two gouge blocks, at the drawn depths, in order
    digits = model_digits(seed_state(int(power_on // 16) * 16))
    _, depths = engrave.bake(job.program, digits=digits)
    gouge_lines = {n for n, line in enumerate(lines, 1) if line in ("G01X#16Y#33Z#114F#9", "G01X#16Z#114F#9")}
    assert len(gouge_lines) == 2
    cut = [m.z for m in run.moves if m.line in gouge_lines]
    np.testing.assert_allclose(cut, depths, atol=1e-9)
    # nothing the macro cut lies outside the nine depths' range
    assert min(m.z for m in by_macro) >= -2.8 - 1e-9 and max(m.z for m in by_macro) <= -1.2 + 1e-9


OLD_FORM = """%
O0001
G90 G21 G54
G00 X-100. Y-49.99 Z20.
Z2.
G01 Z-2. F300.
G66.1 P7023 X100. F1200.
Y-47.049
X-100.
G00 Z20.
X-100. Y-17.644
Z2.
G01 Z-2. F300.
X-62.738 F1200.
G67
G00 Z100.
M30
"""


def test_the_old_form_is_refused_and_would_cut_a_reposition_as_texture():
    # The old post's form: G66.1 left in force over the retract and the 32 mm reposition.
    text = OLD_FORM + macro_program(engrave.GougeTexture(), 3) + "%\n"
    with pytest.raises(MacroError, match="G0 in a block under G66.1") as err:
        run_program(text, clock=clock_16ms(64172), start=(0, 0, 100))
    assert err.value.text == "G00 Z20." and err.value.line == 10
    # Written as the old post wrote it, `G66.1 P7023` alone on its line: refused at once.
    alone = text.replace("G66.1 P7023 X100. F1200.", "G66.1 P7023\nX100. F1200.")
    with pytest.raises(MacroError, match="a G66.1 block without an X, Y or Z word"):
        run_program(alone, clock=clock_16ms(64172), start=(0, 0, 100))
    # What a control that hands the reposition to the macro would cut (the failure):
    # the same block given to O7023 by a G65 call, from the retract height, is cut as texture,
    # a G01 diving from Z 20 to the gouge depths along the 200 mm move.
    called = ("%\nO0001\nG90 G00 X100. Y-47.049 Z20.\nG01 F1200.\nG65 P7023 X-100. Y-17.644\nM30\n"
              + macro_program(engrave.GougeTexture(), 3) + "%\n")
    run = run_program(called, clock=clock_16ms(64172), start=(0, 0, 100))
    dive = run.moves[1:]
    assert all(m.kind == "feed" for m in dive) and len(dive) == 11        # 10 gouges + the rest
    assert dive[0].start[2] == 20.0 and -2.8 - 1e-9 <= dive[0].z <= -1.2 + 1e-9
    assert dive[-1].end[:2] == pytest.approx((-100.0, -17.644))


def test_the_old_surface_arguments_are_axis_addresses_on_a_b_axis_machine():
    # The old O7024 call passed B1 (new gouge) and C (ramp position): on a machine with a B or C
    # axis those are axis words.  The new call passes E, Q and R.
    old = ("%\nO0001\nG90 G00 X-100. Y-49.99 Z20.\nG01 Z-9.821 F300.\n"
           "G66.1 P7024 X-99. Y-49.99 Z-7.696 B1 C0.05 F1200.\nG67\nM30\nO7024\nM99\n%\n")
    assert run_program(old, start=(0, 0, 100)).ended_by == "M30"        # a 3-axis machine
    for axes, letter in (("XYZB", "B"), ("XYZC", "C"), ("XYZAC", "C")):
        with pytest.raises(MacroError, match=f"address {letter} is an axis of this machine"):
            run_program(old, start=(0, 0, 100), axes=axes)
    new = old.replace("B1 C0.05", "E1 Q1 R0.05")
    assert run_program(new, start=(0, 0, 100), axes="XYZABCUVW").ended_by == "M30"


@pytest.mark.parametrize("call, number", [
    ("G65 P7023 X50. Z-1.", 1),          # a Z word: an approach, retract or ramp is no raster block
    ("G65 P7023 F1200.", 1),             # no X, no Y
    ("G65 P7024 X50. Y0. Z-1.", 2),      # no ramp position R
    ("G65 P7024 X50. Y0. R0.5", 2),      # no Z (the surface)
    ("G65 P7024 X50. Y0. Z-1. R0.5", 2),  # no E1 ever: no depth to start from
])
def test_a_call_that_is_no_cutting_block_stops_the_control(call, number):
    from kezuri.post.fanuc import surface_macro_program
    from macrob import MacroAlarm
    texture = engrave.GougeTexture()
    text = (f"%\nO0001\nG90 G00 X0. Y0. Z5.\nG01 Z-2. F300.\n{call}\nM30\n"
            + macro_program(texture, 3) + surface_macro_program(texture, 3) + "%\n")
    with pytest.raises(MacroAlarm) as err:
        run_program(text, clock=iter([4096]))
    assert err.value.number == number and err.value.alarm_message.strip() in ("NOT A RASTER BLOCK", "NOT A ROW BLOCK")
