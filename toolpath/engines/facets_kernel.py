"""Compiled (numba) kernels of the planning mesh (facets.py): each directed edge's reverse
edge, found through the edges leaving each vertex instead of a sort; the facets as the
connected components of a union-find; the facets' boundary loops through their pinned vertices.
Same results as the numpy paths in facets.py."""
from __future__ import annotations

import numpy as np
from numba import njit

_jit = njit(cache=True, nogil=True)


@_jit
def edge_check(faces, vertex_count):
    """(for directed edge 3i+k, faces[i, k] -> faces[i, k+1]: the row of the edge running back, or
    its own row when none; clean; closed): clean when no directed edge
    appears twice (consistent winding) and no edge has more than one edge running back (no edge
    shared by more than two faces); closed when every edge has one running back.
    The edges leaving each vertex are listed together (their end vertex and row side by side),
    so each edge's searches read a few neighbouring entries."""
    m = faces.shape[0]
    start = np.zeros(vertex_count + 1, np.int64)
    for i in range(m):
        for k in range(3):
            start[faces[i, k] + 1] += 1
    for j in range(vertex_count):
        start[j + 1] += start[j]
    fill = start[:-1].copy()
    target = np.empty(3 * m, np.int64)
    row = np.empty(3 * m, np.int64)
    for i in range(m):
        for k in range(3):
            u = faces[i, k]
            target[fill[u]] = faces[i, (k + 1) % 3]
            row[fill[u]] = 3 * i + k
            fill[u] += 1
    reverse = np.arange(3 * m)
    clean = True
    closed = True
    for u in range(vertex_count):
        for s in range(start[u], start[u + 1]):
            w = target[s]
            same = 0
            for t in range(start[u], start[u + 1]):
                if target[t] == w:
                    same += 1
            back = 0
            for t in range(start[w], start[w + 1]):
                if target[t] == u:
                    reverse[row[s]] = row[t]
                    back += 1
            if same != 1 or back > 1:
                clean = False
            if back == 0:
                closed = False
    return reverse, clean, closed


@_jit
def face_pass(vertices, faces):
    """(unit normals (m, 3), zero for a degenerate face; areas (m,); the enclosed volume,
    sum of a . (b x c) / 6, whose sign tells outward from inward normals on a closed mesh).
    The same numbers as meshrays.face_normals, in one pass."""
    m = faces.shape[0]
    normals = np.zeros((m, 3))
    areas = np.empty(m)
    volume = 0.0
    for i in range(m):
        a, b, c = faces[i, 0], faces[i, 1], faces[i, 2]
        ax, ay, az = vertices[a, 0], vertices[a, 1], vertices[a, 2]
        bx, by, bz = vertices[b, 0], vertices[b, 1], vertices[b, 2]
        cx, cy, cz = vertices[c, 0], vertices[c, 1], vertices[c, 2]
        ux, uy, uz = bx - ax, by - ay, bz - az
        vx, vy, vz = cx - ax, cy - ay, cz - az
        nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
        length = np.sqrt(nx * nx + ny * ny + nz * nz)
        if length > 0:
            normals[i, 0], normals[i, 1], normals[i, 2] = nx / length, ny / length, nz / length
        areas[i] = 0.5 * length
        volume += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx)
    return normals, areas, volume / 6.0


@_jit
def coplanar_components(vertices, faces, reverse, normals, areas, labels, tolerance, scale):
    """Facet of each face (its smallest fellow member): faces joined across an edge when their
    normals and plane offsets (normal . first corner / ``scale``) agree within ``tolerance``,
    both have area and labels match."""
    m = faces.shape[0]
    offsets = np.empty(m)
    for i in range(m):
        a = faces[i, 0]
        offsets[i] = (normals[i, 0] * vertices[a, 0] + normals[i, 1] * vertices[a, 1]
                      + normals[i, 2] * vertices[a, 2]) / scale
    parent = np.arange(m)
    for e in range(3 * m):
        g = reverse[e] // 3
        i = e // 3
        if g <= i or areas[i] <= 0 or areas[g] <= 0 or labels[i] != labels[g]:
            continue
        if abs(offsets[i] - offsets[g]) > tolerance:
            continue
        if abs(normals[i, 0] - normals[g, 0]) > tolerance or abs(normals[i, 1] - normals[g, 1]) > tolerance \
                or abs(normals[i, 2] - normals[g, 2]) > tolerance:
            continue
        x = i
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        y = g
        while parent[y] != y:
            parent[y] = parent[parent[y]]
            y = parent[y]
        if x < y:
            parent[y] = x
        elif y < x:
            parent[x] = y
    for i in range(m):
        parent[i] = parent[parent[i]]
    return parent


@_jit
def pinned_loops(edges, splits, pinned, vertex_count):
    """Boundary loops of each facet, through its pinned vertices only.  ``edges`` (k, 2): the
    facets' directed boundary edges, facet by facet (facet j's are rows splits[j]..splits[j+1]).
    Returns (vertices of all loops in order, each loop's length, each facet's loop count, and
    failed facets: a vertex starting two edges, an open chain, or a loop under 3 pinned vertices)."""
    facets = splits.shape[0] - 1
    nxt = np.full(vertex_count, -1, np.int64)
    out = np.empty(edges.shape[0], np.int64)
    lengths = np.empty(edges.shape[0], np.int64)
    counts = np.zeros(facets, np.int64)
    failed = np.zeros(facets, np.bool_)
    used = 0
    loops = 0
    for j in range(facets):
        for r in range(splits[j], splits[j + 1]):
            if nxt[edges[r, 0]] >= 0:
                failed[j] = True
            nxt[edges[r, 0]] = edges[r, 1]
        mark_used, mark_loops = used, loops
        if not failed[j]:
            for r in range(splits[j], splits[j + 1]):
                start = edges[r, 0]
                if nxt[start] < 0:
                    continue                      # already walked
                length = 0
                w = start
                while True:
                    step = nxt[w]
                    if step < 0:
                        failed[j] = True
                        break
                    nxt[w] = -1
                    if pinned[w]:
                        out[used + length] = w
                        length += 1
                    w = step
                    if w == start:
                        break
                if failed[j]:
                    break
                if length < 3:
                    failed[j] = True
                    break
                lengths[loops] = length
                loops += 1
                used += length
                counts[j] += 1
        for r in range(splits[j], splits[j + 1]):
            nxt[edges[r, 0]] = -1
        if failed[j]:
            used, loops = mark_used, mark_loops
            counts[j] = 0
    return out[:used], lengths[:loops], counts, failed


@_jit
def boundary_rows(reverse, facet):
    """Rows of the directed edges on their facet's boundary (``facet``: each face's facet): no
    edge running back, or that edge's face in another facet.  In row order."""
    out = np.empty(reverse.shape[0], np.int64)
    count = 0
    for e in range(reverse.shape[0]):
        r = reverse[e]
        if r == e or facet[r // 3] != facet[e // 3]:
            out[count] = e
            count += 1
    return out[:count].copy()
