"""The controller-macro program, executed by an independent Custom Macro B interpreter
(tests/macrob.py), cuts exactly what the baked program cuts for the same random digits."""
import numpy as np
import pytest

from kezuri import post
from kezuri.toolpath import engrave
from macrob import run_program
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


@pytest.mark.parametrize("seed", [0, 1])
def test_macro_program_cuts_what_the_baked_program_cuts(job, seed):
    rng = np.random.default_rng(seed)
    clock = [int(v) for v in rng.integers(0, 65536, size=5000)]   # #3001: milliseconds, wraps at 65536
    digits = [c % 10 for c in clock]
    macro_text = post.milling_post("fanuc-macro").to_text(job.program)
    run = run_program(macro_text, clock=iter(clock), start=(0, 0, 100))
    baked, depths = engrave.bake(job.program, digits=iter(digits))
    baked_run = run_program(post.milling_post("fanuc").to_text(baked), start=(0, 0, 100))
    assert run.clock_reads == len(depths) > 100
    macro_points, baked_points = path_points(run.moves), path_points(baked_run.moves)
    assert macro_points.shape == baked_points.shape
    assert np.max(np.abs(macro_points - baked_points)) < 1.5e-3   # both written to 0.001 mm
    # The depths the controller reached at each gouge are the baked depths, in order.
    rough_z = [m.z for m in run.moves if m.kind == "feed" and m.z is not None]
    assert set(np.round(depths, 3)) <= set(np.round(rough_z, 3))


def test_digit_five_lands_on_the_base_depth(job):
    macro_text = post.milling_post("fanuc-macro").to_text(job.program)
    run = run_program(macro_text, clock=iter([64175] * 5000), start=(0, 0, 100))
    feed_z = np.array([m.z for m in run.moves if m.kind == "feed"])
    # Digit 5 every time: every gouge at -2.0 (the paper's GT5 would have cut at -1.0).
    assert np.allclose(feed_z[feed_z < 0], -2.0)


def test_clock_digit_extraction_matches_the_paper_example():
    # The paper reads 64172 and extracts 2 -> depth -2 + 0.4 = -1.6.
    program = "%\nO0001\n#32=#3001\n#30=FIX[#32/10]*10\n#28=#32-#30\nM30\n%\n"
    run = run_program(program, clock=iter([64172]))
    assert run.var(28) == 2
    assert engrave.GougeTexture().depth(2) == pytest.approx(-1.6)
