"""Plain-array mesh helpers the shell hands scene geometry to: closed loops from a wire's edges,
fan triangulation of polygons (and labels back per polygon), a mesh's top faces, prisms.

Vertices are (n, 3) float arrays, polygons lists of index arrays; nothing here knows Blender.
"""
from __future__ import annotations

import numpy as np

from ..ir.errors import InputError


class MeshInputError(InputError):
    """Geometry that cannot be used as given; the message names the object."""


def edge_loops(vertices: np.ndarray, edges: np.ndarray, name: str) -> list:
    """Closed loops of a wire (a curve without fill, or a mesh of edges only), as vertex arrays.

    Every vertex must join exactly two edges: an open outline cannot bound a region.
    """
    if not len(edges):
        raise MeshInputError(f"object {name!r} has no outline (no faces and no edges)")
    neighbours: dict = {}
    for a, b in np.asarray(edges).tolist():
        neighbours.setdefault(int(a), []).append(int(b))
        neighbours.setdefault(int(b), []).append(int(a))
    open_ends = [v for v, n in neighbours.items() if len(n) != 2]
    if open_ends:
        p = vertices[open_ends[0]]
        raise MeshInputError(f"object {name!r} has an open or branching outline near "
                             f"({p[0]:.3g}, {p[1]:.3g}, {p[2]:.3g}): close it (or fill the curve)")
    loops, seen = [], set()
    for start in neighbours:
        if start in seen:
            continue
        loop, previous, current = [start], None, start
        seen.add(start)
        while True:
            a, b = neighbours[current]
            nxt = b if a == previous else a
            if nxt == start:
                break
            loop.append(nxt)
            seen.add(nxt)
            previous, current = current, nxt
        loops.append(vertices[loop])
    return loops


def top_faces(vertices: np.ndarray, polygons) -> list:
    """The polygons lying in the mesh's highest plane (within 1e-4 of its height, at least 1e-6)."""
    lo, hi = vertices[:, 2].min(), vertices[:, 2].max()
    tolerance = max(1e-6, (hi - lo) * 1e-4)
    return [p for p in polygons if np.all(np.abs(vertices[p, 2] - hi) <= tolerance)]


def triangulated(polygons) -> tuple:
    """Triangles (fans: corner 0, k, k + 1) of the polygons, and the polygon each triangle came
    from; all at once over the polygons' corners laid end to end (a mesh of 10^5 faces)."""
    lengths = np.array([len(poly) for poly in polygons], dtype=np.int64)
    if not len(lengths) or lengths.max() < 3:
        return np.zeros((0, 3), np.int64), np.zeros(0, np.int64)
    corners = np.concatenate([np.asarray(poly, np.int64).reshape(-1) for poly in polygons])
    counts = np.maximum(lengths - 2, 0)
    owner = np.repeat(np.arange(len(lengths)), counts)
    k = np.arange(len(owner)) - np.repeat(np.cumsum(counts) - counts, counts) + 1
    first = (np.cumsum(lengths) - lengths)[owner]
    return np.column_stack([corners[first], corners[first + k], corners[first + k + 1]]), owner


def polygon_bits(triangle_bits: np.ndarray, owner: np.ndarray, polygon_count: int, all_bits: int) -> np.ndarray:
    """Per polygon, the bits set on all of its triangles (``all_bits``: every bit in use)."""
    labels = np.full(polygon_count, all_bits, dtype=np.int8)
    np.bitwise_and.at(labels, owner, np.asarray(triangle_bits).astype(np.int8))
    return labels


def prism(outline: np.ndarray, top: float, bottom: float) -> tuple:
    """Vertices and faces (top, bottom, sides) of a vertical prism over a closed (k, 2) outline."""
    outline = np.asarray(outline, float)
    k = len(outline)
    vertices = np.vstack([np.column_stack([outline, np.full(k, top)]),
                          np.column_stack([outline, np.full(k, bottom)])])
    faces = [list(range(k))[::-1], list(range(k, 2 * k))]
    faces += [[i, (i + 1) % k, k + (i + 1) % k, k + i] for i in range(k)]
    return vertices, faces


def signed_volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    """The volume a closed triangle mesh encloses, negative when it is inside out (its faces wound
    clockwise seen from outside, so its normals point inward)."""
    tri = np.asarray(vertices, float)[np.asarray(faces, np.int64)]
    centre = np.asarray(vertices, float).mean(axis=0)
    return float(np.einsum("ij,ij->i", tri[:, 0] - centre, np.cross(tri[:, 1] - centre, tri[:, 2] - centre)).sum()
                 / 6.0)


def is_closed(faces: np.ndarray, count: int) -> bool:
    """Every edge of the triangles shared by exactly two of them (``count``: the vertex count)."""
    directed = np.asarray(faces, np.int64)[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    _, counts = np.unique(directed.min(axis=1) * count + directed.max(axis=1), return_counts=True)
    return bool(len(counts)) and bool(np.all(counts == 2))


def inside_out(vertices: np.ndarray, faces: np.ndarray) -> bool:
    """Whether a design mesh's normals point inward.  A closed mesh: its enclosed volume is negative
    (the rule the gate's design check uses).  An open surface (a relief without a bottom): its
    faces, weighted by area, look down rather than up (their projected area is negative)."""
    vertices, faces = np.asarray(vertices, float), np.asarray(faces, np.int64)
    if not len(faces):
        return False
    if is_closed(faces, len(vertices)):
        return signed_volume(vertices, faces) < 0
    tri = vertices[faces]
    normal_z = ((tri[:, 1, 0] - tri[:, 0, 0]) * (tri[:, 2, 1] - tri[:, 0, 1])
                - (tri[:, 1, 1] - tri[:, 0, 1]) * (tri[:, 2, 0] - tri[:, 0, 0]))
    return float(normal_z.sum()) < 0
