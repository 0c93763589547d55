"""W2 rotary pockets: the job's inputs and a pocket's tool-centre geometry.

:class:`Block`, :class:`Pocket` and :class:`RotarySettings` are what :func:`rotary.plan` takes.
:class:`PocketGeometry` checks one pocket against them and answers, in the pocket's local frame
(centre at the origin, ball-centre heights), where the ball centre may go: the regions at each
height, the outline offsets of slanted walls, the bowl's sphere, and the signed distance to the
design surface that the gouge check uses.  :mod:`rotary` has the frames and the sequence of
passes.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from manifold3d import CrossSection

from ...engines import region as rg
from ...ir.errors import InputError
from ...ir.kinematics import DEFAULT_MAX_TABLE_RPM
from ...ir.program import Tool

BOTTOMS = ("flat", "sphere")
MAX_WALL_ANGLE = 75.0          # degrees from vertical
# Elements per block where work on long arrays is cut into blocks: numpy temporaries beyond
# ~128 kB come fresh from the OS (page faults) each time and cost several times the arithmetic.
BLOCK = 4096


class RotaryError(InputError):
    """Input the rotary-pocket workflow cannot use; the message names what is wrong."""


def is_finite_number(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool) \
        and math.isfinite(value)


def row_norms(v: np.ndarray) -> np.ndarray:
    """Lengths of the rows of (n, 2) or (n, 3) vectors (np.linalg.norm is slow on short rows)."""
    return np.sqrt(sum(v[:, k] * v[:, k] for k in range(v.shape[1])))


def same_point(a: np.ndarray, b: np.ndarray) -> bool:
    """np.allclose for two points, without its overhead (it runs once per chain)."""
    return bool(np.all(np.abs(a - b) <= 1e-8 + 1e-5 * np.abs(b)))


@dataclass(frozen=True)
class Block:
    """The board, centred on the rotation axis (mm)."""

    size_x: float = 105.0
    size_y: float = 105.0
    thickness: float = 30.0


@dataclass(frozen=True)
class Pocket:
    """One pocket.  ``outline``: closed polygon in the part frame (mm).  ``depth`` > 0 below
    the top.  ``wall_angle_deg``: 0 = vertical wall.  ``bottom``: "flat" or "sphere" (then
    ``sphere_radius``).  ``centre``: where roughing circles and spirals start and the bowl's
    lowest point is; default the outline's centroid."""

    name: str
    outline: object
    depth: float
    wall_angle_deg: float = 0.0
    bottom: str = "flat"
    sphere_radius: float | None = None
    centre: tuple | None = None


@dataclass(frozen=True)
class RotarySettings:
    """Every number of the job (mm, mm/min, rpm).  Speeds are along the path on the wood."""

    tool: Tool = Tool(1, "ball", 6.0, flute_length=25.0, name="pencil bit")
    spindle_rpm: float = 18000.0
    cutting_speed: float = 1500.0
    plunge_speed: float = 300.0
    spacing: float = 1.0                 # alpha: distance between path points
    stepover: float = 1.0                # P: floor spiral pitch / bowl helix pitch along the surface
    rough_stepover: float | None = None  # growth of the roughing circles; None = the bit radius
    step_down: float = 3.0
    allowance: float = 0.5               # stock roughing leaves on walls and bottom
    wall_stepover: float = 0.5           # wall finishing pitch, along the wall
    tolerance: float = 0.005             # rotary interpolation vs chord; finishing stands off
                                         # tolerance + region.ARC_TOLERANCE from the design surface
    clearance_z: float = 5.0
    safe_z: float = 50.0
    approach_gap: float = 2.0
    rapid_rate: float = 5000.0
    max_table_rpm: float = DEFAULT_MAX_TABLE_RPM

    @property
    def roughing_stepover(self) -> float:
        return self.tool.radius if self.rough_stepover is None else self.rough_stepover

    @property
    def standoff(self) -> float:
        return self.tolerance + rg.ARC_TOLERANCE

    def validate(self):
        names = ("spindle_rpm", "cutting_speed", "plunge_speed", "spacing", "stepover", "roughing_stepover",
                 "step_down", "allowance", "wall_stepover", "tolerance", "clearance_z", "safe_z",
                 "approach_gap", "rapid_rate", "max_table_rpm")
        for name in names:
            value = getattr(self, name)
            if not is_finite_number(value):
                raise RotaryError(f"{name.replace('_', ' ')} must be a finite number, got {value!r}")
        for name in names:
            if name != "allowance" and getattr(self, name) <= 0:
                raise RotaryError(f"{name.replace('_', ' ')} must be greater than zero, got {getattr(self, name):g}")
        if self.allowance < 0:
            raise RotaryError(f"allowance must be >= 0, got {self.allowance:g}")
        if self.tool.kind != "ball":
            raise RotaryError(f"the rotary pockets are cut with a ball-nose bit, not a {self.tool.kind} tool")
        for name in ("stepover", "roughing_stepover", "wall_stepover"):
            if getattr(self, name) > self.tool.diameter:
                raise RotaryError(f"{name.replace('_', ' ')} {getattr(self, name):g} mm is wider than the "
                                  f"{self.tool.diameter:g} mm bit: ridges would be left standing")
        if not 0 < self.approach_gap < self.clearance_z <= self.safe_z:
            raise RotaryError("heights must satisfy 0 < approach gap < clearance plane <= safe Z")


# ----------------------------------------------------------------------------------------
# Pocket geometry (local frame: pocket centre at the origin, ball-centre heights)
# ----------------------------------------------------------------------------------------

def _disk(radius: float) -> CrossSection:
    """A disk whose polygon lies inside the true circle (vertices on it)."""
    n = rg.circle_segments(radius)
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return CrossSection([np.column_stack([radius * np.cos(a), radius * np.sin(a)])])


def squared_distance(px, py, ax, ay, dx, dy, inverse) -> np.ndarray:
    """Squared distance from points (px, py) to segments from (ax, ay) by (dx, dy), with
    ``inverse`` = 1 / (dx^2 + dy^2); arrays that broadcast."""
    rx, ry = px - ax, py - ay
    s = np.clip((rx * dx + ry * dy) * inverse, 0.0, 1.0)
    rx, ry = rx - s * dx, ry - s * dy
    return rx * rx + ry * ry


class OutlineDistance:
    """Signed distance from plan points (n, 2) to a polygon, positive inside: exact, but each
    point is measured against the few edges that can be nearest to it, not against all.

    The polygon's box is cut into square cells.  For a point p in a cell with centre q and
    half-diagonal h, the edge nearest p lies within dist(q) + 2h of q; a cell lists those.
    Cells inside and deeper than ``cap`` list none: their points get ``cap``, less than their
    distance (callers only need "farther than cap" there).  Points off the box are outside and
    measured against every edge."""

    def __init__(self, loop: np.ndarray, region: CrossSection, cap: float):
        self.region, self.cap = region, cap
        vector = np.roll(loop, -1, axis=0) - loop
        self.ax, self.ay = loop[:, 0].copy(), loop[:, 1].copy()
        self.dx, self.dy = vector[:, 0].copy(), vector[:, 1].copy()
        self.inverse = 1.0 / np.maximum(self.dx ** 2 + self.dy ** 2, 1e-300)
        self.low = loop.min(axis=0)
        extent = loop.max(axis=0) - self.low
        self.size = math.sqrt(extent[0] * extent[1] / 512)          # about 512 cells
        self.shape = np.maximum(1, np.ceil(extent / self.size).astype(int))
        ix, iy = np.meshgrid(np.arange(self.shape[0]), np.arange(self.shape[1]))
        cx, cy = self.low[0] + (ix.ravel() + 0.5) * self.size, self.low[1] + (iy.ravel() + 0.5) * self.size
        half = self.size * math.sqrt(0.5)
        inside = rg.contains_points(region, np.column_stack([cx, cy]))
        nearest, count, edges = [], [], []
        for block in np.array_split(np.arange(len(cx)), len(cx) * len(loop) // BLOCK + 1):
            dist = np.sqrt(squared_distance(cx[block, None], cy[block, None], self.ax, self.ay, self.dx, self.dy,
                                             self.inverse))
            nearest.append(dist.min(axis=1))
            listed = ~inside[block] | (nearest[-1] - half < cap)
            mask = listed[:, None] & (dist <= nearest[-1][:, None] + 2 * half)
            count.append(mask.sum(axis=1))
            edges.append(np.nonzero(mask)[1])
        nearest, self.count, self.edges = np.concatenate(nearest), np.concatenate(count), np.concatenate(edges)
        self.first = np.cumsum(self.count) - self.count
        # A cell the outline does not pass through is inside or outside as a whole (0: ask).
        self.side = np.where(nearest > half, np.where(inside, 1.0, -1.0), 0.0)

    def to_all(self, px: np.ndarray, py: np.ndarray) -> np.ndarray:
        """Unsigned distance of points to the polygon, against every edge."""
        return np.sqrt(squared_distance(px[:, None], py[:, None], self.ax, self.ay, self.dx, self.dy,
                                         self.inverse).min(axis=1))

    def __call__(self, points: np.ndarray) -> np.ndarray:
        points = np.asarray(points, float).reshape(-1, 2)
        px, py = points[:, 0].copy(), points[:, 1].copy()
        out = np.full(len(points), self.cap)
        ix, iy = np.floor((px - self.low[0]) / self.size), np.floor((py - self.low[1]) / self.size)
        on_grid = (ix >= 0) & (iy >= 0) & (ix < self.shape[0]) & (iy < self.shape[1])
        cell = np.where(on_grid, iy * self.shape[0] + ix, 0).astype(int)
        rows = np.flatnonzero(on_grid & (self.count[cell] > 0))
        for block in np.array_split(rows, int(self.count[cell[rows]].sum()) // BLOCK + 1):
            count = self.count[cell[block]]
            group = np.cumsum(count) - count
            edge = self.edges[np.repeat(self.first[cell[block]] - group, count) + np.arange(count.sum())]
            point = np.repeat(block, count)
            square = squared_distance(px[point], py[point], self.ax[edge], self.ay[edge], self.dx[edge],
                                       self.dy[edge], self.inverse[edge])
            out[block] = np.sqrt(np.minimum.reduceat(square, group))
        off = np.flatnonzero(~on_grid)
        if len(off):
            out[off] = self.to_all(px[off], py[off])
        side = np.where(on_grid, self.side[cell], -1.0)
        unsure = np.flatnonzero(side == 0)
        if len(unsure):
            side[unsure] = np.where(rg.contains_points(self.region, points[unsure]), 1.0, -1.0)
        return out * side


class PocketGeometry:
    """A validated pocket in its local frame, with the ball radius and stand-off."""

    def __init__(self, pocket: Pocket, block: Block, settings: RotarySettings):
        self.name = pocket.name
        r = settings.tool.radius
        self.r = r
        what = f"pocket {pocket.name!r}"
        try:
            loop = rg.validate_loop(pocket.outline, what)
        except rg.RegionError as error:
            raise RotaryError(str(error)) from None
        absolute = rg.from_loops([loop], what)
        if len(rg.loops(absolute)) != 1 or abs(rg.area(absolute) - abs(rg.signed_area(loop))) > 1e-6 * rg.area(absolute):
            raise RotaryError(f"{what}: the outline crosses itself")
        for name in ("depth", "wall_angle_deg"):
            value = getattr(pocket, name)
            if not is_finite_number(value):
                raise RotaryError(f"{what}: {name.replace('_', ' ')} must be a finite number, got {value!r}")
        if pocket.centre is None:
            centre = np.array(rg.centroid(absolute), float)
        else:
            centre = np.asarray(pocket.centre, float).reshape(-1)
            if centre.shape != (2,) or not np.all(np.isfinite(centre)):
                raise RotaryError(f"{what}: the centre must be two finite numbers, got {pocket.centre!r}")
        if pocket.depth <= 0:
            raise RotaryError(f"{what}: depth must be greater than zero, got {pocket.depth:g}")
        if pocket.depth >= block.thickness:
            raise RotaryError(f"{what}: depth {pocket.depth:.6g} mm goes through the {block.thickness:.6g} mm board")
        if pocket.depth > settings.tool.flute_length:
            raise RotaryError(f"{what}: depth {pocket.depth:.6g} mm is beyond the bit's flute length "
                              f"{settings.tool.flute_length:.6g} mm")
        if not 0 <= pocket.wall_angle_deg <= MAX_WALL_ANGLE:
            raise RotaryError(f"{what}: wall angle must be 0..{MAX_WALL_ANGLE} degrees from vertical, "
                              f"got {pocket.wall_angle_deg:g}")
        if pocket.bottom not in BOTTOMS:
            raise RotaryError(f"{what}: bottom must be one of {BOTTOMS}, got {pocket.bottom!r}")
        half = np.array([block.size_x, block.size_y]) / 2
        if np.any(np.abs(loop) > half + 1e-9):
            raise RotaryError(f"{what}: the outline reaches outside the {block.size_x:.6g} x {block.size_y:.6g} mm board")

        self.centre = centre
        self.loop = loop - centre
        self.region = rg.from_loops([self.loop], what)
        self._insets = {}
        self.depth = float(pocket.depth)
        self.theta = math.radians(pocket.wall_angle_deg)
        self.bottom = pocket.bottom
        self.standoff = settings.standoff
        self.far = float(row_norms(self.loop).max())
        self.sphere_radius = None
        if self.bottom == "sphere":
            rs = pocket.sphere_radius
            if not is_finite_number(rs):
                raise RotaryError(f"{what}: a spherical bowl needs a finite sphere radius, got {rs!r}")
            if pocket.wall_angle_deg != 0:
                raise RotaryError(f"{what}: a spherical bowl has a vertical rim; set the wall angle to 0")
            if not rg.contains_points(self.region, np.zeros((1, 2)))[0]:
                raise RotaryError(f"{what}: the bowl's lowest point (the centre) is outside the outline")
            needed = (self.far ** 2 + self.depth ** 2) / (2 * self.depth)
            if rs < needed:
                raise RotaryError(f"{what}: sphere radius {rs:g} mm is smaller than the opening requires: a bowl "
                                  f"{self.depth:g} mm deep reaching {self.far:.2f} mm from its centre needs "
                                  f"at least {needed:.2f} mm")
            self.sphere_radius = float(rs)
        if rg.area(self.bottom_region()) < rg.MIN_AREA:
            raise RotaryError(f"{what}: the {settings.tool.diameter:g} mm bit does not fit in the pocket"
                              + (" at its floor (the slanted walls close it in)" if self.theta else ""))
        # No ball centre needs to be farther from the outline than at the floor.
        self.walls = OutlineDistance(self.loop, self.region, self.wall_offset(self.floor_z(0.0)) + 1.0)
        self.centre_to_outline = float(self.walls.to_all(np.zeros(1), np.zeros(1))[0])

    # ----- where the ball centre may go ------------------------------------------------
    @property
    def sphere_centre_z(self) -> float:
        return self.sphere_radius - self.depth

    def floor_z(self, extra: float) -> float:
        """Lowest ball-centre height over a flat floor, keeping ``extra`` off it."""
        return -self.depth + self.r + extra

    def wall_offset(self, z: float) -> float:
        """Inward offset of the outline for a ball centre at height z touching the wall."""
        return self.r / math.cos(self.theta) - z * math.tan(self.theta)

    def locus_radius(self, extra: float) -> float:
        """Radius of the sphere the ball centre runs on in a bowl, ``extra`` off the surface."""
        return self.sphere_radius - self.r - extra

    def sphere_z(self, xy: np.ndarray, extra: float) -> np.ndarray:
        """Ball-centre height on the bowl's locus above plan points (n, 2)."""
        rho2 = (np.asarray(xy) ** 2).sum(axis=-1)
        return self.sphere_centre_z - np.sqrt(np.maximum(self.locus_radius(extra) ** 2 - rho2, 0.0))

    def inset(self, distance: float) -> CrossSection:
        """The outline offset inward (kept: vertical walls ask for the same one at every height)."""
        if distance not in self._insets:
            self._insets[distance] = rg.offset(self.region, -distance)
        return self._insets[distance]

    def region_at(self, z: float, extra: float) -> CrossSection:
        """Plan region of ball centres at height z that stay ``extra`` off walls and bottom."""
        area = self.inset(self.wall_offset(z) + extra)
        if self.bottom == "flat":
            return area if z >= self.floor_z(extra) - 1e-9 else CrossSection()
        reach2 = self.locus_radius(extra) ** 2 - (self.sphere_centre_z - z) ** 2
        if reach2 <= 0:
            return CrossSection()
        return area ^ _disk(math.sqrt(reach2))

    def bottom_region(self) -> CrossSection:
        """Plan region the bottom finishing covers (a flat floor, or the bowl inside the rim)."""
        if self.bottom == "flat":        # the ball on the floor, the stand-off from the walls
            return self.inset(self.wall_offset(self.floor_z(0.0)) + self.standoff)
        return self.inset(self.r + self.standoff)

    def rim_wall(self) -> float:
        """Tallest vertical rim of a bowl (0 for a flat pocket)."""
        if self.bottom != "sphere":
            return 0.0
        surface = self.sphere_centre_z - math.sqrt(self.sphere_radius ** 2 - self.centre_to_outline ** 2)
        return max(0.0, -surface)

    # ----- how far a ball cuts past the design surface ----------------------------------
    def need(self, z: np.ndarray) -> np.ndarray:
        """Plan distance from the outline a ball centre at height z (< r) needs to clear the
        wall: the wall's offset below its top edge, the ball's section at the board top above
        it.  Concave in z (the two meet with the same slope) and never growing."""
        r = self.r
        return np.where(z <= r * math.sin(self.theta), self.wall_offset(z), np.sqrt(np.maximum(r * r - z * z, 0.0)))

    def need_slope(self, z: np.ndarray) -> np.ndarray:
        """d need / dz (-inf at z = r)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(z <= self.r * math.sin(self.theta), -math.tan(self.theta),
                            -z / np.sqrt(np.maximum(self.r ** 2 - z * z, 0.0)))

    def probe(self, centres: np.ndarray) -> np.ndarray:
        """Balls at local centres (n, 3) -> (n, 4) columns: z; signed plan distance d to the
        outline (positive inside; deep inside only ``walls.cap``); the bottom's penetration;
        and the PENETRATION, how far the ball cuts past the design surface (<= 0: clear)."""
        r, z = self.r, centres[:, 2]
        d = self.walls(centres[:, :2])
        wall = (self.need(z) - d) * np.where(z <= r * math.sin(self.theta), math.cos(self.theta), 1.0)
        wall = np.where(z >= r, -np.inf, wall)
        if self.bottom == "flat":
            bottom = -self.depth - (z - r)
        else:
            bottom = row_norms(centres - np.array([0.0, 0.0, self.sphere_centre_z])) - (self.sphere_radius - r)
        return np.column_stack([z, d, bottom, np.maximum(wall, bottom)])

    def bound(self, span, v0, v1, speed, bend) -> np.ndarray:
        """Upper bound of the penetration over stretches of moves, from probes v0, v1 at their
        ends (rows of :meth:`probe`).

        A move runs its ball centre through c(t), t in [0, 1], with z linear in t and the plan
        point p(t) bounded by |p'| <= speed, |p''| <= bend; a stretch spans ``span`` of t, so
        at most L = speed * span of plan length.  Then, along the stretch:

        * the plan distance d to the outline is 1-Lipschitz: d >= (d0 + d1 - L) / 2, and
          d >= rho = min(d0, d1) - L / 2.  When rho > 0 the stretch stays inside, where d is
          the least of the distances to the edges, each convex with curvature at most
          1 / distance; so d'' <= speed^2 / rho + bend and d >= min(d0, d1) -
          (speed^2 / rho + bend) span^2 / 8 (a function with f'' <= K lies at most K span^2 / 8
          below its chord);
        * the wall's penetration is (need(z) - d) * w, w = cos(theta) below the wall's top
          edge and 1 above it: at most X * (the largest w on the stretch), or X * (the
          smallest) when X < 0, where X bounds need - d.  need(z) <= need(lowest z), which
          with the bound on d gives one X.  need is also concave, so under its tangent at
          either end, which is linear in t: then need - d stays under the higher of its end
          values (the tangent's) + the sag of d, which gives two more;
        * a flat bottom is linear in t; a sphere's |c - centre| is convex and 1-Lipschitz in c
          with c'' = (p'', 0), so it lies at most bend * span^2 / 8 above its chord.
        """
        (z0, d0), (z1, d1) = v0[:, :2].T, v1[:, :2].T
        length = speed * span
        inside = np.minimum(d0, d1) - length / 2
        curving = speed ** 2 / np.where(inside > 0, inside, 1.0) + bend
        sag = np.where(inside > 0, curving * span ** 2 / 8, np.inf)
        low, high = np.minimum(z0, z1), np.maximum(z0, z1)
        x = self.need(low) + np.minimum(np.maximum(-d0, -d1) + sag, (length - d0 - d1) / 2)
        sloped = np.flatnonzero(low < high)         # (level stretches gain nothing from tangents)
        if len(sloped):
            za, zb, da, db = z0[sloped], z1[sloped], d0[sloped], d1[sloped]
            na, nb, sa, sb = self.need(za), self.need(zb), self.need_slope(za), self.need_slope(zb)
            with np.errstate(invalid="ignore"):
                under_a = np.where(za < self.r, np.maximum(na - da, na + sa * (zb - za) - db), np.inf)
                under_b = np.where(zb < self.r, np.maximum(nb + sb * (za - zb) - da, nb - db), np.inf)
            x[sloped] = np.minimum(x[sloped], np.minimum(under_a, under_b) + sag[sloped])
        edge, slope = self.r * math.sin(self.theta), math.cos(self.theta)
        most, least = np.where(high <= edge, slope, 1.0), np.where(low <= edge, slope, 1.0)
        wall = np.where(low < self.r, x * np.where(x >= 0, most, least), -np.inf)
        bottom = np.maximum(v0[:, 2], v1[:, 2])
        if self.bottom == "sphere":
            bottom = bottom + bend * span ** 2 / 8
        return np.maximum(wall, bottom)

    def highest(self, at, moves, v0, v1, speed, bend, level, overall: bool = False, rounds: int = 10) -> np.ndarray:
        """Upper bound of the penetration along each move, as tight as it needs to be.

        ``at(moves, t)``: ball centres on the moves at parameters t; ``v0``, ``v1``: probes of
        their ends; ``speed``, ``bend``: see :meth:`bound`, per move.  A stretch whose bound is
        above both ``level`` and the highest probe so far (+ 1e-7 mm + 0.1 %) of its move, or
        with ``overall`` of all moves, is halved and probed at its middle, up to ``rounds``
        times.  Each result is never below the true highest penetration of its move; it is
        <= ``level``, or, unless the rounds ran out, within that margin of a probed value
        (with ``overall``: the highest result is)."""
        owner = np.arange(len(moves))
        level = np.broadcast_to(np.asarray(level, float), len(moves))
        best = np.maximum(v0[:, 3], v1[:, 3])
        top = np.full(len(moves), -np.inf)
        t0, t1 = np.zeros(len(moves)), np.ones(len(moves))
        for round_ in range(rounds + 1):
            bound = self.bound(t1 - t0, v0, v1, speed[owner], bend[owner])
            mine = np.full(len(owner), best.max()) if overall else best[owner]
            done = (bound <= np.maximum(level[owner], mine + 1e-7 + 1e-3 * np.maximum(mine, 0.0))) | (round_ == rounds)
            np.maximum.at(top, owner[done], bound[done])
            if done.all():
                break
            owner, t0, t1, v0, v1 = owner[~done], t0[~done], t1[~done], v0[~done], v1[~done]
            middle = (t0 + t1) / 2
            vm = self.probe(at(moves[owner], middle))
            np.maximum.at(best, owner, vm[:, 3])
            owner, t0, t1 = np.concatenate([owner, owner]), np.concatenate([t0, middle]), np.concatenate([middle, t1])
            v0, v1 = np.vstack([v0, vm]), np.vstack([vm, v1])
        return top


def scallop_height(ball_radius: float, stepover: float, surface_radius: float = math.inf) -> float:
    """Cusp height between neighbouring passes of a ball, ``stepover`` apart along the surface.

    Flat surface: r - sqrt(r^2 - (s/2)^2).  Concave sphere of radius R (a bowl): the ball
    centres are on the sphere R - r, beta = s/R apart; the cusp lies where neighbouring
    balls meet, at x = rho cos(beta/2) + sqrt(r^2 - rho^2 sin^2(beta/2)) from the sphere's
    centre, so the scallop is R - x.
    """
    r, s = ball_radius, stepover
    if math.isinf(surface_radius):
        return r - math.sqrt(max(r * r - s * s / 4, 0.0))
    rho, half = surface_radius - r, s / surface_radius / 2
    return surface_radius - (rho * math.cos(half) + math.sqrt(max(r * r - (rho * math.sin(half)) ** 2, 0.0)))
