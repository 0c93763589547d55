"""Programs the control cannot hold or cannot read fast enough are flagged (``post.capacity``),
and the turn-mill planner merges blocks shorter than the machine's block time where it can.

Every count here is taken from the posted TEXT by this file's own reader: a G93 block's time is
1 / F minutes (Fanuc B-64114EN, inverse time feed), a program's size its bytes.  The cam-like
case of a program far past the 0i-T's 512 kB is made with a small ``memory_kb`` instead of a
16 MB program."""
import re

import pytest

from kezuri.post import capacity, turnmill_xzc
from kezuri.toolpath.ir import machine
from kezuri.toolpath.operations.turnmill import turnmill as tm

TURNMILL = machine.preset("fanuc-0it-turnmill")


def g93_block_ms(text: str) -> list:
    """Milliseconds of every G01 block under G93, from its F word; our own reader."""
    times, inverse = [], False
    for line in text.splitlines():
        if line.startswith("("):
            continue
        if re.search(r"\bG93\b", line):
            inverse = True
        if re.search(r"\bG9[48]\b", line):
            inverse = False
        f = re.search(r"\bF([0-9.]+)", line)
        if inverse and f and re.search(r"[XZC]-?[0-9.]", line):
            times.append(60000.0 / float(f.group(1)))
    return times


@pytest.fixture(scope="module")
def sample_texts():
    v, f, stock = tm.sample_part()
    out = {}
    for block_ms in (None, TURNMILL.block_ms):
        plan = tm.plan(v, f, stock, tm.TurnMillSettings(block_ms=block_ms), name="sample")
        out[block_ms] = turnmill_xzc.TurnMillXZCPost().to_text(plan.program)
    return out


def test_the_planner_merges_blocks_shorter_than_the_profiles(sample_texts):
    before = [ms for ms in g93_block_ms(sample_texts[None]) if ms < 7.5]
    after = [ms for ms in g93_block_ms(sample_texts[7.5]) if ms < 7.5]
    assert len(after) < len(before)
    assert min(g93_block_ms(sample_texts[7.5])) >= 60000.0 / 9999.999      # F never past the word's ceiling


def test_the_rest_are_flagged_with_their_count(sample_texts):
    text = sample_texts[7.5]
    short = [ms for ms in g93_block_ms(text) if ms < 7.5]
    assert len(short) > 100                # the sample's convex rolls: chords held to 0.5 micron
    found = capacity.program_findings(text, TURNMILL.replace(memory_kb=None))
    assert len(found) == 1
    assert f"{len(short):,} inverse-time blocks shorter than the 7.5 ms" in found[0]
    assert len(capacity.short_blocks(text, 7.5)) == len(short)


def test_a_program_past_the_memory_is_flagged_with_both_sizes(sample_texts):
    text = sample_texts[7.5]
    size_kb = len(text.encode()) / 1024
    small = TURNMILL.replace(memory_kb=64.0, block_ms=None)
    found = capacity.program_findings(text, small, "the turnmill-xzc program")
    assert found == [f"the turnmill-xzc program is {size_kb:,.1f} kB, larger than the 64 kB program memory of "
                     f"{small.label}: run it from a memory card or DNC, or split it"]
    assert capacity.program_findings(text, small.replace(memory_kb=size_kb + 1)) == []
    assert capacity.program_findings(text, None) == []


def test_the_reader_follows_the_feed_mode():
    text = "%\nO0001\nG93\nG01 X10. F9000.\nX11. F100.\nG98\nG01 X12. F9000.\nG93 G01 Z1. C5. F8500.\nM30\n%\n"
    assert capacity.short_blocks(text, 7.5) == [4, 8]
    assert capacity.program_kb(text) == pytest.approx(len(text) / 1024)


def test_a_milling_program_larger_than_the_control_memory_is_flagged(tmp_path):
    """The carving sample posted for a Fanuc 0i-MF machining centre (512 kB of part program
    storage, the fanuc post's default machine) is far larger: batch says so on stderr and in the
    report, naming both sizes; the size is the file's own, measured here."""
    out = tmp_path / "carve"
    pytest.importorskip("bpy")
    from test_batch_stop import run

    code, message, _ = run(["carve", "--post", "fanuc", "--out", str(out)])
    assert code == 0, message[-2000:]
    size_kb = (out / "carve.nc").stat().st_size / 1024
    assert size_kb > 512
    report = (out / "report.json").read_text()
    expected = f"is {size_kb:,.1f} kB, larger than the 512 kB program memory"
    assert expected in message and expected in report


def test_an_export_measures_only_the_program_the_control_stores(tmp_path, sample_texts):
    """A job's export (operators/exporting.write_program, what ``batch.py job`` and the job list
    write through) flags the Fanuc turn-mill program on the 0i-T, and not the LinuxCNC variant of
    the same plan on the same machine, which is streamed (the turn-mill workflow's own rule)."""
    pytest.importorskip("bpy")
    from kezuri.operators.exporting import write_program

    xzc, linuxcnc = turnmill_xzc.TurnMillXZCPost(), turnmill_xzc.TurnMillLinuxCNCPost()
    assert xzc.machine == TURNMILL and linuxcnc.machine == TURNMILL     # both posts' default machine
    text = sample_texts[7.5]
    assert len(text.encode()) / 1024 > TURNMILL.memory_kb          # past the 0i-T's 512 kB
    stored, streamed = [], []
    write_program(str(tmp_path / "bar.nc"), text, xzc, stored)
    write_program(str(tmp_path / "bar.ngc"), text, linuxcnc, streamed)
    assert any("larger than the 512 kB program memory" in f for f in stored)
    assert streamed == [] and (tmp_path / "bar.ngc").read_text() == text
