"""Level runs of the manifold engine that repeat one another (see sweep.py): the pocket's layers
along one path, a radial tool's rings at one height.  A run that another run of its group covers
from deeper down adds nothing to the cut and is left out; so does a move between runs that
another one holds from below (a zigzag ramp's legs)."""
from __future__ import annotations

import math

import numpy as np


class Repeats:
    """Level runs grouped by what they repeat; a run is left out when another run in its group
    covers its whole path deeper down.

    Each tool grows no narrower from its tip to its shank and its shank reaches out of the
    stock, so the tool contains itself moved away from its tip along its axis: an upright tool
    lower on the same vertical line, a radial tool nearer the C axis on the same ray.  Groups
    are an upright tool along one path (see :class:`Level`) and a radial tool at one height
    (see :class:`RadialLevel`)."""

    def __init__(self):
        self.groups = {}

    def add(self, key, run, make) -> None:
        """``run`` (a Level or RadialLevel) in group ``key``, with ``make()`` returning its pieces."""
        self.groups.setdefault(key, []).append((run, make))

    def kept(self) -> list:
        """The pieces of every run that no other run in its group covers (of runs that cover
        each other, the first)."""
        made = []
        for runs in self.groups.values():
            for n, (run, make) in enumerate(runs):
                if not any(other.covers(run) and (m < n or not run.covers(other))
                           for m, (other, _) in enumerate(runs) if m != n):
                    made.append(make())
        return made


class Level:
    """An upright tool's level run, grouped with runs along the same path: the lower covers the higher."""

    def __init__(self, points: np.ndarray):
        self.low, self.high = float(points[:, 2].min()), float(points[:, 2].max())

    def covers(self, other: "Level") -> bool:
        return self.high <= other.low


class RadialLevel:
    """A radial tool's run at one height, as its reach from the C axis along each angle, grouped
    with the same tool's runs at that height."""

    def __init__(self, points: np.ndarray):
        xy = points[:, :2]
        angle = np.unwrap(np.arctan2(xy[:, 1], xy[:, 0]))
        if angle[-1] < angle[0]:
            angle, xy = angle[::-1], xy[::-1]
        self.monotone = bool(np.all(np.diff(angle) > 1e-12))
        self.angle, self.xy = angle, xy
        self.full = angle[-1] - angle[0] >= 2 * math.pi - 1e-9

    def reach(self, angles: np.ndarray) -> np.ndarray:
        """Where the ray from the C axis at each angle (within the run's) meets the path."""
        k = np.clip(np.searchsorted(self.angle, angles, side="right") - 1, 0, len(self.angle) - 2)
        a, d = self.xy[k], self.xy[k + 1] - self.xy[k]
        return (a[:, 0] * d[:, 1] - a[:, 1] * d[:, 0]) / (np.cos(angles) * d[:, 1] - np.sin(angles) * d[:, 0])

    def covers(self, other: "RadialLevel") -> bool:
        """Whether this run passes nearer the C axis than ``other`` at every angle ``other``
        passes.  Both paths turn one way about C, so comparing them at the vertices of either is
        enough: two straight moves between the same two rays cross at most once."""
        if not (self.monotone and other.monotone):
            return False
        turn, first = 2 * math.pi, self.angle[0]
        low, high = other.angle[0], other.angle[-1]
        if self.full:
            own = self.angle[self.angle < first + turn]
            shifts = np.arange(math.floor((low - first) / turn), math.ceil((high - first) / turn) + 1) * turn
            mine = (own[None, :] + shifts[:, None]).ravel()
            to_own = lambda angles: first + (angles - first) % turn
        else:
            shift = turn * math.floor((low - first) / turn)
            if high > self.angle[-1] + shift + 1e-12:
                return False
            mine = self.angle + shift
            to_own = lambda angles: angles - shift
        angles = np.concatenate([other.angle, mine[(mine > low) & (mine < high)]])
        return bool(np.all(self.reach(to_own(angles)) <= other.reach(angles) + 1e-9))


class LevelPaths:
    """The moves of every level run of an upright tool, by tool and by the two ends of the move
    seen from above (rounded to 1e-6 mm), with the lowest height each is cut at.

    A move of the same tool whose two ends lie on such a move's, no lower than it, lies on the
    same vertical lines higher up: the tool there is contained in the tool below (see
    :class:`Repeats`), so its sweep adds nothing to the cut.  A ramp entry that follows the
    contour it then cuts at depth is such a run of moves."""

    def __init__(self):
        self.lowest = {}         # tool -> {move's two ends: lowest height}

    @staticmethod
    def _keys(points: np.ndarray) -> list:
        ends = np.round(points[:, :2], 6).tolist()
        return [(a[0], a[1], b[0], b[1]) if a <= b else (b[0], b[1], a[0], a[1]) for a, b in zip(ends[:-1], ends[1:])]

    def add(self, tool, run: np.ndarray) -> None:
        """The level run ``run`` (points (n, 3), one height) of ``tool``, which is cut."""
        z = round(float(run[0, 2]), 6)
        lowest = self.lowest.setdefault(tool, {})
        for key in self._keys(run):
            if lowest.get(key, math.inf) > z:
                lowest[key] = z

    def covered(self, tool, points: np.ndarray) -> np.ndarray:
        """Per move of the polyline ``points``: whether a level run of ``tool`` holds it from
        below (the same two ends seen from above, at or below the move's lower end)."""
        lowest = self.lowest.get(tool, {})
        low = np.round(np.minimum(points[:-1, 2], points[1:, 2]), 6)
        return np.array([lowest.get(key, math.inf) <= z + 1e-9 for key, z in zip(self._keys(points), low.tolist())],
                        bool)

    def not_held_below(self, tool, run: np.ndarray) -> list:
        """(first, last) point ranges of the level run ``run`` (one height) whose moves no level run
        of ``tool`` holds from strictly deeper down (the run never holds itself): a pocket layer
        whose rings repeat, in part, the path of a deeper layer."""
        z = round(float(run[0, 2]), 6)
        lowest = self.lowest.get(tool, {})
        keep = np.array([lowest.get(key, math.inf) >= z - 1e-9 for key in self._keys(run)], bool)
        edges = np.flatnonzero(np.diff(np.concatenate([[0], keep.astype(np.int8), [0]])))
        return [(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2])]

    def needed(self, tool, points: np.ndarray) -> list:
        """(first, last) point ranges of the polyline's moves to cut: all but those held from
        below (see :meth:`covered`); the first and last move are always kept, so the whole
        tool stands at both ends (the runs on either side count on it)."""
        keep = ~self.covered(tool, points)
        keep[0] = keep[-1] = True
        edges = np.flatnonzero(np.diff(np.concatenate([[0], keep.astype(np.int8), [0]])))
        return [(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2])]



def without_repeated_moves(points: np.ndarray, ranges: list) -> list:
    """The (first, last) point ranges of the polyline's moves to cut as hulls (``ranges``: all
    moves in them are), less the moves another of them holds from below: the same two ends seen
    from above (rounded to 1e-6 mm), each at or below this move's (a ramp that zigzags down along
    one line: each leg lies over the leg after next).  Each move that holds another is a range of
    its own, so it is cut as a hull of the whole tool, never merged with its neighbours.

    The hull of the tool at both ends of a move is the tool swept along it; the tool lower on the
    same vertical line contains it up to above the stock (see :class:`Repeats`), so the sweep along
    a move that lies over another at every point is contained in the other's.  Of moves at the
    same heights the first holds; a holder left out is itself held by a lower one."""
    cut = np.zeros(len(points) - 1, bool)
    for a, b in ranges:
        cut[a:b] = True
    ends = np.round(points[:, :2], 6).tolist()
    z = points[:, 2].tolist()
    groups = {}
    for k in np.flatnonzero(cut).tolist():
        a, b = ends[k], ends[k + 1]
        if a == b:        # straight up or down: its lower end decides
            key, heights = (a[0], a[1], a[0], a[1]), (min(z[k], z[k + 1]), min(z[k], z[k + 1]))
        elif a < b:
            key, heights = (a[0], a[1], b[0], b[1]), (z[k], z[k + 1])
        else:
            key, heights = (b[0], b[1], a[0], a[1]), (z[k + 1], z[k])
        groups.setdefault(key, []).append((k, heights))
    holder = np.full(len(cut), -1)
    for moves in groups.values():
        for k, (low, high) in moves:
            for m, (lo, hi) in moves:
                if m != k and lo <= low and hi <= high and (lo + hi < low + high or m < k):
                    holder[k] = m
                    break
    if np.all(holder < 0):
        return ranges
    alone = np.zeros(len(cut), bool)
    alone[holder[holder >= 0]] = True
    cut &= holder < 0
    out = []
    for a, b in _edges(cut):
        start = a
        for k in np.flatnonzero(alone[a:b]) + a:
            if k > start:
                out.append((start, int(k)))
            out.append((int(k), int(k) + 1))
            start = int(k) + 1
        if b > start:
            out.append((start, b))
    return out


def _edges(mask: np.ndarray) -> list:
    """(first, last) point ranges of the runs of True moves."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(np.int8), [0]])))
    return [(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2])]
