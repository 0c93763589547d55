"""The plain blocks of an NC program read in bulk, as arrays (the NC reader's fast path).

Nearly every line of a long program is a plain move: an optional ``N`` number, an optional
G0/G1/G2/G3, then X Y Z C I J F words in that order, in capitals, without comments.  Such lines are
found for a whole chunk of text by one regular expression (:data:`PLAIN`), their numbers turned
into arrays, and their effect worked out with array operations: the modal motion and the feed
carried forward, absolute positions carried forward, incremental ones summed in order (the same
additions in the same order as one line at a time, so the same numbers).

A line that could do anything else (raise an error, start a drilling cycle's moves, sit near an
arc tolerance's edge) is not decided here: :func:`plain_moves` stops before it and the reader
follows it one line at a time, as it follows every line that is not plain.  So a program gives
the same moves, the same line numbers and the same errors either way; the tests read programs
both ways and compare.

The moves are kept in :class:`MoveStore`, a list of array chunks, and the line of every move in
:class:`LineNumbers`: no Python object per move.
"""
from __future__ import annotations

import math
import re
from collections.abc import Sequence

import numpy as np

from ..ir.errors import MAX_REACH_MM

# LinuxCNC's arc tolerances (interp_internal.hh), program units
ARC_TOLERANCE_MM = 2 * 0.01 * math.sqrt(2)       # CENTER_ARC_RADIUS_TOLERANCE_MM
ARC_TOLERANCE_INCH = 2 * 0.001 * math.sqrt(2)    # CENTER_ARC_RADIUS_TOLERANCE_INCH
ARC_RELATIVE_TOLERANCE = 0.001                   # SPIRAL_RELATIVE_TOLERANCE
MIN_ARC_RADIUS_INCH = 0.00005                    # RADIUS_TOLERANCE_INCH (0.00127 mm)
# an arc this close (relative) to a tolerance's edge is left to the line-at-a-time check
EDGE = 1e-6

_NUMBER = r"([-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+))"
_GAP = r"[ \t]*"
# One line: plain (groups N, G, X, Y, Z, C, I, J, F; the last group empty) or anything else (the
# last group holds it; an empty line is plain).  Read with re.M over a chunk of lines ended by LF.
PLAIN = re.compile(
    rf"^{_GAP}(?:(N)[0-9]+{_GAP})?(?:G0*([0-3])(?![0-9.]){_GAP})?"
    + "".join(rf"(?:{axis}{_NUMBER}{_GAP})?" for axis in "XYZCIJ")
    + rf"(?:F(\+?(?:[0-9]+\.?[0-9]*|\.[0-9]+)){_GAP})?$|^(.*)$", re.M)
ROW_OTHER = 9            # the index of the "anything else" group in a row of PLAIN.findall
_CODE = {"": -1, "0": 0, "1": 1, "2": 2, "3": 3}
CYCLE_MODE = -2          # a drilling cycle's mode, as the bulk reader marks it


class MoveStore:
    """The moves read so far, in chunks of arrays: kind, point (x, y, z), centre, C, line,
    spindle speed and whether the spindle turns clockwise (or is stopped)."""

    FIELDS = ("kind", "point", "centre", "c", "line", "speed", "turning")

    def __init__(self):
        self.chunks = []
        self.pending = []           # moves appended one at a time, as tuples in FIELDS' order
        self.count = 0

    def append(self, kind, point, centre, c, line, speed, turning):
        self.pending.append((kind, point, centre, c, line, speed, turning))
        self.count += 1

    def extend(self, kind, point, centre, c, line, speed, turning):
        self._flush()
        self.chunks.append((kind, point, centre, c, line, speed, turning))
        self.count += len(kind)

    def _flush(self):
        if self.pending:
            kind, point, centre, c, line, speed, turning = zip(*self.pending)
            self.chunks.append((np.array(kind, np.int8), np.array(point, float).reshape(-1, 3),
                                np.array(centre, float).reshape(-1, 3), np.array(c, float),
                                np.array(line, np.int64), np.array(speed, float), np.array(turning, bool)))
            self.pending = []

    def arrays(self) -> dict:
        """Every field as one array."""
        self._flush()
        return {name: np.concatenate([chunk[k] for chunk in self.chunks]) if self.chunks else np.empty(0)
                for k, name in enumerate(self.FIELDS)}


class LineNumbers(Sequence):
    """The program line of every move, held as an int64 array; reads as a list of ints (an item
    is an ``int``, a slice is LineNumbers, it equals a list of the same numbers)."""

    def __init__(self, values):
        self.values = np.asarray(values, np.int64).reshape(-1)

    def __len__(self):
        return len(self.values)

    def __getitem__(self, index):
        if isinstance(index, slice):
            return LineNumbers(self.values[index])
        return int(self.values[index])

    def __eq__(self, other):
        if isinstance(other, LineNumbers):
            return np.array_equal(self.values, other.values)
        if isinstance(other, (list, tuple)):
            return len(other) == len(self) and all(int(a) == b for a, b in zip(self.values, other))
        return NotImplemented

    def __array__(self, dtype=None, copy=None):
        return self.values if dtype is None else self.values.astype(dtype)

    def __repr__(self):
        return f"LineNumbers({self.values.tolist() if len(self) <= 20 else len(self)})"

    __hash__ = None


def _numbers(column) -> np.ndarray:
    """The numbers of one word's column (NaN where the line has none)."""
    if not any(column):
        return np.full(len(column), np.nan)
    return np.array([float(text) if text else math.nan for text in column])


def _carried(present: np.ndarray, values: np.ndarray, before: float) -> np.ndarray:
    """``values`` carried forward over the lines where they are absent, ``before`` until the first."""
    index = np.where(present, np.arange(len(values)), -1)
    np.maximum.accumulate(index, out=index)
    return np.where(index >= 0, values[np.maximum(index, 0)], before)


def plain_moves(reader, rows: list, first_number: int) -> int:
    """Follow the plain lines ``rows`` (rows of :data:`PLAIN`, the first being line
    ``first_number``) from ``reader``'s state (its position, mode, absolute, scale, feed_rate,
    feed_line, known, speed, direction, saw_c, started, moves and ignore()), appending their moves
    and updating that state.  Returns how many lines it followed: it stops before the first line
    it leaves to the reader's line-at-a-time path."""
    n = len(rows)
    if not n:
        return 0
    names, codes, xs, ys, zs, cs, i_words, j_words, fs = list(zip(*rows))[:ROW_OTHER]
    scale = reader.scale
    raw = {axis: _numbers(column) for axis, column in zip("XYZCIJ", (xs, ys, zs, cs, i_words, j_words))}
    present = {axis: ~np.isnan(values) for axis, values in raw.items()}
    feeds = _numbers(fs)
    has_feed = ~np.isnan(feeds)
    code = np.array([_CODE[text] for text in codes], np.int64)
    mode0 = reader.mode
    start_mode = -1 if mode0 is None else mode0 if isinstance(mode0, int) else CYCLE_MODE
    mode = _carried(code >= 0, code, start_mode).astype(np.int64)
    line = first_number + np.arange(n)
    feed_rate = _carried(has_feed, feeds, math.nan if reader.feed_rate is None else reader.feed_rate)
    feed_line = _carried(has_feed, line, -1 if reader.feed_line is None else reader.feed_line)
    axes = present["X"] | present["Y"] | present["Z"] | present["C"]
    has_ij = present["I"] | present["J"]
    before = reader.moves.count + np.cumsum(axes) - axes        # moves read before each line

    flagged = ~np.isfinite(np.where(has_feed, feeds, 0.0))
    for axis, values in raw.items():
        flagged |= np.abs(values) * (scale if axis != "C" else 1.0) > MAX_REACH_MM
    flagged |= axes & ((mode == -1) | (mode == CYCLE_MODE))
    arc = axes & (mode >= 2)
    flagged |= has_ij & ~arc
    flagged |= axes & (mode >= 1) & ((feed_line < 0) | ~(feed_rate != 0))
    flagged |= arc & (~has_ij | (before == 0))
    if not reader.absolute:
        flagged |= axes & (before == 0)

    position = {}
    for axis in "XYZC":
        value = raw[axis] * (scale if axis != "C" else 1.0)
        if reader.absolute:
            position[axis] = _carried(present[axis], value, reader.position[axis])
        else:
            steps = np.concatenate([[reader.position[axis]], np.where(present[axis], value, 0.0)])
            position[axis] = np.add.accumulate(steps)[1:]
    previous = {axis: np.concatenate([[reader.position[axis]], position[axis][:-1]]) for axis in "XY"}
    centre_x = np.where(arc, previous["X"] + np.where(present["I"], raw["I"], 0.0) * scale, math.nan)
    centre_y = np.where(arc, previous["Y"] + np.where(present["J"], raw["J"], 0.0) * scale, math.nan)
    if arc.any():
        r1 = np.hypot(previous["X"] - centre_x, previous["Y"] - centre_y)
        r2 = np.hypot(position["X"] - centre_x, position["Y"] - centre_y)
        tolerance = (ARC_TOLERANCE_INCH if scale != 1.0 else ARC_TOLERANCE_MM) * scale
        error = np.abs(r1 - r2)
        near = 1 - EDGE
        with np.errstate(invalid="ignore", divide="ignore"):
            doubtful = ((np.minimum(r1, r2) < MIN_ARC_RADIUS_INCH * 25.4 * (1 + EDGE))
                        | (error > 100 * tolerance * near)
                        | ((error > tolerance * near) & (error / np.maximum(r1, r2) > ARC_RELATIVE_TOLERANCE * near)))
        flagged |= arc & doubtful

    done = int(np.argmax(flagged)) if flagged.any() else n
    if not done:
        return 0
    take = slice(0, done)
    moving = np.flatnonzero(axes[take])
    if len(moving):
        speed = reader.speed if reader.direction is not None else 0.0
        count = len(moving)
        reader.moves.extend(
            mode[moving].astype(np.int8),
            np.column_stack([position["X"][moving], position["Y"][moving], position["Z"][moving]]),
            np.column_stack([centre_x[moving], centre_y[moving],
                             np.where(arc[moving], position["Z"][moving], math.nan)]),
            position["C"][moving], line[moving], np.full(count, speed), np.full(count, reader.direction is not False))
    last = done - 1
    for axis in "XYZC":
        reader.position[axis] = float(position[axis][last])
        if present[axis][take].any():
            reader.known.add(axis)
    if mode[last] >= 0:
        reader.mode = int(mode[last])
    feed_rows = np.flatnonzero(has_feed[take])
    if len(feed_rows):
        reader.feed_rate, reader.feed_line = float(feeds[feed_rows[-1]]), int(line[feed_rows[-1]])
        reader.ignore("F", "feed", int(line[feed_rows[0]]), len(feed_rows))
    reader.saw_c = reader.saw_c or bool(present["C"][take].any())
    if not reader.started:
        reader.started = bool((axes[take] | has_feed[take] | has_ij[take] | (code[take] >= 0)).any()
                              or any(names[:done]))
    return done
