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
gouge: the surfaces are left at most that much proud (plus the scallops).  :func:`max_gouge` checks it by sampling
ball positions along the interpolated machine motion against the analytic pocket.

The spherical bowl: its lowest point is at the pocket centre, ``depth`` below the top; the
sphere radius must reach the whole outline at or below the top, R_s >= (a^2 + d^2) / 2d
with a the farthest outline point.  A plane cuts a sphere in a circle, so a non-circular
outline leaves a vertical rim where the outline cuts the sphere below the top (reported as
``rim_wall_mm``; zero for a circle of exactly that size).  Spherical bowls have vertical
rims only (wall angle 0).

Cycle time, compared with the paper: the built-in sample (:func:`sample_job`, three pockets
in a 105 mm block, 6 mm bit, P = alpha = 1 mm, 1500 mm/min on the wood, 300 mm/min plunges)
is estimated at 7 min 59 s (slanted tray 4:46, peanut 2:06, bowl 1:07); the paper machined
its three pockets in 8 min 22 s.  Its feeds and pocket sizes are not published, so this
is a sanity check of the order of magnitude, not a reproduction.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from manifold3d import CrossSection

from . import region as rg
from .errors import InputError
from .program import RAPID, Operation, PathBuilder, Program, Tool

BOTTOMS = ("flat", "sphere")
MAX_WALL_ANGLE = 75.0          # degrees from vertical
DEFAULT_MAX_TABLE_RPM = 60.0   # the face plate as a C axis, for feeds and time estimates
_ON_AXIS = 1e-9                # mm: points closer to the axis than this have no angle of their own


class RotaryError(InputError):
    """Input the rotary-pocket workflow cannot use; the message names what is wrong."""


def _is_number(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool) \
        and math.isfinite(value)


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
# Cylindrical coordinates
# ----------------------------------------------------------------------------------------

def to_cylindrical(xy) -> tuple[np.ndarray, np.ndarray]:
    """Part XY (n, 2) -> (X word = -R, C in degrees in (-180, 180]).  See the module notes for
    the sign of C; a point on the axis gets C = 0 (use :func:`unwrap_c` along a path)."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    # + 0.0 turns -0.0 into 0.0, so a point on the +X axis gets C = 180, not -180.
    return -np.hypot(xy[:, 0], xy[:, 1]), np.degrees(np.arctan2(0.0 - xy[:, 1], 0.0 - xy[:, 0]))


def from_cylindrical(x_word, c_deg) -> np.ndarray:
    """(X word, C degrees) -> part XY (n, 2): the machine point (X, 0) turned back by C."""
    x = np.asarray(x_word, float).reshape(-1)
    c = np.radians(np.asarray(c_deg, float).reshape(-1))
    return np.column_stack([x * np.cos(c), x * np.sin(c)])


def unwrap_c(c_deg, radius, start_c: float | None = None) -> np.ndarray:
    """Continuous C along a path: each value within 180 degrees of the one before it.

    Points on the axis (radius ~ 0) have no angle of their own and keep the previous C (the
    leading ones take the first C off the axis).  ``start_c`` is where the table already is:
    the path starts within half a turn of it.
    """
    c = np.array(c_deg, float).reshape(-1)
    on_axis = np.asarray(radius, float).reshape(-1) < _ON_AXIS
    if on_axis.all():
        return np.full(len(c), 0.0 if start_c is None else float(start_c))
    index = np.where(~on_axis, np.arange(len(c)), 0)
    np.maximum.accumulate(index, out=index)
    first = int(np.flatnonzero(~on_axis)[0])
    c = np.where(np.arange(len(c)) < first, c[first], c[index])
    if start_c is not None:
        c = np.concatenate([[start_c], c])
    c = np.unwrap(c, period=360.0)
    return c[1:] if start_c is not None else c


def _machine_at(x0, c0, z0, x1, c1, z1, t) -> np.ndarray:
    """Part-frame points (n, 3) of linear X/C/Z interpolation at parameter t (n,)."""
    x = x0 + (x1 - x0) * t
    xy = from_cylindrical(x, c0 + (c1 - c0) * t)
    return np.column_stack([xy, z0 + (z1 - z0) * t])


def _endpoints(op: Operation):
    """(x0, c0, z0, x1, c1, z1) per move; the operation starts at its first C."""
    x, z, c = op.xyz[:, 0], op.xyz[:, 2], op.rotary["c"]
    x0 = np.concatenate([[op.start[0]], x[:-1]])
    z0 = np.concatenate([[op.start[2]], z[:-1]])
    c0 = np.concatenate([[c[0]], c[:-1]])
    return x0, c0, z0, x, c, z


def move_lengths(op: Operation) -> np.ndarray:
    """Length of every move along the path it traces on the part (mm)."""
    return op.move_lengths()


def move_times(op: Operation, rapid_rate: float, max_table_rpm: float = DEFAULT_MAX_TABLE_RPM) -> np.ndarray:
    """Seconds per move.  Cutting: path length on the part / the move's feed, or longer when
    the table cannot turn that fast; rapids: the slowest axis (X/Z at ``rapid_rate``, C at
    ``max_table_rpm``)."""
    x0, c0, z0, x1, c1, z1 = _endpoints(op)
    table = np.abs(c1 - c0) / (360.0 * max_table_rpm)
    cutting = op.kind != RAPID
    minutes = np.where(cutting, move_lengths(op) / np.where(cutting, op.feed, 1.0),
                       np.hypot(x1 - x0, z1 - z0) / rapid_rate)
    return np.maximum(minutes, table) * 60.0


def inverse_time_feed(op: Operation, max_table_rpm: float = DEFAULT_MAX_TABLE_RPM) -> np.ndarray:
    """G93 F words: 1 / minutes for each cutting move (NaN for rapids)."""
    minutes = move_times(op, 1.0, max_table_rpm) / 60.0   # (the rapid rate does not matter here)
    with np.errstate(divide="ignore"):
        return np.where(op.kind != RAPID, 1.0 / minutes, np.nan)


def cycle_time(op: Operation, rapid_rate: float, max_table_rpm: float = DEFAULT_MAX_TABLE_RPM) -> float:
    return float(move_times(op, rapid_rate, max_table_rpm).sum())


def part_points(op: Operation) -> np.ndarray:
    """The operation's end points back in the part frame (n, 3), tool tip."""
    return np.column_stack([from_cylindrical(op.xyz[:, 0], op.rotary["c"]), op.xyz[:, 2]])


def _to_machine(kind, xyz, feed, tolerance, start_c):
    """Part-frame moves (tool tip) -> machine moves: cutting moves split until the rotary
    interpolation stays within ``tolerance`` of the chord, C unwrapped."""
    kind, xyz, feed = np.asarray(kind), np.asarray(xyz, float), np.asarray(feed, float)
    moved = np.ones(len(kind), bool)
    moved[1:] = np.any(np.abs(np.diff(xyz, axis=0)) > 1e-9, axis=1)
    kind, xyz, feed = kind[moved], xyz[moved], feed[moved]
    for _ in range(40):
        x_word, c_raw = to_cylindrical(xyz[:, :2])
        c = unwrap_c(c_raw, -x_word, start_c)
        cutting = np.flatnonzero(kind[1:] != RAPID) + 1
        a, b = cutting - 1, cutting
        worst = np.zeros(len(cutting))
        for t in (0.25, 0.5, 0.75):
            on_machine = _machine_at(x_word[a], c[a], xyz[a, 2], x_word[b], c[b], xyz[b, 2], np.full(len(a), t))
            chord = xyz[a] + (xyz[b] - xyz[a]) * t
            worst = np.maximum(worst, np.linalg.norm(on_machine - chord, axis=1))
        split = cutting[worst > tolerance]
        if not len(split):
            return kind, np.column_stack([x_word, np.zeros(len(x_word)), xyz[:, 2]]), feed, c
        mid = (xyz[split - 1] + xyz[split]) / 2
        kind = np.insert(kind, split, kind[split])
        xyz = np.insert(xyz, split, mid, axis=0)
        feed = np.insert(feed, split, feed[split])
    raise RotaryError("a cutting move could not be linearised for the rotary table (path through the axis?)")


# ----------------------------------------------------------------------------------------
# Pocket geometry (local frame: pocket centre at the origin, ball-centre heights)
# ----------------------------------------------------------------------------------------

def _disk(radius: float) -> CrossSection:
    """A disk whose polygon lies inside the true circle (vertices on it)."""
    n = rg.circle_segments(radius)
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return CrossSection([np.column_stack([radius * np.cos(a), radius * np.sin(a)])])


def _signed_distance(loop: np.ndarray, region: CrossSection, pts: np.ndarray, cap: float = math.inf) -> np.ndarray:
    """Distance from points (n, 2) to the polygon, positive inside.

    With ``cap``, points deeper inside than ``cap`` (inside the region offset inward by it) get
    ``cap`` instead of their distance: callers that only compare with smaller values skip the
    exact, points x edges, computation for them."""
    ax, ay = loop[:, 0], loop[:, 1]
    dx, dy = np.roll(ax, -1) - ax, np.roll(ay, -1) - ay
    length2 = np.maximum(dx * dx + dy * dy, 1e-300)
    out = np.full(len(pts), cap, dtype=float)
    near = np.ones(len(pts), bool)
    if math.isfinite(cap):
        near = ~rg.contains_points(rg.offset(region, -cap), pts)
    index = np.flatnonzero(near)
    for s in range(0, len(index), 4096):
        chunk = index[s:s + 4096]
        px, py = pts[chunk, 0:1] - ax, pts[chunk, 1:2] - ay
        t = np.clip((px * dx + py * dy) / length2, 0.0, 1.0)
        out[chunk] = np.sqrt(((px - t * dx) ** 2 + (py - t * dy) ** 2).min(axis=1))
    inside = rg.contains_points(region, pts[index])
    out[index] = np.where(inside, out[index], -out[index])
    return out


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
        self.depth = float(pocket.depth)
        self.theta = math.radians(pocket.wall_angle_deg)
        self.bottom = pocket.bottom
        self.standoff = settings.standoff
        self.far = float(np.linalg.norm(self.loop, axis=1).max())
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

    def region_at(self, z: float, extra: float) -> CrossSection:
        """Plan region of ball centres at height z that stay ``extra`` off walls and bottom."""
        area = rg.offset(self.region, -(self.wall_offset(z) + extra))
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
        return rg.offset(self.region, -(self.r + self.standoff))

    def rim_wall(self) -> float:
        """Tallest vertical rim of a bowl (0 for a flat pocket)."""
        if self.bottom != "sphere":
            return 0.0
        nearest = float(_signed_distance(self.loop, self.region, np.zeros((1, 2)))[0])
        surface = self.sphere_centre_z - math.sqrt(self.sphere_radius ** 2 - nearest ** 2)
        return max(0.0, -surface)

    def penetration(self, centres: np.ndarray) -> np.ndarray:
        """How far (mm) balls at local centres (n, 3) cut past the design surface (<= 0: clear)."""
        r, th = self.r, self.theta
        z = centres[:, 2]
        below_edge = z <= r * math.sin(th)
        need = np.where(below_edge, self.wall_offset(z), np.sqrt(np.maximum(r * r - z * z, 0.0)))
        # Deeper inside than any ball needs: clear of the wall, no exact distance wanted.
        d2 = _signed_distance(self.loop, self.region, centres[:, :2], cap=float(need.max(initial=0.0)) + 1.0)
        wall = (need - d2) * np.where(below_edge, math.cos(th), 1.0)
        wall = np.where(z >= r, -np.inf, wall)
        if self.bottom == "flat":
            bottom = -self.depth - (z - r)
        else:
            s = centres - np.array([0.0, 0.0, self.sphere_centre_z])
            bottom = np.linalg.norm(s, axis=1) - (self.sphere_radius - r)
        return np.maximum(wall, bottom)


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
    keep = np.ones(len(points), bool)
    keep[1:] = np.linalg.norm(np.diff(points, axis=0), axis=1) > 1e-6
    points = points[keep]
    if len(points) < 2:
        return points
    seg = np.diff(points, axis=0)
    count = np.maximum(1, np.ceil(np.linalg.norm(seg, axis=1) / spacing - 1e-9).astype(int))
    starts = np.repeat(points[:-1], count, axis=0)
    steps = np.repeat(seg / count[:, None], count, axis=0)
    k = np.concatenate([np.arange(n) for n in count])
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
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(curve, axis=0), axis=1))])
    targets = np.append(np.arange(0.0, s[-1], spacing), s[-1])
    return np.column_stack([np.interp(targets, s, curve[:, j]) for j in range(curve.shape[1])])


def _locate(loops: list, point: np.ndarray):
    """(loop index, edge index, parameter) of the outline edge a point lies on, or None."""
    best = None
    for li, loop in enumerate(loops):
        d = np.roll(loop, -1, axis=0) - loop
        t = np.clip(((point - loop) * d).sum(1) / np.maximum((d * d).sum(1), 1e-300), 0, 1)
        dist = np.linalg.norm(loop + t[:, None] * d - point, axis=1)
        e = int(np.argmin(dist))
        if best is None or dist[e] < best[0]:
            best = (dist[e], li, e, float(t[e]))
    if best is None or best[0] > 1e-6:
        return None
    return best[1:]


def _walk(loop: np.ndarray, a, ea, ta, b, eb, tb, forward: bool) -> np.ndarray:
    n = len(loop)
    if ea == eb and (tb >= ta if forward else tb <= ta):
        return np.array([a, b])
    pts = [a]
    k = (ea + 1) % n if forward else ea
    stop = eb if forward else (eb + 1) % n
    while True:
        pts.append(loop[k])
        if k == stop:
            break
        k = (k + 1) % n if forward else (k - 1) % n
    pts.append(b)
    return np.array(pts)


def _sweep(points: np.ndarray) -> float:
    angles = np.unwrap(np.arctan2(points[:, 1], points[:, 0]))
    return float(angles[-1] - angles[0])


def _outline_path(loops: list, a: np.ndarray, b: np.ndarray):
    """The way along the region outline from a (where a counter-clockwise curve about the
    origin left the region) to b (where it comes back): the way that turns about the origin
    as the curve did; None when a and b are on different outline loops."""
    where_a, where_b = _locate(loops, a), _locate(loops, b)
    if where_a is None or where_b is None or where_a[0] != where_b[0]:
        return None
    loop = loops[where_a[0]]
    wanted = math.atan2(b[1], b[0]) - math.atan2(a[1], a[0])
    wanted %= 2 * math.pi
    candidates = [_walk(loop, a, where_a[1], where_a[2], b, where_b[1], where_b[2], forward)
                  for forward in (True, False)]

    def score(path):
        return (round(abs(_sweep(path) - wanted), 6), np.linalg.norm(np.diff(path, axis=0), axis=1).sum())
    return min(candidates, key=score)


def follow_inside(curve: np.ndarray, region: CrossSection, closed: bool) -> list:
    """A counter-clockwise curve about the origin (circle or spiral, (k, 2)) kept inside
    ``region``: where it would leave, it follows the region's outline to where it comes back.
    Returns chains (k, 2); pieces that cannot be joined (another outline loop) stay apart."""
    pieces = rg.clip_polyline(curve, region)
    if not pieces:
        return []
    if closed and len(pieces) == 1 and np.allclose(pieces[0][0], pieces[0][-1]):
        return pieces
    loops = rg.loops(region)
    chains = [pieces[0]]
    for piece in pieces[1:]:
        path = _outline_path(loops, chains[-1][-1], piece[0])
        if path is None:
            chains.append(piece)
        else:
            chains[-1] = np.vstack([chains[-1], path[1:-1], piece])
    if closed:
        path = _outline_path(loops, chains[-1][-1], chains[0][0])
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
    bottom_tip = -geo.depth + settings.allowance
    layers = max(1, math.ceil(-bottom_tip / settings.step_down - 1e-9))
    passes = []
    for k in range(1, layers + 1):
        z = bottom_tip * k / layers + geo.r
        for piece in rg.components(geo.region_at(z, extra)):
            centre = _inner_point(piece)
            shifted = piece.translate(tuple(-centre))
            far = float(max(np.linalg.norm(loop, axis=1).max() for loop in rg.loops(shifted)))
            chains = [centre[None, :]]
            radius = settings.roughing_stepover
            while radius < far:
                chains += [c + centre for c in follow_inside(_circle(radius, settings.spacing), shifted, True)]
                radius += settings.roughing_stepover
            chains += _closed_loops(piece)
            passes += [(z, _lift(_densify(c, settings.spacing), z)) for c in chains]
    return passes


def _lift(chain: np.ndarray, z) -> np.ndarray:
    return np.column_stack([chain, np.broadcast_to(z, len(chain))])


def _wall_levels(geo: _Geometry, settings: RotarySettings) -> np.ndarray:
    step = settings.wall_stepover * math.cos(geo.theta)
    if geo.bottom == "flat":
        top, bottom = geo.r * math.sin(geo.theta), geo.floor_z(settings.standoff)
    else:
        # Down to where the ball last touches the rim: on the bowl's locus, beside the wall.
        nearest = float(_signed_distance(geo.loop, geo.region, np.zeros((1, 2)))[0]) - geo.r - settings.standoff
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
        shifted = piece.translate(tuple(-centre))
        far = max(float(np.linalg.norm(loop, axis=1).max()) for loop in rg.loops(shifted))
        turns = far / settings.stepover + 1
        phi = np.linspace(0, 2 * math.pi * turns, max(2000, math.ceil(40 * turns * far / settings.spacing)))
        spiral = _by_arc_length(np.column_stack([b * phi * np.cos(phi), b * phi * np.sin(phi)]), settings.spacing)
        chains += [_lift(_densify(c + centre, settings.spacing), z) for c in follow_inside(spiral, shifted, False)]
    return chains


def _bowl_spiral(geo: _Geometry, settings: RotarySettings) -> list:
    area = geo.bottom_region()
    rho = geo.locus_radius(settings.standoff)
    far = max(float(np.linalg.norm(loop, axis=1).max()) for loop in rg.loops(area))
    psi_end = math.asin(min(1.0, far / rho + settings.stepover / geo.sphere_radius))
    turns = psi_end * geo.sphere_radius / settings.stepover
    phi = np.linspace(0, 2 * math.pi * turns, max(2000, math.ceil(40 * turns * far / settings.spacing)))
    psi = phi / (2 * math.pi) * settings.stepover / geo.sphere_radius
    helix = np.column_stack([rho * np.sin(psi) * np.cos(phi), rho * np.sin(psi) * np.sin(phi),
                             geo.sphere_centre_z - rho * np.cos(psi)])
    helix = _by_arc_length(helix, settings.spacing)
    chains = []
    for c in follow_inside(helix[:, :2], area, False):
        chains.append(_densify(np.column_stack([c, geo.sphere_z(c, settings.standoff)]), settings.spacing))
    return chains


# ----------------------------------------------------------------------------------------
# Planning
# ----------------------------------------------------------------------------------------

def _link_is_safe(geo: _Geometry, a: np.ndarray, b: np.ndarray, margin: float) -> bool:
    """Can the ball feed straight from centre a to centre b (local) without cutting the wall?"""
    t = np.linspace(0, 1, max(3, math.ceil(np.linalg.norm(b - a) / 0.25) + 1))[:, None]
    return bool(np.all(geo.penetration(a + (b - a) * t) <= -margin))


def _pocket_operation(geo: _Geometry, settings: RotarySettings, start_c):
    """Build one pocket's moves in the part frame, then convert them to C-X-Z."""
    rough = _roughing(geo, settings)
    wall = _wall_finishing(geo, settings)
    bottom = _floor_spiral(geo, settings) if geo.bottom == "flat" else _bowl_spiral(geo, settings)
    builder = PathBuilder(settings.clearance_z, settings.cutting_speed, settings.plunge_speed,
                          settings.approach_gap)
    offset = np.array([geo.centre[0], geo.centre[1], -geo.r])
    here = None
    for chain in [c for _, c in rough] + [c for _, c in wall] + bottom:
        if here is not None:
            chain = _start_nearest(chain, here)
        if here is not None and _link_is_safe(geo, here, chain[0], settings.tolerance / 2):
            down = chain[0][2] < here[2] - 1e-9
            builder.line(*(chain[0] + offset), feed=settings.plunge_speed if down else None)
        else:
            builder.plunge(*(chain[0] + offset))
        builder.polyline(chain[1:] + offset)
        here = chain[-1]
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
    return len(chain) > 2 and np.allclose(chain[0], chain[-1])


def _start_nearest(chain: np.ndarray, here: np.ndarray) -> np.ndarray:
    if not _is_closed(chain):
        return chain
    index = int(np.argmin(np.linalg.norm(chain[:-1] - here, axis=1)))
    return rg.rotate_closed(chain, index)


def max_gouge(pocket: Pocket, op: Operation, block: Block = Block(), settings: RotarySettings = RotarySettings(),
              samples: int = 8) -> float:
    """Deepest cut past the pocket's design surface (mm, 0 when clear), from ball positions
    sampled along every cutting move as the machine interpolates it (X, C, Z linear)."""
    geo = _Geometry(pocket, block, settings)
    x0, c0, z0, x1, c1, z1 = _endpoints(op)
    cutting = np.flatnonzero(op.kind != RAPID)
    if not len(cutting):
        return 0.0
    t = np.tile(np.linspace(0, 1, samples + 1), len(cutting))
    i = np.repeat(cutting, samples + 1)
    tips = _machine_at(x0[i], c0[i], z0[i], x1[i], c1[i], z1[i], t)
    centres = tips - np.array([geo.centre[0], geo.centre[1], -geo.r])
    return max(0.0, float(geo.penetration(centres).max()))


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
        entry = {
            "name": pocket.name,
            "bottom": pocket.bottom,
            "wall_angle_deg": float(pocket.wall_angle_deg),
            "depth_mm": geo.depth,
            "centre": [round(float(v), 4) for v in geo.centre],
            "sphere_radius_mm": geo.sphere_radius,
            "outline": [[round(float(x), 4), round(float(y), 4)] for x, y in geo.loop + geo.centre],
            "points": int(np.count_nonzero(op.kind != RAPID)),
            "path_length_mm": round(float(move_lengths(op)[op.kind != RAPID].sum()), 1),
            "max_gouge_mm": round(max_gouge(pocket, op, block, settings), 6),
            "scallop_mm": round(max(scallop_bottom, scallop_wall), 4),
            "scallop_bottom_mm": round(scallop_bottom, 4),
            "scallop_wall_mm": round(scallop_wall, 4),
            "rim_wall_mm": round(geo.rim_wall(), 3),
            "cycle_time_s": round(cycle_time(op, settings.rapid_rate, settings.max_table_rpm), 1),
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
