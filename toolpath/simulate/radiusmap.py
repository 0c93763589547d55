"""Radius map r(theta, z): the simulated stock of radial turn-mill work (SPEC W4 + W6).

A radial turn-mill tool points at the C axis and the part turns under it, so its cuts are seen
from the axis outwards, not from above: a height field cannot hold them.  The radius map is a
grid of cylindrical dexels: the ray from the axis at angle theta and height z keeps the radius up
to which material remains.  A ball of radius R at centre c (radius rho, angle phi, height zc)
cuts that ray from where the ray enters the ball outwards (the shank lies further out along the
tool axis; cutting the dexel from the entry outwards is the radius-map analogue of the height
field cutting a column from the lowest point up).  The entry radius is exact::

    r = rho cos(d) - sqrt(R^2 - (z - zc)^2 - rho^2 sin^2(d)),   d = theta - phi

Moves are interpolated in machine coordinates (X, Z and C linear, as the controller does) and the
ball is stamped at centres no further apart than 2 sqrt(2 R t - t^2): between two stamps the
envelope then dips at most t (the ``tolerance``) below the true swept surface, always on the side
of leaving material.

Gouge checks compare the map with the design's outer radius along the same rays, read from the
part mesh by slicing it at each row's height.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..ir.program import ARC_CCW, ARC_CW, Operation

_STAMP_BATCH = 1024      # ball stamps evaluated together (bounds the memory of one batch)
_TRIANGLE_BATCH = 4096   # design triangles sliced together


@dataclass
class RadiusMap:
    """``radii[i, k]``: the material radius along the ray at angle (i + 0.5) * cell_theta
    (radians from +X, counter-clockwise) and height z0 + (k + 0.5) * cell_z; the stock radius
    where nothing cut.  ``operation[i, k]``: the last operation that cut the dexel (-1: never)."""

    radius: float
    z0: float
    cell_z: float
    cell_theta: float
    radii: np.ndarray
    operation: np.ndarray

    @property
    def shape(self):
        return self.radii.shape

    def theta(self) -> np.ndarray:
        return (np.arange(self.shape[0]) + 0.5) * self.cell_theta

    def z(self) -> np.ndarray:
        return self.z0 + (np.arange(self.shape[1]) + 0.5) * self.cell_z

    def removed_volume(self) -> float:
        """mm^3 between the stock's cylinder and the map (each dexel a sector of an annulus)."""
        r = np.clip(self.radii, 0.0, self.radius).astype(np.float64)
        return float(np.sum(self.radius ** 2 - r ** 2) / 2 * self.cell_theta * self.cell_z)

    def cells_of(self, theta, z):
        """(i, k) indices of the dexels at angles ``theta`` (radians) and heights ``z`` (clamped)."""
        i = np.floor(np.mod(theta, 2 * math.pi) / self.cell_theta).astype(np.int64) % self.shape[0]
        k = np.clip(np.floor((np.asarray(z) - self.z0) / self.cell_z).astype(np.int64), 0, self.shape[1] - 1)
        return i, k

    def removed_above(self, x, y, z_low, z_high) -> np.ndarray:
        """For columns at (x, y): how much of z_low..z_high the map has removed there (mm), summed
        over the map's rows: the overlap of a height-field cut with this map's cuts."""
        rho = np.hypot(x, y)
        i, _ = self.cells_of(np.arctan2(y, x), np.zeros_like(x))
        z = self.z()
        out = np.zeros(len(x))
        if not len(x):
            return out
        rows = np.flatnonzero((z + self.cell_z / 2 > np.min(z_low)) & (z - self.cell_z / 2 < np.max(z_high)))
        for k in rows:
            lo, hi = z[k] - self.cell_z / 2, z[k] + self.cell_z / 2
            span = np.clip(np.minimum(z_high, hi) - np.maximum(z_low, lo), 0.0, None)
            out += np.where(rho > self.radii[i, k], span, 0.0)
        return out


def grid(radius: float, z_min: float, z_max: float, cell: float) -> RadiusMap:
    """An uncut map of a bar: dexels about ``cell`` mm square on the bar's surface."""
    n_theta = max(8, math.ceil(2 * math.pi * radius / cell))
    n_z = max(1, math.ceil((z_max - z_min) / cell))
    return RadiusMap(float(radius), float(z_min), (z_max - z_min) / n_z, 2 * math.pi / n_theta,
                     np.full((n_theta, n_z), radius, np.float64), np.full((n_theta, n_z), -1, np.int16))


def stamp_spacing(ball_radius: float, tolerance: float) -> float:
    """Centre spacing whose dip between two balls is exactly ``tolerance``."""
    t = min(tolerance, ball_radius)
    return 2.0 * math.sqrt(2.0 * ball_radius * t - t * t)


@dataclass
class BallStamps:
    """Ball centres of one radial operation in part cylindrical coordinates, in cutting order;
    ``move[s]``: the operation's move that stamp s belongs to (-1: the start point);
    ``checked[s]``: the move must be tested against the material before it cuts."""

    rho: np.ndarray
    phi: np.ndarray
    z: np.ndarray
    move: np.ndarray
    checked: np.ndarray


def ball_stamps(op: Operation, spacing: float, checked_moves: np.ndarray) -> BallStamps:
    """Stamps along the operation's moves, interpolated in machine X, Z and C.

    The radial tool's tip is at machine X (the radius), its ball centre R further out."""
    if np.any((op.kind == ARC_CW) | (op.kind == ARC_CCW)):
        raise ValueError(f"operation {op.name!r}: radial turn-mill moves are straight in X, Z and C, not G2/G3 arcs")
    r = op.tool.radius
    c_end = np.radians(op.rotary["c"])
    start = op.start_points()
    c_start = np.concatenate([[c_end[0]], c_end[:-1]])
    rho_a, rho_b = start[:, 0] + r, op.xyz[:, 0] + r
    reach = np.maximum(np.abs(rho_a), np.abs(rho_b))
    length = np.sqrt((rho_b - rho_a) ** 2 + (op.xyz[:, 2] - start[:, 2]) ** 2 + (reach * (c_end - c_start)) ** 2)
    pieces = np.maximum(1, np.ceil(length / spacing)).astype(np.int64)
    move = np.repeat(np.arange(len(op)), pieces)
    t = (np.arange(len(move)) - np.repeat(np.cumsum(pieces) - pieces, pieces) + 1) / pieces[move]
    rho = np.concatenate([[rho_a[0]], rho_a[move] + t * (rho_b - rho_a)[move]])
    z = np.concatenate([[start[0, 2]], start[move, 2] + t * (op.xyz[:, 2] - start[:, 2])[move]])
    phi = np.concatenate([[c_start[0]], c_start[move] + t * (c_end - c_start)[move]])
    moves = np.concatenate([[-1], move])
    return BallStamps(rho, phi, z, moves, np.concatenate([[False], checked_moves[move]]))


def entry_radii(rm: RadiusMap, rho, phi, zc, ball_radius: float):
    """(dexel index into radii.ravel(), entry radius, stamp index) for every dexel the balls
    reach: the exact ray-sphere entry, 0 where the ray starts inside the ball."""
    n_theta, n_z = rm.shape
    r2 = ball_radius * ball_radius
    near = np.flatnonzero(rho - ball_radius < rm.radius)      # balls that reach the bar
    rho, phi, zc = rho[near], phi[near], zc[near]
    k0 = np.clip(np.ceil((zc - ball_radius - rm.z0) / rm.cell_z - 0.5), 0, n_z).astype(np.int64)
    k1 = np.clip(np.floor((zc + ball_radius - rm.z0) / rm.cell_z - 0.5), -1, n_z - 1).astype(np.int64)
    rows = np.maximum(k1 - k0 + 1, 0)
    stamp = np.repeat(np.arange(len(rho)), rows)
    k = np.arange(len(stamp)) - np.repeat(np.cumsum(rows) - rows, rows) + k0[stamp]
    dz = rm.z0 + (k + 0.5) * rm.cell_z - zc[stamp]
    w2 = r2 - dz * dz
    keep = w2 > 0
    stamp, k, w2 = stamp[keep], k[keep], w2[keep]
    rho_s, phi_s = rho[stamp], phi[stamp]
    # Rays that meet the ball: |d| <= asin(w / rho), or every ray when the ball holds the axis.
    ratio = np.sqrt(w2) / np.maximum(np.abs(rho_s), 1e-12)
    half = np.where(ratio >= 1.0, math.pi, np.arcsin(np.minimum(ratio, 1.0)))
    centre = np.where(rho_s >= 0, phi_s, phi_s + math.pi)
    i0 = np.ceil((centre - half) / rm.cell_theta - 0.5).astype(np.int64)
    i1 = np.floor((centre + half) / rm.cell_theta - 0.5).astype(np.int64)
    count = np.clip(i1 - i0 + 1, 0, n_theta)
    pair = np.repeat(np.arange(len(stamp)), count)
    i = np.arange(len(pair)) - np.repeat(np.cumsum(count) - count, count) + i0[pair]
    d = (i + 0.5) * rm.cell_theta - phi_s[pair]
    rho_p = rho_s[pair]
    sin_d = np.sin(d)
    entry = rho_p * np.cos(d) - np.sqrt(np.maximum(w2[pair] - rho_p * rho_p * sin_d * sin_d, 0.0))
    index = np.mod(i, n_theta) * n_z + k[pair]
    return index, np.maximum(entry, 0.0), near[stamp[pair]]


@dataclass
class Touch:
    """A checked move that reached into the material: its operation, move, depth and where."""

    operation: int
    move: int
    depth: float
    point: tuple


def cut(rm: RadiusMap, stamps: BallStamps, ball_radius: float, operation: int, touch: float, progress=None,
        kernels=None) -> list:
    """Cut the map with one operation's stamps, in order; returns the checked moves that
    reached more than ``touch`` mm into the material as it was before them (:class:`Touch`).
    ``progress(fraction)`` is called after every block of stamps (it may raise to cancel).
    ``kernels``: the compiled kernels module (kernel.py), or None for numpy; checked
    moves always take numpy."""
    flat = rm.radii.reshape(-1)
    before = flat.copy()
    touches = []
    n = len(stamps.rho)
    # Blocks of stamps: a checked move's stamps alone (measured before they cut), the rest in batches.
    change = np.flatnonzero((stamps.checked[1:] != stamps.checked[:-1])
                            | ((stamps.move[1:] != stamps.move[:-1]) & stamps.checked[1:]))
    edges = np.unique(np.concatenate([[0, n], change + 1, np.arange(0, n, _STAMP_BATCH)]))
    for a, b in zip(edges[:-1], edges[1:]):
        if kernels is not None and not stamps.checked[a]:
            kernels.cut_radial_balls(flat, rm.shape[0], rm.shape[1], rm.z0, rm.cell_z, rm.cell_theta,
                                     stamps.rho[a:b], stamps.phi[a:b], stamps.z[a:b], float(ball_radius),
                                     rm.radius)
            if progress is not None:
                progress(b / n)
            continue
        index, entry, stamp = entry_radii(rm, stamps.rho[a:b], stamps.phi[a:b], stamps.z[a:b], ball_radius)
        if not len(index):
            continue
        if stamps.checked[a]:
            depth = flat[index] - entry
            worst = int(np.argmax(depth))
            if depth[worst] > touch:
                i, k = divmod(int(index[worst]), rm.shape[1])
                theta = (i + 0.5) * rm.cell_theta
                point = (float(flat[index[worst]] * math.cos(theta)), float(flat[index[worst]] * math.sin(theta)),
                         float(rm.z0 + (k + 0.5) * rm.cell_z))
                touches.append(Touch(operation, int(stamps.move[a + stamp[worst]]), float(depth[worst]), point))
        np.minimum.at(flat, index, entry)
        if progress is not None:
            progress(b / n)
    rm.operation.reshape(-1)[flat < before] = operation
    return touches



def outer_radii(rm: RadiusMap, vertices: np.ndarray, faces: np.ndarray, kernels=None) -> np.ndarray:
    """The design mesh's outer radius along every ray of the map (0 where the ray misses it).

    Every triangle is sliced at each row's height; each slice segment sets the radius of the
    rays it crosses, and the largest wins.  ``kernels``: the compiled kernels module (kernel.py)
    for the rays (the same radii, bit for bit), or None for numpy."""
    n_theta, n_z = rm.shape
    out = np.zeros(n_theta * n_z)
    tri = vertices[faces]
    zs = rm.z()
    for start in range(0, len(tri), _TRIANGLE_BATCH):
        t = tri[start:start + _TRIANGLE_BATCH]
        lo = np.clip(np.ceil((t[:, :, 2].min(1) - rm.z0) / rm.cell_z - 0.5), 0, n_z).astype(np.int64)
        hi = np.clip(np.floor((t[:, :, 2].max(1) - rm.z0) / rm.cell_z - 0.5), -1, n_z - 1).astype(np.int64)
        rows = np.maximum(hi - lo + 1, 0)
        tri_of = np.repeat(np.arange(len(t)), rows)
        k = np.arange(len(tri_of)) - np.repeat(np.cumsum(rows) - rows, rows) + lo[tri_of]
        z = zs[k]
        # The two edges that cross the plane (half-open, so a vertex on the plane counts once):
        # the first one's crossing point is a, the second one's b.
        corner = [[np.ascontiguousarray(t[:, e, axis])[tri_of] for axis in range(3)] for e in range(3)]
        crossing = np.zeros(len(k), np.int64)
        ax, ay, bx, by = (np.zeros(len(k)) for _ in range(4))
        for e in range(3):
            (px, py, pz), (qx, qy, qz) = corner[e], corner[(e + 1) % 3]
            hit = (pz <= z) != (qz <= z)
            s = (z - pz) / np.where(hit, qz - pz, 1.0)
            x, y = px + s * (qx - px), py + s * (qy - py)
            first, second = hit & (crossing == 0), hit & (crossing == 1)
            ax, ay = np.where(first, x, ax), np.where(first, y, ay)
            bx, by = np.where(second, x, bx), np.where(second, y, by)
            crossing += hit
        ends = crossing == 2
        k, ax, ay, bx, by = k[ends], ax[ends], ay[ends], bx[ends], by[ends]
        angle_a = np.arctan2(ay, ax)
        sweep = np.angle(np.exp(1j * (np.arctan2(by, bx) - angle_a)))
        lo_angle = np.where(sweep >= 0, angle_a, angle_a + sweep)
        i0 = np.ceil(lo_angle / rm.cell_theta - 0.5).astype(np.int64)
        i1 = np.floor((lo_angle + np.abs(sweep)) / rm.cell_theta - 0.5).astype(np.int64)
        count = np.clip(i1 - i0 + 1, 0, n_theta)
        met = count > 0
        if not met.any():
            continue
        # the rays' directions from a table over the angles met (cos and sin once per angle)
        first = int(i0[met].min())
        theta = (np.arange(first, int((i0 + count - 1)[met].max()) + 1) + 0.5) * rm.cell_theta
        cos_t, sin_t = np.cos(theta), np.sin(theta)
        ex, ey = bx - ax, by - ay
        numerator = ax * ey - ay * ex
        if kernels is not None:
            kernels.outer_rays(out, n_theta, n_z, k, i0, count, ex, ey, numerator, cos_t, sin_t, first)
            continue
        seg = np.repeat(np.arange(len(k)), count)
        i = np.arange(len(seg)) - np.repeat(np.cumsum(count) - count, count) + i0[seg]
        denominator = cos_t[i - first] * ey[seg] - sin_t[i - first] * ex[seg]
        numerator = numerator[seg]
        ok = np.abs(denominator) > 1e-12
        radius = np.where(ok, numerator / np.where(ok, denominator, 1.0), 0.0)
        np.maximum.at(out, np.mod(i, n_theta) * n_z + k[seg], np.maximum(radius, 0.0))
    return out.reshape(n_theta, n_z)


def lowest_stamp(rm: RadiusMap, stamps: BallStamps, ball_radius: float, i: int, k: int):
    """(stamp index, entry radius) of the stamp that cut deepest into dexel (i, k)."""
    theta = (i + 0.5) * rm.cell_theta
    dz = rm.z0 + (k + 0.5) * rm.cell_z - stamps.z
    d = theta - stamps.phi
    sin_d = np.sin(d)
    disc = ball_radius ** 2 - dz * dz - stamps.rho ** 2 * sin_d * sin_d
    entry = np.where(disc >= 0, stamps.rho * np.cos(d) - np.sqrt(np.maximum(disc, 0.0)), np.inf)
    best = int(np.argmin(entry))
    return best, float(max(entry[best], 0.0))


def mesh_grid(rm: RadiusMap, z_min: float, z_max: float, max_cells: int | None = None) -> np.ndarray:
    """The vertices of ``mesh``'s side as an (n_theta, columns, 3) grid: column 0 at ``z_min``,
    the last at ``z_max``, the others at the (pooled) cell centres."""
    radii = np.clip(rm.radii, 1e-3, rm.radius)
    n_theta, n_z = radii.shape
    block = 1
    if max_cells is not None and n_theta * n_z > max_cells:
        block = math.ceil(math.sqrt(n_theta * n_z / max_cells))
        pad_t, pad_z = -n_theta % block, -n_z % block
        padded = np.pad(np.pad(radii, ((0, pad_t), (0, 0)), mode="wrap"), ((0, 0), (0, pad_z)), mode="edge")
        radii = padded.reshape(padded.shape[0] // block, block, padded.shape[1] // block, block).min(axis=(1, 3))
    n_theta, n_z = radii.shape
    theta = (np.arange(n_theta) + 0.5) * (2 * math.pi / n_theta)
    cell_z = (z_max - z_min) / n_z
    zs = np.concatenate([[z_min], np.minimum(z_min + (np.arange(n_z) + 0.5) * cell_z, z_max), [z_max]])
    r = np.pad(radii, ((0, 0), (1, 1)), mode="edge")
    return np.stack([r * np.cos(theta)[:, None], r * np.sin(theta)[:, None],
                     np.broadcast_to(zs, r.shape)], axis=-1)


def grid_mesh(grid: np.ndarray, bottom_cap: bool = True, top_cap: bool = True):
    """A grid of ``mesh_grid`` (or a run of its columns) as triangles: the side, then a fan
    closing the first column (``bottom_cap``) and one closing the last (``top_cap``), each about
    a centre on the axis appended after the grid's vertices.  Outward normals."""
    n_theta, columns = grid.shape[:2]
    ids = np.arange(n_theta * columns).reshape(n_theta, columns)
    nxt = np.roll(ids, -1, axis=0)
    a, b, c, d = ids[:, :-1].ravel(), nxt[:, :-1].ravel(), nxt[:, 1:].ravel(), ids[:, 1:].ravel()
    faces = [np.column_stack([a, b, c]), np.column_stack([a, c, d])]
    vertices = [grid.reshape(-1, 3)]
    if bottom_cap:
        faces.append(np.column_stack([np.full(n_theta, n_theta * columns), nxt[:, 0], ids[:, 0]]))
    if top_cap:
        faces.append(np.column_stack([np.full(n_theta, n_theta * columns + int(bottom_cap)), ids[:, -1], nxt[:, -1]]))
    vertices += [[[0.0, 0.0, grid[0, 0, 2]]]] if bottom_cap else []
    vertices += [[[0.0, 0.0, grid[0, -1, 2]]]] if top_cap else []
    return np.vstack(vertices), np.vstack(faces)


def mesh(rm: RadiusMap, z_min: float, z_max: float, max_cells: int | None = None):
    """The map as a closed triangle mesh: (vertices, faces), outward normals.  Pooled to at most
    ``max_cells`` dexels first, keeping the deepest cut of each block."""
    return grid_mesh(mesh_grid(rm, z_min, z_max, max_cells))
