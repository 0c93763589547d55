"""W2: non-circular pockets on a rotating table, C-X-Z (seed 001, Hashimoto).

A CNC wood lathe holds a board on its face plate.  The board turns about the C axis; a
ball-nose "pencil" bit (diameter D, flute length L) moves in X (distance from the rotation
centre, on the negative side only: X = -R) and in Z (into the board).

Frames and conventions
----------------------
* Part frame: workpiece XY in mm with the origin on the rotation axis; the board top is
  Z = 0 and Z is negative into the board.  Pocket outlines are given in this frame.
* The geometry is computed for the **ball centre** (offsets of walls, floors and spheres
  are exact there); everything handed out (the IR, the chains of :class:`PocketPath`,
  the NC) is the **tool tip** = ball centre - D/2 in Z, as :mod:`program` defines Z.
* Machine frame: ``X = -R`` (R = distance from the axis), ``C`` in degrees, Z as in the
  part frame.  C is the angle of the part point measured counter-clockwise (seen from +Z,
  the tool side) from the part's -X axis, so ``(-R, 0)`` has C = 0.  To bring that point
  under the tool the table turns by -C: **+C turns the table clockwise seen from the
  tool**, i.e. the tool moves counter-clockwise relative to the part (the ISO 841 sense of
  +C for the tool).  C is unwrapped (continuous, may exceed 360) so the table never swings
  back through a turn between neighbouring points.
* The machine interpolates X, C and Z linearly, which traces a spiral piece in the part
  frame, not the straight chord.  Cutting moves are split until that spiral stays within
  ``tolerance`` of the chord; the true part-frame length of each move (what the bit
  travels over the wood) sets its inverse-time feed.

Toolpath per pocket (the paper's sequence), computed as if the pocket's centre were on
the rotation axis, then translated to its real centre and converted to C-X-Z:

1. Roughing: depth layers no deeper than ``step_down``; in each, concentric circles about
   the pocket centre, radius growing by ``rough_stepover`` (the bit radius by default);
   where a circle would leave the tool-centre region (walls/floor + ``allowance``) it
   follows that region's outline instead, then rejoins the circle.
2. Wall finishing: waterline contours at a fine pitch (``wall_stepover``, measured along a
   slanted wall).  A slanted wall is the outline offset inward by depth * tan(angle); the
   ball centre that touches it at height z lies on the outline offset by
   ``r / cos(a) - z tan(a)`` (exact for a ball in a tapered pocket, cones included).
3. Bottom: a flat floor gets one Archimedean spiral (pitch = ``stepover``) from the centre,
   clipped to the floor's tool-centre region and joined along its outline.  A spherical
   bowl gets a spiral on the sphere: the ball centre runs on the sphere of radius
   ``R_s - r`` and climbs ``stepover`` **measured along the design surface** per turn
   (the paper's helix pitch P), so the scallop is the same on steep and flat parts.
   Points are ``spacing`` (the paper's alpha) apart along circles and spirals, and at
   most ``spacing`` apart along outlines (outline vertices are kept so corners are not cut).

Finishing passes stand ``tolerance + region.ARC_TOLERANCE`` off the design surface, so the
polygonal approximation of round offsets and the machine's rotary interpolation never
gouge: the surfaces are left at most that much proud (plus the scallops).  :func:`max_gouge` checks it against
the analytic pocket: from ball positions along the interpolated machine motion it bounds the
penetration in between, probing more positions only where that bound is not tight.

The spherical bowl: its lowest point is at the pocket centre, ``depth`` below the top; the
sphere radius must reach the whole outline at or below the top, R_s >= (a^2 + d^2) / 2d
with a the farthest outline point.  A plane cuts a sphere in a circle, so a non-circular
outline leaves a vertical rim where the outline cuts the sphere below the top (reported as
``rim_wall_mm``; zero for a circle of exactly that size).  Spherical bowls have vertical
rims only (wall angle 0).

Cycle time, compared with the paper: the built-in sample (:func:`sample_job`, three pockets
in a 105 mm block, 6 mm bit, P = alpha = 1 mm, 1500 mm/min on the wood, 300 mm/min plunges)
is estimated at 8 min 43 s (slanted tray 5:14, peanut 2:21, bowl 1:07); the paper machined
its three pockets in 8 min 22 s.  Its feeds and pocket sizes are not published, so this
is a sanity check of the order of magnitude, not a reproduction.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from manifold3d import CrossSection

from . import kinematics
from . import region as rg
from .errors import InputError
from .kinematics import (DEFAULT_MAX_TABLE_RPM, cycle_time, from_cylindrical, inverse_time_feed,  # noqa: F401
                         move_times, part_points, to_cylindrical, unwrap_c)
from .program import RAPID, Operation, PathBuilder, Program, Tool

BOTTOMS = ("flat", "sphere")
MAX_WALL_ANGLE = 75.0          # degrees from vertical
# Elements per block where work on long arrays is cut into blocks: numpy temporaries beyond
# ~128 kB come fresh from the OS (page faults) each time and cost several times the arithmetic.
_BLOCK = 4096


class RotaryError(InputError):
    """Input the rotary-pocket workflow cannot use; the message names what is wrong."""


def _is_number(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool) \
        and math.isfinite(value)


def _norms(v: np.ndarray) -> np.ndarray:
    """Lengths of the rows of (n, 2) or (n, 3) vectors (np.linalg.norm is slow on short rows)."""
    return np.sqrt(sum(v[:, k] * v[:, k] for k in range(v.shape[1])))


def _same_point(a: np.ndarray, b: np.ndarray) -> bool:
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
            if not _is_number(value):
                raise RotaryError(f"{name.replace('_', ' ')} must be a finite number, got {value!r}")
        for name in names:
            if name != "allowance" and getattr(self, name) <= 0:
                raise RotaryError(f"{name.replace('_', ' ')} must be greater than zero, got {getattr(self, name)}")
        if self.allowance < 0:
            raise RotaryError(f"allowance must be >= 0, got {self.allowance}")
        if self.tool.kind != "ball":
            raise RotaryError(f"the rotary pockets are cut with a ball-nose bit, not a {self.tool.kind} tool")
        for name in ("stepover", "roughing_stepover", "wall_stepover"):
            if getattr(self, name) > self.tool.diameter:
                raise RotaryError(f"{name.replace('_', ' ')} {getattr(self, name)} mm is wider than the "
                                  f"{self.tool.diameter} mm bit: ridges would be left standing")
        if not 0 < self.approach_gap < self.clearance_z <= self.safe_z:
            raise RotaryError("heights must satisfy 0 < approach gap < clearance plane <= safe Z")


@dataclass
class PocketPath:
    """One pocket's result.  Chains are part-frame tool-tip points (k, 3), in cutting order."""

    pocket: Pocket
    operation: Operation
    report: dict
    roughing: list = field(default_factory=list)      # [(tip z of the layer, chain), ...]
    wall: list = field(default_factory=list)          # [(tip z of the contour, chain), ...]
    bottom: list = field(default_factory=list)        # [chain, ...]


@dataclass
class RotaryResult:
    program: Program
    pockets: list
    reports: list
    cycle_time_s: float


# ----------------------------------------------------------------------------------------
# Machine coordinates (the conversion itself: :mod:`kinematics`)
# ----------------------------------------------------------------------------------------

def _endpoints(op: Operation):
    """(x0, c0, z0, x1, c1, z1) per move; the operation starts at its first C."""
    a, b, c0, c1 = kinematics.operation_c_moves(op)
    return a[:, 0], c0, a[:, 2], b[:, 0], c1, b[:, 2]


def move_lengths(op: Operation) -> np.ndarray:
    """Length of every move along the path it traces on the part (mm)."""
    return op.move_lengths()


def _to_machine(kind, xyz, feed, tolerance, start_c):
    """Part-frame moves (tool tip) -> machine moves: cutting moves split until the rotary
    interpolation stays within ``tolerance`` of the chord, C unwrapped.  A move is sampled
    unless its bend (:func:`kinematics.speed_and_bend`) keeps it that close anyway; after a split only
    the two halves are checked again (a split leaves every other move as it was)."""
    kind, xyz, feed = np.asarray(kind), np.asarray(xyz, float), np.asarray(feed, float)
    moved = np.ones(len(kind), bool)
    moved[1:] = np.any(np.abs(np.diff(xyz, axis=0)) > 1e-9, axis=1)
    kind, xyz, feed = kind[moved], xyz[moved], feed[moved]
    check = np.flatnonzero(kind[1:] != RAPID) + 1        # cutting moves, by the index of their end
    for _ in range(40):
        x_word, c_raw = to_cylindrical(xyz[:, :2])
        c = unwrap_c(c_raw, -x_word, start_c)
        _, bend = kinematics.speed_and_bend(x_word[check - 1], c[check - 1], x_word[check], c[check])
        check = check[bend > 8 * tolerance]
        a, b = check - 1, check
        worst = np.zeros(len(check))
        for t in (0.25, 0.5, 0.75):
            on_machine = kinematics.interpolate(x_word[a], c[a], xyz[a, 2], x_word[b], c[b], xyz[b, 2],
                                                np.full(len(a), t))
            chord = xyz[a] + (xyz[b] - xyz[a]) * t
            worst = np.maximum(worst, _norms(on_machine - chord))
        split = check[worst > tolerance]
        if not len(split):
            return kind, np.column_stack([x_word, np.zeros(len(x_word)), xyz[:, 2]]), feed, c
        mid = (xyz[split - 1] + xyz[split]) / 2
        kind = np.insert(kind, split, kind[split])
        xyz = np.insert(xyz, split, mid, axis=0)
        feed = np.insert(feed, split, feed[split])
        inserted = split + np.arange(len(split))         # where the midpoints went
        check = np.column_stack([inserted, inserted + 1]).ravel()
    raise RotaryError("a cutting move could not be linearised for the rotary table (path through the axis?)")


# ----------------------------------------------------------------------------------------
# Pocket geometry (local frame: pocket centre at the origin, ball-centre heights)
# ----------------------------------------------------------------------------------------

def _disk(radius: float) -> CrossSection:
    """A disk whose polygon lies inside the true circle (vertices on it)."""
    n = rg.circle_segments(radius)
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return CrossSection([np.column_stack([radius * np.cos(a), radius * np.sin(a)])])


def _squared_distance(px, py, ax, ay, dx, dy, inverse) -> np.ndarray:
    """Squared distance from points (px, py) to segments from (ax, ay) by (dx, dy), with
    ``inverse`` = 1 / (dx^2 + dy^2); arrays that broadcast."""
    rx, ry = px - ax, py - ay
    s = np.clip((rx * dx + ry * dy) * inverse, 0.0, 1.0)
    rx, ry = rx - s * dx, ry - s * dy
    return rx * rx + ry * ry


class _OutlineDistance:
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
        for block in np.array_split(np.arange(len(cx)), len(cx) * len(loop) // _BLOCK + 1):
            dist = np.sqrt(_squared_distance(cx[block, None], cy[block, None], self.ax, self.ay, self.dx, self.dy,
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
        return np.sqrt(_squared_distance(px[:, None], py[:, None], self.ax, self.ay, self.dx, self.dy,
                                         self.inverse).min(axis=1))

    def __call__(self, points: np.ndarray) -> np.ndarray:
        points = np.asarray(points, float).reshape(-1, 2)
        px, py = points[:, 0].copy(), points[:, 1].copy()
        out = np.full(len(points), self.cap)
        ix, iy = np.floor((px - self.low[0]) / self.size), np.floor((py - self.low[1]) / self.size)
        on_grid = (ix >= 0) & (iy >= 0) & (ix < self.shape[0]) & (iy < self.shape[1])
        cell = np.where(on_grid, iy * self.shape[0] + ix, 0).astype(int)
        rows = np.flatnonzero(on_grid & (self.count[cell] > 0))
        for block in np.array_split(rows, int(self.count[cell[rows]].sum()) // _BLOCK + 1):
            count = self.count[cell[block]]
            group = np.cumsum(count) - count
            edge = self.edges[np.repeat(self.first[cell[block]] - group, count) + np.arange(count.sum())]
            point = np.repeat(block, count)
            square = _squared_distance(px[point], py[point], self.ax[edge], self.ay[edge], self.dx[edge],
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


class _Geometry:
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
            if not _is_number(value):
                raise RotaryError(f"{what}: {name.replace('_', ' ')} must be a finite number, got {value!r}")
        if pocket.centre is None:
            centre = np.array(rg.centroid(absolute), float)
        else:
            centre = np.asarray(pocket.centre, float).reshape(-1)
            if centre.shape != (2,) or not np.all(np.isfinite(centre)):
                raise RotaryError(f"{what}: the centre must be two finite numbers, got {pocket.centre!r}")
        if pocket.depth <= 0:
            raise RotaryError(f"{what}: depth must be greater than zero, got {pocket.depth}")
        if pocket.depth >= block.thickness:
            raise RotaryError(f"{what}: depth {pocket.depth} mm goes through the {block.thickness} mm board")
        if pocket.depth > settings.tool.flute_length:
            raise RotaryError(f"{what}: depth {pocket.depth} mm is beyond the bit's flute length "
                              f"{settings.tool.flute_length} mm")
        if not 0 <= pocket.wall_angle_deg <= MAX_WALL_ANGLE:
            raise RotaryError(f"{what}: wall angle must be 0..{MAX_WALL_ANGLE} degrees from vertical, "
                              f"got {pocket.wall_angle_deg}")
        if pocket.bottom not in BOTTOMS:
            raise RotaryError(f"{what}: bottom must be one of {BOTTOMS}, got {pocket.bottom!r}")
        half = np.array([block.size_x, block.size_y]) / 2
        if np.any(np.abs(loop) > half + 1e-9):
            raise RotaryError(f"{what}: the outline reaches outside the {block.size_x} x {block.size_y} mm board")

        self.centre = centre
        self.loop = loop - centre
        self.region = rg.from_loops([self.loop], what)
        self._insets = {}
        self.depth = float(pocket.depth)
        self.theta = math.radians(pocket.wall_angle_deg)
        self.bottom = pocket.bottom
        self.standoff = settings.standoff
        self.far = float(_norms(self.loop).max())
        self.sphere_radius = None
        if self.bottom == "sphere":
            rs = pocket.sphere_radius
            if not _is_number(rs):
                raise RotaryError(f"{what}: a spherical bowl needs a finite sphere radius, got {rs!r}")
            if pocket.wall_angle_deg != 0:
                raise RotaryError(f"{what}: a spherical bowl has a vertical rim; set the wall angle to 0")
            if not rg.contains_points(self.region, np.zeros((1, 2)))[0]:
                raise RotaryError(f"{what}: the bowl's lowest point (the centre) is outside the outline")
            needed = (self.far ** 2 + self.depth ** 2) / (2 * self.depth)
            if rs < needed:
                raise RotaryError(f"{what}: sphere radius {rs} mm is smaller than the opening requires: a bowl "
                                  f"{self.depth} mm deep reaching {self.far:.2f} mm from its centre needs "
                                  f"at least {needed:.2f} mm")
            self.sphere_radius = float(rs)
        if rg.area(self.bottom_region()) < rg.MIN_AREA:
            raise RotaryError(f"{what}: the {settings.tool.diameter:g} mm bit does not fit in the pocket"
                              + (" at its floor (the slanted walls close it in)" if self.theta else ""))
        # No ball centre needs to be farther from the outline than at the floor.
        self.walls = _OutlineDistance(self.loop, self.region, self.wall_offset(self.floor_z(0.0)) + 1.0)
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
        if self.bottom == "flat":
            return self.region_at(self.floor_z(self.standoff), self.standoff)
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
            bottom = _norms(centres - np.array([0.0, 0.0, self.sphere_centre_z])) - (self.sphere_radius - r)
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


# ----------------------------------------------------------------------------------------
# Curves and joining them along outlines
# ----------------------------------------------------------------------------------------

def _densify(points: np.ndarray, spacing: float) -> np.ndarray:
    """Keep every vertex, split segments longer than ``spacing``; drop repeated points."""
    points = np.asarray(points, float)
    seg = np.diff(points, axis=0)
    length = _norms(seg)
    if not np.all(length > 1e-6):
        points = points[np.concatenate([[True], length > 1e-6])]
        seg = np.diff(points, axis=0)
        length = _norms(seg)
    count = np.maximum(1, np.ceil(length / spacing - 1e-9).astype(int))
    if len(points) < 2 or count.max() == 1:
        return points
    starts = np.repeat(points[:-1], count, axis=0)
    steps = np.repeat(seg / count[:, None], count, axis=0)
    k = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    return np.vstack([starts + steps * k[:, None], points[-1:]])


def _circle(radius: float, spacing: float) -> np.ndarray:
    """Closed circle about the origin, counter-clockwise, points ``spacing`` apart (at most)."""
    n = max(12, math.ceil(2 * math.pi * radius / spacing))
    a = np.linspace(0, 2 * np.pi, n + 1)
    pts = np.column_stack([radius * np.cos(a), radius * np.sin(a)])
    pts[-1] = pts[0]
    return pts


def _by_arc_length(curve: np.ndarray, spacing: float) -> np.ndarray:
    """Points ``spacing`` apart along a densely sampled curve (k, d)."""
    s = np.concatenate([[0.0], np.cumsum(_norms(np.diff(curve, axis=0)))])
    targets = np.append(np.arange(0.0, s[-1], spacing), s[-1])
    return np.column_stack([np.interp(targets, s, curve[:, j]) for j in range(curve.shape[1])])


class _Boundary:
    """A region's outline, prepared once for clipping curves to it and walking along it.

    Edges are numbered loop after loop; edge k runs from ``start[k]`` by ``vector[k]``."""

    def __init__(self, region: CrossSection):
        self.region = region
        self.loops = rg.loops(region)
        sizes = [len(loop) for loop in self.loops]
        self.loop_of = np.repeat(np.arange(len(sizes)), sizes)
        self.first_edge = np.cumsum(sizes) - sizes
        self.start = np.vstack(self.loops)
        self.vector = np.vstack([np.roll(loop, -1, axis=0) for loop in self.loops]) - self.start
        ends = self.start[:, 1] + self.vector[:, 1]
        self.y_low, self.y_high = np.minimum(self.start[:, 1], ends), np.maximum(self.start[:, 1], ends)
        self.far = float(_norms(self.start).max())            # from the origin to the farthest vertex
        vx, vy = self.vector[:, 0], self.vector[:, 1]            # and to the nearest point of the outline
        self.near = float(np.sqrt(_squared_distance(0.0, 0.0, self.start[:, 0], self.start[:, 1], vx, vy,
                                                    1.0 / np.maximum(vx * vx + vy * vy, 1e-300)).min()))
        # Per loop, over two rounds so any run of edges is one slice: the angle each edge turns
        # about the origin and its length, summed from the loop's first vertex.
        self.angles, self.turned, self.walked = [], [], []
        for loop in self.loops:
            angle = np.arctan2(loop[:, 1], loop[:, 0])
            step = np.tile(_short(np.roll(angle, -1) - angle), 2)
            length = np.tile(_norms(np.roll(loop, -1, axis=0) - loop), 2)
            self.angles.append(angle)
            self.turned.append(np.concatenate([[0.0], np.cumsum(step)]))
            self.walked.append(np.concatenate([[0.0], np.cumsum(length)]))

    def _crossings(self, starts: np.ndarray, vectors: np.ndarray) -> np.ndarray:
        """Where a polyline's segments cross the outline, as segment index + parameter.

        Only segment-edge pairs whose heights overlap are tested: with the segments sorted by
        their lower end, those an edge can meet are one run, found by binary search."""
        low = np.minimum(starts[:, 1], starts[:, 1] + vectors[:, 1])
        order = np.argsort(low, kind="stable")
        rising = float(np.abs(vectors[:, 1]).max())
        first = np.searchsorted(low[order], self.y_low - rising, "left")
        count = np.searchsorted(low[order], self.y_high, "right") - first
        edge = np.repeat(np.arange(len(count)), count)
        segment = order[np.repeat(first, count) + np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)]
        d, f = vectors[segment], self.vector[edge]
        rel = self.start[edge] - starts[segment]
        denom = d[:, 0] * f[:, 1] - d[:, 1] * f[:, 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (rel[:, 0] * f[:, 1] - rel[:, 1] * f[:, 0]) / denom
            u = (rel[:, 0] * d[:, 1] - rel[:, 1] * d[:, 0]) / denom
        hit = (np.abs(denom) > 1e-15) & (t > 0) & (t < 1) & (u >= 0) & (u <= 1)
        return segment[hit] + t[hit]

    def clip(self, points: np.ndarray) -> list:
        """Parts of a polyline inside the region, as (k, 2) arrays: split at every crossing, a
        part kept when its midpoint is inside; a closed polyline cut open is re-joined across
        its start."""
        starts, vectors = points[:-1], np.diff(points, axis=0)
        u = np.unique(np.concatenate([np.arange(len(points), dtype=float), self._crossings(starts, vectors)]))
        segment = np.minimum(np.floor(u).astype(int), len(starts) - 1)
        refined = starts[segment] + vectors[segment] * (u - segment)[:, None]
        keep = rg.contains_points(self.region, (refined[:-1] + refined[1:]) / 2)
        change = np.flatnonzero(np.diff(np.concatenate([[False], keep, [False]])))
        pieces = [refined[a:b + 1] for a, b in zip(change[::2], change[1::2])]
        if _same_point(points[0], points[-1]) and len(pieces) > 1 and keep[0] and keep[-1]:
            pieces[0] = np.vstack([pieces.pop()[:-1], pieces[0]])
        return [p for p in pieces if len(p) >= 2]

    def locate(self, points: np.ndarray) -> list:
        """For each point (n, 2): (loop, edge within it, parameter) of the outline edge it lies
        on, or None."""
        d = self.vector
        rx, ry = points[:, None, 0] - self.start[:, 0], points[:, None, 1] - self.start[:, 1]
        t = np.clip((rx * d[:, 0] + ry * d[:, 1]) / np.maximum(d[:, 0] ** 2 + d[:, 1] ** 2, 1e-300), 0, 1)
        dist = np.sqrt((rx - t * d[:, 0]) ** 2 + (ry - t * d[:, 1]) ** 2)
        edge = np.argmin(dist, axis=1)
        found = []
        for k, e in enumerate(edge):
            loop = self.loop_of[e]
            found.append(None if dist[k, e] > 1e-6 else (loop, e - self.first_edge[loop], float(t[k, e])))
        return found

    def path(self, a: np.ndarray, where_a, b: np.ndarray, where_b):
        """The way along the outline from a (where a counter-clockwise curve about the origin
        left the region) to b (where it comes back), given where they lie (:meth:`locate`):
        the way that turns about the origin as the curve did, the shorter one if both do;
        None when a and b are not on the same outline loop."""
        if where_a is None or where_b is None or where_a[0] != where_b[0]:
            return None
        wanted = (math.atan2(b[1], b[0]) - math.atan2(a[1], a[0])) % (2 * math.pi)
        ways = [self._way(a, where_a, b, where_b, forward) for forward in (True, False)]
        forward = min(ways, key=lambda way: (round(abs(way[0] - wanted), 6), way[1])) is ways[0]
        (index, ea, ta), (_, eb, tb) = where_a, where_b
        return _walk(self.loops[index], a, ea, ta, b, eb, tb, forward)

    def _way(self, a, where_a, b, where_b, forward: bool) -> tuple:
        """(angle turned about the origin, length) of :func:`_walk`'s way from a to b, from the
        loop's running sums: a few numbers, not the path."""
        (index, ea, ta), (_, eb, tb) = where_a, where_b
        loop, angle = self.loops[index], self.angles[index]
        n = len(loop)
        if ea == eb and (tb >= ta if forward else tb <= ta):
            return _short(math.atan2(b[1], b[0]) - math.atan2(a[1], a[0])), math.dist(a, b)
        if forward:      # a, vertices ea + 1 ... eb, b
            first, last, count = (ea + 1) % n, eb, (eb - ea - 1) % n
            edges, sign = first, 1.0
        else:            # a, vertices ea ... eb + 1, b (the edges between them walked backwards)
            first, last, count = ea, (eb + 1) % n, (ea - eb - 1) % n
            edges, sign = last, -1.0
        turned = self.turned[index][edges + count] - self.turned[index][edges]
        walked = self.walked[index][edges + count] - self.walked[index][edges]
        sweep = (_short(angle[first] - math.atan2(a[1], a[0])) + sign * turned
                 + _short(math.atan2(b[1], b[0]) - angle[last]))
        return sweep, math.dist(a, loop[first]) + walked + math.dist(loop[last], b)


def _short(angle):
    """An angle (radians) taken the short way round, in (-pi, pi]."""
    return math.pi - (math.pi - angle) % (2 * math.pi)


def _walk(loop: np.ndarray, a, ea, ta, b, eb, tb, forward: bool) -> np.ndarray:
    """From a (on edge ea at ta) along the loop to b (on edge eb at tb), through the vertices
    between them."""
    n = len(loop)
    if ea == eb and (tb >= ta if forward else tb <= ta):
        return np.array([a, b])
    if forward:
        vertices = (ea + 1 + np.arange((eb - ea - 1) % n + 1)) % n
    else:
        vertices = (ea - np.arange((ea - eb - 1) % n + 1)) % n
    return np.vstack([a, loop[vertices], b])


def follow_inside(curve: np.ndarray, boundary: _Boundary, closed: bool) -> list:
    """A counter-clockwise curve about the origin (circle or spiral, (k, 2)) kept inside
    the region: where it would leave, it follows the region's outline to where it comes back.
    Returns chains (k, 2); pieces that cannot be joined (another outline loop) stay apart."""
    pieces = boundary.clip(curve)
    if not pieces:
        return []
    if closed and len(pieces) == 1 and _same_point(pieces[0][0], pieces[0][-1]):
        return pieces
    where = boundary.locate(np.array([p[0] for p in pieces] + [p[-1] for p in pieces]))
    begins, ends = where[:len(pieces)], where[len(pieces):]
    chains = [pieces[0]]
    for k in range(1, len(pieces)):
        path = boundary.path(pieces[k - 1][-1], ends[k - 1], pieces[k][0], begins[k])
        if path is None:
            chains.append(pieces[k])
        else:
            chains[-1] = np.vstack([chains[-1], path[1:-1], pieces[k]])
    if closed:
        path = boundary.path(pieces[-1][-1], ends[-1], pieces[0][0], begins[0])
        if path is not None:
            if len(chains) == 1:
                chains[0] = np.vstack([chains[0], path[1:-1], chains[0][:1]])
            else:
                chains[0] = np.vstack([chains.pop(), path[1:-1], chains[0]])
    return chains


def _closed_loops(region: CrossSection) -> list:
    return [np.vstack([loop, loop[:1]]) for loop in rg.loops(region)]


def _inner_point(piece: CrossSection) -> np.ndarray:
    """The origin when it is inside the piece, else a point well inside it."""
    for candidate in (np.zeros(2), np.array(rg.centroid(piece))):
        if rg.contains_points(piece, candidate[None, :])[0]:
            return candidate
    y, intervals = rg.raster_rows(piece, 1e9)[0]
    x0, x1 = max(intervals, key=lambda iv: iv[1] - iv[0])
    return np.array([(x0 + x1) / 2, y])


# ----------------------------------------------------------------------------------------
# Passes (local frame, ball centres)
# ----------------------------------------------------------------------------------------

def _roughing(geo: _Geometry, settings: RotarySettings) -> list:
    """[(z, chain (k, 3)), ...]: per layer, each piece's centre, then circles out to its outline."""
    extra = settings.allowance + settings.standoff
    # The deepest layer: on a flat floor the ball keeps the standoff too, or that layer's region
    # would be empty and the floor finishing would take the whole last step at once.
    bottom_tip = geo.floor_z(extra) - geo.r if geo.bottom == "flat" else -geo.depth + settings.allowance
    layers = max(1, math.ceil(-bottom_tip / settings.step_down - 1e-9))
    passes, region, chains = [], None, []
    for k in range(1, layers + 1):
        z = bottom_tip * k / layers + geo.r
        above = region
        region = geo.region_at(z, extra)
        if region is not above:     # (geo.inset hands vertical walls over a flat floor one region)
            chains = [_densify(c, settings.spacing) for c in _layer(region, settings)]
        passes += [(z, _lift(c, z)) for c in chains]
    return passes


def _layer(region: CrossSection, settings: RotarySettings) -> list:
    """One roughing layer in plan: per piece of the region its centre, then circles out to its
    outline, then the outline."""
    chains = []
    for piece in rg.components(region):
        centre = _inner_point(piece)
        boundary = _Boundary(piece.translate(tuple(-centre)))
        chains.append(centre[None, :])
        radius = settings.roughing_stepover
        while radius < boundary.far:
            circle = _circle(radius, settings.spacing)
            # Nearer the (inner) centre than the outline is, the circle is inside as a whole.
            inside = [circle] if radius < boundary.near else follow_inside(circle, boundary, True)
            chains += [c + centre for c in inside]
            radius += settings.roughing_stepover
        chains += _closed_loops(piece)
    return chains


def _lift(chain: np.ndarray, z) -> np.ndarray:
    return np.column_stack([chain, np.broadcast_to(z, len(chain))])


def _wall_levels(geo: _Geometry, settings: RotarySettings) -> np.ndarray:
    step = settings.wall_stepover * math.cos(geo.theta)
    if geo.bottom == "flat":
        top, bottom = geo.r * math.sin(geo.theta), geo.floor_z(settings.standoff)
    else:
        # Down to where the ball last touches the rim: on the bowl's locus, beside the wall.
        nearest = geo.centre_to_outline - geo.r - settings.standoff
        top = 0.0
        bottom = float(geo.sphere_z(np.array([[nearest, 0.0]]), settings.standoff)[0])
        if bottom >= top:
            return np.empty(0)
    count = max(1, math.ceil((top - bottom) / step - 1e-9))
    return top - (top - bottom) * np.arange(1, count + 1) / count


def _wall_finishing(geo: _Geometry, settings: RotarySettings) -> list:
    passes = []
    for z in _wall_levels(geo, settings):
        for loop in _closed_loops(geo.region_at(z, settings.standoff)):
            passes.append((z, _lift(_densify(loop, settings.spacing), z)))
    return passes


def _floor_spiral(geo: _Geometry, settings: RotarySettings) -> list:
    """One Archimedean spiral per piece of the floor (the pocket centre when it is on the
    floor), pitch ``stepover``, clipped to the floor's tool-centre region."""
    z = geo.floor_z(settings.standoff)
    b = settings.stepover / (2 * math.pi)
    chains = []
    for piece in rg.components(geo.bottom_region()):
        centre = _inner_point(piece)
        boundary = _Boundary(piece.translate(tuple(-centre)))
        far = boundary.far
        turns = far / settings.stepover + 1
        phi = np.linspace(0, 2 * math.pi * turns, max(2000, math.ceil(40 * turns * far / settings.spacing)))
        spiral = _by_arc_length(np.column_stack([b * phi * np.cos(phi), b * phi * np.sin(phi)]), settings.spacing)
        chains += [_lift(_densify(c + centre, settings.spacing), z) for c in follow_inside(spiral, boundary, False)]
    return chains


def _bowl_spiral(geo: _Geometry, settings: RotarySettings) -> list:
    boundary = _Boundary(geo.bottom_region())
    rho = geo.locus_radius(settings.standoff)
    far = boundary.far
    psi_end = math.asin(min(1.0, far / rho + settings.stepover / geo.sphere_radius))
    turns = psi_end * geo.sphere_radius / settings.stepover
    phi = np.linspace(0, 2 * math.pi * turns, max(2000, math.ceil(40 * turns * far / settings.spacing)))
    psi = phi / (2 * math.pi) * settings.stepover / geo.sphere_radius
    helix = np.column_stack([rho * np.sin(psi) * np.cos(phi), rho * np.sin(psi) * np.sin(phi),
                             geo.sphere_centre_z - rho * np.cos(psi)])
    helix = _by_arc_length(helix, settings.spacing)
    chains = []
    for c in follow_inside(helix[:, :2], boundary, False):
        chains.append(_densify(np.column_stack([c, geo.sphere_z(c, settings.standoff)]), settings.spacing))
    return chains


# ----------------------------------------------------------------------------------------
# Planning
# ----------------------------------------------------------------------------------------

def _safe_links(geo: _Geometry, a: np.ndarray, b: np.ndarray, margin: float) -> np.ndarray:
    """Which balls can feed straight from centre a to centre b (rows, local) and stay
    ``margin`` off the design surface all the way?"""
    def at(links, t):
        return a[links] + (b[links] - a[links]) * t[:, None]
    plan_length = _norms((b - a)[:, :2])
    top = geo.highest(at, np.arange(len(a)), geo.probe(a), geo.probe(b), plan_length, np.zeros(len(a)), -margin)
    return top <= -margin


def _pocket_operation(geo: _Geometry, settings: RotarySettings, start_c):
    """Build one pocket's moves in the part frame, then convert them to C-X-Z."""
    rough = _roughing(geo, settings)
    wall = _wall_finishing(geo, settings)
    bottom = _floor_spiral(geo, settings) if geo.bottom == "flat" else _bowl_spiral(geo, settings)
    builder = PathBuilder(settings.clearance_z, settings.cutting_speed, settings.plunge_speed,
                          settings.approach_gap)
    offset = np.array([geo.centre[0], geo.centre[1], -geo.r])
    chains = [c for _, c in rough] + [c for _, c in wall] + bottom
    for k in range(1, len(chains)):
        chains[k] = _start_nearest(chains[k], chains[k - 1][-1])
    ends = np.array([c[-1] for c in chains[:-1]]).reshape(-1, 3)
    starts = np.array([c[0] for c in chains[1:]]).reshape(-1, 3)
    linked = np.concatenate([[False], _safe_links(geo, ends, starts, settings.tolerance / 2)])
    for k, chain in enumerate(chains):
        if linked[k]:
            down = chain[0][2] < chains[k - 1][-1][2] - 1e-9
            builder.line(*(chain[0] + offset), feed=settings.plunge_speed if down else None)
        else:
            builder.plunge(*(chain[0] + offset))
        builder.polyline(chain[1:] + offset)
    builder.retract()
    moves = builder.arrays()
    kind, xyz, feed, c = _to_machine(moves["kind"], moves["xyz"], moves["feed"], settings.tolerance, start_c)
    op = Operation(name=geo.name, tool=settings.tool, spindle_rpm=settings.spindle_rpm, kind=kind, xyz=xyz,
                   feed=feed, rotary={"c": c}, clearance_z=settings.clearance_z, safe_z=settings.safe_z,
                   start=np.array([xyz[0, 0], 0.0, settings.safe_z]),
                   comment="C-X-Z pocket: X = -R, C degrees, tool tip Z, feeds along the part")

    return (op, [(z - geo.r, c + offset) for z, c in rough], [(z - geo.r, c + offset) for z, c in wall],
            [c + offset for c in bottom])


def _is_closed(chain: np.ndarray) -> bool:
    return len(chain) > 2 and _same_point(chain[0], chain[-1])


def _start_nearest(chain: np.ndarray, here: np.ndarray) -> np.ndarray:
    if not _is_closed(chain):
        return chain
    index = int(np.argmin(_norms(chain[:-1] - here)))
    return np.vstack([chain[index:-1], chain[:index + 1]])       # the closed chain from index round


def max_gouge(pocket: Pocket, op: Operation, block: Block = Block(),
              settings: RotarySettings = RotarySettings()) -> float:
    """Deepest cut past the pocket's design surface (mm, 0 when clear) along every cutting move
    as the machine interpolates it (X, C, Z linear).

    Not a sample but a bound: never below the true depth, and above it by at most
    1e-7 mm + 0.1 % (:meth:`_Geometry.highest`).  So 0 means the ball never cuts in."""
    return _max_gouge(_Geometry(pocket, block, settings), op)


def _max_gouge(geo: _Geometry, op: Operation) -> float:
    x0, c0, z0, x1, c1, z1 = _endpoints(op)
    offset = np.array([geo.centre[0], geo.centre[1], -geo.r])

    def at(moves, t):
        return kinematics.interpolate(x0[moves], c0[moves], z0[moves], x1[moves], c1[moves], z1[moves], t) - offset
    speed, bend = kinematics.speed_and_bend(x0, c0, x1, c1)
    deepest, before = 0.0, geo.probe(at(np.zeros(1, int), np.zeros(1)))
    for moves in np.array_split(np.arange(len(op)), len(op) // _BLOCK + 1):
        ends = geo.probe(at(moves, np.ones(len(moves))))
        starts = np.vstack([before, ends[:-1]])
        before = ends[-1:]
        cut = op.kind[moves] != RAPID
        if cut.any():
            top = geo.highest(at, moves[cut], starts[cut], ends[cut], speed[moves[cut]], bend[moves[cut]], 0.0,
                              overall=True)
            deepest = max(deepest, float(top.max()))
    return deepest


def plan(block: Block, pockets: list, settings: RotarySettings = RotarySettings(),
         name: str = "rotary pockets", progress=None) -> RotaryResult:
    """Plan every pocket in order: one Operation per pocket, C continuous across them.

    The IR holds machine coordinates: xyz = (X word = -R, 0, tool-tip Z), rotary["c"] in
    degrees, feed in mm/min along the path on the part (the post turns it into G93 F).
    ``progress``: optional callable(fraction, text).
    """
    settings.validate()
    report = progress or (lambda fraction, text: None)
    for value in (block.size_x, block.size_y, block.thickness):
        if not (_is_number(value) and value > 0):
            raise RotaryError(f"board sizes must be positive numbers, got {block}")
    if not pockets:
        raise RotaryError("no pockets to cut")
    names = [p.name for p in pockets]
    if len(set(names)) != len(names):
        raise RotaryError(f"pocket names must be unique, got {names}")
    geometries = [_Geometry(p, block, settings) for p in pockets]
    for i, a in enumerate(geometries):
        for b in geometries[i + 1:]:
            overlap = rg.area(a.region.translate(tuple(a.centre)) ^ b.region.translate(tuple(b.centre)))
            if overlap > rg.MIN_AREA:
                raise RotaryError(f"pockets {a.name!r} and {b.name!r} overlap ({overlap:.1f} mm^2)")

    results, c_now = [], None
    for index, (pocket, geo) in enumerate(zip(pockets, geometries)):
        report(index / len(pockets), f"pocket {pocket.name}")
        op, rough, wall, bottom = _pocket_operation(geo, settings, c_now)
        c_now = float(op.rotary["c"][-1])
        surface_radius = geo.sphere_radius if geo.bottom == "sphere" else math.inf
        scallop_bottom = scallop_height(geo.r, settings.stepover, surface_radius)
        scallop_wall = scallop_height(geo.r, settings.wall_stepover)
        lengths = move_lengths(op)
        entry = {
            "name": pocket.name,
            "bottom": pocket.bottom,
            "wall_angle_deg": float(pocket.wall_angle_deg),
            "depth_mm": geo.depth,
            "centre": [round(float(v), 4) for v in geo.centre],
            "sphere_radius_mm": geo.sphere_radius,
            "outline": [[round(float(x), 4), round(float(y), 4)] for x, y in geo.loop + geo.centre],
            "points": int(np.count_nonzero(op.kind != RAPID)),
            "path_length_mm": round(float(lengths[op.kind != RAPID].sum()), 1),
            "max_gouge_mm": round(_max_gouge(geo, op), 6),
            "scallop_mm": round(max(scallop_bottom, scallop_wall), 4),
            "scallop_bottom_mm": round(scallop_bottom, 4),
            "scallop_wall_mm": round(scallop_wall, 4),
            "rim_wall_mm": round(geo.rim_wall(), 3),
            "cycle_time_s": round(float(move_times(op, settings.rapid_rate, settings.max_table_rpm, lengths).sum()), 1),
        }
        results.append(PocketPath(pocket, op, entry, rough, wall, bottom))
    report(1.0, "done")
    program = Program(name, [r.operation for r in results], rapid_rate=settings.rapid_rate,
                      notes=[f"C-X-Z rotary table: {len(pockets)} pockets, tool tip programmed, "
                             f"{settings.cutting_speed:g} mm/min along the path on the part"])
    total = sum(r.report["cycle_time_s"] for r in results)
    return RotaryResult(program, results, [r.report for r in results], round(total, 1))


# ----------------------------------------------------------------------------------------
# The built-in sample (the paper's bento block)
# ----------------------------------------------------------------------------------------

def _rounded_rectangle(cx, cy, width, height, radius, spacing=1.0) -> np.ndarray:
    hx, hy = width / 2 - radius, height / 2 - radius
    pts = []
    for (sx, sy), start in (((1, 1), 0), ((-1, 1), 90), ((-1, -1), 180), ((1, -1), 270)):
        a = np.radians(np.linspace(start, start + 90, max(2, math.ceil(radius * math.pi / 2 / spacing)) + 1))
        pts.append(np.column_stack([cx + sx * hx + radius * np.cos(a), cy + sy * hy + radius * np.sin(a)]))
    return np.vstack(pts)


def _polar_outline(cx, cy, radius_of, count=180) -> np.ndarray:
    a = np.linspace(0, 2 * np.pi, count, endpoint=False)
    r = radius_of(a)
    return np.column_stack([cx + r * np.cos(a), cy + r * np.sin(a)])


def sample_job() -> tuple[Block, list]:
    """A 105 x 105 x 30 mm block (the paper's larch block) with three non-circular pockets:

    1. "slanted tray": 56 x 34 mm rounded rectangle, 12 mm deep, walls 15 degrees, flat floor;
    2. "peanut": a waisted outline (concave sides), 10 mm deep, vertical walls, flat floor;
    3. "bowl": a rounded square (superellipse), no wall, spherical bowl 9 mm deep, R 22 mm.
    """
    pockets = [
        Pocket("slanted tray", _rounded_rectangle(0.0, 25.0, 56.0, 34.0, 10.0), depth=12.0, wall_angle_deg=15.0),
        Pocket("peanut", _polar_outline(-24.0, -24.0, lambda a: 15.0 * (1 + 0.3 * np.cos(2 * a))), depth=10.0),
        Pocket("bowl", _polar_outline(25.0, -25.0, lambda a: 16.0 / (np.abs(np.cos(a)) ** 2.5
                                                                      + np.abs(np.sin(a)) ** 2.5) ** (1 / 2.5)),
               depth=9.0, bottom="sphere", sphere_radius=22.0),
    ]
    return Block(105.0, 105.0, 30.0), pockets
