"""What a simulation returns: the cut stock (a height field, a radius map or a solid), its
findings, and the stock as a mesh for the viewport and the pictures."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from manifold3d import Manifold

from . import radiusmap as rmap
from .meshes import heightfield_mesh, manifold_arrays, solid_of, turned_mesh, turned_surface
from .stock import BoxStock, CylinderStock, HeightField


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
        if self.solid is not None:
            return manifold_arrays(self.solid)
        if self.radiusmap is None:
            return heightfield_mesh(self.heightfield, self.stock, max_cells)
        return turned_mesh(self.radiusmap, self.heightfield if self.axial_cut else None, self.stock, max_cells)

    def surface(self, max_cells: int | None = 250_000):
        """A triangle surface that looks like :meth:`mesh`, for pictures: a turned bar's is
        built without a boolean and is not a closed solid (see :func:`.meshes.turned_surface`)."""
        if self.solid is None and self.radiusmap is not None:
            return turned_surface(self.radiusmap, self.heightfield if self.axial_cut else None, self.stock,
                                   max_cells)
        return self.mesh(max_cells)

    def __getstate__(self):
        """Picklable (a simulation run in another process sends its result back): the solid
        travels as its triangle mesh."""
        state = dict(self.__dict__)
        if self.solid is not None:
            state["solid"] = manifold_arrays(self.solid)
        return state

    def __setstate__(self, state):
        if state.get("solid") is not None:
            vertices, faces = state["solid"]
            state["solid"] = solid_of(vertices, faces)
        self.__dict__.update(state)
