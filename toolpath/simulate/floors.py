"""Where upright tools have cleared the stock to the top (the manifold engine's 2-D footprints,
see sweep.py): a level run's path offset by the tool radius, and the union of such footprints
below a height."""
from __future__ import annotations

import bisect

import numpy as np
from manifold3d import CrossSection, FillRule, JoinType, Manifold, OpType

from .facets import polygon_sides, tool_rings


class Floors:
    """Where upright tools have cleared everything: above the height where a tool's end meets its
    shank, over the footprint of each level run (its path offset by the tool radius).  A piece of
    a run higher up that lies wholly inside such a footprint adds nothing to the cut (the deeper
    run is always cut itself, so leaving the piece out keeps the union the same); in a pocket
    with many layers that is most of every layer but the deepest."""

    def __init__(self, levels: list, tolerance: float):
        """``levels``: (tool, points) of every level run of an upright tool, which is cut."""
        floors = []
        for tool, run in levels:
            floors.append((float(run[0, 2]) + tool_rings(tool, tolerance)[-1][1], run[:, :2], tool.radius))
        floors.sort(key=lambda floor: floor[0])
        self.heights = [height for height, _, _ in floors]
        self.footprints = [(path, radius) for _, path, radius in floors]
        self.tolerance = tolerance
        self.cleared = [CrossSection()]      # cleared[k]: the union of the k lowest footprints
        self.shapes = {}                     # k: the k-th lowest footprint
        self.unions = {}                     # footprints' indices: their union
        self.boxes = np.array([[*(path.min(axis=0) - radius), *(path.max(axis=0) + radius)]
                               for path, radius in self.footprints]).reshape(-1, 4)

    def shape(self, k: int) -> CrossSection:
        """The footprint of the k-th lowest level run."""
        if k not in self.shapes:
            path, radius = self.footprints[k]
            self.shapes[k] = footprint(path, radius, self.tolerance)
        return self.shapes[k]

    def below(self, z: float) -> CrossSection:
        """The area cleared all the way down to ``z`` by runs below it."""
        k = bisect.bisect_right(self.heights, z - 1e-9)   # strictly deeper: a run never clears itself
        while len(self.cleared) <= k:
            self.cleared.append(self.cleared[-1] + self.shape(len(self.cleared) - 1))
        return self.cleared[k]

    def needed(self, run: np.ndarray, radius: float) -> list:
        """(first, last) vertex ranges of the run that are not wholly inside cleared area."""
        whole = [(0, len(run) - 1)]
        cleared = self.below(float(run[:, 2].min()))
        if cleared.is_empty():
            return whole
        core = cleared.offset(-radius, JoinType.Round)
        if core.is_empty():
            return whole
        inside = inside_polygons(run[:, :2], core.to_polygons())
        keep = ~(inside[:-1] & inside[1:])      # per move
        edges = np.flatnonzero(np.diff(np.concatenate([[1], keep.astype(np.int8), [1]])))
        for a, b in zip(edges[::2], edges[1::2]):
            # moves a..b-1 have both ends in the core; the footprint decides
            rest = footprint(run[a:b + 1, :2], radius + self.tolerance / 4, self.tolerance / 8) - cleared
            if rest.area() > 1e-6:
                keep[a:b] = True
        edges = np.flatnonzero(np.diff(np.concatenate([[0], keep.astype(np.int8), [0]])))
        return [(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2])]

    def holds(self, points: np.ndarray, radius: float) -> bool:
        """Whether a hull of the tool at ``points`` (a plunge, ramp or link between runs: its
        shape seen from above is the convex hull of the points widened by ``radius``) lies wholly
        in what deeper level runs have cleared: that outline, widened as :meth:`needed` widens a
        run's footprint, inside the area cleared down to the lowest point (only the footprints
        whose bounds meet the outline's are unioned)."""
        k = bisect.bisect_right(self.heights, float(points[:, 2].min()) - 1e-9)
        wide = radius + self.tolerance / 4
        lo, hi = points[:, :2].min(axis=0) - wide, points[:, :2].max(axis=0) + wide
        boxes = self.boxes[:k]
        near = np.flatnonzero((boxes[:, 0] < hi[0]) & (boxes[:, 2] > lo[0]) & (boxes[:, 1] < hi[1]) & (boxes[:, 3] > lo[1]))
        if not len(near):
            return False
        key = tuple(near.tolist())
        if key not in self.unions:
            self.unions[key] = CrossSection.batch_boolean([self.shape(int(i)) for i in near], OpType.Add)
        cleared = self.unions[key]
        n = polygon_sides(wide, self.tolerance / 8)
        around = np.arange(n) * (2 * np.pi / n)
        circle = wide * np.column_stack([np.cos(around), np.sin(around)])
        outline = CrossSection.hull_points((points[:, None, :2] + circle[None]).reshape(-1, 2))
        return (outline - cleared).area() <= 1e-6


class Shanks:
    """The sweep of the shank (a cylinder of the tool's radius from where its end meets it up to
    above the stock) along level runs: exactly the run's footprint, from that height up.  Those
    starting at one height are merged in 2-D (cheap) and become one prism each."""

    def __init__(self, tolerance: float):
        self.tolerance = tolerance
        self.footprints = {}

    def add(self, run: np.ndarray, radius: float, bottom: float) -> None:
        """The shank of radius ``radius`` from height ``bottom`` up, along the level run (its points, (n, 2+))."""
        self.footprints.setdefault(round(bottom, 9), []).append((run[:, :2], radius))

    def pieces(self, top: float) -> list:
        """Functions building one prism per height, reaching 1 mm above ``top`` and more (each
        its own amount: many tops in one plane make the union slow)."""
        def prism(bottom, parts):
            area = CrossSection.batch_boolean([footprint(path, radius, self.tolerance / 4) for path, radius in parts],
                                              OpType.Add)
            lift = 0.05 + 0.45 * ((bottom * 0.3819660113) % 1.0)
            return Manifold.extrude(area, top + 1.0 + lift - bottom).translate([0.0, 0.0, bottom])
        return [lambda bottom=bottom, parts=parts: prism(bottom, parts) for bottom, parts in self.footprints.items()]


def footprint(path: np.ndarray, radius: float, tolerance: float) -> CrossSection:
    """The 2-D polyline offset by ``radius`` (round ends and joins; facets inside the circle
    within ``tolerance``): a ribbon 1e-4 mm wide on each side, one polygon per stretch without a
    turn over 90 degrees so its sides cannot fold, offset by the rest of the radius."""
    thin = 1e-4
    d = np.diff(path, axis=0)
    t = d / np.linalg.norm(d, axis=1)[:, None]
    folds = np.flatnonzero(np.einsum("ij,ij->i", t[:-1], t[1:]) <= 0.0) + 1
    ribbons = []
    for a, b in zip(np.concatenate([[0], folds]), np.concatenate([folds, [len(path) - 1]])):
        along = np.vstack([t[a:a + 1], t[a:b - 1] + t[a + 1:b], t[b - 1:b]])
        across = np.column_stack([-along[:, 1], along[:, 0]])
        across *= thin / np.maximum(np.linalg.norm(across, axis=1), 1e-12)[:, None]
        ribbons.append(np.vstack([path[a:b + 1] + across, (path[a:b + 1] - across)[::-1]]))
    segments = polygon_sides(radius, tolerance)
    return CrossSection(ribbons, FillRule.NonZero).offset(radius - thin, JoinType.Round, 2.0, segments)


def inside_polygons(points: np.ndarray, polygons: list) -> np.ndarray:
    """Which points lie inside the polygons (even-odd over all their edges)."""
    inside = np.zeros(len(points), bool)
    x, y = points[:, 0, None], points[:, 1, None]
    for polygon in polygons:
        a = np.asarray(polygon, float)
        b = np.roll(a, -1, axis=0)
        for s in range(0, len(a), 2048):
            ax, ay, bx, by = a[s:s + 2048, 0], a[s:s + 2048, 1], b[s:s + 2048, 0], b[s:s + 2048, 1]
            straddles = (ay > y) != (by > y)
            cross_x = ax + (y - ay) * (bx - ax) / np.where(by != ay, by - ay, 1.0)
            inside ^= (np.count_nonzero(straddles & (x < cross_x), axis=1) % 2).astype(bool)
    return inside
