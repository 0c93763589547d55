"""A batch run short of memory ends with a message and exit status 4, never a SIGSEGV or a traceback,
and writes nothing.  Real limits: a child process whose address space (RLIMIT_AS, ``ulimit -v``) is
capped.  Below about 1.3 GB Blender's module dies loading (SIGSEGV in its allocator: 1.2 and
1.25 GB crashed, 1.15 GB loaded, so it varies), so batch refuses a cap under 1.5 GB before loading
anything; at 1.6 GB a simulation on a 0.01 mm cell (5e7 cells: over 2.6 GB) runs out in numpy
and the MemoryError is reported, far from the edge (the engraving sample itself needs about 1.6 GB)."""
import os
import resource
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def capped_run(megabytes: int, *argv) -> subprocess.CompletedProcess:
    def cap():
        resource.setrlimit(resource.RLIMIT_AS, (megabytes << 20, megabytes << 20))
    return subprocess.run([sys.executable, os.path.join(ROOT, "batch.py"), *argv], capture_output=True, text=True,
                          timeout=600, preexec_fn=cap, cwd=ROOT)


def test_an_address_space_too_small_for_blender_is_refused_before_loading(tmp_path):
    done = capped_run(700, "carve", "--sample", "dome", "--out", str(tmp_path / "out"))
    assert done.returncode == 4, (done.returncode, done.stderr[-2000:])
    assert done.stderr.strip() == ("kezuri: the address space is capped at 700 MB (ulimit -v); Blender's module "
                                   "crashes while loading below about 1300 MB: give the run 1536 MB or more")
    assert os.listdir(tmp_path) == []


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="address-space limits as measured on Linux")
def test_running_out_of_memory_is_a_message_and_nothing_is_written(tmp_path):
    program = tmp_path / "line.ngc"
    program.write_text("G21 G90 G17\nG0 Z5\nG0 X0 Y0\nG1 Z-1 F300\nG1 X100 Y50 F600\nG0 Z5\nM30\n")
    done = capped_run(1600, "simulate", "--nc", str(program), "--tool", "flat:6", "--stock", "box:0,0,-10,100,50,0",
                      "--cell", "0.01", "--out", str(tmp_path / "out"))
    assert done.returncode == 4, (done.returncode, done.stderr[-2000:])
    assert "Traceback" not in done.stderr
    assert done.stderr.strip().splitlines()[-1] == (
        "kezuri: out of memory (the address space is capped at 1600 MB, ulimit -v): nothing was written; give the "
        "run more memory, or lighter settings (a coarser stepover, sample spacing or simulation cell)")
    assert sorted(os.listdir(tmp_path)) == ["line.ngc"]
