"""Safety checks: the design's heights over the grid (a function, a mesh's upper envelope, a
floor, keep regions), gouges below it, rapids and plunges into material, travel limits."""
from __future__ import annotations

import math

import numpy as np
from manifold3d import CrossSection

from ..engines import region as rg
from ..engines.meshdata import signed_volume
from ..engines.selfcross import self_crossing
from .heightfield import Simulation, lowest_move
from .meshtop import mesh_top
from .paths import machine_samples
from .stock import GOUGE_TOLERANCE, Finding, HeightField, SimulationError, stock_box



# ----- design surface ---------------------------------------------------------------------------

ROWS_PER_BLOCK = 256       # grid rows (X) of the design's heights made and compared at a time


class DesignHeights:
    """Lowest Z the finished part allows per cell (-inf: anything may be cut), made a block of
    grid rows at a time (:meth:`rows`): a design given as one number with keep regions (an
    engraving's floor and its letters) never takes a full grid of memory.  A function or a mesh
    is evaluated over the whole grid once (``grid``), its keep regions put into it."""

    def __init__(self, hf: HeightField, floor: float, keeps: list, grid: np.ndarray | None = None):
        self.hf, self.floor, self.keeps, self.grid = hf, floor, keeps, grid

    def rows(self, i0: int, i1: int) -> np.ndarray:
        """The heights of grid rows i0..i1-1, an (i1 - i0, ny) float array."""
        if self.grid is not None:
            return self.grid[i0:i1]
        allowed = np.full((i1 - i0, self.hf.shape[1]), self.floor)
        _keep_standing(allowed, i0, self.hf, self.keeps)
        return allowed


def _keep_standing(allowed: np.ndarray, i0: int, hf: HeightField, keeps: list) -> None:
    """Raise ``allowed`` (grid rows i0.. of ``hf``) to each keep region's Z inside it.  A cell's
    parity depends only on its own x and its row's crossings, so a block of rows gets the same
    cells as one ``grid_inside`` over the whole region."""
    i1 = i0 + allowed.shape[0]
    for area, z_min, (k0, k1), (j0, j1) in keeps:
        a, b = max(i0, k0), min(i1, k1)
        if a >= b:
            continue
        inside = rg.grid_inside(area, hf.x()[a:b], hf.y()[j0:j1])
        block = allowed[a - i0:b - i0, j0:j1]
        block[inside] = np.maximum(block[inside], z_min)


def design_heights(hf: HeightField, design, keep_regions) -> DesignHeights | None:
    """The design's heights over the grid (:class:`DesignHeights`), or None when nothing limits
    the cutting.  Refuses a design that is neither a function z(x, y), a mesh nor a number, and
    NaN heights."""
    if design is None and not keep_regions:
        return None
    floor, grid = -np.inf, None
    if design is not None:
        if callable(design):
            gx, gy = np.meshgrid(hf.x(), hf.y(), indexing="ij")
            values = np.asarray(design(gx, gy), float)
            grid = np.broadcast_to(values, hf.shape).copy()
        elif hasattr(design, "vertices") and hasattr(design, "faces"):
            grid = mesh_top(hf, np.asarray(design.vertices, float), np.asarray(design.faces, np.int64))
        else:
            try:
                floor = float(design)
            except (TypeError, ValueError):
                raise SimulationError("design must be a function z(x, y), a mesh with vertices and faces, or a number")
        if (grid is not None and np.isnan(grid).any()) or np.isnan(floor):
            raise SimulationError("design surface has NaN heights")
    keeps = []
    for item in keep_regions or ():
        shape, z_min = (item if isinstance(item, tuple) else (item, hf.top))
        area = _keep_area(shape)
        x0, y0, x1, y1 = area.bounds()
        i0, i1 = _index_range(hf.x0, hf.cell_x, hf.shape[0], x0, x1)
        j0, j1 = _index_range(hf.y0, hf.cell_y, hf.shape[1], y0, y1)
        if i0 < i1 and j0 < j1:
            keeps.append((area, float(z_min), (i0, i1), (j0, j1)))
    if grid is not None:
        _keep_standing(grid, 0, hf, keeps)
    return DesignHeights(hf, floor, keeps, grid)


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


# ----- safety checks ------------------------------------------------------------------------------

def travel_findings(ops: list, travel: dict) -> list:
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
        xyz, c, move = machine_samples(op)
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


def cut_findings(sim: Simulation, chains: list, ops: list, design_z) -> list:
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
        # a block of rows at a time: the depth below the design is never a full grid
        worst, where, count = -np.inf, None, 0
        for i0 in range(0, hf.shape[0], ROWS_PER_BLOCK):
            i1 = min(i0 + ROWS_PER_BLOCK, hf.shape[0])
            material_floor = np.minimum(design_z.rows(i0, i1), hf.top)
            depth = np.where(hf.inside[i0:i1], material_floor - np.maximum(hf.heights[i0:i1], hf.bottom), -np.inf)
            gouged = depth > GOUGE_TOLERANCE
            if gouged.any():
                count += int(gouged.sum())
                k = int(np.argmax(depth))
                if depth.flat[k] > worst:      # the first of equal depths, as one argmax over the grid
                    worst, where = float(depth.flat[k]), (i0 + k // depth.shape[1], k % depth.shape[1])
        if count:
            i, j = where
            xy = (float(hf.x()[i]), float(hf.y()[j]))
            chain, segment, _ = lowest_move(chains, hf, int(i), int(j), sim.tolerance)
            move = int(chain.move[segment])
            area = float(count * hf.cell_x * hf.cell_y)
            findings.append(Finding("gouge", f"{ops[chain.op_index].name}: move {move} cuts {worst:.3f} mm below the "
                                    f"design at ({xy[0]:.2f}, {xy[1]:.2f}); {area:.1f} mm^2 gouged in all",
                                    chain.op_index, move, xy, worst))
    return findings


# ----- the stock's floor and the spindle ---------------------------------------------------------

def floor_findings(ops: list, stock, fixture_clearance: float) -> list:
    """A tool tip below the stock's bottom by more than ``fixture_clearance`` (a drill breaking
    through onto a spoil board) cuts the fixture or the machine table: one finding per operation."""
    if not (math.isfinite(fixture_clearance) and fixture_clearance >= 0):
        raise SimulationError(f"fixture clearance must be a finite number >= 0 mm, got {fixture_clearance!r}")
    bottom = getattr(stock, "z0", None)
    if bottom is None:      # a bar on a rotary axis: its chuck side is not below the tool
        return []
    findings = []
    for index, op in enumerate(ops):
        if not len(op):
            continue
        xyz, _, move = machine_samples(op)
        depth = bottom - xyz[:, 2]
        bad = depth > fixture_clearance + GOUGE_TOLERANCE
        if bad.any():
            worst = int(np.argmax(np.where(bad, depth, -np.inf)))
            x, y = float(xyz[worst, 0]), float(xyz[worst, 1])
            findings.append(Finding(
                "below_stock", f"{op.name}: move {int(move[worst])} goes {depth[worst]:.3f} mm below the stock's "
                f"bottom (Z {bottom:g}) at ({x:.2f}, {y:.2f}): into the fixture or the table",
                index, int(move[worst]), (x, y), float(depth[worst]), float(xyz[worst, 2])))
    return findings


def spindle_findings(ops: list) -> list:
    """Feeding with the spindle stopped breaks the tool: every operation with cutting moves needs
    a spindle speed above zero."""
    findings = []
    for index, op in enumerate(ops):
        cutting = np.flatnonzero(op.kind != 0) if len(op) else []
        if len(cutting) and not op.spindle_rpm > 0:
            findings.append(Finding("spindle_stopped", f"{op.name}: move {int(cutting[0])} cuts with the spindle "
                                    f"at {op.spindle_rpm:g} rpm", index, int(cutting[0])))
    return findings


# What stops an export (the export gate): everything a simulation can find.
BLOCKING_KINDS = ("gouge", "rapid_in_material", "plunge", "below_stock", "spindle_stopped", "travel")


def blocking(findings) -> list:
    """The findings that stop a program from being written unless the user overrides them."""
    return [f for f in findings if f.kind in BLOCKING_KINDS]


# ----- the design mesh, before it is trusted ------------------------------------------------------

DESIGN_SLACK = 0.05        # mm: how far a design may stand outside the stock (rounding of exported meshes)


def check_design_mesh(design, stock, name: str = "design", progress=None) -> tuple:
    """(design, warnings): a mesh design checked before any gouge is measured against it.

    Refused, naming ``name``: no faces (an empty or unreadable file loads as none), NaN or
    infinite vertices, bad face indices, an open or non-manifold surface (an edge not shared by
    exactly two faces, or faces wound against each other), faces passing through each other
    (:func:`selfcross.self_crossing`, naming the first pair and where), no volume, no overlap with the stock,
    or a part that stands outside the stock (it cannot be cut from it: every cut would gouge it).
    Repaired and said in ``warnings``: an inside-out mesh (negative volume) gets its faces flipped.
    Returns a plain ``SimpleNamespace(vertices, faces)`` when it repaired, else ``design`` itself.
    ``progress``: optional callable(fraction), a cancel point during the self-crossing search."""
    from types import SimpleNamespace

    try:
        vertices = np.asarray(design.vertices, dtype=float)
        faces = np.asarray(design.faces)
    except (TypeError, ValueError):
        raise SimulationError(f"design {name}: vertices and faces must be numeric arrays") from None
    if faces.size == 0 or vertices.size == 0:
        raise SimulationError(f"design {name}: the mesh has no faces (an empty or unreadable mesh file)")
    if vertices.ndim != 2 or vertices.shape[1] < 3 or faces.ndim != 2 or faces.shape[1] != 3:
        raise SimulationError(f"design {name}: needs (n, 3) vertices and (m, 3) triangles, got {vertices.shape} "
                              f"and {faces.shape}")
    vertices = vertices[:, :3]
    if not np.issubdtype(faces.dtype, np.integer) or faces.min() < 0 or faces.max() >= len(vertices):
        raise SimulationError(f"design {name}: face indices must be integers in 0..{len(vertices) - 1}")
    if not np.isfinite(vertices).all():
        raise SimulationError(f"design {name}: the mesh has NaN or infinite vertex coordinates")
    faces = faces.astype(np.int64)
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    n = len(vertices)
    undirected, counts = np.unique(directed.min(axis=1) * n + directed.max(axis=1), return_counts=True)
    open_edges = int(np.sum(counts == 1))
    if open_edges or np.any(counts > 2):
        what = (f"{open_edges} edge(s) border only one face (a hole)" if open_edges
                else f"{int(np.sum(counts > 2))} edge(s) are shared by more than two faces")
        raise SimulationError(f"design {name}: the mesh is not a closed solid: {what}; close it (e.g. Blender's "
                              "Fill Holes, or 3D-Print Toolbox > Make Manifold)")
    if len(np.unique(directed[:, 0] * n + directed[:, 1])) < len(directed):
        raise SimulationError(f"design {name}: the faces are wound inconsistently (some normals are flipped): "
                              "recalculate normals")
    crossing = self_crossing(vertices, faces, progress)
    if crossing is not None:
        (i, j), (x, y, z) = crossing.faces, crossing.point
        raise SimulationError(f"design {name}: the mesh passes through itself ({crossing.pairs} pair(s) of faces "
                              f"cross, the first faces {i} and {j} at ({x:.3f}, {y:.3f}, {z:.3f}) mm), so its inside "
                              "is ambiguous: join the pieces with a boolean union (Blender: Boolean modifier, or "
                              "3D-Print Toolbox > Intersections to find them)")
    volume = signed_volume(vertices, faces)     # the sign is the rule carve planning flips by too
    size = float(np.ptp(vertices, axis=0).max())
    if not abs(volume) > 1e-9 * max(size, 1.0) ** 3:
        raise SimulationError(f"design {name}: the mesh encloses no volume")
    warnings = []
    if volume < 0:
        warnings.append(f"design {name}: the mesh was inside out (its normals pointed inward); its faces were "
                        "flipped")
        design = SimpleNamespace(vertices=vertices, faces=faces[:, ::-1].copy())
    (sx0, sy0, sz0), (sx1, sy1, sz1) = stock_box(stock)
    low, high = vertices.min(axis=0), vertices.max(axis=0)
    if np.any(high <= (sx0, sy0, sz0)) or np.any(low >= (sx1, sy1, sz1)):
        raise SimulationError(f"design {name}: the part ({low[0]:.3f}, {low[1]:.3f}, {low[2]:.3f})..({high[0]:.3f}, "
                              f"{high[1]:.3f}, {high[2]:.3f}) does not overlap the stock: are both in the same "
                              "coordinates?")
    beyond = np.concatenate([(sx0, sy0, sz0) - low, high - (sx1, sy1, sz1)])
    if hasattr(stock, "radius"):
        beyond = np.append(beyond, float(np.hypot(vertices[:, 0], vertices[:, 1]).max()) - stock.radius)
    worst = float(beyond.max())
    if worst > DESIGN_SLACK:
        raise SimulationError(f"design {name}: the part stands {worst:.3f} mm outside the stock (more than "
                              f"{DESIGN_SLACK} mm): it cannot be cut from this stock")
    return design, warnings
