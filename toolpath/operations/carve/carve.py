"""Carving a 3-D surface (a relief, a domed plate, any mesh) with 3-axis tools.

The design is a triangle mesh in millimetres; the stock is the box of its XY extent from its
lowest point up to ``stock_top`` (default: its highest point).  Every tool position comes from
the drop cutter (:mod:`.dropcutter`), so no move of either operation goes below the design:

* **Roughing** (flat end mill by default) in Z levels ``step_down`` apart, on height-field
  offsets: along parallel raster lines the tool's drop-cutter height with the stock allowance
  (the tool grown by the allowance, exact) is computed once; level L cuts at max(L, that
  height), only where the level above left material (where the grown tool's height is below
  the level above), retracting between runs.  The last level follows the grown tool's height
  everywhere, so roughing leaves the allowance all over (plus the steps on slopes).
* **Finishing** (ball end mill) by one zigzag raster at ``raster_angle`` over the whole stock,
  the tool dropped along it and the path refined until it stands within ``tolerance`` of the
  dropped tool everywhere.  The stepover comes from the scallop height h asked for: on a
  level surface a ball of radius r leaves h between passes s = 2 sqrt(2 r h - h^2) apart;
  across a slope of angle a the passes are s / cos(a) apart on the surface, so the raster
  spacing is s * cos(a_max), a_max the steepest slope across the raster direction among the
  faces the raster finishes: those no steeper than ``max_slope_deg`` across it (steeper ones
  are the cleanup's or the wall pass's, or reported when those are off).
  On a convex bend of radius rho the passes' contacts stand further apart than on a plane
  (h ~ s^2 (1/r + 1/rho) / 8), so the spacing is also multiplied by sqrt(rho / (rho + r)), rho
  the sharpest convex bend between upward faces (the angle between their normals over the
  distance between their centroids) but no less than r, and by 0.95 (:data:`MARGIN`: that
  estimate from facets is good to a few percent).  The floor: the spacing is never below
  0.95 s cos(max_slope_deg) sqrt(1/2).  Why rho >= r: for passes whose ball centres stand c
  apart over a bend of radius rho, the cusp is sqrt((rho + r)^2 - c^2/4) - sqrt(r^2 - c^2/4) - rho,
  below a plane's r - sqrt(r^2 - c^2/4) for every rho (it falls to 0 as rho -> 0: the ball rolls
  over a crease), so a tighter bend, which facets make of a wall's top edge or a crease, needs
  no smaller spacing; the factor is kept for wider bends, where it was before.  The raster runs out to 0.7 r beyond the stock, so the
  ball's last contacts reach the stock's edge.
* **Steep-region cleanup** (``steep_cleanup``, the same ball, no tool change): where upward faces
  slope across the raster more than the stepover allows for (``max_slope_deg``), the raster's
  scallop is higher than asked.  Those faces are marked on a grid (their XY footprint, grown by
  the ball's radius: a ball touching a face of slope a stands r sin a beside it), and a second
  raster at ``raster_angle + 90`` runs only over the marks, its stepover chosen like the first
  from the steepest slope across it among the faces there.  Each run is dropped on the design;
  the next run starting within 4 ball diameters (:data:`LINK`) is reached along the surface
  (the ball dropped along the straight link, over ground already finished), a farther one by a
  retract, a rapid over at the clearance height and a feed down.

* **Wall pass** (``wall_pass``, the same ball): the walls no raster finishes (:func:`wall_faces`:
  vertical, or steeper than ``max_slope_deg`` across both rasters; not the stock's own sides)
  get waterlines (:mod:`.waterline`: iso-lines of the ball's drop-cutter height field, so each
  lies on the ball's envelope) from where the ball's equator meets the walls' top down to their
  foot, dz = 0.95 * 2 sqrt(2 r h - h^2) * sin(a_min) apart (a_min the least steep wall face:
  the contacts stand dz / sin(a) apart along a wall of slope a, and two contacts c apart on a
  plane leave r - sqrt(r^2 - c^2/4)), climb (the wall on the right of travel, spindle M03),
  each wall top-down, the next level reached by a straight feed where it stays on the envelope.

Output: a :class:`~.program.Program` with one operation per tool, written by every milling post.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...engines.dropcutter import STEEP, DropCutter, DropCutterError, Mesh
from ...ir.errors import MAX_REACH_MM, InputError
from ...ir.program import Operation, PathBuilder, Program, Tool
from ...engines import waterline

MIN_SIZE_MM = 0.5           # a relief narrower than this in X or Y is no carving (a unit mistake)
MARGIN = 0.95       # the bend radius is estimated from facets: 5 % spare on the finishing stepover
LINK = 4.0          # cleanup pieces closer than this many ball diameters are linked along the surface
MAX_WALL_LEVELS = 2000   # waterline levels of the wall pass at most (20 mm of wall at 0.01 mm)


class CarveError(InputError):
    """Carving settings or a design mesh that cannot be used; the message names the value."""


@dataclass(frozen=True)
class CarveSettings:
    rough_tool: Tool = Tool(1, "flat", 6.0, name="roughing")
    finish_tool: Tool = Tool(2, "ball", 3.0, name="finishing")
    rough: bool = True                # rough in Z levels before finishing
    allowance: float = 0.5            # mm roughing leaves on the design
    step_down: float = 3.0            # mm between roughing levels
    rough_stepover: float = 2.4       # mm between roughing raster lines
    scallop: float = 0.02             # mm scallop height the finishing may leave
    raster_angle: float = 0.0         # degrees from +X, finishing (roughing runs across it)
    max_slope_deg: float = 60.0       # slopes steeper than this do not shrink the stepover further
    steep_cleanup: bool = True        # a cross raster over the faces steeper than max_slope_deg
    wall_pass: bool = True            # waterlines along the walls no raster finishes (see wall_faces)
    sample_spacing: float = 0.25      # mm between dropped points along a raster line
    tolerance: float = 0.0003         # mm the path may stand above the dropped tool between points
    rough_rpm: float = 16000.0
    finish_rpm: float = 18000.0
    rough_feed: float = 1500.0
    finish_feed: float = 2000.0
    plunge_feed: float = 400.0
    clearance: float = 5.0            # mm above the stock top for moves between cuts
    safe_z: float = 50.0              # mm above the stock top at the start and end

    def check(self):
        for name in ("allowance", "step_down", "rough_stepover", "scallop", "sample_spacing", "tolerance",
                     "rough_feed", "finish_feed", "plunge_feed", "clearance", "safe_z"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
                raise CarveError(f"{name.replace('_', ' ')} must be a number >= 0, got {value!r}")
            if value == 0 and name != "allowance":
                raise CarveError(f"{name.replace('_', ' ')} must be greater than 0")
        if self.finish_tool.kind != "ball":
            raise CarveError(f"finishing needs a ball end mill (the scallop rule is a ball's), got a "
                             f"{self.finish_tool.describe()}")
        if self.rough and self.rough_tool.shape.pointed:
            raise CarveError(f"roughing needs a flat, ball or bull nose end mill, got a {self.rough_tool.describe()}")
        if self.scallop >= self.finish_tool.radius:
            raise CarveError(f"scallop {self.scallop:g} mm must be smaller than the ball's radius "
                             f"{self.finish_tool.radius:g} mm")
        if self.rough_stepover > self.rough_tool.diameter:
            raise CarveError(f"roughing stepover {self.rough_stepover:g} mm is wider than the "
                             f"{self.rough_tool.diameter:g} mm tool")
        if not 0 <= self.max_slope_deg < 90:
            raise CarveError(f"max slope must be 0..90 degrees, got {self.max_slope_deg:g}")
        if self.safe_z < self.clearance:
            raise CarveError(f"safe Z {self.safe_z:g} mm must be at least the clearance {self.clearance:g} mm")


@dataclass
class CarveResult:
    program: Program
    stock: tuple                      # (x0, y0, z0, x1, y1, z1) in mm
    stepover: float                   # finishing raster spacing in mm
    flat_stepover: float              # what a level surface would allow
    steepest_slope_deg: float         # across the raster, over the upward faces
    convex_radius: float              # the sharpest convex bend of the design (mm; inf: none)
    levels: list                      # roughing Z levels
    warnings: list = field(default_factory=list)
    cleanup_stepover: float | None = None   # the steep-region cleanup's raster spacing (None: no cleanup)
    cleanup_slope_deg: float = 0.0          # steepest slope across the cleanup raster among its faces
    steep_area_mm2: float = 0.0             # XY area of the faces steeper than the raster allows for
    raster_slope_deg: float = 0.0           # steepest slope across the raster among the faces it finishes
    walls: "WallPass | None" = None         # the wall pass (None: no walls, or the pass is off)
    wall_area_mm2: float = 0.0              # area of the wall faces (not their XY footprint)


@dataclass
class WallPass:
    operation: Operation | None
    z_step: float                     # mm between waterline levels
    levels: list                      # tip Z of each level
    shallowest_deg: float             # the least steep wall face
    scallop: float                    # closed form: the cusp between two levels on the least steep wall
    links: int                        # feeds from one level to the next along the wall


def ball_stepover(radius: float, scallop: float) -> float:
    """Stepover of a ball of ``radius`` leaving ``scallop`` on a level surface."""
    return 2.0 * math.sqrt(2.0 * radius * scallop - scallop * scallop)


def check_mesh(vertices, faces) -> tuple:
    vertices = np.asarray(vertices, float)
    faces = np.asarray(faces)
    if vertices.ndim != 2 or vertices.shape[-1] != 3:
        raise CarveError(f"the design mesh needs (n, 3) vertices, got shape {vertices.shape}")
    if len(vertices) < 3:
        raise CarveError(f"the design mesh has {len(vertices)} vertices, fewer than one triangle needs (an empty or "
                         f"unreadable mesh file?)")
    if faces.ndim != 2 or faces.shape[-1] != 3 or not len(faces):
        raise CarveError("the design mesh has no triangles")
    if not np.all(np.isfinite(vertices)):
        raise CarveError("the design mesh has a non-finite vertex")
    reach = float(np.abs(vertices).max())
    if reach > MAX_REACH_MM:      # 1e300 mm made the raster lines endless (a hang, not a refusal)
        raise CarveError(f"the design mesh reaches {reach:g} mm from the work zero (more than {MAX_REACH_MM:g} mm): "
                         f"is it in other units?")
    if faces.size and (faces.min() < 0 or faces.max() >= len(vertices)):
        raise CarveError(f"the design mesh has a face with a vertex index outside 0..{len(vertices) - 1}")
    size = vertices.max(axis=0) - vertices.min(axis=0)
    if size[0] <= 0 or size[1] <= 0:
        raise CarveError(f"the design mesh is flat in X or Y ({size[0]:g} x {size[1]:g} mm): nothing to carve")
    if min(size[0], size[1]) < MIN_SIZE_MM:   # a relief scaled 1e-9 was planned, then refused by the gate's grid
        raise CarveError(f"the design mesh is {size[0]:.3g} x {size[1]:.3g} mm, under {MIN_SIZE_MM:g} mm across: "
                         "is it in other units (metres read as mm)?")
    return vertices, faces.astype(np.int64)


def steepest_slope(vertices, faces, angle_deg: float) -> float:
    """Steepest slope (degrees) across the raster direction over the mesh's upward faces."""
    tri = vertices[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    up = normal[:, 2] > 1e-9 * np.linalg.norm(normal, axis=1)
    if not up.any():
        return 0.0
    gradient = -normal[up, :2] / normal[up, 2:3]
    return float(math.degrees(math.atan(np.abs(_across(gradient, angle_deg)).max())))


def _across(gradient: np.ndarray, angle_deg: float) -> np.ndarray:
    """Each row of ``gradient`` (k, 2) dotted with the unit vector across ``angle_deg``, written
    out (a matrix-vector product would wake BLAS's helper thread for nothing)."""
    sx, cy = -math.sin(math.radians(angle_deg)), math.cos(math.radians(angle_deg))
    return gradient[:, 0] * sx + gradient[:, 1] * cy


def sharpest_convex_radius(vertices, faces, min_up: float = 0.3) -> float:
    """Smallest radius of a convex bend between two upward faces (normal Z above ``min_up``):
    the angle between their normals over the distance between their centroids; inf if none."""
    tri = vertices[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normal, axis=1)
    ok = length > 0
    unit = np.where(ok[:, None], normal / np.where(ok, length, 1)[:, None], 0)
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    owner = np.tile(np.arange(len(faces)), 3)
    order = np.lexsort((edges[:, 1], edges[:, 0]))
    edges, owner = edges[order], owner[order]
    same = np.all(edges[1:] == edges[:-1], axis=1)
    a, b = owner[:-1][same], owner[1:][same]
    up = (unit[a, 2] > min_up) & (unit[b, 2] > min_up)
    a, b = a[up], b[up]
    centre = tri.mean(axis=1)
    gap = centre[b] - centre[a]
    convex = np.einsum("ij,ij->i", unit[b] - unit[a], gap) < 0     # normals turn away: a ridge
    angle = np.arccos(np.clip(np.einsum("ij,ij->i", unit[a], unit[b]), -1, 1))
    bend = convex & (angle > 1e-9)
    if not bend.any():
        return math.inf
    return float(np.min(np.linalg.norm(gap[bend], axis=1) / angle[bend]))


def raster_lines(bounds: tuple, angle_deg: float, spacing: float) -> list:
    """Lines at ``angle_deg`` ``spacing`` apart covering the rectangle (x0, y0, x1, y1), each
    clipped to it, as (2, 2) arrays; the first and last touch the rectangle's extreme corners."""
    x0, y0, x1, y1 = bounds
    a = math.radians(angle_deg)
    u = np.array([math.cos(a), math.sin(a)])
    v = np.array([-u[1], u[0]])
    corners = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
    offsets = corners @ v
    lo, hi = offsets.min(), offsets.max()
    count = max(1, math.ceil((hi - lo) / spacing - 1e-9))
    lines = []
    for k in range(count + 1):
        c = lo + (hi - lo) * k / count
        base = c * v
        # clip base + t*u to the rectangle
        t_lo, t_hi = -np.inf, np.inf
        for axis, (low, high) in enumerate(((x0, x1), (y0, y1))):
            if abs(u[axis]) < 1e-12:
                if not low - 1e-9 <= base[axis] <= high + 1e-9:
                    t_lo, t_hi = 1.0, 0.0
                continue
            ta, tb = (low - base[axis]) / u[axis], (high - base[axis]) / u[axis]
            t_lo, t_hi = max(t_lo, min(ta, tb)), min(t_hi, max(ta, tb))
        if t_lo <= t_hi + 1e-12:
            start, end = base + t_lo * u, base + max(t_hi, t_lo) * u
            start = np.clip(start, [x0, y0], [x1, y1])
            end = np.clip(end, [x0, y0], [x1, y1])
            lines.append(np.array([start, end]))
    return lines


def _zigzag(lines: list) -> np.ndarray:
    points = []
    for k, line in enumerate(lines):
        points.extend(line if k % 2 == 0 else line[::-1])
    points = np.array(points)
    keep = np.concatenate([[True], np.linalg.norm(np.diff(points, axis=0), axis=1) > 1e-9])
    return points[keep]


def plan(vertices, faces, settings: CarveSettings | None = None, *, name: str = "carve",
         stock_top: float | None = None, progress=None, kernel: str = "auto") -> CarveResult:
    """Roughing and finishing of the design mesh; see the module docstring."""
    settings = settings or CarveSettings()
    settings.check()
    vertices, faces = check_mesh(vertices, faces)
    report = progress or (lambda fraction, text="": None)
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    top = float(hi[2]) if stock_top is None else float(stock_top)
    if not math.isfinite(top) or top < hi[2] - 1e-9:
        raise CarveError(f"stock top {stock_top!r} mm is below the design's highest point {hi[2]:.3f} mm")
    bounds = (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))
    bottom = float(lo[2])
    if top <= bottom:   # a flat design with nothing above it: "stock box ... encloses no volume" from the gate
        raise CarveError(f"the design is flat (Z {bottom:g} mm everywhere) and no stock stands above it: nothing to "
                         f"carve (Stock Above in the Carve panel gives the stock)")
    warnings = []
    operations = []
    levels = []
    clearance_z, safe_z = top + settings.clearance, top + settings.safe_z
    try:
        mesh = Mesh(vertices, faces)          # one for every tool
        if settings.rough:
            report(0.0, "roughing")
            rough, levels = _roughing(vertices, faces, mesh, settings, bounds, top, bottom, clearance_z, safe_z,
                                      kernel, lambda f, text="": report(0.5 * f, "roughing"))
            if rough is not None:
                operations.append(rough)
        flat = ball_stepover(settings.finish_tool.radius, settings.scallop)
        walls = wall_faces(vertices, faces, settings.raster_angle, settings.max_slope_deg, bounds)
        wall_area = float(_areas(vertices, faces[walls]).sum())
        if not settings.wall_pass:
            if walls.any():
                warnings.append(f"{wall_area:.0f} mm2 of walls are steeper than {settings.max_slope_deg:g} degrees "
                                f"across both rasters (or vertical) and Wall Pass is off: no raster finishes them")
            walls = np.zeros(len(faces), bool)
        slope = steepest_slope(vertices, faces[~walls], settings.raster_angle)
        if slope > settings.max_slope_deg and not settings.steep_cleanup:
            warnings.append(f"faces slope up to {slope:.0f} degrees across the finishing raster; the stepover "
                            f"allows for {settings.max_slope_deg:g} degrees, so the scallop is higher there")
        rho = sharpest_convex_radius(vertices, faces)
        raster_slope = raster_slope_deg(vertices, faces[~walls], settings.raster_angle, settings.max_slope_deg)
        stepover = _spacing(flat, raster_slope, settings.max_slope_deg, rho, settings.finish_tool.radius)
        steep = settings.steep_cleanup and slope > settings.max_slope_deg
        share = (0.3 if steep else 0.4) if walls.any() else (0.35 if steep else 0.5)
        report(0.5, "finishing")
        operations.append(_finishing(vertices, faces, mesh, settings, bounds, top, bottom, stepover, clearance_z,
                                     safe_z, kernel, lambda f, text="": report(0.5 + share * f, "finishing")))
        cleanup = None
        if steep:
            report(0.5 + share, "steep cleanup")
            cleanup = _steep_cleanup(vertices, faces, mesh, settings, bounds, top, bottom, flat, rho, clearance_z,
                                     safe_z, kernel, lambda f, text="": report(0.5 + share + 0.15 * f,
                                                                               "steep cleanup"), ~walls)
            if cleanup.operation is not None:
                operations.append(cleanup.operation)
            if cleanup.slope > settings.max_slope_deg:
                warnings.append(f"faces in the steep regions slope up to {cleanup.slope:.0f} degrees across the "
                                f"cleanup raster too; its stepover allows for {settings.max_slope_deg:g} degrees, "
                                f"so the scallop is higher there")
        wall_pass = None
        if walls.any():
            report(0.9, "walls")
            wall_pass = _wall_pass(vertices, faces, mesh, settings, walls, flat, top, bottom, clearance_z, safe_z,
                                   kernel, lambda f, text="": report(0.9 + 0.1 * f, "walls"))
            if wall_pass.operation is not None:
                operations.append(wall_pass.operation)
    except DropCutterError as error:
        raise CarveError(str(error)) from None
    report(1.0, "done")
    program = Program(name, operations, notes=list(warnings))
    result = CarveResult(program, (bounds[0], bounds[1], bottom, bounds[2], bounds[3], top), stepover, flat, slope,
                         rho, levels, warnings, raster_slope_deg=raster_slope, walls=wall_pass,
                         wall_area_mm2=wall_area)
    if cleanup is not None:
        result.steep_area_mm2 = cleanup.area
        if cleanup.operation is not None:
            result.cleanup_stepover, result.cleanup_slope_deg = cleanup.stepover, cleanup.slope
    return result


def _spacing(flat: float, slope_deg: float, cap_deg: float, rho: float, r: float) -> float:
    """Raster spacing for a scallop whose level-ground stepover is ``flat``: see the module docstring."""
    rho = max(rho, r)         # the floor: a bend tighter than the ball counts as one of its radius
    bend = math.sqrt(rho / (rho + r)) if rho < math.inf else 1.0
    return MARGIN * flat * math.cos(math.radians(min(slope_deg, cap_deg))) * bend


def raster_slope_deg(vertices, faces, angle_deg: float, cap_deg: float) -> float:
    """Steepest slope across the raster among the upward faces it finishes (those no steeper
    than ``cap_deg`` across it; the steeper ones are the cleanup's or the wall pass's)."""
    slope, up = face_slopes(vertices, faces, angle_deg)
    ok = up & (slope <= cap_deg + 1e-9)
    return float(slope[ok].max()) if ok.any() else 0.0


def _areas(vertices, faces) -> np.ndarray:
    tri = vertices[faces]
    return 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)


def wall_faces(vertices, faces, angle_deg: float, cap_deg: float, bounds) -> np.ndarray:
    """Per face: a wall no finishing raster finishes, left to the wall pass.  A wall is not
    turned down (an overhang no 3-axis tool reaches), does not lie on a side of the stock's box
    (nothing stands beyond it), and either stands vertical (a raster only drops past it) or
    slopes more than ``cap_deg`` across both the raster (``angle_deg``) and the cleanup's
    raster at +90 degrees."""
    tri = vertices[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normal, axis=1)
    vertical = (np.abs(normal[:, 2]) <= 1e-9 * length) & (length > 0)
    across, up = face_slopes(vertices, faces, angle_deg)
    cross, _ = face_slopes(vertices, faces, angle_deg + 90.0)
    steep = up & (across > cap_deg + 1e-9) & (cross > cap_deg + 1e-9)
    x0, y0, x1, y1 = bounds
    near = 1e-9 * max(x1 - x0, y1 - y0)
    side = np.zeros(len(faces), bool)
    for axis, value in ((0, x0), (0, x1), (1, y0), (1, y1)):
        side |= np.all(np.abs(tri[:, :, axis] - value) <= near, axis=1)
    return (vertical | steep) & ~side


def _wall_pass(vertices, faces, mesh, s: CarveSettings, walls, flat, top, bottom, clearance_z, safe_z, kernel,
               report) -> WallPass:
    """Waterlines along the walls (:mod:`.waterline`), from the walls' top down to their foot,
    ``z_step`` apart: on a wall of slope a, levels dz apart put the ball's contacts dz / sin(a)
    apart along it, and two ball contacts c apart on a plane leave r - sqrt(r^2 - c^2 / 4), so
    dz = MARGIN * 2 sqrt(2 r h - h^2) * sin(a) for the least steep wall leaves at most h."""
    r = s.finish_tool.radius
    tri = vertices[faces[walls]]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    sine = np.sqrt(normal[:, 0] ** 2 + normal[:, 1] ** 2) / np.linalg.norm(normal, axis=1)
    shallowest = float(np.degrees(np.arcsin(np.clip(sine.min(), 0.0, 1.0))))
    z_step = MARGIN * flat * float(sine.min())
    contact = z_step / float(sine.min())
    scallop = r - math.sqrt(r * r - contact * contact / 4)
    # tip levels: from where the ball's equator meets the walls' top edge down to their foot
    z_top, z_foot = float(tri[:, :, 2].max()) - r, max(float(tri[:, :, 2].min()), bottom)
    count = max(1, math.ceil((z_top - z_foot) / z_step - 1e-9)) if z_top > z_foot else 0
    if count > MAX_WALL_LEVELS:     # Max Slope near 0 makes every sloped face a wall, at a Z step near 0
        raise CarveError(f"the wall pass would need {count} waterline levels {z_step:.4g} mm apart (walls as shallow "
                         f"as {shallowest:.1f} degrees, steeper than Max Slope {s.max_slope_deg:g}): raise Max Slope "
                         f"or turn Wall Pass off")
    levels = list(np.linspace(z_top, z_foot, count + 1)) if count else [z_foot]
    # the drop cutter's heights once, on a grid over the walls' footprint grown by the ball
    cell = min(s.sample_spacing, r / 4)
    lo, hi = tri[:, :, :2].reshape(-1, 2).min(axis=0) - r - 3 * cell, tri[:, :, :2].reshape(-1, 2).max(axis=0) + r + 3 * cell
    x = lo[0] + cell * np.arange(int(math.ceil((hi[0] - lo[0]) / cell)) + 1)
    y = lo[1] + cell * np.arange(int(math.ceil((hi[1] - lo[1]) / cell)) + 1)
    band = footprint_mask(tri[:, :, :2], lo, (len(x), len(y)), cell, r + cell)
    cutter = DropCutter(vertices, faces, s.finish_tool, floor=-np.inf, kernel=kernel, mesh=mesh)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    heights = np.full(band.shape, -np.inf)
    heights[band] = cutter.points(np.column_stack([gx[band], gy[band]]))
    pieces = []
    for n, z in enumerate(levels):
        for points, closed in waterline.contours(cutter, z, x, y, heights, band, s.tolerance):
            if len(points) >= 2:
                pieces.append((n, float(z), points, closed))
        report(0.8 * (n + 1) / len(levels))
    builder = PathBuilder(clearance_z, s.finish_feed, s.plunge_feed, surface_z=top)
    links = waterline.cut(builder, cutter, pieces, LINK * s.finish_tool.diameter, s.sample_spacing, s.tolerance)
    if builder.position is None:
        return WallPass(None, z_step, levels, shallowest, scallop, 0)
    builder.retract()
    builder.rapid(builder.position[0], builder.position[1], safe_z)
    operation = Operation("wall pass", s.finish_tool, s.finish_rpm, clearance_z=clearance_z, safe_z=safe_z,
                          comment=f"waterlines {z_step:.3f} mm apart on walls steeper than {s.max_slope_deg:g} deg, "
                                  f"climb", **builder.arrays())
    return WallPass(operation, z_step, levels, shallowest, scallop, links)


MAX_ROUGHING_MOVES = 10_000_000   # a program past this is hundreds of MB; the memory runs out first


def _roughing(vertices, faces, mesh, s: CarveSettings, bounds, top, bottom, clearance_z, safe_z, kernel, report):
    cutter = DropCutter(vertices, faces, s.rough_tool, allowance=s.allowance, floor=bottom, kernel=kernel,
                        mesh=mesh)
    lines = raster_lines(bounds, s.raster_angle + 90.0, s.rough_stepover)
    spacing = min(s.sample_spacing * 2, s.rough_tool.radius / 2)
    dropped = []
    for k, line in enumerate(lines):
        if np.linalg.norm(line[1] - line[0]) < 1e-9:
            continue
        dropped.append(cutter.path(line if k % 2 == 0 else line[::-1], spacing, max(s.allowance / 4, s.tolerance)))
        report(0.6 * (k + 1) / len(lines))
    lowest = min(float(p[:, 2].min()) for p in dropped)
    levels = []
    level = top
    while level > lowest + 1e-9:
        level = max(level - s.step_down, lowest)
        levels.append(level)
    if not levels:
        return None, []
    builder = PathBuilder(clearance_z, s.rough_feed, s.plunge_feed, surface_z=top)
    above, written = top, 0
    for n, level in enumerate(levels):
        for points in dropped:
            material = points[:, 2] < above - 1e-9
            if not material.any():
                continue
            grown = material.copy()        # one more point each side: the tool enters and leaves on the surface
            grown[1:] |= material[:-1]
            grown[:-1] |= material[1:]
            edges = np.flatnonzero(np.diff(np.concatenate([[0], grown.astype(np.int8), [0]])))
            written += int((edges[1::2] - edges[::2]).sum())
            if written > MAX_ROUGHING_MOVES:    # 1000 mm of stock at a 0.01 mm step down: a MemoryError
                raise CarveError(f"the roughing would need more than {MAX_ROUGHING_MOVES} moves ({len(levels)} levels "
                                 f"{s.step_down:g} mm apart through {top - lowest:g} mm of stock): give a larger "
                                 f"step down or roughing stepover, or less stock above the design")
            for start, end in zip(edges[::2], edges[1::2]):
                run = points[start:end].copy()
                run[:, 2] = np.maximum(run[:, 2], level)
                builder.plunge(*run[0])
                builder.polyline(run[1:])
        above = level
        report(0.6 + 0.4 * (n + 1) / len(levels))
    builder.retract()
    builder.rapid(builder.position[0], builder.position[1], safe_z)
    tool = s.rough_tool
    return Operation("roughing", tool, s.rough_rpm, clearance_z=clearance_z, safe_z=safe_z,
                     comment=f"Z levels {s.step_down:g} mm, allowance {s.allowance:g} mm",
                     **builder.arrays()), levels


def _finishing(vertices, faces, mesh, s: CarveSettings, bounds, top, bottom, stepover, clearance_z, safe_z, kernel,
               report):
    cutter = DropCutter(vertices, faces, s.finish_tool, floor=-np.inf, kernel=kernel, mesh=mesh)
    # out to 0.7 r beyond the stock: the ball's last contacts reach the stock's edge, and no
    # point of the grown box is further than r from a box-shaped design (0.7 * sqrt(2) < 1)
    g = 0.7 * s.finish_tool.radius
    path = _zigzag(raster_lines((bounds[0] - g, bounds[1] - g, bounds[2] + g, bounds[3] + g), s.raster_angle,
                                stepover))
    if len(path) < 2:
        path = np.vstack([path, path])
    chunks = []
    pieces = max(1, len(path) // 16)
    for k in range(0, len(path) - 1, pieces):
        part = cutter.path(path[k:k + pieces + 1], s.sample_spacing, s.tolerance)
        chunks.append(part if not chunks else part[1:])
        report(min(1.0, (k + pieces) / (len(path) - 1)))
    points = np.vstack(chunks)
    # beside a design's side wall the ball would drop past its foot: the tip stays on the stock's
    # bottom (the table is below it), where the ball still clears the wall
    points[:, 2] = np.where(np.isfinite(points[:, 2]), np.maximum(points[:, 2], bottom), points[:, 2])
    builder = PathBuilder(clearance_z, s.finish_feed, s.plunge_feed, surface_z=top)
    # where nothing is under the ball (beyond a design that does not fill its box) the path
    # breaks: retract, and come down again where the ball meets the design
    touching = np.isfinite(points[:, 2])
    edges = np.flatnonzero(np.diff(np.concatenate([[0], touching.astype(np.int8), [0]])))
    for start, end in zip(edges[::2], edges[1::2]):
        run = _drop_collinear(points[start:end], s.tolerance / 2)
        builder.plunge(*run[0])
        builder.polyline(run[1:])
    builder.retract()
    builder.rapid(builder.position[0], builder.position[1], safe_z)
    return Operation("finishing", s.finish_tool, s.finish_rpm, clearance_z=clearance_z, safe_z=safe_z,
                     comment=f"raster {s.raster_angle:g} deg, stepover {stepover:.3f} mm, scallop {s.scallop:g} mm",
                     **builder.arrays())


@dataclass
class _Cleanup:
    operation: Operation | None
    stepover: float
    slope: float                      # steepest slope across the cleanup raster among its faces
    area: float                       # XY area of the steep faces


def face_slopes(vertices, faces, angle_deg: float) -> tuple:
    """Per face: the slope in degrees across the direction ``angle_deg`` (0 for faces not facing
    up), and whether it faces up."""
    tri = vertices[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    up = normal[:, 2] > 1e-9 * np.linalg.norm(normal, axis=1)
    slope = np.zeros(len(faces))
    slope[up] = np.degrees(np.arctan(np.abs(_across(-normal[up, :2] / normal[up, 2:3], angle_deg))))
    return slope, up


def footprint_mask(triangles: np.ndarray, origin, shape, cell: float, grow: float) -> np.ndarray:
    """Grid (``shape``, cell centres ``origin + cell * index``): True within about ``grow`` of the
    XY footprint of ``triangles`` (m, 3, 2).  Each triangle is sampled on a barycentric grid no
    coarser than the cell, so no point of it is further than a cell from a marked centre; the
    marks then grow by a disk of ``grow`` plus one cell."""
    nx, ny = shape
    mask = np.zeros(shape, bool)
    if not len(triangles):
        return mask
    edges = np.linalg.norm(triangles - np.roll(triangles, 1, axis=1), axis=2).max(axis=1)
    counts = np.maximum(np.ceil(edges / cell), 1).astype(np.int64)
    for n in np.unique(counts):
        i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
        keep = i + j <= n
        weights = np.column_stack([i[keep], j[keep], n - i[keep] - j[keep]]) / n
        chosen = triangles[counts == n]
        batch = max(1, 1_000_000 // len(weights))          # bounded memory for large triangles
        for start in range(0, len(chosen), batch):
            points = np.einsum("pk,tkd->tpd", weights, chosen[start:start + batch]).reshape(-1, 2)
            ix = np.clip(np.rint((points[:, 0] - origin[0]) / cell).astype(np.int64), 0, nx - 1)
            iy = np.clip(np.rint((points[:, 1] - origin[1]) / cell).astype(np.int64), 0, ny - 1)
            mask[ix, iy] = True
    return dilate(mask, math.ceil(grow / cell) + 1)


def dilate(mask: np.ndarray, k: int) -> np.ndarray:
    """``mask`` grown by a disk of ``k`` cells (row by row: a run of half-width sqrt(k^2 - d^2)
    along Y, d rows away along X)."""
    if k <= 0:
        return mask.copy()
    nx, ny = mask.shape
    running = np.concatenate([np.zeros((nx, 1), np.int64), np.cumsum(mask, axis=1)], axis=1)
    j = np.arange(ny)
    out = np.zeros_like(mask)
    for d in range(-k, k + 1):
        w = math.isqrt(k * k - d * d)
        row = running[:, np.clip(j + w + 1, 0, ny)] - running[:, np.clip(j - w, 0, ny)] > 0
        if d >= 0:
            out[:nx - d] |= row[d:]
        else:
            out[-d:] |= row[:nx + d]
    return out


def _steep_cleanup(vertices, faces, mesh, s: CarveSettings, bounds, top, bottom, flat, rho, clearance_z, safe_z,
                   kernel, report, rastered) -> _Cleanup:
    r = s.finish_tool.radius
    slope, up = face_slopes(vertices, faces, s.raster_angle)
    steep = up & (slope > s.max_slope_deg + 1e-9) & rastered        # the walls are the wall pass's
    tri = vertices[faces[steep]][:, :, :2]
    area = float(0.5 * np.abs(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])).sum())
    g = 0.7 * r
    x0, y0, x1, y1 = bounds[0] - g, bounds[1] - g, bounds[2] + g, bounds[3] + g
    cell = max(min(s.sample_spacing, r / 3), math.sqrt((x1 - x0) * (y1 - y0) / 4e6))
    shape = (int(math.ceil((x1 - x0) / cell)) + 1, int(math.ceil((y1 - y0) / cell)) + 1)
    mask = footprint_mask(tri, (x0, y0), shape, cell, r)

    def inside(xy):
        ix = np.clip(np.rint((xy[:, 0] - x0) / cell).astype(np.int64), 0, shape[0] - 1)
        iy = np.clip(np.rint((xy[:, 1] - y0) / cell).astype(np.int64), 0, shape[1] - 1)
        return mask[ix, iy]

    # the cleanup's own stepover: the steepest slope across it among the faces it passes over
    cross, _ = face_slopes(vertices, faces, s.raster_angle + 90.0)
    # (not counting the faces steeper across it than across the first raster: that one finishes them)
    cap = s.max_slope_deg + 1e-9
    near = up & rastered & inside(vertices[faces].mean(axis=1)[:, :2]) & ~((cross > cap) & (slope <= cap))
    cross_slope = float(cross[near].max()) if near.any() else 0.0
    stepover = _spacing(flat, cross_slope, s.max_slope_deg, rho, r)
    cutter = DropCutter(vertices, faces, s.finish_tool, floor=-np.inf, kernel=kernel, mesh=mesh)
    builder = PathBuilder(clearance_z, s.finish_feed, s.plunge_feed, surface_z=top)
    lines = raster_lines((x0, y0, x1, y1), s.raster_angle + 90.0, stepover)
    for k, line in enumerate(lines):
        a, b = line if k % 2 == 0 else line[::-1]
        length = float(np.linalg.norm(b - a))
        count = max(2, math.ceil(length / (cell / 2)) + 1)
        samples = a + np.outer(np.linspace(0.0, 1.0, count), b - a)
        edges = np.flatnonzero(np.diff(np.concatenate([[0], inside(samples).astype(np.int8), [0]])))
        for start, end in zip(edges[::2], edges[1::2]):
            if end - start < 2:
                continue
            points = cutter.path(samples[[start, end - 1]], s.sample_spacing, s.tolerance)
            points[:, 2] = np.where(np.isfinite(points[:, 2]), np.maximum(points[:, 2], bottom), points[:, 2])
            touching = np.isfinite(points[:, 2])
            runs = np.flatnonzero(np.diff(np.concatenate([[0], touching.astype(np.int8), [0]])))
            for first, last in zip(runs[::2], runs[1::2]):
                if last - first < 2:
                    continue
                run = _drop_collinear(points[first:last], s.tolerance / 2)
                bridge = _bridge(cutter, builder.position, run[0], LINK * s.finish_tool.diameter, s, bottom)
                if bridge is None:
                    builder.plunge(*run[0])
                else:
                    builder.polyline(bridge[1:])
                builder.polyline(run[1:])
        report((k + 1) / len(lines))
    if builder.position is None:
        return _Cleanup(None, stepover, cross_slope, area)
    builder.retract()
    builder.rapid(builder.position[0], builder.position[1], safe_z)
    operation = Operation("steep cleanup", s.finish_tool, s.finish_rpm, clearance_z=clearance_z, safe_z=safe_z,
                          comment=f"raster {s.raster_angle + 90.0:g} deg over faces steeper than "
                                  f"{s.max_slope_deg:g} deg, stepover {stepover:.3f} mm", **builder.arrays())
    return _Cleanup(operation, stepover, cross_slope, area)


def _bridge(cutter, position, start, reach: float, s: CarveSettings, bottom: float):
    """The ball dropped along the straight line from ``position`` to ``start`` (both dropped
    points), if that is at most ``reach`` long and on the design all the way; else None."""
    if position is None:
        return None
    here = np.asarray(position, float)
    gap = float(np.linalg.norm(start[:2] - here[:2]))
    if not 1e-9 < gap <= reach:
        return None
    bridge = cutter.path(np.array([here[:2], start[:2]]), s.sample_spacing, s.tolerance)
    if not np.all(np.isfinite(bridge[:, 2])):
        return None
    bridge[:, 2] = np.maximum(bridge[:, 2], bottom)
    if abs(bridge[0, 2] - here[2]) > 1e-9 or abs(bridge[-1, 2] - start[2]) > 1e-9:
        return None
    return _drop_collinear(bridge, s.tolerance / 2)


def _drop_collinear(points: np.ndarray, tolerance: float) -> np.ndarray:
    """Leave out points within ``tolerance`` of the line through their neighbours (one pass,
    never two neighbours in a row, so no point ends up further than that from the path; never
    one beside a segment steeper than 89 degrees)."""
    if len(points) < 3:
        return points
    a, b, c = points[:-2], points[1:-1], points[2:]
    ac = c - a
    length = np.linalg.norm(ac, axis=1)
    t = np.einsum("ij,ij->i", b - a, ac) / np.where(length > 0, length ** 2, 1)
    off = np.linalg.norm(a + ac * t[:, None] - b, axis=1)
    below = (b[:, 2] <= (a + ac * t[:, None])[:, 2] + tolerance)
    # nor a point next to a jump (a vertical wall): the near-vertical line through its neighbours
    # passes within the tolerance of points that hold the ball off the wall
    run = np.linalg.norm(np.diff(points[:, :2], axis=0), axis=1)
    jump = np.abs(np.diff(points[:, 2])) > STEEP * run
    drop = (off <= tolerance) & below & (t > 0) & (t < 1) & ~jump[:-1] & ~jump[1:]
    # never two in a row: of each run of neighbouring candidates, the first, third, ... go
    keep = np.ones(len(points), bool)
    candidates = np.flatnonzero(drop) + 1
    if len(candidates):
        starts = np.flatnonzero(np.diff(candidates, prepend=-2) != 1)      # where each run begins
        run_start = np.repeat(starts, np.diff(np.append(starts, len(candidates))))
        keep[candidates[(np.arange(len(candidates)) - run_start) % 2 == 0]] = False
    return points[keep]


def measured_scallop(heightfield, vertices, faces) -> dict:
    """What the finishing left on the design, from a simulated height field: the largest
    height of material above the design measured along the surface normal (the vertical
    excess times the cosine of the design's slope there, from the design's heights on the
    grid), the largest vertical excess, where the first is, and the deepest cut below the design."""
    from ...simulate.meshtop import mesh_top

    top = mesh_top(heightfield, np.asarray(vertices, float), np.asarray(faces, np.int64))
    known = np.isfinite(top) & heightfield.inside
    if not known.any():
        raise CarveError("the design does not lie over the simulated stock")
    excess = np.where(known, heightfield.heights.astype(float) - top, -np.inf)
    gx, gy = np.gradient(np.where(known, top, 0.0), heightfield.cell_x, heightfield.cell_y)
    normal = excess / np.sqrt(1 + gx * gx + gy * gy)
    i, j = np.unravel_index(int(np.argmax(normal)), normal.shape)
    return {"max_scallop_mm": float(normal[i, j]), "max_vertical_excess_mm": float(excess[known].max()),
            "at": [float(heightfield.x()[i]), float(heightfield.y()[j])],
            "deepest_below_design_mm": float(max(0.0, -excess[known].min()))}
