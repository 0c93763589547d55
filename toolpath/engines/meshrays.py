"""Triangle meshes for the turn-mill workflow: the checks a mesh must pass, and ray and
nearest-point queries against its triangles.

:func:`check_mesh` validates vertices and faces (:func:`checked_mesh` also hands on what it found,
a :class:`CheckedMesh`); :func:`face_samples` spreads points over them.
:class:`Triangles` answers "does this ray hit the mesh?" (Moller-Trumbore) and "how far is the
nearest surface point?" (Ericson's region test) in numpy, culling with bounding boxes a chunk of
queries at a time.  :class:`TrimeshRayEngine` is the default :class:`RayEngine` for
classification: Embree through trimesh when embreex is installed, otherwise :class:`Triangles`.  Errors are the turn-mill workflow's
(:class:`meshdata.MeshInputError`).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from .compiled import kernel_module
from .meshdata import MeshInputError

PAIR_BUDGET = 1 << 20    # (query, triangle) pairs handled at once: bounds the memory
QUERY_CHUNK = 256        # at most this many nearby queries are culled against the triangles together
MAX_SUBDIVISION = 16     # at most 16 x 16 samples per face (face_samples)


@dataclass(frozen=True, eq=False)
class CheckedMesh:
    """A mesh that passed :func:`checked_mesh`, with what the check found on the way so the
    planning mesh (:func:`facets.planning_mesh`) need not find it again: ``reverse``, each directed
    edge's reverse edge row, and ``normals``, (unit normals, areas) of the faces; None where the
    check did not compute them (the numpy path).  The caller keeps it and passes it on: nothing is
    remembered between calls."""

    vertices: np.ndarray
    faces: np.ndarray
    reverse: np.ndarray | None = None
    normals: tuple | None = None


def check_mesh(vertices, faces) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (n, 3) float, faces (m, 3) int) after the checks the workflow relies on:
    finite coordinates, valid indices, no edge shared by more than two faces (slicing chains
    sections edge to edge), consistent winding, and outward normals when the mesh is closed."""
    mesh = checked_mesh(vertices, faces)
    return mesh.vertices, mesh.faces


def checked_mesh(vertices, faces) -> CheckedMesh:
    """:func:`check_mesh`, keeping what the check found (see :class:`CheckedMesh`)."""
    try:
        v = np.asarray(vertices, dtype=float)
        f = np.asarray(faces)
    except (TypeError, ValueError):
        raise MeshInputError("vertices and faces must be numeric arrays") from None
    if v.size == 0 or f.size == 0:
        raise MeshInputError("the mesh is empty: it needs vertices and triangles")
    if v.ndim != 2 or v.shape[1] != 3:
        raise MeshInputError(f"vertices must have shape (n, 3), got {v.shape}")
    if f.ndim != 2 or f.shape[1] != 3:
        raise MeshInputError(f"faces must be triangles, shape (m, 3), got {f.shape}")
    if not np.all(np.isfinite(v)):
        raise MeshInputError("the mesh has NaN or infinite vertex coordinates")
    if not np.issubdtype(f.dtype, np.integer):
        raise MeshInputError(f"face indices must be integers, got {f.dtype}")
    if f.min() < 0 or f.max() >= len(v):
        raise MeshInputError(f"face indices must lie in 0..{len(v) - 1}")
    f = f.astype(np.int64)
    if np.any((f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 2] == f[:, 0])):
        raise MeshInputError("a face uses the same vertex twice")
    compiled = kernel_module("auto", f"{__package__}.facets_kernel", MeshInputError, "facet kernel")
    if compiled is not None:                    # one pass over each vertex's edges instead of sorting
        reverse, clean, closed = compiled.edge_check(f, len(v))
        if clean:
            normals, areas, volume = compiled.face_pass(v, f)
            if closed and volume < 0:
                raise MeshInputError(INWARD)
            return CheckedMesh(v, f, reverse, (normals, areas))
    directed = f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    _, counts = np.unique(directed.min(axis=1) * len(v) + directed.max(axis=1), return_counts=True)
    if np.any(counts > 2):
        raise MeshInputError(f"the mesh is non-manifold: {int(np.sum(counts > 2))} edge(s) are shared by more "
                            f"than two faces")
    if len(np.unique(directed[:, 0] * len(v) + directed[:, 1])) < len(directed):
        raise MeshInputError("the faces are wound inconsistently (some normals are flipped): recalculate normals")
    if np.all(counts == 2):
        _check_outward(v, f)
    return CheckedMesh(v, f)


INWARD = "the face normals point inward: flip them so they point out of the part"


def _check_outward(v: np.ndarray, f: np.ndarray) -> None:
    tri = v[f]
    volume = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0
    if volume < 0:
        raise MeshInputError(INWARD)


def face_normals(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit normals (zero for degenerate faces) and areas."""
    cross = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    length = np.linalg.norm(cross, axis=1)
    normals = np.divide(cross, length[:, None], out=np.zeros_like(cross), where=length[:, None] > 0)
    return normals, 0.5 * length


# ----- ray casting ----------------------------------------------------------------------------
class RayEngine(Protocol):
    """What classification needs from a ray caster.  The Blender shell adds a
    mathutils.bvhtree engine with the same method."""

    def intersects_any(self, origins: np.ndarray, directions: np.ndarray) -> np.ndarray:
        """(k,) bool: does the ray from each origin along each direction hit any face?"""


class BoxGrid:
    """Axis-aligned boxes (triangles' bounds) filed on a uniform grid, for "which boxes can meet
    this region?" without testing every box: each box is listed in every cell it touches.  The
    cell follows the boxes' median size (so a box lies in a few cells), coarsened until the
    listing stays within ``budget`` entries."""

    def __init__(self, lo: np.ndarray, hi: np.ndarray, budget: int = 1 << 23):
        self.dims = lo.shape[1]
        self.origin = lo.min(axis=0) if len(lo) else np.zeros(self.dims)
        extent = float(np.max(hi.max(axis=0) - self.origin)) if len(lo) else 1.0
        size = float(np.median(np.max(hi - lo, axis=1))) if len(lo) else extent
        self.cell = max(size, extent / 1024, 1e-9)
        while True:
            first = np.floor((lo - self.origin) / self.cell).astype(np.int64)
            last = np.floor((hi - self.origin) / self.cell).astype(np.int64)
            span = last - first + 1
            count = np.prod(span, axis=1)
            if int(count.sum()) <= budget:
                break
            self.cell *= 2
        self.shape = last.max(axis=0) + 1 if len(lo) else np.ones(self.dims, np.int64)
        box = np.repeat(np.arange(len(lo)), count)
        # the k-th cell of box b: unravel k over its span
        k = np.arange(len(box)) - np.repeat(np.cumsum(count) - count, count)
        index = np.zeros((len(box), self.dims), np.int64)
        for axis in range(self.dims - 1, -1, -1):
            index[:, axis] = first[box, axis] + k % span[box, axis]
            k //= span[box, axis]
        keys = self._keys(index)
        order = np.lexsort((box, keys))
        self.keys, self.boxes = keys[order], box[order]
        self.unique, self.starts = np.unique(self.keys, return_index=True)
        self.ends = np.r_[self.starts[1:], len(self.keys)]

    def _keys(self, index: np.ndarray) -> np.ndarray:
        key = np.zeros(len(index), np.int64)
        for axis in range(self.dims):
            key = key * (int(self.shape[axis]) + 1) + index[:, axis]
        return key

    def cells_of(self, points: np.ndarray) -> np.ndarray:
        """The key of the cell each point lies in (-1 outside the grid)."""
        index = np.floor((points - self.origin) / self.cell).astype(np.int64)
        inside = np.all((index >= 0) & (index < self.shape), axis=1)
        keys = np.full(len(points), -1, np.int64)
        keys[inside] = self._keys(index[inside])
        return keys

    def listed(self, keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(start, stop) of each key's boxes in ``self.boxes`` (empty for keys with none)."""
        if not len(self.unique):
            return np.zeros(len(keys), np.int64), np.zeros(len(keys), np.int64)
        where = np.clip(np.searchsorted(self.unique, keys), 0, len(self.unique) - 1)
        found = (keys >= 0) & (self.unique[where] == keys)
        return np.where(found, self.starts[where], 0), np.where(found, self.ends[where], 0)

    def near(self, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        """Sorted indices of the boxes listed in the cells the box lo..hi touches (a superset of
        those meeting it)."""
        first = np.maximum(np.floor((lo - self.origin) / self.cell).astype(np.int64), 0)
        last = np.minimum(np.floor((hi - self.origin) / self.cell).astype(np.int64), self.shape - 1)
        if np.any(last < first):
            return np.empty(0, np.int64)
        axes = np.meshgrid(*[np.arange(a, b + 1) for a, b in zip(first, last)], indexing="ij")
        start, stop = self.listed(self._keys(np.column_stack([a.ravel() for a in axes])))
        count = stop - start
        if not count.sum():
            return np.empty(0, np.int64)
        take = np.repeat(start - np.cumsum(count) + count, count) + np.arange(int(count.sum()))
        return np.unique(self.boxes[take])


class Triangles:
    """The mesh triangles with bounding boxes, for the numpy ray and nearest-point queries.
    Queries are paired with triangles whose boxes overlap theirs, a chunk at a time."""

    def __init__(self, triangles: np.ndarray, kernel: str = "auto"):
        self.compiled = kernel_module(kernel, f"{__package__}.nearest_kernel", MeshInputError,
                                      "numba nearest-point kernel")
        self._tree = None
        normals, areas = face_normals(triangles)
        size = max(float(np.ptp(triangles.reshape(-1, 3), axis=0).max()), 1e-9)
        tri = triangles[areas > 1e-14 * size * size]
        self.a, self.b, self.c = (np.ascontiguousarray(tri[:, k]) for k in range(3))
        self.normal = normals[areas > 1e-14 * size * size]
        self.lo = tri.min(axis=1)
        self.hi = tri.max(axis=1)
        pad = 1e-6 * size
        self.box_lo = self.lo.min(axis=0) - pad
        self.box_hi = self.hi.max(axis=0) + pad
        self._grid = None           # built on the first numpy query (the compiled one uses a tree)

    @property
    def grid(self):
        if self._grid is None and len(self.lo):
            self._grid = BoxGrid(self.lo, self.hi)
        return self._grid

    def _pairs(self, lo: np.ndarray, hi: np.ndarray):
        """Yield (query index, triangle index) arrays for overlapping boxes.  Queries are grouped by
        the cell (1/16 of the part size) their box centre lies in, at most QUERY_CHUNK together.
        Only the triangles meeting a group's box are tested pairwise.  Each group holds whole
        queries."""
        extent = self.box_hi - self.box_lo
        cells = np.clip(np.floor((0.5 * (lo + hi) - self.box_lo) / (extent.max() / 16)), 0, 1023).astype(np.int64)
        key = (cells[:, 0] * 1024 + cells[:, 1]) * 1024 + cells[:, 2]
        order = np.argsort(key, kind="stable")
        key = key[order]
        first = np.r_[0, np.flatnonzero(np.diff(key)) + 1]
        rank = np.arange(len(key)) - np.repeat(first, np.diff(np.r_[first, len(key)]))
        bounds = np.r_[np.flatnonzero((np.r_[1, np.diff(key)] != 0) | (rank % QUERY_CHUNK == 0)), len(key)]
        for begin, stop in zip(bounds[:-1], bounds[1:]):
            query = order[begin:stop]
            chunk_lo, chunk_hi = lo[query].min(axis=0), hi[query].max(axis=0)
            if self.grid is None:
                continue
            near = self.grid.near(chunk_lo, chunk_hi)      # the triangles filed round the chunk, sorted
            near = near[np.all((self.lo[near] <= chunk_hi) & (self.hi[near] >= chunk_lo), axis=1)]
            if not len(near):
                continue
            overlap = np.all((lo[query, None, :] <= self.hi[near][None]) & (hi[query, None, :] >= self.lo[near][None]),
                             axis=2)
            q, t = np.nonzero(overlap)
            yield query[q], near[t]

    def intersects_any(self, origins: np.ndarray, directions: np.ndarray) -> np.ndarray:
        # Clip each ray where it leaves the mesh box, so it has a finite box to cull with.
        with np.errstate(divide="ignore", invalid="ignore"):
            t1 = (self.box_lo - origins) / directions
            t2 = (self.box_hi - origins) / directions
            exit_t = np.where(directions != 0, np.maximum(t1, t2), np.inf).min(axis=1)
        end = origins + directions * np.clip(exit_t, 0.0, None)[:, None]
        hit = np.zeros(len(origins), dtype=bool)
        for query, tri in self._pairs(np.minimum(origins, end), np.maximum(origins, end)):
            found = _ray_hits(origins[query], directions[query], self.a[tri], self.b[tri], self.c[tri])
            hit[query[found]] = True
        return hit

    def nearest(self, points: np.ndarray, reach: float) -> tuple[np.ndarray, np.ndarray]:
        """Distance to the nearest surface point within ``reach`` (inf beyond) and that point.
        Compiled: a branch-and-bound search in a tree of the triangles (nearest_kernel.py);
        numpy: every triangle whose box meets the cube of side 2 ``reach`` round the point."""
        points = np.ascontiguousarray(points, dtype=float)
        if self.compiled is not None:
            if not len(self.a) or not len(points):
                return np.full(len(points), np.inf), points.copy()
            if self._tree is None:
                self._tree = self.compiled.build(self.lo, self.hi)
            return self.compiled.nearest(points, float(reach), self.a, self.b, self.c, self.lo, self.hi, *self._tree)
        return self._nearest_numpy(points, reach)

    def _nearest_numpy(self, points: np.ndarray, reach: float) -> tuple[np.ndarray, np.ndarray]:
        distance = np.full(len(points), np.inf)
        closest = points.copy()
        batch: list = []

        def settle():
            query = np.concatenate([q for q, _ in batch])
            tri = np.concatenate([t for _, t in batch])
            p = points[query]
            box_gap = np.maximum(np.maximum(self.lo[tri] - p, p - self.hi[tri]), 0.0)
            plane = np.abs(np.einsum("ij,ij->i", p - self.a[tri], self.normal[tri]))
            near = (np.einsum("ij,ij->i", box_gap, box_gap) <= reach * reach) & (plane <= reach)
            query, tri = query[near], tri[near]
            batch.clear()
            if not len(query):
                return
            q = _closest_on_triangles(points[query], self.a[tri], self.b[tri], self.c[tri])
            d2 = np.einsum("ij,ij->i", points[query] - q, points[query] - q)
            order = np.lexsort((d2, query))
            first = order[np.r_[True, query[order][1:] != query[order][:-1]]]
            # a triangle whose box is within reach may itself lie beyond it, and an earlier batch
            # may already hold a nearer triangle for the same point: keep only nearer ones in reach
            better = (d2[first] <= reach * reach) & (d2[first] < distance[query[first]] ** 2)
            first = first[better]
            distance[query[first]] = np.sqrt(d2[first])
            closest[query[first]] = q[first]

        pending = 0
        for pair in self._pairs(points - reach, points + reach):
            batch.append(pair)
            pending += len(pair[0])
            if pending >= PAIR_BUDGET // 4:
                settle()
                pending = 0
        if batch:
            settle()
        return distance, closest


def moller_trumbore(o, d, a, b, c) -> tuple:
    """Moller-Trumbore for line/triangle pairs (k, 3) each: (det, u, v, t) with the crossing at
    o + t d = a + u (b - a) + v (c - a); inf/nan where det is 0 (the line is in the plane)."""
    e1, e2 = b - a, c - a
    p = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, p)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        s = o - a
        u = np.einsum("ij,ij->i", s, p) * inv
        q = np.cross(s, e1)
        v = np.einsum("ij,ij->i", d, q) * inv
        t = np.einsum("ij,ij->i", e2, q) * inv
    return det, u, v, t


def _ray_hits(o, d, a, b, c) -> np.ndarray:
    """Ray/triangle pairs; hits strictly in front of the origin."""
    det, u, v, t = moller_trumbore(o, d, a, b, c)
    with np.errstate(invalid="ignore"):
        return (det != 0) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)


def _closest_on_triangles(p, a, b, c) -> np.ndarray:
    """Closest point on each triangle to each point (pairwise), Ericson's region test."""
    def dot(x, y):
        return np.einsum("ij,ij->i", x, y)

    ab, ac = b - a, c - a
    d1, d2 = dot(ab, p - a), dot(ac, p - a)
    d3, d4 = dot(ab, p - b), dot(ac, p - b)
    d5, d6 = dot(ab, p - c), dot(ac, p - c)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        result = a + ab * (vb / denom)[:, None] + ac * (vc / denom)[:, None]
        # Later regions override earlier ones: Ericson tests A, B, AB, C, AC, BC, then the face.
        on_bc = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        result = np.where(on_bc[:, None], b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))[:, None], result)
        on_ac = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        result = np.where(on_ac[:, None], a + ac * (d2 / (d2 - d6))[:, None], result)
        result = np.where(((d6 >= 0) & (d5 <= d6))[:, None], c, result)
        on_ab = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        result = np.where(on_ab[:, None], a + ab * (d1 / (d1 - d3))[:, None], result)
        result = np.where(((d3 >= 0) & (d4 <= d3))[:, None], b, result)
        return np.where(((d1 <= 0) & (d2 <= 0))[:, None], a, result)


class TrimeshRayEngine:
    """The default :class:`RayEngine`.  It uses Embree through trimesh when embreex is installed.
    Otherwise it uses a numpy Moller-Trumbore with bounding-box culling: trimesh's own numpy
    intersector needs rtree, which is neither bundled nor installed.  Rays go ``chunk_size`` at a
    time, because a large batch exhausts memory."""

    def __init__(self, vertices, faces, chunk_size: int = 20000):
        if not (isinstance(chunk_size, int) and chunk_size > 0):
            raise MeshInputError(f"ray chunk size must be a positive integer, got {chunk_size!r}")
        v, f = check_mesh(vertices, faces)
        self.chunk_size = chunk_size
        try:
            import trimesh
            from trimesh.ray.ray_pyembree import RayMeshIntersector
        except ImportError:
            self._cast = Triangles(v[f]).intersects_any
            self.backend = "numpy"
        else:
            self._cast = RayMeshIntersector(trimesh.Trimesh(v, f, process=False)).intersects_any
            self.backend = "embree"

    def intersects_any(self, origins: np.ndarray, directions: np.ndarray) -> np.ndarray:
        origins = np.asarray(origins, dtype=float).reshape(-1, 3)
        directions = np.asarray(directions, dtype=float).reshape(-1, 3)
        hit = np.zeros(len(origins), dtype=bool)
        for start in range(0, len(origins), self.chunk_size):
            stop = start + self.chunk_size
            hit[start:stop] = self._cast(origins[start:stop], directions[start:stop])
        return hit


def _subtriangle_centroids(k: int) -> np.ndarray:
    """(k*k, 2) barycentric weights of vertices 1 and 2: the centroids of the k*k sub-triangles."""
    i, j = np.meshgrid(np.arange(k), np.arange(k), indexing="ij")
    up = (i + j) <= k - 1
    down = (i + j) <= k - 2
    return np.vstack([np.column_stack([i[up] + 1 / 3, j[up] + 1 / 3]),
                      np.column_stack([i[down] + 2 / 3, j[down] + 2 / 3])]) / k


def face_samples(triangles: np.ndarray, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """Deterministic area-weighted samples: each face is cut into k x k similar sub-triangles
    (k from its area and ``spacing``, 2..16) and sampled at their centroids.  Returns the
    points and the face each belongs to; degenerate faces get none."""
    _, areas = face_normals(triangles)
    k = np.clip(np.ceil(np.sqrt(2.0 * areas) / spacing), 2, MAX_SUBDIVISION).astype(int)
    k[areas <= 0] = 0
    points, owner = [np.empty((0, 3))], [np.empty(0, dtype=np.int64)]
    for level in np.unique(k[k > 0]):
        ids = np.flatnonzero(k == level)
        weights = _subtriangle_centroids(int(level))
        tri = triangles[ids]
        pts = (tri[:, None, 0] * (1 - weights.sum(axis=1))[None, :, None] + tri[:, None, 1] * weights[None, :, 0, None]
               + tri[:, None, 2] * weights[None, :, 1, None])
        points.append(pts.reshape(-1, 3))
        owner.append(np.repeat(ids, len(weights)))
    return np.vstack(points), np.concatenate(owner)
