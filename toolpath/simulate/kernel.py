"""Compiled height-field kernels (numba): the closed forms of the numpy path (families.py),
evaluated item by item and grid column by column straight into the flat height array,
with no index or value arrays in between.

Each step is done as the numpy path does it, in the same order and precision: the
y-intervals and per-run constants in float64, the values along a run of cells in float32.
So both kernels write the same heights, and the safety checks, which run on the numpy
path, see the same stock.  heightfield.py imports this module only when numba is wanted
and importable.

``grid`` is (ny, x0, y0, cell_x, cell_y) of the height field; ``flat`` its heights, row
major (cell (i, j) at i * ny + j); ``c0``, ``ncol`` the first grid column and number of
columns of each item; ``eps`` the widening of every region (families.``_EPS``).
"""
from __future__ import annotations

import numpy as np
from numba import njit

_jit = njit(cache=True, nogil=True)


# ----- y-intervals, as simulate's _halfline, _sqrt_condition, _pieces, _disk_span ------------------

@_jit
def _halfline(a, b):
    """Where a + b*y >= 0: (lo, hi), possibly everything or nothing."""
    if b > 1e-15:
        return -a / b, np.inf
    if b < -1e-15:
        return -np.inf, -a / b
    if a >= 0:
        return -np.inf, np.inf
    return np.inf, -np.inf


@_jit
def _sqrt_condition(a, b, c, q, p, g, dlo, dhi):
    """Where a + b*y >= c * sqrt(q - (p + g*y)^2) in [dlo, dhi]: (lo, hi, hole_lo, hole_hi)."""
    h_lo, h_hi = _halfline(a, b)
    h_lo = max(h_lo, dlo)
    h_hi = min(h_hi, dhi)
    c2 = c * c
    qa = b * b + c2 * g * g
    qb = 2.0 * (a * b + c2 * p * g)
    qc = a * a + c2 * (p * p - q)
    disc = qb * qb - 4.0 * qa * qc
    r1 = np.inf
    r2 = -np.inf
    if disc >= 0 and qa > 1e-30 and abs(c) > 1e-12:
        s = np.sqrt(disc)
        r1 = (-qb - s) / (2.0 * qa)
        r2 = (-qb + s) / (2.0 * qa)
    lo, hi = h_lo, h_hi
    if c < -1e-12:
        if h_lo > h_hi:
            lo, hi = r1, r2
        else:
            lo, hi = min(h_lo, r1), max(h_hi, r2)
    if c > 1e-12:
        return lo, hi, r1, r2
    return lo, hi, np.inf, -np.inf


@_jit
def _pieces(dlo, dhi, first, second, eps):
    """The domain cut by two conditions: two (lo, hi) pieces as (lo1, hi1, lo2, hi2)."""
    lo = max(max(dlo, first[0]), second[0])
    hi = min(min(dhi, first[1]), second[1])
    hole_lo, hole_hi = first[2], first[3]
    if hole_lo >= hole_hi:
        hole_lo, hole_hi = second[2], second[3]
    lo = lo - eps
    hi = hi + eps
    if hole_lo + eps < hole_hi - eps:
        return lo, min(hi, hole_lo + eps), max(lo, hole_hi - eps), hi
    return lo, hi, np.inf, -np.inf


@_jit
def _disk_span(dx, r):
    if abs(dx) <= r:
        half = np.sqrt(max(r * r - dx * dx, 0.0))
        return -half, half
    return np.inf, -np.inf


@_jit
def _band_intervals(dx, ux, uy, length, s, r, eps):
    """Cells of a band in one column, as families._band_intervals: |e| <= r and
    0 <= q - s*sqrt(r^2 - e^2) <= length, with q = dx*ux + dy*uy, e = dy*ux - dx*uy."""
    if abs(ux) > 1e-12:
        e1 = (-r + dx * uy) / ux
        e2 = (r + dx * uy) / ux
        dlo, dhi = min(e1, e2), max(e1, e2)
    elif abs(dx * uy) <= r:
        dlo, dhi = -np.inf, np.inf          # a move along Y, within reach of the column
    else:
        dlo, dhi = np.inf, -np.inf
    p = -dx * uy
    rr = r * r
    start = _sqrt_condition(dx * ux, uy, s, rr, p, ux, dlo, dhi)
    end = _sqrt_condition(length - dx * ux, -uy, -s, rr, p, ux, dlo, dhi)
    return _pieces(dlo, dhi, start, end, eps)


@_jit
def _band_side_interval(dx, ux, uy, length, mu, w, side, eps):
    """Cells of one side of a cone or level band in one column, as families._band_side_interval."""
    lo, hi = -np.inf, np.inf
    start = dx * (ux + side * mu * uy)
    slant = uy - side * mu * ux
    for a, b in ((-side * dx * uy, side * ux), (w + side * dx * uy, -side * ux), (start, slant),
                 (length - start, -slant)):
        side_lo, side_hi = _halfline(a, b)
        lo, hi = max(lo, side_lo), min(hi, side_hi)
    return lo - eps, hi + eps


@_jit
def _vertex_intervals(dx, d1x, d1y, dz1, d2x, d2y, dz2, r, eps):
    """Cells of a vertex sphere in one column, as families._SphereVertices.intervals."""
    dlo, dhi = _disk_span(dx, r)
    q = r * r - dx * dx
    incoming = _sqrt_condition(dx * d1x, d1y, dz1, q, 0.0, 1.0, dlo, dhi)
    outgoing = _sqrt_condition(-dx * d2x, -d2y, -dz2, q, 0.0, 1.0, dlo, dhi)
    return _pieces(dlo, dhi, incoming, outgoing, eps)


@_jit
def _rows(oy, lo, hi, grid):
    """The grid rows whose centres lie in oy + [lo, hi]: (first, count)."""
    ny, _, y0, _, cell_y = grid
    first = min(max(np.ceil((oy + lo - y0) / cell_y - 0.5), 0.0), float(ny))
    last = min(max(np.floor((oy + hi - y0) / cell_y - 0.5), -1.0), float(ny - 1))
    return int(first), int(last) - int(first) + 1


@_jit
def _dx(col, ox, grid):
    _, x0, _, cell_x, _ = grid
    return x0 + (col + 0.5) * cell_x - ox


@_jit
def _dy0(first, oy, grid):
    _, _, y0, _, cell_y = grid
    return y0 + (first + 0.5) * cell_y - oy


# ----- the item families -------------------------------------------------------------------------

@_jit
def cut_bands(flat, grid, eps, c0, ncol, ox, oy, ux, uy, length, s, z, a, b, r):
    """Bands (families._Bands): value = z + a*q - b*sqrt(r^2 - e^2)."""
    ny, _, _, _, cell_y = grid
    for k in range(len(ox)):
        rb = np.float32(r[k] * b[k])
        e_step = np.float32(cell_y * ux[k] * b[k])
        z_step = np.float32(cell_y * uy[k] * a[k])
        for col in range(c0[k], c0[k] + ncol[k]):
            dx = _dx(col, ox[k], grid)
            lo1, hi1, lo2, hi2 = _band_intervals(dx, ux[k], uy[k], length[k], s[k], r[k], eps)
            for lo, hi in ((lo1, hi1), (lo2, hi2)):
                first, count = _rows(oy[k], lo, hi, grid)
                dy0 = _dy0(first, oy[k], grid)
                e0 = np.float32((dy0 * ux[k] - dx * uy[k]) * b[k])
                z0 = np.float32((dx * ux[k] + dy0 * uy[k]) * a[k] + z[k])
                cells = flat[col * ny + first:col * ny + first + count]
                for j in range(count):
                    jf = np.float32(j)
                    e = jf * e_step + e0
                    cells[j] = min(cells[j], jf * z_step + z0 - np.sqrt(np.abs(rb * rb - e * e)))


@_jit
def cut_cone_bands(flat, grid, eps, c0, ncol, ox, oy, ux, uy, length, z, a, g, mu, w):
    """Cone bands (families._ConeBands): value = z + a*q + g*|e|."""
    ny, _, _, _, cell_y = grid
    for k in range(len(ox)):
        e_step = np.float32(cell_y * ux[k])
        z_step = np.float32(cell_y * uy[k] * a[k])
        rise = np.float32(g[k])
        for col in range(c0[k], c0[k] + ncol[k]):
            dx = _dx(col, ox[k], grid)
            for side in (1.0, -1.0):
                lo, hi = _band_side_interval(dx, ux[k], uy[k], length[k], mu[k], w[k], side, eps)
                first, count = _rows(oy[k], lo, hi, grid)
                dy0 = _dy0(first, oy[k], grid)
                e0 = np.float32(dy0 * ux[k] - dx * uy[k])
                z0 = np.float32((dx * ux[k] + dy0 * uy[k]) * a[k] + z[k])
                cells = flat[col * ny + first:col * ny + first + count]
                for j in range(count):
                    jf = np.float32(j)
                    cells[j] = min(cells[j], (jf * z_step + z0) + np.abs(jf * e_step + e0) * rise)


@_jit
def cut_level_bands(flat, grid, eps, c0, ncol, ox, oy, ux, uy, length, z, radius, tip_tan, corner, flat_radius):
    """Level bands (families._LevelBands): value = z + profile(|e|)."""
    ny, _, _, _, cell_y = grid
    reach = np.float32(radius)
    for k in range(len(ox)):
        e_step = np.float32(cell_y * ux[k])
        tip = np.float32(z[k])
        for col in range(c0[k], c0[k] + ncol[k]):
            dx = _dx(col, ox[k], grid)
            for side in (1.0, -1.0):
                lo, hi = _band_side_interval(dx, ux[k], uy[k], length[k], 0.0, radius, side, eps)
                first, count = _rows(oy[k], lo, hi, grid)
                e0 = np.float32(_dy0(first, oy[k], grid) * ux[k] - dx * uy[k])
                cells = flat[col * ny + first:col * ny + first + count]
                for j in range(count):
                    d = min(np.abs(np.float32(j) * e_step + e0), reach)
                    cells[j] = min(cells[j], _profile(d, tip_tan, corner, flat_radius) + tip)


@_jit
def cut_sphere_vertices(flat, grid, eps, c0, ncol, ox, oy, d1x, d1y, dz1, d2x, d2y, dz2, z, r):
    """Vertex spheres (families._SphereVertices): value = centre z - sqrt(r^2 - |D|^2)."""
    ny, _, _, _, cell_y = grid
    step = np.float32(cell_y)
    for k in range(len(ox)):
        centre = np.float32(z[k])
        for col in range(c0[k], c0[k] + ncol[k]):
            dx = _dx(col, ox[k], grid)
            lo1, hi1, lo2, hi2 = _vertex_intervals(dx, d1x[k], d1y[k], dz1[k], d2x[k], d2y[k], dz2[k], r[k], eps)
            across = np.float32(np.sqrt(max(r[k] * r[k] - dx * dx, 0.0)))   # the sphere's half chord
            for lo, hi in ((lo1, hi1), (lo2, hi2)):
                first, count = _rows(oy[k], lo, hi, grid)
                dy0 = np.float32(_dy0(first, oy[k], grid))
                cells = flat[col * ny + first:col * ny + first + count]
                for j in range(count):
                    dy = np.float32(j) * step + dy0
                    cells[j] = min(cells[j], centre - np.sqrt(np.abs(across * across - dy * dy)))


@_jit
def _profile(d, tip_tan, corner, flat_radius):
    """tools.ToolShape.height_at in float32: a cone if tip_tan > 0, else a disc rounded by corner."""
    if tip_tan > 0:
        return d / np.float32(tip_tan)
    off = max(d - np.float32(flat_radius), np.float32(0.0))
    return np.float32(corner) - np.sqrt(max(np.float32(corner * corner) - off * off, np.float32(0.0)))


@_jit
def cut_stamps(flat, grid, eps, c0, ncol, ox, oy, z, radius, tip_tan, corner, flat_radius):
    """Whole-tool stamps (families._Stamps): value = tip z + profile(|D|)."""
    ny, _, _, _, cell_y = grid
    step = np.float32(cell_y)
    reach = np.float32(radius)
    for k in range(len(ox)):
        tip = np.float32(z[k])
        for col in range(c0[k], c0[k] + ncol[k]):
            dx = _dx(col, ox[k], grid)
            dlo, dhi = _disk_span(dx, radius)
            first, count = _rows(oy[k], dlo - eps, dhi + eps, grid)
            dy0 = np.float32(_dy0(first, oy[k], grid))
            dx2 = np.float32(dx * dx)
            cells = flat[col * ny + first:col * ny + first + count]
            for j in range(count):
                dy = np.float32(j) * step + dy0
                d = min(np.sqrt(dy * dy + dx2), reach)
                cells[j] = min(cells[j], _profile(d, tip_tan, corner, flat_radius) + tip)


# ----- radius map (radiusmap.py): radial ball stamps --------------------------------------------------

@_jit
def cut_radial_balls(flat, n_theta, n_z, z0, cell_z, cell_theta, rho, phi, zc, radius, limit):
    """radiusmap.entry_radii + minimum, stamp by stamp: each dexel the ball reaches keeps the
    smaller of its radius and the ray's entry into the ball (0 where the ray starts inside).
    Balls beyond ``limit`` (the bar's radius) are skipped.  The angle steps by rotation, so the
    entries agree with the numpy path's to rounding (about 1e-12 mm), not bit for bit."""
    r2 = radius * radius
    cos_step, sin_step = np.cos(cell_theta), np.sin(cell_theta)
    for s in range(len(rho)):
        if rho[s] - radius >= limit:
            continue                        # the whole ball is outside the bar
        k0 = max(int(np.ceil((zc[s] - radius - z0) / cell_z - 0.5)), 0)
        k1 = min(int(np.floor((zc[s] + radius - z0) / cell_z - 0.5)), n_z - 1)
        for k in range(k0, k1 + 1):
            dz = z0 + (k + 0.5) * cell_z - zc[s]
            w2 = r2 - dz * dz
            if w2 <= 0:
                continue
            ratio = np.sqrt(w2) / max(abs(rho[s]), 1e-12)
            half = np.pi if ratio >= 1.0 else np.arcsin(ratio)
            centre = phi[s] if rho[s] >= 0 else phi[s] + np.pi
            i0 = int(np.ceil((centre - half) / cell_theta - 0.5))
            i1 = int(np.floor((centre + half) / cell_theta - 0.5))
            count = min(max(i1 - i0 + 1, 0), n_theta)
            # No ray of the row enters the ball nearer the axis than |rho| - sqrt(w2): a row whose
            # material lies inside that everywhere is left as it is (a margin far above rounding).
            nearest = abs(rho[s]) - np.sqrt(w2) - 1e-9
            i = i0 % n_theta
            deeper = False
            for _ in range(count):
                if flat[i * n_z + k] > nearest:
                    deeper = True
                    break
                i += 1
                if i == n_theta:
                    i = 0
            if not deeper:
                continue
            # cos and sin of the angle from the ball's plane, cell after cell by rotation
            d = (i0 + 0.5) * cell_theta - phi[s]
            cos_d, sin_d = np.cos(d), np.sin(d)
            rho2 = rho[s] * rho[s]
            i = i0 % n_theta
            for _ in range(count):
                entry = rho[s] * cos_d - np.sqrt(max(w2 - rho2 * sin_d * sin_d, 0.0))
                index = i * n_z + k
                if entry < flat[index]:
                    flat[index] = max(entry, 0.0)
                cos_d, sin_d = cos_d * cos_step - sin_d * sin_step, sin_d * cos_step + cos_d * sin_step
                i += 1
                if i == n_theta:
                    i = 0


@_jit
def outer_rays(out, n_theta, n_z, k, i0, count, ex, ey, numerator, cos_t, sin_t, first):
    """radiusmap.outer_radii's rays, segment by segment: segment s of row ``k[s]`` (from a, edge
    (ex, ey), numerator a x e) meets the rays i0[s] .. i0[s] + count[s] - 1 (angles of the table
    ``cos_t``, ``sin_t`` from ray ``first``) at radius numerator / (u x e); the largest radius
    (at least 0) of every ray is kept in ``out``.  The numpy path's arithmetic, so the same radii."""
    for s in range(len(k)):
        for j in range(count[s]):
            i = i0[s] + j
            denominator = cos_t[i - first] * ey[s] - sin_t[i - first] * ex[s]
            radius = numerator[s] / denominator if abs(denominator) > 1e-12 else 0.0
            index = (i % n_theta) * n_z + k[s]
            value = max(radius, 0.0)
            if value > out[index]:
                out[index] = value
