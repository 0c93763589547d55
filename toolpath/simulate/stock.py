"""The simulation's inputs and outputs: its settings, the stock, findings and results."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from manifold3d import Manifold, Mesh

from ..ir.errors import InputError
from . import radiusmap as rmap
from . import sweep

ENGINES = ("heightfield", "manifold")
from ..engines.compiled import KERNELS
CHORD_TOLERANCE = 0.01     # mm: arcs and rotary moves are cut into chords this close to the path
TOUCH_TOLERANCE = 1e-3     # mm: a rapid must go this deep into material to count as touching it
GOUGE_TOLERANCE = 1e-3     # mm: cutting this far below the design is reported
MAX_CELLS = 60_000_000     # a finer grid than this is refused (memory)


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
        depth = np.maximum(start - np.clip(self.heights, self.bottom, self.top), 0.0)
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
    # What the simulation repaired in its input and says so (an inside-out design flipped ...).
    warnings: list = field(default_factory=list)

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
        from .meshes import _heightfield_mesh, _turned_mesh

        if self.solid is not None:
            return _manifold_arrays(self.solid)
        if self.radiusmap is None:
            return _heightfield_mesh(self.heightfield, self.stock, max_cells)
        return _turned_mesh(self.radiusmap, self.heightfield if self.axial_cut else None, self.stock, max_cells)

    def surface(self, max_cells: int | None = 250_000):
        """A triangle surface that looks like :meth:`mesh`, for pictures: a turned bar's is
        built without a boolean and is not a closed solid (see :func:`.meshes._turned_surface`)."""
        if self.solid is None and self.radiusmap is not None:
            from .meshes import _turned_surface

            return _turned_surface(self.radiusmap, self.heightfield if self.axial_cut else None, self.stock,
                                   max_cells)
        return self.mesh(max_cells)

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
