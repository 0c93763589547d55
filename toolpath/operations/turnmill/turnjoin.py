"""Turn-mill passes: runs of ball centres kept a stepover apart (:func:`short_segments`), and
joining the runs of a layer into passes, nearest first; whether a merged move keeps the ball clear
(:func:`merged_move_clear`).

:func:`join_runs` orders the runs of one layer nearest first and joins neighbours into passes; the
nearest run end is found on a grid (:class:`_RunEnds`), so the time follows the number of runs,
not its square (comparing every run with every other took over 5 minutes on a plain 64-sided
cylinder)."""
from __future__ import annotations

import itertools
import math

import numpy as np

from ...ir import kinematics
from .errors import TurnMillError

MAX_BALL_POSITIONS = 5_000_000     # roughing copies of the passes: past this the memory runs out first
CHORD_DIP = 5e-4    # mm: how far a chord between ball centres may dip towards the part (the gate reports 1e-3)


def count_positions(total: list, more: int, direction: str, layers: int, step: float, stock, vertices) -> None:
    """Count ``more`` tool positions into ``total`` ([finishing, roughing]: layer 0 is finishing),
    refused past :data:`MAX_BALL_POSITIONS` naming the cause: the stock's excess over the part for
    roughing (a bar 10 m above the part: 24 GB, then killed), the fineness for finishing."""
    total[layers > 0] += more
    if total[layers > 0] <= MAX_BALL_POSITIONS:
        return
    if layers == 0:     # the finishing layer alone: the tolerance and spacing, not the stock
        raise TurnMillError(f"the {direction} finishing alone would need more than {MAX_BALL_POSITIONS} tool "
                            f"positions: give a coarser tolerance or sample spacing")
    if direction == "radial":
        why = (f"the stock's radius {stock.radius:g} mm stands up to "
               f"{stock.radius - float(np.hypot(vertices[:, 0], vertices[:, 1]).min()):g} mm outside the part")
    else:
        above = stock.z_max - float(vertices[:, 2].max())
        why = f"the stock's end face Z {stock.z_max:g} stands {above:g} mm above the part"
    raise TurnMillError(f"the {direction} roughing would need more than {MAX_BALL_POSITIONS} tool positions "
                        f"({layers} layers of {step:g} mm so far): {why}; give a stock closer to the part")


class TurnMillCancelled(Exception):
    """The progress callback asked to stop."""


def subdivide(points: np.ndarray, counts: np.ndarray, normals: np.ndarray | None = None):
    """Split segment i of the polyline into counts[i] equal parts (normals interpolated)."""
    idx = np.repeat(np.arange(len(counts)), counts)
    starts = np.repeat(np.cumsum(counts) - counts, counts)
    frac = ((np.arange(len(idx)) - starts) / np.repeat(counts, counts))[:, None]
    out = np.vstack([points[idx] + frac * (points[idx + 1] - points[idx]), points[-1:]])
    if normals is None:
        return out
    n = np.vstack([normals[idx] + frac * (normals[idx + 1] - normals[idx]), normals[-1:]])
    return out, n / np.maximum(np.linalg.norm(n, axis=1), 1e-12)[:, None]


def short_segments(runs: list, spacing: float, rounds: int, push) -> list:
    """Each run of clear ball centres with centres inserted until no two neighbours are more than
    ``spacing`` (the stepover) apart; ``push(centres)`` -> (centres pushed clear, clear?) fits the
    inserted ones.  For each run, the list of runs it became: it is split where an inserted centre
    cannot be pushed clear, or where a segment is still too long after ``rounds`` rounds.

    Why: two centres each clear of every surface point by r and at most s apart keep the whole
    segment between them at least sqrt(r^2 - s^2 / 4) from the surface, whatever its shape (no
    single surface point can come nearer); with s the stepover, that is r minus the tolerance (the
    scallop).  Pushing centres clear and moving roughing layers outward spread neighbours apart,
    and a pass rounding a convex edge (a spool flange's rim) cut its corner by 0.03 mm."""
    pieces = [[run] for run in runs]
    for _ in range(rounds):
        flat = [(i, piece) for i, group in enumerate(pieces) for piece in group]
        # a long segment is cut into parts 0.9 stepover long, so a small push keeps them short
        counts = [np.where(d > spacing, np.ceil(d / (0.9 * spacing)), 1).astype(int)
                  for d in (np.linalg.norm(np.diff(piece, axis=0), axis=1) for _, piece in flat)]
        if not any(np.any(c > 1) for c in counts):
            return _tight_chords(pieces, rounds, push)
        dense, inserted = [], []
        for (_, piece), c in zip(flat, counts):
            added = np.zeros(int(c.sum()) + 1, dtype=bool)
            if np.any(c > 1):
                added[:] = True                    # segment k's first point is the original one
                added[np.r_[np.cumsum(c) - c, c.sum()]] = False
                piece = subdivide(piece, c)
            dense.append(piece)
            inserted.append(added)
        points, mask = np.vstack(dense), np.concatenate(inserted)
        clear = np.ones(len(points), dtype=bool)
        points[mask], clear[mask] = push(points[mask])
        pieces = [[] for _ in runs]
        start = 0
        for (i, _), piece in zip(flat, dense):
            keep = clear[start:start + len(piece)]
            cuts = np.flatnonzero(np.diff(keep.astype(np.int8)) != 0) + 1
            pieces[i] += [p for p, k in zip(np.split(points[start:start + len(piece)], cuts),
                                            np.split(keep, cuts)) if k[0]]
            start += len(piece)
    return _tight_chords([[piece[run] for piece in group
                           for run in np.split(np.arange(len(piece)),
                                               np.flatnonzero(np.linalg.norm(np.diff(piece, axis=0), axis=1) > spacing)
                                               + 1)]
                          for group in pieces], rounds, push)


def _tight_chords(groups: list, rounds: int, push) -> list:
    """Each group's runs with the midpoint of every chord that dips more than :data:`CHORD_DIP`
    towards the surface inserted, pushed clear, and the halves checked again (at most ``rounds``
    times); a run is split where a midpoint cannot be pushed clear.

    Why: a stepover between clear centres bounds the dip by the scallop (the tolerance), but the
    export gate reports a cut 1 micron below the part; rounding a convex edge, or every edge of a
    faceted sphere, the chords of a 6 mm ball cut 0.007 mm."""
    flat = [piece for group in groups for piece in group]
    owner = [index for index, group in enumerate(groups) for _ in group]
    fresh = [np.ones(max(len(piece) - 1, 0), dtype=bool) for piece in flat]    # chords still to check
    for _ in range(rounds):
        where = [np.flatnonzero(f) for f in fresh]
        if not sum(len(w) for w in where):
            break
        middle = np.vstack([(piece[w] + piece[w + 1]) / 2 for piece, w in zip(flat, where) if len(w)])
        pushed, clear = push(middle)
        deep = ~clear | (np.linalg.norm(pushed - middle, axis=1) > CHORD_DIP)
        if not deep.any():
            break
        out, out_fresh, out_owner, start = [], [], [], 0
        for piece, w, own in zip(flat, where, owner):
            mine = slice(start, start + len(w))
            start += len(w)
            if not deep[mine].any():
                out.append(piece)
                out_fresh.append(np.zeros(max(len(piece) - 1, 0), dtype=bool))
                out_owner.append(own)
                continue
            insert = np.zeros(len(piece) - 1, dtype=bool)
            blocked = np.zeros(len(piece) - 1, dtype=bool)
            insert[w] = deep[mine] & clear[mine]
            blocked[w] = deep[mine] & ~clear[mine]
            added = np.zeros((len(piece) - 1, 3))
            added[w] = pushed[mine]
            if not blocked.any():       # the centres inserted; both halves of a split chord are new
                out.append(np.insert(piece, np.flatnonzero(insert) + 1, added[insert], axis=0))
                out_fresh.append(np.repeat(insert, np.where(insert, 2, 1)))
                out_owner.append(own)
                continue
            # the piece with the inserted centres, and per chord of it whether it is new
            points, chords = [piece[:1]], []
            for k in range(len(piece) - 1):
                if blocked[k]:                        # the ball cannot pass there: two runs
                    out.append(np.vstack(points))
                    out_fresh.append(np.array(chords, dtype=bool))
                    out_owner.append(own)
                    points, chords = [piece[k + 1:k + 2]], []
                    continue
                if insert[k]:
                    points.append(added[k:k + 1])
                    chords += [True, True]
                else:
                    chords.append(False)
                points.append(piece[k + 1:k + 2])
            out.append(np.vstack(points))
            out_fresh.append(np.array(chords, dtype=bool))
            out_owner.append(own)
        flat, fresh, owner = out, out_fresh, out_owner
    regrouped = [[] for _ in groups]
    for piece, own in zip(flat, owner):
        regrouped[own].append(piece)
    return regrouped


def link_clear(a: np.ndarray, b: np.ndarray, surface, settings) -> bool:
    """Can the ball feed straight from centre a to centre b?  Points along the link, ``s`` apart,
    must each be clear by r - :data:`CHORD_DIP` / 2; between two of them the ball then dips by at
    most s^2 / 8r = :data:`CHORD_DIP` / 2 more.  Points a stepover apart are tried first: most
    links that fail, fail there."""
    r = settings.radius
    length = float(np.linalg.norm(b - a))
    for spacing, allowance in ((settings.pick_feed, settings.tolerance / 10), (math.sqrt(4 * r * CHORD_DIP),
                                                                               CHORD_DIP / 2)):
        count = max(1, math.ceil(length / spacing))
        points = a + (b - a) * (np.arange(1, count)[:, None] / count)
        if len(points):
            distance, _ = surface.nearest(points, r)
            if not np.all(distance >= r - allowance):
                return False
    return True


class _RunEnds:
    """The two ends of every run on a grid, for "which remaining run end is nearest to this
    point?" without comparing every run with every other: the cells round the point are searched
    ring by ring until nothing unsearched can be nearer; far from every run (rare: a jump to
    another feature) the remaining ends are compared at once with numpy."""

    RINGS = 3        # rings searched before the numpy comparison of everything left

    def __init__(self, runs: list, cell: float):
        self.points = np.array([p for r in runs for p in (r[0], r[-1])], dtype=float).reshape(-1, 3)
        self.alive = np.ones(len(runs), dtype=bool)
        self.left = len(runs)
        self.cell = float(cell)
        keys = np.floor(self.points / self.cell).astype(np.int64)
        order = np.lexsort(keys.T[::-1])
        self.grid: dict = {}
        for key, group in itertools.groupby(order.tolist(), key=lambda i: tuple(keys[i])):
            self.grid[key] = np.array(list(group), dtype=np.int64)

    def remove(self, run: int) -> None:
        self.alive[run] = False
        self.left -= 1

    def _best(self, ids: np.ndarray, q: np.ndarray):
        ids = ids[self.alive[ids // 2]]
        if not len(ids):
            return None
        d = np.sqrt(((self.points[ids] - q) ** 2).sum(axis=1))
        k = np.lexsort((ids // 2, d))[0]
        return float(d[k]), int(ids[k] // 2)

    def nearest(self, q: np.ndarray) -> tuple:
        """(distance, run) of the nearest remaining run end; ties go to the lowest run."""
        centre = np.floor(q / self.cell).astype(np.int64)
        best = None
        for ring in range(self.RINGS + 1):
            ids = [self.grid[key] for key in _ring_keys(centre, ring) if key in self.grid]
            if ids:
                found = self._best(np.concatenate(ids), q)
                if found is not None and (best is None or found < best):
                    best = found
            # everything not searched yet is at least ring * cell away
            if best is not None and best[0] < ring * self.cell:
                return best
        return self._best(np.flatnonzero(np.repeat(self.alive, 2)), q)


def _ring_keys(centre: np.ndarray, ring: int):
    """Grid keys at Chebyshev distance ``ring`` from ``centre``."""
    cx, cy, cz = (int(v) for v in centre)
    if ring == 0:
        yield (cx, cy, cz)
        return
    span = range(-ring, ring + 1)
    for dx in span:
        for dy in span:
            if abs(dx) == ring or abs(dy) == ring:
                for dz in span:
                    yield (cx + dx, cy + dy, cz + dz)
            else:
                yield (cx + dx, cy + dy, cz - ring)
                yield (cx + dx, cy + dy, cz + ring)


def join_layers(layers: dict, surface, settings, progress=None) -> list:
    """:func:`join_runs` on every layer, outermost first; ``progress(fraction)`` over all of them."""
    total = max(1, sum(len(runs) for runs in layers.values()))
    done, joined = 0, []
    for k in range(max(layers), -1, -1):
        runs = layers.get(k, [])
        report = None if progress is None else \
            (lambda fraction, base=done, size=len(runs): progress((base + fraction * size) / total))
        joined.append(join_runs(runs, surface, settings, report))
        done += len(runs)
    return joined


def join_runs(runs: list, surface, settings, progress=None) -> list:
    """Order the runs of one layer nearest first (a run may be reversed), and join a run to the
    one before it into a pass when the gap is at most four stepovers and the straight link is clear.

    The nearest run is found on a grid of run ends (:class:`_RunEnds`), so the time follows the
    number of runs, not its square.  ``progress(fraction)`` is called every 256 runs; returning
    False cancels (:class:`TurnMillCancelled`)."""
    if not runs:
        return []
    ends = _RunEnds(runs, 4 * settings.pick_feed)
    ends.remove(0)
    passes = [runs[0]]
    for count in range(1, len(runs)):
        if progress is not None and count % 256 == 0 and progress(count / len(runs)) is False:
            raise TurnMillCancelled("turn-mill planning cancelled")
        end = passes[-1][-1]
        gap, i = ends.nearest(end)
        ends.remove(i)
        run = runs[i]
        to_start, to_end = np.linalg.norm(run[0] - end), np.linalg.norm(run[-1] - end)
        if to_end < to_start:
            run = run[::-1]
        if min(to_start, to_end) <= 4 * settings.pick_feed and link_clear(end, run[0], surface, settings):
            passes[-1] = np.vstack([passes[-1], run])
        else:
            passes.append(run)
    return passes


def merged_move_clear(direction: str, surface, settings):
    """``accept`` for :func:`program.merge_short_moves`: along each merged X-Z-C move (the curve the
    machine traces), ball centres the chord spacing of :func:`link_clear` apart each stay clear of
    the part by r - CHORD_DIP / 2, so between them the ball dips no deeper than a planned chord.
    All the moves asked about at once are checked in one nearest-point query."""
    r = settings.radius
    dx, dz = (r, 0.0) if direction == "radial" else (0.0, r)
    spacing = math.sqrt(4 * r * CHORD_DIP)

    def accept(a, c_a, b, c_b) -> np.ndarray:
        a, b = np.atleast_2d(a), np.atleast_2d(b)
        c_a, c_b = np.atleast_1d(np.asarray(c_a, float)), np.atleast_1d(np.asarray(c_b, float))

        def centres(owner, t):
            return kinematics.interpolate(a[owner, 0] + dx, c_a[owner], a[owner, 2] + dz,
                                          b[owner, 0] + dx, c_b[owner], b[owner, 2] + dz, t)
        every = np.arange(len(a))
        length = np.linalg.norm(centres(every, np.ones(len(a))) - centres(every, np.zeros(len(a))), axis=1)
        counts = np.maximum(2, np.ceil(length / spacing).astype(np.int64) + 1)
        owner = np.repeat(every, counts)
        t = (np.arange(len(owner)) - np.repeat(np.cumsum(counts) - counts, counts)) / (counts[owner] - 1)
        distance, _ = surface.nearest(centres(owner, t), r)
        return np.bincount(owner, weights=(distance < r - CHORD_DIP / 2).astype(float), minlength=len(a)) == 0
    return accept
