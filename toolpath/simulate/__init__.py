"""W6: material-removal simulation and safety checks.

One call, :func:`simulate`, with two engines behind it:

``"heightfield"`` (Z-map)
    The stock is a grid of columns; each column keeps the lowest Z any tool reached over
    its centre.  The tool axis is Z (3-axis jobs, and C-X-Z jobs where the tool is parallel
    to the table axis).  Per cell the value is the *exact* lower envelope of the tool swept
    along each straight move (closed forms, no sampling along the move):

    * ball: the capsule (the ball centre's segment thickened by R);
    * flat end: the swept disc, lowest at one end of the contact range;
    * bull nose: the flat disc of radius R - r plus the torus: beside level moves exact, elsewhere
      a ring of spheres (spaced so the surface error stays within ``tolerance``);
    * drill / V-bit: the cone's flank beside each move, its rim (a flat disc at the cone's
      top) beside each move that climbs or falls, and the whole cone at the points.

    Speed comes from taking the tool path as one chain.  The envelope of a convex tool over
    one move, g(t) = z(t) + h(|P - C(t)|), is convex in t, so at a cell P the lowest value
    over the whole chain is either an interior minimum of one move (a band of width ~ the
    move's length beside the move: the cylinder part of the capsule, or the leading edge
    of the flat disc) or sits at a vertex where the incoming move still falls and the
    outgoing one rises (for a raster that is a thin sliver).  Each of these regions is cut
    per grid column into exact y-intervals (roots of a quadratic), so a short raster move
    costs ~2R*L/cell^2 cells instead of the ~pi*R^2/cell^2 of stamping the whole tool.

    Two kernels evaluate the regions (``kernel=``): a compiled one (numba, in
    kernel.py), used where numba can be imported, and pure numpy, the fallback.
    They do the same arithmetic in the same order and write the same heights.

``"manifold"``
    Exact solids: the stock minus the swept tool, built in sweep.py (tubes of the tool's
    section along runs of moves, wedges of the tool at corners, hulls of the tool elsewhere),
    unioned in chunks with ``Manifold.batch_boolean``.  Every piece lies inside the true
    sweep, within ``tolerance`` of it, so the error is always material left.

Rotary C (SPEC W2, C-X-Z): the table turns about Z; a machine position (X, Y, C) is the part
point ``Rot(C) @ (X, Y)`` (X = -R, C = the angle of the part point from the -X axis).
Moves are interpolated in machine coordinates (X, Y, Z and C linear; G2/G3 arcs in machine
XY), cut into chords within :data:`CHORD_TOLERANCE` and converted to part coordinates.

Safety checks (:func:`check`, also part of every :func:`simulate` result): gouges below a
design surface, rapids touching material (moves processed in order against the stock as it
is at that moment), moves outside the machine travel, and plunges with tools that cannot
plunge.  Every :class:`Finding` names the operation and the move index within it.

Coordinates are millimetres, Z is the tool tip.  Stock: a box, or a cylinder about the Z
axis with its top face at z = 0 (a board on a rotary table).
"""
from __future__ import annotations

import math
import numbers
import os
import time
from dataclasses import dataclass

import numpy as np
from manifold3d import CrossSection, Error, Manifold, Mesh

from . import radiusmap as rmap
from .. import region as rg
from . import sweep
from ..errors import InputError
from ..program import ARC_CCW, ARC_CW, FEED, RAPID, TIP_ANGLE_DEG, Operation, Program, Tool, arc_sweep

ENGINES = ("heightfield", "manifold")
KERNELS = ("auto", "numba", "numpy")    # height field kernels; "auto": numba where it can be imported
CHORD_TOLERANCE = 0.01     # mm: arcs and rotary moves are cut into chords this close to the path
TOUCH_TOLERANCE = 1e-3     # mm: a rapid must go this deep into material to count as touching it
GOUGE_TOLERANCE = 1e-3     # mm: cutting this far below the design is reported
MAX_CELLS = 60_000_000     # a finer grid than this is refused (memory)
# A move shorter than this in XY is taken as vertical: its ends are stamped whole instead.
MIN_XY_LENGTH = 1e-3
PLUNGING_KINDS = ("drill", "ball", "flat")
_ITEM_BATCH = 2048         # triangles per numpy batch when rasterising a design mesh
_PAIR_BATCH = 32768        # (item, grid column) pairs per numpy batch
_CELL_CHUNK = 1 << 17      # cells per evaluation chunk, in reused buffers
_COMMON_RUNS = 1024        # runs of one length this many get a chunk without padding
_EPS = 1e-6                # mm: regions are widened by this so no cell falls between two of them


class SimulationError(InputError):
    """A stock, design or setting the simulation cannot use."""


class SimulationCancelled(Exception):
    """The progress callback asked to stop."""


# ----- input ------------------------------------------------------------------------------

@dataclass(frozen=True)
class BoxStock:
    """A block of material, x0..x1, y0..y1, z0..z1 (mm)."""

    x0: float
    y0: float
    z0: float
    x1: float
    y1: float
    z1: float

    def __post_init__(self):
        values = (self.x0, self.y0, self.z0, self.x1, self.y1, self.z1)
        if not all(isinstance(v, (int, float, np.floating, np.integer)) and math.isfinite(v) for v in values):
            raise SimulationError(f"stock box needs six finite numbers, got {values}")
        if not (self.x1 > self.x0 and self.y1 > self.y0 and self.z1 > self.z0):
            raise SimulationError(f"stock box ({self.x0}, {self.y0}, {self.z0})..({self.x1}, {self.y1}, {self.z1}) "
                             "encloses no volume: every max must be above its min")

    @property
    def top(self) -> float:
        return float(self.z1)

    @property
    def bottom(self) -> float:
        return float(self.z0)

    def volume(self) -> float:
        return (self.x1 - self.x0) * (self.y1 - self.y0) * (self.z1 - self.z0)


@dataclass(frozen=True)
class CylinderStock:
    """A disc of material on the rotary table, or a bar in a turn-mill chuck: axis Z through
    the origin, top (end) face at z = ``z_top`` (0 unless given)."""

    radius: float
    height: float
    z_top: float = 0.0

    def __post_init__(self):
        for name in ("radius", "height"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float, np.floating, np.integer)) and math.isfinite(v) and v > 0):
                raise SimulationError(f"stock cylinder {name} must be a positive number, got {v!r}")
        if not (isinstance(self.z_top, (int, float, np.floating, np.integer)) and math.isfinite(self.z_top)):
            raise SimulationError(f"stock cylinder top must be a finite number, got {self.z_top!r}")

    @property
    def top(self) -> float:
        return float(self.z_top)

    @property
    def bottom(self) -> float:
        return float(self.z_top) - float(self.height)

    def volume(self) -> float:
        return math.pi * self.radius ** 2 * self.height


def as_stock(stock) -> BoxStock | CylinderStock:
    """A stock object from a BoxStock, a CylinderStock, a turn-mill bar (anything with
    ``radius``, ``z_min`` and ``z_max``) or six numbers (x0, y0, z0, x1, y1, z1)."""
    if isinstance(stock, (BoxStock, CylinderStock)):
        return stock
    if all(hasattr(stock, name) for name in ("radius", "z_min", "z_max")):
        return CylinderStock(stock.radius, stock.z_max - stock.z_min, stock.z_max)
    try:
        values = [float(v) for v in stock]
    except (TypeError, ValueError):
        raise SimulationError(f"stock must be a BoxStock, a CylinderStock or (x0, y0, z0, x1, y1, z1), got {stock!r}")
    if len(values) != 6:
        raise SimulationError(f"a stock box needs six numbers (x0, y0, z0, x1, y1, z1), got {len(values)}")
    return BoxStock(*values)


def can_plunge(tool: Tool, no_plunge_tools=()) -> bool:
    """Whether the tool may feed straight down into material (centre-cutting).

    Drills, ball and flat end mills can, unless their tool number is in ``no_plunge_tools``
    (e.g. a flat end mill that is not centre-cutting)."""
    return tool.kind in PLUNGING_KINDS and tool.number not in set(no_plunge_tools)


def _operations(program_or_operations) -> list:
    if isinstance(program_or_operations, Program):
        ops = list(program_or_operations.operations)
    elif isinstance(program_or_operations, Operation):
        ops = [program_or_operations]
    else:
        try:
            ops = list(program_or_operations)
        except TypeError:
            raise SimulationError("simulate needs a Program, an Operation or a list of Operations")
    for op in ops:
        if not isinstance(op, Operation):
            raise SimulationError(f"not an Operation: {op!r}")
        op.validate()
        if not np.all(np.isfinite(op.start)):
            raise SimulationError(f"operation {op.name!r}: start point has a non-finite coordinate")
        unknown = set(op.rotary) - {"c"}
        if unknown:
            raise SimulationError(f"operation {op.name!r}: rotary axes {sorted(unknown)} are not simulated "
                             "(only C, a table turning about Z)")
    if not any(len(op) for op in ops):
        raise SimulationError("nothing to simulate: the program has no moves")
    return ops


# ----- output -----------------------------------------------------------------------------

@dataclass(frozen=True)
class Finding:
    """One safety problem.  ``operation`` indexes the program's operations, ``move`` the
    operation's move arrays (a post maps it to an NC line)."""

    kind: str                 # "gouge", "rapid_in_material", "plunge", "travel"
    message: str
    operation: int
    move: int
    xy: tuple | None = None   # where (part coordinates, mm)
    depth_mm: float | None = None
    z: float | None = None    # the height, where it matters (radial turn-mill findings)


@dataclass
class HeightField:
    """Z-map: ``heights[i, j]`` is the lowest the tool reached over the centre of cell (i, j),
    (x0 + (i + 0.5) * cell_x, y0 + (j + 0.5) * cell_y), or the stock top where it never cut;
    the material top is that clamped to [bottom, top].  ``inside`` marks cells of the stock
    (outside a cylinder stock heights are -inf).  ``operation[i, j]``: the index of the last
    operation that lowered the cell, the one whose surface shows there (-1: never cut)."""

    x0: float
    y0: float
    cell_x: float
    cell_y: float
    heights: np.ndarray
    inside: np.ndarray
    top: float
    bottom: float
    operation: np.ndarray | None = None

    def operation_at(self, xy) -> np.ndarray:
        """The ``operation`` of the cells under (k, 2) points (clamped to the grid)."""
        xy = np.asarray(xy, float).reshape(-1, 2)
        i = np.clip(np.floor((xy[:, 0] - self.x0) / self.cell_x).astype(np.int64), 0, self.shape[0] - 1)
        j = np.clip(np.floor((xy[:, 1] - self.y0) / self.cell_y).astype(np.int64), 0, self.shape[1] - 1)
        return self.operation[i, j]

    @property
    def shape(self):
        return self.heights.shape

    def x(self) -> np.ndarray:
        return self.x0 + (np.arange(self.shape[0]) + 0.5) * self.cell_x

    def y(self) -> np.ndarray:
        return self.y0 + (np.arange(self.shape[1]) + 0.5) * self.cell_y

    def removed_volume(self) -> float:
        depth = self.top - np.clip(self.heights, self.bottom, self.top)
        return float(np.sum(depth, where=self.inside, dtype=np.float64) * self.cell_x * self.cell_y)


@dataclass
class SimulationResult:
    engine: str
    removed_volume_mm3: float
    seconds: float
    cell: float | None          # height field cell (mm); None for the manifold engine
    tolerance: float            # mm: tool-shape approximation (facets, torus ring)
    findings: list
    stock: BoxStock | CylinderStock
    heightfield: HeightField | None = None
    solid: Manifold | None = None
    kernel: str = "numpy"       # the height field kernel that ran: "numba" or "numpy"
    # Radial turn-mill work: the radius map of the radial operations.  The stock is then the
    # material inside both the radius map and the height field of the other operations.
    radiusmap: rmap.RadiusMap | None = None
    axial_cut: bool = True      # whether any operation cut the height field
    # The manifold engine with a closed design mesh: the volume of the design that was cut away.
    gouge_volume_mm3: float | None = None

    def findings_of(self, kind: str) -> list:
        return [f for f in self.findings if f.kind == kind]

    def depth_at(self, points) -> np.ndarray:
        """How deep below the stock's surface (k, 3) points of the simulated stock lie: below
        the top face, or for a turned bar the least depth below its end face, its outside and its
        chuck end."""
        points = np.asarray(points, float).reshape(-1, 3)
        depth = self.stock.top - points[:, 2]
        if self.radiusmap is not None:
            depth = np.minimum(depth, self.stock.radius - np.hypot(points[:, 0], points[:, 1]))
            depth = np.minimum(depth, points[:, 2] - self.stock.bottom)
        return np.maximum(depth, 0.0)

    def operation_at(self, points) -> np.ndarray:
        """The operation whose surface shows at (k, 3) points of the simulated stock (-1: none
        recorded; the manifold engine records none)."""
        points = np.asarray(points, float).reshape(-1, 3)
        operation = np.full(len(points), -1, np.int64)
        hf = self.heightfield
        if hf is not None and hf.operation is not None:
            operation[:] = hf.operation_at(points[:, :2])
        if self.radiusmap is not None:
            rm = self.radiusmap
            radial = self.stock.radius - np.hypot(points[:, 0], points[:, 1]) < self.stock.top - points[:, 2]
            i, k = rm.cells_of(np.arctan2(points[:, 1], points[:, 0]), points[:, 2])
            operation[radial] = rm.operation[i[radial], k[radial]]
        return operation

    def mesh(self, max_cells: int | None = 250_000):
        """The simulated stock as a closed triangle mesh: (vertices (k, 3), faces (f, 3)).

        A height field is min-pooled to at most ``max_cells`` cells first (None: full
        resolution), so the viewport shows the deepest cut of every pooled block."""
        if self.solid is not None:
            return _manifold_arrays(self.solid)
        if self.radiusmap is None:
            return _heightfield_mesh(self.heightfield, self.stock, max_cells)
        return _turned_mesh(self.radiusmap, self.heightfield if self.axial_cut else None, self.stock, max_cells)

    def __getstate__(self):
        """Picklable (a simulation run in another process sends its result back): the solid
        travels as its triangle mesh."""
        state = dict(self.__dict__)
        if self.solid is not None:
            state["solid"] = _manifold_arrays(self.solid)
        return state

    def __setstate__(self, state):
        if state.get("solid") is not None:
            vertices, faces = state["solid"]
            state["solid"] = _solid_of(vertices, faces)
        self.__dict__.update(state)


def _solid_of(vertices, faces) -> Manifold:
    return Manifold(Mesh(vert_properties=np.ascontiguousarray(vertices, np.float32),
                         tri_verts=np.ascontiguousarray(faces, np.uint32)))


# ----- the path as the simulation sees it ---------------------------------------------------

@dataclass
class _Chain:
    """One operation's tool tip path in part coordinates: points[s] -> points[s + 1] is
    segment s, cut by move ``move[s]``; ``checked`` segments are tested against the material
    before they are applied (rapids, plunges of tools that cannot plunge)."""

    op_index: int
    tool: Tool
    points: np.ndarray
    move: np.ndarray
    rapid: np.ndarray
    checked: np.ndarray
    radial: bool = False       # a turn-mill radial tool: its axis points from the C axis to the tip


def _machine_samples(op: Operation):
    """Points along every move in machine coordinates: (xyz (k, 3), c (k,), move (k,)), ending
    at each move's end point.

    Each move is cut into chords within CHORD_TOLERANCE of the true path: G2/G3 arcs in XY,
    and moves that turn C (a straight machine move is an arc on the part)."""
    n = len(op)
    a = op.start_points()
    b = op.xyz
    has_c = "c" in op.rotary
    c_end = op.rotary["c"] if has_c else np.zeros(n)
    c_start = np.concatenate([[c_end[0]], c_end[:-1]]) if n else c_end
    arcs = (op.kind == ARC_CW) | (op.kind == ARC_CCW)
    sweep = np.zeros(n)
    radius_a = np.zeros(n)
    radius_b = np.zeros(n)
    pieces = np.ones(n, dtype=np.int64)
    if arcs.any():
        centre = op.center[arcs, :2]
        sweep[arcs] = arc_sweep(a[arcs, :2], b[arcs, :2], centre, op.kind[arcs] == ARC_CW)
        radius_a[arcs] = np.linalg.norm(a[arcs, :2] - centre, axis=1)
        radius_b[arcs] = np.linalg.norm(b[arcs, :2] - centre, axis=1)
        pieces[arcs] = _chords(np.abs(sweep[arcs]), np.maximum(radius_a[arcs], radius_b[arcs]))
    if has_c:
        reach = np.maximum(np.hypot(a[:, 0], a[:, 1]), np.hypot(b[:, 0], b[:, 1]))
        pieces = np.maximum(pieces, _chords(np.radians(np.abs(c_end - c_start)), reach))
    move = np.repeat(np.arange(n), pieces)
    t = (np.arange(len(move)) - np.repeat(np.cumsum(pieces) - pieces, pieces) + 1) / pieces[move]
    xyz = a[move] + t[:, None] * (b - a)[move]
    on_arc = arcs[move]
    if on_arc.any():
        m = move[on_arc]
        centre = op.center[m, :2]
        start_angle = np.arctan2(a[m, 1] - centre[:, 1], a[m, 0] - centre[:, 0])
        angle = start_angle + t[on_arc] * sweep[m]
        r = radius_a[m] + t[on_arc] * (radius_b[m] - radius_a[m])
        xyz[on_arc, 0] = centre[:, 0] + r * np.cos(angle)
        xyz[on_arc, 1] = centre[:, 1] + r * np.sin(angle)
    c = c_start[move] + t * (c_end - c_start)[move]
    return xyz, c, move


def _chords(angle: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """Chords needed to follow an arc of ``angle`` radians at ``radius`` within CHORD_TOLERANCE."""
    ratio = np.clip(1.0 - CHORD_TOLERANCE / np.maximum(radius, 1e-12), -1.0, 1.0)
    step = 2.0 * np.arccos(ratio)
    return np.maximum(1, np.ceil(angle / np.maximum(step, 1e-9) - 1e-9)).astype(np.int64)


def _to_part(xyz: np.ndarray, c_deg: np.ndarray) -> np.ndarray:
    """Machine (X, Y, Z) at table angle C -> part coordinates: (X, Y) turned by +C."""
    angle = np.radians(c_deg)
    cos, sin = np.cos(angle), np.sin(angle)
    return np.column_stack([xyz[:, 0] * cos - xyz[:, 1] * sin, xyz[:, 0] * sin + xyz[:, 1] * cos, xyz[:, 2]])


def _chains(ops: list, no_plunge_tools) -> list:
    chains = []
    for index, op in enumerate(ops):
        if not len(op):
            continue
        xyz, c, move = _machine_samples(op)
        start_c = op.rotary["c"][0] if "c" in op.rotary else 0.0
        machine = np.vstack([op.start[None, :], xyz])
        c_all = np.concatenate([[start_c], c])
        points = _to_part(machine, c_all)
        # Drop repeated points: every segment then has a length.
        keep = np.ones(len(points), bool)
        keep[1:] = np.any(np.abs(np.diff(points, axis=0)) > 1e-9, axis=1)
        seg_move = move[keep[1:]]
        points = points[keep]
        if len(points) < 2:
            continue
        rapid = op.kind[seg_move] == RAPID
        checked = rapid.copy()
        if not can_plunge(op.tool, no_plunge_tools):
            # A plunge: a feed move along -Z alone (no X, Y or C travel) in machine coordinates.
            a = op.start_points()
            straight_down = ((op.kind == FEED) & (np.abs(op.xyz[:, 0] - a[:, 0]) < 1e-9)
                             & (np.abs(op.xyz[:, 1] - a[:, 1]) < 1e-9) & (op.xyz[:, 2] < a[:, 2]))
            if "c" in op.rotary:
                c_end = op.rotary["c"]
                straight_down &= np.abs(c_end - np.concatenate([[c_end[0]], c_end[:-1]])) < 1e-9
            checked |= straight_down[seg_move]
        chains.append(_Chain(index, op.tool, points, seg_move, rapid, checked,
                             getattr(op, "direction", None) == "radial"))
    return chains


# ----- tool shapes ------------------------------------------------------------------------

def _profile_shape(tool: Tool):
    """(tip_tan, corner, flat): a cone whose half angle has tangent tip_tan if tip_tan > 0,
    else a flat disc of radius ``flat`` rounded by a ``corner`` radius."""
    if tool.kind in TIP_ANGLE_DEG:
        return math.tan(math.radians(TIP_ANGLE_DEG[tool.kind]) / 2), 0.0, 0.0
    corner = 0.0 if tool.kind == "flat" else float(tool.corner_radius)
    return 0.0, corner, float(tool.radius) - corner


def _profile(tool: Tool, d):
    """Height of the tool's underside above its tip at distance d from the axis (d <= R)."""
    tip_tan, corner, flat = _profile_shape(tool)
    if tip_tan > 0:
        return d / tip_tan
    off = np.maximum(d - flat, 0)
    return corner - np.sqrt(np.maximum(corner * corner - off * off, 0))


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

def _halfline(a, b):
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
    h_lo, h_hi = _halfline(a, b)
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


class _Family:
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

    def take(self, sel) -> "_Family":
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


class _Bands(_Family):
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
        kernels.cut_bands(flat, _kernel_grid(hf), _EPS, *_columns(hf, self), self.ox, self.oy, self.ux, self.uy,
                          self.length, self.s, self.z, self.a, self.b, self.r)


class _Profiled(_Family):
    """Items whose value is the tool's profile at a distance from its axis, above the tip z."""

    def __init__(self, segment, ox, oy, tool, **arrays):
        super().__init__(segment, ox, oy, **arrays)
        self.tool = tool
        self.r = tool.radius

    def profile_at(self, k, distance, out):
        """out <- z + profile(min(distance, R)); ``distance`` is clipped in place."""
        np.minimum(distance, np.float32(self.r), out=distance)
        out[...] = _profile(self.tool, distance)
        out += _row(self.z[k])


class _ConeBands(_Family):
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
        kernels.cut_cone_bands(flat, _kernel_grid(hf), _EPS, *_columns(hf, self), self.ox, self.oy, self.ux,
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
        kernels.cut_level_bands(flat, _kernel_grid(hf), _EPS, *_columns(hf, self), self.ox, self.oy, self.ux,
                                self.uy, self.length, self.z, self.r, *_profile_shape(self.tool))


def _band_side_interval(dx, ux, uy, length, mu, w, side):
    """Cells of one side of a cone or level band in a column (side +1: e >= 0, -1: e <= 0):
    0 <= side*e <= w and 0 <= q - mu*side*e <= length, with q = dx*ux + dy*uy and
    e = dy*ux - dx*uy (dy the unknown)."""
    lo, hi = np.full_like(dx, -np.inf), np.full_like(dx, np.inf)
    start = dx * (ux + side * mu * uy)
    slant = uy - side * mu * ux
    for a, b in ((-side * dx * uy, side * ux), (w + side * dx * uy, -side * ux), (start, slant),
                 (length - start, -slant)):
        side_lo, side_hi = _halfline(a, b)
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


class _SphereVertices(_Family):
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
        kernels.cut_sphere_vertices(flat, _kernel_grid(hf), _EPS, *_columns(hf, self), self.ox, self.oy, self.d1x,
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
        kernels.cut_stamps(flat, _kernel_grid(hf), _EPS, *_columns(hf, self), self.ox, self.oy, self.z,
                           self.r, *_profile_shape(self.tool))


# ----- height field: which items a chain needs ------------------------------------------------

def _families(chain: _Chain, top: float, tolerance: float) -> list:
    """The bands, vertex spheres and whole-tool stamps whose union is the chain's envelope."""
    tool = chain.tool
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
    if tool.kind in ("flat", "bull"):
        # The flat disc's lowest value sits at a point only where the path turns upward.
        dz_in = np.concatenate([[0.0], delta[:, 2]])
        dz_out = np.concatenate([delta[:, 2], [1.0]])
        stamped |= (dz_in <= 0) & (dz_out > 0)
    families = []
    bands = ~steep & low
    if tool.kind == "ball":
        families += _sphere_chain(p, delta, length, bands, ~stamped & (p[:, 2] < top), seg_of_vertex,
                                  tool.radius, (0.0, 0.0))
    elif tool.kind in ("flat", "bull"):
        rc = tool.corner_radius if tool.kind == "bull" else 0.0
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
    if tool.kind in TIP_ANGLE_DEG:
        slope = 1 / math.tan(math.radians(TIP_ANGLE_DEG[tool.kind]) / 2)
        # the flank beside each move, and where the move climbs or falls, the rim (a flat disc
        # at the cone's top) beside it: with the cone at the points, the exact envelope
        s = np.flatnonzero(bands & (np.abs(delta[:, 2]) < slope * length))
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


# ----- height field: evaluation -------------------------------------------------------------

def _grid(stock, cell: float) -> HeightField:
    if isinstance(stock, BoxStock):
        x0, y0, x1, y1 = stock.x0, stock.y0, stock.x1, stock.y1
    else:
        x0 = y0 = -stock.radius
        x1 = y1 = stock.radius
    nx = max(1, math.ceil((x1 - x0) / cell - 1e-9))
    ny = max(1, math.ceil((y1 - y0) / cell - 1e-9))
    if nx * ny > MAX_CELLS:
        raise SimulationError(f"a {cell} mm cell gives {nx} x {ny} cells over the stock (more than {MAX_CELLS}); "
                         "use a coarser cell")
    hf = HeightField(x0, y0, (x1 - x0) / nx, (y1 - y0) / ny, np.full((nx, ny), stock.top, np.float32),
                     np.ones((nx, ny), bool), stock.top, stock.bottom)
    if isinstance(stock, CylinderStock):
        hf.inside = np.hypot(hf.x()[:, None], hf.y()[None, :]) <= stock.radius
        hf.heights[~hf.inside] = -np.inf    # no material: nothing to cut or touch
    return hf


def _columns(hf: HeightField, family: _Family):
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


def _compiled_kernels(kernel: str):
    """The compiled kernels module for ``kernel`` ("auto", "numba", "numpy"), or None for numpy.

    numba is optional: "auto" falls back to numpy where it cannot be imported or where the
    environment sets KEZURI_NO_NUMBA=1; "numba" then refuses."""
    if kernel not in KERNELS:
        raise SimulationError(f"kernel must be one of {KERNELS}, got {kernel!r}")
    if kernel == "numpy":
        return None
    if os.environ.get("KEZURI_NO_NUMBA") == "1":
        why = "KEZURI_NO_NUMBA=1 is set"
    else:
        try:
            from . import kernel as heightfield_kernel
            return heightfield_kernel
        except (ImportError, OSError, RuntimeError) as error:
            # OSError: llvmlite's library would not load; RuntimeError: numba finds no
            # writable place for its cache of compiled kernels
            why = f"numba cannot be used ({error})"
    if kernel == "numba":
        raise SimulationError(f"the numba kernel is not available: {why}")
    return None


class _Scratch:
    """Buffers reused for every chunk of cells: fresh temporaries of this size would cost more
    in page faults than the arithmetic done in them."""

    def __init__(self):
        self.size = 0
        self.width = 0

    def views(self, width: int, runs: int):
        need = runs * width
        if need > self.size:
            self.size = max(need, _CELL_CHUNK)
            self.float = [np.empty(self.size, np.float32) for _ in range(2)]
            self.index = np.empty(self.size, np.int64)
            self.pad = np.empty(self.size, bool)
        if width > self.width:
            self.width = width
            self.j = np.arange(width)[:, None]
            self.jf = self.j.astype(np.float32)
        out, tmp = (f[:need].reshape(width, runs) for f in self.float)
        return out, tmp, self.index[:need].reshape(width, runs), self.pad[:need].reshape(width, runs)


def _cells(hf: HeightField, family: _Family, scratch: _Scratch):
    """Yield (family batch, item index per run, cell index, values) for every cell of every
    item, chunk by chunk.

    A chunk is a block of column runs of one length (or padded to a multiple of 8) laid out
    run-minor, so per-run constants broadcast along contiguous rows.  Padding has value +inf
    and an index up to ``ny + 8`` past the run's start (possibly past the grid: index a buffer
    with that margin).  The arrays live in ``scratch`` and are overwritten by the next chunk."""
    ny = hf.shape[1]
    c0, ncol = _columns(hf, family)
    items = np.flatnonzero(ncol)
    if not len(items):
        return
    # Batches of items with about _PAIR_BATCH (item, column) pairs each.
    cum = np.cumsum(ncol[items])
    cuts = np.searchsorted(cum, np.arange(_PAIR_BATCH, cum[-1], _PAIR_BATCH), side="right")
    for sel in np.split(items, cuts):
        if not len(sel):
            continue
        batch = family.take(sel)
        n = ncol[sel]
        k = np.repeat(np.arange(len(sel)), n)
        col = np.arange(len(k)) - np.repeat(np.cumsum(n) - n, n) + c0[sel][k]
        dx = hf.x0 + (col + 0.5) * hf.cell_x - batch.ox[k]
        oy = batch.oy[k]
        parts = []
        for lo, hi in batch.intervals(k, dx):
            r0 = np.clip(np.ceil((oy + lo - hf.y0) / hf.cell_y - 0.5), 0, ny).astype(np.int64)
            r1 = np.clip(np.floor((oy + hi - hf.y0) / hf.cell_y - 0.5), -1, ny - 1).astype(np.int64)
            count = r1 - r0 + 1
            use = count > 0
            parts.append((k[use], col[use], dx[use], r0[use], count[use], oy[use]))
        k, col, dx, r0, count, oy = (np.concatenate(p) for p in zip(*parts))
        if not len(k):
            continue
        start = col * ny + r0
        dy0 = hf.y0 + (r0 + 0.5) * hf.cell_y - oy
        # Runs of one length together; lengths that fewer than _COMMON_RUNS runs share are
        # padded to a multiple of 8 cells instead (a raster's bands mostly share a few lengths).
        lengths, runs_of = np.unique(count, return_counts=True)
        common = np.isin(count, lengths[runs_of >= _COMMON_RUNS])
        width = np.where(common, count, 8 * ((count + 7) // 8))
        for w in np.unique(width).tolist():
            group = np.flatnonzero(width == w)
            step = max(1, _CELL_CHUNK // w)
            for g in range(0, len(group), step):
                runs = group[g:g + step]
                out, tmp, index, pad = scratch.views(w, len(runs))
                batch.values(k[runs], dx[runs], dy0[runs], hf.cell_y, scratch.jf[:w], out, tmp)
                if count[runs].min() < w:
                    np.greater_equal(scratch.j[:w], count[runs][None, :], out=pad)
                    np.copyto(out, np.inf, where=pad)
                np.add(scratch.j[:w], start[runs][None, :], out=index)
                yield batch, k[runs], index.reshape(-1), out.reshape(-1)


def _runs(chain: _Chain, families: list, longest: int = 5000):
    """Split the chain into runs of segments applied together (at most ``longest``, so progress
    is reported); every checked segment that reaches below the stock top is a run of its own,
    tested against the material before it is applied."""
    m = len(chain.move)
    reaching = np.zeros(m, bool)
    for fam in families:
        reaching[fam.segment] = True
    checked = np.flatnonzero(chain.checked & reaching)
    edges = np.unique(np.concatenate([np.arange(0, m, longest), [m], checked, checked + 1]))
    return [(int(a), int(b), bool(b - a == 1 and chain.checked[a] and reaching[a]))
            for a, b in zip(edges[:-1], edges[1:])]


class _Simulation:
    """The height field engine: runs the chains in order and records what it finds.

    ``kernels``: the compiled kernels module, or None for the numpy kernel.  Checked moves
    always take the numpy path (they are few, and must be measured before they cut)."""

    def __init__(self, hf: HeightField, tolerance: float, progress=None, kernels=None):
        self.hf = hf
        self.tolerance = tolerance
        self.progress = progress
        self.kernels = kernels
        self.touches = []       # (chain, segment, depth, xy) of checked moves that met material
        self.scratch = _Scratch()

    def run(self, chains: list):
        nx, ny = self.hf.shape
        flat = np.full(nx * ny + ny + 8, np.inf, np.float32)    # margin for the runs' padding
        flat[:nx * ny] = self.hf.heights.reshape(-1)
        total = sum(len(ch.move) for ch in chains) or 1
        done = 0
        operation = np.full(nx * ny, -1, np.int16)
        for chain in chains:
            before = flat[:nx * ny].copy()
            families = _families(chain, self.hf.top, self.tolerance)
            for a, b, checked in _runs(chain, families):
                parts = [fam.take(slice(*np.searchsorted(fam.segment, [a, b]))) for fam in families]
                if checked:
                    self._checked(flat, chain, a, parts)
                elif self.kernels is not None:
                    for fam in parts:
                        fam.cut(self.kernels, flat, self.hf)
                else:
                    for fam in parts:
                        for _, _, index, values in _cells(self.hf, fam, self.scratch):
                            np.minimum.at(flat, index, values)
                done += b - a
                if self.progress is not None and self.progress(done / total) is False:
                    raise SimulationCancelled("simulation cancelled")
            operation[flat[:nx * ny] < before] = chain.op_index
        self.hf.heights[...] = flat[:nx * ny].reshape(nx, ny)
        self.hf.operation = operation.reshape(nx, ny)

    def _checked(self, flat, chain, segment, families):
        """Apply one checked move, recording it if it reaches into the material as it is
        before the move."""
        cells = [(index.copy(), values.copy()) for fam in families
                 for _, _, index, values in _cells(self.hf, fam, self.scratch)]
        if not cells:
            return
        index = np.concatenate([c[0] for c in cells])
        values = np.concatenate([c[1] for c in cells])
        depth = flat[index] - values
        worst = int(np.argmax(depth))
        if depth[worst] > TOUCH_TOLERANCE:
            i, j = divmod(int(index[worst]), self.hf.shape[1])
            xy = (float(self.hf.x0 + (i + 0.5) * self.hf.cell_x), float(self.hf.y0 + (j + 0.5) * self.hf.cell_y))
            self.touches.append((chain, segment, float(depth[worst]), xy))
        np.minimum.at(flat, index, values)


def _lowest_move(chains: list, hf: HeightField, i: int, j: int, tolerance: float):
    """(chain, segment, value) of the move that went lowest over cell (i, j)."""
    probe = HeightField(hf.x0 + i * hf.cell_x, hf.y0 + j * hf.cell_y, hf.cell_x, hf.cell_y,
                        np.zeros((1, 1), np.float32), np.ones((1, 1), bool), hf.top, hf.bottom)
    scratch = _Scratch()
    best = (None, -1, np.inf)
    for chain in chains:
        for fam in _families(chain, hf.top, tolerance):
            for batch, k, index, values in _cells(probe, fam, scratch):
                w = int(np.argmin(values))
                if values[w] < best[2]:
                    best = (chain, int(batch.segment[k[w % len(k)]]), float(values[w]))
    return best


# ----- design surface ---------------------------------------------------------------------------

def _design_heights(hf: HeightField, design, keep_regions) -> np.ndarray | None:
    """Lowest Z the finished part allows per cell (-inf: anything may be cut), or None."""
    if design is None and not keep_regions:
        return None
    allowed = np.full(hf.shape, -np.inf)
    if design is not None:
        if callable(design):
            gx, gy = np.meshgrid(hf.x(), hf.y(), indexing="ij")
            values = np.asarray(design(gx, gy), float)
            allowed = np.broadcast_to(values, hf.shape).copy()
        elif hasattr(design, "vertices") and hasattr(design, "faces"):
            allowed = _mesh_top(hf, np.asarray(design.vertices, float), np.asarray(design.faces, np.int64))
        else:
            try:
                allowed[:] = float(design)
            except (TypeError, ValueError):
                raise SimulationError("design must be a function z(x, y), a mesh with vertices and faces, or a number")
        if np.isnan(allowed).any():
            raise SimulationError("design surface has NaN heights")
    for item in keep_regions or ():
        shape, z_min = (item if isinstance(item, tuple) else (item, hf.top))
        area = _keep_area(shape)
        x0, y0, x1, y1 = area.bounds()
        i0, i1 = _index_range(hf.x0, hf.cell_x, hf.shape[0], x0, x1)
        j0, j1 = _index_range(hf.y0, hf.cell_y, hf.shape[1], y0, y1)
        if i0 >= i1 or j0 >= j1:
            continue
        gx, gy = np.meshgrid(hf.x()[i0:i1], hf.y()[j0:j1], indexing="ij")
        inside = rg.contains_points(area, np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape)
        block = allowed[i0:i1, j0:j1]
        block[inside] = np.maximum(block[inside], float(z_min))
    return allowed


def _keep_area(shape) -> CrossSection:
    """A keep region: a CrossSection, one closed loop ((k, 2) points), or a list of loops read
    even-odd (letters with their counters: the counters are not kept)."""
    if isinstance(shape, CrossSection):
        return shape
    array = np.asarray(shape, dtype=object if isinstance(shape, list) else float)
    if array.dtype != object and array.ndim == 2:
        return rg.from_loops([array], "keep region")
    return rg.from_loops(list(shape), "keep region")


def _index_range(origin, cell, n, lo, hi):
    return (int(np.clip(math.ceil((lo - origin) / cell - 0.5), 0, n)),
            int(np.clip(math.floor((hi - origin) / cell - 0.5) + 1, 0, n)))


def _mesh_top(hf: HeightField, vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Upper envelope of a triangle mesh over the grid (a z-buffer seen from above); cell
    centres on a triangle's edge belong to neither side (-inf there: nothing to check)."""
    top = np.full(hf.shape, -np.inf)
    flat = top.reshape(-1)
    nx, ny = hf.shape
    tri = vertices[faces]
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    area2 = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    keep = np.abs(area2) > 1e-12
    tri, area2 = tri[keep], area2[keep]
    for start in range(0, len(tri), _ITEM_BATCH):
        t = tri[start:start + _ITEM_BATCH]
        sign = np.sign(area2[start:start + _ITEM_BATCH])
        c0 = np.clip(np.ceil((t[:, :, 0].min(1) - hf.x0) / hf.cell_x - 0.5), 0, nx).astype(np.int64)
        c1 = np.clip(np.floor((t[:, :, 0].max(1) - hf.x0) / hf.cell_x - 0.5), -1, nx - 1).astype(np.int64)
        ncol = np.maximum(c1 - c0 + 1, 0)
        k = np.repeat(np.arange(len(t)), ncol)
        col = np.arange(len(k)) - np.repeat(np.cumsum(ncol) - ncol, ncol) + c0[k]
        x = hf.x0 + (col + 0.5) * hf.cell_x
        lo = np.full(len(k), -np.inf)
        hi = np.full(len(k), np.inf)
        for e in range(3):
            p, q = t[k, e], t[k, (e + 1) % 3]
            # inside: sign * cross(q - p, X - p) >= 0, linear in y
            ex, ey = q[:, 0] - p[:, 0], q[:, 1] - p[:, 1]
            # Shrunk by a hair: a cell centre on a vertical wall's top edge is not held to the
            # top of the wall (it may as well be the floor's), and is left unchecked.
            e_lo, e_hi = _halfline(sign[k] * (ex * (-p[:, 1]) - ey * (x - p[:, 0])) - 1e-7, sign[k] * ex)
            lo, hi = np.maximum(lo, e_lo), np.minimum(hi, e_hi)
        r0 = np.clip(np.ceil((lo - hf.y0) / hf.cell_y - 0.5), 0, ny).astype(np.int64)
        r1 = np.clip(np.floor((hi - hf.y0) / hf.cell_y - 0.5), -1, ny - 1).astype(np.int64)
        cnt = np.maximum(r1 - r0 + 1, 0)
        total = int(cnt.sum())
        if not total:
            continue
        j = np.arange(total) - np.repeat(np.cumsum(cnt) - cnt, cnt)
        row = np.repeat(r0, cnt) + j
        ke = np.repeat(k, cnt)
        xe = np.repeat(x, cnt)
        ye = hf.y0 + (row + 0.5) * hf.cell_y
        p0, p1, p2 = t[ke, 0], t[ke, 1], t[ke, 2]
        # z on the triangle's plane
        u1, u2 = p1 - p0, p2 - p0
        normal = np.cross(u1, u2)
        z = p0[:, 2] - (normal[:, 0] * (xe - p0[:, 0]) + normal[:, 1] * (ye - p0[:, 1])) / normal[:, 2]
        np.maximum.at(flat, np.repeat(col, cnt) * ny + row, z)
    return top


# ----- safety checks ------------------------------------------------------------------------------

def _travel_findings(ops: list, travel: dict) -> list:
    limits = {}
    for axis, bounds in travel.items():
        name = str(axis).lower()
        if name not in ("x", "y", "z", "c"):
            raise SimulationError(f"travel limits: unknown axis {axis!r} (use x, y, z, c)")
        lo, hi = (float(v) for v in bounds)
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            raise SimulationError(f"travel limits for {axis}: need finite (min, max) with min <= max, got {bounds!r}")
        limits[name] = (lo, hi)
    findings = []
    for index, op in enumerate(ops):
        if not len(op):
            continue
        xyz, c, move = _machine_samples(op)
        values = {"x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2], "c": c}
        for axis, (lo, hi) in limits.items():
            if axis == "c" and "c" not in op.rotary:
                continue
            v = values[axis]
            for side, bad in (("below", v < lo - 1e-9), ("above", v > hi + 1e-9)):
                if bad.any():
                    first = int(np.flatnonzero(bad)[0])
                    worst = float(v[bad].min() if side == "below" else v[bad].max())
                    moves = np.unique(move[bad])
                    limit = lo if side == "below" else hi
                    findings.append(Finding(
                        "travel", f"{op.name}: move {move[first]} goes {side} the {axis.upper()} travel limit "
                        f"{limit:g} (reaches {worst:.3f}; {len(moves)} move(s))", index, int(move[first])))
    return findings


def _findings(sim: _Simulation, chains: list, ops: list, design_z) -> list:
    findings = []
    for chain, segment, depth, xy in sim.touches:
        op = ops[chain.op_index]
        move = int(chain.move[segment])
        if chain.rapid[segment]:
            findings.append(Finding("rapid_in_material", f"{op.name}: rapid move {move} runs {depth:.3f} mm into "
                                    f"material at ({xy[0]:.2f}, {xy[1]:.2f})", chain.op_index, move, xy, depth))
        else:
            findings.append(Finding("plunge", f"{op.name}: {op.tool.describe()} cannot plunge, but move {move} "
                                    f"feeds {depth:.3f} mm straight down into material at ({xy[0]:.2f}, {xy[1]:.2f})",
                                    chain.op_index, move, xy, depth))
    hf = sim.hf
    if design_z is not None:
        material_floor = np.minimum(design_z, hf.top)
        depth = np.where(hf.inside, material_floor - np.maximum(hf.heights, hf.bottom), -np.inf)
        gouged = depth > GOUGE_TOLERANCE
        if gouged.any():
            i, j = np.unravel_index(int(np.argmax(depth)), hf.shape)
            worst = float(depth[i, j])
            xy = (float(hf.x()[i]), float(hf.y()[j]))
            chain, segment, _ = _lowest_move(chains, hf, int(i), int(j), sim.tolerance)
            move = int(chain.move[segment])
            area = float(gouged.sum() * hf.cell_x * hf.cell_y)
            findings.append(Finding("gouge", f"{ops[chain.op_index].name}: move {move} cuts {worst:.3f} mm below the "
                                    f"design at ({xy[0]:.2f}, {xy[1]:.2f}); {area:.1f} mm^2 gouged in all",
                                    chain.op_index, move, xy, worst))
    return findings


def check(program_or_operations, stock, *, cell: float = 0.1, tolerance: float = 0.03, design=None,
          keep_regions=None, travel: dict | None = None, no_plunge_tools=(), progress=None,
          kernel: str = "auto") -> list:
    """Safety findings alone (runs the height field engine); see :func:`simulate`."""
    return simulate(program_or_operations, stock, engine="heightfield", cell=cell, tolerance=tolerance,
                    design=design, keep_regions=keep_regions, travel=travel, no_plunge_tools=no_plunge_tools,
                    progress=progress, kernel=kernel).findings


# ----- manifold engine -----------------------------------------------------------------------------

def _stock_solid(stock, tolerance: float) -> Manifold:
    if isinstance(stock, BoxStock):
        return Manifold.cube([stock.x1 - stock.x0, stock.y1 - stock.y0, stock.z1 - stock.z0]).translate(
            [stock.x0, stock.y0, stock.z0])
    n = sweep.segments_for(stock.radius, tolerance / 2)
    return Manifold.cylinder(stock.height, stock.radius, stock.radius, n).translate([0, 0, stock.bottom])


def _stock_box(stock):
    if isinstance(stock, BoxStock):
        return (stock.x0, stock.y0, stock.z0), (stock.x1, stock.y1, stock.z1)
    return (-stock.radius, -stock.radius, stock.bottom), (stock.radius, stock.radius, stock.top)


def _manifold_arrays(solid: Manifold):
    mesh = solid.to_mesh()
    return np.asarray(mesh.vert_properties[:, :3], float), np.asarray(mesh.tri_verts, np.int64)


# ----- height field -> mesh -------------------------------------------------------------------------

def _pooled(heights: np.ndarray, max_cells) -> tuple:
    """(heights min-pooled to at most ``max_cells`` cells, block size): each block keeps its deepest cut."""
    nx, ny = heights.shape
    if max_cells is None or nx * ny <= max_cells:
        return heights, 1
    block = math.ceil(math.sqrt(nx * ny / max_cells))
    padded = np.pad(heights, ((0, -nx % block), (0, -ny % block)), mode="edge")
    return padded.reshape(padded.shape[0] // block, block, padded.shape[1] // block, block).min(axis=(1, 3)), block


def _relief_mesh(heights: np.ndarray, x0, y0, x1, y1, cx, cy, bottom):
    """A closed mesh of columns over the rectangle: vertices at the cell centres (x0 + (i + 0.5)
    cx, ...) plus a ring on the rectangle's edge (heights copied outward), walls, a flat bottom."""
    xs = np.concatenate([[x0], np.minimum(x0 + (np.arange(heights.shape[0]) + 0.5) * cx, x1), [x1]])
    ys = np.concatenate([[y0], np.minimum(y0 + (np.arange(heights.shape[1]) + 0.5) * cy, y1), [y1]])
    z = np.pad(heights, 1, mode="edge")
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    top_vertices = np.column_stack([gx.ravel(), gy.ravel(), z.ravel()])
    w, h = len(xs), len(ys)
    ids = np.arange(w * h).reshape(w, h)
    a, b, c, d = ids[:-1, :-1].ravel(), ids[1:, :-1].ravel(), ids[1:, 1:].ravel(), ids[:-1, 1:].ravel()
    top_faces = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    # The boundary ring, counter-clockwise seen from above, then walls and a bottom fan.
    ring = np.concatenate([ids[:, 0], ids[-1, 1:], ids[-2::-1, -1], ids[0, -2:0:-1]])
    low_vertices = top_vertices[ring].copy()
    low_vertices[:, 2] = bottom
    n_top = len(top_vertices)
    low = n_top + np.arange(len(ring))
    centre = n_top + len(ring)
    nxt = np.roll(np.arange(len(ring)), -1)
    walls = np.concatenate([np.column_stack([ring, low, low[nxt]]), np.column_stack([ring, low[nxt], ring[nxt]])])
    fan = np.column_stack([np.full(len(ring), centre), low[nxt], low])
    vertices = np.vstack([top_vertices, low_vertices, [[(x0 + x1) / 2, (y0 + y1) / 2, bottom]]])
    return vertices, np.vstack([top_faces, walls, fan])


def _heightfield_mesh(hf: HeightField, stock, max_cells):
    heights = np.where(hf.inside, hf.heights, hf.top)
    heights, block = _pooled(np.clip(heights, hf.bottom + 1e-3, hf.top).astype(float), max_cells)
    (x0, y0, _), (x1, y1, _) = _stock_box(stock)
    cx, cy = block * hf.cell_x, block * hf.cell_y
    vertices, faces = _relief_mesh(heights, x0, y0, x1, y1, cx, cy, hf.bottom)
    if isinstance(stock, CylinderStock):
        return _manifold_arrays(_solid_of(vertices, faces) ^ _stock_solid(stock, max(cx, cy) / 4))
    return vertices, faces


def _turned_mesh(rm: rmap.RadiusMap, hf: HeightField | None, stock: CylinderStock, max_cells):
    """The bar of the radius map, less the air the height field's cuts opened above it.

    The air is a box over the cut cells minus their columns (uncut cells stand above the box),
    so only the cut area meets the bar in the boolean, and no faces of the two coincide."""
    bar = rmap.mesh(rm, stock.bottom, stock.top, max_cells)
    cut = None if hf is None else hf.inside & (hf.heights < hf.top - 1e-6)
    if cut is None or not cut.any():
        return bar
    nx, ny = hf.shape
    i, j = np.nonzero(cut)
    i0, i1, j0, j1 = max(i.min() - 2, 0), min(i.max() + 3, nx), max(j.min() - 2, 0), min(j.max() + 3, ny)
    heights = np.clip(hf.heights[i0:i1, j0:j1], hf.bottom + 1e-3, hf.top).astype(float)
    heights[~cut[i0:i1, j0:j1]] = hf.top + 1.0
    heights, block = _pooled(heights, max_cells)
    cx, cy = block * hf.cell_x, block * hf.cell_y
    x0, y0 = hf.x0 + i0 * hf.cell_x, hf.y0 + j0 * hf.cell_y
    x1, y1 = x0 + heights.shape[0] * cx, y0 + heights.shape[1] * cy
    columns = _solid_of(*_relief_mesh(heights, x0 - cx, y0 - cy, x1 + cx, y1 + cy, cx, cy, hf.bottom - 2.0))
    box = Manifold.cube([x1 - x0 - cx, y1 - y0 - cy, hf.top - hf.bottom + 1.5]).translate(
        [x0 + cx / 2, y0 + cy / 2, hf.bottom - 1.0])
    return _manifold_arrays(_solid_of(*bar) - (box - columns))


# ----- the one call -----------------------------------------------------------------------------------

def simulate(program_or_operations, stock, *, engine: str = "heightfield", cell: float = 0.1,
             tolerance: float = 0.03, design=None, keep_regions=None, travel: dict | None = None,
             no_plunge_tools=(), progress=None, chunk: int = sweep.CHUNK_TRIANGLES,
             kernel: str = "auto") -> SimulationResult:
    """Cut the stock with the program and check it.

    ``stock``: a BoxStock, a CylinderStock or (x0, y0, z0, x1, y1, z1).
    ``engine``: "heightfield" (Z-map with ``cell`` mm columns) or "manifold" (exact solids;
    its safety checks still run on a height field of ``cell``).
    ``tolerance``: how far the tool shape may be approximated (manifold facets, the bull
    nose's torus ring); always on the side of leaving material.
    ``design``: the finished part, for gouge checks: a function z(x, y) on arrays, a mesh
    (anything with ``vertices`` and ``faces``, e.g. trimesh.Trimesh: its upper envelope), or
    a number (a floor plane).  ``keep_regions``: 2-D loops where nothing may be cut, or
    (loop, z_min) pairs.  ``travel``: {"x": (min, max), ...} machine limits (x, y, z, c).
    ``no_plunge_tools``: tool numbers that cannot feed straight down (see :func:`can_plunge`).
    ``progress(fraction)`` is called as work completes; returning False cancels
    (:class:`SimulationCancelled`).  ``chunk``: for the manifold engine, how many triangles of
    swept pieces are unioned before they are subtracted from the stock (each is a progress step).
    ``kernel``: how the height field is computed: "numba" (compiled, several times faster),
    "numpy", or "auto" (numba where it can be imported, see :data:`KERNELS`); both give the
    same heights.  The result's ``kernel`` says which ran.
    """
    started = time.perf_counter()
    if engine not in ENGINES:
        raise SimulationError(f"engine must be one of {ENGINES}, got {engine!r}")
    for name, value in (("cell", cell), ("tolerance", tolerance)):
        if not (isinstance(value, numbers.Real) and math.isfinite(value) and value > 0):
            raise SimulationError(f"{name} must be a positive number of mm, got {value!r}")
    if not (isinstance(chunk, int) and chunk > 0):
        raise SimulationError(f"chunk must be a positive number of triangles, got {chunk!r}")
    kernels = _compiled_kernels(kernel)
    stock = as_stock(stock)
    ops = _operations(program_or_operations)
    radial = [getattr(op, "direction", None) == "radial" for op in ops]
    if any(radial) and not isinstance(stock, CylinderStock):
        raise SimulationError("radial turn-mill operations cut a bar: give a cylinder stock about the C axis")
    all_chains = _chains(ops, no_plunge_tools)
    chains = [chain for chain in all_chains if not radial[chain.op_index]]
    hf = _grid(stock, float(cell))
    design_z = _design_heights(hf, design, keep_regions)
    findings = _travel_findings(ops, travel) if travel else []
    solid = None
    if engine == "manifold":
        solid = sweep.cut(_stock_solid(stock, tolerance), all_chains, tolerance, chunk,
                          _cancelling(_part_of(progress, 0.0, 0.8)))
        progress = _part_of(progress, 0.8, 1.0)      # the safety checks still run on the maps
    rm = None
    if any(radial):
        share = sum(len(op) for op, r in zip(ops, radial) if r) / sum(len(op) for op in ops)
        rm, radial_findings = _radius_map_cut(ops, radial, stock, float(cell), tolerance, design, no_plunge_tools,
                                              _part_of(progress, 0.0, share), kernels)
        findings += radial_findings
        progress = _part_of(progress, share, 1.0)
    if chains:
        sim = _Simulation(hf, tolerance, progress, kernels)
        sim.run(chains)
        findings += _findings(sim, chains, ops, design_z)
    seconds = time.perf_counter() - started
    ran = "numpy" if kernels is None else "numba"
    if solid is not None:
        removed = _stock_solid(stock, tolerance).volume() - solid.volume()
        return SimulationResult("manifold", float(removed), seconds, None, tolerance, findings, stock, solid=solid,
                                kernel=ran, radiusmap=rm, axial_cut=bool(chains),
                                gouge_volume_mm3=_gouge_volume(solid, design))
    if rm is None:
        return SimulationResult("heightfield", hf.removed_volume(), seconds, hf.cell_x, tolerance, findings, stock,
                                heightfield=hf, kernel=ran)
    removed = rm.removed_volume()
    if chains:
        removed += hf.removed_volume() - _overlap_volume(hf, rm)
    return SimulationResult("radiusmap+heightfield" if chains else "radiusmap", removed, seconds, hf.cell_x,
                            tolerance, findings, stock, heightfield=hf, kernel=ran, radiusmap=rm,
                            axial_cut=bool(chains))


def _gouge_volume(solid: Manifold, design) -> float | None:
    """Volume of the design (a closed mesh) that the simulated stock no longer holds; None when
    the design is not a closed mesh."""
    if not (hasattr(design, "vertices") and hasattr(design, "faces")):
        return None
    part = _solid_of(np.asarray(design.vertices)[:, :3], np.asarray(design.faces))
    if part.status() != Error.NoError or part.is_empty():
        return None
    return float((part - solid).volume())


def _overlap_volume(hf: HeightField, rm: rmap.RadiusMap) -> float:
    """Material that both the height field and the radius map removed (counted once)."""
    top = np.clip(hf.heights, hf.bottom, hf.top)
    cut = hf.inside & (top < hf.top)
    i, j = np.nonzero(cut)
    overlap = rm.removed_above(hf.x()[i], hf.y()[j], top[i, j].astype(float), np.full(len(i), hf.top))
    return float(overlap.sum() * hf.cell_x * hf.cell_y)


def _radius_map_cut(ops, radial, stock: CylinderStock, cell: float, tolerance: float, design, no_plunge_tools,
                    progress, kernels):
    """The radial turn-mill operations on a radius map: (map, findings)."""
    dexels = math.ceil(2 * math.pi * stock.radius / cell) * math.ceil(stock.height / cell)
    if dexels > MAX_CELLS:
        raise SimulationError(f"a {cell} mm cell gives {dexels} dexels round the bar (more than {MAX_CELLS}); "
                              "use a coarser cell")
    rm = rmap.grid(stock.radius, stock.bottom, stock.top, cell)
    total = sum(len(op) for op, r in zip(ops, radial) if r)
    done = 0
    stamps_of, findings = {}, []
    for index, op in enumerate(ops):
        if not radial[index] or not len(op):
            continue
        if op.tool.kind != "ball":
            raise SimulationError(f"operation {op.name!r}: radial turn-mill work is simulated for ball end mills, "
                                  f"not a {op.tool.describe()}")
        checked = op.kind == RAPID
        if not can_plunge(op.tool, no_plunge_tools):
            # straight in towards the axis: X falls, nothing else moves
            a = op.start_points()
            c_end = op.rotary["c"]
            checked |= ((op.kind == FEED) & (op.xyz[:, 0] < a[:, 0]) & (np.abs(op.xyz[:, 2] - a[:, 2]) < 1e-9)
                        & (np.abs(c_end - np.concatenate([[c_end[0]], c_end[:-1]])) < 1e-9))
        try:
            stamps = rmap.ball_stamps(op, rmap.stamp_spacing(op.tool.radius, tolerance), checked)
        except ValueError as error:
            raise SimulationError(str(error)) from None

        def report(fraction, base=done, size=len(op)):
            if progress is not None and progress((base + fraction * size) / total) is False:
                raise SimulationCancelled("simulation cancelled")
        for touch in rmap.cut(rm, stamps, op.tool.radius, index, TOUCH_TOLERANCE, report, kernels):
            x, y, z = touch.point
            where = f"({x:.2f}, {y:.2f}, z {z:.2f})"
            if op.kind[touch.move] == RAPID:
                message = f"{op.name}: rapid move {touch.move} runs {touch.depth:.3f} mm into material at {where}"
                kind = "rapid_in_material"
            else:
                message = (f"{op.name}: {op.tool.describe()} cannot plunge, but move {touch.move} feeds "
                           f"{touch.depth:.3f} mm straight in into material at {where}")
                kind = "plunge"
            findings.append(Finding(kind, message, index, touch.move, (x, y), touch.depth, z))
        stamps_of[index] = stamps
        done += len(op)
    if design is not None and hasattr(design, "vertices") and hasattr(design, "faces"):
        findings += _radial_gouges(rm, stamps_of, ops, np.asarray(design.vertices, float),
                                   np.asarray(design.faces, np.int64))
    return rm, findings


def _radial_gouges(rm: rmap.RadiusMap, stamps_of: dict, ops: list, vertices, faces) -> list:
    """The deepest cut inside the design's outer radius, with the move that made it."""
    outer = rmap.outer_radii(rm, vertices, faces)
    depth = outer - rm.radii
    gouged = (outer > 0) & (depth > GOUGE_TOLERANCE)
    if not gouged.any():
        return []
    i, k = np.unravel_index(int(np.argmax(np.where(gouged, depth, -np.inf))), rm.shape)
    worst = float(depth[i, k])
    best = (np.inf, None, -1)
    for index, stamps in stamps_of.items():
        s, entry = rmap.lowest_stamp(rm, stamps, ops[index].tool.radius, int(i), int(k))
        if entry < best[0]:
            best = (entry, index, int(stamps.move[s]))
    _, index, move = best
    theta, z = (i + 0.5) * rm.cell_theta, rm.z0 + (k + 0.5) * rm.cell_z
    x, y = rm.radii[i, k] * math.cos(theta), rm.radii[i, k] * math.sin(theta)
    area = float(np.sum(outer[gouged]) * rm.cell_theta * rm.cell_z)
    return [Finding("gouge", f"{ops[index].name}: move {max(move, 0)} cuts {worst:.3f} mm inside the design at "
                    f"({x:.2f}, {y:.2f}, z {z:.2f}); {area:.1f} mm^2 gouged in all", index, max(move, 0), (x, y),
                    worst, z)]


def _cancelling(progress):
    """The callback, raising SimulationCancelled when it returns False."""
    if progress is None:
        return None

    def report(fraction):
        if progress(fraction) is False:
            raise SimulationCancelled("simulation cancelled")
    return report


def _part_of(progress, start: float, end: float):
    """A progress callback reporting into [start, end] of the caller's."""
    if progress is None:
        return None
    return lambda fraction: progress(start + (end - start) * fraction)
