"""``batch.py simulate --nc`` of a long program (a million moves): it shows its progress on stderr
while it reads and cuts, and Ctrl-C (SIGINT) stops it within seconds with nothing written.  (Its
speed is measured in bench/bench_scaling.py, not here.)"""
import signal

import numpy as np
import pytest

pytest.importorskip("bpy")
from test_batch_stop import everything_under, run  # noqa: E402


def raster_program(path, moves: int):
    """A zigzag at Z -1 over a 100 x 50 mm box, one plain G1 move a line."""
    per_row = 1000
    rows = moves // per_row
    x = np.tile(np.r_[np.linspace(0, 100, per_row), np.linspace(100, 0, per_row)], rows // 2 + 1)[:rows * per_row]
    y = np.repeat(np.linspace(0, 50, rows), per_row)
    body = "\n".join(f"X{a:.3f} Y{b:.3f}" for a, b in zip(x, y))
    path.write_text(f"G21 G90\nG0 X0 Y0 Z5\nS10000 M3\nG1 Z-1 F1000\n{body}\nM5\nM2\n")
    return path


BOX = ("--tool", "flat:6", "--stock", "box:-5,-5,-10,105,55,0")


def test_progress_on_stderr_and_the_moves_read(tmp_path):
    nc = raster_program(tmp_path / "small.ngc", 20_000)
    status, message, _ = run(["simulate", "--nc", str(nc), *BOX, "--cell", "0.5", "--out", str(tmp_path / "out")])
    assert status == 0, message[-2000:]
    assert "simulate" in message and "reading" in message and "cutting" in message and "100%" in message


def test_ctrl_c_stops_a_million_moves_within_seconds(tmp_path):
    nc = raster_program(tmp_path / "big.ngc", 1_000_000)
    out = tmp_path / "out"
    status, message, late = run(["simulate", "--nc", str(nc), *BOX, "--out", str(out)], signal_after=1.5,
                                signum=signal.SIGINT)
    assert status == 130, message[-2000:]
    assert "stopped by SIGINT" in message and "nothing was written" in message and "Traceback" not in message
    assert late is not None and late < 3.0, f"stopped {late:.1f} s after the signal"
    assert not out.exists() and everything_under(tmp_path) == ["big.ngc"]
