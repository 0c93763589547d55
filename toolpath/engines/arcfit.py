"""Arcs out: stretches of straight feed moves that follow a circle become G2/G3 arcs.

Planners flatten curves into chords (Clipper's offsets of letters, pocket corners, circles); a
control runs such a polyline block by block, slower and in more memory than one arc.  This filter
takes a planned :class:`~.program.Operation` and gives it back with every stretch of at least
``min_segments`` feed moves at one height, one feed (and one link flag) that an arc reproduces
within ``tolerance`` replaced by that arc (rules: :mod:`.arcfit_kernel`).  Nothing else changes:
rapids, plunges, ramps, moves that change Z, arcs already there, and operations with a texture
or rotary axes are left as they are.

What it promises, checked by the tests against brute force: every point of the old path lies
within ``tolerance`` of the new one and every point of the new one within ``tolerance`` of the old
(both ways, so the simulation and the part see the same cut), every arc's ends lie at one radius
from its centre, and the path keeps its direction.
"""
from __future__ import annotations

import numpy as np

from . import arcfit_kernel
from ..ir.errors import InputError
from ..ir.program import ARC_CCW, ARC_CW, FEED, Operation, Program
from .region import ARC_TOLERANCE

# mm: the chord error the planners flatten curves with (Clipper's round joins), so the arcs of an
# offset outline are found again; an arc lies on the side the chords cut off, where the round
# join really is.
DEFAULT_TOLERANCE = ARC_TOLERANCE
MIN_SEGMENTS = 3               # an arc replaces at least this many chords
MAX_RADIUS = 5000.0            # mm: flatter than this is a line to every control


class ArcFitError(InputError):
    """Settings the arc filter cannot work with."""


def fit_arcs(op: Operation, tolerance: float = DEFAULT_TOLERANCE, min_segments: int = MIN_SEGMENTS,
             max_radius: float = MAX_RADIUS) -> Operation:
    """``op`` with its circular stretches of feed moves as arcs (a new Operation; ``op`` is kept)."""
    if not (np.isfinite(tolerance) and 0 < tolerance <= 1.0):
        raise ArcFitError(f"arc tolerance must lie in 0..1 mm, got {tolerance!r}")
    if not (isinstance(min_segments, int) and min_segments >= 2):
        raise ArcFitError(f"an arc must replace at least 2 chords, got {min_segments!r}")
    n = len(op)
    if n < min_segments or op.rotary or op.texture is not None or op.texture_marks is not None:
        return op
    runs = _planar_runs(op, min_segments)
    if not runs:
        return op
    starts = op.start_points()
    links = op.links if op.links is not None else np.zeros(n, bool)
    pieces, copied_from = [], 0
    for first, last in runs:                       # moves first..last (inclusive) form one run
        if first > copied_from:
            pieces.append(_moves(op, links, np.arange(copied_from, first)))
        points = np.vstack([starts[first, :2], op.xyz[first:last + 1, :2]])
        fitted = arcfit_kernel.fit_run(np.ascontiguousarray(points[:, 0]), np.ascontiguousarray(points[:, 1]),
                                       float(tolerance), int(min_segments), float(max_radius))
        pieces.append(_run_moves(op, links, first, fitted))
        copied_from = last + 1
    if copied_from < n:
        pieces.append(_moves(op, links, np.arange(copied_from, n)))
    kind, xyz, feed, center, link = (np.concatenate([p[k] for p in pieces]) for k in range(5))
    if len(kind) == n:
        return op
    return op.replace(kind=kind, xyz=xyz, feed=feed, center=center,
                      links=link if op.links is not None else None)


def fit_program(program: Program, tolerance: float = DEFAULT_TOLERANCE) -> Program:
    """Every operation of ``program`` through :func:`fit_arcs` (a new Program)."""
    return Program(program.name, [fit_arcs(op, tolerance) for op in program.operations], program.units,
                   program.work_offset, program.rapid_rate, list(program.notes))


def _planar_runs(op: Operation, min_segments: int) -> list:
    """(first, last) move indices of every stretch of at least ``min_segments`` feed moves that
    keep their height, feed and link flag."""
    starts = op.start_points()
    planar = (op.kind == FEED) & (np.abs(op.xyz[:, 2] - starts[:, 2]) <= 1e-9)
    links = op.links if op.links is not None else np.zeros(len(op), bool)
    same = np.zeros(len(op), bool)
    same[1:] = planar[1:] & planar[:-1] & (op.feed[1:] == op.feed[:-1]) & (links[1:] == links[:-1])
    # a run starts at a planar move whose predecessor does not continue it
    begin = np.flatnonzero(planar & ~same)
    end = np.append(begin[1:], len(op))
    runs = []
    for first, stop in zip(begin.tolist(), end.tolist()):
        last = first
        while last + 1 < stop and same[last + 1]:
            last += 1
        if last - first + 1 >= min_segments:
            runs.append((first, last))
    return runs


def _moves(op: Operation, links, index: np.ndarray) -> tuple:
    return op.kind[index], op.xyz[index], op.feed[index], op.center[index], links[index]


def _run_moves(op: Operation, links, first: int, fitted: np.ndarray) -> tuple:
    """The run's moves from the kernel's pieces: a line keeps its original move, an arc ends
    where its last chord ended."""
    ends = fitted[:, 0].astype(np.int64)             # point index, 1-based within the run's moves
    turn = fitted[:, 3]
    index = first + ends - 1                         # the original move that ends each piece
    kind = np.where(turn > 0, ARC_CCW, np.where(turn < 0, ARC_CW, FEED)).astype(np.int8)
    z = op.xyz[index, 2]
    center = np.where((turn != 0)[:, None], np.column_stack([fitted[:, 1], fitted[:, 2], z]), op.center[index])
    return kind, op.xyz[index], op.feed[index], center, links[index]
