"""W2: non-circular pockets on a rotating table, C-X-Z (seed 001, Hashimoto).

A CNC wood lathe holds a board on its face plate.  The board turns about the C axis; a
ball-nose "pencil" bit (diameter D, flute length L) moves in X (distance from the rotation
centre, on the negative side only: X = -R) and in Z (into the board).

Frames and conventions
----------------------
* Part frame: workpiece XY in mm with the origin on the rotation axis; the board top is
  Z = 0 and Z is negative into the board.  Pocket outlines are given in this frame.
* The geometry is computed for the **ball centre** (offsets of walls, floors and spheres
  are exact there); everything handed out (the IR, the chains of :class:`PocketPath`,
  the NC) is the **tool tip** = ball centre - D/2 in Z, as :mod:`program` defines Z.
* Machine frame: ``X = -R`` (R = distance from the axis), ``C`` in degrees, Z as in the
  part frame.  C is the angle of the part point measured counter-clockwise (seen from +Z,
  the tool side) from the part's -X axis, so ``(-R, 0)`` has C = 0.  To bring that point
  under the tool the table turns by -C: **+C turns the table clockwise seen from the
  tool**, i.e. the tool moves counter-clockwise relative to the part (the ISO 841 sense of
  +C for the tool).  C is unwrapped (continuous, may exceed 360) so the table never swings
  back through a turn between neighbouring points.
* The machine interpolates X, C and Z linearly, which traces a spiral piece in the part
  frame, not the straight chord.  Cutting moves are split until that spiral stays within
  ``tolerance`` of the chord; the true part-frame length of each move (what the bit
  travels over the wood) sets its inverse-time feed.

Toolpath per pocket (the paper's sequence), computed as if the pocket's centre were on
the rotation axis, then translated to its real centre and converted to C-X-Z:

1. Roughing: depth layers no deeper than ``step_down``; in each, concentric circles about
   the pocket centre, radius growing by ``rough_stepover`` (the bit radius by default);
   where a circle would leave the tool-centre region (walls/floor + ``allowance``) it
   follows that region's outline instead, then rejoins the circle.
2. Wall finishing: waterline contours at a fine pitch (``wall_stepover``, measured along a
   slanted wall).  A slanted wall is the outline offset inward by depth * tan(angle); the
   ball centre that touches it at height z lies on the outline offset by
   ``r / cos(a) - z tan(a)`` (exact for a ball in a tapered pocket, cones included).
3. Bottom: a flat floor gets one Archimedean spiral (pitch = ``stepover``) from the centre,
   clipped to the floor's tool-centre region and joined along its outline.  A spherical
   bowl gets a spiral on the sphere: the ball centre runs on the sphere of radius
   ``R_s - r`` and climbs ``stepover`` **measured along the design surface** per turn
   (the paper's helix pitch P), so the scallop is the same on steep and flat parts.
   Points are ``spacing`` (the paper's alpha) apart along circles and spirals, and at
   most ``spacing`` apart along outlines (outline vertices are kept so corners are not cut).

Finishing passes stand ``tolerance + region.ARC_TOLERANCE`` off the walls and a bowl, so the
polygonal approximation of round offsets and the machine's rotary interpolation never
gouge: those surfaces are left at most that much proud (plus the scallops).  A flat floor
is cut at its depth exactly: the floor spiral keeps Z constant, and both those errors are in
plan, so it keeps the stand-off from the walls only.  :func:`max_gouge` checks it against
the analytic pocket: from ball positions along the interpolated machine motion it bounds the
penetration in between, probing more positions only where that bound is not tight.

The spherical bowl: its lowest point is at the pocket centre, ``depth`` below the top; the
sphere radius must reach the whole outline at or below the top, R_s >= (a^2 + d^2) / 2d
with a the farthest outline point.  A plane cuts a sphere in a circle, so a non-circular
outline leaves a vertical rim where the outline cuts the sphere below the top (reported as
``rim_wall_mm``; zero for a circle of exactly that size).  Spherical bowls have vertical
rims only (wall angle 0).

Cycle time, compared with the paper: the built-in sample (:func:`sample_job`, three pockets
in a 105 mm block, 6 mm bit, P = alpha = 1 mm, 1500 mm/min on the wood, 300 mm/min plunges)
is estimated at 8 min 46 s (slanted tray 5:16, peanut 2:23, bowl 1:07); the paper machined
its three pockets in 8 min 22 s.  Its feeds and pocket sizes are not published, so this
is a sanity check of the order of magnitude, not a reproduction.
"""
from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field

import numpy as np
from manifold3d import CrossSection

from ...ir import kinematics
from ...engines import region as rg
from ...ir.kinematics import (DEFAULT_MAX_TABLE_RPM, cycle_time, from_cylindrical, inverse_time_feed, move_times, part_points, to_cylindrical, unwrap_c)
from ...ir.program import RAPID, Operation, PathBuilder, Program, merge_short_moves
from .rotary_curves import Boundary, by_arc_length, circle_points, closed_loops, densify, follow_inside, inner_point
from .rotary_pocket import (BLOCK, BOTTOMS, MAX_WALL_ANGLE, Block, Pocket, PocketGeometry, RotaryError, RotarySettings,
                            is_finite_number, row_norms, same_point, scallop_height)


@dataclass
class PocketPath:
    """One pocket's result.  Chains are part-frame tool-tip points (k, 3), in cutting order."""

    pocket: Pocket
    operation: Operation
    report: dict
    roughing: list = field(default_factory=list)      # [(tip z of the layer, chain), ...]
    wall: list = field(default_factory=list)          # [(tip z of the contour, chain), ...]
    bottom: list = field(default_factory=list)        # [chain, ...]


@dataclass
class RotaryResult:
    program: Program
    pockets: list
    reports: list
    cycle_time_s: float


# ----------------------------------------------------------------------------------------
# Machine coordinates (the conversion itself: :mod:`kinematics`)
# ----------------------------------------------------------------------------------------

def _endpoints(op: Operation):
    """(x0, c0, z0, x1, c1, z1) per move; the operation starts at its first C."""
    a, b, c0, c1 = kinematics.operation_c_moves(op)
    return a[:, 0], c0, a[:, 2], b[:, 0], c1, b[:, 2]


def move_lengths(op: Operation) -> np.ndarray:
    """Length of every move along the path it traces on the part (mm)."""
    return op.move_lengths()


def _to_machine(kind, xyz, feed, tolerance, start_c):
    """Part-frame moves (tool tip) -> machine moves: cutting moves split until the rotary
    interpolation stays within ``tolerance`` of the chord, C unwrapped.  A move is sampled
    unless its bend (:func:`kinematics.speed_and_bend`) keeps it that close anyway; after a split only
    the two halves are checked again (a split leaves every other move as it was)."""
    kind, xyz, feed = np.asarray(kind), np.asarray(xyz, float), np.asarray(feed, float)
    moved = np.ones(len(kind), bool)
    moved[1:] = np.any(np.abs(np.diff(xyz, axis=0)) > 1e-9, axis=1)
    kind, xyz, feed = kind[moved], xyz[moved], feed[moved]
    check = np.flatnonzero(kind[1:] != RAPID) + 1        # cutting moves, by the index of their end
    for _ in range(40):
        x_word, c_raw = to_cylindrical(xyz[:, :2])
        c = unwrap_c(c_raw, -x_word, start_c)
        _, bend = kinematics.speed_and_bend(x_word[check - 1], c[check - 1], x_word[check], c[check])
        check = check[bend > 8 * tolerance]
        a, b = check - 1, check
        worst = np.zeros(len(check))
        for t in (0.25, 0.5, 0.75):
            on_machine = kinematics.interpolate(x_word[a], c[a], xyz[a, 2], x_word[b], c[b], xyz[b, 2],
                                                np.full(len(a), t))
            chord = xyz[a] + (xyz[b] - xyz[a]) * t
            worst = np.maximum(worst, row_norms(on_machine - chord))
        split = check[worst > tolerance]
        if not len(split):
            return kind, np.column_stack([x_word, np.zeros(len(x_word)), xyz[:, 2]]), feed, c
        mid = (xyz[split - 1] + xyz[split]) / 2
        kind = np.insert(kind, split, kind[split])
        xyz = np.insert(xyz, split, mid, axis=0)
        feed = np.insert(feed, split, feed[split])
        inserted = split + np.arange(len(split))         # where the midpoints went
        check = np.column_stack([inserted, inserted + 1]).ravel()
    raise RotaryError("a cutting move could not be linearised for the rotary table (path through the axis?)")


# ----------------------------------------------------------------------------------------
# Passes (local frame, ball centres)
# ----------------------------------------------------------------------------------------

def _roughing(geo: PocketGeometry, settings: RotarySettings) -> list:
    """[(z, chain (k, 3)), ...]: per layer, each piece's centre, then circles out to its outline."""
    extra = settings.allowance + settings.standoff
    # The deepest layer: on a flat floor the ball keeps the standoff too, or that layer's region
    # would be empty and the floor finishing would take the whole last step at once.
    bottom_tip = geo.floor_z(extra) - geo.r if geo.bottom == "flat" else -geo.depth + settings.allowance
    layers = max(1, math.ceil(-bottom_tip / settings.step_down - 1e-9))
    passes, region, chains = [], None, []
    for k in range(1, layers + 1):
        z = bottom_tip * k / layers + geo.r
        above = region
        region = geo.region_at(z, extra)
        if region is not above:     # (geo.inset hands vertical walls over a flat floor one region)
            chains = [densify(c, settings.spacing) for c in _layer(region, settings)]
        passes += [(z, _lift(c, z)) for c in chains]
    return passes


def _layer(region: CrossSection, settings: RotarySettings) -> list:
    """One roughing layer in plan: per piece of the region its centre, then circles out to its
    outline, then the outline."""
    chains = []
    for piece in rg.components(region):
        centre = inner_point(piece)
        boundary = Boundary(piece.translate(tuple(-centre)))
        chains.append(centre[None, :])
        radius = settings.roughing_stepover
        while radius < boundary.far:
            circle = circle_points(radius, settings.spacing)
            # Nearer the (inner) centre than the outline is, the circle is inside as a whole.
            inside = [circle] if radius < boundary.near else follow_inside(circle, boundary, True)
            chains += [c + centre for c in inside]
            radius += settings.roughing_stepover
        chains += closed_loops(piece)
    return chains


def _lift(chain: np.ndarray, z) -> np.ndarray:
    return np.column_stack([chain, np.broadcast_to(z, len(chain))])


def _wall_levels(geo: PocketGeometry, settings: RotarySettings) -> np.ndarray:
    step = settings.wall_stepover * math.cos(geo.theta)
    if geo.bottom == "flat":
        top, bottom = geo.r * math.sin(geo.theta), geo.floor_z(settings.standoff)
    else:
        # Down to where the ball last touches the rim: on the bowl's locus, beside the wall.
        nearest = geo.centre_to_outline - geo.r - settings.standoff
        top = 0.0
        bottom = float(geo.sphere_z(np.array([[nearest, 0.0]]), settings.standoff)[0])
        if bottom >= top:
            return np.empty(0)
    count = max(1, math.ceil((top - bottom) / step - 1e-9))
    return top - (top - bottom) * np.arange(1, count + 1) / count


def _wall_finishing(geo: PocketGeometry, settings: RotarySettings) -> list:
    passes = []
    for z in _wall_levels(geo, settings):
        for loop in closed_loops(geo.region_at(z, settings.standoff)):
            passes.append((z, _lift(densify(loop, settings.spacing), z)))
    return passes


def _floor_spiral(geo: PocketGeometry, settings: RotarySettings) -> list:
    """One Archimedean spiral per piece of the floor (the pocket centre when it is on the
    floor), pitch ``stepover``, clipped to the floor's tool-centre region.  The ball runs on
    the floor itself (no stand-off): its Z is constant, so neither the rotary interpolation
    nor the polygonal offsets (both in plan) can take it below the floor."""
    z = geo.floor_z(0.0)
    b = settings.stepover / (2 * math.pi)
    chains = []
    for piece in rg.components(geo.bottom_region()):
        centre = inner_point(piece)
        boundary = Boundary(piece.translate(tuple(-centre)))
        far = boundary.far
        turns = far / settings.stepover + 1
        phi = np.linspace(0, 2 * math.pi * turns, max(2000, math.ceil(40 * turns * far / settings.spacing)))
        spiral = by_arc_length(np.column_stack([b * phi * np.cos(phi), b * phi * np.sin(phi)]), settings.spacing)
        chains += [_lift(densify(c + centre, settings.spacing), z) for c in follow_inside(spiral, boundary, False)]
    return chains


def _bowl_spiral(geo: PocketGeometry, settings: RotarySettings) -> list:
    boundary = Boundary(geo.bottom_region())
    rho = geo.locus_radius(settings.standoff)
    far = boundary.far
    psi_end = math.asin(min(1.0, far / rho + settings.stepover / geo.sphere_radius))
    turns = psi_end * geo.sphere_radius / settings.stepover
    phi = np.linspace(0, 2 * math.pi * turns, max(2000, math.ceil(40 * turns * far / settings.spacing)))
    psi = phi / (2 * math.pi) * settings.stepover / geo.sphere_radius
    helix = np.column_stack([rho * np.sin(psi) * np.cos(phi), rho * np.sin(psi) * np.sin(phi),
                             geo.sphere_centre_z - rho * np.cos(psi)])
    helix = by_arc_length(helix, settings.spacing)
    chains = []
    for c in follow_inside(helix[:, :2], boundary, False):
        chains.append(densify(np.column_stack([c, geo.sphere_z(c, settings.standoff)]), settings.spacing))
    return chains


# ----------------------------------------------------------------------------------------
# Planning
# ----------------------------------------------------------------------------------------

def _safe_links(geo: PocketGeometry, a: np.ndarray, b: np.ndarray, margin: float) -> np.ndarray:
    """Which balls can feed straight from centre a to centre b (rows, local) and stay
    ``margin`` off the design surface all the way?"""
    def at(links, t):
        return a[links] + (b[links] - a[links]) * t[:, None]
    plan_length = row_norms((b - a)[:, :2])
    top = geo.highest(at, np.arange(len(a)), geo.probe(a), geo.probe(b), plan_length, np.zeros(len(a)), -margin)
    return top <= -margin


MAX_PATH_POINTS = 5_000_000   # a pocket's path past this runs out of memory in the C unwrapping


def _pocket_operation(geo: PocketGeometry, settings: RotarySettings, start_c):
    """Build one pocket's moves in the part frame, then convert them to C-X-Z."""
    rough = _roughing(geo, settings)
    wall = _wall_finishing(geo, settings)
    bottom = _floor_spiral(geo, settings) if geo.bottom == "flat" else _bowl_spiral(geo, settings)
    builder = PathBuilder(settings.clearance_z, settings.cutting_speed, settings.plunge_speed,
                          settings.approach_gap)
    offset = np.array([geo.centre[0], geo.centre[1], -geo.r])
    chains = [c for _, c in rough] + [c for _, c in wall] + bottom
    points = sum(len(c) for c in chains)
    if points > MAX_PATH_POINTS:    # Spacing and Step Down both 0.01 (in range): a MemoryError in unwrapping C
        raise RotaryError(f"pocket {geo.name!r}: the toolpath would have {points} points (more than "
                          f"{MAX_PATH_POINTS}) at a spacing of {settings.spacing:g} mm and a step down of "
                          f"{settings.step_down:g} mm: give a coarser spacing or step down")
    for k in range(1, len(chains)):
        chains[k] = _start_nearest(chains[k], chains[k - 1][-1])
    ends = np.array([c[-1] for c in chains[:-1]]).reshape(-1, 3)
    starts = np.array([c[0] for c in chains[1:]]).reshape(-1, 3)
    # Links keep tolerance / 2 off the walls and a bowl; over a flat floor, which the floor
    # spiral runs on exactly, they only must not go below it.
    floor_geo = geo
    if geo.bottom == "flat":
        floor_geo = copy.copy(geo)
        floor_geo.depth = geo.depth + settings.tolerance / 2 + 1e-6     # (the bound's slack)
    linked = np.concatenate([[False], _safe_links(floor_geo, ends, starts, settings.tolerance / 2)])
    for k, chain in enumerate(chains):
        if linked[k]:
            down = chain[0][2] < chains[k - 1][-1][2] - 1e-9
            builder.line(*(chain[0] + offset), feed=settings.plunge_speed if down else None)
        else:
            builder.plunge(*(chain[0] + offset))
        builder.polyline(chain[1:] + offset)
    builder.retract()
    moves = builder.arrays()
    kind, xyz, feed, c = _to_machine(moves["kind"], moves["xyz"], moves["feed"], settings.tolerance, start_c)
    op = Operation(name=geo.name, tool=settings.tool, spindle_rpm=settings.spindle_rpm, kind=kind, xyz=xyz,
                   feed=feed, rotary={"c": c}, clearance_z=settings.clearance_z, safe_z=settings.safe_z,
                   start=np.array([xyz[0, 0], 0.0, settings.safe_z]),
                   comment="C-X-Z pocket: X = -R, C degrees, tool tip Z, feeds along the part")
    op = merge_short_moves(op, settings.tolerance)     # no block shorter than a control can time

    return (op, [(z - geo.r, c + offset) for z, c in rough], [(z - geo.r, c + offset) for z, c in wall],
            [c + offset for c in bottom])


def _is_closed(chain: np.ndarray) -> bool:
    return len(chain) > 2 and same_point(chain[0], chain[-1])


def _start_nearest(chain: np.ndarray, here: np.ndarray) -> np.ndarray:
    if not _is_closed(chain):
        return chain
    index = int(np.argmin(row_norms(chain[:-1] - here)))
    return np.vstack([chain[index:-1], chain[:index + 1]])       # the closed chain from index round


def max_gouge(pocket: Pocket, op: Operation, block: Block = Block(),
              settings: RotarySettings = RotarySettings()) -> float:
    """Deepest cut past the pocket's design surface (mm, 0 when clear) along every cutting move
    as the machine interpolates it (X, C, Z linear).

    Not a sample but a bound: never below the true depth, and above it by at most
    1e-7 mm + 0.1 % (:meth:`PocketGeometry.highest`).  So 0 means the ball never cuts in."""
    return _max_gouge(PocketGeometry(pocket, block, settings), op)


def _max_gouge(geo: PocketGeometry, op: Operation) -> float:
    x0, c0, z0, x1, c1, z1 = _endpoints(op)
    offset = np.array([geo.centre[0], geo.centre[1], -geo.r])

    def at(moves, t):
        return kinematics.interpolate(x0[moves], c0[moves], z0[moves], x1[moves], c1[moves], z1[moves], t) - offset
    speed, bend = kinematics.speed_and_bend(x0, c0, x1, c1)
    deepest, before = 0.0, geo.probe(at(np.zeros(1, int), np.zeros(1)))
    for moves in np.array_split(np.arange(len(op)), len(op) // BLOCK + 1):
        ends = geo.probe(at(moves, np.ones(len(moves))))
        starts = np.vstack([before, ends[:-1]])
        before = ends[-1:]
        cut = op.kind[moves] != RAPID
        if cut.any():
            top = geo.highest(at, moves[cut], starts[cut], ends[cut], speed[moves[cut]], bend[moves[cut]], 0.0,
                              overall=True)
            deepest = max(deepest, float(top.max()))
    return deepest


def plan(block: Block, pockets: list, settings: RotarySettings = RotarySettings(),
         name: str = "rotary pockets", progress=None) -> RotaryResult:
    """Plan every pocket in order: one Operation per pocket, C continuous across them.

    The IR holds machine coordinates: xyz = (X word = -R, 0, tool-tip Z), rotary["c"] in
    degrees, feed in mm/min along the path on the part (the post turns it into G93 F).
    ``progress``: optional callable(fraction, text).
    """
    settings.validate()
    report = progress or (lambda fraction, text: None)
    for value in (block.size_x, block.size_y, block.thickness):
        if not (is_finite_number(value) and value > 0):
            raise RotaryError(f"board sizes must be positive numbers, got {block}")
    if not pockets:
        raise RotaryError("no pockets to cut")
    names = [p.name for p in pockets]
    if len(set(names)) != len(names):
        raise RotaryError(f"pocket names must be unique, got {names}")
    geometries = [PocketGeometry(p, block, settings) for p in pockets]
    for i, a in enumerate(geometries):
        for b in geometries[i + 1:]:
            overlap = rg.area(a.region.translate(tuple(a.centre)) ^ b.region.translate(tuple(b.centre)))
            if overlap > rg.MIN_AREA:
                raise RotaryError(f"pockets {a.name!r} and {b.name!r} overlap ({overlap:.1f} mm^2)")

    results, c_now = [], None
    for index, (pocket, geo) in enumerate(zip(pockets, geometries)):
        report(index / len(pockets), f"pocket {pocket.name}")
        op, rough, wall, bottom = _pocket_operation(geo, settings, c_now)
        c_now = float(op.rotary["c"][-1])
        surface_radius = geo.sphere_radius if geo.bottom == "sphere" else math.inf
        scallop_bottom = scallop_height(geo.r, settings.stepover, surface_radius)
        scallop_wall = scallop_height(geo.r, settings.wall_stepover)
        lengths = move_lengths(op)
        entry = {
            "name": pocket.name,
            "bottom": pocket.bottom,
            "wall_angle_deg": float(pocket.wall_angle_deg),
            "depth_mm": geo.depth,
            "centre": [round(float(v), 4) for v in geo.centre],
            "sphere_radius_mm": geo.sphere_radius,
            "outline": [[round(float(x), 4), round(float(y), 4)] for x, y in geo.loop + geo.centre],
            "points": int(np.count_nonzero(op.kind != RAPID)),
            "path_length_mm": round(float(lengths[op.kind != RAPID].sum()), 1),
            "max_gouge_mm": round(_max_gouge(geo, op), 6),
            "scallop_mm": round(max(scallop_bottom, scallop_wall), 4),
            "scallop_bottom_mm": round(scallop_bottom, 4),
            "scallop_wall_mm": round(scallop_wall, 4),
            "rim_wall_mm": round(geo.rim_wall(), 3),
            "cycle_time_s": round(float(move_times(op, settings.rapid_rate, settings.max_table_rpm, lengths).sum()), 1),
        }
        results.append(PocketPath(pocket, op, entry, rough, wall, bottom))
    report(1.0, "done")
    program = Program(name, [r.operation for r in results], rapid_rate=settings.rapid_rate,
                      notes=[f"C-X-Z rotary table: {len(pockets)} pockets, tool tip programmed, "
                             f"{settings.cutting_speed:g} mm/min along the path on the part"])
    total = sum(r.report["cycle_time_s"] for r in results)
    return RotaryResult(program, results, [r.report for r in results], round(total, 1))


# ----------------------------------------------------------------------------------------
# The built-in sample (the paper's bento block)
# ----------------------------------------------------------------------------------------

def _rounded_rectangle(cx, cy, width, height, radius, spacing=1.0) -> np.ndarray:
    hx, hy = width / 2 - radius, height / 2 - radius
    pts = []
    for (sx, sy), start in (((1, 1), 0), ((-1, 1), 90), ((-1, -1), 180), ((1, -1), 270)):
        a = np.radians(np.linspace(start, start + 90, max(2, math.ceil(radius * math.pi / 2 / spacing)) + 1))
        pts.append(np.column_stack([cx + sx * hx + radius * np.cos(a), cy + sy * hy + radius * np.sin(a)]))
    return np.vstack(pts)


def _polar_outline(cx, cy, radius_of, count=180) -> np.ndarray:
    a = np.linspace(0, 2 * np.pi, count, endpoint=False)
    r = radius_of(a)
    return np.column_stack([cx + r * np.cos(a), cy + r * np.sin(a)])


def sample_job() -> tuple[Block, list]:
    """A 105 x 105 x 30 mm block (the paper's larch block) with three non-circular pockets:

    1. "slanted tray": 56 x 34 mm rounded rectangle, 12 mm deep, walls 15 degrees, flat floor;
    2. "peanut": a waisted outline (concave sides), 10 mm deep, vertical walls, flat floor;
    3. "bowl": a rounded square (superellipse), no wall, spherical bowl 9 mm deep, R 22 mm.
    """
    pockets = [
        Pocket("slanted tray", _rounded_rectangle(0.0, 25.0, 56.0, 34.0, 10.0), depth=12.0, wall_angle_deg=15.0),
        Pocket("peanut", _polar_outline(-24.0, -24.0, lambda a: 15.0 * (1 + 0.3 * np.cos(2 * a))), depth=10.0),
        Pocket("bowl", _polar_outline(25.0, -25.0, lambda a: 16.0 / (np.abs(np.cos(a)) ** 2.5
                                                                      + np.abs(np.sin(a)) ** 2.5) ** (1 / 2.5)),
               depth=9.0, bottom="sphere", sphere_radius=22.0),
    ]
    return Block(105.0, 105.0, 30.0), pockets
