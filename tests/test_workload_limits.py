"""Work limits at their edge (toolpath/workload.py), as the scaling table (bench/bench_scaling.py)
states them.  ``batch.py simulate --nc``: a program of more than 1e7 lines (about 4 GB and 40 s of
reading and cutting at the 370 bytes and 3.7 us a move bench/scaling.json measured) is refused
after its text is read and before any line is followed: exit 2, a message naming the file, its
lines and the limit, nothing written, in a few seconds.  Just over a limit, the advice names a
value that passes (carve's spacing, turn-mill's faces), never the value already given."""
import os
import re
import time

import numpy as np
import pytest

from kezuri.toolpath import workload
from kezuri.toolpath.operations.carve.carve import CarveSettings
from kezuri.toolpath.operations.turnmill.turnmill import TurnMillSettings
from test_hostile import time_limit


def test_lines_are_counted_as_the_nc_reader_ends_them():
    assert workload.nc_lines("") == 0
    assert workload.nc_lines("G0 X1") == 1
    assert workload.nc_lines("G0 X1\n") == 1
    assert workload.nc_lines("G0 X1\nG1 X2") == 2
    assert workload.nc_lines("G0 X1\r\nG1 X2\r\n") == 2           # CR LF is one end
    assert workload.nc_lines("G0 X1\rG1 X2\rM2") == 3              # CR alone ends a line too
    assert workload.nc_lines("\n" * 10_000_000) == 10_000_000


def test_ten_million_lines_pass_and_one_more_is_refused_naming_the_file():
    assert workload.nc_program("raster.ngc", 10_000_000)[0].amount == 10_000_000
    with pytest.raises(workload.WorkloadError) as caught:
        workload.nc_program("raster.ngc", 10_000_001)
    assert str(caught.value) == ("the NC file 'raster.ngc' is about 1e7 lines, over the 1e7 this machine can "
                                 "simulate; split it into files of fewer lines, or write it with a coarser stepover "
                                 "or tolerance")


def test_the_refusal_comes_out_in_japanese_with_no_english_left():
    pytest.importorskip("bpy")
    from kezuri.operators import translations
    with pytest.raises(workload.WorkloadError) as caught:
        workload.nc_program("raster.ngc", 11_000_000)
    japanese = translations.japanese_message(str(caught.value))
    assert japanese == ("NC ファイル 'raster.ngc' は約 1.1e7 行 で、この機械でシミュレーションできる上限 1e7 を超えています。"
                        "行数の少ない複数のファイルに分けるか、ステップオーバーか公差を粗くして書き出してください")
    assert not [w for w in re.findall(r"[A-Za-z]{3,}", japanese) if w not in ("raster", "ngc")], japanese


def test_batch_refuses_a_program_past_the_line_limit_with_exit_2_before_reading_it(tmp_path):
    """11 million lines (a plain move on the first, then empty lines: 11 MB) are counted, not read:
    the refusal comes in seconds where reading and cutting them would take about 40 s and 4 GB."""
    pytest.importorskip("bpy")
    from test_batch_job import run
    nc = tmp_path / "huge.ngc"
    nc.write_text("G21 G90 G0 X0 Y0 Z5\n" + "\n" * 10_999_999)
    out = tmp_path / "out"
    started = time.perf_counter()
    with time_limit(60):
        status, message, _ = run("simulate", "--nc", str(nc), "--tool", "flat:6", "--stock", "box:0,0,-10,50,50,0",
                                 out=str(out))
    assert status == 2, message[-2000:]
    assert f"the NC file '{nc}' is about 1.1e7 lines, over the 1e7 this machine can simulate; split it" in message, \
        message[-2000:]
    assert "Traceback" not in message and "reading" not in message      # refused before the reader's progress
    assert not out.exists() and os.listdir(tmp_path) == ["huge.ngc"]
    assert time.perf_counter() - started < 30


def test_carve_just_over_the_limit_advises_a_sample_spacing_that_passes():
    """The finishing ball (3 mm, r 1.5) at scallop 0.02 mm steps 2 sqrt(2 x 1.5 x 0.02 - 0.02^2) =
    0.48826 mm; a design 486.16 x 4997.9 mm has a raster 488.26 x 5000 mm (r x 1.4 = 2.1 mm more):
    1001 lines of 5000 / 0.25 + 1 = 20,001 positions = 2.0021e7, just over 2e7.  Leaving out the
    +1s, the advice was 488.26 x 5000 / (0.48826 x 2e7) = 0.25 mm: the spacing given.  The spacing
    s with 1001 x (5000 / s + 1) = 2e7 is 5000 / (2e7 / 1001 - 1) = 0.25026: 0.26 mm."""
    settings = CarveSettings(scallop=0.02, sample_spacing=0.25)
    with pytest.raises(workload.WorkloadError) as caught:
        workload.carve("relief", (4997.9, 486.16, 10.0), 0.0, settings)
    assert "is about 2e7 tool positions, over the 2e7 this machine can plan; raise sample spacing to 0.26 mm or " \
           "more, or the scallop" in str(caught.value), str(caught.value)
    passes = workload.carve("relief", (4997.9, 486.16, 10.0), 0.0, CarveSettings(scallop=0.02, sample_spacing=0.26))[0]
    assert 1.9e7 < passes.amount < 2e7              # 1001 x (5000 / 0.26 + 1) = 1.926e7


def test_carve_with_more_raster_lines_than_the_limit_advises_the_scallop_alone():
    """At scallop 0.0001 mm the ball steps 0.03464 mm: a design a kilometre deep has 2.9e7 lines,
    more than 2e7 positions whatever the sample spacing."""
    with pytest.raises(workload.WorkloadError) as caught:
        workload.carve("relief", (10.0, 1e6, 10.0), 0.0, CarveSettings(scallop=0.0001, sample_spacing=100.0))
    assert str(caught.value).endswith("this machine can plan; raise the scallop"), str(caught.value)


def test_a_turn_mill_mesh_of_more_faces_than_a_quarter_of_the_limit_is_told_to_use_fewer_faces():
    """Every face has at least 2 x 2 classification samples: 1.3 million faces are 5.2e6 samples
    at any spacing (the advice named a spacing of 0.12 mm, finer than the 2 mm given)."""
    with time_limit(20), pytest.raises(workload.WorkloadError) as caught:
        workload.turnmill("part", np.full(1_300_000, 0.01), TurnMillSettings(sample_spacing=2.0))
    assert str(caught.value) == ("turn-mill 'part': 1.3e6 faces at sample spacing 2 mm is about 5.2e6 classification "
                                 "samples, over the 5e6 this machine can plan; use a mesh of at most 1.2e6 faces (each "
                                 "face is sampled at least 4 times)")
    assert workload.turnmill("part", np.full(1_250_000, 0.01), TurnMillSettings(sample_spacing=2.0))[0].amount == 5e6


def test_the_new_advice_comes_out_in_japanese():
    pytest.importorskip("bpy")
    from kezuri.operators import translations
    calls = [lambda: workload.carve("relief", (10.0, 1e6, 10.0), 0.0, CarveSettings(scallop=0.0001, sample_spacing=100.0)),
             lambda: workload.turnmill("part", np.full(1_300_000, 0.01), TurnMillSettings(sample_spacing=2.0))]
    for call in calls:
        with pytest.raises(workload.WorkloadError) as caught:
            call()
        japanese = translations.japanese_message(str(caught.value))
        assert japanese is not None, str(caught.value)
        assert not [w for w in re.findall(r"[A-Za-z]{3,}", japanese) if w not in ("relief", "part")], japanese


def test_the_engraving_is_refused_before_planning_past_two_million_gouges():
    """The scaling table's engrave row: at the default stepover 3 mm and gouge spacing 20 mm a
    gouge is 60 mm2 of plate, so 2e6 gouges are 1.2e8 mm2 (a 15.5 x 7.7 m plate)."""
    from kezuri.toolpath.operations.engrave.engrave import EngraveSettings
    assert workload.engrave("sign", 1.2e8 - 60, 0.0, EngraveSettings())[0].amount == pytest.approx(2e6 - 1)
    with pytest.raises(workload.WorkloadError) as caught:
        workload.engrave("sign", 1.2e8 + 60, 0.0, EngraveSettings())
    assert str(caught.value) == ("engrave 'sign': the gouge texture at stepover 3 mm and spacing 20 mm over 120000060 "
                                 "mm2 is about 2e6 gouges, over the 2e6 this machine can plan; raise stepover to 3.1 mm "
                                 "or more")


def test_the_gates_finest_grid_ends_at_eighty_million_cells():
    """The scaling table's engrave row: a 1265 x 632.5 mm stock is 12,650 x 6,325 = 80,011,250 cells
    of 0.1 mm, over the 80,000,000 the height field holds (1264 x 632 mm: 79,884,800), refused
    before any cell is made (the gate then goes to 0.2 mm)."""
    from kezuri.toolpath.simulate import BoxStock, CellTooFine
    from kezuri.toolpath.simulate.heightfield import stock_grid
    with time_limit(10), pytest.raises(CellTooFine) as caught:
        stock_grid(BoxStock(0.0, 0.0, -10.0, 1265.0, 632.5, 0.0), 0.1)
    assert str(caught.value) == ("a 0.1 mm cell gives 1.265e+04 x 6325 cells over the stock (more than 80000000); "
                                 "use a coarser cell")
