"""Does a closed triangle mesh pass through itself?

Two faces that do not share a vertex cross when an edge of one pierces the other (two
triangles in different planes that meet do so along a segment whose ends lie on their edges,
so one of the six edges pierces the other triangle).  Candidate pairs come from a grid of the
faces' bounding boxes (:class:`meshrays.BoxGrid`), so the time follows the number of faces, not
its square.  Faces that only touch (a vertex on a face, coplanar faces) do not count: only an
edge passing through a face makes the inside and the outside of the mesh ambiguous.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .meshrays import BoxGrid, moller_trumbore

PAIR_CHUNK = 1 << 19       # candidate pairs tested at once: bounds the memory
STRICT = 1e-9              # barycentric and segment margins: touching is not crossing


@dataclass(frozen=True)
class Crossing:
    pairs: int                   # face pairs that cross
    faces: tuple                 # the first crossing pair (face indices)
    point: tuple                 # where one of its edges pierces the other face (mesh units)


def _pierces(p, q, a, b, c, ab=None, ac=None) -> tuple[np.ndarray, np.ndarray]:
    """(k,) bool: does segment p-q pass through triangle abc (its edges included, not in its plane),
    its ends strictly off the plane, and where.  ``ab``, ``ac``: the lengths |b - a| and |c - a|
    when the caller has them."""
    d = q - p
    det, u, v, t = moller_trumbore(p, d, a, b, c)
    ab = np.linalg.norm(b - a, axis=1) if ab is None else ab
    ac = np.linalg.norm(c - a, axis=1) if ac is None else ac
    scale = np.linalg.norm(d, axis=1) * ab * ac
    with np.errstate(invalid="ignore"):
        hit = (np.abs(det) > 1e-12 * scale) & (u >= -STRICT) & (v >= -STRICT) & (u + v <= 1 + STRICT) & \
            (t > STRICT) & (t < 1 - STRICT)
    return hit, p + d * np.where(hit, t, 0.0)[:, None]


def _candidates(grid: BoxGrid):
    """Yield (a, b) arrays of face pairs (a < b) filed in a common grid cell, a chunk at a time."""
    keys, boxes = grid.keys, grid.boxes
    for gap in range(1, len(keys)):
        same = np.flatnonzero(keys[:-gap] == keys[gap:])
        if not len(same):
            return
        for start in range(0, len(same), PAIR_CHUNK):
            take = same[start:start + PAIR_CHUNK]
            yield boxes[take], boxes[take + gap]


def self_crossing(vertices, faces, progress=None) -> Crossing | None:
    """The faces of a mesh that cross each other (None if none do).  ``vertices`` (n, 3) finite,
    ``faces`` (m, 3) valid indices (checked by the caller).  ``progress``: optional callable(fraction),
    called before each chunk of candidate pairs (a cancel point: it may raise)."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    tri = v[f]
    lo, hi = tri.min(axis=1), tri.max(axis=1)
    if len(f) < 2:
        return None
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    columns = [np.ascontiguousarray(f[:, k]) for k in range(3)]
    side_ab = np.linalg.norm(tri[:, 1] - tri[:, 0], axis=1)
    side_ac = np.linalg.norm(tri[:, 2] - tri[:, 0], axis=1)
    grid = BoxGrid(lo, hi)
    seen = set()
    count, first = 0, None
    for a, b in _candidates(grid):
        if progress is not None:
            progress(0.0)
        # neighbours (a shared corner) touch, not cross
        corners_a, corners_b = [column[a] for column in columns], [column[b] for column in columns]
        shared = np.zeros(len(a), bool)
        for ca in corners_a:
            for cb in corners_b:
                shared |= ca == cb
        a, b = a[~shared], b[~shared]
        overlap = np.all((lo[a] <= hi[b]) & (lo[b] <= hi[a]), axis=1)
        a, b = a[overlap], b[overlap]
        # a pair filed in several common cells once (its first time: the same first crossing)
        _, once = np.unique(a * len(f) + b, return_index=True)
        once.sort()
        a, b = a[once], b[once]
        for _ in range(2):          # drop a face wholly on one side of the other's plane; then swap
            side = np.einsum("ikj,ij->ik", tri[b] - tri[a, :1], normal[a])
            meets = ~(np.all(side > 0, axis=1) | np.all(side < 0, axis=1))
            a, b = b[meets], a[meets]
        if not len(a):
            continue
        crossed = np.zeros(len(a), bool)
        where = np.zeros((len(a), 3))
        for one, other in ((a, b), (b, a)):
            corners = [tri[one, k] for k in range(3)]
            face = [tri[other, k] for k in range(3)] + [side_ab[other], side_ac[other]]
            for k in range(3):
                hit, point = _pierces(corners[k], corners[(k + 1) % 3], *face)
                where[hit & ~crossed] = point[hit & ~crossed]
                crossed |= hit
        if not crossed.any():
            continue
        pair_keys = a[crossed] * len(f) + b[crossed]
        fresh = ~np.isin(pair_keys, np.fromiter(seen, np.int64, len(seen))) if seen else np.ones(len(pair_keys), bool)
        unique, index = np.unique(pair_keys[fresh], return_index=True)
        seen.update(unique.tolist())
        count += len(unique)
        if first is None and len(unique):
            i = np.flatnonzero(crossed)[np.flatnonzero(fresh)[index[0]]]
            first = ((int(a[i]), int(b[i])), tuple(float(x) for x in where[i]))
    if not count:
        return None
    return Crossing(count, first[0], first[1])
