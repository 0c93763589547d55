"""Compiled nearest-surface-point kernel (numba): a bounding-volume tree over the triangles and a
branch-and-bound search in it, point by point.

:func:`build` splits the triangles at the median of their centroids along the longest axis of
each node's box until a node holds at most LEAF triangles.  :func:`nearest` walks the tree from
the root, nearer child first, and skips every node whose box is farther from the point than the
nearest surface point found so far (or than ``reach``); in a leaf each triangle is measured with
Ericson's region test, as ``meshrays._closest_on_triangles`` does in numpy.  So the work per
point follows the surface close to it, not the number of faces within ``reach``: a ball resting
on a finely subdivided surface measures the few faces under its contact point, where the numpy
path measured every face in a cube of side 2 ``reach``.  meshrays.py imports this module only
when numba is wanted and importable (``compiled.kernel_module``).
"""
from __future__ import annotations

import numpy as np
from numba import njit

_jit = njit(cache=True, nogil=True)

LEAF = 8


@_jit
def build(lo, hi):
    """The tree over boxes lo..hi (m, 3): (node_lo, node_hi, left, right, start, count, order);
    a leaf (left = -1) holds order[start:start + count]."""
    m = lo.shape[0]
    centre = 0.5 * (lo + hi)
    order = np.arange(m)
    capacity = 4 * (m // LEAF + 1) + 1     # every leaf holds over LEAF / 2 triangles
    node_lo = np.empty((capacity, 3))
    node_hi = np.empty((capacity, 3))
    left = np.full(capacity, -1, np.int64)
    right = np.full(capacity, -1, np.int64)
    start = np.zeros(capacity, np.int64)
    count = np.zeros(capacity, np.int64)
    stack = np.empty(128, np.int64)
    nodes = 1
    start[0], count[0] = 0, m
    stack[0] = 0
    top = 1
    while top > 0:
        top -= 1
        node = stack[top]
        s, n = start[node], count[node]
        for axis in range(3):
            node_lo[node, axis] = np.inf
            node_hi[node, axis] = -np.inf
        for k in range(s, s + n):
            t = order[k]
            for axis in range(3):
                node_lo[node, axis] = min(node_lo[node, axis], lo[t, axis])
                node_hi[node, axis] = max(node_hi[node, axis], hi[t, axis])
        if n <= LEAF:
            continue
        axis, widest = 0, -1.0
        for a in range(3):
            spread = node_hi[node, a] - node_lo[node, a]
            if spread > widest:
                axis, widest = a, spread
        keys = np.empty(n)
        for k in range(n):
            keys[k] = centre[order[s + k], axis]
        part = np.argsort(keys, kind="mergesort")
        chunk = order[s:s + n].copy()
        for k in range(n):
            order[s + k] = chunk[part[k]]
        half = n // 2
        left[node], right[node] = nodes, nodes + 1
        start[nodes], count[nodes] = s, half
        start[nodes + 1], count[nodes + 1] = s + half, n - half
        stack[top], stack[top + 1] = nodes, nodes + 1
        top += 2
        nodes += 2
    return node_lo[:nodes], node_hi[:nodes], left[:nodes], right[:nodes], start[:nodes], count[:nodes], order


@_jit
def _box_distance2(px, py, pz, lo, hi, node):
    gx = max(lo[node, 0] - px, px - hi[node, 0], 0.0)
    gy = max(lo[node, 1] - py, py - hi[node, 1], 0.0)
    gz = max(lo[node, 2] - pz, pz - hi[node, 2], 0.0)
    return gx * gx + gy * gy + gz * gz


@_jit
def _closest(p, a, b, c, out):
    """Closest point on triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5) into out."""
    ab = b - a
    ac = c - a
    ap = p - a
    d1 = ab[0] * ap[0] + ab[1] * ap[1] + ab[2] * ap[2]
    d2 = ac[0] * ap[0] + ac[1] * ap[1] + ac[2] * ap[2]
    if d1 <= 0.0 and d2 <= 0.0:
        out[:] = a
        return
    bp = p - b
    d3 = ab[0] * bp[0] + ab[1] * bp[1] + ab[2] * bp[2]
    d4 = ac[0] * bp[0] + ac[1] * bp[1] + ac[2] * bp[2]
    if d3 >= 0.0 and d4 <= d3:
        out[:] = b
        return
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        out[:] = a + ab * (d1 / (d1 - d3))
        return
    cp = p - c
    d5 = ab[0] * cp[0] + ab[1] * cp[1] + ab[2] * cp[2]
    d6 = ac[0] * cp[0] + ac[1] * cp[1] + ac[2] * cp[2]
    if d6 >= 0.0 and d5 <= d6:
        out[:] = c
        return
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        out[:] = a + ac * (d2 / (d2 - d6))
        return
    va = d3 * d6 - d5 * d4
    if va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0:
        out[:] = b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))
        return
    denom = 1.0 / (va + vb + vc)
    out[:] = a + ab * (vb * denom) + ac * (vc * denom)


@_jit
def nearest(points, reach, a, b, c, lo, hi, node_lo, node_hi, left, right, start, count, order):
    """(distance, closest point) of each point: the nearest surface point when it lies within
    ``reach``, else (inf, the point itself).  The search starts from the triangle nearest to the
    previous point (points come along paths, so it is usually near again): a tight bound at once."""
    n = points.shape[0]
    distance = np.full(n, np.inf)
    closest = points.copy()
    stack = np.empty(256, np.int64)
    here = np.empty(3)
    reach2 = reach * reach
    last = -1
    for i in range(n):
        p = points[i]
        best2 = reach2
        found = False
        if last >= 0:
            _closest(p, a[last], b[last], c[last], here)
            d2 = (here[0] - p[0]) ** 2 + (here[1] - p[1]) ** 2 + (here[2] - p[2]) ** 2
            if d2 <= best2:
                best2 = d2
                found = True
                closest[i, 0], closest[i, 1], closest[i, 2] = here[0], here[1], here[2]
        top = 0
        if _box_distance2(p[0], p[1], p[2], node_lo, node_hi, 0) <= best2:
            stack[0] = 0
            top = 1
        while top > 0:
            top -= 1
            node = stack[top]
            if _box_distance2(p[0], p[1], p[2], node_lo, node_hi, node) > best2:
                continue
            if left[node] < 0:
                for k in range(start[node], start[node] + count[node]):
                    t = order[k]
                    if _box_distance2(p[0], p[1], p[2], lo, hi, t) > best2:
                        continue
                    _closest(p, a[t], b[t], c[t], here)
                    d2 = (here[0] - p[0]) ** 2 + (here[1] - p[1]) ** 2 + (here[2] - p[2]) ** 2
                    if d2 < best2 or (not found and d2 <= best2):
                        best2 = d2
                        found = True
                        last = t
                        closest[i, 0], closest[i, 1], closest[i, 2] = here[0], here[1], here[2]
                continue
            near, far = left[node], right[node]
            dn = _box_distance2(p[0], p[1], p[2], node_lo, node_hi, near)
            df = _box_distance2(p[0], p[1], p[2], node_lo, node_hi, far)
            if dn > df:
                near, far, dn, df = far, near, df, dn
            if df <= best2:
                stack[top] = far
                top += 1
            if dn <= best2:
                stack[top] = near
                top += 1
        if found:
            distance[i] = np.sqrt(best2)
    return distance, closest
