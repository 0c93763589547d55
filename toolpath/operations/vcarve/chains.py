"""The medial axis cut into the V-bit's paths: pieces split where the radius crosses a limit,
joined end to end into chains, and the chains ordered nearest first.

A piece is (points (k, 2), radii (k,)); where the radius crosses ``limit`` between two samples
the crossing point is put in (the radius is interpolated linearly between samples, which the
medial axis's sampling keeps within its tolerance of the true radius).
"""
from __future__ import annotations

import numpy as np

KEY = 1e-6          # mm: end points closer than this are one node


def split_at(points: np.ndarray, radii: np.ndarray, limit: float) -> tuple:
    """(below, above): the pieces of the path with radius <= limit and > limit."""
    below, above = [], []
    inside = radii <= limit
    if inside.all():
        return [(points, radii)], []
    if not inside.any():
        return [], [(points, radii)]
    # insert the crossing points
    new_points, new_radii, flags = [points[0]], [radii[0]], [inside[0]]
    for i in range(1, len(points)):
        if inside[i] != inside[i - 1]:
            t = (limit - radii[i - 1]) / (radii[i] - radii[i - 1])
            cross = points[i - 1] + t * (points[i] - points[i - 1])
            new_points.append(cross)
            new_radii.append(limit)
            flags.append(None)
        new_points.append(points[i])
        new_radii.append(radii[i])
        flags.append(inside[i])
    new_points, new_radii = np.array(new_points), np.array(new_radii)
    start, state = 0, flags[0]
    for i in range(1, len(flags)):
        if flags[i] is None:
            (below if state else above).append((new_points[start:i + 1], new_radii[start:i + 1]))
            start, state = i, not state
    (below if state else above).append((new_points[start:], new_radii[start:]))
    return [p for p in below if len(p[0]) > 1], [p for p in above if len(p[0]) > 1]


def _key(point) -> tuple:
    return (round(float(point[0]) / KEY), round(float(point[1]) / KEY))


def join(pieces: list) -> list:
    """Pieces joined where they share end points into chains (points, radii), each piece used
    once: a walk goes on from its end along any unused piece there, then starts again from a
    node with unused pieces, leaves first (the corners, where the radius is 0)."""
    at: dict = {}
    for index, (points, _) in enumerate(pieces):
        at.setdefault(_key(points[0]), []).append((index, False))
        at.setdefault(_key(points[-1]), []).append((index, True))
    used = np.zeros(len(pieces), bool)
    order = sorted(at, key=lambda key: (len(at[key]) != 1, key))
    chains = []
    for start in order:
        while True:
            here = start
            points, radii = [], []
            while True:
                found = next(((i, rev) for i, rev in at[here] if not used[i]), None)
                if found is None:
                    break
                index, reverse = found
                used[index] = True
                p, r = pieces[index]
                if reverse:
                    p, r = p[::-1], r[::-1]
                points.append(p if not points else p[1:])
                radii.append(r if not radii else r[1:])
                here = _key(p[-1])
            if not points:
                break
            chains.append((np.vstack(points), np.concatenate(radii)))
    return chains


def nearest_order(chains: list, start=(0.0, 0.0)) -> list:
    """Chains in the order a greedy walk visits them, each turned to start at its end nearer the
    tool (closed chains as they are)."""
    if not chains:
        return []
    firsts = np.array([c[0][0] for c in chains])
    lasts = np.array([c[0][-1] for c in chains])
    left = np.ones(len(chains), bool)
    here = np.asarray(start, float)
    ordered = []
    for _ in range(len(chains)):
        d0 = np.where(left, np.hypot(*(firsts - here).T), np.inf)
        d1 = np.where(left, np.hypot(*(lasts - here).T), np.inf)
        i0, i1 = int(np.argmin(d0)), int(np.argmin(d1))
        if d1[i1] < d0[i0]:
            points, radii = chains[i1]
            chain, index = (points[::-1], radii[::-1]), i1
        else:
            chain, index = chains[i0], i0
        left[index] = False
        ordered.append(chain)
        here = chain[0][-1]
    return ordered
