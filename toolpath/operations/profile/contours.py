"""The contours of a profile: the shape's outlines checked (closed, not crossing), offset to the
tool centre (Clipper2 through manifold's CrossSection, round joins within :data:`FINE` mm), put in
cutting order (a contour nested inside another is cut first) and walked by arclength.

Orientation: CrossSection returns outer boundaries counter-clockwise and holes clockwise, so its
region lies on the left of every loop.  Climb milling with the spindle turning clockwise (M03)
keeps the material on the tool's right; :func:`directed` turns the loops so the part is on the
right for climb and on the left for conventional cutting.
"""
from __future__ import annotations

import math

import numpy as np
from manifold3d import CrossSection, JoinType

from ...engines import region as rg
from ...ir.errors import InputError

FINE = 0.002            # mm: chord error of the offset's round joins (the outline test asks 0.01)
CORNER_DEG = 30.0       # a vertex of the shape turning more than this is a corner


class ProfileError(InputError):
    """A shape or a setting a profile cannot cut; the message names the object or the setting."""


def offset(shape: CrossSection, delta: float) -> CrossSection:
    """Grow (delta > 0) or shrink the region with round joins within :data:`FINE` mm."""
    if delta == 0:
        return shape
    return shape.offset(delta, JoinType.Round, 2.0, rg.circle_segments(delta, FINE))


def check_crossings(loops: list, what: str) -> None:
    """Refuse outlines that cross themselves or each other (an even-odd reading of them would not
    be the shape drawn).  Edges sorted by their least X; each chunk is tested against the edges
    whose X range meets its own, so the work follows the edges near each other."""
    a = np.vstack(loops)
    b = np.vstack([np.roll(loop, -1, axis=0) for loop in loops])
    owner = np.concatenate([np.full(len(loop), k) for k, loop in enumerate(loops)])
    index = np.concatenate([np.arange(len(loop)) for loop in loops])
    sizes = np.array([len(loop) for loop in loops])[owner]
    order = np.argsort(np.minimum(a[:, 0], b[:, 0]), kind="stable")
    a, b, owner, index, sizes = a[order], b[order], owner[order], index[order], sizes[order]
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    d = b - a
    for first in range(0, len(a), 256):
        rows = np.arange(first, min(first + 256, len(a)))
        reach = int(np.searchsorted(lo[:, 0], hi[rows, 0].max(), "right"))
        cols = np.arange(first, reach)
        cols = cols[hi[cols, 0] >= lo[rows, 0].min()]
        if not len(cols):
            continue
        i, j = rows[:, None], cols[None, :]
        p, r, q, s = a[i], d[i], a[j], d[j]
        denom = r[..., 0] * s[..., 1] - r[..., 1] * s[..., 0]
        qp = q - p
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (qp[..., 0] * s[..., 1] - qp[..., 1] * s[..., 0]) / denom
            u = (qp[..., 0] * r[..., 1] - qp[..., 1] * r[..., 0]) / denom
        same = owner[i] == owner[j]
        gap = np.abs(index[i] - index[j])
        neighbours = same & ((gap <= 1) | (gap == sizes[i] - 1))
        hit = (np.abs(denom) > 1e-12) & (t > 1e-9) & (t < 1 - 1e-9) & (u > 1e-9) & (u < 1 - 1e-9) & ~neighbours & (j > i)
        if hit.any():
            row, col = np.argwhere(hit)[0]
            x, y = p[row, 0] + t[row, col] * r[row, 0]
            raise ProfileError(f"{what}: the outline crosses itself at ({x:.2f}, {y:.2f}): a profile needs closed "
                               "outlines that do not cross")


def shape_region(loops, what: str) -> tuple:
    """(the region the outlines bound (even-odd), the clean loops)."""
    clean = [rg.validate_loop(loop, what) for loop in loops]
    if not clean:
        raise ProfileError(f"{what}: no closed outline to profile")
    check_crossings(clean, what)
    return rg.from_loops(clean, what), clean


def closed(loop: np.ndarray) -> np.ndarray:
    return np.vstack([loop, loop[:1]])


def lengths(path: np.ndarray) -> np.ndarray:
    """Cumulative arclength at every point of the path (starting at 0)."""
    return np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(path[:, :2], axis=0).T))])


def nearest(path: np.ndarray, point) -> tuple:
    """(arclength, distance, point) of the point of the open or closed polyline nearest ``point``."""
    p = np.asarray(point, float)[:2]
    a, b = path[:-1, :2], path[1:, :2]
    d = b - a
    length2 = np.maximum((d * d).sum(axis=1), 1e-30)
    t = np.clip(((p - a) * d).sum(axis=1) / length2, 0.0, 1.0)
    foot = a + d * t[:, None]
    dist = np.hypot(*(foot - p).T)
    k = int(np.argmin(dist))
    return float(lengths(path)[k] + t[k] * math.sqrt(length2[k])), float(dist[k]), foot[k]


def at(path: np.ndarray, s: float) -> tuple:
    """(point, unit tangent) of a closed polyline at arclength ``s`` (taken round the loop)."""
    cum = lengths(path)
    s = float(s) % cum[-1]
    k = int(np.clip(np.searchsorted(cum, s, "right") - 1, 0, len(path) - 2))
    d = path[k + 1] - path[k]
    seg = max(float(np.hypot(*d)), 1e-30)
    return path[k] + d * (s - cum[k]) / seg, d / seg


def with_points(path: np.ndarray, stations) -> np.ndarray:
    """The closed polyline with vertices added at the arclengths ``stations`` (taken round the loop)."""
    cum = lengths(path)
    perimeter = cum[-1]
    extra = np.unique(np.mod(np.asarray(list(stations), float), perimeter))
    s = np.unique(np.concatenate([cum[:-1], extra]))
    s = s[np.concatenate([[True], np.diff(s) > 1e-6])]
    xy = np.column_stack([np.interp(s, cum, path[:, 0]), np.interp(s, cum, path[:, 1])])
    return closed(xy)


def started_at(path: np.ndarray, s: float) -> np.ndarray:
    """The closed polyline re-started at arclength ``s`` (a vertex is put there)."""
    dense = with_points(path, [s])
    cum = lengths(dense)
    k = int(np.argmin(np.abs(cum[:-1] - float(s) % cum[-1])))
    return rg.rotate_closed(dense, k)


def corners(loops: list) -> list:
    """(point, turn in radians) of every vertex of the shape's loops turning more than CORNER_DEG."""
    found = []
    for loop in loops:
        before = loop - np.roll(loop, 1, axis=0)
        after = np.roll(loop, -1, axis=0) - loop
        turn = np.arctan2(before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0], (before * after).sum(axis=1))
        for k in np.flatnonzero(np.abs(turn) > math.radians(CORNER_DEG)):
            found.append((loop[k], float(turn[k])))
    return found


def nesting_order(loops: list, start_xy) -> list:
    """Indices of closed loops in cutting order: a loop inside more of the others first (holes and
    inner shapes before the outer cut-out), nearest first among equals."""
    depth = []
    for k, loop in enumerate(loops):
        inside = 0
        for m, other in enumerate(loops):
            if m != k and rg.contains_points(CrossSection([other[:-1]]), loop[:1, :2])[0]:
                inside += 1
        depth.append(inside)
    order, here = [], np.asarray(start_xy, float)
    for level in sorted(set(depth), reverse=True):
        items = [k for k in range(len(loops)) if depth[k] == level]
        for (k, _) in rg.order_loops_nearest(items, here, key=lambda k: loops[k]):
            order.append(k)
            here = loops[k][0, :2]
    return order


def directed(shape: CrossSection, part_left: bool, climb: bool) -> list:
    """The region's boundary loops, closed, turned so the part lies on the tool's right for climb
    (``part_left``: the part lies on the region's side of its loops as CrossSection gives them)."""
    turn = part_left == climb
    return [closed(loop[::-1] if turn else loop) for loop in rg.loops(shape)]
