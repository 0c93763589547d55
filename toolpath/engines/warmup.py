"""Compile the numba kernels ahead of the first Simulate.

numba compiles a kernel the first time it is called with a given set of argument types, and
with ``cache=True`` keeps the machine code on disk (beside the module, or where the install
folder is read-only, in the user's cache folder: ``NUMBA_CACHE_DIR`` or numba's user-wide
default).  :func:`warm_kernels` calls every kernel once through the same public calls a job
makes, on tiny inputs (every tool shape; straight, arc and plunging moves; a radial turn-mill
move; the drop-cutter; turn-mill's nearest-point query and planning mesh), so the types match
and the first real Simulate (or turn-mill plan) finds them compiled or loads them from the
cache.  The shell runs it in a child process after registering (``operators.start_warmup``).
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from .meshdata import prism, triangulated
from ..ir.program import ARC_CCW, FEED, RAPID, Operation, Tool
from ..ir.program import TurnMillOperation
from ..ir.tools import KINDS


def _box_operation(kind: str, number: int) -> Operation:
    moves = [(RAPID, (1.0, 1.0, 5.0)), (RAPID, (1.0, 1.0, 1.0)), (FEED, (1.0, 1.0, -0.5)),
             (FEED, (6.0, 2.0, -0.8)), (ARC_CCW, (6.0, 6.0, -0.8)), (FEED, (2.0, 6.0, -0.4)),
             (RAPID, (2.0, 6.0, 5.0))]
    centre = np.full((len(moves), 3), np.nan)
    centre[4] = (6.0, 4.0, -0.8)
    return Operation(f"warm {kind}", Tool(number, kind, 2.0), 10000, [k for k, _ in moves],
                     [p for _, p in moves], [np.nan if k == RAPID else 300.0 for k, _ in moves], center=centre,
                     clearance_z=5.0, safe_z=5.0)


def _radial_operation() -> TurnMillOperation:
    xyz = [(12.0, 0.0, -2.0), (9.5, 0.0, -2.0), (9.5, 0.0, -4.0), (12.0, 0.0, -4.0)]
    kinds = [RAPID, FEED, FEED, RAPID]
    return TurnMillOperation("warm radial", Tool(1, "ball", 2.0), 8000, kinds, xyz,
                             [np.nan if k == RAPID else 300.0 for k in kinds],
                             rotary={"c": np.array([0.0, 0.0, 40.0, 40.0])}, direction="radial",
                             clearance_z=5.0, safe_z=5.0, start=np.array([12.0, 0.0, -2.0]))


def _prism(radius: float, z0: float, z1: float, sides: int = 8) -> SimpleNamespace:
    """A closed ``sides``-gon prism round the Z axis (vertices, triangles), faces wound outward
    (:func:`.meshdata.prism` over a clockwise outline)."""
    angle = np.linspace(0.0, -2 * np.pi, sides, endpoint=False)
    vertices, polygons = prism(np.column_stack([radius * np.cos(angle), radius * np.sin(angle)]), z1, z0)
    return SimpleNamespace(vertices=vertices, faces=triangulated(polygons)[0])


def warm_kernels(progress=None) -> list:
    """Run every compiled kernel once; returns what ran ("heightfield ball", ...).  Without
    numba (or with KEZURI_NO_NUMBA=1) the numpy paths run and nothing is compiled."""
    from .dropcutter import DropCutter
    from .meshrays import Triangles
    from ..simulate import BoxStock, CylinderStock, simulate

    ran = []
    operations = [_box_operation(kind, number) for number, kind in enumerate(KINDS, start=1)]
    for op in operations:
        simulate([op], BoxStock(0.0, 0.0, -3.0, 8.0, 8.0, 0.0), cell=0.5)
        ran.append(f"heightfield {op.tool.kind}")
    bar = _prism(8.0, -10.0, 0.0)          # a design inside the cut: the radial gouge check's rays
    simulate([_radial_operation()], CylinderStock(10.0, 10.0, 0.0), cell=0.5, design=bar)
    ran.append("radius map")
    vertices = np.array([(0.0, 0.0, 0.0), (8.0, 0.0, 0.0), (8.0, 8.0, 1.0), (0.0, 8.0, 1.0)])
    faces = np.array([(0, 1, 2), (0, 2, 3)])
    xy = np.array([(2.0, 2.0), (4.0, 5.0)])
    for op in operations:
        DropCutter(vertices, faces, op.tool).points(xy)
        ran.append(f"drop-cutter {op.tool.kind}")
    Triangles(vertices[faces]).nearest(np.array([(2.0, 2.0, 3.0), (6.0, 5.0, 2.5)]), 5.0)   # turn-mill's
    ran.append("nearest point")
    from ..pictures.picture import Picture, View
    Picture(32, 32).triangles(View(vertices, (0, 0, 32, 32)), vertices, faces, (200, 200, 200))  # batch pictures'
    ran.append("picture")
    from .facets import planning_mesh
    from .meshrays import check_mesh
    planning_mesh(*check_mesh(bar.vertices, bar.faces))        # the mesh check's one pass over the faces
    square = np.array([(0.0, 0.0, 0.0), (8.0, 0.0, 0.0), (8.0, 8.0, 0.0), (0.0, 8.0, 0.0), (4.0, 4.0, 0.0)])
    planning_mesh(square, np.array([(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)], dtype=np.int64))   # turn-mill's
    ran.append("planning mesh")
    from ..ir import arcfit_kernel
    if arcfit_kernel.COMPILED:      # called directly: fit_arcs runs a small operation interpreted
        angle = np.linspace(0.0, np.pi / 2, 9)
        arcfit_kernel.fit_runs(4.0 * np.cos(angle), 4.0 * np.sin(angle), np.array([0]), np.array([7]), 0.01, 3, 5000.0)
    ran.append("arc fit")
    return ran
