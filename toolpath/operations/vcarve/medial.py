"""The medial axis of a region: where the centres of its largest inscribed circles lie, with
their radii, from the Voronoi diagram of the outline's segments.

The diagram comes from Boost.Polygon's Voronoi builder (through pyvoronoi, the library FreeCAD's
V-carve uses): it is exact on integer input, robust on thousands of segments with touching and
near-degenerate contours.  Coordinates are therefore snapped to a grid of 1/SCALE mm (0.1 um;
int32 holds +-214 m at that scale) before the diagram is built.  Segments that cross would make
the builder's output corrupt, so the region is first shrunk by SEPARATION (0.15 um, round joins):
contours that touch (a counter meeting its letter's outline at a point) or nearly touch then
stand apart by more than the snap can close (it moves a point 0.07 um at most), and slivers
thinner than that vanish.  (pyvoronoi's own GetIntersectingSegments is not used: in 1.2.8 it
reports segments of a plain rectangle that do not cross.)

Of the diagram only the *primary* finite edges whose middle lies inside the region are kept: the
edges between two outline segments (straight), between a segment and a reflex vertex (a parabola,
sampled here so that neither its points nor the radius between samples stray more than the
tolerance from the curve: a chord of length L on a parabola of focal distance h strays at most
L^2 / (8 h)), and between two reflex vertices (straight, the radius along it sampled the same
way).  The radius at every point is its distance to the sites of its edge (computed here, not
taken from the builder), so each point's inscribed circle touches the outline: a V-bit whose tip
runs at depth radius / tan(angle / 2) below the top cuts walls that meet the outline.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...engines import region as rg
from ...ir.errors import InputError

SCALE = 10000           # integer units per mm for Boost.Polygon (0.1 um)
SEPARATION = 1.5 / SCALE    # mm the region is shrunk by before the snap (see the module notes)
MAX_COORDINATE = 2.0e5  # mm: 200 m; int32 at SCALE holds 214 m
MAX_SAMPLES = 400       # per edge (a parabola 40 mm long at 0.1 mm steps)
MAX_SEGMENTS = 2_000_000


class MedialError(InputError):
    """A region whose medial axis cannot be built; the message says where."""


@dataclass
class MedialAxis:
    """The kept edges: ``nodes`` (k, 2) their end points (Voronoi vertices), ``ends`` (m, 2) node
    indices of each edge, ``paths`` m (j, 2) point arrays from end to end and ``radii`` m (j,)
    arrays of the inscribed circle's radius at each point."""

    nodes: np.ndarray
    ends: np.ndarray
    paths: list
    radii: list

    def max_radius(self) -> float:
        return max((float(r.max()) for r in self.radii), default=0.0)


def snapped_segments(region, what: str) -> np.ndarray:
    """The outline's edges (n, 2, 2) snapped to the 1/SCALE mm grid, zero-length ones dropped."""
    segments = []
    for loop in rg.loops(region.offset(-SEPARATION, rg.JoinType.Round, 2.0, 8)):
        points = np.round(np.asarray(loop, float) * SCALE) / SCALE
        if not np.all(np.isfinite(points)) or np.abs(points).max() > MAX_COORDINATE:
            raise MedialError(f"{what}: the outline reaches beyond {MAX_COORDINATE / 1000:g} m from the origin")
        keep = np.any(points != np.roll(points, 1, axis=0), axis=1)
        points = points[keep]
        if len(points) < 3:
            continue
        segments.append(np.stack([points, np.roll(points, -1, axis=0)], axis=1))
    if not segments:
        raise MedialError(f"{what}: the region has no outline")
    found = np.concatenate(segments)
    if len(found) > MAX_SEGMENTS:
        raise MedialError(f"{what}: the outline has {len(found)} segments, more than {MAX_SEGMENTS}")
    return found


def _point_distance(points, site):
    return np.hypot(points[:, 0] - site[0], points[:, 1] - site[1])


def _segment_distance(points, a, b):
    span = b - a
    length2 = float(span @ span)
    t = np.clip(((points - a) @ span) / length2, 0.0, 1.0) if length2 > 0 else np.zeros(len(points))
    foot = a + t[:, None] * span
    return np.hypot(points[:, 0] - foot[:, 0], points[:, 1] - foot[:, 1])


def _samples(count: int) -> np.ndarray:
    return np.linspace(0.0, 1.0, count + 1)


def _parabola(focus, a, b, start, end, tolerance):
    """Points from ``start`` to ``end`` on the parabola of ``focus`` and the line a-b."""
    u = (b - a) / np.hypot(*(b - a))
    normal = np.array([-u[1], u[0]])
    h = float((focus - a) @ normal)
    if h < 0:
        normal, h = -normal, -h
    if h < 1e-9:
        return None
    sp = float((focus - a) @ u)
    s0, s1 = float((start - a) @ u), float((end - a) @ u)
    step = math.sqrt(8.0 * h * tolerance)
    count = min(MAX_SAMPLES, max(1, math.ceil(abs(s1 - s0) / step)))
    s = s0 + (s1 - s0) * _samples(count)
    t = ((s - sp) ** 2 + h * h) / (2 * h)
    points = a + s[:, None] * u + t[:, None] * normal
    points[0], points[-1] = start, end
    return points


def medial_axis(region, tolerance: float = 0.01, what: str = "region") -> MedialAxis:
    """The medial axis of ``region`` (a CrossSection), curves sampled within ``tolerance`` mm."""
    try:
        import pyvoronoi        # here, not at the top: the job model loads every kind, V-carve or not
    except ImportError:
        raise MedialError(f"{what}: V-carving needs pyvoronoi (Boost.Polygon's Voronoi), which is not installed "
                          "for this Blender (no wheel for this platform)") from None
    segments = snapped_segments(region, what)
    builder = pyvoronoi.Pyvoronoi(SCALE)
    for segment in segments:
        builder.AddSegment(segment.tolist())
    builder.Construct()
    vertices = np.array([(v.X, v.Y) for v in builder.GetVertices()], float).reshape(-1, 2)
    cells = builder.GetCells()
    sites = []
    for cell in cells:
        if cell.contains_point:
            sites.append((0, segments[cell.site][0 if cell.source_category == 1 else 1], None))
        else:
            sites.append((1, segments[cell.site][0], segments[cell.site][1]))
    chosen, paths = [], []
    edges = builder.GetEdges()
    for index, edge in enumerate(edges):
        if not edge.is_primary or edge.start < 0 or edge.end < 0 or edge.twin < index:
            continue
        start, end = vertices[edge.start], vertices[edge.end]
        one, other = sites[edge.cell], sites[edges[edge.twin].cell]
        path = None
        if one[0] + other[0] == 1:          # a point and a segment: a parabola (or a line through the point)
            point, segment = (one, other) if one[0] == 0 else (other, one)
            path = _parabola(point[1], segment[1], segment[2], start, end, tolerance)
        elif one[0] == 0 and other[0] == 0:     # two points: the radius along the line is a hyperbola
            h = float(np.hypot(*(one[1] - other[1]))) / 2
            length = float(np.hypot(*(end - start)))
            count = min(MAX_SAMPLES, max(1, math.ceil(length / math.sqrt(8.0 * max(h, 1e-9) * tolerance))))
            path = start + _samples(count)[:, None] * (end - start)
        if path is None:
            path = np.array([start, end])
        chosen.append((edge.start, edge.end, one))
        paths.append(path)
    if not paths:
        raise MedialError(f"{what}: the region has no medial axis (no area?)")
    middles = np.array([p[len(p) // 2] if len(p) > 2 else (p[0] + p[-1]) / 2 for p in paths])
    inside = rg.contains_points(region, middles)
    kept_paths, kept_radii, ends = [], [], []
    for keep, path, (a, b, site) in zip(inside, paths, chosen):
        if not keep:
            continue
        radii = _point_distance(path, site[1]) if site[0] == 0 else _segment_distance(path, site[1], site[2])
        kept_paths.append(path)
        kept_radii.append(radii)
        ends.append((a, b))
    if not kept_paths:
        raise MedialError(f"{what}: no part of the medial axis lies inside the region")
    return MedialAxis(vertices, np.array(ends, np.int64).reshape(-1, 2), kept_paths, kept_radii)
