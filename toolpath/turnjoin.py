"""Turn-mill passes: joining the runs of a layer into passes, nearest first.

:func:`_join` orders the runs of one layer nearest first and joins neighbours into passes; the
nearest run end is found on a grid (:class:`_RunEnds`), so the time follows the number of runs,
not its square (comparing every run with every other took over 5 minutes on a plain 64-sided
cylinder)."""
from __future__ import annotations

import itertools
import math

import numpy as np


class TurnMillCancelled(Exception):
    """The progress callback asked to stop."""


def _link_clear(a: np.ndarray, b: np.ndarray, surface, settings) -> bool:
    """Can the ball feed straight from centre a to centre b?  Points a stepover apart along the
    link must each be clear by r: between them the ball then dips by at most the scallop height,
    the tolerance, as along the passes."""
    count = max(1, math.ceil(np.linalg.norm(b - a) / settings.pick_feed))
    points = a + (b - a) * (np.arange(1, count)[:, None] / count)
    if not len(points):
        return True
    distance, _ = surface.nearest(points, settings.radius)
    return bool(np.all(distance >= settings.radius - settings.tolerance / 10))


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


def _join_layers(layers: dict, surface, settings, progress=None) -> list:
    """:func:`_join` on every layer, outermost first; ``progress(fraction)`` over all of them."""
    total = max(1, sum(len(runs) for runs in layers.values()))
    done, joined = 0, []
    for k in range(max(layers), -1, -1):
        runs = layers.get(k, [])
        report = None if progress is None else \
            (lambda fraction, base=done, size=len(runs): progress((base + fraction * size) / total))
        joined.append(_join(runs, surface, settings, report))
        done += len(runs)
    return joined


def _join(runs: list, surface, settings, progress=None) -> list:
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
        if min(to_start, to_end) <= 4 * settings.pick_feed and _link_clear(end, run[0], surface, settings):
            passes[-1] = np.vstack([passes[-1], run])
        else:
            passes.append(run)
    return passes
