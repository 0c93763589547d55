"""W2 rotary pockets: curves for the passes, and joining them along outlines.

Circles and resampled curves at the point spacing, and :func:`follow_inside`: where a curve
leaves a tool-centre region it follows that region's outline (:class:`Boundary`) instead, then
rejoins the curve.
"""
from __future__ import annotations

import math

import numpy as np
from manifold3d import CrossSection

from ...engines import region as rg
from .rotary_pocket import row_norms, same_point, squared_distance


def densify(points: np.ndarray, spacing: float) -> np.ndarray:
    """Keep every vertex, split segments longer than ``spacing``; drop repeated points."""
    points = np.asarray(points, float)
    seg = np.diff(points, axis=0)
    length = row_norms(seg)
    if not np.all(length > 1e-6):
        points = points[np.concatenate([[True], length > 1e-6])]
        seg = np.diff(points, axis=0)
        length = row_norms(seg)
    count = np.maximum(1, np.ceil(length / spacing - 1e-9).astype(int))
    if len(points) < 2 or count.max() == 1:
        return points
    starts = np.repeat(points[:-1], count, axis=0)
    steps = np.repeat(seg / count[:, None], count, axis=0)
    k = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    return np.vstack([starts + steps * k[:, None], points[-1:]])


def circle_points(radius: float, spacing: float) -> np.ndarray:
    """Closed circle about the origin, counter-clockwise, points ``spacing`` apart (at most)."""
    n = max(12, math.ceil(2 * math.pi * radius / spacing))
    a = np.linspace(0, 2 * np.pi, n + 1)
    pts = np.column_stack([radius * np.cos(a), radius * np.sin(a)])
    pts[-1] = pts[0]
    return pts


def by_arc_length(curve: np.ndarray, spacing: float) -> np.ndarray:
    """Points ``spacing`` apart along a densely sampled curve (k, d)."""
    s = np.concatenate([[0.0], np.cumsum(row_norms(np.diff(curve, axis=0)))])
    targets = np.append(np.arange(0.0, s[-1], spacing), s[-1])
    return np.column_stack([np.interp(targets, s, curve[:, j]) for j in range(curve.shape[1])])


class Boundary:
    """A region's outline, prepared once for clipping curves to it and walking along it.

    Edges are numbered loop after loop; edge k runs from ``start[k]`` by ``vector[k]``."""

    def __init__(self, region: CrossSection):
        self.region = region
        self.loops = rg.loops(region)
        sizes = [len(loop) for loop in self.loops]
        self.loop_of = np.repeat(np.arange(len(sizes)), sizes)
        self.first_edge = np.cumsum(sizes) - sizes
        self.start = np.vstack(self.loops)
        self.vector = np.vstack([np.roll(loop, -1, axis=0) for loop in self.loops]) - self.start
        ends = self.start[:, 1] + self.vector[:, 1]
        self.y_low, self.y_high = np.minimum(self.start[:, 1], ends), np.maximum(self.start[:, 1], ends)
        self.far = float(row_norms(self.start).max())            # from the origin to the farthest vertex
        vx, vy = self.vector[:, 0], self.vector[:, 1]            # and to the nearest point of the outline
        self.near = float(np.sqrt(squared_distance(0.0, 0.0, self.start[:, 0], self.start[:, 1], vx, vy,
                                                    1.0 / np.maximum(vx * vx + vy * vy, 1e-300)).min()))
        # Per loop, over two rounds so any run of edges is one slice: the angle each edge turns
        # about the origin and its length, summed from the loop's first vertex.
        self.angles, self.turned, self.walked = [], [], []
        for loop in self.loops:
            angle = np.arctan2(loop[:, 1], loop[:, 0])
            step = np.tile(_short(np.roll(angle, -1) - angle), 2)
            length = np.tile(row_norms(np.roll(loop, -1, axis=0) - loop), 2)
            self.angles.append(angle)
            self.turned.append(np.concatenate([[0.0], np.cumsum(step)]))
            self.walked.append(np.concatenate([[0.0], np.cumsum(length)]))

    def _crossings(self, starts: np.ndarray, vectors: np.ndarray) -> np.ndarray:
        """Where a polyline's segments cross the outline, as segment index + parameter.

        Only segment-edge pairs whose heights overlap are tested: with the segments sorted by
        their lower end, those an edge can meet are one run, found by binary search."""
        low = np.minimum(starts[:, 1], starts[:, 1] + vectors[:, 1])
        order = np.argsort(low, kind="stable")
        rising = float(np.abs(vectors[:, 1]).max())
        first = np.searchsorted(low[order], self.y_low - rising, "left")
        count = np.searchsorted(low[order], self.y_high, "right") - first
        edge = np.repeat(np.arange(len(count)), count)
        segment = order[np.repeat(first, count) + np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)]
        d, f = vectors[segment], self.vector[edge]
        rel = self.start[edge] - starts[segment]
        denom = d[:, 0] * f[:, 1] - d[:, 1] * f[:, 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (rel[:, 0] * f[:, 1] - rel[:, 1] * f[:, 0]) / denom
            u = (rel[:, 0] * d[:, 1] - rel[:, 1] * d[:, 0]) / denom
        hit = (np.abs(denom) > 1e-15) & (t > 0) & (t < 1) & (u >= 0) & (u <= 1)
        return segment[hit] + t[hit]

    def clip(self, points: np.ndarray) -> list:
        """Parts of a polyline inside the region, as (k, 2) arrays: split at every crossing, a
        part kept when its midpoint is inside; a closed polyline cut open is re-joined across
        its start."""
        starts, vectors = points[:-1], np.diff(points, axis=0)
        u = np.unique(np.concatenate([np.arange(len(points), dtype=float), self._crossings(starts, vectors)]))
        segment = np.minimum(np.floor(u).astype(int), len(starts) - 1)
        refined = starts[segment] + vectors[segment] * (u - segment)[:, None]
        keep = rg.contains_points(self.region, (refined[:-1] + refined[1:]) / 2)
        change = np.flatnonzero(np.diff(np.concatenate([[False], keep, [False]])))
        pieces = [refined[a:b + 1] for a, b in zip(change[::2], change[1::2])]
        if same_point(points[0], points[-1]) and len(pieces) > 1 and keep[0] and keep[-1]:
            pieces[0] = np.vstack([pieces.pop()[:-1], pieces[0]])
        return [p for p in pieces if len(p) >= 2]

    def locate(self, points: np.ndarray) -> list:
        """For each point (n, 2): (loop, edge within it, parameter) of the outline edge it lies
        on, or None."""
        d = self.vector
        rx, ry = points[:, None, 0] - self.start[:, 0], points[:, None, 1] - self.start[:, 1]
        t = np.clip((rx * d[:, 0] + ry * d[:, 1]) / np.maximum(d[:, 0] ** 2 + d[:, 1] ** 2, 1e-300), 0, 1)
        dist = np.sqrt((rx - t * d[:, 0]) ** 2 + (ry - t * d[:, 1]) ** 2)
        edge = np.argmin(dist, axis=1)
        found = []
        for k, e in enumerate(edge):
            loop = self.loop_of[e]
            found.append(None if dist[k, e] > 1e-6 else (loop, e - self.first_edge[loop], float(t[k, e])))
        return found

    def path(self, a: np.ndarray, where_a, b: np.ndarray, where_b):
        """The way along the outline from a (where a counter-clockwise curve about the origin
        left the region) to b (where it comes back), given where they lie (:meth:`locate`):
        the way that turns about the origin as the curve did, the shorter one if both do;
        None when a and b are not on the same outline loop."""
        if where_a is None or where_b is None or where_a[0] != where_b[0]:
            return None
        wanted = (math.atan2(b[1], b[0]) - math.atan2(a[1], a[0])) % (2 * math.pi)
        ways = [self._way(a, where_a, b, where_b, forward) for forward in (True, False)]
        forward = min(ways, key=lambda way: (round(abs(way[0] - wanted), 6), way[1])) is ways[0]
        (index, ea, ta), (_, eb, tb) = where_a, where_b
        return _walk(self.loops[index], a, ea, ta, b, eb, tb, forward)

    def _way(self, a, where_a, b, where_b, forward: bool) -> tuple:
        """(angle turned about the origin, length) of :func:`_walk`'s way from a to b, from the
        loop's running sums: a few numbers, not the path."""
        (index, ea, ta), (_, eb, tb) = where_a, where_b
        loop, angle = self.loops[index], self.angles[index]
        n = len(loop)
        if ea == eb and (tb >= ta if forward else tb <= ta):
            return _short(math.atan2(b[1], b[0]) - math.atan2(a[1], a[0])), math.dist(a, b)
        if forward:      # a, vertices ea + 1 ... eb, b
            first, last, count = (ea + 1) % n, eb, (eb - ea - 1) % n
            edges, sign = first, 1.0
        else:            # a, vertices ea ... eb + 1, b (the edges between them walked backwards)
            first, last, count = ea, (eb + 1) % n, (ea - eb - 1) % n
            edges, sign = last, -1.0
        turned = self.turned[index][edges + count] - self.turned[index][edges]
        walked = self.walked[index][edges + count] - self.walked[index][edges]
        sweep = (_short(angle[first] - math.atan2(a[1], a[0])) + sign * turned
                 + _short(math.atan2(b[1], b[0]) - angle[last]))
        return sweep, math.dist(a, loop[first]) + walked + math.dist(loop[last], b)


def _short(angle):
    """An angle (radians) taken the short way round, in (-pi, pi]."""
    return math.pi - (math.pi - angle) % (2 * math.pi)


def _walk(loop: np.ndarray, a, ea, ta, b, eb, tb, forward: bool) -> np.ndarray:
    """From a (on edge ea at ta) along the loop to b (on edge eb at tb), through the vertices
    between them."""
    n = len(loop)
    if ea == eb and (tb >= ta if forward else tb <= ta):
        return np.array([a, b])
    if forward:
        vertices = (ea + 1 + np.arange((eb - ea - 1) % n + 1)) % n
    else:
        vertices = (ea - np.arange((ea - eb - 1) % n + 1)) % n
    return np.vstack([a, loop[vertices], b])


def follow_inside(curve: np.ndarray, boundary: Boundary, closed: bool) -> list:
    """A counter-clockwise curve about the origin (circle or spiral, (k, 2)) kept inside
    the region: where it would leave, it follows the region's outline to where it comes back.
    Returns chains (k, 2); pieces that cannot be joined (another outline loop) stay apart."""
    pieces = boundary.clip(curve)
    if not pieces:
        return []
    if closed and len(pieces) == 1 and same_point(pieces[0][0], pieces[0][-1]):
        return pieces
    where = boundary.locate(np.array([p[0] for p in pieces] + [p[-1] for p in pieces]))
    begins, ends = where[:len(pieces)], where[len(pieces):]
    chains = [pieces[0]]
    for k in range(1, len(pieces)):
        path = boundary.path(pieces[k - 1][-1], ends[k - 1], pieces[k][0], begins[k])
        if path is None:
            chains.append(pieces[k])
        else:
            chains[-1] = np.vstack([chains[-1], path[1:-1], pieces[k]])
    if closed:
        path = boundary.path(pieces[-1][-1], ends[-1], pieces[0][0], begins[0])
        if path is not None:
            if len(chains) == 1:
                chains[0] = np.vstack([chains[0], path[1:-1], chains[0][:1]])
            else:
                chains[0] = np.vstack([chains.pop(), path[1:-1], chains[0]])
    return chains


def closed_loops(region: CrossSection) -> list:
    return [np.vstack([loop, loop[:1]]) for loop in rg.loops(region)]


def inner_point(piece: CrossSection) -> np.ndarray:
    """The origin when it is inside the piece, else a point well inside it."""
    for candidate in (np.zeros(2), np.array(rg.centroid(piece))):
        if rg.contains_points(piece, candidate[None, :])[0]:
            return candidate
    y, intervals = rg.raster_rows(piece, 1e9)[0]
    x0, x1 = max(intervals, key=lambda iv: iv[1] - iv[0])
    return np.array([(x0 + x1) / 2, y])
