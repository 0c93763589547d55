"""The planning mesh: coplanar faces merged back into as few triangles as their outline needs.

A mesh subdivided for rendering or sculpting (every face split into many coplanar ones) describes
the same surface as the coarse mesh it came from, so it should plan the same toolpath in about
the same time.  :func:`planning_mesh` groups edge-connected faces that lie in one plane (and carry
the same label, when labels are given) into facets.  Each facet of more than two faces is
re-triangulated from its boundary loops in its own plane.  A vertex on a facet's boundary is
dropped only where exactly two boundary edges meet in a straight line and both facets beside it
are re-triangulated: the two neighbours then drop it together, so no T-junction appears and a
closed mesh stays closed.  A facet is kept as it was unless its new triangulation has fewer faces,
so a mesh without redundant faces (quads split into two triangles, polygons fanned without inner
vertices) comes back unchanged: the same arrays, the same order.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .compiled import kernel_module
from .meshrays import face_normals
from .meshdata import MeshInputError

PLANE_TOLERANCE = 1e-9       # normals and plane offsets (relative to the part's size) this close are one plane


@dataclass
class PlanningMesh:
    """``vertices``/``faces``: the mesh to plan on.  ``source[i]``: an input face inside planning
    face i's facet.  ``group[j]``: a planning face inside input face j's facet (so a per-face result
    on the planning mesh maps back as ``result[group]``).  ``merged``: facets re-triangulated."""

    vertices: np.ndarray
    faces: np.ndarray
    source: np.ndarray
    group: np.ndarray
    merged: int


def _identity(v, f) -> PlanningMesh:
    ids = np.arange(len(f))
    return PlanningMesh(v, f, ids, ids, 0)


def _compiled():
    return kernel_module("auto", f"{__package__}.facets_kernel", MeshInputError, "facet kernel")


def connected(count: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Connected components of ``count`` nodes joined by pairs (a, b): each node's smallest member."""
    comp = np.arange(count)
    while True:
        ca, cb = comp[a], comp[b]
        if np.array_equal(ca, cb):
            return comp
        low = np.minimum(ca, cb)
        np.minimum.at(comp, ca, low)
        np.minimum.at(comp, cb, low)
        while True:                                # pointer jumping to the roots
            jumped = comp[comp]
            if np.array_equal(jumped, comp):
                break
            comp = jumped


def _reverse(faces: np.ndarray, vertex_count: int) -> np.ndarray:
    """For directed edge 3i+k (faces[i, k] -> faces[i, k+1]): the row of the edge running back,
    or its own row when there is none."""
    compiled = _compiled()
    if compiled is not None:
        return compiled.edge_check(faces, vertex_count)[0]
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    key = np.minimum(directed[:, 0], directed[:, 1]) * vertex_count + np.maximum(directed[:, 0], directed[:, 1])
    order = np.argsort(key)
    pair = np.flatnonzero(key[order[1:]] == key[order[:-1]])     # check_mesh: at most two per edge
    reverse = np.arange(len(directed))
    reverse[order[pair]] = order[pair + 1]
    reverse[order[pair + 1]] = order[pair]
    return reverse


def _directed(faces: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """(k, 2) start and end vertex of the directed edges ``rows`` (edge 3i+k runs from faces[i, k])."""
    flat = faces.reshape(-1)
    return np.column_stack([flat[rows], flat[rows - rows % 3 + (rows % 3 + 1) % 3]])


def facet_ids(vertices: np.ndarray, faces: np.ndarray, labels=None, reverse=None, normals=None) -> np.ndarray:
    """(m,) facet id of each face: edge-connected faces in one plane with the same label."""
    normals, areas = face_normals(vertices[faces]) if normals is None else normals
    scale = max(float(np.ptp(vertices, axis=0).max()), 1e-12)
    reverse = _reverse(faces, len(vertices)) if reverse is None else reverse
    compiled = _compiled()
    if compiled is not None:
        marks = np.zeros(len(faces), np.int64) if labels is None else np.asarray(labels, np.int64)
        return compiled.coplanar_components(vertices, faces, reverse, normals, areas, marks, PLANE_TOLERANCE, scale)
    offsets = np.einsum("ij,ij->i", normals, vertices[faces[:, 0]]) / scale
    rows = np.arange(len(reverse))
    directed = _directed(faces, rows)
    owner, has_twin = rows // 3, reverse != rows
    once = np.flatnonzero(has_twin & (directed[:, 0] < directed[:, 1]))
    a, b = owner[once], owner[reverse[once]]
    same = (np.abs(normals[a] - normals[b]).max(axis=1) <= PLANE_TOLERANCE) & \
           (np.abs(offsets[a] - offsets[b]) <= PLANE_TOLERANCE) & (areas[a] > 0) & (areas[b] > 0)
    if labels is not None:
        same &= labels[a] == labels[b]
    return connected(len(faces), a[same], b[same])


def _pinned_loops(edges, splits, pinned, vertex_count):
    """numpy path of facets_kernel.pinned_loops (same results)."""
    flat, lengths, counts, failed = [], [], np.zeros(len(splits) - 1, np.int64), np.zeros(len(splits) - 1, bool)
    for j in range(len(splits) - 1):
        nxt, loops = {}, []
        for u, w in edges[splits[j]:splits[j + 1]].tolist():
            failed[j] |= u in nxt
            nxt[u] = w
        while nxt and not failed[j]:
            start = next(iter(nxt))
            loop, w = [], start
            while True:
                step = nxt.pop(w, None)
                if step is None:
                    failed[j] = True
                    break
                if pinned[w]:
                    loop.append(w)
                w = step
                if w == start:
                    break
            failed[j] |= len(loop) < 3
            loops.append(loop)
        if not failed[j]:
            flat += [w for loop in loops for w in loop]
            lengths += [len(loop) for loop in loops]
            counts[j] = len(loops)
    return np.array(flat, np.int64), np.array(lengths, np.int64), counts, failed


def planning_mesh(vertices, faces, labels=None, reverse=None, normals=None) -> PlanningMesh:
    """Merge coplanar, edge-connected faces (with equal ``labels`` when given) back into the
    fewest triangles their outlines need; see the module notes.  ``vertices``/``faces`` must
    have passed ``check_mesh``; ``reverse`` and ``normals``: what the check found for them
    (:class:`meshrays.CheckedMesh`), or None to compute them here."""
    from manifold3d import triangulate

    v, f = vertices, faces
    labels = None if labels is None else np.asarray(labels)
    normals = face_normals(v[f]) if normals is None else normals
    reverse = _reverse(f, len(v)) if reverse is None else reverse
    facet = facet_ids(v, f, labels, reverse, normals)
    members = np.bincount(facet, minlength=len(f))     # facet ids are their smallest face: no sort needed
    roots = np.flatnonzero(members)
    inverse = (np.cumsum(members > 0) - 1)[facet]
    sizes = members[roots]
    if sizes.max() <= 2:
        return _identity(v, f)
    candidate = sizes[inverse] > 2                 # faces in facets that may shrink
    n = len(v)
    # a directed edge is on its facet's boundary unless its reverse lies in the same facet;
    # only those edges are needed from here on (``rows``: their rows, in order)
    compiled = _compiled()
    if compiled is not None:
        rows = compiled.boundary_rows(reverse, inverse)
    else:
        every = np.arange(len(reverse))
        rows = np.flatnonzero((reverse == every) | (inverse[reverse // 3] != inverse[every // 3]))
    directed, owner, has_twin = _directed(f, rows), rows // 3, reverse[rows] != rows
    normals = normals[0]
    # each facet's plane basis (e1, e2, normal) right-handed, so outer loops run anticlockwise
    facet_normal = normals[roots]
    e1 = np.cross(facet_normal, np.where(np.abs(facet_normal[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]]))
    e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    basis = np.stack([e1, np.cross(facet_normal, e1)], axis=2)
    scale = max(float(np.ptp(v, axis=0).max()), 1e-12)
    rejected = np.zeros(len(roots), bool)
    for _attempt in range(8):
        keep = ~candidate | rejected[inverse]
        # pinned vertices: on a kept face, or where boundary edges do not meet two in a straight line
        pinned = np.zeros(n, bool)
        pinned[f[keep].reshape(-1)] = True
        undirected = directed[~has_twin | (directed[:, 0] < directed[:, 1])]
        degree = np.bincount(undirected.reshape(-1), minlength=n)
        pinned |= (degree != 2) & (degree > 0)
        ends = np.concatenate([undirected, undirected[:, ::-1]])
        ends = ends[np.argsort(ends[:, 0], kind="stable")]
        two = degree[ends[0::1, 0]] == 2
        pairs = ends[two].reshape(-1, 2, 2)        # each degree-2 vertex's two edges, in vertex order
        p = v[pairs[:, 0, 0]]
        d1, d2 = v[pairs[:, 0, 1]] - p, v[pairs[:, 1, 1]] - p
        bent = (np.linalg.norm(np.cross(d1, d2), axis=1) >
                PLANE_TOLERANCE * np.linalg.norm(d1, axis=1) * np.linalg.norm(d2, axis=1)) | \
               (np.einsum("ij,ij->i", d1, d2) >= 0)
        pinned[pairs[bent, 0, 0]] = True
        # re-triangulate each candidate facet from its boundary loops, without unpinned vertices
        chosen = ~keep[owner]
        edge_facet = inverse[owner[chosen]]
        edge_order = np.argsort(edge_facet, kind="stable")
        chosen_edges = directed[chosen][edge_order]
        splits = np.searchsorted(edge_facet[edge_order], np.arange(len(roots) + 1))
        new_faces, new_source, failed = [], [], False
        loop_of = _pinned_loops if compiled is None else compiled.pinned_loops
        flat, lengths, counts, broken = loop_of(chosen_edges, splits, pinned, n)
        ends = np.cumsum(lengths)
        first_loop = np.concatenate([[0], np.cumsum(counts)])
        for k in np.flatnonzero(~rejected & (sizes > 2)):
            if broken[k]:
                rejected[k] = failed = True
                continue
            loops = range(first_loop[k], first_loop[k + 1])
            index = flat[ends[loops[0]] - lengths[loops[0]]:ends[loops[-1]]]
            xy = index_xy = v[index] @ basis[k]
            tris = np.asarray(triangulate([index_xy[ends[i] - lengths[i] - ends[loops[0]] + lengths[loops[0]]:
                                                    ends[i] - ends[loops[0]] + lengths[loops[0]]] for i in loops],
                                          PLANE_TOLERANCE * scale))
            del xy
            if len(tris) >= sizes[k] or len(tris) != len(index) + 2 * len(loops) - 4:
                rejected[k] = failed = True
                continue
            new_faces.append(index[tris])
            new_source.append(np.full(len(tris), roots[k]))
        if not failed:
            break
    else:
        return _identity(v, f)
    keep = ~candidate | rejected[inverse]
    if keep.all():
        return _identity(v, f)
    kept = np.flatnonzero(keep)
    out_faces = np.concatenate([f[kept]] + new_faces)
    source = np.concatenate([kept] + new_source)
    used = np.unique(out_faces)
    remap = np.full(n, -1, np.int64)
    remap[used] = np.arange(len(used))
    # each input face's representative planning face: the first planning face of its facet
    first = np.full(len(roots), -1, np.int64)
    facet_of_planning = inverse[source]
    first[facet_of_planning[::-1]] = np.arange(len(source))[::-1]
    return PlanningMesh(v[used], remap[out_faces], source, first[inverse], int((~rejected & (sizes > 2)).sum()))
