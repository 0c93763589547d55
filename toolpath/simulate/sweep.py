"""Swept solids for the manifold engine (W6): the stock minus the tool at every point of every move.

Every piece lies within ``tolerance`` of the tool's true sweep.  The tool's corner (a ball's
quarter arc) is an area-equal polygon (see :func:`area_scale`), so a swept section is not
biased to material left (a straight ball slot reads within 0.1 % of its closed form at the
default tolerance); its inner vertices, and so the pieces, reach beyond the true sweep by at
most :func:`outside` (under three quarters of the tolerance, about a third at fine ones);
every other error is material left.  Each chain of moves (one operation's tip path in part coordinates)
becomes pieces, which are unioned in chunks with ``Manifold.batch_boolean`` and subtracted from
the stock.  The booleans' cost follows the number and size of the pieces, so moves are swept
along runs wherever the geometry allows, instead of one hull per move:

* A *gentle run* of an upright tool (axis along Z; on a rotary table it also turns about its
  own axis, which changes nothing): moves that climb or fall no steeper than the tool's slope
  allowance.  The tool's section through its axis (end and shank, up to above the stock),
  held upright and across the path, is carried along the run as a tube: where a tool of
  revolution moves horizontally, that section is exactly where it touches its sweep.  A tube
  follows the path while it turns gently (the section stands on the bisector at each vertex);
  at a sharp corner, after 60 degrees of turning and at both ends it stops square to its move
  and a wedge of the tool (the section's outer half turned about the tool axis over the open
  angle) fills the corner; at a reversal the whole tool does.  On a *level* run the shank
  (a cylinder from where the end meets it up to above the stock) sweeps exactly its footprint,
  the path offset by the radius: that is one prism (see :class:`Shanks`), and the tubes and
  wedges carry the end alone, up SHANK_OVERLAP into the prism; a flat end mill's level run is
  its prism alone, however jagged its path.
* A *run of a radial ball* (turn-mill: the axis runs from the C axis through the tip): moves
  that travel across the axis rather than along it, level or ramping along the bar.  Its tube
  carries the tip-side half of the ball's great circle square to the move and the shank's two
  lines out beyond the bar.  A stretch turns one way about C (so the long shank lines cannot
  fold) and bends across the bar only gently; the whole tool closes each stretch.
* A *level staircase* of a ball or flat end mill on a grid (turn-mill axial passes): the tool
  at its vertices, one hull per stretch of a grid row (see :func:`_level_staircase`).
* Everything else (plunges, steep ramps, other staircases of short moves): the hull of the tool
  at both ends of a move; a nearly straight run of moves is one hull of a slightly shrunk tool.
  Where a run ends next to such hulls, they close it.

Runs that add nothing are left out: a level run that another run along the same path covers
from deeper down (an upright tool lower on the same vertical lines: the layers of a pocket with
vertical walls; a radial tool nearer the C axis on the same rays: roughing rings and pocket
layers on the side of a bar; see :class:`Repeats`), any stretch lying wholly over ground
that deeper level runs have cleared to the top (see :class:`Floors`), the moves of a level run
that a deeper level run of the tool repeats (a pocket layer whose rings follow, in part, a deeper
layer's; the tool below holds the tool at the ends of what is left), and moves between runs
that a level run holds from below (a ramp entry along its contour; see :class:`LevelPaths`), that
another such move holds from below (a ramp zigzagging down one line; see
:func:`without_repeated_moves`) or whose hull lies over cleared ground (see :meth:`Floors.holds`).
Moves shorter than SHORT_MOVE are merged into the next first.

Budget of a tube: the section's facets a quarter of the tolerance (either side), the
joints a quarter (at a vertex turning by d the section stands full size across the bisector, so
the tube lies W (1/cos(d/2) - 1) inside the sweep on the inner side, W (1 - cos(d/2)) on the
outer), thinning the path an eighth, and on a slope the upright section up to a quarter (on a
level path, that quarter goes to the joints too).  A thinned path's chord passes within the
deviation of the points it leaves out, and the true path crosses the line square to the chord
through any of its points within [-minus, plus] of it (minus, plus: how far the points left out
lie right and left of the chord; on a convex curve only on its outer side, by the sagitta: the
chords lie inside the curve).  On a slope the section is shrunk all round by an eighth and the
path thinned within an eighth, either side.  On a level path the section keeps its size, the path
is thinned within a sixteenth, and each ring is moved in on the side the true path does not
stray to: its left half right by minus, its right half left by plus, so it lies in the tool
wherever across the chords beside it the true path crosses (see :func:`_one_sided`; on a curve
only the inner half moves).  Across the path a level tube then leaves the band plus + minus
(the sagitta on a curve) where a shrunk section left twice the shrink round its whole outline: a
ball groove round a 15 mm circle reads within 0.04 % of Pappus at 0.005-0.05 mm, against -0.34 %
at 0.03 mm shrunk.  The joints need no such treatment to lie inside (a ring stands in the tool
at its vertex, a point of the true path); they only leave material, W d^2 / 8 a side (0.02 % of
that groove).  The inner side's could be won back (the mitre point W / cos(d/2) out along the
bisector lies W from both chords), the outer's not (its mitre lies beyond the tool at the vertex).
A straight run needs no thinning room: its section is not shrunk.  A prism's facets (its round
ends and joins) lie inside the offset within a quarter; it has no other error.

Budget of a level staircase: facets a half, the tool shrunk by a quarter (for a row's dip and
straightness, or a run of moves merged into one hull), and a quarter for each move it leaves
out (its dip plus its distance from paths already held; see :func:`_level_staircase`).
"""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
from manifold3d import CrossSection, Error, Manifold, Mesh64, OpType

from ..ir.program import Tool
from .facets import area_scale, outside, polygon_sides, segments_for, tool_points, tool_rings  # noqa: F401 (the engine's names)
from .floors import Floors, Shanks
from .paths import without_short_moves
from .repeats import Level, LevelPaths, RadialLevel, Repeats, without_repeated_moves

MIN_RUN_MOVES = 3                # a run of at least this many gentle moves is swept as tubes
MAX_STRETCH_TURN = math.pi / 3   # a tube turns at most this much in all (it cannot fold back onto itself)
WEDGE_OVERLAP = math.radians(5.0)  # a wedge of the tool at a corner reaches this far over the tubes
MAX_RADIAL_TILT = math.radians(60.0)  # a radial tool's run moves at most this far from across its axis
MAX_RADIAL_SLOPE = math.radians(45.0)  # ... and climbs or falls along the bar at most this steeply
MAX_SHARP_SHARE = 0.25           # runs that break at more than this share of their vertices are cut as hulls
REVERSAL = math.radians(150.0)   # a corner turning more than this is a reversal (see :func:`_tube_pieces`)
_PULL_BACK = 1e-3                # mm: a tube's square end stops this short of a reversal, a wedge's floor this high
ROW_STRAIGHTNESS = 0.02          # of the tolerance: how far the vertices of one row may stray from its line
# triangles of pieces per union before it is subtracted: small enough that the union stays near
# the stock (in a bar, every tool's shank reaches out of it, and far-reaching unions grow slow),
# large enough that the solid is not rebuilt too often
CHUNK_TRIANGLES = 25_000
SHANK_OVERLAP = 0.5              # mm: a level run's tubes reach this far up its shank's prism (see :class:`Shanks`)
LEVEL = 1e-6                     # mm: a run whose height varies less than this is level (posts round to 1e-4)
SHORT_MOVE = 1e-6                # mm: shorter moves (noise between two arcs) are merged into the next


def straight_runs(points: np.ndarray, deviation: float) -> list:
    """Split a polyline into runs of consecutive points that all lie within ``deviation`` of
    the chord of their run; returns the indices where runs start and end (greedy: the run
    length is doubled, then bisected)."""

    def fits(i, j):
        a, d = points[i], points[j] - points[i]
        inner = points[i + 1:j] - a
        t = np.clip(inner @ d / max(d @ d, 1e-300), 0.0, 1.0)
        return not len(inner) or float(np.max(np.linalg.norm(inner - t[:, None] * d, axis=1))) <= deviation

    ends = [0]
    last = len(points) - 1
    i = 0
    while i < last:
        good = 1
        while i + 2 * good <= last and fits(i, i + 2 * good):
            good *= 2
        bad = min(2 * good, last - i + 1)
        while bad - good > 1:
            mid = (good + bad) // 2
            if fits(i, i + mid):
                good = mid
            else:
                bad = mid
        i += good
        ends.append(i)
    return ends


def placed(tool: np.ndarray, run: np.ndarray, axes: np.ndarray | None) -> np.ndarray:
    """The tool's points (tip at the origin, axis +Z) at every point of the run: upright, or
    for a radial tool turned so its axis is the run's horizontal ``axes``."""
    if axes is None:
        return (run[:, None, :] + tool[None, :, :]).reshape(-1, 3)
    ux, uy = axes[:, None, 0], axes[:, None, 1]
    a, b, c = tool[None, :, 0], tool[None, :, 1], tool[None, :, 2]
    # local (a, b, c) -> a * Z + b * (-uy, ux, 0) + c * (ux, uy, 0)
    turned = np.stack([c * ux - b * uy, c * uy + b * ux, np.broadcast_to(a, ux.shape[:1] + a.shape[1:])], axis=-1)
    return (run[:, None, :] + turned).reshape(-1, 3)


def cut(stock: Manifold, chains: list, tolerance: float, chunk: int = CHUNK_TRIANGLES, progress=None) -> Manifold:
    """The stock minus every chain's swept tool.

    ``chains``: objects with ``tool``, ``points`` (the tip path in part coordinates, (n, 3))
    and ``radial`` (the tool axis runs from the Z axis through the tip, as in radial turn-mill
    work; otherwise it is +Z).  Pieces are unioned in path order until they hold ``chunk``
    triangles, and subtracted; ``progress(fraction)`` is called after each chunk (it may raise
    to cancel).  Moves shorter than SHORT_MOVE are merged into the next (see :func:`without_short_moves`)."""
    chains = [SimpleNamespace(tool=chain.tool, points=without_short_moves(chain.points, SHORT_MOVE), radial=chain.radial)
              for chain in chains]
    bounds = stock.bounding_box()
    levels = level_runs(chains)
    floors = Floors(levels, tolerance)
    repeats, paths = Repeats(), LevelPaths()
    for tool, run in levels:
        paths.add(tool, run)
    pieces, shanks = [], Shanks(tolerance)
    for chain in chains:
        pieces += _chain_pieces(chain, tolerance, bounds, floors, repeats, paths, shanks)
    # each run kept from the repeats is one piece: its own tubes unioned first (near each other,
    # they go fast)
    pieces += [lambda made=made: Manifold.batch_boolean([m() for m in made], OpType.Add)
               for made in repeats.kept() if made]
    pieces += shanks.pieces(bounds[5])       # after every run is planned (repeats.kept plans the level ones)
    solid = stock
    swept, size = [], 0
    for done, make in enumerate(pieces, 1):
        swept.append(make())
        size += swept[-1].num_tri()
        if size >= chunk or done == len(pieces):
            solid = solid - Manifold.batch_boolean(swept, OpType.Add)
            solid.num_tri()                    # evaluate now: a natural progress point
            swept, size = [], 0
            if progress is not None:
                progress(done / len(pieces))
    return solid


def level_runs(chains: list) -> list:
    """(tool, points) of every level run of an upright tool (see :func:`_gentle_runs`)."""
    return [(chain.tool, chain.points[i:j + 1]) for chain in chains if not chain.radial
            for i, j in _gentle_runs(chain.points, 0.0)]


def _chain_pieces(chain, tolerance: float, bounds, floors, repeats, paths=None, shanks=None) -> list:
    """The chain as pieces, each a function that builds its solid: its gentle runs as tubes, and
    hulls for the moves between them but those a level run holds from below (``paths``, a
    LevelPaths: a ramp entry along the contour it then cuts).  Level runs (radial ones: at one height) go to
    ``repeats``, which leaves out those that a deeper run along the same path contains."""
    p = chain.points
    x0, y0, _, x1, y1, top = bounds
    bar_radius = max(-x0, x1, -y0, y1)
    if chain.radial:
        reach = np.hypot(p[:, 0], p[:, 1])
        axes = p[:, :2] / np.maximum(reach, 1e-12)[:, None]
        height = bar_radius + 1.0 - float(reach.min())      # the shank reaches out of the bar from any depth
        runs = _radial_runs(p, axes) if chain.tool.shape.spherical else []
    else:
        axes = None
        height = top + 1.0 - float(p[:, 2].min())           # the shank reaches above the stock from any depth
        runs = _gentle_runs(p, _max_slope(chain.tool, tolerance / 4))
    whole = tool_points(chain.tool, tolerance, height)
    # the moves between runs, cut as hulls; where there are some, they hold the whole tool at the
    # run's end, and the run need not close that end itself
    starts = [0] + [j for _, j in runs]
    ends = [i for i, _ in runs] + [len(p) - 1]
    between = [j > i for i, j in zip(starts, ends)]
    pieces = []
    for k, (i, j) in enumerate(runs):
        run = p[i:j + 1]
        level = np.ptp(run[:, 2]) <= LEVEL
        closed = (between[k], between[k + 1])
        if chain.radial:
            make = lambda run=run, i=i, j=j, closed=closed: _radial_run(chain.tool, run, axes[i:j + 1], whole,
                                                                        tolerance, bar_radius, closed)
            if level:
                # roughing rings or pocket layers at one height: the same tool nearer the C axis
                # at the same angle contains it
                repeats.add((chain.tool, round(float(run[0, 2]), 6)), RadialLevel(run), make)
            else:
                pieces += make()
        elif level:
            # a pocket with vertical walls repeats its path at every depth: the same tool lower
            # down contains it, the whole run (see Repeats) or some of its moves (see LevelPaths,
            # and there the tool lower down holds the whole tool at the ends of what is left)
            for a, b in [(0, len(run) - 1)] if paths is None else paths.not_held_below(chain.tool, run):
                part = run[a:b + 1]
                held = (closed[0] if a == 0 else True, closed[1] if b == len(run) - 1 else True)
                repeats.add((chain.tool, np.round(part[:, :2], 6).tobytes()), Level(part),
                            lambda part=part, held=held: _axial_run(chain, part, whole, height, tolerance, bounds,
                                                                    floors, held, shanks))
        else:
            pieces += _axial_run(chain, run, whole, height, tolerance, bounds, floors, closed, shanks)
    for i, j in zip(starts, ends):
        ranges = ([] if j <= i else [(0, j - i)] if paths is None or chain.radial
                  else without_repeated_moves(p[i:j + 1], paths.needed(chain.tool, p[i:j + 1])))
        for a, b in ranges:
            pieces += _hull_pieces(chain, p[i + a:i + b + 1], None if axes is None else axes[i + a:i + b + 1], whole,
                                   height, tolerance, bounds, floors)
    return pieces


def _max_slope(tool: Tool, allowance: float) -> float:
    """The steepest move (radians) along which the upright section of an upright tool stays within
    ``allowance`` of the true sweep: a flat bottom of radius f leaves up to f tan(a) under its
    leading edge, a corner of radius c up to c (1/cos(a) - 1) below its lowest point.  Cones are
    taken on level moves only."""
    if tool.shape.pointed:
        return 0.0
    flat, corner = tool.radius - tool.corner_radius, tool.corner_radius
    limits = [math.pi / 4]
    if flat > 0:
        limits.append(math.atan(allowance / 2 / flat))
    if corner > 0:
        limits.append(math.acos(1.0 / (1.0 + allowance / 2 / corner)))
    return min(limits)


def _gentle_runs(p: np.ndarray, max_slope: float) -> list:
    """(first, last) point indices of the runs of at least MIN_RUN_MOVES moves that each climb or
    fall no steeper than ``max_slope`` (0: level moves only)."""
    d = np.diff(p, axis=0)
    across = np.hypot(d[:, 0], d[:, 1])
    gentle = (across > 1e-6) & (np.abs(d[:, 2]) <= np.maximum(across * math.tan(max_slope), 1e-9))
    edges = np.flatnonzero(np.diff(np.concatenate([[0], gentle.astype(np.int8), [0]])))
    return [(int(i), int(j)) for i, j in zip(edges[::2], edges[1::2]) if j - i >= MIN_RUN_MOVES]


def _hull_pieces(chain, p, axes, whole, height, tolerance, bounds, floors=None) -> list:
    """One hull of the tool at both ends of each move, or of a slightly shrunk tool along a nearly
    straight run of moves (within a sixth of ``tolerance`` of its chord, so the hull of its
    points is within a third of the path); the facets take the other two thirds.  With ``floors``,
    an upright tool's hulls that lie wholly over ground deeper level runs cleared are left out
    (see :meth:`Floors.holds`: plunges, ramps and retracts inside a pocket)."""
    x0, y0, bottom, x1, y1, top = bounds
    bar_radius = max(-x0, x1, -y0, y1)
    merge = tolerance / 3
    r = chain.tool.radius
    if axes is not None:
        # The tool axis turns with C: a run is merged where both the tip and the far end of the
        # shank stay within merge / 2 of their chords (a rigid motion: every point of the tool
        # between them does too, near enough).
        reach = np.hypot(p[:, 0], p[:, 1])
        ends = straight_runs(np.column_stack([p, p[:, :2] + height * axes]), merge / 2)
    else:
        # cones are never merged: only the disc-and-corner tools are shrunk here
        ends = list(range(len(p))) if chain.tool.shape.pointed else straight_runs(p, merge / 2)
    shrunk = tool_points(chain.tool, tolerance - merge, height, inset=merge)
    pieces = []
    for i, j in zip(ends[:-1], ends[1:]):
        run = p[i:j + 1]
        lo, hi = run.min(axis=0), run.max(axis=0)
        if axes is not None:
            inside = reach[i:j + 1].min() < bar_radius and hi[2] + r > bottom and lo[2] - r < top
        else:
            inside = lo[2] < top and hi[0] + r > x0 and lo[0] - r < x1 and hi[1] + r > y0 and lo[1] - r < y1
            inside = inside and (floors is None or not floors.holds(run, r))
        if inside:
            points = placed(whole if j == i + 1 else shrunk, run, None if axes is None else axes[i:j + 1])
            pieces.append(lambda points=points: Manifold.hull_points(points))
    return pieces


def _axial_run(chain, p: np.ndarray, whole: np.ndarray, height: float, tolerance: float, bounds, floors,
               closed: tuple = (False, False), shanks: Shanks | None = None) -> list:
    """path (+) tool for an upright tool along a gentle run: the tool's section through its axis
    (end and shank, up to above the stock) carried along the path as tubes, upright and across
    the path, with wedges of the tool at sharp corners and at both ends; stretches that deeper
    level runs have already cleared (see :class:`Floors`) are left out.  A run too jagged for
    tubes (see :func:`_tube_pieces`) is cut as hulls, or if it is a level staircase of a ball or
    flat end mill, as rows of tool places (see :func:`_level_staircase`).  ``closed``: whether
    other pieces already hold the whole tool at the run's first and last point."""
    x0, y0, _, x1, y1, top = bounds
    tool = chain.tool
    r = tool.radius
    lo, hi = p.min(axis=0), p.max(axis=0)
    if lo[2] >= top or hi[0] + r <= x0 or lo[0] - r >= x1 or hi[1] + r <= y0 or lo[1] - r >= y1:
        return []
    facets, inset = _section_budget(r, tolerance)
    level = np.ptp(p[:, 2]) <= LEVEL
    if level or len(straight_runs(p, LEVEL)) == 2:
        # a straight run is followed exactly: no room needed to thin it; a level one takes the
        # thinning's room ring by ring, on the side it lies (see :func:`_one_sided`)
        inset = 0.0
    rings = tool_rings(tool, 2 * facets, inset)
    # up to above the stock, and always a shank over the end: a section whose top were the end's
    # last ring would have it lifted by _lifted (a V-bit's cone steepened: 7 % of a V-groove left)
    reach = max(top + 1.0 - lo[2], rings[-1][1] + SHANK_OVERLAP)
    # a level run's shank sweeps its footprint: a prism, and the tubes carry the end alone
    prism = level and reach > rings[-1][1] + SHANK_OVERLAP
    section = _section(rings, r - inset, rings[-1][1] + SHANK_OVERLAP if prism else reach)
    pieces = []
    own = Shanks(tolerance) if shanks is None else shanks
    for a, b in floors.needed(p, r):
        if prism and not tool.corner_radius and not tool.shape.pointed:
            own.add(p[a:b + 1], r, float(p[0, 2]))       # a flat end mill: the prism is all
            continue
        tubes = _tube_pieces(p[a:b + 1], section, tolerance, (closed[0] and a == 0, closed[1] and b == len(p) - 1),
                             one_sided=level)
        if tubes is not None:
            pieces += tubes
            if prism:
                own.add(p[a:b + 1], r, float(p[0, 2]) + rings[-1][1] + SHANK_OVERLAP / 2)
        elif tool.shape.staircase and np.ptp(p[a:b + 1, 2]) <= LEVEL:
            pieces += _level_staircase(chain, p[a:b + 1], height, tolerance, bounds)
        else:
            pieces += _hull_pieces(chain, p[a:b + 1], None, whole, height, tolerance, bounds)
    return pieces + (own.pieces(top) if shanks is None else [])


def _level_staircase(chain, p: np.ndarray, height: float, tolerance: float, bounds) -> list:
    """A level run of a ball or flat end mill that steps along a grid (as the turn-mill axial
    passes do), cut along the grid's rows rather than along its moves.

    Two places of a ball or flat end mill a gap g apart hold between them the tool shrunk by
    its dip r - sqrt(r^2 - g^2 / 4) anywhere on the line joining them.  Every piece here holds
    the tool shrunk by three quarters of the tolerance at each point of its path (facets a half,
    the rest a quarter), so:

    * the vertices are sorted into rows along the grid (straight within ROW_STRAIGHTNESS of the
      tolerance), and each stretch of at least three vertices without a wider gap is one hull
      of the tool shrunk by a quarter of the tolerance at its two ends (the dip and the
      straightness within that quarter);
    * the other moves are taken in order: a short move between two vertices that lie near the
      paths already held (its dip plus that distance at most a quarter of the tolerance) adds
      too little to be cut on its own, as where a pass runs back over its own path along a
      wall; every other move is cut as elsewhere (see :func:`_hull_pieces`), with the tighter
      budget.
    """
    x0, y0, _, x1, y1, top = bounds
    r = chain.tool.radius

    def span(dip):
        """The widest gap between two tool places that dips no more than ``dip`` between them."""
        return 2.0 * math.sqrt(max(2.0 * r * dip - dip * dip, 0.0))

    d = np.diff(p[:, :2], axis=0)
    length = np.linalg.norm(d, axis=1)
    # the grid's direction: the commonest direction of travel (by length) modulo a quarter turn
    angle = np.degrees(np.arctan2(d[:, 1], d[:, 0])) % 90.0
    counts, edges = np.histogram(angle, bins=180, range=(0.0, 90.0), weights=length)
    peak = edges[np.argmax(counts)]
    heading = math.radians(float(np.median(angle[np.abs((angle - peak + 45.0) % 90.0 - 45.0) <= 0.5])))
    along = p[:, 0] * math.cos(heading) + p[:, 1] * math.sin(heading)
    across = p[:, 1] * math.cos(heading) - p[:, 0] * math.sin(heading)
    straightness = tolerance * ROW_STRAIGHTNESS
    gap = span(tolerance / 4 - 2 * straightness)
    shrunk = tool_points(chain.tool, tolerance / 2, height, inset=tolerance / 4)
    pieces, held = [], []
    order = np.argsort(across, kind="stable")
    rows = [0] + [k for k in range(1, len(order)) if across[order[k]] - across[order[k - 1]] > straightness]
    rows = [order[a:b] for a, b in zip(rows, rows[1:] + [len(order)])]
    for row in rows:
        if len(row) < 3 or np.ptp(across[row]) > 2 * straightness:
            continue
        row = row[np.argsort(along[row], kind="stable")]
        for stretch in np.split(row, np.flatnonzero(np.diff(along[row]) > gap) + 1):
            if len(np.unique(np.round(along[stretch], 9))) < 3:
                continue
            ends = p[[stretch[0], stretch[-1]]]
            held.append(ends[:, :2])
            lo, hi = ends.min(axis=0), ends.max(axis=0)
            if lo[2] < top and hi[0] + r > x0 and lo[0] - r < x1 and hi[1] + r > y0 and lo[1] - r < y1:
                pieces.append(lambda ends=ends: Manifold.hull_points(placed(shrunk, ends, None)))
    near = np.full(len(p), np.inf)
    if held:
        held = np.asarray(held)
        near = np.min([_distance_to_segment(p[:, :2], a, b) for a, b in held], axis=0)
    allowance = tolerance / 4
    held_radius = r - tolerance        # the pieces hold a tool at least this wide: its dip is deeper
    dip = held_radius - np.sqrt(np.maximum(held_radius ** 2 - length * length / 4, 0.0))
    cut = np.zeros(len(length), bool)
    for k in range(len(length)):
        if dip[k] + max(near[k], near[k + 1]) > allowance:
            cut[k] = True
            near = np.minimum(near, _distance_to_segment(p[:, :2], p[k, :2], p[k + 1, :2]))
    edges = np.flatnonzero(np.diff(np.concatenate([[0], cut.astype(np.int8), [0]])))
    tight = 3 * tolerance / 4
    whole = tool_points(chain.tool, tight, height)
    for i, j in zip(edges[::2], edges[1::2]):
        pieces += _hull_pieces(chain, p[i:j + 1], None, whole, height, tight, bounds)
    return pieces


def _distance_to_segment(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Each 2-D point's distance from the segment a-b."""
    d = b - a
    t = np.clip((points - a) @ d / max(float(d @ d), 1e-300), 0.0, 1.0)
    return np.hypot(*(points - a - t[:, None] * d).T)


def _radial_run(tool: Tool, p: np.ndarray, axes: np.ndarray, whole: np.ndarray, tolerance: float,
                bar_radius: float, closed: tuple = (False, False)) -> list:
    """A radial ball along a run across its axis: the tip-side half of the ball's great circle
    square to the move and the shank's lines out beyond the bar (together the curve where the
    tool touches its sweep, see :func:`_radial_rings`) carried along the path as tubes, with the
    whole tool at both ends of each stretch (except the run's first or last point where
    ``closed`` says other pieces hold it).  A stretch turns one way about C, so the long shank
    lines cannot fold, and bends across the bar (seen unrolled: round C against along Z) only as
    gently as an upright tool's tube bends (see :func:`_stretches`)."""
    r = tool.radius
    centres = np.column_stack([p[:, :2] + r * axes, p[:, 2]])
    reach = np.hypot(centres[:, 0], centres[:, 1])
    if reach.min() - r >= bar_radius:
        return []
    facets, inset = _section_budget(r, tolerance)
    ball = r - inset
    n = polygon_sides(ball, facets)
    inner = np.linspace(math.pi / 2, 3 * math.pi / 2, n // 2 + 1)
    length = bar_radius + 1.0 - float(reach.min()) + r          # out beyond the bar from any depth
    # thinned so both the centre and the far end of the shank stay within the inset of their path
    keep = np.asarray(straight_runs(np.column_stack([centres, centres[:, :2] + length * axes]),
                                    min(tolerance / 8, r / 4)))
    turn = np.sign(centres[keep[:-1], 0] * centres[keep[1:], 1] - centres[keep[:-1], 1] * centres[keep[1:], 0])
    reversals = [k for k in range(1, len(keep) - 1) if turn[k - 1] != turn[k]]
    unrolled = np.column_stack([np.unwrap(np.arctan2(centres[keep, 1], centres[keep, 0])) * reach[keep].mean(),
                                centres[keep, 2]])
    ends = sorted(set(reversals) | set(_stretches(unrolled, ball, _max_turn(ball, tolerance / 4))))
    pieces = []
    for a, b in zip(ends[:-1], ends[1:]):
        stretch = keep[a:b + 1]
        pieces.append(lambda stretch=stretch: _tube_mesh(_radial_rings(centres[stretch], axes[stretch], ball,
                                                                       inner, length)))
    for k in ends[1 if closed[0] else 0:-1 if closed[1] else None]:
        i = keep[k]
        pieces.append(lambda i=i: Manifold.hull_points(placed(whole, p[i:i + 1], axes[i:i + 1])))
    return pieces


def _radial_rings(centres: np.ndarray, axes: np.ndarray, ball: float, inner: np.ndarray, length: float) -> np.ndarray:
    """(m, k, 3) rings of a radial ball's tube: at each centre, the tip-side half of the great
    circle square to the direction of travel, then the shank's two lines out to ``length`` along
    the tool axis from where that circle meets the shank's side.  A ball moving in a straight
    line touches its sweep along that great circle; the shank (a cylinder about the tool axis)
    along the two lines on it square to both the axis and the travel."""
    d = np.diff(centres, axis=0)
    t = d / np.linalg.norm(d, axis=1)[:, None]
    travel = np.vstack([t[:1], t[:-1] + t[1:], t[-1:]])
    travel /= np.linalg.norm(travel, axis=1)[:, None]
    axis = np.column_stack([axes, np.zeros(len(axes))])
    outward = axis - np.einsum("ij,ij->i", axis, travel)[:, None] * travel      # the axis, square to the travel
    outward /= np.linalg.norm(outward, axis=1)[:, None]
    side = np.cross(travel, axis)
    side /= (np.linalg.norm(side, axis=1) * np.sign(side[:, 2]))[:, None]       # upwards (runs are never steep)
    circle = (np.cos(inner)[None, :, None] * outward[:, None, :] + np.sin(inner)[None, :, None] * side[:, None, :])
    shank = np.stack([axis * length - ball * side, axis * length + ball * side], axis=1)
    return centres[:, None, :] + np.concatenate([circle * ball, shank], axis=1)


def _radial_runs(p: np.ndarray, axes: np.ndarray) -> list:
    """(first, last) point indices of the runs of at least MIN_RUN_MOVES moves of a radial tool
    that travel across its axis: within MAX_RADIAL_TILT of square to it round C, and no steeper
    than MAX_RADIAL_SLOPE along the bar (steeper moves, like the steps between rows, are hulls)."""
    d = np.diff(p, axis=0)
    across = np.hypot(d[:, 0], d[:, 1])
    middle = axes[:-1] + axes[1:]
    radial = np.abs(np.einsum("ij,ij->i", d[:, :2], middle)) / np.maximum(np.linalg.norm(middle, axis=1), 1e-12)
    gentle = ((across > 1e-6) & (np.abs(d[:, 2]) <= across * math.tan(MAX_RADIAL_SLOPE))
              & (radial <= across * math.sin(MAX_RADIAL_TILT)))
    edges = np.flatnonzero(np.diff(np.concatenate([[0], gentle.astype(np.int8), [0]])))
    return [(int(i), int(j)) for i, j in zip(edges[::2], edges[1::2]) if j - i >= MIN_RUN_MOVES]


def _section_budget(radius: float, tolerance: float) -> tuple:
    """(facet sagitta, inset) of a tube's section, each a quarter and an eighth of the tolerance:
    the inset leaves room to follow the path only within it (see :func:`_tube_pieces`; a level
    run's tubes take that room ring by ring instead, and use no inset)."""
    return tolerance / 4, min(tolerance / 8, radius / 4)


def _section(rings: list, shank_radius: float, height: float) -> np.ndarray:
    """The tool cut by a plane through its axis, from the tip up to ``height``: a convex polygon
    (s, h), counter-clockwise; ``rings`` is its end (see :func:`tool_rings`)."""
    right = list(rings) + [(shank_radius, height)]
    left = [(-s, h) for s, h in reversed(right) if s > 1e-12]
    return np.array(right + left, float)


def _max_turn(half_width: float, allowance: float) -> float:
    """The largest turn at a tube vertex that keeps the tube within ``allowance`` of the sweep."""
    return 2.0 * math.acos(1.0 / (1.0 + allowance / half_width))


def _stretches(path: np.ndarray, half_width: float, max_turn: float) -> list:
    """Vertex indices where a tube of this half-width along the 2-D polyline breaks, both ends
    included: a turn sharper than ``max_turn``, a move too short for the turns at its ends (the
    sections there would cross within the half-width), or MAX_STRETCH_TURN of turning since the
    last break.  The tubes on either side of a break end square to their moves and a wedge of
    the tool fills the corner."""
    d = np.diff(path, axis=0)
    length = np.linalg.norm(d, axis=1)
    heading = np.arctan2(d[:, 1], d[:, 0])
    turn = np.abs((np.diff(heading) + math.pi) % (2 * math.pi) - math.pi)
    lean = np.tan(turn / 2)                  # a section at a vertex leans this much per unit of half-width
    m = len(path) - 1
    breaks, turned = [0], 0.0
    for i in range(1, m):
        before = 0.0 if breaks[-1] == i - 1 else lean[i - 2]
        after = lean[i] if i < m - 1 else 0.0
        if (turn[i - 1] > max_turn or turned + turn[i - 1] > MAX_STRETCH_TURN
                or length[i - 1] <= 1.25 * half_width * (before + lean[i - 1])
                or length[i] <= 1.25 * half_width * (lean[i - 1] + after)):
            breaks.append(i)
            turned = 0.0
        else:
            turned += turn[i - 1]
    breaks.append(m)
    return breaks


def _tube_pieces(path: np.ndarray, section: np.ndarray, tolerance: float, closed: tuple = (False, False),
                 one_sided: bool = False) -> list:
    """Tubes of ``section`` (s across the path, h up) along the gentle 3-D polyline, and at every
    break (see :func:`_stretches`) and at both ends the section's outer half turned about the
    vertical axis through the vertex over the angle the tubes leave open (a wedge of the tool;
    half of it at the ends, unless ``closed`` says other pieces hold the whole tool there).

    Every piece lies inside the true sweep, but for the corner polygon's :func:`outside`.
    The polyline is first thinned to the vertices it needs to stay within the section's inset
    (an eighth of the tolerance) of every point, so the tubes along it still do; or with
    ``one_sided`` (a level path and a section not shrunk) within a sixteenth, each ring moved in
    on the side the points left out do not lie (see :func:`_one_sided`).  Joints take a quarter
    of the tolerance (a half on a level path, which needs none for its slope), facets another
    quarter.  At a reversal (a turn over REVERSAL) the whole tool stands at the vertex instead
    of a wedge.

    None when more than MAX_SHARP_SHARE of the vertices are breaks (a staircase of short
    moves): tubes one move long and a wedge at every corner, all overlapping, union slower than
    hulls of the tool."""
    half_width = float(np.max(np.abs(section[:, 0])))
    deviation = min(tolerance / (16 if one_sided else 8), half_width / 4)
    keep = straight_runs(path, deviation)
    sides = _chord_sides(path, keep) if one_sided else None
    path = path[keep]
    flat = path[:, :2]
    # the joints take a quarter of the tolerance, or on a level path also the quarter a slope would
    joints = tolerance / 2 if np.ptp(path[:, 2]) <= LEVEL else tolerance / 4
    breaks = _stretches(flat, half_width, _max_turn(half_width, joints))
    if len(breaks) - 2 > MAX_SHARP_SHARE * len(path):
        return None
    d = np.diff(flat, axis=0)
    t = d / np.linalg.norm(d, axis=1)[:, None]
    heading = np.arctan2(t[:, 1], t[:, 0])
    bisector = np.vstack([t[:1], t[:-1] + t[1:], t[-1:]])
    turn = np.concatenate([[0.0], (np.diff(heading) + math.pi) % (2 * math.pi) - math.pi, [0.0]])
    reversal = np.abs(turn) > REVERSAL
    pieces = []
    for k, (a, b) in enumerate(zip(breaks[:-1], breaks[1:])):
        # the ends stand square to their moves, through the vertex (a tube coming in and one
        # going out touch only along its axis), but at a reversal their ends would lie in one
        # plane: there they stop a hair short, and the whole tool fills the gap
        along = bisector[a:b + 1].copy()
        along[0], along[-1] = t[a], t[b - 1]
        stretch = path[a:b + 1].copy()
        if b - a > 1 or np.linalg.norm(d[a]) > 4 * _PULL_BACK:
            stretch[0, :2] += _PULL_BACK * t[a] * reversal[a]
            stretch[-1, :2] -= _PULL_BACK * t[b - 1] * reversal[b]
        if sides is None:
            rings = _lifted(section, k)
        else:
            # each ring takes the deviations of the chords on either side of its vertex
            chords = np.arange(a, b + 1)
            plus = np.maximum(sides[np.maximum(chords - 1, a), 0], sides[np.minimum(chords, b - 1), 0])
            minus = np.maximum(sides[np.maximum(chords - 1, a), 1], sides[np.minimum(chords, b - 1), 1])
            kappa = np.cos(turn[a:b + 1] / 2)
            kappa[[0, -1]] = 1.0         # the ends stand square to their one chord
            rings = _one_sided(_lifted(section, k), plus, minus, kappa, 2 * deviation)
        pieces.append(lambda stretch=stretch, along=along, rings=rings: _tube(stretch, along, rings))
    right = section[section[:, 0] > 1e-9 * half_width]
    outer = np.vstack([[0.0, section[:, 1].min()], right[np.argsort(right[:, 1], kind="stable")],
                       [0.0, section[:, 1].max()]])
    segments = polygon_sides(half_width, tolerance / 4)
    last = len(path) - 1
    for k, i in enumerate(breaks):
        if (i == 0 and closed[0]) or (i == last and closed[1]):
            continue
        if i == 0:
            start, sweep = heading[0] + math.pi / 2, math.pi
        elif i == last:
            start, sweep = heading[-1] - math.pi / 2, math.pi
        elif reversal[i]:
            start, sweep = 0.0, 2 * math.pi
        else:
            start, sweep = ((heading[i - 1] - math.pi / 2, turn[i]) if turn[i] > 0
                            else (heading[i] + math.pi / 2, -turn[i]))
        if sweep < 2 * math.pi:
            # reaching WEDGE_OVERLAP past the tubes' end faces on both sides: overlapping, never
            # touching (faces that nearly coincide make slivers and slow booleans)
            start, sweep = start - WEDGE_OVERLAP, sweep + 2 * WEDGE_OVERLAP
        outline = CrossSection([_raised_floor(_lifted(outer, k + 0.5))])
        pieces.append(lambda start=start, sweep=sweep, at=path[i].tolist(), outline=outline: Manifold.revolve(
            outline, max(3, math.ceil(segments * sweep / (2 * math.pi))), math.degrees(sweep))
            .rotate([0.0, 0.0, math.degrees(start)]).translate(at))
    return pieces


def _chord_sides(path: np.ndarray, keep: list) -> np.ndarray:
    """(len(keep) - 1, 2): how far the level path's points between two kept vertices lie on the
    left of the chord joining them (across its left normal) and on its right, at least 0."""
    keep = np.asarray(keep)
    chord = np.clip(np.searchsorted(keep, np.arange(len(path)), side="right") - 1, 0, len(keep) - 2)
    a, b = path[keep[chord], :2], path[keep[chord + 1], :2]
    d = b - a
    signed = (d[:, 0] * (path[:, 1] - a[:, 1]) - d[:, 1] * (path[:, 0] - a[:, 0])) / np.maximum(
        np.hypot(d[:, 0], d[:, 1]), 1e-300)
    return np.column_stack([np.maximum.reduceat(np.maximum(signed, 0.0), keep[:-1]),
                            np.maximum.reduceat(np.maximum(-signed, 0.0), keep[:-1])])


def _one_sided(section: np.ndarray, plus: np.ndarray, minus: np.ndarray, kappa: np.ndarray,
               clear: float) -> np.ndarray:
    """(m, k, 2) rings of a tube along a thinned level path: at each vertex the section (full
    size) with its left half (s > 0) moved right by ``minus`` and its right half moved left by
    ``plus``, where the true path strays up to ``plus`` left and ``minus`` right of the chords
    beside the vertex (``kappa``: cos of half the turn there, the section standing on the
    bisector).  Vertices nearer the axis than ``clear`` (at least the largest shift doubled) are
    replaced by one bottom point, lifted until the section is wide enough there.

    Why it lies in the true sweep: the true path crosses the line square to a chord through any
    of its points c within [-minus, plus] of c, so c + x lies in the tool there for every x in
    K = T n (T + plus n) n (T - minus n) (T the tool of revolution of the section, n the chord's
    left normal; T convex).  A moved vertex s0 > 0 standing on the bisector lies within the
    tool's radius at its height of every such centre when s0 - minus >= plus / (2 kappa), true
    beyond ``clear`` while kappa >= 1/2 (turns inside a tube are far smaller; its ends stand
    square to their one chord: 1); the bottom point at s = (plus - minus) / 2 within (plus + minus) / 2 +
    max(plus, minus) sqrt(2 (1 - kappa)).  Every ring so lies in v + K of both chords beside it,
    and the tube between two rings in the sweep of K along their chord."""
    m = len(plus)
    s, h = section[:, 0], section[:, 1]
    near = (np.abs(s) < clear)
    chain = np.flatnonzero((s >= 0.0))
    chain = chain[np.argsort(h[chain], kind="stable")]
    bottom = np.flatnonzero(near)
    kept = np.flatnonzero(~near)
    moved = np.broadcast_to(section[kept], (m, len(kept), 2)).copy()
    moved[:, :, 0] += np.where(s[kept] > 0, -minus[:, None], plus[:, None])
    if not len(bottom):
        return moved
    need = (plus + minus) / 2 + np.maximum(plus, minus) * np.sqrt(np.maximum(2 * (1 - kappa), 0.0))
    tip = np.column_stack([(plus - minus) / 2, np.interp(need, s[chain], h[chain])])
    at = int(np.searchsorted(kept, bottom[0]))
    return np.concatenate([moved[:, :at], tip[:, None, :], moved[:, at:]], axis=1)


def _raised_floor(section: np.ndarray) -> np.ndarray:
    """The section with its flat bottom (if any) raised by _PULL_BACK: a wedge's floor then never
    lies in the plane of the tubes' floor (coplanar floors leave slivers in the union)."""
    raised = section.copy()
    raised[section[:, 1] == section[:, 1].min(), 1] += _PULL_BACK
    return raised


def _lifted(section: np.ndarray, k: float) -> np.ndarray:
    """The section with its top raised by a different amount for each piece k (up to 0.5 mm; the
    top lies above the stock): many pieces with their tops in one plane make the union slow."""
    lifted = section.copy()
    top = section[:, 1] == section[:, 1].max()
    lifted[top, 1] += 0.05 + 0.45 * ((k * 0.6180339887) % 1.0)
    return lifted


def _tube(path: np.ndarray, along: np.ndarray, section: np.ndarray) -> Manifold:
    """``section`` (s, h) carried along the 3-D polyline, upright and across the horizontal
    direction ``along`` at each vertex (s along its left normal, h up), closed at both ends."""
    along = along / np.linalg.norm(along, axis=1)[:, None]
    normal = np.column_stack([-along[:, 1], along[:, 0], np.zeros(len(along))])
    section = np.broadcast_to(section, (len(path),) + section.shape[-2:])
    rings = path[:, None, :] + section[:, :, 0, None] * normal[:, None, :]
    rings[:, :, 2] += section[:, :, 1]
    return _tube_mesh(rings)


def _tube_mesh(rings: np.ndarray) -> Manifold:
    """The closed tube through rings (m, k, 3) of corresponding points, capped by fans at both
    ends (each end ring must be star-shaped from its first point).  Each ring lies in the tool at
    its place, so the tube lies in the hulls of consecutive tool places."""
    m, k, _ = rings.shape
    origin = rings.reshape(-1, 3).mean(axis=0)
    vertices = rings.reshape(-1, 3) - origin
    ring = np.arange(k)
    a = (np.arange(m - 1) * k)[:, None] + ring
    b = (np.arange(m - 1) * k)[:, None] + (ring + 1) % k
    sides = np.concatenate([np.stack([a, b, b + k], -1), np.stack([a, b + k, a + k], -1)]).reshape(-1, 3)
    fan = np.column_stack([np.zeros(k - 2, np.int64), np.arange(1, k - 1), np.arange(2, k)])
    faces = np.vstack([sides, fan[:, ::-1], fan + (m - 1) * k])
    v0, v1, v2 = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    if np.einsum("ij,ij->", v0, np.cross(v1, v2)) < 0:
        faces = faces[:, ::-1]
    tube = Manifold(Mesh64(vert_properties=np.ascontiguousarray(vertices + origin, np.float64),
                           tri_verts=np.ascontiguousarray(faces, np.uint64)))
    if tube.status() != Error.NoError:
        # not expected (the stretches are chosen so tubes cannot fold); hulls of ring pairs
        # still lie inside the sweep
        return Manifold.batch_boolean([Manifold.hull_points(np.vstack([rings[i], rings[i + 1]]))
                                       for i in range(m - 1)], OpType.Add)
    return tube
