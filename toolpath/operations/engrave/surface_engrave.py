"""W1 on a curved plate: the gouge texture, the band and the burr contour following any surface.

The XY planning is :func:`engrave.plan`'s, unchanged; this module adds the surface-following Z
in one place, :func:`follow`.  Every operation is planned as on a flat plate whose top is
Z = 0, so a cutting move's Z is its depth ``d`` below the top.  On the curved plate the
tool goes where the drop cutter (:mod:`dropcutter`) puts it touching the surface over that XY,
then ``d`` further down along its axis:

    z_tip(x, y) = contact(x, y) + d

so the depth is measured along the tool axis from the surface, the paper's rule and numbers
unchanged, and no point of the tool goes deeper than ``|d|`` below the surface anywhere under
it (the surface beside the cut, a raised rim, is not gouged).  On a flat plate contact = 0
and nothing changes.  Where the tool stands over a letter (the planning keeps it clear, so
only within rounding) a second drop, onto the letters' solid (the letters, shrunk by the
simulation's keep margin, capped by the surface), lifts it: the letters' tops are never cut.

Between two points of a straight move the tool runs in a line, so each move is cut into
pieces at most ``STEP`` mm long, and halved again where the tool's contact height between two
points stands more than ``TOLERANCE`` above the chord (the line would cut below the surface
offset).  Rapids at or above the clearance plane stay there; the approach gap is measured
from the surface.

The controller-macro mode: the roughing is followed untextured (``d`` = 0 on its cutting
rows: the tool touching the surface) and split where a new gouge begins; its
``texture_marks`` tell the macro (post/fanuc.py, O7024) where it draws a new depth and how
far along the gouge's ramp each block ends, and the macro adds the depth to the block's Z.
"""
from __future__ import annotations

import math

import numpy as np

from . import engrave as flat
from ...engines import region as rg
from ...engines.dropcutter import DropCutter, DropCutterError
from ...ir.program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, Program, Tool
from ...ir.program import EngraveError

STEP = 1.0            # mm: longest piece of a followed cutting move
TOLERANCE = 5e-4      # mm: the tool between two points may stand this far above the chord
MIN_STEP = 0.02       # mm: pieces are not halved below this
COVER_STEP = 2.0      # mm: the plate is checked to be under the surface at this spacing
LETTER_CELL = 0.25    # mm: the letters' tops are sampled from the surface at this spacing
_POINT = Tool(0, "flat", 0.002, name="point")


class Surface:
    """The plate's top: a triangle mesh (work mm), its upper side is the surface."""

    def __init__(self, vertices, faces, name: str = "surface"):
        self.name = name
        try:
            try:
                array = np.asarray(vertices, float)
            except (TypeError, ValueError):
                raise EngraveError(f"surface {name!r}: vertices must be an (n, 3) array of numbers (mm)") from None
            usable = array.ndim == 2 and array.shape[1] == 3 and len(array) and np.all(np.isfinite(array))
            span = float(np.max(np.ptp(array[:, :2], axis=0))) if usable else 1.0
            DropCutter(vertices, faces, _POINT, bucket=max(span, 1.0))     # checks the arrays
        except DropCutterError as error:
            raise EngraveError(f"surface {name!r}: {error}") from None
        self.vertices = array
        self.faces = _upper_side(array, np.asarray(faces, np.int64))
        self.point = DropCutter(self.vertices, self.faces, _POINT, bucket=max(span / 256, 0.05))
        self._cutters = {}

    def heights(self, xy) -> np.ndarray:
        """The surface's Z over (k, 2) points (-inf where the mesh is not under a point)."""
        return self.point.points(xy)

    def cutter(self, tool: Tool) -> DropCutter:
        key = (tool.kind, tool.diameter, tool.corner_radius)
        if key not in self._cutters:
            self._cutters[key] = DropCutter(self.vertices, self.faces, tool)
        return self._cutters[key]

    def check_covers(self, plate_loops) -> np.ndarray:
        """Raise unless the mesh lies under every point of the plate outline; returns the
        surface heights at the points checked (the boundary and a grid inside)."""
        plate = rg.from_loops(plate_loops, "plate")
        points = [_resample(np.vstack([loop, loop[:1]]), COVER_STEP) for loop in plate_loops]
        x0, y0, x1, y1 = _bounds(plate_loops)
        gx, gy = np.meshgrid(np.arange(x0, x1, COVER_STEP), np.arange(y0, y1, COVER_STEP), indexing="ij")
        grid = np.column_stack([gx.ravel(), gy.ravel()])
        points.append(grid[rg.contains_points(plate, grid)])
        xy = np.vstack(points)
        z = self.heights(xy)
        missing = ~np.isfinite(z)
        if missing.any():
            x, y = xy[int(np.flatnonzero(missing)[0])]
            raise EngraveError(f"surface {self.name!r} does not cover the plate: nothing of it lies over or under "
                               f"X{x:.1f} Y{y:.1f}; it must be a mesh spanning the whole plate outline")
        return z


def _upper_side(vertices, faces) -> np.ndarray:
    """The faces that can be the top: a mesh with faces turned both up and down is a solid (the
    plate with its bottom), so only the faces not turned down are kept.  Then a hole in its top is
    a hole (the drop finds nothing there and the job is refused) rather than a view of its bottom."""
    tri = vertices[faces]
    nz = ((tri[:, 1, 0] - tri[:, 0, 0]) * (tri[:, 2, 1] - tri[:, 0, 1])
          - (tri[:, 1, 1] - tri[:, 0, 1]) * (tri[:, 2, 0] - tri[:, 0, 0]))
    scale = np.maximum(np.ptp(vertices[:, :2], axis=0).max(), 1e-9) ** 2 * 1e-12
    if np.any(nz > scale) and np.any(nz < -scale):
        return faces[nz >= -scale]
    return faces


def _bounds(loops):
    points = np.vstack(loops)
    (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
    return float(x0), float(y0), float(x1), float(y1)


def _resample(polyline: np.ndarray, step: float) -> np.ndarray:
    seg = np.linalg.norm(np.diff(polyline, axis=0), axis=1)
    pieces = np.maximum(np.ceil(seg / step), 1).astype(np.int64)
    return np.vstack([polyline[i] + np.outer(np.arange(n) / n, polyline[i + 1] - polyline[i])
                      for i, n in enumerate(pieces)] + [polyline[-1:]])


# ----------------------------------------------------------------------------------------
# Solids: the letters standing on the surface, and the design the simulation checks against
# ----------------------------------------------------------------------------------------

def _heightmap(surface: Surface, x0, y0, x1, y1, cell, bottom, lift=0.0):
    from ..carve.carve_samples import heightmap_solid

    x = np.linspace(x0, x1, max(2, int(math.ceil((x1 - x0) / cell)) + 1))
    y = np.linspace(y0, y1, max(2, int(math.ceil((y1 - y0) / cell)) + 1))
    gx, gy = np.meshgrid(x, y, indexing="ij")
    top = surface.heights(np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape)
    covered = np.isfinite(top)
    if not covered.any():
        raise EngraveError(f"surface {surface.name!r} does not cover the plate and the letters")
    # outside a plate that does not fill its box the surface may end: nothing is cut there
    top = np.where(covered, top, np.min(top[covered]))
    return heightmap_solid(x, y, np.maximum(top + lift, bottom + 0.01), bottom)


def _manifold(vertices, faces):
    from manifold3d import Manifold, Mesh

    return Manifold(Mesh(vert_properties=np.asarray(vertices, np.float32), tri_verts=np.asarray(faces, np.uint32)))


def _arrays(solid):
    mesh = solid.to_mesh()
    return np.asarray(mesh.vert_properties, float)[:, :3], np.asarray(mesh.tri_verts, np.int64)


def letters_solid(surface: Surface, letter_loops, bottom: float, margin: float = flat.KEEP_MARGIN):
    """The letters (shrunk by ``margin``) standing from ``bottom`` up to the surface: (vertices, faces)."""
    region = rg.offset(rg.from_loops(list(letter_loops), "letters"), -margin)
    x0, y0, x1, y1 = region.bounds()
    top = _heightmap(surface, x0 - 1, y0 - 1, x1 + 1, y1 + 1, LETTER_CELL, bottom)
    prism = region.extrude(float(surface.vertices[:, 2].max() - bottom + 1)).translate((0, 0, bottom))
    return _arrays(_manifold(*top) ^ prism)


def design_solid(surface: Surface, plate_loops, letter_loops, floor: float, bottom: float, cell: float = 0.5):
    """What the finished curved plate must keep: the field at ``floor`` (< 0) below the surface,
    with the letters standing up to the surface; (vertices, faces), a closed solid."""
    x0, y0, x1, y1 = _bounds(plate_loops)
    field = _manifold(*_heightmap(surface, x0, y0, x1, y1, cell, bottom, lift=floor))
    letters = _manifold(*letters_solid(surface, letter_loops, bottom))
    return _arrays(field + letters)


# ----------------------------------------------------------------------------------------
# Following the surface
# ----------------------------------------------------------------------------------------

def _gouge_splits(op: Operation):
    """Where :func:`engrave.apply_texture` draws a new depth on each move of the untextured
    roughing: {move index: [fractions of the move]} (the macro mode supports ramps without
    jitter only, as O7023 does)."""
    texture = op.texture
    angle = math.radians(texture.raster_angle)
    direction = np.array([math.cos(angle), math.sin(angle)])
    splits, textured = {}, np.zeros(len(op), bool)
    starts = op.start_points()
    for i, (kind, start, target) in enumerate(zip(op.kind, starts, op.xyz)):
        if kind != FEED or abs(target[2] - start[2]) > 1e-9:
            continue
        textured[i] = True
        travel = abs(float(np.dot(target[:2] - start[:2], direction)))
        if travel <= texture.spacing:
            continue
        count = int(math.floor((travel + flat.TRAVEL_TOLERANCE) / texture.spacing))
        splits[i] = [min(1.0, k * texture.spacing / travel) for k in range(1, count + 1)]
    return splits, textured


def follow(op: Operation, surface: Surface, guard: DropCutter | None, marks: bool = False, progress=None) -> tuple:
    """``op`` (planned on a flat top at Z = 0) on the surface: (operation, lifted points).

    ``marks``: the operation is the untextured roughing for the controller macro; its rows
    are followed at the surface (depth 0) and carry ``texture_marks``: per move (1 where a
    new gouge depth is drawn at the move's start, else 0; how far along the gouge's ramp the
    move ends, 0..1, 1 after the last full gouge; NaN: cut as programmed).
    ``progress(fraction)`` is called as the work goes on (the shell's Esc cancels there)."""
    tick = progress or (lambda fraction: None)
    if np.any((op.kind == ARC_CW) | (op.kind == ARC_CCW)):
        raise EngraveError(f"{op.name}: arcs cannot follow a surface")
    cutter = surface.cutter(op.tool)
    splits, textured = _gouge_splits(op) if marks else ({}, np.zeros(len(op), bool))
    starts = op.start_points()
    spans = op.xyz[:, :2] - starts[:, :2]
    lengths = np.linalg.norm(spans, axis=1)
    travels = (op.kind != RAPID) & (lengths > 1e-12)
    # 1. samples: a parameter t in [0, 1] along each cutting move, gouge boundaries included
    params = {}
    for i in np.flatnonzero(travels):
        cuts = [0.0] + splits.get(i, [])
        if cuts[-1] < 1.0:
            cuts.append(1.0)
        t = [0.0]
        for a, b in zip(cuts[:-1], cuts[1:]):
            n = max(1, int(math.ceil(lengths[i] * (b - a) / STEP - 1e-9)))
            t += list(a + (b - a) * np.arange(1, n + 1) / n)
        params[i] = np.array(t)
    heights = {i: None for i in params}

    def drop(selection):
        xy = [starts[i][:2] + np.outer(t, spans[i]) for i, t in selection]
        return cutter.points(np.vstack(xy)) if xy else np.empty(0)

    if params:
        values = drop(params.items())
        cursor = 0
        for i, t in params.items():
            heights[i] = values[cursor:cursor + len(t)]
            cursor += len(t)
    # 2. halve where the contact between two samples stands above their chord
    for level in range(14):
        tick(0.2 + 0.05 * level)
        mids = {}
        for i, t in params.items():
            long_enough = np.diff(t) * lengths[i] > 2 * MIN_STEP
            if long_enough.any():
                mids[i] = (np.flatnonzero(long_enough), 0.5 * (t[:-1] + t[1:])[long_enough])
        if not mids:
            break
        values = drop((i, m) for i, (_, m) in mids.items())
        cursor, changed = 0, False
        for i, (where, m) in mids.items():
            zm = values[cursor:cursor + len(m)]
            cursor += len(m)
            h = heights[i]
            high = zm > 0.5 * (h[where] + h[where + 1]) + TOLERANCE
            if high.any():
                changed = True
                order = np.argsort(np.concatenate([params[i], m[high]]), kind="stable")
                params[i] = np.concatenate([params[i], m[high]])[order]
                heights[i] = np.concatenate([h, zm[high]])[order]
        if not changed:
            break
    # 3. the moves: the contact height plus the flat Z, lifted off the letters
    single = [i for i in range(len(op)) if i not in params]
    single_h = cutter.points(op.xyz[single, :2]) if single else np.empty(0)
    single_h = dict(zip(single, single_h))
    tick(0.9)
    kinds, points, feeds, marks_out = [], [], [], []
    for i, kind in enumerate(op.kind):
        if i in params:
            t = params[i][1:]
            xy = starts[i][:2] + np.outer(t, spans[i])
            flat_z = 0.0 * t if textured[i] else starts[i][2] + t * (op.xyz[i][2] - starts[i][2])
            tip = heights[i][1:] + flat_z
            new, fraction = _ramp(t, splits.get(i, []), textured[i])
        else:
            xy, t = op.xyz[i][None, :2], np.ones(1)
            new, fraction = np.zeros(1), np.full(1, np.nan)
            above = kind == RAPID and op.xyz[i][2] >= op.clearance_z - 1e-9
            tip = np.array([op.xyz[i][2] if above else single_h[i] + op.xyz[i][2]])
        kinds += [kind] * len(t)
        points.append(np.column_stack([xy, tip]))
        feeds += [op.feed[i]] * len(t)
        marks_out.append(np.column_stack([new, fraction]))
    xyz = np.vstack(points)
    kinds = np.array(kinds, np.int8)
    if not np.all(np.isfinite(xyz[:, 2])):
        x, y = xyz[int(np.flatnonzero(~np.isfinite(xyz[:, 2]))[0]), :2]
        raise EngraveError(f"surface {surface.name!r} has a hole under the {op.name} near X{x:.1f} Y{y:.1f}: "
                           "it must cover the whole plate")
    lifted = []
    if guard is not None:
        cutting = kinds != RAPID
        floor = np.full(len(xyz), -np.inf)
        floor[cutting] = guard.points(xyz[cutting, :2])
        over = floor > xyz[:, 2] + 1e-9
        if over.any():
            lifted = [tuple(q) for q in xyz[over, :2]]
            xyz[over, 2] = floor[over]
    tick(1.0)
    extra = {"texture_marks": np.vstack(marks_out)} if marks else {}
    followed = op.replace(kind=kinds, xyz=xyz, feed=np.array(feeds, float),
                          center=np.full((len(xyz), 3), np.nan), **extra)
    return followed, lifted


def _ramp(t, cuts, textured):
    """Per sample of a move: (1 if a new gouge begins with it, fraction of the ramp at its end)."""
    if not textured:
        return np.zeros(len(t)), np.full(len(t), np.nan)
    bounds = np.array([0.0] + list(cuts))
    k = np.searchsorted(bounds, t - 1e-12, side="left") - 1        # the gouge a sample ends in
    in_gouge = k < len(cuts)
    kk = np.minimum(k, len(cuts) - 1) if cuts else k
    fraction = np.ones(len(t))
    if cuts:
        lo, hi = bounds[kk], bounds[kk + 1]
        fraction = np.where(in_gouge, (t - lo) / (hi - lo), 1.0)
    new = np.zeros(len(t))
    first = np.concatenate([[True], k[1:] != k[:-1]]) & in_gouge
    new[first] = 1.0
    return new, np.clip(fraction, 0.0, 1.0)


# ----------------------------------------------------------------------------------------
# The job
# ----------------------------------------------------------------------------------------

class SurfaceJob:
    """A planned curved-plate engraving: ``result`` (the flat plan, as engrave.plan returns
    it), ``baked`` (the textured program on the surface), ``depths`` (the gouge depths below
    the surface, in order), ``macro`` (the untextured roughing on the surface with its texture
    and marks, for the controller-macro post), ``floor`` (the deepest planned depth)."""

    def __init__(self, result, baked, depths, macro, surface, lifted):
        self.result, self.baked, self.depths, self.macro = result, baked, depths, macro
        self.surface, self.lifted = surface, lifted


def plan(plate_loops, letters, surface: Surface, settings: flat.EngraveSettings = flat.EngraveSettings(),
         name: str = "engrave", progress=None, plate_thickness: float | None = None,
         texts: dict | None = None, characters=None) -> SurfaceJob:
    """Plan the three operations on a flat top (:func:`engrave.plan`), then follow the surface.

    ``surface`` must lie over or under the whole plate outline; its highest point plus the
    approach gap must stay below the clearance plane; with ``plate_thickness`` every cut must
    stay above the plate's bottom, Z = -thickness."""
    report = progress or (lambda fraction, text: None)
    report(0.0, "surface")
    heights = surface.check_covers(plate_loops)
    result = flat.plan(plate_loops, letters, settings, name=name, texts=texts, characters=characters,
                       progress=lambda f, text: report(0.05 + 0.25 * f, text))
    reach = max(op.tool.radius for op in result.program.operations)
    x0, y0, x1, y1 = _bounds(plate_loops)
    gx, gy = np.meshgrid(np.linspace(x0 - reach, x1 + reach, 60), np.linspace(y0 - reach, y1 + reach, 60))
    around = surface.heights(np.column_stack([gx.ravel(), gy.ravel()]))
    top = float(max(np.max(heights), np.max(around[np.isfinite(around)], initial=-np.inf)))
    if top + settings.approach_gap >= settings.clearance_z:
        raise EngraveError(f"surface {surface.name!r} rises to Z {top:.2f}: with the {settings.approach_gap:g} mm "
                           f"approach gap that reaches the clearance plane Z {settings.clearance_z:g}; lower the "
                           "surface (the work zero) or raise the clearance plane")
    letter_loops = [loop for _, loops in letters for loop in loops]
    bottom = float(np.min(heights)) - 50.0
    report(0.3, "letters on the surface")
    guard_mesh = letters_solid(surface, letter_loops, bottom)
    baked_flat, depths = flat.bake(result.program)
    followed, macro_ops, lifted = [], [], []
    count = len(result.program.operations)
    steps = count + sum(op.texture is not None for op in result.program.operations)
    done_steps = 0

    def part(text):
        first = done_steps
        return lambda f: report(0.35 + 0.6 * (first + f) / steps, text)

    for op, baked_op in zip(result.program.operations, baked_flat.operations):
        text = f"following the surface: {op.name}"
        report(0.35 + 0.6 * done_steps / steps, text)
        guard = DropCutter(*guard_mesh, op.tool)
        done, lifts = follow(baked_op, surface, guard, progress=part(text))
        done_steps += 1
        followed.append(done)
        lifted += lifts
        if op.texture is not None:
            marked, _ = follow(op, surface, guard, marks=True, progress=part(text))
            done_steps += 1
            macro_ops.append(marked)
        else:
            macro_ops.append(done)
    if lifted:
        x, y = lifted[0]
        result.warnings.append(f"{len(lifted)} point(s) of the toolpaths were lifted to keep the tools off the letters "
                               f"(first near X{x:.1f} Y{y:.1f})")
    program = result.program
    baked = Program(program.name, followed, program.units, program.work_offset, program.rapid_rate, list(program.notes))
    macro = Program(program.name, macro_ops, program.units, program.work_offset, program.rapid_rate,
                    list(program.notes))
    if plate_thickness is not None:
        texture = next((op.texture for op in program.operations if op.texture is not None), None)
        lowest = min(float(op.xyz[op.kind != RAPID, 2].min()) for op in followed if np.any(op.kind != RAPID))
        rough = [op for op in macro_ops if op.texture is not None]
        if rough and texture is not None:
            lowest = min(lowest, float(rough[0].xyz[rough[0].kind != RAPID, 2].min()) + texture.deepest)
        if lowest <= -plate_thickness:
            raise EngraveError(f"on surface {surface.name!r} the deepest cut reaches Z {lowest:.2f}, through the "
                               f"{plate_thickness:g} mm plate (its bottom is Z {-plate_thickness:g}); make the cuts "
                               "shallower or the plate thicker")
    report(1.0, "done")
    return SurfaceJob(result, baked, depths, macro, surface, lifted)


def floor_depth(program: Program, band_depth: float) -> float:
    texture = next((op.texture for op in program.operations if op.texture is not None), None)
    return min(texture.deepest, band_depth) if texture is not None else band_depth


def simulation_limits(surface: Surface, plate_loops, letter_loops, program: Program, band_depth: float,
                      bottom: float) -> dict:
    """The design the simulation checks a curved engraving against: the field may be cut down to
    the deepest planned depth below the surface (less the keep margin), the letters stand to it."""
    from types import SimpleNamespace

    floor = floor_depth(program, band_depth) - flat.KEEP_MARGIN
    vertices, faces = design_solid(surface, plate_loops, letter_loops, floor, bottom)
    return {"design": SimpleNamespace(vertices=vertices, faces=faces)}


def plate_stock(surface: Surface, outline_loops, thickness: float):
    """The curved plate as the simulation's stock: the outline's box, its top cut to the surface."""
    from ...simulate import SurfaceStock

    x0, y0, x1, y1 = _bounds(outline_loops)
    heights = surface.check_covers(outline_loops)
    return SurfaceStock(x0, y0, -float(thickness), x1, y1, float(np.max(heights)) + 1e-3,
                        surface=(surface.vertices, surface.faces))


# ----------------------------------------------------------------------------------------
# Sample surfaces, built in code (work mm; the highest point at Z = 0)
# ----------------------------------------------------------------------------------------

DOME_RADIUS = 800.0          # a spherical cap: z = sqrt(R^2 - x^2 - y^2) - R
CYLINDER_RADIUS = 150.0      # a cylinder about the X axis: z = sqrt(R^2 - y^2) - R


def dome(x0, y0, x1, y1, bottom, cell: float = 1.0, radius: float = DOME_RADIUS):
    from ..carve.carve_samples import heightmap_solid

    x, y = _axis(x0, x1, cell), _axis(y0, y1, cell)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    return heightmap_solid(x, y, np.sqrt(radius ** 2 - gx ** 2 - gy ** 2) - radius, bottom)


def cylinder(x0, y0, x1, y1, bottom, cell: float = 1.0, radius: float = CYLINDER_RADIUS):
    from ..carve.carve_samples import heightmap_solid

    x, y = _axis(x0, x1, cell), _axis(y0, y1, cell)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    return heightmap_solid(x, y, np.sqrt(radius ** 2 - gy ** 2) - radius, bottom)


def _axis(a, b, cell):
    return np.linspace(a, b, max(2, int(math.ceil((b - a) / cell - 1e-9)) + 1))


SURFACES = {"dome": dome, "cylinder": cylinder}
