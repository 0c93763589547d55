"""Drop cutter: the lowest tool-tip Z at which a 3-axis tool touches a triangle mesh, per XY.

The tool (a :class:`~.program.Tool`: ball, flat, bull nose, V-bit or drill) hangs on a
vertical axis over a point C = (x, y) and is lowered until it touches the mesh.  Its underside
is h(d) above its tip at distance d from the axis (``ToolShape.height_at``), so the tip stops at

    z(C) = max over mesh points P with |P_xy - C| <= R of  P_z - h(|P_xy - C|).

Every tool here is convex, so over one triangle the function P -> P_z - h(|P_xy - C|) is
concave and its maximum is in one of three places, each with a closed form:

* a **vertex** (inside the tool's reach);
* the **facet**: the point of the plane z = a + g.xy where the tool meets it first, at
  distance ``facet_support(|g|)`` from the axis in the direction of g (ball: r|g|/sqrt(1+|g|^2),
  i.e. the contact point r*n_xy from the axis; bull nose: the flat radius plus that for the
  corner; flat end: the rim, R; cone: the tip when |g| is below the cone's slope 1/tan(half
  angle), else its rim), when it falls inside the triangle;
* an **edge**: along the edge, at xy distance t from C and rising m per mm, the function of
  u (position along the edge from the foot of the perpendicular) z0 + m*u - h(sqrt(t^2+u^2))
  is concave, so its maximum on the part of the edge under the tool is its stationary point
  clamped to that part: ball u* = m*sqrt((r^2 - t^2)/(1 + m^2)); cone u* = m*t/sqrt(k^2 - m^2)
  (k = 1/tan(half angle); an end of the part when |m| >= k); flat end: an end of the part
  (the rim); bull nose: the root of the (falling) derivative by 64 bisections, i.e. to
  about 1e-18 of the tool's reach: exact to rounding.

When the maximum over the triangle is not at an interior facet point it lies on the
triangle's boundary, so the three kinds together are exact (to floating-point rounding).

Speed: triangles go into a bucket grid over XY (each into every bucket its XY box, grown by
the tool radius, overlaps), sorted in each bucket by falling top Z; a point tests only its
bucket's triangles, and the compiled kernel (dropcutter_kernel.py, numba) stops at the first
triangle whose top is no higher than the tip found so far.  The numpy path evaluates the same
closed forms over (point, triangle) pairs in chunks of at most ``PAIR_CHUNK`` pairs; both give
the same heights to rounding (the tests check 1e-9 mm).

A closed, outward-facing mesh (a solid: every edge shared by two faces in opposite directions)
is dropped on its faces that are not turned down only (:func:`closed_outward` says why that
is exact); that halves the work on a sphere.

Stock allowance: a tool kept ``allowance`` away from the mesh is the tool grown by a ball of
that radius (ball r -> ball r+a, flat R -> bull nose R+a with corner a, bull R, r -> R+a, r+a)
dropped, then raised by a: exact, not an approximation.  Pointed tools take no allowance.

Everything is in millimetres; points with no triangle under the tool get ``floor``.
"""
from __future__ import annotations

import math

import numpy as np

from .compiled import KERNELS, kernel_module  # noqa: F401 (KERNELS re-exported)
from ..ir.errors import InputError

PAIR_CHUNK = 1 << 20          # (point, triangle) pairs per numpy batch
MAX_ENTRIES = 30_000_000      # bucket entries (triangle, bucket) kept at most; buckets grow beyond
STEEP = math.tan(math.radians(89.0))   # a path segment rising faster than this spans a jump (a vertical wall)
RISING = math.tan(math.radians(60.0))  # ...and one rising faster than this may: its midpoint is checked both ways
ROUNDED, CONE = 0, 1


class DropCutterError(InputError):
    """A mesh, a tool or points the drop cutter cannot use."""


def tool_profile(tool, allowance: float = 0.0) -> np.ndarray:
    """(kind, R, rc, flat radius, k) of a :class:`~.program.Tool` grown by ``allowance``."""
    shape = tool.shape
    if not (math.isfinite(allowance) and allowance >= 0):
        raise DropCutterError(f"stock allowance must be a number >= 0 mm, got {allowance!r}")
    if shape.pointed:
        if allowance > 0:
            raise DropCutterError(f"a {tool.describe()} cannot leave a stock allowance (use a ball, flat or bull nose)")
        return np.array([CONE, shape.radius, 0.0, 0.0, 1.0 / shape.tip_tan])
    rc = shape.corner_radius + allowance
    radius = shape.radius + allowance
    return np.array([ROUNDED, radius, rc, radius - rc, 0.0])


def facet_support(profile: np.ndarray, g):
    """Distance from the axis at which the tool first touches a plane of gradient |grad z| = g."""
    kind, R, rc, fr, k = profile
    g = np.asarray(g, float)
    if kind == CONE:
        return np.where(g <= k, 0.0, R)
    if rc <= 0:
        return np.where(g > 0, R, 0.0)
    return np.where(g > 0, fr + rc * g / np.sqrt(1 + g * g), 0.0)


def underside(profile: np.ndarray, d):
    """h(d): height of the (grown) tool's underside above its tip at distance d."""
    kind, R, rc, fr, k = profile
    d = np.asarray(d, float)
    if kind == CONE:
        return k * d
    off = np.maximum(d - fr, 0.0)
    return rc - np.sqrt(np.maximum(rc * rc - off * off, 0.0))


def _underside_slope(profile, d):
    kind, R, rc, fr, k = profile
    if kind == CONE:
        return np.full_like(d, k)
    off = np.maximum(d - fr, 0.0)
    q = rc * rc - off * off
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(d <= fr, 0.0, np.where(q > 0, off / np.sqrt(np.maximum(q, 1e-300)), np.inf))


def _edge_best(profile, m, t, ua, ub):
    """Where z0 + m*u - h(sqrt(t^2 + u^2)) is largest on [ua, ub] (arrays)."""
    kind, R, rc, fr, k = profile
    with np.errstate(divide="ignore", invalid="ignore"):
        if kind == CONE:
            u = np.where(np.abs(m) < k, m * t / np.sqrt(np.maximum(k * k - m * m, 1e-300)),
                         np.where(m > 0, np.inf, -np.inf))
        elif rc <= 0:
            u = np.where(m > 0, np.inf, np.where(m < 0, -np.inf, ua))
        elif fr <= 0:
            u = m * np.sqrt(np.maximum(rc * rc - t * t, 0.0) / (1 + m * m))
        else:
            lo, hi = ua.copy(), ub.copy()
            for _ in range(64):
                mid = 0.5 * (lo + hi)
                d = np.sqrt(t * t + mid * mid)
                rising = m - np.where(d > 0, _underside_slope(profile, d) * mid / np.where(d > 0, d, 1), 0.0) > 0
                lo = np.where(rising, mid, lo)
                hi = np.where(rising, hi, mid)
            u = 0.5 * (lo + hi)
    return np.minimum(np.maximum(u, ua), ub)


class Mesh:
    """A triangle mesh prepared for dropping: triangles (n, 3, 3), their planes and top Z."""

    def __init__(self, vertices, faces):
        vertices = np.asarray(vertices, float)
        faces = np.asarray(faces)
        if vertices.ndim != 2 or vertices.shape[1] != 3 or not len(vertices):
            raise DropCutterError(f"vertices must be an (n, 3) array of mm, got shape {vertices.shape}")
        if not np.all(np.isfinite(vertices)):
            raise DropCutterError("a vertex has a non-finite coordinate")
        if faces.ndim != 2 or faces.shape[1] != 3 or not len(faces):
            raise DropCutterError(f"faces must be an (m, 3) array of vertex indices, got shape {faces.shape}")
        if faces.min() < 0 or faces.max() >= len(vertices):
            raise DropCutterError(f"a face refers to vertex {int(faces.max())}, but there are {len(vertices)}")
        faces = faces.astype(np.int64)
        self.closed = closed_outward(vertices, faces)
        if self.closed:
            tri = vertices[faces]
            nz = ((tri[:, 1, 0] - tri[:, 0, 0]) * (tri[:, 2, 1] - tri[:, 0, 1])
                  - (tri[:, 1, 1] - tri[:, 0, 1]) * (tri[:, 2, 0] - tri[:, 0, 0]))
            faces = faces[nz >= 0]          # a closed solid is touched from above on its other faces
        self.tris = np.ascontiguousarray(vertices[faces])
        a, b, c = self.tris[:, 0], self.tris[:, 1], self.tris[:, 2]
        normal = np.cross(b - a, c - a)
        area2 = normal[:, 2]            # twice the signed XY area
        scale = np.maximum(np.abs(normal).max(axis=1), 1e-300)
        upright = np.abs(area2) > 1e-12 * scale
        with np.errstate(divide="ignore", invalid="ignore"):
            gx = np.where(upright, -normal[:, 0] / area2, 0.0)
            gy = np.where(upright, -normal[:, 1] / area2, 0.0)
        z0 = a[:, 2] - gx * a[:, 0] - gy * a[:, 1]
        self.planes = np.column_stack([gx, gy, z0, upright.astype(float), np.sign(area2)])
        self.zmax = self.tris[:, :, 2].max(axis=1)
        self.lo = self.tris[:, :, :2].min(axis=1)
        self.hi = self.tris[:, :, :2].max(axis=1)

    @property
    def z_range(self) -> tuple:
        return float(self.tris[:, :, 2].min()), float(self.zmax.max())


def closed_outward(vertices, faces) -> bool:
    """Whether the triangles bound a solid, faces turned outward: every directed edge (a, b)
    has exactly one twin (b, a), and the enclosed volume is positive.  Then no point of a
    face turned down can be the first contact from above (just above it is the solid, whose
    top face over that point is at least as high), and its edges and corners belong to faces
    that are not turned down or lie under them, so the drop skips those faces."""
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    n = int(vertices.shape[0])
    key = directed[:, 0] * n + directed[:, 1]
    twin = directed[:, 1] * n + directed[:, 0]
    order = np.sort(key)
    if len(order) > 1 and np.any(order[1:] == order[:-1]):
        return False
    found = np.searchsorted(order, twin)
    if np.any(found >= len(order)) or np.any(order[np.minimum(found, len(order) - 1)] != twin):
        return False
    tri = vertices[faces]
    volume = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6
    return bool(volume > 0)


def precomputed(mesh: Mesh, profile: np.ndarray) -> np.ndarray:
    """Per triangle, what the compiled kernel needs that depends on the triangle and the tool
    alone: the facet contact's offset from the axis (x, y) and the tool's height there, then per
    edge its XY unit direction (x, y), XY length and slope: (n, 15)."""
    gx, gy = mesh.planes[:, 0], mesh.planes[:, 1]
    g = np.hypot(gx, gy)
    d = np.where(g > 0, facet_support(profile, g), 0.0)
    safe = np.where(g > 0, g, 1.0)
    columns = [d * gx / safe, d * gy / safe, underside(profile, d)]
    t = mesh.tris
    for e in range(3):
        p, q = t[:, e], t[:, (e + 1) % 3]
        ex, ey = q[:, 0] - p[:, 0], q[:, 1] - p[:, 1]
        length = np.hypot(ex, ey)
        ok = length > 1e-12
        safe = np.where(ok, length, 1.0)
        columns += [np.where(ok, ex / safe, 0.0), np.where(ok, ey / safe, 0.0), np.where(ok, length, 0.0),
                    np.where(ok, (q[:, 2] - p[:, 2]) / safe, 0.0)]
    return np.ascontiguousarray(np.column_stack(columns))


class Buckets:
    """Triangles per XY bucket (grown by the tool's reach), each bucket by falling top Z."""

    def __init__(self, mesh: Mesh, reach: float, size: float | None = None):
        lo, hi = mesh.lo - reach, mesh.hi + reach
        self.bbox = np.ascontiguousarray(np.column_stack([lo, hi]))
        x0, y0 = lo.min(axis=0)
        x1, y1 = hi.max(axis=0)
        size = float(size) if size else max(reach / 2, 1e-3)
        while True:
            nbx = max(1, math.ceil((x1 - x0) / size + 1e-9))
            nby = max(1, math.ceil((y1 - y0) / size + 1e-9))
            i0 = np.floor((lo[:, 0] - x0) / size).astype(np.int64)
            i1 = np.minimum(np.floor((hi[:, 0] - x0) / size).astype(np.int64), nbx - 1)
            j0 = np.floor((lo[:, 1] - y0) / size).astype(np.int64)
            j1 = np.minimum(np.floor((hi[:, 1] - y0) / size).astype(np.int64), nby - 1)
            ni, nj = i1 - i0 + 1, j1 - j0 + 1
            total = int(np.sum(ni * nj))
            if total <= MAX_ENTRIES and nbx * nby <= MAX_ENTRIES:
                break
            size *= 1.5
        # entries made triangle by triangle from the highest top down, then a stable sort by
        # bucket: each bucket by falling top Z (ties by triangle index)
        rank = np.argsort(-mesh.zmax, kind="stable")
        i0, j0, ni, nj = i0[rank], j0[rank], ni[rank], nj[rank]
        count = ni * nj
        tri = np.repeat(np.arange(len(lo)), count)
        local = np.arange(total) - np.repeat(np.cumsum(count) - count, count)
        bi = i0[tri] + local // nj[tri]
        bj = j0[tri] + local % nj[tri]
        bucket = bi * nby + bj
        # (numpy sorts 16-bit keys by radix: the same stable order, several times faster)
        order = np.argsort(bucket.astype(np.uint16) if nbx * nby <= 1 << 16 else bucket, kind="stable")
        self.entries = np.ascontiguousarray(rank[tri[order]].astype(np.int64))
        self.start = np.zeros(nbx * nby + 1, np.int64)
        np.cumsum(np.bincount(bucket, minlength=nbx * nby), out=self.start[1:])
        self.grid = np.array([x0, y0, size, nbx, nby], float)

    def of_points(self, x, y) -> np.ndarray:
        """Bucket index per point (-1 outside the grid)."""
        x0, y0, size, nbx, nby = self.grid
        fi, fj = (x - x0) / size, (y - y0) / size
        inside = (fi >= 0) & (fj >= 0) & (fi < nbx) & (fj < nby)
        return np.where(inside, np.floor(np.where(inside, fi, 0)).astype(np.int64) * int(nby)
                        + np.floor(np.where(inside, fj, 0)).astype(np.int64), -1)


def _kernel_module(kernel: str):
    return kernel_module(kernel, f"{__package__}.dropcutter_kernel", DropCutterError, "numba drop-cutter kernel")


class DropCutter:
    """A tool over a mesh: :meth:`points`, :meth:`grid` and :meth:`path` give tip heights.

    ``tool``: a program.Tool; ``allowance``: mm of stock the tool keeps from the mesh;
    ``floor``: the height where no triangle is under the tool; ``kernel``: "numba", "numpy" or
    "auto" (numba where it can be imported); ``bucket``: bucket size in mm (default R/2);
    ``mesh``: the :class:`Mesh` of these vertices and faces when the caller has made it already
    (several tools over one design share it)."""

    def __init__(self, vertices, faces, tool, *, allowance: float = 0.0, floor: float = -np.inf,
                 kernel: str = "auto", bucket: float | None = None, mesh: Mesh | None = None):
        self.profile = tool_profile(tool, allowance)
        self.allowance = float(allowance)
        self.mesh = Mesh(vertices, faces) if mesh is None else mesh
        self.buckets = Buckets(self.mesh, float(self.profile[1]), bucket)
        self.floor = float(floor)
        self.compiled = _kernel_module(kernel)
        self.kernel = "numpy" if self.compiled is None else "numba"
        self.pre = precomputed(self.mesh, self.profile) if self.compiled is not None else None

    def points(self, xy, progress=None) -> np.ndarray:
        """Tip Z over every point (n, 2)."""
        xy = np.asarray(xy, float).reshape(-1, 2)
        if not np.all(np.isfinite(xy)):
            raise DropCutterError("a query point has a non-finite coordinate")
        x, y = np.ascontiguousarray(xy[:, 0]), np.ascontiguousarray(xy[:, 1])
        shift = self.allowance
        out = np.full(len(x), self.floor - shift)
        step = 1 << 14
        for begin in range(0, len(x), step):
            part = slice(begin, begin + step)
            if self.compiled is not None:
                b = self.buckets
                view = out[part]
                self.compiled.drop_points(x[part], y[part], view, self.mesh.tris, self.mesh.planes, self.pre,
                                          self.mesh.zmax,
                                          b.bbox, b.start, b.entries, b.grid, self.profile)
            else:
                out[part] = self._numpy(x[part], y[part], out[part])
            if progress is not None:
                progress(min(1.0, (begin + step) / max(len(x), 1)))
        return out + shift

    def grid(self, x, y, progress=None) -> np.ndarray:
        """Tip Z over the grid x (nx,) by y (ny,): (nx, ny)."""
        x, y = np.asarray(x, float), np.asarray(y, float)
        gx, gy = np.meshgrid(x, y, indexing="ij")
        return self.points(np.column_stack([gx.ravel(), gy.ravel()]), progress).reshape(len(x), len(y))

    def path(self, xy, spacing: float, tolerance: float = 1e-4, min_step: float = 1e-3) -> np.ndarray:
        """The tool dropped along the polyline ``xy`` (k, 2): (n, 3) points, sampled at most
        ``spacing`` apart, then refined where the tip between two points stands more than
        ``tolerance`` above the straight line between them (down to ``min_step``), and where the
        tip rises more than 60 degrees between them and the midpoint stands more than ``tolerance``
        off that line either way, or more than 89 degrees (down to ``tolerance``): beside a vertical wall
        the envelope jumps (the ball's equator meets the wall), and a midpoint on the low side of
        the jump says nothing of the high side, so such a segment is halved until the jump lies
        within ``tolerance`` in XY."""
        xy = np.asarray(xy, float).reshape(-1, 2)
        if len(xy) < 2:
            raise DropCutterError("a path needs at least two points")
        if not (spacing > 0 and tolerance > 0):
            raise DropCutterError(f"spacing and tolerance must be > 0 mm, got {spacing!r}, {tolerance!r}")
        seg = np.linalg.norm(np.diff(xy, axis=0), axis=1)
        pieces = np.maximum(np.ceil(seg / spacing), 1).astype(np.int64)
        fractions = [np.arange(n) / n for n in pieces]
        samples = np.vstack([xy[i] + np.outer(f, xy[i + 1] - xy[i]) for i, f in enumerate(fractions)] + [xy[-1:]])
        z = self.points(samples)
        # per segment: its midpoint's tip Z, once dropped (a segment left whole keeps it: the
        # next rounds drop only the halves of the segments just split)
        zm = np.full(len(samples) - 1, -np.inf)
        known = np.zeros(len(samples) - 1, bool)
        for _ in range(40):
            a, b = samples[:-1], samples[1:]
            length = np.linalg.norm(b - a, axis=1)
            long_enough = length > 2 * min_step
            with np.errstate(invalid="ignore"):
                rise = np.where(np.isfinite(z[1:]) & np.isfinite(z[:-1]), np.abs(z[1:] - z[:-1]), 0.0)
            steep = (rise > RISING * length) & (length > tolerance)
            mid = 0.5 * (a + b)
            fresh = (long_enough | steep) & ~known
            if fresh.any():
                zm[fresh] = self.points(mid[fresh])
                known |= fresh
            chord = 0.5 * (z[:-1] + z[1:])
            with np.errstate(invalid="ignore"):
                off = np.abs(zm - chord) > tolerance
            high = (long_enough & (zm > chord + tolerance)) | (steep & (off | (rise > STEEP * length)))
            if not high.any():
                break
            split = np.flatnonzero(high)
            # sample i moves up by the splits before it; a midpoint goes right after its segment's start
            moved = np.arange(len(samples))
            moved[1:] += np.cumsum(high)
            placed = moved[split] + 1
            grown = np.empty((len(samples) + len(split), 2))
            grown[moved], grown[placed] = samples, mid[split]
            z_grown = np.empty(len(grown))
            z_grown[moved], z_grown[placed] = z, zm[split]
            samples, z = grown, z_grown
            # segment i becomes segment moved[i] and, when split, the next one too
            first = moved[:-1]
            zm_next = np.full(len(samples) - 1, -np.inf)
            known_next = np.ones(len(samples) - 1, bool)
            zm_next[first] = zm
            known_next[first] = known & ~high
            known_next[first[split] + 1] = False
            zm, known = zm_next, known_next
        return np.column_stack([samples, z])

    # ----- the numpy path: the same closed forms over (point, triangle) pairs --------------------
    def _numpy(self, x, y, out):
        b, mesh, prof = self.buckets, self.mesh, self.profile
        bucket = b.of_points(x, y)
        count = np.where(bucket >= 0, b.start[bucket + 1] - b.start[np.maximum(bucket, 0)], 0)
        begin = 0
        while begin < len(x):
            total = np.cumsum(count[begin:])
            end = begin + max(1, int(np.searchsorted(total, PAIR_CHUNK, side="right")))
            n = count[begin:end]
            pairs = int(n.sum())
            if pairs:
                point = np.repeat(np.arange(begin, end), n)
                local = np.arange(pairs) - np.repeat(np.cumsum(n) - n, n)
                tri = b.entries[b.start[bucket[point]] + local]
                box = b.bbox[tri]
                px, py = x[point], y[point]
                near = (px >= box[:, 0]) & (px <= box[:, 2]) & (py >= box[:, 1]) & (py <= box[:, 3])
                point, tri, px, py = point[near], tri[near], px[near], py[near]
                value = _pairs(prof, mesh.tris[tri], mesh.planes[tri], px, py)
                np.maximum.at(out, point, value)
            begin = end
        return out


def _pairs(prof, t, planes, cx, cy) -> np.ndarray:
    """The highest tip for each (triangle, point) pair: vertices, edges, facet."""
    kind, R, rc, fr, k = prof
    best = np.full(len(cx), -np.inf)
    for v in range(3):
        d = np.hypot(t[:, v, 0] - cx, t[:, v, 1] - cy)
        best = np.maximum(best, np.where(d <= R, t[:, v, 2] - underside(prof, np.minimum(d, R)), -np.inf))
    for e in range(3):
        p, q = t[:, e], t[:, (e + 1) % 3]
        ex, ey = q[:, 0] - p[:, 0], q[:, 1] - p[:, 1]
        length = np.hypot(ex, ey)
        ok = length > 1e-12
        safe = np.where(ok, length, 1.0)
        ux, uy = ex / safe, ey / safe
        wx, wy = cx - p[:, 0], cy - p[:, 1]
        s0 = wx * ux + wy * uy
        dist = np.abs(wx * uy - wy * ux)
        ok &= dist <= R
        w = np.sqrt(np.maximum(R * R - dist * dist, 0.0))
        ua, ub = np.maximum(-s0, -w), np.minimum(length - s0, w)
        ok &= ua <= ub
        m = (q[:, 2] - p[:, 2]) / safe
        u = _edge_best(prof, m, dist, ua, np.where(ok, ub, ua))
        z = p[:, 2] + m * (s0 + u) - underside(prof, np.minimum(np.sqrt(dist * dist + u * u), R))
        best = np.maximum(best, np.where(ok, z, -np.inf))
    gx, gy, z0, upright, sign = planes.T
    g = np.hypot(gx, gy)
    d = np.where(g > 0, facet_support(prof, g), 0.0)
    safe = np.where(g > 0, g, 1.0)
    fx, fy = cx + d * gx / safe, cy + d * gy / safe
    inside = upright > 0
    for e in range(3):
        p, q = t[:, e], t[:, (e + 1) % 3]
        inside &= sign * ((q[:, 0] - p[:, 0]) * (fy - p[:, 1]) - (q[:, 1] - p[:, 1]) * (fx - p[:, 0])) >= 0
    z = z0 + gx * fx + gy * fy - underside(prof, d)
    return np.maximum(best, np.where(inside, z, -np.inf))
