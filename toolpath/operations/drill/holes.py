"""Holes found in the model: circles among closed curves, cylindrical holes in meshes.

A closed curve is a circle when all its points lie on one circle within ``tolerance`` mm and go
round it (no gap between neighbouring points wider than ``MAX_GAP_DEG`` of arc): its centre and
diameter are the least-squares circle's (Kasa's algebraic fit: x^2 + y^2 + D x + E y + F = 0
solved for D, E, F; centre (-D/2, -E/2), radius sqrt(D^2/4 + E^2/4 - F)), its radial
deviations checked afterwards against the fitted circle.

In a mesh, a cylindrical hole is a connected set of faces whose normals are horizontal (|n_z| <
``WALL_NZ``), whose vertices lie on one vertical cylinder (the circle fit of their X, Y) and whose
normals point towards its axis (material outside: a hole, not a boss).  Its depth runs from its
faces' highest to lowest Z; it is a through hole when its lowest Z is the mesh's lowest.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

MAX_GAP_DEG = 45.0
MIN_POINTS = 12
WALL_NZ = 1e-3


@dataclass(frozen=True)
class FoundHole:
    """A hole in work mm: centre, diameter, and for a mesh's its top and bottom Z and whether it
    goes through (a curve's: top and bottom None)."""

    x: float
    y: float
    diameter: float
    top: float | None = None
    bottom: float | None = None
    through: bool = False


def fit_circle(points: np.ndarray):
    """(cx, cy, r) of the least-squares circle through (k, 2) points (Kasa's fit); None if degenerate."""
    p = np.asarray(points, float)
    shift = p.mean(axis=0)
    q = p - shift
    a = np.column_stack([q[:, 0], q[:, 1], np.ones(len(q))])
    b = -(q ** 2).sum(axis=1)
    solution, _, rank, _ = np.linalg.lstsq(a, b, rcond=None)
    if rank < 3:
        return None
    d, e, f = solution
    r2 = d * d / 4 + e * e / 4 - f
    if not r2 > 0:
        return None
    return float(shift[0] - d / 2), float(shift[1] - e / 2), float(np.sqrt(r2))


def goes_round(points: np.ndarray, cx: float, cy: float) -> bool:
    angles = np.sort(np.arctan2(points[:, 1] - cy, points[:, 0] - cx))
    gaps = np.diff(np.concatenate([angles, [angles[0] + 2 * np.pi]]))
    return bool(np.degrees(gaps.max()) <= MAX_GAP_DEG)


def circle_of(loop, tolerance: float = 0.01):
    """(cx, cy, diameter) when the closed curve ``loop`` (k, 2) is a circle, else None."""
    p = np.asarray(loop, float).reshape(-1, 2)
    if len(p) > 1 and np.allclose(p[0], p[-1]):
        p = p[:-1]
    if len(p) < MIN_POINTS or not np.isfinite(p).all():
        return None
    fit = fit_circle(p)
    if fit is None:
        return None
    cx, cy, r = fit
    if np.abs(np.hypot(p[:, 0] - cx, p[:, 1] - cy) - r).max() > tolerance or not goes_round(p, cx, cy):
        return None
    return cx, cy, 2 * r


def circles_in_curves(loops, tolerance: float = 0.01) -> list:
    """The :class:`FoundHole` of every closed curve among ``loops`` that is a circle, in their order."""
    found = []
    for loop in loops:
        circle = circle_of(loop, tolerance)
        if circle is not None:
            found.append(FoundHole(*circle))
    return found


def components(faces: np.ndarray, count: int) -> np.ndarray:
    """Label of each face: faces sharing a vertex have the same label (union-find over vertices)."""
    parent = np.arange(count)

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b, c in faces:
        ra, rb, rc = root(a), root(b), root(c)
        parent[rb] = ra
        parent[root(rc)] = ra
    return np.array([root(int(face[0])) for face in faces], int)


def cylinder_holes(vertices, faces, tolerance: float = 0.01) -> list:
    """The :class:`FoundHole` of every vertical cylindrical hole in the mesh (triangles), sorted by
    centre (x, then y).  Vertices closer than a micron are one (meshes from STL are not welded)."""
    v = np.asarray(vertices, float).reshape(-1, 3)
    f = np.asarray(faces, int).reshape(-1, 3)
    if not len(f):
        return []
    _, weld, = np.unique(np.round(v / 1e-6).astype(np.int64), axis=0, return_inverse=True)[:2]
    weld = weld.reshape(-1)
    f = weld[f]
    tri = v[np.asarray(faces, int).reshape(-1, 3)]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normal, axis=1)
    ok = length > 1e-12
    unit = np.zeros_like(normal)
    unit[ok] = normal[ok] / length[ok, None]
    wall = ok & (np.abs(unit[:, 2]) < WALL_NZ)
    bottom_z = float(v[:, 2].min())
    found = []
    if not wall.any():
        return found
    walls = np.flatnonzero(wall)
    labels = components(f[walls], int(weld.max()) + 1)
    for label in np.unique(labels):
        members = walls[labels == label]
        points = tri[members].reshape(-1, 3)
        fit = fit_circle(points[:, :2])
        if fit is None:
            continue
        cx, cy, r = fit
        if np.abs(np.hypot(points[:, 0] - cx, points[:, 1] - cy) - r).max() > tolerance:
            continue
        if not goes_round(points[:, :2], cx, cy):
            continue
        middle = tri[members].mean(axis=1)
        inward = (unit[members, 0] * (cx - middle[:, 0]) + unit[members, 1] * (cy - middle[:, 1])) > 0
        if not inward.all():
            continue                      # a boss (normals outward) or a mix: not a hole
        top, low = float(points[:, 2].max()), float(points[:, 2].min())
        found.append(FoundHole(cx, cy, 2 * r, top, low, low <= bottom_z + tolerance))
    return sorted(found, key=lambda h: (round(h.x, 6), round(h.y, 6)))
