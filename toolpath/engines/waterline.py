"""Waterlines: the paths of a 3-axis tool held at one Z, touching a mesh, from the drop cutter.

The drop cutter's height field H(x, y) (:class:`~.dropcutter.DropCutter`) is the lowest tip Z
at which the tool touches the design over (x, y): it IS the tool's envelope.  The tool at tip
height z over (x, y) touches the design where H(x, y) = z, stands clear where H < z and cuts
into it where H > z.  A waterline at z is therefore the iso-line H = z, with the region H > z
(the design's side) on one hand; no offsetting of 2-D contours is involved.

:func:`contours` finds it in three steps:

1. **Marching squares** over H sampled once on a grid (the caller's, reused for every z): each
   cell whose corners lie on both sides of z gets one or two oriented segments between the
   crossed edges, the side H > z on the segment's right (the saddle resolved by the cell's mean);
   segments sharing an edge join into chains (closed loops, or open where the grid's band ends).
2. **Crossings by bisection**: a crossed edge's point is not interpolated (H jumps at a vertical
   wall: from the floor to the wall's top minus the radius, where the ball's equator meets the
   wall) but found by bisecting the edge with the drop cutter until the bracket is shorter than
   the tolerance; the point kept is the bracket's end with H <= z, so the tool there never cuts
   into the design, and it stands less than the tolerance off the envelope.
3. **Refinement**: for each segment, the crossing on the line through its midpoint across it
   (found the same way); where that is more than the tolerance from the midpoint (the chord of a
   curved envelope cuts in, or stands off), it is inserted, until no segment needs it.

Everything is in millimetres.
"""
from __future__ import annotations

import numpy as np

EPS = 1e-7                  # mm: H > z + EPS counts as the design's side (a level floor at z is not)
ROUNDS = 16                 # refinement rounds at most

# marching squares: corners c0 (i, j), c1 (i+1, j), c2 (i+1, j+1), c3 (i, j+1) counter-clockwise;
# edge k runs from corner k to corner k+1.  Going round the cell, an edge from an outside corner to
# an inside one is an entry, the other way an exit; a segment from an entry's point to an exit's
# point has the inside on its right.


def _table() -> dict:
    """(case, centre inside) -> [(entry edge, exit edge), ...]; case = sum of 2^k over inside corners."""
    table = {}
    for case in range(16):
        inside = [(case >> k) & 1 for k in range(4)]
        entries = [k for k in range(4) if not inside[k] and inside[(k + 1) % 4]]
        exits = [k for k in range(4) if inside[k] and not inside[(k + 1) % 4]]
        for centre in (False, True):
            pairs = []
            for e in entries:
                # centre outside: the exit that follows the entry going round (the inside corners
                # cut off one by one); inside: the exit before it (the inside joined, the outside
                # corners cut off).  With one entry both are the one exit.
                ring = [(e + step) % 4 for step in range(1, 4)]
                pairs.append((e, next(k for k in (ring[::-1] if centre else ring) if k in exits)))
            table[case, centre] = pairs
    return table


TABLE = _table()


def crossing(cutter, z: float, outside: np.ndarray, inside: np.ndarray, tolerance: float) -> np.ndarray:
    """Points (n, 2) on the segments from ``outside`` (H <= z) to ``inside`` (H > z) within
    ``tolerance`` of where H crosses z, each on the outside (H <= z): by bisection."""
    lo, hi = np.array(outside, float), np.array(inside, float)
    while len(lo):
        far = np.linalg.norm(hi - lo, axis=1) > tolerance
        if not far.any():
            break
        mid = 0.5 * (lo[far] + hi[far])
        up = cutter.points(mid) > z + EPS
        sub_lo, sub_hi = lo[far], hi[far]
        sub_hi[up] = mid[up]
        sub_lo[~up] = mid[~up]
        lo[far], hi[far] = sub_lo, sub_hi
    return lo


def contours(cutter, z: float, x: np.ndarray, y: np.ndarray, heights: np.ndarray, band: np.ndarray,
             tolerance: float, min_step: float = 1e-3) -> list:
    """The waterline of ``cutter`` at tip height ``z``: a list of (points (k, 2), closed) with the
    design's side on the right of travel, within the grid ``x`` (nx,) by ``y`` (ny,) whose
    drop-cutter ``heights`` (nx, ny) are known where ``band`` (nx, ny) is True."""
    nx, ny = heights.shape
    inside = band & (heights > z + EPS)
    cells = band[:-1, :-1] & band[1:, :-1] & band[1:, 1:] & band[:-1, 1:]
    corners = (inside[:-1, :-1], inside[1:, :-1], inside[1:, 1:], inside[:-1, 1:])
    case = sum(c.astype(np.int64) << k for k, c in enumerate(corners))
    live = cells & (case > 0) & (case < 15)
    ci, cj = np.nonzero(live)
    if not len(ci):
        return []
    cases = case[ci, cj]
    h = np.stack([heights[ci, cj], heights[ci + 1, cj], heights[ci + 1, cj + 1], heights[ci, cj + 1]])
    centre = np.where(np.all(np.isfinite(h), axis=0), h.mean(axis=0), -np.inf) > z + EPS
    # global edge ids: the edge (i, j)-(i+1, j) is i * ny + j; (i, j)-(i, j+1) is nx * ny + i * ny + j
    edge_ids = np.stack([ci * ny + cj, nx * ny + (ci + 1) * ny + cj, ci * ny + cj + 1, nx * ny + ci * ny + cj])
    following = {}
    for n in range(len(ci)):
        for entry, exit_ in TABLE[int(cases[n]), bool(centre[n])]:
            following[int(edge_ids[entry, n])] = int(edge_ids[exit_, n])
    ids = np.array(sorted(set(following) | set(following.values())), np.int64)
    vertical = ids >= nx * ny
    local = np.where(vertical, ids - nx * ny, ids)
    i, j = local // ny, local % ny
    a = np.column_stack([x[i], y[j]])
    b = np.column_stack([np.where(vertical, x[i], x[np.minimum(i + 1, nx - 1)]),
                         np.where(vertical, y[np.minimum(j + 1, ny - 1)], y[j])])
    a_in = inside[i, j]
    # (each crossed edge has one end inside and one outside: the segments join only such edges)
    points = crossing(cutter, z, np.where(a_in[:, None], b, a), np.where(a_in[:, None], a, b), tolerance)
    where = {int(e): k for k, e in enumerate(ids)}
    chains = _chains(following)
    found = [(points[[where[e] for e in chain]], closed) for chain, closed in chains]
    return [(_refine(cutter, z, p, closed, tolerance, min_step), closed) for p, closed in found]


def _chains(following: dict) -> list:
    """The successor map's chains: open ones from the ids nothing leads to, then the loops."""
    targets = set(following.values())
    seen, chains = set(), []
    for start in [e for e in following if e not in targets] + list(following):
        if start in seen:
            continue
        chain, e = [], start
        while e not in seen:
            seen.add(e)
            chain.append(e)
            if e not in following:
                break
            e = following[e]
        closed = e == start and len(chain) > 2
        if len(chain) >= 2:
            chains.append((chain, closed))
    return chains


def _refine(cutter, z, points, closed, tolerance, min_step) -> np.ndarray:
    """Insert, where a segment's midpoint stands more than ``tolerance`` off the iso-line across
    it, the iso-line's point there (outside)."""
    for _ in range(ROUNDS):
        ring = np.vstack([points, points[:1]]) if closed else points
        a, b = ring[:-1], ring[1:]
        d = b - a
        length = np.linalg.norm(d, axis=1)
        check = np.flatnonzero(length > 2 * min_step)
        if not len(check):
            break
        mid = 0.5 * (a[check] + b[check])
        right = np.column_stack([d[check, 1], -d[check, 0]]) / length[check, None]     # into the design
        reach = np.maximum(length[check], 4 * tolerance)
        up = cutter.points(mid) > z + EPS
        target = np.where(up[:, None], mid - reach[:, None] * right, mid + reach[:, None] * right)
        t_up = cutter.points(target) > z + EPS
        # a midpoint in the design needs an outside point beyond it; one outside, a crossing within reach
        for _ in range(4):
            stuck = up & t_up
            if not stuck.any():
                break
            reach[stuck] *= 2
            target[stuck] = mid[stuck] - reach[stuck, None] * right[stuck]
            t_up[stuck] = cutter.points(target[stuck]) > z + EPS
        usable = np.where(up, ~t_up, t_up)
        if not usable.any():
            break
        out = np.where(up[:, None], target, mid)[usable]
        into = np.where(up[:, None], mid, target)[usable]
        found = crossing(cutter, z, out, into, tolerance)
        off = np.linalg.norm(found - mid[usable], axis=1) > tolerance
        if not off.any():
            break
        where = check[usable][off]
        points = np.insert(points, where + 1, found[off], axis=0) if len(where) else points
    return points


def link_is_safe(cutter, a, b, spacing: float, tolerance: float) -> bool:
    """Whether the tool fed straight from tip ``a`` to tip ``b`` (x, y, z) stays on or above the
    drop cutter's envelope along the way (the envelope dropped along it, refined to ``tolerance``)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    span = b[:2] - a[:2]
    length = float(np.linalg.norm(span))
    if length < 1e-9:
        return bool(cutter.points(a[None, :2])[0] <= min(a[2], b[2]) + EPS)
    dropped = cutter.path(np.array([a[:2], b[:2]]), spacing, tolerance)
    t = np.clip((dropped[:, :2] - a[:2]) @ span / (length * length), 0.0, 1.0)
    return bool(np.all(a[2] + t * (b[2] - a[2]) >= dropped[:, 2] - EPS))


def cut(builder, cutter, pieces: list, reach: float, spacing: float, tolerance: float) -> int:
    """Feed along every piece (level index, z, points (k, 2), closed), each wall from its top
    level down: after a piece, the nearest piece one level lower is reached by a straight feed
    if it starts within ``reach`` and the feed stays on the envelope (:func:`link_is_safe`);
    otherwise the highest remaining level's nearest piece, by ``builder.plunge`` (retract, rapid
    over, feed down).  A closed piece starts at its point nearest the tool and ends where it
    started.  Returns the number of straight links."""
    remaining = set(range(len(pieces)))
    links = 0

    def start_of(k, here):
        level, z, points, closed = pieces[k]
        if not closed or here is None:
            return 0
        return int(np.argmin(np.linalg.norm(points - np.asarray(here[:2]), axis=1)))

    level = None
    while remaining:
        here = builder.position
        chosen = None
        if here is not None and level is not None:
            below = [k for k in remaining if pieces[k][0] == level + 1]
            options = []
            for k in below:
                first = start_of(k, here)
                gap = float(np.linalg.norm(pieces[k][2][first] - np.asarray(here[:2])))
                if gap <= reach:
                    options.append((gap, k, first))
            for gap, k, first in sorted(options):
                target = (*pieces[k][2][first], pieces[k][1])
                if link_is_safe(cutter, here, target, spacing, tolerance):
                    chosen = (k, first)
                    builder.line(*target, link=True)
                    links += 1
                    break
        if chosen is None:
            top = min(pieces[k][0] for k in remaining)
            options = sorted(k for k in remaining if pieces[k][0] == top)
            if here is not None:
                options.sort(key=lambda k: float(np.linalg.norm(pieces[k][2][start_of(k, here)] - np.asarray(here[:2]))))
            k = options[0]
            first = start_of(k, here)
            chosen = (k, first)
            builder.plunge(*pieces[k][2][first], pieces[k][1])
        k, first = chosen
        level, z, points, closed = pieces[k]
        if closed:
            points = np.vstack([np.roll(points, -first, axis=0), points[first:first + 1]])
        builder.polyline(np.column_stack([points[1:], np.full(len(points) - 1, z)]))
        remaining.discard(k)
    return links
