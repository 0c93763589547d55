"""Arcs out: stretches of straight feed moves that follow a circle become G2/G3 arcs.

Planners flatten curves into chords (Clipper's offsets of letters, pocket corners, circles); a
control runs such a polyline block by block, slower and in more memory than one arc.  This filter
takes a planned :class:`~.program.Operation` and gives it back with every stretch of at least
``min_segments`` feed moves at one slope, one feed (and one link flag) that an arc reproduces
within ``tolerance`` replaced by that arc (rules: :mod:`.arcfit_kernel`).  A stretch at one height
becomes a plane arc; a stretch that climbs or sinks evenly (a ramp entry along a rounded outline)
becomes a helical arc (G2/G3 with Z, which every milling control here interpolates linearly in the
angle), kept only where every old vertex's Z lies within ``tolerance`` of the helix at its angle.
Nothing else changes: rapids, plunges (no XY), moves whose slope changes (a stretch never crosses a
plunge or a link boundary), arcs already there, and operations with a texture request (the
controller macro needs the single moves) or rotary axes are left as they are.

Where it runs, and why here.  The posts write it: :meth:`post.gcode.GcodePost.arcs_out` passes
every milling program through :func:`fit_program` just before writing, with the control's
arc-end tolerance (``ControllerLimits.arc_end_tolerance``) and its own number format, unless the
machine profile says Arcs off (``MachineProfile.arcs``; batch ``--no-arcs``, Machine & Stock >
Arcs).  A post may import only the IR, so the filter lives here, in ``toolpath/ir/``: it is one
step every export passes through (the panel's, batch's, job files'), like a PyCAM toolpath
filter before the exporter, and the only place that knows how the control will read the centre
words.  The plans (preview, simulation, export gate) stay the polylines the planners made; the
arcs lie within ``tolerance`` (0.01 mm) of them, far below the gate's 0.1 mm cells, and the tests
simulate both and compare.

What the control reads.  Given ``written`` (the post's number format: values -> the numbers its
words read back as), every arc is checked as the control will see it: its start and end as
written, its centre as the written start plus the written I/J.  The centre offset is chosen among
the format's grid points round the true centre so that the start and end radii differ least;
an arc whose radii still differ by more than ``end_tolerance`` (the control's alarm threshold),
or whose written ends coincide (a control would cut a full circle), or whose written sweep is not
the fitted one, is left as its chords.

What it promises, checked by the tests against brute force: every point of the old path lies
within ``tolerance`` of the new one and every point of the new one within ``tolerance`` of the old
(both ways, so the simulation and the part see the same cut), every arc's ends lie at one radius
from its centre, and the path keeps its direction.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from . import arcfit_kernel
from .errors import InputError
from .moves import ARC_CCW, ARC_CW, FEED, arc_sweep

# mm: the chord error the planners flatten curves with (engines.region.ARC_TOLERANCE, Clipper's round
# joins; the IR imports no engine, a test keeps the two equal), so the arcs of an offset outline are
# found again; an arc lies on the side the chords cut off, where the round join really is.
DEFAULT_TOLERANCE = 0.01
MIN_SEGMENTS = 3               # an arc replaces at least this many chords
MAX_RADIUS = 5000.0            # mm: flatter than this is a line to every control


class ArcFitError(InputError):
    """Settings the arc filter cannot work with."""


def fit_arcs(op, tolerance: float = DEFAULT_TOLERANCE, min_segments: int = MIN_SEGMENTS,
             max_radius: float = MAX_RADIUS, end_tolerance: float | None = None, written=None,
             step: float = 0.0):
    """``op`` (an :class:`~.program.Operation`) with its circular stretches of feed moves as arcs (a
    new Operation; ``op`` is kept, and returned itself where nothing changes).  ``written``: the post's number format, a function
    of an array of values giving the numbers the written words read as (None: exact numbers), and
    ``step`` its least increment (mm); ``end_tolerance``: the most the written start and end radii
    of an arc may differ (mm; None: no limit beyond the fit).  See the module's docstring."""
    if not (np.isfinite(tolerance) and 0 < tolerance <= 1.0):
        raise ArcFitError(f"arc tolerance must lie in 0..1 mm, got {tolerance!r}")
    if not (isinstance(min_segments, int) and min_segments >= 2):
        raise ArcFitError(f"an arc must replace at least 2 chords, got {min_segments!r}")
    if end_tolerance is not None and not (np.isfinite(end_tolerance) and end_tolerance > 0):
        raise ArcFitError(f"arc end tolerance must be a positive length in mm, got {end_tolerance!r}")
    if written is not None and not (np.isfinite(step) and 0 < step <= 0.1):
        raise ArcFitError(f"the number format's least increment must lie in 0..0.1 mm, got {step!r}")
    n = len(op)
    if n < min_segments or op.rotary or op.texture is not None or op.texture_marks is not None:
        return op
    runs = _even_runs(op, min_segments)
    if not runs:
        return op
    starts = op.start_points()
    # moves first..last (inclusive) form one run; its points are the first's start and the moves'
    # ends: points[first:last + 2] of the operation's start followed by every end
    firsts, lasts = (np.array(column, np.int64) for column in zip(*runs))
    points = np.vstack([op.start[None, :2], op.xyz[:, :2]])
    search = arcfit_kernel.fit_runs_for(int(np.sum(lasts - firsts + 2)))
    fitted = search(np.ascontiguousarray(points[:, 0]), np.ascontiguousarray(points[:, 1]), firsts, lasts,
                    float(tolerance), int(min_segments), float(max_radius))
    run = fitted[:, 0].astype(np.int64)
    ends = firsts[run] + fitted[:, 1].astype(np.int64) - 1        # the original move that ends each piece
    opens = np.ones(len(run), bool)                                 # a run's first piece begins at its first move
    opens[1:] = run[1:] != run[:-1]
    begins = np.where(opens, firsts[run], np.concatenate([[0], ends[:-1] + 1]))
    arc = fitted[:, 4] != 0
    first_move, last_move = begins[arc], ends[arc]
    centres, turns = fitted[arc, 2:4].reshape(-1, 2), fitted[arc, 4]
    if written is not None:
        good, centres = _as_written(starts[first_move, :2], op.xyz[last_move, :2], centres, turns < 0,
                                    written, step, end_tolerance)
        first_move, last_move, centres, turns = first_move[good], last_move[good], centres[good], turns[good]
    if len(first_move):
        good = _helix_holds(op, starts, first_move, last_move, centres, turns < 0, tolerance)
        first_move, last_move, centres, turns = first_move[good], last_move[good], centres[good], turns[good]
    if not len(first_move):
        return op
    keep = np.ones(n, bool)
    inside = np.zeros(n + 1, np.int64)              # moves strictly inside an arc (all but its last) go
    np.add.at(inside, first_move, 1)
    np.add.at(inside, last_move, -1)
    keep &= np.cumsum(inside)[:n] == 0
    kind, center = op.kind.copy(), op.center.copy()
    kind[last_move] = np.where(turns > 0, ARC_CCW, ARC_CW)
    center[last_move] = np.column_stack([centres, op.xyz[last_move, 2]])
    return op.replace(kind=kind[keep], xyz=op.xyz[keep], feed=op.feed[keep], center=center[keep],
                      links=op.links[keep] if op.links is not None else None)


def fit_program(program, tolerance: float = DEFAULT_TOLERANCE, end_tolerance: float | None = None,
                written=None, step: float = 0.0):
    """Every operation of ``program`` (a :class:`~.program.Program`) through :func:`fit_arcs`: a new
    Program, its other fields as they were."""
    return replace(program, operations=[fit_arcs(op, tolerance, end_tolerance=end_tolerance, written=written,
                                                 step=step) for op in program.operations], notes=list(program.notes))


def _as_written(start: np.ndarray, end: np.ndarray, centre: np.ndarray, clockwise: np.ndarray, written,
                step: float, end_tolerance: float | None) -> tuple:
    """(which arcs the control reads as fitted, their centres as it reads them).

    The control reads the centre as the written start plus the written offset I/J: among the
    nine offsets on the format's grid (``step`` apart) round the true one, the one whose start
    and end radii differ least is taken."""
    ws, we = written(start.reshape(-1)).reshape(-1, 2), written(end.reshape(-1)).reshape(-1, 2)
    offset = written((centre - ws).reshape(-1)).reshape(-1, 2)
    best = np.full(len(ws), np.inf)
    chosen = centre.copy()
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            trial = offset + step * np.array([di, dj])
            trial = written(trial.reshape(-1)).reshape(-1, 2)          # a number the format writes as is
            read = ws + trial
            mismatch = np.abs(np.hypot(trial[:, 0], trial[:, 1]) - np.hypot(*(we - read).T))
            better = mismatch < best - 1e-12
            best = np.where(better, mismatch, best)
            chosen[better] = read[better]
    apart = np.abs(we - ws).max(axis=1) >= 2 * step - 1e-12          # a control reads equal ends as a full circle
    fitted_sweep = arc_sweep(start, end, centre, clockwise)
    read_sweep = arc_sweep(ws, we, chosen, clockwise)
    same_way = np.abs(read_sweep - fitted_sweep) <= 0.25 * np.abs(fitted_sweep) + 1e-9
    good = apart & same_way & (best <= (np.inf if end_tolerance is None else end_tolerance))
    return good, chosen


# slope (dZ per mm of XY) two moves may differ by and still be one stretch: a planner's even ramp
# gives equal slopes to rounding; the helix check below bounds the Z error of what is fitted
SLOPE_TOLERANCE = 1e-6


def _even_runs(op, min_segments: int) -> list:
    """(first, last) move indices of every stretch of at least ``min_segments`` feed moves that
    keep their slope (0: one height), feed and link flag.  A move with no XY length that changes
    Z (a plunge) belongs to no stretch."""
    starts = op.start_points()
    d = op.xyz - starts
    length = np.hypot(d[:, 0], d[:, 1])
    flat = np.abs(d[:, 2]) <= 1e-9
    usable = (op.kind == FEED) & ((length > 1e-9) | flat)
    slope = np.where(flat, 0.0, d[:, 2] / np.maximum(length, 1e-300))
    links = op.links if op.links is not None else np.zeros(len(op), bool)
    same = np.zeros(len(op), bool)
    same[1:] = (usable[1:] & usable[:-1] & (op.feed[1:] == op.feed[:-1]) & (links[1:] == links[:-1])
                & (np.abs(slope[1:] - slope[:-1]) <= SLOPE_TOLERANCE) & (flat[1:] == flat[:-1]))
    # a run starts at a usable move whose predecessor does not continue it
    begin = np.flatnonzero(usable & ~same)
    end = np.append(begin[1:], len(op))
    runs = []
    for first, stop in zip(begin.tolist(), end.tolist()):
        last = first
        while last + 1 < stop and same[last + 1]:
            last += 1
        if last - first + 1 >= min_segments:
            runs.append((first, last))
    return runs


def _helix_holds(op, starts: np.ndarray, first_move: np.ndarray, last_move: np.ndarray,
                 centres: np.ndarray, clockwise: np.ndarray, tolerance: float) -> np.ndarray:
    """Which fitted arcs keep every old vertex's Z within ``tolerance`` of the arc's Z at that
    vertex's angle (a control moves Z in proportion to the angle swept).  Plane arcs always do."""
    z0 = starts[first_move, 2]
    z1 = op.xyz[last_move, 2]
    good = np.ones(len(first_move), bool)
    for index in np.flatnonzero(np.abs(z1 - z0) > 1e-9).tolist():
        first, last = int(first_move[index]), int(last_move[index])
        points = np.vstack([starts[first], op.xyz[first:last + 1]])
        angle = np.unwrap(np.arctan2(points[:, 1] - centres[index, 1], points[:, 0] - centres[index, 0]))
        swept = angle - angle[0]
        total = swept[-1]
        if abs(total) < 1e-12 or (total < 0) != bool(clockwise[index]):
            good[index] = False
            continue
        expected = z0[index] + (z1[index] - z0[index]) * swept / total
        good[index] = bool(np.abs(points[:, 2] - expected).max() <= tolerance)
    return good
