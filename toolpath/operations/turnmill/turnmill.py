"""W4: 4.5-axis turn-mill CAM (seed 003, Yano and Asakawa, Kanazawa University).

The machine is a turn-mill centre: an NC lathe whose turret carries driven tools.  It moves X, Z
and C (no Y).  The part turns about Z, the C axis.  A turret station holds either a radial tool,
whose axis lies along machine X (perpendicular to the part axis), or an axial tool along Z.  The
paper calls this 4-axis motion plus the switch between the two tools by turret indexing
"4.5-axis".

Part coordinates are the mesh in mm.  The C axis is the Z axis, and the stock is a bar about Z
(:class:`Stock`).  The built-in sample puts the end face at z = 0 and the chuck side at z = -60.
This follows the paper, where the axial layers stop once their lowest point clears Z = tool radius.

The workflow, after the paper:

1. :func:`classify_faces` (:mod:`.turnreach`).  Rays cast from samples of every face, radially
   out from the axis and along +Z, label it NEITHER, RADIAL, AXIAL or BOTH.
2. :func:`radial_layers`.  Planes parallel to XY slice the radial faces.  The section points are
   offset to the ball centre, then offset again step by step along the normal projected onto XY,
   out to the stock (the roughing layers).  Centres whose ball would not cut stock are deleted and
   the rest are joined into passes.  In each layer, runs are taken nearest first, and neighbours
   whose straight link keeps the ball clear of the part become one pass.
3. :func:`axial_layers`.  Points on the axial faces at the stepover are offset to the ball centre
   and put on a grid (cell = stepover).  They are chained from a start cell by searching the
   neighbouring cells in the paper's order: outward, counter-clockwise, inward, clockwise.  That
   path is then copied upward in +Z by the roughing step until it no longer cuts stock (the
   paper: until its lowest Z clears the tool radius).  The copies are executed from the top down.
4. :func:`plan`.  Four operations in the IR (:class:`TurnMillOperation`): radial roughing and
   finishing on the radial turret station, axial roughing and finishing on the axial one.  A
   face labelled BOTH is cut once, from the direction it faces more squarely
   (:func:`path_faces`).  Between passes the tool retracts along its own axis to a clearance
   outside the stock and turns C there.

Ball centres are exact.  Every centre is pushed clear of the whole mesh to the tool radius,
against walls, shoulders and other faces, and deleted if it cannot be.  The extreme centres of a
feature therefore land on its boundary, whatever the point spacing.  The paper's 20 mm axial
feature came out 19.8 mm because its points were too far apart.  The spacings follow the chordal
``tolerance`` (default 0.01 mm):

- stepover (slices, grid): the ball's scallop height equals the tolerance;
- arcs where the normal turns: the chord under a rolling ball stays within the tolerance;
- polar interpolation: the machine interpolates X, Z and C linearly, which bends a straight
  part-space segment into a spiral.  Segments are split until that bend is within the tolerance.

Machine coordinates (the IR): ``xyz = (X, 0, Z)``, ``rotary = {"c": degrees}``.

- C is the part angle atan2(y, x) of the ball centre.  The control turns the part to bring that
  angle to the tool on the machine's +X side: machine point = Rz(-C) . part point.  C is
  unwrapped: neighbouring moves never differ by more than 180 degrees.
- X is the distance of the tool tip from the axis (a radius; the post may write a diameter).
  Z is the tip height.  Radial tool: tip = ball centre - r along the radial direction.  Axial
  tool: tip = ball centre - r in Z.
- Axial milling with X-Z-C only, the tool along Z, is polar interpolation done in machine
  coordinates: a part point (x, y) is reached with X = its radius and C = its angle.  A path
  through the axis itself turns C by 180 degrees there, with the tool on the axis.

Limits: the gouge check covers the ball (against the whole mesh), not the shank or holder.
The approach and retract lines along the tool axis are not re-checked: classification found the
face clear in that direction.  A ball centre pushed through a wall thinner than the tool radius is
not detected.  The roughing copies of an axial feature stand on its floor, as in the paper.  They
follow vertical walls; a tapered wall gets its own grid only if it faces +Z.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from ...ir import kinematics
from . import turnskip
from ...engines.facets import planning_mesh
from ...engines.meshrays import (PAIR_BUDGET, BoxGrid, RayEngine, Triangles, TrimeshRayEngine, check_mesh, checked_mesh,
                                 face_normals, face_samples)
from ...ir.program import FEED, RAPID, Program, Tool, merge_short_moves
from ...ir.program import TurnMillOperation
from .errors import TurnMillError
from .turnreach import AXIAL, BOTH, DIRECTIONS, LABEL_NAMES, NEITHER, RADIAL, classify_faces, path_faces
from .turnjoin import (CHORD_DIP, MAX_BALL_POSITIONS, TurnMillCancelled, count_positions, join_layers, merged_move_clear,
                       short_segments, subdivide)

PUSH_ITERATIONS = 8      # rounds of pushing a ball centre clear of the surface (corners need 2-3)

# The grid search order of the axial chaining (paper 4.4): outward, counter-clockwise, inward,
# clockwise, as (step along the outward axis, step along the counter-clockwise axis).
NEIGHBOUR_ORDER = ((1, 0), (0, 1), (-1, 0), (0, -1))


# ----- inputs ---------------------------------------------------------------------------------
def check_on_axis(vertices: np.ndarray) -> None:
    """A turned part is modelled around the spindle axis (Z): refused, naming its extent, when it
    has no length along Z or the axis X0 Y0 lies outside its X/Y extent (a part placed 5 m off the
    axis was planned as a 10 m bar, X10044 in the program, in 6 minutes)."""
    v = np.asarray(vertices, float)
    lo, hi = v.min(axis=0), v.max(axis=0)
    if hi[2] - lo[2] <= 1e-9:
        raise TurnMillError(f"the part has no length along Z, the spindle axis (Z {lo[2]:g} to {hi[2]:g} mm): "
                            "model it around the Z axis")
    if not (lo[0] <= 0.0 <= hi[0] and lo[1] <= 0.0 <= hi[1]):
        raise TurnMillError(f"the part lies off the spindle axis: X {lo[0]:.4g} to {hi[0]:.4g} mm, Y {lo[1]:.4g} to "
                            f"{hi[1]:.4g} mm, the axis X0 Y0 outside them; model it around the Z axis")


@dataclass(frozen=True)
class Stock:
    """Round bar stock on the C axis: its radius and the Z range it occupies (z_max = end face)."""

    radius: float
    z_min: float
    z_max: float

    def __post_init__(self):
        values = (self.radius, self.z_min, self.z_max)
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
            raise TurnMillError(f"stock radius and Z range must be finite numbers, got {values}")
        if self.radius <= 0:
            raise TurnMillError(f"stock radius must be > 0, got {self.radius}")
        if self.z_min >= self.z_max:
            raise TurnMillError(f"stock z_min ({self.z_min}) must be below z_max ({self.z_max})")

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Distance of each point from the solid stock (0 inside)."""
        rho = np.hypot(points[:, 0], points[:, 1])
        radial = np.maximum(rho - self.radius, 0.0)
        axial = np.maximum(np.maximum(points[:, 2] - self.z_max, self.z_min - points[:, 2]), 0.0)
        return np.hypot(radial, axial)


@dataclass(frozen=True)
class TurnMillSettings:
    """Tooling and path parameters (mm, mm/min, rpm).  Both turret stations carry the same ball
    end mill, as in the paper (6 mm)."""

    tool_diameter: float = 6.0
    tolerance: float = 0.01        # chordal tolerance: scallops, rolling arcs, polar interpolation
    stepover: float | None = None  # slice / grid spacing; None = scallop height equal to the tolerance
    roughing_step: float = 1.0     # depth of each roughing layer
    sample_spacing: float = 2.0    # spacing of the classification samples
    clearance: float = 2.0         # retract this far outside the stock (radial: X, axial: Z)
    feed: float = 500.0
    plunge_feed: float = 150.0
    spindle_rpm: float = 4000.0
    radial_station: int = 1
    axial_station: int = 2
    rapid_rate: float = 5000.0     # for the cycle-time estimate
    block_ms: float | None = None  # the control's shortest block (ms, machine profile): shorter moves merge

    def __post_init__(self):
        def positive(value):
            return isinstance(value, (int, float)) and math.isfinite(value) and value > 0

        if not positive(self.tool_diameter):
            raise TurnMillError(f"the tool radius must be > 0, got a tool diameter of {self.tool_diameter!r}")
        for name in ("tolerance", "roughing_step", "sample_spacing", "clearance", "feed", "plunge_feed",
                     "spindle_rpm", "rapid_rate"):
            if not positive(getattr(self, name)):
                raise TurnMillError(f"{name.replace('_', ' ')} must be a number > 0, got {getattr(self, name)!r}")
        if self.tolerance >= self.radius:
            raise TurnMillError(f"tolerance {self.tolerance:g} must be smaller than the tool radius {self.radius:g}")
        if self.stepover is not None and not (positive(self.stepover) and self.stepover <= self.tool_diameter):
            raise TurnMillError(f"stepover must be > 0 and at most the tool diameter, got {self.stepover!r}")
        if self.block_ms is not None and not positive(self.block_ms):
            raise TurnMillError(f"block time must be a number > 0 (ms), got {self.block_ms!r}")
        if self.radial_station == self.axial_station:
            raise TurnMillError("the radial and axial tools need different turret stations")
        for direction in DIRECTIONS:
            try:
                self.tool(direction)
            except ValueError as error:
                raise TurnMillError(str(error)) from None

    @property
    def radius(self) -> float:
        return self.tool_diameter / 2

    @property
    def pick_feed(self) -> float:
        """The stepover: given, or the one whose ball scallop is exactly the tolerance."""
        if self.stepover is not None:
            return float(self.stepover)
        r, h = self.radius, self.tolerance
        return 2.0 * math.sqrt(2.0 * r * h - h * h)

    @property
    def shortest_block_minutes(self) -> float:
        """Cutting moves shorter than this are merged where the path stays within tolerance: the
        control's block time (``block_ms``), never less than the timing floor of every G93 F word."""
        given = 0.0 if self.block_ms is None else self.block_ms / 60000.0
        return max(given, kinematics.SHORTEST_BLOCK_MINUTES)

    @property
    def max_turn(self) -> float:
        """Largest normal turn (radians) between ball centres whose chord stays within the tolerance."""
        return 2.0 * math.acos(1.0 - self.tolerance / self.radius)

    def tool(self, direction: str) -> Tool:
        station = self.radial_station if direction == "radial" else self.axial_station
        return Tool(station, "ball", float(self.tool_diameter), name=direction)


def _face_ids(face_ids, face_count: int) -> np.ndarray:
    ids = np.unique(np.asarray(face_ids, dtype=np.int64).reshape(-1))
    if len(ids) and (ids[0] < 0 or ids[-1] >= face_count):
        raise TurnMillError(f"face indices must lie in 0..{face_count - 1}")
    return ids


# ----- ball centres -----------------------------------------------------------------------------
def _dedupe(points: np.ndarray, *others: np.ndarray):
    keep = np.r_[True, np.linalg.norm(np.diff(points, axis=0), axis=1) > 1e-9]
    return (points[keep],) + tuple(o[keep] for o in others) if others else points[keep]


def _densify(points: np.ndarray, spacing: float, normals: np.ndarray):
    """Points at most ``spacing`` apart along the polyline (normals interpolated)."""
    counts = np.maximum(1, np.ceil(np.linalg.norm(np.diff(points, axis=0), axis=1) / spacing)).astype(int)
    return subdivide(points, counts, normals)


def densify_polar(points: np.ndarray, tolerance: float) -> np.ndarray:
    """Split part-space segments so that linear X-C interpolation between the points bends away
    from the straight segment by at most ``tolerance`` (:func:`kinematics.polar_split_counts`)."""
    if len(points) < 2:
        return points
    return subdivide(points, kinematics.polar_split_counts(points, tolerance))


def _clear_ball(surface: Triangles, centres: np.ndarray, r: float, allowance: float):
    """Push ball centres straight away from their nearest surface point until no surface is closer
    than r.  This is how centres slide into a corner or stop at a wall.  Returns the centres and
    whether each is clear (nothing closer than r - allowance)."""
    centres = centres.copy()
    gap = np.full(len(centres), np.inf)         # distance to the surface where it is below r
    active = np.arange(len(centres))
    for _ in range(PUSH_ITERATIONS):
        distance, closest = surface.nearest(centres[active], r)
        gap[active] = distance
        close = (distance < r - 1e-7) & (distance > 1e-12)
        if not close.any():
            break
        active, closest, distance = active[close], closest[close], distance[close]
        centres[active] = closest + (centres[active] - closest) * (r / distance)[:, None]
    else:
        gap[active], _ = surface.nearest(centres[active], r)
    return centres, gap >= r - allowance


def _run_indices(keep: np.ndarray, closed: bool) -> list:
    """Index arrays of the runs of kept points; on a closed polyline (last point = first) a run
    through the seam is one run."""
    idx = np.flatnonzero(keep)
    if not len(idx):
        return []
    runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
    if closed and len(runs) > 1 and keep[0] and keep[-1]:
        runs = runs[1:-1] + [np.concatenate([runs[-1], runs[0][1:]])]
    return runs


def _fit_runs(polylines: list, closed: list, surface, stock, settings, max_z_shift: list | None = None) -> list:
    """For each polyline of ball centres, the runs that cut stock (penetrate it by more than the
    tolerance) and sit clear of the part after pushing.  Centres of polyline i pushed in Z by
    ``max_z_shift[i]`` or more are dropped.  All polylines are pushed in one batch."""
    r, tol = settings.radius, settings.tolerance
    points = np.vstack(polylines)
    limits = [np.inf] * len(polylines) if max_z_shift is None else max_z_shift
    shift_limit = np.repeat(limits, [len(p) for p in polylines])
    touching = np.flatnonzero(stock.distance(points) < r - tol)
    fitted = points.copy()
    fitted[touching], clear = _clear_ball(surface, points[touching], r, tol / 10)
    keep = np.zeros(len(points), dtype=bool)
    keep[touching] = (clear & (stock.distance(fitted[touching]) < r - tol)
                      & (np.abs(fitted[touching, 2] - points[touching, 2]) < shift_limit[touching]))
    runs, start = [], 0
    for polyline, is_closed in zip(polylines, closed):
        part = slice(start, start + len(polyline))
        runs.append([_dedupe(fitted[part][run]) for run in _run_indices(keep[part], is_closed)])
        start += len(polyline)
    # no two centres of a run more than a stepover apart, so no segment cuts a convex edge's corner
    pieces = iter(short_segments([run for group in runs for run in group], settings.pick_feed, PUSH_ITERATIONS,
                                  lambda centres: _clear_ball(surface, centres, r, tol / 10)))
    return [[piece for _ in group for piece in next(pieces)] for group in runs]


# ----- radial paths ---------------------------------------------------------------------------
def _sections(v, faces, normals, zlo, zhi, z) -> list:
    """Polylines where the plane at height z cuts the faces: (points, segment normals, closed).
    A triangle's segment runs from the edge that crosses the plane going down to the one going up.
    With outward normals that is counter-clockwise about +Z.  Segments are chained through shared
    mesh edges, so neighbouring faces meet exactly."""
    cut = np.flatnonzero((zlo <= z) & (zhi > z))
    if not len(cut):
        return []
    fv = faces[cut]
    above = v[fv, 2] > z
    after = np.roll(above, -1, axis=1)
    rows = np.arange(len(cut))

    def crossing(edge):
        i, j = fv[rows, edge], fv[rows, (edge + 1) % 3]
        lo, hi = np.minimum(i, j), np.maximum(i, j)
        t = (z - v[lo, 2]) / (v[hi, 2] - v[lo, 2])
        return v[lo] + t[:, None] * (v[hi] - v[lo]), lo * len(v) + hi

    start, start_key = crossing(np.argmax(above & ~after, axis=1))
    end, end_key = crossing(np.argmax(~above & after, axis=1))
    # successor[i]: the segment starting where segment i ends (the last such, as a dict would keep)
    order = np.argsort(start_key, kind="stable")
    place = np.searchsorted(start_key[order], end_key, side="right") - 1
    found = (place >= 0) & (start_key[order[np.maximum(place, 0)]] == end_key)
    successor = np.where(found, order[np.maximum(place, 0)], -1).tolist()
    seeds = np.flatnonzero(~np.isin(start_key, end_key)).tolist() + list(range(len(cut)))
    used = bytearray(len(cut))
    chains = []
    for seed in seeds:
        if used[seed]:
            continue
        chain = [seed]
        used[seed] = 1
        while (nxt := successor[chain[-1]]) >= 0 and not used[nxt]:
            chain.append(nxt)
            used[nxt] = 1
        closed = end_key[chain[-1]] == start_key[chain[0]]
        chains.append((np.vstack([start[chain[0]], end[chain]]), normals[cut[chain]], closed))
    return chains


def _arc_normals(n1: np.ndarray, n2: np.ndarray, max_turn: float) -> np.ndarray:
    """Normals strictly between n1 and n2 (great-circle steps of at most max_turn)."""
    angle = math.acos(min(1.0, max(-1.0, float(n1 @ n2))))
    steps = math.ceil(angle / max_turn)
    if steps <= 1 or math.sin(angle) < 1e-9:
        return np.empty((0, 3))
    t = np.arange(1, steps)[:, None] / steps
    return (np.sin((1 - t) * angle) * n1 + np.sin(t * angle) * n2) / math.sin(angle)


def _offset_section(points, normals, closed, r, max_turn):
    """Ball centres along a section: each segment offset by r along its face normal (segments
    of one plane merged).  Where the normal turns by more than max_turn, the ball rolls around the
    joint on arc points.  At concave joints those points are pushed clear later."""
    straight = np.einsum("ij,ij->i", normals[:-1], normals[1:]) >= 1 - 1e-12
    points, normals = points[np.r_[True, ~straight, True]], normals[np.r_[True, ~straight]]
    ends = np.stack([points[:-1] + r * normals, points[1:] + r * normals], axis=1).reshape(-1, 3)
    end_normals = np.repeat(normals, 2, axis=0)
    following = np.roll(normals, -1, axis=0)
    turns = np.arccos(np.clip(np.einsum("ij,ij->i", normals, following), -1.0, 1.0))
    if not closed:
        turns[-1] = 0.0
    centres, centre_normals, begin = [], [], 0
    for i in np.flatnonzero(turns > max_turn):
        arc = _arc_normals(normals[i], following[i], max_turn)
        centres += [ends[begin:2 * i + 2], points[i + 1] + r * arc]
        centre_normals += [end_normals[begin:2 * i + 2], arc]
        begin = 2 * i + 2
    centres.append(ends[begin:])
    centre_normals.append(end_normals[begin:])
    if closed:
        centres.append(ends[:1])
        centre_normals.append(end_normals[:1])
    return _dedupe(np.vstack(centres), np.vstack(centre_normals))


def radial_layers(vertices, faces, face_ids, stock: Stock, settings: TurnMillSettings, progress=None,
                  surface: Triangles | None = None) -> list:
    """Ball-centre passes (part coordinates, (k, 3) arrays) for the radial tool, one list per
    layer: the outermost roughing layer first, the finishing layer (on the surface) last.

    The finishing slices are at most ``pick_feed`` apart in Z.  A section point's ball centre is
    the point plus r times its face's normal.  This is the full 3-D normal, so a sloped face is
    not gouged; on a vertical face it is the paper's normal projected onto XY.

    Each roughing layer is the finishing layer moved out by ``roughing_step`` along the
    XY-projected normal.  It uses every n-th slice, about ``roughing_step`` apart (a 3 mm ball
    1 mm apart leaves 0.04 mm).  Layers stop where they no longer reach the stock.

    Near a shoulder, centres are pushed off their slice.  Those pushed in Z by a slice spacing or
    more are dropped: they belong to the slice nearest the shoulder, which is always within a
    spacing.  So each shoulder gets one pass at exactly the right height.

    ``surface``: the part's :class:`Triangles` when the caller has them (:func:`plan` builds them
    once for every stage); None builds them here.
    """
    v, f = check_mesh(vertices, faces)
    ids = _face_ids(face_ids, len(f))
    if not len(ids):
        return []
    r, tol, step = settings.radius, settings.tolerance, settings.roughing_step
    sub = f[ids]
    normals, _ = face_normals(v[sub])
    zlo, zhi = v[sub, 2].min(axis=1), v[sub, 2].max(axis=1)
    count = max(1, math.ceil((zhi.max() - zlo.min()) / settings.pick_feed - 1e-9))
    spacing = (zhi.max() - zlo.min()) / count
    levels = zlo.min() + (np.arange(count) + 0.5) * spacing
    every = max(1, round(step / spacing))
    max_layers = math.ceil(2 * (stock.radius + r) / step) + 1
    layer_of, polylines, closed_flags, shifts, total = [], [], [], [], [0, 0]
    for number, z in enumerate(levels[::-1]):
        for points, seg_normals, closed in _sections(v, sub, normals, zlo, zhi, z):
            centres, centre_normals = _offset_section(points, seg_normals, closed, r, settings.max_turn)
            if len(centres) < 2:
                continue
            centres, centre_normals = _densify(centres, settings.pick_feed, centre_normals)
            outward = np.zeros_like(centres)
            outward[:, :2] = centre_normals[:, :2]
            outward /= np.maximum(np.linalg.norm(outward, axis=1), 1e-12)[:, None]
            for k in range(1 if number % every else max_layers):
                layer = centres + k * step * outward
                if not np.any(stock.distance(layer) < r - tol):
                    break
                count_positions(total, len(layer), "radial", k, step, stock, v)
                layer_of.append(k)
                polylines.append(layer)
                closed_flags.append(closed)
                shifts.append((1 if k == 0 else every) * spacing - 1e-9)
    if not polylines:
        return []
    surface = Triangles(v[f]) if surface is None else surface
    layers: dict = {}
    for k, runs in zip(layer_of, _fit_runs(polylines, closed_flags, surface, stock, settings, shifts)):
        layers.setdefault(k, []).extend(runs)
    return join_layers(layers, surface, settings, progress)


# ----- axial paths ----------------------------------------------------------------------------
def _components(faces: np.ndarray, ids: np.ndarray) -> list:
    """Groups of the given faces connected through shared edges (each a feature such as a pocket floor)."""
    edges = np.sort(faces[ids][:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    keys = edges[:, 0] * (faces.max() + 1) + edges[:, 1]
    owner = np.repeat(np.arange(len(ids)), 3)
    order = np.argsort(keys, kind="stable")
    same = keys[order][1:] == keys[order][:-1]
    parent = list(range(len(ids)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b in zip(owner[order][:-1][same].tolist(), owner[order][1:][same].tolist()):
        parent[root(a)] = root(b)
    groups: dict = {}
    for i in range(len(ids)):
        groups.setdefault(root(i), []).append(i)
    return [ids[np.array(g)] for g in sorted(groups.values(), key=lambda g: g[0])]


def _project_down(xy: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Height and face of the highest triangle above/below each XY point (NaN, -1 where none).
    Each point is tested only against the triangles filed in its cell of a :class:`BoxGrid`
    (ties: the lowest face)."""
    z = np.full(len(xy), np.nan)
    face = np.full(len(xy), -1)
    if not len(xy) or not len(triangles):
        return z, face
    flat = triangles[:, :, :2]
    lo, hi = flat.min(axis=1), flat.max(axis=1)
    grid = BoxGrid(lo - 1e-9, hi + 1e-9)
    start, stop = grid.listed(grid.cells_of(xy))
    count = stop - start
    ends = np.cumsum(count)
    begin = 0
    while begin < len(xy):
        # as many points as keep the (point, triangle) pairs within the budget
        end = max(begin + 1, int(np.searchsorted(ends, (ends[begin - 1] if begin else 0) + PAIR_BUDGET,
                                                 side="right")))
        c = count[begin:end]
        query = np.repeat(np.arange(begin, end), c)
        take = np.repeat(start[begin:end] - np.cumsum(c) + c, c) + np.arange(int(c.sum()))
        tri = grid.boxes[take]
        keep = np.all((xy[query] >= lo[tri] - 1e-9) & (xy[query] <= hi[tri] + 1e-9), axis=1)
        query, tri = query[keep], tri[keep]
        a, b, c3 = triangles[tri, 0], triangles[tri, 1], triangles[tri, 2]
        e1, e2, p = b[:, :2] - a[:, :2], c3[:, :2] - a[:, :2], xy[query] - a[:, :2]
        det = e1[:, 0] * e2[:, 1] - e2[:, 0] * e1[:, 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            l1 = (p[:, 0] * e2[:, 1] - e2[:, 0] * p[:, 1]) / det
            l2 = (e1[:, 0] * p[:, 1] - p[:, 0] * e1[:, 1]) / det
        inside = (np.abs(det) > 1e-12) & (l1 >= -1e-9) & (l2 >= -1e-9) & (l1 + l2 <= 1 + 1e-9)
        query, tri, height = query[inside], tri[inside], (a[:, 2] + l1 * (b[:, 2] - a[:, 2])
                                                          + l2 * (c3[:, 2] - a[:, 2]))[inside]
        order = np.lexsort((tri, -height, query))
        first = order[np.r_[True, query[order][1:] != query[order][:-1]]] if len(order) else order
        z[query[first]] = height[first]
        face[query[first]] = tri[first]
        begin = end
    return z, face


def chain_cells(occupied: np.ndarray) -> list:
    """Chain the occupied cells of a grid (axis 0 = outward, axis 1 = counter-clockwise) into
    paths.  From the start cell (the most clockwise, then innermost), each step takes the first
    free neighbour in the order outward, counter-clockwise, inward, clockwise.  When none is free
    the path ends, and the next starts at the nearest free cell.  Returns lists of (i, j)."""
    free = np.array(occupied, dtype=bool)
    cells = np.argwhere(free)
    if not len(cells):
        return []
    current = tuple(int(x) for x in cells[np.lexsort((cells[:, 0], cells[:, 1]))[0]])
    paths = []
    while True:
        path = [current]
        free[current] = False
        while True:
            for di, dj in NEIGHBOUR_ORDER:
                i, j = current[0] + di, current[1] + dj
                if 0 <= i < free.shape[0] and 0 <= j < free.shape[1] and free[i, j]:
                    break
            else:
                break
            current = (i, j)
            free[current] = False
            path.append(current)
        paths.append(path)
        remaining = np.argwhere(free)
        if not len(remaining):
            return paths
        nearest = np.argmin(((remaining - np.array(current)) ** 2).sum(axis=1))
        current = tuple(int(x) for x in remaining[nearest])


def _grid_passes(v, faces, surface, stock, settings) -> list:
    """The finishing passes of one axial feature: grid points on its faces, pushed clear, chained."""
    r, tol = settings.radius, settings.tolerance
    triangles = v[faces]
    normals, areas = face_normals(triangles)
    centroid = (triangles.mean(axis=1)[:, :2] * areas[:, None]).sum(axis=0) / max(areas.sum(), 1e-300)
    length = float(np.hypot(*centroid))
    outward = centroid / length if length > 1e-6 else np.array([1.0, 0.0])
    ccw = np.array([-outward[1], outward[0]])
    xy = triangles[:, :, :2].reshape(-1, 2)
    s, w = xy @ outward, xy @ ccw
    h = settings.pick_feed
    ns = max(1, math.ceil((s.max() - s.min()) / h - 1e-9))
    nw = max(1, math.ceil((w.max() - w.min()) / h - 1e-9))
    si = s.min() + (np.arange(ns) + 0.5) * (s.max() - s.min()) / ns
    wj = w.min() + (np.arange(nw) + 0.5) * (w.max() - w.min()) / nw
    nodes = (si[:, None, None] * outward + wj[None, :, None] * ccw).reshape(-1, 2)
    z, face = _project_down(nodes, triangles)
    found = np.flatnonzero(~np.isnan(z))
    centres = np.full((len(nodes), 3), np.nan)
    centres[found] = np.column_stack([nodes[found], z[found]]) + r * normals[face[found]]
    occupied = np.zeros(len(nodes), dtype=bool)
    touching = found[stock.distance(centres[found]) < r - tol]
    if len(touching):
        centres[touching], clear = _clear_ball(surface, centres[touching], r, tol / 10)
        occupied[touching] = clear & (stock.distance(centres[touching]) < r - tol)
    grid = centres.reshape(ns, nw, 3)
    paths = [_dedupe(np.array([grid[c] for c in path])) for path in chain_cells(occupied.reshape(ns, nw))]
    # cells a stepover apart across lie further apart along a slope: chords cut convex edges (a sphere's)
    pieces = short_segments(paths, settings.pick_feed, PUSH_ITERATIONS,
                             lambda points: _clear_ball(surface, points, r, tol / 10))
    return [piece for group in pieces for piece in group]


def axial_layers(vertices, faces, face_ids, stock: Stock, settings: TurnMillSettings, progress=None,
                 surface: Triangles | None = None) -> list:
    """Ball-centre passes for the axial tool, one list per layer: the highest roughing copy first,
    the finishing layer (on the faces) last.

    Each connected group of faces (a feature) gets its own grid.  The grid is aligned with the
    feature's direction from the axis, so "outward" is a grid axis.  The finishing passes are
    copied up by ``roughing_step`` at a time until no copy reaches the stock (the paper: until
    the path's lowest Z clears the tool radius above the end face).  Copies are pushed clear like
    the finishing passes, so the walls above a floor are respected.  ``surface``: as for
    :func:`radial_layers`."""
    v, f = check_mesh(vertices, faces)
    ids = _face_ids(face_ids, len(f))
    if not len(ids):
        return []
    surface = Triangles(v[f]) if surface is None else surface
    r, tol = settings.radius, settings.tolerance
    finishing = [p for group in _components(f, ids) for p in _grid_passes(v, f[group], surface, stock, settings)]
    if not finishing:
        return []
    layer_of, copies, total = [], [], [0, 0]
    for k in itertools.count(1):
        lifted = [p + np.array([0.0, 0.0, k * settings.roughing_step]) for p in finishing]
        touching = [c for c in lifted if np.any(stock.distance(c) < r - tol)]
        if not touching:
            break
        count_positions(total, sum(len(c) for c in touching), "axial", k, settings.roughing_step, stock, v)
        layer_of += [k] * len(touching)
        copies += touching
    layers: dict = {0: finishing}
    if copies:
        for k, runs in zip(layer_of, _fit_runs(copies, [False] * len(copies), surface, stock, settings)):
            layers.setdefault(k, []).extend(runs)
    return join_layers(layers, surface, settings, progress)


# ----- machine coordinates and operations ------------------------------------------------------
def _machine(centres: np.ndarray, direction: str, r: float):
    """Tool-tip machine X, Z and the part angle (radians) for ball centres.  On the axis, where
    the angle is undefined, the previous angle is kept (:func:`kinematics.polar`)."""
    rho, angle = kinematics.polar(centres)
    if direction == "radial":
        return rho - r, centres[:, 2], angle
    return rho, centres[:, 2] - r, angle


def _operation(name, direction, layers, stock, settings, surface=None) -> TurnMillOperation | None:
    """Moves through the passes, layer by layer.  Between passes the tool retracts along its own
    axis to the clearance outside the stock, turns C there, and feeds back in."""
    passes = [p for layer in layers for p in layer]
    if not passes:
        return None
    r = settings.radius
    x_clear = stock.radius + settings.clearance
    z_clear = stock.z_max + settings.clearance
    kind, x, z, angle, feed = [], [], [], [], []

    def add(k, xs, zs, angles, f):
        n = len(np.atleast_1d(xs))
        if not n:
            return
        kind.append(np.full(n, k))
        x.append(np.atleast_1d(xs))
        z.append(np.atleast_1d(zs))
        angle.append(np.atleast_1d(angles))
        feed.append(np.full(n, f))

    for centres in passes:
        px, pz, pa = _machine(densify_polar(centres, settings.tolerance), direction, r)
        if direction == "radial":
            if kind:
                add(RAPID, x_clear, z[-1][-1], angle[-1][-1], np.nan)
            add(RAPID, x_clear, pz[0], pa[0], np.nan)
        else:
            if kind:
                add(RAPID, x[-1][-1], z_clear, angle[-1][-1], np.nan)
            add(RAPID, px[0], z_clear, pa[0], np.nan)
        add(FEED, px[0], pz[0], pa[0], settings.plunge_feed)
        add(FEED, px[1:], pz[1:], pa[1:], settings.feed)
    if direction == "radial":
        add(RAPID, x_clear, z[-1][-1], angle[-1][-1], np.nan)
    else:
        add(RAPID, x[-1][-1], z_clear, angle[-1][-1], np.nan)
    xs = np.concatenate(x)
    xyz = np.column_stack([xs, np.zeros(len(xs)), np.concatenate(z)])
    c = np.degrees(np.unwrap(np.concatenate(angle)))
    op = TurnMillOperation(name, settings.tool(direction), settings.spindle_rpm, np.concatenate(kind), xyz,
                           np.concatenate(feed), rotary={"c": c}, clearance_z=z_clear, safe_z=z_clear,
                           start=np.array([x_clear, 0.0, z_clear]), direction=direction)
    # no dip deeper than a chord's; then blocks shorter than the control processes in time merge within the
    # chordal tolerance where the ball stays clear of the part along the merged move
    dip = min(settings.tolerance, CHORD_DIP)
    if surface is None:
        return merge_short_moves(op, dip, settings.shortest_block_minutes)
    return merge_short_moves(op, settings.tolerance, settings.shortest_block_minutes,
                             accept=merged_move_clear(direction, surface, settings), accept_above=dip)


@dataclass
class TurnMillPlan:
    """The result of :func:`plan`.  It holds the program and the face labels (for the viewport
    colours).  It also holds which faces each tool machines, and the ball-centre layers in part
    coordinates (for the preview).  Each list of layers runs roughing first, finishing last."""

    program: Program
    labels: np.ndarray
    radial_faces: np.ndarray
    axial_faces: np.ndarray
    radial_layers: list
    axial_layers: list
    skipped: list = field(default_factory=list)    # turnskip.SkippedFeature s: faces no tool reaches

    def skipped_faces(self) -> np.ndarray:
        """Ids of the input faces no tool reaches (sorted)."""
        return np.sort(np.concatenate([f.faces for f in self.skipped])) if self.skipped else np.zeros(0, np.int64)


def plan(vertices, faces, stock: Stock, settings: TurnMillSettings | None = None, engine: RayEngine | None = None,
         labels=None, name: str = "turn-mill", progress=None, reported=None) -> TurnMillPlan:
    """Classify the faces (or use ``labels``), generate the radial and axial layers, and build the
    program: radial roughing, radial finishing (radial station), axial roughing, axial finishing
    (axial station).  Operations with nothing to cut are left out.
    ``progress``: optional callable(fraction, text); while the passes are joined, returning False
    cancels (:class:`TurnMillCancelled`).  Faces labelled NEITHER that no ball sweeps either are
    named (:attr:`TurnMillPlan.skipped`, in the program's notes): among ``reported`` (a face mask;
    default every face), so faces a user left out of a selection are not reported as skipped."""
    report = progress or (lambda fraction, text="": None)
    settings = TurnMillSettings() if settings is None else settings
    if not isinstance(stock, Stock):
        raise TurnMillError(f"stock must be a Stock, got {type(stock).__name__}")
    checked = checked_mesh(vertices, faces)
    v, f = checked.vertices, checked.faces
    given_v, given_f = v, f
    outside = (np.hypot(v[:, 0], v[:, 1]) > stock.radius + settings.tolerance) | \
              (v[:, 2] < stock.z_min - settings.tolerance) | (v[:, 2] > stock.z_max + settings.tolerance)
    if outside.any():
        raise TurnMillError(f"the part does not fit in the stock: {int(outside.sum())} vertices lie outside the "
                            f"{2 * stock.radius:g} mm bar from z = {stock.z_min:g} to {stock.z_max:g}")
    if labels is not None:
        labels = np.asarray(labels)
        if labels.shape != (len(f),) or not np.all(np.isin(labels, (NEITHER, RADIAL, AXIAL, BOTH))):
            raise TurnMillError(f"labels must be {len(f)} values from NEITHER, RADIAL, AXIAL, BOTH")
    # plan on the planning mesh: coplanar faces split into many merged back (the same surface)
    planning = planning_mesh(v, f, labels, checked.reverse, checked.normals)
    face_count = len(f)
    if planning.merged:
        v, f = check_mesh(planning.vertices, planning.faces)
    if labels is None:
        labels = classify_faces(v, f, engine, settings.sample_spacing,
                                lambda fraction, text="": report(0.5 * fraction, text))
    else:
        labels = labels[planning.source]
    radial_ids, axial_ids = path_faces(v, f, labels)
    surface = Triangles(v[f])            # one nearest-point structure for every stage below
    report(0.5, "radial layers")
    radial = radial_layers(v, f, radial_ids, stock, settings,
                           lambda fraction: report(0.5 + 0.3 * fraction, "radial layers"), surface)
    report(0.8, "axial layers")
    axial = axial_layers(v, f, axial_ids, stock, settings,
                         lambda fraction: report(0.8 + 0.15 * fraction, "axial layers"), surface)
    report(0.95, "operations")
    operations = []
    for direction, layers in (("radial", radial), ("axial", axial)):
        for label, part in (("roughing", layers[:-1]), ("finishing", layers[-1:])):
            op = _operation(f"{direction} {label}", direction, part, stock, settings, surface)
            if op is not None:
                operations.append(op)
    if not operations:
        raise TurnMillError("nothing to machine: no radially or axially reachable face lies inside the stock")
    # Each operation starts at the turn of C nearest to where the last one ended, so the table
    # never unwinds whole turns between operations.
    for previous, op in zip(operations, operations[1:]):
        c = op.rotary["c"]
        c += 360.0 * np.round((previous.rotary["c"][-1] - c[0]) / 360.0)
    skipped = _skipped(v, f, labels, planning, given_v, given_f, stock, settings, radial + axial, reported)
    notes = [f"tolerance {settings.tolerance:g} mm, stepover {settings.pick_feed:.3f} mm, "
             f"roughing step {settings.roughing_step:g} mm"] + turnskip.notes(skipped)
    program = Program(name, operations, rapid_rate=settings.rapid_rate, notes=notes)
    return TurnMillPlan(program, np.asarray(labels, dtype=np.int8)[planning.group],
                        _mapped(radial_ids, planning, face_count), _mapped(axial_ids, planning, face_count), radial, axial,
                        skipped)


def _skipped(v, f, labels, planning, given_v, given_f, stock, settings, layers, reported) -> list:
    """The NEITHER faces no ball centre comes near (:mod:`.turnskip`), tested on the planning mesh
    and named as input faces, grouped into features."""
    candidates = np.flatnonzero((np.asarray(labels) == NEITHER)
                                & ~turnskip.on_stock_surface(v, f, stock, settings.tolerance))
    centres = [p for layer in layers for p in layer]
    centres = np.vstack(centres) if centres else np.zeros((0, 3))
    distance = turnskip.reach(settings.radius, settings.roughing_step, settings.pick_feed, settings.tolerance)
    missed = np.zeros(len(f), bool)
    missed[turnskip.unreached_faces(v, f, candidates, centres, distance, settings.sample_spacing)] = True
    chosen = missed[planning.group] if planning.merged else missed
    if reported is not None:
        chosen &= np.asarray(reported, bool)
    return turnskip.features(given_v, given_f, np.flatnonzero(chosen))


def _mapped(ids: np.ndarray, planning, face_count: int) -> np.ndarray:
    """Planning-mesh face ids as the input faces of the same facets."""
    if not planning.merged:
        return ids
    chosen = np.zeros(face_count, bool)
    chosen[ids] = True
    return np.flatnonzero(chosen[planning.group])


# ----- the built-in sample ---------------------------------------------------------------------
SAMPLE_SLOT_X = (10.0, 30.0)     # the axial pocket spans x 10..30: the paper's 20 mm check


def sample_part(segments: int = 192) -> tuple[np.ndarray, np.ndarray, Stock]:
    """The demo part: a 85 mm bar, 60 mm long, end face at z = 0, chuck side at z = -60.

    The paper's Fig. 8 is not in the seed, so this part is our own, with the same features.
    Radial features: a flat at x = 35 from z = -45 to -30 (with shoulders), and a groove 8 mm
    wide with floor radius 36 from z = -20 to -12.  Axial features on the end face: a pocket
    x 10..30, y -15..15, 6 mm deep (exactly 20 mm wide radially), and a 16 mm round pocket,
    4 mm deep, at (-20, 0).  192 segments keep the facets within 0.006 mm of the true bar.
    Returns (vertices, faces, stock).
    """
    from manifold3d import Manifold

    stock = Stock(radius=42.5, z_min=-60.0, z_max=0.0)
    bar = Manifold.cylinder(60.0, 42.5, 42.5, segments).translate((0.0, 0.0, -60.0))
    flat = Manifold.cube((20.0, 120.0, 15.0)).translate((35.0, -60.0, -45.0))
    groove = (Manifold.cylinder(8.0, 50.0, 50.0, segments)
              - Manifold.cylinder(10.0, 36.0, 36.0, segments).translate((0.0, 0.0, -1.0))).translate((0.0, 0.0, -20.0))
    slot = Manifold.cube((20.0, 30.0, 7.0)).translate((10.0, -15.0, -6.0))
    round_pocket = Manifold.cylinder(5.0, 8.0, 8.0, segments // 3).translate((-20.0, 0.0, -4.0))
    mesh = (bar - flat - groove - slot - round_pocket).to_mesh64()
    return (np.array(mesh.vert_properties[:, :3], dtype=float), np.array(mesh.tri_verts, dtype=np.int64), stock)
