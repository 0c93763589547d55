"""The one call, :func:`simulate` (and :func:`check`): the engines behind it, and the radial
turn-mill work on a radius map."""
from __future__ import annotations

import math
import numbers
import time

import numpy as np
from manifold3d import Error, Manifold

from ..ir.program import FEED, RAPID
from . import radiusmap as rmap
from . import sweep
from .checks import (design_heights, cut_findings, floor_findings, spindle_findings, travel_findings, check_design_mesh)
from .heightfield import Simulation, compiled_kernels, grid_of, stock_grid
from .meshes import solid_of
from .result import SimulationResult
from .paths import chains_of, operations_of, can_plunge
from .stock import (ENGINES, GOUGE_TOLERANCE, MAX_CELLS, MAX_DEXELS, TOUCH_TOLERANCE, CylinderStock, Finding, HeightField, CellError, CellTooFine, SimulationCancelled, SimulationError, stock_box, stock_solid, as_stock)

MIN_CELLS_ACROSS = 4       # a cell coarser than a quarter of the stock's smaller side means nothing

def check(program_or_operations, stock, *, cell: float = 0.1, tolerance: float = 0.03, design=None,
          keep_regions=None, travel: dict | None = None, no_plunge_tools=(), progress=None,
          kernel: str = "auto") -> list:
    """Safety findings alone (runs the height field engine); see :func:`simulate`."""
    return simulate(program_or_operations, stock, engine="heightfield", cell=cell, tolerance=tolerance,
                    design=design, keep_regions=keep_regions, travel=travel, no_plunge_tools=no_plunge_tools,
                    progress=progress, kernel=kernel).findings


# ----- the one call -----------------------------------------------------------------------------------

def simulate(program_or_operations, stock, *, engine: str = "heightfield", cell: float = 0.1,
             tolerance: float = 0.03, design=None, keep_regions=None, travel: dict | None = None,
             no_plunge_tools=(), progress=None, chunk: int = sweep.CHUNK_TRIANGLES,
             kernel: str = "auto", fixture_clearance: float = 0.0, design_name: str = "design") -> SimulationResult:
    """Cut the stock with the program and check it.

    ``stock``: a BoxStock, a CylinderStock or (x0, y0, z0, x1, y1, z1).
    ``engine``: "heightfield" (Z-map with ``cell`` mm columns) or "manifold" (exact solids;
    its safety checks still run on a height field of ``cell``).
    ``tolerance``: how far the tool shape may be approximated (manifold facets, the bull
    nose's torus ring); on the side of leaving material, but for the manifold engine's
    area-equal tool corner (beyond the true tool by under 0.75 x tolerance).
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
    same heights.  The result's ``kernel`` says which ran.  ``fixture_clearance``: how far below a
    box stock's bottom a tool may go (a drill breaking through onto a spoil board); deeper is a
    ``below_stock`` finding.  An operation that cuts with its spindle at 0 rpm is a
    ``spindle_stopped`` finding.  A design mesh is checked first (:func:`check_design_mesh`,
    named ``design_name`` in its messages); a repair it made is in the result's ``warnings``.
    ``cell`` must lie between the finest the memory allows (:data:`MAX_CELLS`) and a quarter of
    the stock's smaller side.
    """
    started = time.perf_counter()
    if engine not in ENGINES:
        raise SimulationError(f"engine must be one of {ENGINES}, got {engine!r}")
    for name, value in (("cell", cell), ("tolerance", tolerance)):
        if not (isinstance(value, numbers.Real) and math.isfinite(value) and value > 0):
            raise SimulationError(f"{name} must be a positive number of mm, got {value!r}")
    if not (isinstance(chunk, int) and chunk > 0):
        raise SimulationError(f"chunk must be a positive number of triangles, got {chunk!r}")
    kernels = compiled_kernels(kernel)
    stock = as_stock(stock)
    _check_cell(stock, float(cell))
    warnings = []
    if design is not None and hasattr(design, "vertices") and hasattr(design, "faces"):
        design, warnings = check_design_mesh(design, stock, design_name, _cancelling(_part_of(progress, 0.0, 0.0)))
    ops = operations_of(program_or_operations)
    radial = [getattr(op, "direction", None) == "radial" for op in ops]
    if any(radial) and not isinstance(stock, CylinderStock):
        raise SimulationError("radial turn-mill operations cut a bar: give a cylinder stock about the C axis")
    all_chains = chains_of(ops, no_plunge_tools)
    chains = [chain for chain in all_chains if not radial[chain.op_index]]
    hf = stock_grid(stock, float(cell))
    design_z = design_heights(hf, design, keep_regions)
    findings = travel_findings(ops, travel) if travel else []
    findings += spindle_findings(ops) + floor_findings(ops, stock, float(fixture_clearance))
    solid = None
    if engine == "manifold" and getattr(stock, "surface", None):
        raise SimulationError("a plate with a curved top is simulated on the height field only (engine "
                              "\"heightfield\")")
    if engine == "manifold":
        solid = sweep.cut(stock_solid(stock, tolerance), all_chains, tolerance, chunk,
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
        sim = Simulation(hf, tolerance, progress, kernels)
        sim.run(chains)
        findings += cut_findings(sim, chains, ops, design_z)
    result = _result(stock, tolerance, findings, kernels, solid, design, hf, rm, chains, started)
    result.warnings = warnings
    return result


def check_cell(stock, cell: float) -> None:
    """Refuse a height-field ``cell`` for ``stock`` as :func:`simulate` would, before any program
    is read or cell made: too coarse (:class:`CellError`), or more columns than the memory
    allows (:class:`CellTooFine`), with the same messages."""
    stock = as_stock(stock)
    _check_cell(stock, float(cell))
    grid_of(stock, float(cell))


def _check_cell(stock, cell: float) -> None:
    (x0, y0, _), (x1, y1, _) = stock_box(stock)
    side = min(x1 - x0, y1 - y0)
    coarsest = side / MIN_CELLS_ACROSS
    if cell > coarsest:
        finest = math.sqrt((x1 - x0) * (y1 - y0) / MAX_CELLS)
        raise CellError(f"cell {cell:g} mm is too coarse for a stock {side:g} mm across (fewer than "
                              f"{MIN_CELLS_ACROSS} cells): give a cell from {finest:.3g} to {coarsest:.3g} mm")


def _result(stock, tolerance, findings, kernels, solid, design, hf, rm, chains, started) -> SimulationResult:
    seconds = time.perf_counter() - started
    ran = "numpy" if kernels is None else "numba"
    if solid is not None:
        removed = stock_solid(stock, tolerance).volume() - solid.volume()
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
    part = solid_of(np.asarray(design.vertices)[:, :3], np.asarray(design.faces))
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
    if dexels > MAX_DEXELS:
        raise CellTooFine(f"a {cell} mm cell gives {dexels} dexels round the bar (more than {MAX_DEXELS}); "
                              "use a coarser cell")
    rm = rmap.grid(stock.radius, stock.bottom, stock.top, cell)
    total = sum(len(op) for op, r in zip(ops, radial) if r)
    done = 0
    stamps_of, findings = {}, []
    for index, op in enumerate(ops):
        if not radial[index] or not len(op):
            continue
        if not op.tool.shape.spherical:
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
                                   np.asarray(design.faces, np.int64), kernels)
    return rm, findings


def _radial_gouges(rm: rmap.RadiusMap, stamps_of: dict, ops: list, vertices, faces, kernels=None) -> list:
    """The deepest cut inside the design's outer radius, with the move that made it."""
    outer = rmap.outer_radii(rm, vertices, faces, kernels)
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
