"""Cutting a contour to depth in step-downs, entering each level on a ramp along the contour.

A flat end mill cannot feed straight down into material (its centre does not cut), and a small
one breaks if it takes more than its diameter in depth at once.  So a contour cut at depth
``depth`` below the top is cut at :func:`levels` (equal steps of at most ``step``), and each
level is entered on a ramp *along the contour itself* at ``angle`` degrees: the tool descends
``tan(angle)`` mm per mm travelled, so the ramp to a level ``h`` lower is ``h / tan(angle)`` mm
long.  Then the whole contour is cut at that level, and the next ramp starts where it ended.

A closed contour (first point == last point) is walked round and round (a ramp longer than the
contour winds down like a helix along it).  An open one is ramped out and back over its start
(half the ramp out, half back, so the level begins at the contour's end), then cut end to end;
the next level starts from the end it reached, so directions alternate and the first is chosen
so that the last level runs the contour as given (the climb direction the planner chose).
"""
from __future__ import annotations

import math

import numpy as np

from ..ir.errors import InputError


class RampError(InputError):
    """A step-down or ramp angle that cannot be cut."""


MAX_ANGLE = 45.0        # degrees: steeper than this is a plunge, not a ramp


def levels(depth: float, step: float, top: float = 0.0) -> list:
    """The depths from ``top`` down to ``depth`` in equal steps of at most ``step`` (the last is
    ``depth``)."""
    if not (math.isfinite(step) and step > 0):
        raise RampError(f"step down must be a number > 0 mm, got {step!r}")
    if not (math.isfinite(depth) and depth < top):
        raise RampError(f"depth {depth!r} must lie below the top Z {top:g}")
    count = max(1, math.ceil((top - depth) / step - 1e-9))      # a step deeper than the cut: one level
    return [top + (depth - top) * k / count for k in range(1, count + 1)]


def _walk(path: np.ndarray, start: float, length: float) -> tuple:
    """Points of the closed ``path`` (m, 2) from arclength ``start`` over ``length`` mm (wrapping):
    (points (k, 2), distance of each from the walk's start); the walk's end point is the last."""
    seg = np.hypot(*np.diff(path, axis=0).T)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    perimeter = cum[-1]
    laps = int(math.ceil((start + length) / perimeter)) + 1
    s = np.concatenate([cum[:-1] + k * perimeter for k in range(laps)] + [[laps * perimeter]])
    xy = np.vstack([path[:-1]] * laps + [path[:1]])
    end = start + length
    inside = (s > start + 1e-9) & (s < end - 1e-9)
    along = np.concatenate([s[inside], [end]])
    points = np.column_stack([np.interp(along, s, xy[:, 0]), np.interp(along, s, xy[:, 1])])
    return points, along - start


def ramped_passes(path, depths: list, angle: float, top: float = 0.0) -> np.ndarray:
    """Points (k, 3) cutting ``path`` (m, 2) at each of ``depths`` in turn, each level entered on
    a ramp of ``angle`` degrees along the path.  The first point is where the tool enters, at Z
    ``top`` (``path[0]``, or an open path's last point when it is cut an even number of times);
    the rest are feed moves.  See the module notes."""
    if not (math.isfinite(angle) and 0 < angle <= MAX_ANGLE):
        raise RampError(f"ramp angle must be more than 0 and at most {MAX_ANGLE:g} degrees, got {angle!r}")
    path = np.asarray(path, float)[:, :2]
    slope = math.tan(math.radians(angle))
    closed = len(path) > 2 and np.allclose(path[0], path[-1])
    if not closed:
        return _open_passes(path, depths, slope, top)
    perimeter = float(np.hypot(*np.diff(path, axis=0).T).sum())
    moves, s, z = [np.array([[path[0, 0], path[0, 1], top]])], 0.0, top
    for level in depths:
        ramp = (z - level) / slope
        points, along = _walk(path, s, ramp)
        moves.append(np.column_stack([points, z + (level - z) * along / ramp]))
        s = (s + ramp) % perimeter
        points, _ = _walk(path, s, perimeter)
        moves.append(np.column_stack([points, np.full(len(points), level)]))
        z = level
    return np.vstack(moves)


def _open_passes(path: np.ndarray, depths: list, slope: float, top: float) -> np.ndarray:
    forward = len(depths) % 2 == 1        # the last level runs the path as given
    entry = path[0] if forward else path[-1]
    moves, z = [np.array([[entry[0], entry[1], top]])], top
    for level in depths:
        run = path if forward else path[::-1]
        out = np.vstack([run, run[-2::-1]])
        ramp = (z - level) / slope
        points, along = _walk(out, 0.0, ramp / 2)
        half = z + (level - z) / 2
        down = np.column_stack([points, z + (half - z) * along / (ramp / 2)])
        back = np.vstack([down[-2::-1, :2], run[:1]])
        back_along = ramp / 2 - np.concatenate([along[-2::-1], [0.0]])
        moves += [down, np.column_stack([back, half + (level - half) * back_along / (ramp / 2)])]
        moves.append(np.column_stack([run[1:], np.full(len(run) - 1, level)]))
        z, forward = level, not forward
    return np.vstack(moves)
