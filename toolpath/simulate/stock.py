"""The simulation's inputs and what it works on: its settings and errors, the stock (a box, a plate
with a curved top, a bar; as a box and as a solid), findings, and the height field."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from manifold3d import Manifold

from ..engines.compiled import KERNELS
from ..ir.errors import InputError
from .facets import segments_for

ENGINES = ("heightfield", "manifold")
CHORD_TOLERANCE = 0.01     # mm: arcs and rotary moves are cut into chords this close to the path
TOUCH_TOLERANCE = 1e-3     # mm: a rapid must go this deep into material to count as touching it
GOUGE_TOLERANCE = 1e-3     # mm: cutting this far below the design is reported
# a finer height field than this is refused (memory): 80 M cells take about 1.5 GB at the peak of an
# engraving's gate (16 bytes a cell), so a 1200 x 600 mm sign is checked at 0.1 mm (bench_scaling.py)
MAX_CELLS = 80_000_000
MAX_DEXELS = 60_000_000    # the radius map round a bar: more dexels than this are refused (memory)


class SimulationError(InputError):
    """A stock, design or setting the simulation cannot use."""


class CellError(SimulationError):
    """The cell does not suit the stock (too fine for the memory, too coarse to mean anything)."""


class CellTooFine(CellError):
    """More cells than the memory allows (:data:`MAX_CELLS`): a coarser cell would do."""


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
class SurfaceStock(BoxStock):
    """A plate whose top is a surface: the box x0..x1, y0..y1, z0..z1 cut down to the upper
    side of the mesh ``surface`` = (vertices (n, 3), faces (m, 3)), which must cover the box
    (a curved name plate; the height-field engine only)."""

    surface: tuple = field(default=(), compare=False, repr=False)


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


# ----- output -----------------------------------------------------------------------------

@dataclass(frozen=True)
class Finding:
    """One safety problem.  ``operation`` indexes the program's operations, ``move`` the
    operation's move arrays (a post maps it to an NC line)."""

    kind: str                 # "gouge", "rapid_in_material", "plunge", "travel", "below_stock", "spindle_stopped"
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
    initial: np.ndarray | None = None      # the material's top before cutting where it is not flat (a surface stock)

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
        start = self.top if self.initial is None else self.initial
        depth = np.clip(self.heights, self.bottom, self.top)       # one temporary grid, worked in place
        np.subtract(start, depth, out=depth)
        np.maximum(depth, 0.0, out=depth)
        return float(np.sum(depth, where=self.inside, dtype=np.float64) * self.cell_x * self.cell_y)


# ----- manifold engine -----------------------------------------------------------------------------

def stock_solid(stock, tolerance: float) -> Manifold:
    if isinstance(stock, BoxStock):
        return Manifold.cube([stock.x1 - stock.x0, stock.y1 - stock.y0, stock.z1 - stock.z0]).translate(
            [stock.x0, stock.y0, stock.z0])
    n = segments_for(stock.radius, tolerance / 2)
    return Manifold.cylinder(stock.height, stock.radius, stock.radius, n).translate([0, 0, stock.bottom])


def stock_box(stock):
    if isinstance(stock, BoxStock):
        return (stock.x0, stock.y0, stock.z0), (stock.x1, stock.y1, stock.z1)
    return (-stock.radius, -stock.radius, stock.bottom), (stock.radius, stock.radius, stock.top)
