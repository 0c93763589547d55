"""``batch.py simulate --nc`` refuses a stock too big for the height field's 80,000,000 cells
before it reads the program: the stock and the cell are known from the options, so a user with a
long file and a too-fine ``--cell`` hears it at once, not after the whole read.  Same message as
the simulation's own (``use a coarser cell``), exit 2, nothing written."""
import os
import time

import pytest

from kezuri.toolpath.simulate import BoxStock, CellError, CellTooFine, CylinderStock, check_cell
from kezuri.toolpath.simulate.heightfield import stock_grid
from test_hostile import time_limit

# 1000 / 0.01 = 100,000 columns along X and along Y: 1e10 cells, over 80,000,000
BIG = ("--tool", "flat:6", "--stock", "box:0,0,-10,1000,1000,0", "--cell", "0.01")
TOO_FINE = ("a 0.01 mm cell gives 1e+05 x 1e+05 cells over the stock (more than 80000000); use a coarser cell")


def test_the_check_refuses_what_the_height_field_refuses_with_its_message():
    """At the edge (the scaling table's row): 1264 x 632 mm at 0.1 mm is 12,640 x 6,320 =
    79,884,800 cells and passes; 1265 x 632.5 mm is 12,650 x 6,325 = 80,011,250 and is refused,
    word for word as stock_grid refuses it.  A bar of radius 500 mm at 0.1 mm: 10,000 x 10,000."""
    check_cell(BoxStock(0.0, 0.0, -10.0, 1264.0, 632.0, 0.0), 0.1)
    with pytest.raises(CellTooFine) as caught:
        check_cell(BoxStock(0.0, 0.0, -10.0, 1265.0, 632.5, 0.0), 0.1)
    assert str(caught.value) == ("a 0.1 mm cell gives 1.265e+04 x 6325 cells over the stock (more than 80000000); "
                                 "use a coarser cell")
    with pytest.raises(CellTooFine) as made:
        stock_grid(BoxStock(0.0, 0.0, -10.0, 1265.0, 632.5, 0.0), 0.1)
    assert str(made.value) == str(caught.value)
    with pytest.raises(CellTooFine, match=r"a 0\.1 mm cell gives 1e\+04 x 1e\+04 cells over the stock"):
        check_cell(CylinderStock(500.0, 100.0), 0.1)
    with pytest.raises(CellError, match="cell 30 mm is too coarse for a stock 100 mm across"):
        check_cell((0.0, 0.0, -10.0, 100.0, 100.0, 0.0), 30.0)      # the other end, as simulate checks it


def test_a_stock_too_fine_for_the_height_field_is_refused_before_a_huge_file_is_read(tmp_path):
    """An 8 GiB program (a first line, then a hole in a sparse file: nothing on disk): reading it
    would take 8 GiB of memory and many seconds; the refusal comes first, in well under one."""
    pytest.importorskip("bpy")
    from test_batch_job import run
    nc = tmp_path / "huge.ngc"
    with open(nc, "wb") as handle:
        handle.write(b"G21 G90 G0 X0 Y0 Z5\n")
        handle.truncate(8 << 30)
    assert os.path.getsize(nc) == 8 << 30
    out = tmp_path / "out"
    started = time.perf_counter()
    with time_limit(20):
        status, message, _ = run("simulate", "--nc", str(nc), *BIG, out=str(out))
    seconds = time.perf_counter() - started
    assert status == 2, message[-2000:]
    assert TOO_FINE in message and "Traceback" not in message, message[-2000:]
    assert "reading" not in message                     # no reader's progress: refused before it
    assert not out.exists() and os.listdir(tmp_path) == ["huge.ngc"]
    assert seconds < 3.0, f"refused after {seconds:.1f} s"


def test_the_cell_is_refused_before_the_program_is_even_counted(tmp_path):
    """11 million lines are over the 1e7 the reader takes (refused once the text is read); with a
    too-fine cell as well, the cell's refusal comes, since it needs no reading."""
    pytest.importorskip("bpy")
    from test_batch_job import run
    nc = tmp_path / "long.ngc"
    nc.write_text("G21 G90 G0 X0 Y0 Z5\n" + "\n" * 10_999_999)
    out = tmp_path / "out"
    with time_limit(60):
        status, message, _ = run("simulate", "--nc", str(nc), *BIG, out=str(out))
    assert status == 2, message[-2000:]
    assert TOO_FINE in message and "1.1e7 lines" not in message, message[-2000:]
    assert not out.exists() and os.listdir(tmp_path) == ["long.ngc"]
