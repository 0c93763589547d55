"""The posts' column-at-once word formatting (post/words.py) against words written out by hand:
rounding at the half digit, minus zero, trailing zeros, large values, modal words."""
import numpy as np

from kezuri.post import words
from kezuri.post.cldata import CLDataPost
from kezuri.post.gcode import GcodePost, fmt
from kezuri.toolpath.ir.program import ARC_CCW, FEED, RAPID, Operation, Tool


def test_column_words_at_the_edges():
    values = [0.0005, -0.0005, -0.0004, 0.0, -0.0, 0.0004, 2.5, 2.50049, 106.0, 0.0625, 0.1875, 99999.9996,
              123456789.125, -1234.5, 2.5]
    # 0.0005 is stored a little above 0.0005, so it rounds up; 0.0625 and 0.1875 are exact halves
    # at the 4th decimal and round to the even digit; -0.0004 reads as zero, written without a sign
    expected = ["0.001", "-0.001", "0.", "0.", "0.", "0.", "2.5", "2.5", "106.", "0.062", "0.188", "100000.",
                "123456789.125", "-1234.5", "2.5"]
    texts, ids = words.column(np.array(values), lambda v: fmt(v, 3))
    assert texts[ids].tolist() == expected
    # the same id exactly where the text is the same
    for i in range(len(values)):
        for j in range(len(values)):
            assert (ids[i] == ids[j]) == (expected[i] == expected[j]), (values[i], values[j])
    texts, ids = words.column(np.array([-0.00004, 1.0, 0.00005, np.nan]), lambda v: f"{v:.4f}")
    assert texts[ids].tolist() == ["-0.0000", "1.0000", "0.0001", "nan"]

    # the same texts from the formatters of whole lists
    texts, ids = words.column(np.array(values), lambda v: fmt(v, 3), lambda many: words.trimmed(many, 3))
    assert texts[ids].tolist() == expected


def test_list_formatters_write_what_the_scalar_ones_do():
    """words.fixed / words.trimmed and cldata's list formatter against the f-string, gcode.fmt and
    cldata._num, value by value: halves, minus zeros, NaN, infinities, large and tiny values."""
    from kezuri.post.cldata import _num, _nums

    rng = np.random.default_rng(7)
    values = np.concatenate([[0.0, -0.0, 0.5, -0.5, 1.5, 2.5, 0.0625, -0.0625, 0.00005, -0.00005, -0.00004,
                              1e-300, -1e-300, 99999.9995, 123456789.125, np.nan, np.inf, -np.inf],
                             rng.uniform(-1000, 1000, 2000), np.round(rng.uniform(-10, 10, 2000), 4) + 5e-5,
                             rng.integers(-10 ** 6, 10 ** 6, 500) / 2 ** rng.integers(1, 12, 500)]).tolist()
    for decimals in (0, 1, 3, 4, 6):
        assert words.fixed(values, decimals) == [f"{v:.{decimals}f}" for v in values]
        assert words.trimmed(values, decimals) == [fmt(v, decimals) for v in values]
        assert _nums(values, decimals) == [_num(v, decimals) for v in values]
    assert words.fixed([], 3) == [] and words.trimmed([], 3) == []


def test_previous_where_and_join():
    assert words.previous_where(np.array([True, False, True, False])).tolist() == [-1, 0, 0, 2]
    lines = words.join_words([np.array(["G01", "", ""], object), np.array(["X1.", "", "X2."], object),
                              np.array(["", "Y3.", ""], object)])
    assert lines == ["G01 X1.", "Y3.", "X2."]


def test_gcode_moves_written_by_hand():
    """Moves: a rapid, a feed that rounds to no motion (dropped), feeds with a change below the
    F resolution, an arc (G03 and X Y always, I J from the last written point), a rapid."""
    kind = [RAPID, FEED, FEED, FEED, FEED, ARC_CCW, RAPID]
    xyz = [(10, 0, 5), (10.0004, 0, 5), (10, 0, -1.0625), (30, 0, -1.0625), (30, 10, -1), (20, 20, -1),
           (20, 20, 5)]
    feed = [np.nan, 300.0, 300.04, 300.04, 500.0, 500.0, np.nan]
    center = np.full((7, 3), np.nan)
    center[5] = (20, 10, -1)
    op = Operation("o", Tool(1, "flat", 6.0), 1000, kind, xyz, feed, center=center, start=np.array([0.0, 0.0, 20.0]))
    assert GcodePost().moves(op, op.start) == [
        "G00 X10. Z5.", "G01 Z-1.062 F300.", "X30.", "Y10. Z-1. F500.", "G03 X20. Y20. I-10. J0.", "G00 Z5."]


def test_cldata_moves_written_by_hand():
    kind = [RAPID, FEED, FEED, RAPID]
    xyz = [(1, 2, 3), (1, 2, -0.00004), (4.03125, 2, 0), (4, 2, 10)]
    feed = [np.nan, 150.0, 150.04, np.nan]
    op = Operation("o", Tool(2, "flat", 4.0), 1000, kind, xyz, feed, start=np.array([0.0, 0.0, 10.0]))
    lines = CLDataPost().operation(0, op)
    assert lines[lines.index("FROM/0.0000,0.0000,10.0000") + 1:] == [
        "RAPID", "GOTO/1.0000,2.0000,3.0000,0.000000,0.000000,1.000000",
        "FEDRAT/MMPM,150.0", "GOTO/1.0000,2.0000,0.0000,0.000000,0.000000,1.000000",
        "GOTO/4.0312,2.0000,0.0000,0.000000,0.000000,1.000000",
        "RAPID", "GOTO/4.0000,2.0000,10.0000,0.000000,0.000000,1.000000", "SPINDL/OFF"]
