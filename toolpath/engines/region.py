"""2-D regions on ``manifold3d.CrossSection``: build, offset, clip, raster-fill, contour rings.

A region is a CrossSection (Clipper2 inside).  Loops coming from the scene are validated
here, once, so the workflows can trust what they get.  Outer boundaries of the loops that
CrossSection returns run counter-clockwise, holes clockwise.
"""
from __future__ import annotations

import math

import numpy as np
from manifold3d import CrossSection, FillRule, JoinType

from ..ir.errors import InputError

# Round joins: chord error of an offset arc stays below this (mm).
ARC_TOLERANCE = 0.01
# A raster fill with more rows than this is a mistake (a stepover in metres, or 1e-9), not a job.
MAX_ROWS = 100_000
# Pieces of a region smaller than this (mm^2) are numerical dust, not islands.
MIN_AREA = 0.01


class RegionError(InputError):
    """Bad 2-D input: open or degenerate outlines, NaN, empty regions."""


def validate_loop(loop, what: str) -> np.ndarray:
    """Return a clean (k, 2) float array of a closed loop, or raise RegionError naming ``what``."""
    pts = np.asarray(loop, dtype=float)
    if pts.ndim != 2 or pts.shape[1] < 2:
        raise RegionError(f"{what}: an outline must be a list of (x, y) points")
    pts = pts[:, :2]
    if not np.all(np.isfinite(pts)):
        raise RegionError(f"{what}: outline has a non-finite coordinate (NaN or infinity)")
    if len(pts) > 1 and np.allclose(pts[0], pts[-1]):
        pts = pts[:-1]
    keep = np.ones(len(pts), bool)
    keep[1:] = np.any(np.abs(np.diff(pts, axis=0)) > 1e-9, axis=1)
    pts = pts[keep]
    if len(pts) < 3:
        raise RegionError(f"{what}: outline has fewer than 3 distinct points")
    if abs(signed_area(pts)) < 1e-9:
        raise RegionError(f"{what}: outline encloses no area")
    return pts


def signed_area(loop: np.ndarray) -> float:
    x, y = loop[:, 0], loop[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def from_loops(loops, what: str = "outline") -> CrossSection:
    """Region bounded by closed loops, even-odd: a loop inside another is a hole (glyph counters)."""
    clean = [validate_loop(loop, what) for loop in loops]
    if not clean:
        raise RegionError(f"{what}: no closed outline")
    return CrossSection(clean, FillRule.EvenOdd)


def union_of_faces(faces, what: str = "faces") -> CrossSection:
    """The region covered by planar faces (either winding); slivers of no area are ignored."""
    polygons = []
    for face in faces:
        pts = np.asarray(face, dtype=float)[:, :2]
        if len(pts) >= 3 and np.all(np.isfinite(pts)) and abs(signed_area(pts)) > 1e-12:
            # each face counter-clockwise: a closed mesh's bottom faces, clockwise from above, would
            # otherwise cancel its top faces under the non-zero rule
            polygons.append(pts if signed_area(pts) > 0 else pts[::-1])
    if not polygons:
        raise RegionError(f"{what}: no faces with an area when seen from above")
    return CrossSection(polygons, FillRule.NonZero)


def rectangle(x0: float, y0: float, x1: float, y1: float) -> CrossSection:
    return CrossSection([np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], float)])


def circle_segments(radius: float, tolerance: float = ARC_TOLERANCE) -> int:
    """Segments for a full circle so the chord error is at most ``tolerance``."""
    r = abs(radius)
    if r <= tolerance:
        return 8
    n = math.pi / math.acos(1 - tolerance / r)
    return int(min(max(8, math.ceil(n)), 720))


def offset(region: CrossSection, delta: float) -> CrossSection:
    """Grow (delta > 0) or shrink (delta < 0) with round joins, within ARC_TOLERANCE."""
    if delta == 0:
        return region
    return region.offset(delta, JoinType.Round, 2.0, circle_segments(delta))


def loops(region: CrossSection) -> list:
    """The boundary loops as (k, 2) arrays (outer CCW, holes CW)."""
    return [np.asarray(p, dtype=float) for p in region.to_polygons() if len(p) >= 3]


def area(region: CrossSection) -> float:
    return float(region.area())


def components(region: CrossSection, min_area: float = MIN_AREA) -> list:
    """Connected pieces (each with its holes), dust dropped, largest first."""
    parts = [p for p in region.decompose() if p.area() >= min_area]
    return sorted(parts, key=lambda p: -p.area())


def centroid(region: CrossSection) -> tuple:
    total, cx, cy = 0.0, 0.0, 0.0
    for loop in loops(region):
        x, y = loop[:, 0], loop[:, 1]
        xn, yn = np.roll(x, -1), np.roll(y, -1)
        cross = x * yn - xn * y
        total += cross.sum() / 2
        cx += ((x + xn) * cross).sum() / 6
        cy += ((y + yn) * cross).sum() / 6
    if abs(total) < 1e-12:
        (x0, y0), (x1, y1) = region.bounds()[:2], region.bounds()[2:]
        return ((x0 + x1) / 2, (y0 + y1) / 2)
    return (cx / total, cy / total)


def is_inside(inner: CrossSection, outer: CrossSection, tolerance_area: float = MIN_AREA) -> bool:
    return (inner - outer).area() <= tolerance_area


def _edges(region: CrossSection) -> np.ndarray:
    """All boundary edges as (m, 4) rows x0, y0, x1, y1."""
    rows = []
    for loop in loops(region):
        nxt = np.roll(loop, -1, axis=0)
        rows.append(np.hstack([loop, nxt]))
    return np.vstack(rows) if rows else np.empty((0, 4))


def contains_points(region: CrossSection, points: np.ndarray) -> np.ndarray:
    """Even-odd point-in-region test for (n, 2) points."""
    points = np.asarray(points, float).reshape(-1, 2)
    px, py = points[:, 0], points[:, 1]
    # Sweep: each edge only meets the points whose y lies in its span (found by binary search
    # in the points sorted by y), so the work is the crossings, not points x edges.
    order = np.argsort(py, kind="stable")
    ys = py[order]
    edges = _edges(region)
    edges = edges[edges[:, 1] != edges[:, 3]]
    x0, y0, x1, y1 = edges.T
    first = np.searchsorted(ys, np.minimum(y0, y1), "left")
    count = np.searchsorted(ys, np.maximum(y0, y1), "left") - first
    # Every (edge, point) pair with the point in the edge's span, as two flat index arrays.
    edge = np.repeat(np.arange(len(edges)), count)
    offset = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    point = order[np.repeat(first, count) + offset]
    xi = x0[edge] + (py[point] - y0[edge]) * (x1[edge] - x0[edge]) / (y1[edge] - y0[edge])
    crossings = np.bincount(point, weights=px[point] < xi, minlength=len(points))
    return crossings.astype(np.int64) % 2 == 1


def grid_inside(region: CrossSection, xs: np.ndarray, ys: np.ndarray, rows_per_block: int = 256) -> np.ndarray:
    """:func:`contains_points` of every grid point (xs[i], ys[j]) as a (len(xs), len(ys)) bool
    array, by scan lines: each edge meets only the rows in its span, and a crossing at x turns
    the parity of every point left of it; so the work is the crossings plus one pass over the
    grid, and no array of points is made.  ``xs`` and ``ys`` must be ascending.  The same rule
    and the same arithmetic as :func:`contains_points` (a point exactly on an edge falls the
    same way), which the tests check point for point."""
    xs = np.asarray(xs, float).reshape(-1)
    ys = np.asarray(ys, float).reshape(-1)
    inside = np.zeros((len(xs), len(ys)), bool)
    edges = _edges(region)
    edges = edges[edges[:, 1] != edges[:, 3]]
    if not len(edges) or not len(xs) or not len(ys):
        return inside
    x0, y0, x1, y1 = edges.T
    first = np.searchsorted(ys, np.minimum(y0, y1), "left")
    last = np.searchsorted(ys, np.maximum(y0, y1), "left")
    for start in range(0, len(ys), rows_per_block):
        stop = min(start + rows_per_block, len(ys))
        lo, hi = np.maximum(first, start), np.minimum(last, stop)
        count = np.maximum(hi - lo, 0)
        if not count.any():
            continue
        edge = np.repeat(np.arange(len(edges)), count)
        row = np.repeat(lo, count) + np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
        xi = x0[edge] + (ys[row] - y0[edge]) * (x1[edge] - x0[edge]) / (y1[edge] - y0[edge])
        # points 0..k-1 of the row lie left of the crossing (xs < xi): their parity turns
        k = np.searchsorted(xs, xi, "left")
        toggles = np.zeros((stop - start, len(xs) + 1), np.uint8)
        np.add.at(toggles, (row - start, k), 1)
        parity = np.bitwise_xor.accumulate(toggles[:, ::-1] & 1, axis=1)[:, ::-1]
        inside[:, start:stop] = parity[:, 1:].T.astype(bool)
    return inside


def _rotation(angle_deg: float) -> np.ndarray:
    a = math.radians(angle_deg)
    return np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])


def raster_rows(region: CrossSection, stepover: float) -> list:
    """Scan the region with lines parallel to X.

    Rows are spread evenly over the region's height, at most ``stepover`` apart, the first and
    last just inside the bottom and top so a thin piece is never missed.  Returns
    ``[(y, [(x_start, x_end), ...]), ...]`` with intervals sorted along X.
    """
    if not (np.isfinite(stepover) and stepover > 0):
        raise RegionError(f"stepover must be a positive number, got {stepover}")
    edges = _edges(region)
    if not len(edges):
        return []
    y_lo, y_hi = edges[:, [1, 3]].min(), edges[:, [1, 3]].max()
    height = y_hi - y_lo
    inset = min(0.01, height / 4)
    span = height - 2 * inset
    count = max(1, math.ceil(span / stepover - 1e-9) + 1) if span > 0 else 1
    if count > MAX_ROWS:
        raise RegionError(f"{count} raster rows ({height:.1f} mm at a {stepover:g} mm stepover): more than {MAX_ROWS}")
    ys = np.linspace(y_lo + inset, y_hi - inset, count) if count > 1 else np.array([(y_lo + y_hi) / 2])
    x0, y0, x1, y1 = edges.T
    rows = []
    for y in ys:
        crosses = (y0 > y) != (y1 > y)
        xi = np.sort(x0[crosses] + (y - y0[crosses]) * (x1[crosses] - x0[crosses]) / (y1[crosses] - y0[crosses]))
        intervals = [(xi[k], xi[k + 1]) for k in range(0, len(xi) - 1, 2) if xi[k + 1] - xi[k] > 1e-6]
        if intervals:
            rows.append((float(y), intervals))
    return rows


def _crosses_boundary(a: np.ndarray, b: np.ndarray, edges: np.ndarray, eps: float = 1e-6) -> bool:
    """True when segment a-b properly crosses a boundary edge (touching at a or b does not count)."""
    d = b - a
    e0, e1 = edges[:, :2], edges[:, 2:]
    f = e1 - e0
    denom = d[0] * f[:, 1] - d[1] * f[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = ((e0[:, 0] - a[0]) * f[:, 1] - (e0[:, 1] - a[1]) * f[:, 0]) / denom
        u = ((e0[:, 0] - a[0]) * d[1] - (e0[:, 1] - a[1]) * d[0]) / denom
    hit = (np.abs(denom) > 1e-12) & (t > eps) & (t < 1 - eps) & (u > eps) & (u < 1 - eps)
    return bool(hit.any())


def zigzag(region: CrossSection, stepover: float, angle_deg: float = 0.0) -> list:
    """Zigzag (bidirectional raster) fill of ``region`` for a tool centre.

    Raster lines run at ``angle_deg`` from +X, ``stepover`` apart.  Each connected piece of
    the region is filled on its own; within a piece, a row links to the overlapping row
    above it by a short straight move when that move stays inside the region, otherwise a
    new chain starts.  Returns a list of chains, each an (k, 2) array of points to visit
    with the tool down.
    """
    rot = _rotation(angle_deg)
    chains = []
    for piece in components(region):
        local = piece.transform(np.hstack([rot.T, np.zeros((2, 1))])) if angle_deg else piece
        edges = _edges(local)
        rows = raster_rows(local, stepover)
        visited = [[False] * len(iv) for _, iv in rows]
        for first_row in range(len(rows)):
            for first_seg in range(len(rows[first_row][1])):
                if visited[first_row][first_seg]:
                    continue
                chain = []
                row, seg, forward = first_row, first_seg, True
                while True:
                    visited[row][seg] = True
                    y = rows[row][0]
                    xa, xb = rows[row][1][seg]
                    start, end = ((xa, y), (xb, y)) if forward else ((xb, y), (xa, y))
                    chain += [start, end]
                    nxt = _next_segment(rows, visited, row, (xa, xb), forward, np.array(end), edges)
                    if nxt is None:
                        break
                    row, seg = nxt
                    forward = not forward
                pts = np.array(chain, float)
                chains.append(pts @ rot.T if angle_deg else pts)
    return chains


def _next_segment(rows, visited, row, interval, going_right, end, edges):
    """The unvisited overlapping interval of the next row to link to, entered at the end on
    the side this row finished (the zigzag turns back), or None."""
    if row + 1 >= len(rows):
        return None
    y_next, intervals = rows[row + 1]
    best = None
    for k, (xa, xb) in enumerate(intervals):
        if visited[row + 1][k] or xb < interval[0] or xa > interval[1]:
            continue
        entry = np.array([xb if going_right else xa, y_next])
        if _crosses_boundary(end, entry, edges):
            continue
        dist = abs(entry[0] - end[0])
        if best is None or dist < best[0]:
            best = (dist, k)
    return None if best is None else (row + 1, best[1])


def contour_rings(base: CrossSection, distances, clip: CrossSection | None = None) -> list:
    """Tool-centre loops at each distance outside ``base`` (negative: inside), in the given order.

    Returns ``[(distance, loop), ...]``; a loop is a closed (k, 2) array whose last point repeats
    the first.  With ``clip``, loops are cut to the parts inside ``clip`` (then they may be open).
    """
    rings = []
    for d in distances:
        grown = offset(base, d)
        inside = clip is None or is_inside(grown, clip, tolerance_area=1e-9)
        for loop in loops(grown):
            closed = np.vstack([loop, loop[:1]])
            if inside:
                rings.append((d, closed))
            else:
                rings += [(d, piece) for piece in clip_polyline(closed, clip)]
    return rings


def clip_polyline(points: np.ndarray, region: CrossSection) -> list:
    """Parts of a polyline that lie inside ``region``, as a list of (k, 2) arrays.

    The polyline is split at every boundary crossing; a piece between two splits is kept when
    its midpoint is inside.  A closed loop cut open is re-joined across its start point.
    """
    points = np.asarray(points, float)
    edges = _edges(region)
    starts, vectors = points[:-1], np.diff(points, axis=0)
    params = [np.arange(len(points), dtype=float)]
    e0, f = edges[:, :2], edges[:, 2:] - edges[:, :2]
    for first in range(0, len(starts), 1024):
        a, d = starts[first:first + 1024, None, :], vectors[first:first + 1024, None, :]
        denom = d[..., 0] * f[None, :, 1] - d[..., 1] * f[None, :, 0]
        rel = e0[None, :, :] - a
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (rel[..., 0] * f[None, :, 1] - rel[..., 1] * f[None, :, 0]) / denom
            u = (rel[..., 0] * d[..., 1] - rel[..., 1] * d[..., 0]) / denom
        hit = (np.abs(denom) > 1e-15) & (t > 0) & (t < 1) & (u >= 0) & (u <= 1)
        rows, cols = np.nonzero(hit)
        params.append(first + rows + t[rows, cols])
    u = np.unique(np.concatenate(params))
    segment = np.minimum(np.floor(u).astype(int), len(starts) - 1)
    refined = starts[segment] + vectors[segment] * (u - segment)[:, None]
    keep = contains_points(region, (refined[:-1] + refined[1:]) / 2)
    pieces = []
    run_start = None
    for index, inside in enumerate(np.append(keep, False)):
        if inside and run_start is None:
            run_start = index
        elif not inside and run_start is not None:
            pieces.append(refined[run_start:index + 1])
            run_start = None
    closed = np.allclose(points[0], points[-1])
    if closed and len(pieces) > 1 and keep[0] and keep[-1]:
        pieces[0] = np.vstack([pieces.pop()[:-1], pieces[0]])
    return [p for p in pieces if len(p) >= 2]


def order_loops_nearest(items: list, start_xy, key=lambda item: item) -> list:
    """Greedy nearest-neighbour order of closed loops; each loop is rotated to start nearest."""
    remaining = list(items)
    here = np.asarray(start_xy, float)
    ordered = []
    while remaining:
        best = None
        for k, item in enumerate(remaining):
            pts = key(item)
            d = np.linalg.norm(pts[:, :2] - here, axis=1)
            j = int(np.argmin(d))
            if best is None or d[j] < best[0]:
                best = (d[j], k, j)
        _, k, j = best
        item = remaining.pop(k)
        ordered.append((item, j))
        here = key(item)[j, :2]
    return ordered


def rotate_closed(loop: np.ndarray, start_index: int) -> np.ndarray:
    """A closed loop (last == first) re-started at ``start_index``."""
    body = loop[:-1]
    body = np.roll(body, -start_index, axis=0)
    return np.vstack([body, body[:1]])
