"""Compiled drop-cutter kernel (numba): the closed forms of dropcutter.py, point by point.

For each query point the kernel walks the triangles of the point's bucket in order of falling
top Z and stops as soon as a triangle's highest vertex is no higher than the tool tip found so
far (a triangle cannot lift the tool above its own top: every tool's underside is at or above
its tip).  Within a triangle, a bull nose's edge that cannot lift the tip above the best so
far is skipped, and its bisection stops early where a bound says so; both skip only
what cannot raise the best, so every tip is bit for bit what the search without them gives.
Each triangle is tested as dropcutter.py's numpy path tests it: its three vertices, its facet
(the support point of the tool in the facet's gradient direction, when it falls inside the
triangle) and its three edges (the concave 1-D maximum along the edge, clamped to the part of
the edge under the tool).  dropcutter.py imports this module only when numba is wanted and
importable.

Tool codes and parameters (``prof``): kind 0 rounded (flat radius ``fr`` + corner ``rc``:
ball, flat, bull nose), 1 cone (``k`` = 1 / tan(half angle), radius ``R``).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

_jit = njit(cache=True, nogil=True)

ROUNDED, CONE = 0, 1
BISECTIONS = 64
PROBE = 6           # bull nose edges: bisection steps before the bound that may skip the rest
SLACK = 1e-12       # relative room for rounding in that bound
STEEP = 1e3         # the bound is used where the corner's slope is at most this


@_jit
def height(kind, R, rc, fr, k, d):
    """Height of the tool's underside above its tip at distance d (d <= R)."""
    if kind == CONE:
        return k * d
    if d <= fr:
        return 0.0
    off = d - fr
    return rc - math.sqrt(max(rc * rc - off * off, 0.0))


@_jit
def slope(kind, R, rc, fr, k, d):
    """dh/dd, the underside's slope at distance d (inf at the rim of a flat or bull nose)."""
    if kind == CONE:
        return k
    if d <= fr:
        return 0.0
    off = d - fr
    q = rc * rc - off * off
    if q <= 0.0:
        return np.inf
    return off / math.sqrt(q)


@_jit
def support(kind, R, rc, fr, k, g):
    """Distance from the axis of the point where the tool touches a plane of gradient g
    (|grad z|) first, as dropcutter.facet_support."""
    if kind == CONE:
        return 0.0 if g <= k else R
    if g <= 0.0:
        return 0.0
    if rc <= 0.0:
        return R
    return fr + rc * g / math.sqrt(1.0 + g * g)


@_jit
def edge_best(kind, R, rc, fr, k, m, t, ua, ub):
    """The u in [ua, ub] where z0 + m*u - h(sqrt(t^2 + u^2)) is largest (a concave function)."""
    if kind == CONE:
        if abs(m) < k:
            u = m * t / math.sqrt(k * k - m * m)
        else:
            u = np.inf if m > 0 else -np.inf
    elif rc <= 0.0:                      # flat: linear along the edge
        u = np.inf if m > 0 else (-np.inf if m < 0 else ua)
    elif fr <= 0.0:                      # ball
        u = m * math.sqrt(max(rc * rc - t * t, 0.0) / (1.0 + m * m))
    else:                                # bull nose: bisection on the falling derivative
        if _edge_derivative(kind, R, rc, fr, k, m, t, ua) <= 0.0:
            return ua
        if _edge_derivative(kind, R, rc, fr, k, m, t, ub) >= 0.0:
            return ub
        lo, hi = bisect(kind, R, rc, fr, k, m, t, ua, ub, BISECTIONS)
        u = 0.5 * (lo + hi)
    return min(max(u, ua), ub)


@_jit
def bisect(kind, R, rc, fr, k, m, t, lo, hi, steps):
    """``steps`` halvings of [lo, hi] towards the root of the falling edge derivative.  Once
    the midpoint rounds to an end of the interval, the interval after that step is the one every
    further step leaves as it is, so it stops there: the same (lo, hi) as all the steps."""
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        stuck = mid == lo or mid == hi
        if _edge_derivative(kind, R, rc, fr, k, m, t, mid) > 0.0:
            lo = mid
        else:
            hi = mid
        if stuck:
            break
    return lo, hi


@_jit
def _bull_edge(R, rc, fr, m, t, ua, ub, z0, s0, best):
    """edge_best for a bull nose (kind 0, rc > 0, fr > 0), or NaN when the edge cannot lift
    the tip above ``best``.  After PROBE of the bisection's steps the top is in [lo, hi], and
    over a concave function it is below both tangents there: f(lo) + f'(lo) (hi - lo) and
    f(hi) - f'(hi) (hi - lo).  Where that bound, with room for rounding (SLACK, and a share of
    the tangents' rise: the derivative is less exact where the corner turns steep, so only below
    STEEP), stays at or below ``best``, the other steps are skipped; else they run from there,
    which is the same bisection as edge_best's."""
    if _edge_derivative(ROUNDED, R, rc, fr, 0.0, m, t, ua) <= 0.0:
        return ua
    if _edge_derivative(ROUNDED, R, rc, fr, 0.0, m, t, ub) >= 0.0:
        return ub
    lo, hi = bisect(ROUNDED, R, rc, fr, 0.0, m, t, ua, ub, PROBE)
    dlo = math.sqrt(t * t + lo * lo)
    dhi = math.sqrt(t * t + hi * hi)
    if slope(ROUNDED, R, rc, fr, 0.0, dlo) <= STEEP and slope(ROUNDED, R, rc, fr, 0.0, dhi) <= STEEP:
        width = hi - lo
        rise_lo = _edge_derivative(ROUNDED, R, rc, fr, 0.0, m, t, lo) * width
        rise_hi = -_edge_derivative(ROUNDED, R, rc, fr, 0.0, m, t, hi) * width
        f_lo = z0 + m * (s0 + lo) - height(ROUNDED, R, rc, fr, 0.0, min(dlo, R))
        f_hi = z0 + m * (s0 + hi) - height(ROUNDED, R, rc, fr, 0.0, min(dhi, R))
        bound = min(f_lo + rise_lo, f_hi + rise_hi)
        if bound + SLACK * (1.0 + abs(f_lo) + abs(f_hi)) + 1e-5 * (abs(rise_lo) + abs(rise_hi)) <= best:
            return np.nan
    lo, hi = bisect(ROUNDED, R, rc, fr, 0.0, m, t, lo, hi, BISECTIONS - PROBE)
    return min(max(0.5 * (lo + hi), ua), ub)


@_jit
def _edge_derivative(kind, R, rc, fr, k, m, t, u):
    d = math.sqrt(t * t + u * u)
    if d <= 0.0:
        return m
    return m - slope(kind, R, rc, fr, k, d) * u / d


@_jit
def triangle_drop(kind, R, rc, fr, k, cx, cy, tri, plane, pre, best):
    """The highest tool tip over (cx, cy) that touches triangle ``tri`` (3, 3), if above ``best``.
    ``pre`` holds what depends on the triangle and the tool only (dropcutter.precomputed): the
    facet's contact offset from the axis and the tool's height there, and per edge its XY unit
    direction, XY length and slope.  The facet first (most often the contact on a smooth
    surface), then the edges and vertices, each skipped when its highest point is no higher
    than the best tip so far (a bull nose's edge also when its highest point under the tool,
    less the tool's height at the edge's distance from the axis, is no higher: that bound is
    rounded as the edge's own tip is, so it never skips a higher one)."""
    R2 = R * R
    if plane[3] > 0.0:                  # not a vertical facet
        x = cx + pre[0]
        y = cy + pre[1]
        inside = True
        sign = plane[4]
        for e in range(3):
            p = tri[e]
            q = tri[(e + 1) % 3]
            if sign * ((q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0])) < 0.0:
                inside = False
                break
        if inside:
            z = plane[2] + plane[0] * x + plane[1] * y - pre[2]
            if z > best:
                best = z
    for e in range(3):
        p = tri[e]
        q = tri[(e + 1) % 3]
        if max(p[2], q[2]) <= best:
            continue
        length = pre[5 + 4 * e]
        if length <= 1e-12:
            continue
        ux = pre[3 + 4 * e]
        uy = pre[4 + 4 * e]
        wx = cx - p[0]
        wy = cy - p[1]
        s0 = wx * ux + wy * uy
        t = abs(wx * uy - wy * ux)
        if t > R:
            continue
        w = math.sqrt(R2 - t * t)
        ua = max(-s0, -w)
        ub = min(length - s0, w)
        if ua > ub:
            continue
        m = pre[6 + 4 * e]
        if kind == CONE or rc <= 0.0 or fr <= 0.0:
            u = edge_best(kind, R, rc, fr, k, m, t, ua, ub)
        else:
            # a bull nose bisects: first, the edge under the tool rises to its end uphill, and
            # the tool's underside is at least h(t) above the tip there, so the tip is no higher
            # than that (each step rounds no lower than the same step of the tip's formula below)
            top = p[2] + m * (s0 + (ub if m > 0.0 else ua))
            if top - height(kind, R, rc, fr, k, min(math.sqrt(t * t), R)) <= best:
                continue
            u = _bull_edge(R, rc, fr, m, t, ua, ub, p[2], s0, best)
            if math.isnan(u):
                continue
        z = p[2] + m * (s0 + u) - height(kind, R, rc, fr, k, min(math.sqrt(t * t + u * u), R))
        if z > best:
            best = z
    for v in range(3):
        if tri[v, 2] <= best:
            continue                    # h >= 0: a vertex lifts the tip to at most its own Z
        dx = tri[v, 0] - cx
        dy = tri[v, 1] - cy
        d2 = dx * dx + dy * dy
        if d2 <= R2:
            z = tri[v, 2] - height(kind, R, rc, fr, k, math.sqrt(d2))
            if z > best:
                best = z
    return best


@_jit
def drop_points(px, py, out, tris, planes, pre, zmax, bbox, start, entries, grid, prof):
    """out[i] = the highest tip Z over (px[i], py[i]) (out holds the floor on entry)."""
    kind = int(prof[0])
    R, rc, fr, k = prof[1], prof[2], prof[3], prof[4]
    bx0, by0, size = grid[0], grid[1], grid[2]
    nbx, nby = int(grid[3]), int(grid[4])
    for i in range(len(px)):
        cx = px[i]
        cy = py[i]
        fi = (cx - bx0) / size
        fj = (cy - by0) / size
        if not (fi >= 0.0 and fj >= 0.0 and fi < nbx and fj < nby):
            continue
        b = int(fi) * nby + int(fj)
        best = out[i]
        for n in range(start[b], start[b + 1]):
            t = entries[n]
            if zmax[t] <= best:
                break                   # sorted by falling top Z: nothing further can lift the tool
            if cx < bbox[t, 0] or cx > bbox[t, 2] or cy < bbox[t, 1] or cy > bbox[t, 3]:
                continue
            # the triangle's XY box is ``R`` inside the grown one: no part of the triangle is
            # nearer the axis than the box, so it lifts the tip to at most zmax - h(that distance)
            gx = max(bbox[t, 0] + R - cx, cx - (bbox[t, 2] - R), 0.0)
            gy = max(bbox[t, 1] + R - cy, cy - (bbox[t, 3] - R), 0.0)
            near2 = gx * gx + gy * gy
            if near2 > R * R or zmax[t] - height(kind, R, rc, fr, k, math.sqrt(near2)) <= best:
                continue
            best = triangle_drop(kind, R, rc, fr, k, cx, cy, tris[t], planes[t], pre[t], best)
        out[i] = best
