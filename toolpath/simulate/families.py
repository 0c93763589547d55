"""The height field's regions: per chain, the bands beside its moves, the spheres at its
points and the whole-tool stamps whose union is the chain's exact lower envelope, and for each
the cells it covers, column by column (roots of quadratics), and its values there."""
from __future__ import annotations

import math

import numpy as np

from .paths import Chain
from .stock import HeightField

# A move shorter than this in XY is taken as vertical: its ends are stamped whole instead.
MIN_XY_LENGTH = 1e-3
_EPS = 1e-6                # mm: regions are widened by this so no cell falls between two of them
MAX_CONE_MU = 300.0        # the steepest cone band kept (|a|/g; see the cone bands in families_of)


def _ring_count(flat_radius: float, corner_radius: float, tolerance: float) -> int:
    """Spheres on the torus ring so that a ring of them stays within ``tolerance`` of the torus:
    at the inner edge of the corner the underside sags (a*d/2)^2 / (2 r) between two spheres
    (d = 2 pi / N), at the rim the reach falls short by about (a/8)(1 + a/r) d^2."""
    a, r = flat_radius, corner_radius
    if a <= 0:
        return 1
    step = min(2 * math.sqrt(2 * r * tolerance) / a, math.sqrt(8 * tolerance / (a * (1 + a / r))))
    return int(min(max(math.ceil(2 * math.pi / step), 8), 720))


# ----- height field: cells of a region, column by column -----------------------------------

def halfline(a, b):
    """Where a + b*y >= 0: (lo, hi), possibly everything or nothing."""
    with np.errstate(divide="ignore", invalid="ignore"):
        root = -a / b
    up = b > 1e-15
    down = b < -1e-15
    level_ok = ~(up | down) & (a >= 0)
    lo = np.where(up, root, np.where(down | level_ok, -np.inf, np.inf))
    hi = np.where(down, root, np.where(up | level_ok, np.inf, -np.inf))
    return lo, hi


def _sqrt_condition(a, b, c, q, p, g, dlo, dhi):
    """Where a + b*y >= c * sqrt(q - (p + g*y)^2), for y in the domain [dlo, dhi].

    The answer is an interval minus an open hole: (lo, hi, hole_lo, hole_hi).  With c <= 0
    the set is a single interval, with c > 0 it is the half-line a + b*y >= 0 outside the
    roots of (a + b*y)^2 = c^2 (q - (p + g*y)^2)."""
    h_lo, h_hi = halfline(a, b)
    h_lo = np.maximum(h_lo, dlo)
    h_hi = np.minimum(h_hi, dhi)
    c2 = c * c
    qa = b * b + c2 * g * g
    qb = 2.0 * (a * b + c2 * p * g)
    qc = a * a + c2 * (p * p - q)
    disc = qb * qb - 4.0 * qa * qc
    real = (disc >= 0) & (qa > 1e-30) & (np.abs(c) > 1e-12)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.sqrt(np.where(real, disc, 0.0))
        r1 = np.where(real, (-qb - s) / (2.0 * qa), np.inf)
        r2 = np.where(real, (-qb + s) / (2.0 * qa), -np.inf)
    falls = c < -1e-12
    rises = c > 1e-12
    half_empty = h_lo > h_hi
    lo = np.where(falls, np.where(half_empty, r1, np.minimum(h_lo, r1)), h_lo)
    hi = np.where(falls, np.where(half_empty, r2, np.maximum(h_hi, r2)), h_hi)
    hole_lo = np.where(rises, r1, np.inf)
    hole_hi = np.where(rises, r2, -np.inf)
    return lo, hi, hole_lo, hole_hi


def _pieces(dlo, dhi, conditions):
    """Intersect a domain with conditions from _sqrt_condition: up to two (lo, hi) pieces.

    Where two conditions both have holes only the first is kept (a superset, used only for
    tool positions, whose values are right anywhere)."""
    lo, hi = dlo, dhi
    hole_lo = np.full_like(dlo, np.inf)
    hole_hi = np.full_like(dlo, -np.inf)
    for c_lo, c_hi, c_hole_lo, c_hole_hi in conditions:
        lo = np.maximum(lo, c_lo)
        hi = np.minimum(hi, c_hi)
        free = hole_lo >= hole_hi
        hole_lo = np.where(free, c_hole_lo, hole_lo)
        hole_hi = np.where(free, c_hole_hi, hole_hi)
    lo = lo - _EPS
    hi = hi + _EPS
    hole = (hole_lo + _EPS) < (hole_hi - _EPS)
    first_hi = np.where(hole, np.minimum(hi, hole_lo + _EPS), hi)
    second_lo = np.where(hole, np.maximum(lo, hole_hi - _EPS), np.inf)
    second_hi = np.where(hole, hi, -np.inf)
    return [(lo, first_hi), (second_lo, second_hi)]


def _disk_span(dx, r):
    half = np.sqrt(np.maximum(r * r - dx * dx, 0.0))
    inside = np.abs(dx) <= r
    return np.where(inside, -half, np.inf), np.where(inside, half, -np.inf)


class Family:
    """Items of one kind (bands or tool positions): their reference point (ox, oy), the
    segment each belongs to, and named per-item arrays.

    A subclass gives the x and y ranges of its items, their y-intervals per grid column and
    their values over runs of cells (the numpy kernel), and ``cut``: the same through the
    compiled kernel (kernel.py), min-written straight into the flat heights."""

    def __init__(self, segment, ox, oy, **arrays):
        # contiguous float arrays: the compiled kernels then need one signature each
        self.segment = np.asarray(segment)
        self.ox = np.ascontiguousarray(ox, float)
        self.oy = np.ascontiguousarray(oy, float)
        self.arrays = {k: np.ascontiguousarray(v, float) for k, v in arrays.items()}

    def __len__(self):
        return len(self.segment)

    def __getattr__(self, name):
        try:
            return self.__dict__["arrays"][name]
        except KeyError:
            raise AttributeError(name)

    def take(self, sel) -> "Family":
        clone = object.__new__(type(self))
        clone.__dict__.update(self.__dict__)
        clone.segment = self.segment[sel]
        clone.ox = self.ox[sel]
        clone.oy = self.oy[sel]
        clone.arrays = {k: v[sel] for k, v in self.arrays.items()}
        return clone


def _row(values):
    """Per-run values as a float32 row, broadcast down the cells of each run."""
    return np.asarray(values, np.float32)[None, :]


class _Bands(Family):
    """Cells beside a move whose lowest value lies strictly inside it, where

        value = z + a*q - b*sqrt(r^2 - e^2)

    with q the distance along the move from its start, e across it, both in XY, and the band
    0 <= q - s*sqrt(r^2 - e^2) <= length.  Two tools use this:

    * ball (the cylinder part of the capsule): z = centre Z at the start, a = dz/l,
      b = L/l, s = dz/L (l the XY length, L the 3-D length);
    * flat disc (moves turned to run downhill, so the disc's rim leaves a cell at its lowest):
      z = tip Z at the start, a = dz/l, b = -dz/l, s = -1.

    Arrays: ux, uy (unit XY direction), length, s, z, a, b, r."""

    def xrange(self):
        return _band_span(self.ox, self.ux, self.uy, self.length, self.r * np.minimum(self.s, 0),
                          self.r * np.maximum(self.s, 0), self.r)

    def yrange(self):
        ends = self.oy + self.uy * self.length
        return np.minimum(self.oy, ends) - self.r - _EPS, np.maximum(self.oy, ends) + self.r + _EPS

    def intervals(self, k, dx):
        return _band_intervals(dx, self.ux[k], self.uy[k], self.length[k], self.s[k], self.r[k])

    def values(self, k, dx, dy0, cell_y, j, out, tmp):
        ux, uy, a, b, r = (self.arrays[n][k] for n in ("ux", "uy", "a", "b", "r"))
        # e*b and z + a*q are affine in the cell number j along the run (dy = dy0 + j*cell_y).
        np.multiply(j, _row(cell_y * ux * b), out=tmp)
        tmp += _row((dy0 * ux - dx * uy) * b)
        _sqrt_of_r2_minus_square(tmp, _row(r * b))         # b >= 0 for both tools
        np.multiply(j, _row(cell_y * uy * a), out=out)
        out += _row((dx * ux + dy0 * uy) * a + self.z[k])
        out -= tmp

    def cut(self, kernels, flat, hf):
        kernels.cut_bands(flat, _kernel_grid(hf), _EPS, *family_columns(hf, self), self.ox, self.oy, self.ux, self.uy,
                          self.length, self.s, self.z, self.a, self.b, self.r)


class _Profiled(Family):
    """Items whose value is the tool's profile at a distance from its axis, above the tip z."""

    def __init__(self, segment, ox, oy, tool, **arrays):
        super().__init__(segment, ox, oy, **arrays)
        self.tool = tool
        self.shape = tool.shape
        self.r = tool.radius

    def profile_at(self, k, distance, out):
        """out <- z + profile(min(distance, R)); ``distance`` is clipped in place."""
        np.minimum(distance, np.float32(self.r), out=distance)
        out[...] = self.shape.height_at(distance)
        out += _row(self.z[k])


class _ConeBands(Family):
    """Cells beside a move of a pointed tool (V-bit, drill) whose lowest value lies on the
    cone's flank strictly inside the move.  With q the distance along the move from its start
    and e across it (both in XY), the tip climbing a = dz/l per mm and the flank rising k per mm
    from the axis (k = 1 / tan of the half angle, a < k), the flank's lowest point over a cell
    is g*|e| above the tip (g = sqrt(k^2 - a^2)) at mu*|e| behind the cell (mu = a / g), so

        value = z + a*q + g*|e|  over  |e| <= w, 0 <= q - mu*|e| <= length

    where w = r*g/k keeps that point within the cone's radius r (beyond it the rim takes over:
    see :func:`_disc_bands`).  Arrays: ux, uy, length, z, a, g, mu, w."""

    def xrange(self):
        return _band_span(self.ox, self.ux, self.uy, self.length, -self.w * np.abs(self.mu),
                          self.w * np.abs(self.mu), self.w)

    def yrange(self):
        reach = self.w * (1.0 + np.abs(self.mu))
        ends = self.oy + self.uy * self.length
        return np.minimum(self.oy, ends) - reach - _EPS, np.maximum(self.oy, ends) + reach + _EPS

    def intervals(self, k, dx):
        return [_band_side_interval(dx, self.ux[k], self.uy[k], self.length[k], self.mu[k], self.w[k], side)
                for side in (1.0, -1.0)]

    def values(self, k, dx, dy0, cell_y, j, out, tmp):
        ux, uy, a, g = self.ux[k], self.uy[k], self.a[k], self.g[k]
        # e and z + a*q are affine in the cell number j along the run (dy = dy0 + j*cell_y)
        np.multiply(j, _row(cell_y * ux), out=tmp)
        tmp += _row(dy0 * ux - dx * uy)
        np.abs(tmp, out=tmp)
        tmp *= _row(g)
        np.multiply(j, _row(cell_y * uy * a), out=out)
        out += _row((dx * ux + dy0 * uy) * a + self.z[k])
        out += tmp

    def cut(self, kernels, flat, hf):
        kernels.cut_cone_bands(flat, _kernel_grid(hf), _EPS, *family_columns(hf, self), self.ox, self.oy, self.ux,
                               self.uy, self.length, self.z, self.a, self.g, self.mu, self.w)


class _LevelBands(_Profiled):
    """Cells beside a level move of a bull nose: its lowest point over a cell lies square to the
    move, so with q along the move and e across it the value is the tool's profile there,

        value = z + profile(|e|)  over  0 <= q <= length, |e| <= R

    (exact: the torus needs no ring of spheres here).  Arrays: ux, uy, length, z."""

    def xrange(self):
        return _band_span(self.ox, self.ux, self.uy, self.length, 0.0, 0.0, self.r)

    def yrange(self):
        ends = self.oy + self.uy * self.length
        return np.minimum(self.oy, ends) - self.r - _EPS, np.maximum(self.oy, ends) + self.r + _EPS

    def intervals(self, k, dx):
        return [_band_side_interval(dx, self.ux[k], self.uy[k], self.length[k], 0.0, self.r, side)
                for side in (1.0, -1.0)]

    def values(self, k, dx, dy0, cell_y, j, out, tmp):
        ux, uy = self.ux[k], self.uy[k]
        np.multiply(j, _row(cell_y * ux), out=tmp)          # e, affine in the cell number j
        tmp += _row(dy0 * ux - dx * uy)
        np.abs(tmp, out=tmp)
        self.profile_at(k, tmp, out)

    def cut(self, kernels, flat, hf):
        kernels.cut_level_bands(flat, _kernel_grid(hf), _EPS, *family_columns(hf, self), self.ox, self.oy, self.ux,
                                self.uy, self.length, self.z, self.r, *self.shape.profile())


def _band_side_interval(dx, ux, uy, length, mu, w, side):
    """Cells of one side of a cone or level band in a column (side +1: e >= 0, -1: e <= 0):
    0 <= side*e <= w and 0 <= q - mu*side*e <= length, with q = dx*ux + dy*uy and
    e = dy*ux - dx*uy (dy the unknown)."""
    lo, hi = np.full_like(dx, -np.inf), np.full_like(dx, np.inf)
    start = dx * (ux + side * mu * uy)
    slant = uy - side * mu * ux
    for a, b in ((-side * dx * uy, side * ux), (w + side * dx * uy, -side * ux), (start, slant),
                 (length - start, -slant)):
        side_lo, side_hi = halfline(a, b)
        lo, hi = np.maximum(lo, side_lo), np.minimum(hi, side_hi)
    return lo - _EPS, hi + _EPS


def _sqrt_of_r2_minus_square(x, r):
    """x <- sqrt(r^2 - x^2) in place; the cells of a region have |x| <= r up to rounding."""
    np.multiply(x, x, out=x)
    np.subtract(r * r, x, out=x)
    np.abs(x, out=x)
    np.sqrt(x, out=x)


def _band_span(o, along, across, length, q_lo, q_hi, r):
    """Range of one world coordinate over the rectangle q in [q_lo, length + q_hi], e in [-r, r]
    (q along the move, e across it); ``along``/``across`` are that coordinate's components."""
    a = o + np.minimum(q_lo * along, (length + q_hi) * along)
    b = o + np.maximum(q_lo * along, (length + q_hi) * along)
    spread = r * np.abs(across)
    return a - spread - _EPS, b + spread + _EPS


def _band_intervals(dx, ux, uy, length, s, r):
    """Cells of a band: |e| <= r and 0 <= q - s*sqrt(r^2 - e^2) <= length, with
    q = dx*ux + dy*uy and e = dy*ux - dx*uy (dy the unknown)."""
    across = np.abs(ux) > 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        e1 = np.where(across, (-r + dx * uy) / ux, -np.inf)
        e2 = np.where(across, (r + dx * uy) / ux, np.inf)
    lie_in = across | (np.abs(dx * uy) <= r)
    dlo = np.where(lie_in, np.minimum(e1, e2), np.inf)
    dhi = np.where(lie_in, np.maximum(e1, e2), -np.inf)
    p = -dx * uy
    rr = r * r
    start = _sqrt_condition(dx * ux, uy, s, rr, p, ux, dlo, dhi)
    end = _sqrt_condition(length - dx * ux, -uy, -s, rr, p, ux, dlo, dhi)
    return _pieces(dlo, dhi, [start, end])


class _SphereVertices(Family):
    """Ball (or torus-ring sphere) centres at the chain's points, only where the lowest value of
    the chain can sit there: the incoming move still falls towards the cell (d1 . D >= dz1 w)
    and the outgoing one rises (-d2 . D >= -dz2 w), w = sqrt(r^2 - |D|^2), D = cell - point.
    Arrays: d1x, d1y, dz1, d2x, d2y, dz2 (zero where there is no such move), z (centre), r."""

    def xrange(self):
        return _cut_disk_span(self.ox, self.r, self.d1x, self.d1y, self.dz1, self.d2x, self.d2y, self.dz2)

    def yrange(self):
        return self.oy - self.r - _EPS, self.oy + self.r + _EPS

    def intervals(self, k, dx):
        r = self.r[k]
        dlo, dhi = _disk_span(dx, r)
        q = r * r - dx * dx
        zero = np.zeros_like(dx)
        incoming = _sqrt_condition(dx * self.d1x[k], self.d1y[k], self.dz1[k], q, zero, 1.0, dlo, dhi)
        outgoing = _sqrt_condition(-dx * self.d2x[k], -self.d2y[k], -self.dz2[k], q, zero, 1.0, dlo, dhi)
        return _pieces(dlo, dhi, [incoming, outgoing])

    def values(self, k, dx, dy0, cell_y, j, out, tmp):
        """value = centre z - sqrt(r^2 - |D|^2)."""
        np.multiply(j, np.float32(cell_y), out=out)
        out += _row(dy0)
        _sqrt_of_r2_minus_square(out, _row(np.sqrt(np.maximum(self.r[k] ** 2 - dx * dx, 0))))
        np.subtract(_row(self.z[k]), out, out=out)

    def cut(self, kernels, flat, hf):
        kernels.cut_sphere_vertices(flat, _kernel_grid(hf), _EPS, *family_columns(hf, self), self.ox, self.oy, self.d1x,
                                    self.d1y, self.dz1, self.d2x, self.d2y, self.dz2, self.z, self.r)


def _cut_disk_span(o, r, n1a, n1b, dz1, n2a, n2b, dz2):
    """Range of one coordinate (component a; b the other) over the disk of radius r cut by
    n1 . D >= min(0, dz1 r) and -n2 . D >= min(0, -dz2 r): a superset of the vertex region."""
    normals = [(n1a, n1b, np.minimum(0, dz1 * r)), (-n2a, -n2b, np.minimum(0, -dz2 * r))]
    candidates = [np.zeros_like(o), -r, r]     # the centre and the disk's extremes
    valid = [np.ones(len(o), bool)]
    for extreme in (-r, r):
        valid.append(np.all([na * extreme >= c - 1e-9 for na, nb, c in normals], axis=0))
    for i, (na, nb, c) in enumerate(normals):
        other = normals[1 - i]
        norm2 = na * na + nb * nb
        with np.errstate(divide="ignore", invalid="ignore"):
            foot = c / norm2
            half = np.sqrt(np.maximum(r * r - c * c / norm2, 0) / norm2)
        for sign in (-1, 1):
            pa = foot * na - sign * half * nb
            pb = foot * nb + sign * half * na
            ok = (norm2 > 1e-24) & (c * c <= r * r * norm2) & (other[0] * pa + other[1] * pb >= other[2] - 1e-9)
            candidates.append(np.where(ok, pa, 0.0))
            valid.append(ok)
    (n1a_, n1b_, c1), (n2a_, n2b_, c2) = normals
    det = n1a_ * n2b_ - n1b_ * n2a_
    with np.errstate(divide="ignore", invalid="ignore"):
        pa = (c1 * n2b_ - c2 * n1b_) / det
        pb = (n1a_ * c2 - n2a_ * c1) / det
    ok = (np.abs(det) > 1e-24) & (pa * pa + pb * pb <= r * r)
    candidates.append(np.where(ok, pa, 0.0))
    valid.append(ok)
    cand = np.array([np.broadcast_to(c, o.shape) for c in candidates])
    ok = np.array(valid)
    lo = np.min(np.where(ok, cand, np.inf), axis=0)
    hi = np.max(np.where(ok, cand, -np.inf), axis=0)
    return o + lo - _EPS, o + hi + _EPS


class _Stamps(_Profiled):
    """The whole tool standing at a point (its full underside over the disk of radius R).
    Arrays: z (tip)."""

    def xrange(self):
        return self.ox - self.r - _EPS, self.ox + self.r + _EPS

    def yrange(self):
        return self.oy - self.r - _EPS, self.oy + self.r + _EPS

    def intervals(self, k, dx):
        dlo, dhi = _disk_span(dx, self.r)
        return [(dlo - _EPS, dhi + _EPS)]

    def values(self, k, dx, dy0, cell_y, j, out, tmp):
        np.multiply(j, np.float32(cell_y), out=tmp)
        tmp += _row(dy0)
        np.multiply(tmp, tmp, out=tmp)
        tmp += _row(dx * dx)
        np.sqrt(tmp, out=tmp)
        self.profile_at(k, tmp, out)

    def cut(self, kernels, flat, hf):
        kernels.cut_stamps(flat, _kernel_grid(hf), _EPS, *family_columns(hf, self), self.ox, self.oy, self.z,
                           self.r, *self.shape.profile())


# ----- height field: which items a chain needs ------------------------------------------------

def families_of(chain: Chain, top: float, tolerance: float) -> list:
    """The bands, vertex spheres and whole-tool stamps whose union is the chain's envelope."""
    tool = chain.tool
    shape = tool.shape
    p = chain.points
    m = len(p) - 1
    delta = np.diff(p, axis=0)
    length = np.hypot(delta[:, 0], delta[:, 1])
    steep = length < MIN_XY_LENGTH
    low = np.minimum(p[:-1, 2], p[1:, 2]) < top
    seg_of_vertex = np.maximum(np.arange(m + 1) - 1, 0)

    stamped = np.zeros(m + 1, bool)        # points that get the whole tool
    stamped[:-1] |= steep
    stamped[1:] |= steep | chain.checked
    if shape.envelope == "disc":
        # The flat disc's lowest value sits at a point only where the path turns upward.
        dz_in = np.concatenate([[0.0], delta[:, 2]])
        dz_out = np.concatenate([delta[:, 2], [1.0]])
        stamped |= (dz_in <= 0) & (dz_out > 0)
    families = []
    bands = ~steep & low
    if shape.envelope == "sphere":
        families += _sphere_chain(p, delta, length, bands, ~stamped & (p[:, 2] < top), seg_of_vertex,
                                  tool.radius, (0.0, 0.0))
    elif shape.envelope == "disc":
        rc = shape.corner_radius
        flat = tool.radius - rc
        if flat > 0:
            families.append(_disc_bands(p, delta, length, bands, flat))
        if rc > 0:
            # beside a level move the torus is exact (see _LevelBands); elsewhere, and at the
            # points, a ring of spheres within the tolerance
            level = bands & (delta[:, 2] == 0)
            s = np.flatnonzero(level)
            families.append(_LevelBands(s, p[s, 0], p[s, 1], tool, ux=delta[s, 0] / length[s],
                                        uy=delta[s, 1] / length[s], length=length[s], z=p[s, 2]))
            n = _ring_count(flat, rc, tolerance)
            for angle in np.arange(n) * (2 * math.pi / n):
                families += _sphere_chain(p, delta, length, bands & ~level, ~stamped & (p[:, 2] < top),
                                          seg_of_vertex, rc, (flat * math.cos(angle), flat * math.sin(angle)))
    else:  # cones: the whole tool at every point
        stamped[:] = True
    points = np.flatnonzero(stamped & (p[:, 2] < top))
    seg = seg_of_vertex[points]
    xy = p[points, :2]
    z = p[points, 2]
    if shape.envelope == "cone":
        slope = 1 / shape.tip_tan
        # the flank beside each move, and where the move climbs or falls, the rim (a flat disc
        # at the cone's top) beside it: with the cone at the points, the exact envelope
        # a move falling or climbing (nearly) along the flank itself, |a| -> k, gets no band: the
        # band's cells are widened by _EPS across the move, and there its formula reads the move
        # |mu|*_EPS beyond its end (mu = a/g: a 2 mm move along a 60 deg flank cut 12 mm deep).
        # Without the band the cones at the ends are the envelope but for (k - |a|) per mm of the
        # move and the radius: |mu| <= MAX_CONE_MU bounds the first error by MAX_CONE_MU*_EPS*k
        # (5e-4 mm at k = 1.7) and the second by k/(2*MAX_CONE_MU^2), 1e-5 mm per mm
        a_all = np.divide(delta[:, 2], length, out=np.zeros(len(length)), where=length > 0)
        g_all = np.sqrt(np.maximum(slope * slope - a_all * a_all, 0.0))
        s = np.flatnonzero(bands & (np.abs(delta[:, 2]) < slope * length)
                           & (np.abs(a_all) <= MAX_CONE_MU * g_all))
        a = delta[s, 2] / length[s]
        g = np.sqrt(slope * slope - a * a)
        families.append(_ConeBands(s, p[s, 0], p[s, 1], ux=delta[s, 0] / length[s], uy=delta[s, 1] / length[s],
                                   length=length[s], z=p[s, 2], a=a, g=g, mu=a / g, w=tool.radius * g / slope))
        families.append(_disc_bands(p, delta, length, bands & (delta[:, 2] != 0), tool.radius,
                                    lift=tool.radius * slope))
    families.append(_Stamps(seg, xy[:, 0], xy[:, 1], tool, z=z))
    return [f for f in families if len(f)]


def _sphere_chain(p, delta, length, bands, vertices, seg_of_vertex, r, offset):
    """Bands and vertex spheres for a sphere of radius r whose centre is offset (dx, dy) from
    the tool axis, r above the tip."""
    ox, oy = offset
    s = np.flatnonzero(bands)
    d = delta[s]
    l = length[s]
    big = np.linalg.norm(d, axis=1)
    sphere_bands = _Bands(s, p[s, 0] + ox, p[s, 1] + oy, ux=d[:, 0] / l, uy=d[:, 1] / l, length=l,
                          s=d[:, 2] / big, z=p[s, 2] + r, a=d[:, 2] / l, b=big / l, r=np.full(len(s), r))
    m = len(delta)
    # Where the path runs straight on in XY and its slope does not increase, the ball at the
    # point is inside the two capsules beside it: no cell needs it.
    d_in, d_out = delta[:-1], delta[1:]
    straight = (np.abs(d_in[:, 0] * d_out[:, 1] - d_in[:, 1] * d_out[:, 0]) <= 1e-12 * length[:-1] * length[1:]) \
        & (d_in[:, 0] * d_out[:, 0] + d_in[:, 1] * d_out[:, 1] > 0)
    bends_down = straight & (d_out[:, 2] * length[:-1] <= d_in[:, 2] * length[1:])
    vertices = vertices & ~np.concatenate([[False], bends_down, [False]])
    v = np.flatnonzero(vertices)
    zero = np.zeros(len(v))
    has_in = v > 0
    has_out = v < m
    d_in = delta[np.maximum(v - 1, 0)]
    d_out = delta[np.minimum(v, m - 1)]
    sphere_vertices = _SphereVertices(seg_of_vertex[v], p[v, 0] + ox, p[v, 1] + oy,
                                      d1x=np.where(has_in, d_in[:, 0], zero), d1y=np.where(has_in, d_in[:, 1], zero),
                                      dz1=np.where(has_in, d_in[:, 2], zero),
                                      d2x=np.where(has_out, d_out[:, 0], zero),
                                      d2y=np.where(has_out, d_out[:, 1], zero),
                                      dz2=np.where(has_out, d_out[:, 2], zero), z=p[v, 2] + r,
                                      r=np.full(len(v), r))
    return [sphere_bands, sphere_vertices]


def _disc_bands(p, delta, length, bands, r, lift=0.0):
    """Bands of a flat disc of radius r, ``lift`` above the tip (a cone's rim: its top)."""
    s = np.flatnonzero(bands)
    # Turn every move to run downhill; the swept disc is the same.
    down = delta[s, 2] <= 0
    start = np.where(down[:, None], p[s], p[s + 1])
    d = np.where(down[:, None], delta[s], -delta[s])
    l = length[s]
    return _Bands(s, start[:, 0], start[:, 1], ux=d[:, 0] / l, uy=d[:, 1] / l, length=l, s=np.full(len(s), -1.0),
                  z=start[:, 2] + lift, a=d[:, 2] / l, b=-d[:, 2] / l, r=np.full(len(s), r))


def family_columns(hf: HeightField, family: Family):
    """(first grid column, number of columns) of every item of the family."""
    nx, ny = hf.shape
    xlo, xhi = family.xrange()
    ylo, yhi = family.yrange()
    c0 = np.clip(np.ceil((xlo - hf.x0) / hf.cell_x - 0.5), 0, nx).astype(np.int64)
    c1 = np.clip(np.floor((xhi - hf.x0) / hf.cell_x - 0.5), -1, nx - 1).astype(np.int64)
    ncol = np.maximum(c1 - c0 + 1, 0)
    ncol[(yhi < hf.y0) | (ylo > hf.y0 + ny * hf.cell_y)] = 0
    return c0, ncol


def _kernel_grid(hf: HeightField):
    """The grid as the compiled kernels take it (one type for every grid: one compilation)."""
    return hf.shape[1], float(hf.x0), float(hf.y0), float(hf.cell_x), float(hf.cell_y)
