"""The moves of one STEP-NC operation: rapids at the clearance plane, approaches stopping above
the material (the in-process stock), the TWO5D paths layer by layer, retracts; and the helpers the
strategies share (levels, stepover, offsets).  Split from workplan.py."""
from __future__ import annotations

import math
from decimal import Decimal

import numpy as np
from manifold3d import CrossSection, JoinType

from ...engines import region as rg
from ...ir.program import ARC_CCW, ARC_CW, FEED, Operation, PathBuilder
from .inprocess import InProcessStock
from .errors import StepNcError
from .geometry import CHORD_TOLERANCE
from .process import PlungeHelix, PlungeRamp

# Rapids stop this far (mm) above the level already cut, and feeding starts there.
APPROACH_GAP = 2.0
# Guards against values that would run for hours (a mistyped 1.E-9 radial depth): no stepover below
# MIN_STEPOVER mm, no more than MAX_PASSES layers or contour passes in one operation.
MIN_STEPOVER = 0.01
MAX_PASSES = 5000
# Stepover as a ratio of the tool diameter when the strategy gives neither overlap nor radial depth.
DEFAULT_STEPOVER_RATIO = 0.5
# A move at cutting depth between two paths is allowed when it stays this close (mm) to the region.
LINK_TOLERANCE = 0.01


class Motion:
    """The moves of one operation.

    Between cuts the tool rapids at the clearance (retract) plane, rapids down to
    APPROACH_GAP above the level already cut, then approaches.  Consecutive paths at the same
    depth are joined by a feed move when the straight link stays inside ``region`` (the tool
    centre region); otherwise the tool retracts and approaches again.

    The level already cut is the layer above (``cleared_z``) when that is safe: when the in-process
    ``stock`` (what earlier workingsteps left), or this path cut at the layer above, bounds the
    material under the tool there.  Otherwise the rapid stops APPROACH_GAP above that bound and the
    approach feeds the rest (finishing before its roughing, any order of the workingsteps).
    """

    def __init__(self, clearance_z, feed, approach=None, retract=None, region: CrossSection | None = None,
                 stock: InProcessStock | None = None, radius: float = 0.0):
        self.path = PathBuilder(clearance_z, feed, feed)
        self.stock = stock
        self.radius = radius
        self.levels: dict = {}         # (id of a path list, index) -> the lowest level that path was cut at
        self.clearance_z = clearance_z
        self.approach = approach
        self.retract_strategy = retract
        self.region = None if region is None else round_offset(region, LINK_TOLERANCE)  # None: never link
        self.notes: list = []
        self.entry_z = clearance_z     # where the last approach started (the retract ends there)
        self.previous_xy = None        # the point before the current one along the cut (retract ramp)

    def cut(self, paths, z: float, cleared_z: float, link: bool = True):
        """Cut every path ((k, 2) XY points) at height z; the material above cleared_z is gone.
        ``link=False`` lifts between paths even when a link would fit (one-way strokes)."""
        for index, points in enumerate(paths):
            key = (id(paths), index)
            points = np.asarray(points, float)
            here = self.path.position
            if (link and here is not None and abs(here[2] - z) < 1e-9
                    and _segment_inside(self.region, here[:2], points[0])):
                self.path.line(points[0][0], points[0][1], z, link=True)
            else:
                self.leave()
                self._enter(points, z, self.entry_height(points[0], cleared_z, self.levels.get(key)))
            self.levels[key] = min(z, self.levels.get(key, math.inf))
            for x, y in points[1:]:
                self.previous_xy = np.array(self.path.position[:2])
                self.path.line(x, y, z)

    def material_top(self, xy, cut_here=None) -> float:
        """The highest the material can be under the tool at ``xy`` (-inf: none): the in-process
        stock's bound, lowered to ``cut_here`` when this operation already cut there (inf: no bound)."""
        bound = math.inf if self.stock is None else self.stock.top_under(xy[0], xy[1], self.radius)
        return min(bound, math.inf if cut_here is None else cut_here)

    def entry_height(self, xy, cleared_z, cut_here=None) -> float:
        """Where the rapid down to a cut stops: APPROACH_GAP above the layer cleared before, or above
        the material when the material may be higher there."""
        level = cleared_z
        if self.stock is not None:
            material = self.material_top(xy, cut_here)
            if material > cleared_z + 1e-9:
                level = material
        return min(level + APPROACH_GAP, self.clearance_z)

    def _enter(self, points, z, top):
        x, y = points[0]
        self.path.rapid(x, y, self.clearance_z)
        if top < self.clearance_z - 1e-9:
            self.path.rapid(x, y, top)
        self.entry_z = top
        self._add(self._plunge(self.approach, points, top, z))
        self.previous_xy = None

    def leave(self):
        """Retract (the approach strategy played backwards), then rapid to the clearance plane."""
        here = self.path.position
        if here is None or here[2] >= self.clearance_z - 1e-9:
            return
        if self.retract_strategy is not None and here[2] < self.entry_z:
            back = [here[:2]] if self.previous_xy is None else [here[:2], self.previous_xy]
            down = self._plunge(self.retract_strategy, np.array(back), self.entry_z, here[2])
            self._add(_reversed(down, (here[0], here[1], self.entry_z)))
        self.path.retract()

    def _add(self, moves):
        for kind, (x, y, z), centre in moves:
            if kind == FEED:
                self.path.line(x, y, z)
            else:
                self.path.arc(x, y, z, centre[0], centre[1], clockwise=kind == ARC_CW)

    def _plunge(self, strategy, points, top, z) -> list:
        """Moves from (points[0], top) down to (points[0], z): straight down, a ramp back and forth
        along the first segment of the path, or a helix inside the region."""
        start = np.asarray(points[0], float)
        if isinstance(strategy, PlungeHelix) and strategy.angle < 90:
            moves = self._helix(start, top, z, strategy.radius, strategy.angle)
            if moves:
                return moves
            self.notes.append(f"no room for a {strategy.radius:g} mm helix at X{start[0]:.3f} Y{start[1]:.3f}; "
                              "ramped instead")
            strategy = PlungeRamp(strategy.tool_orientation, strategy.angle)
        if isinstance(strategy, PlungeRamp) and strategy.angle < 90:
            following = [p for p in np.asarray(points[1:], float) if np.linalg.norm(p - start) > 1e-3]
            if following:
                return _ramp(start, following[0], top, z, strategy.angle)
        return [(FEED, (start[0], start[1], z), None)]

    def _helix(self, start, top, z, radius, angle) -> list:
        """Counter-clockwise turns through ``start`` at exactly ``angle`` (:func:`helix_moves`), centred
        where the circle fits the region."""
        if radius <= 0:
            return []
        circle = np.linspace(0, 2 * math.pi, 64, endpoint=False)
        for direction in ((1, 0), (0, 1), (-1, 0), (0, -1)):
            centre = start + radius * np.array(direction, float)
            ring = centre + radius * np.column_stack([np.cos(circle), np.sin(circle)])
            if self.region is None or rg.contains_points(self.region, ring).all():
                return helix_moves(centre, start, top, z, helix_pitch(radius, angle), True)
        return []

    def operation(self, name, tool, rpm, clockwise, safe_z, coolant, comment, source_id=None) -> Operation:
        self.leave()
        x, y, _ = self.path.position
        self.path.rapid(x, y, safe_z)
        arrays = self.path.arrays()
        first = arrays["xyz"][0]
        return Operation(name=name, tool=tool, spindle_rpm=rpm, spindle_cw=clockwise,
                         clearance_z=self.clearance_z, safe_z=safe_z, start=[first[0], first[1], safe_z],
                         coolant=coolant, comment=comment, source_id=source_id, links=self.path.links(), **arrays)


def helix_pitch(radius: float, angle: float) -> float:
    """The drop per turn (mm) of a helix of ``radius`` (the tool centre's) rising at ``angle`` degrees
    from the horizontal: pi * D * tan(angle)."""
    return 2 * math.pi * radius * math.tan(math.radians(angle))


def helix_moves(centre, start, top: float, z: float, pitch: float, ccw: bool) -> list:
    """Moves down a helix about ``centre`` from (start, top) to depth z at ``pitch`` mm a turn (so at
    the angle the pitch says, the last turn a part of one), in arcs of at most 180 degrees; then
    along the circle at z back to ``start``.  [(kind, (x, y, z), centre)]."""
    centre = np.asarray(centre, float)
    offset = np.asarray(start, float) - centre
    radius = float(np.hypot(*offset))
    first = math.atan2(offset[1], offset[0])
    sign = 1.0 if ccw else -1.0
    kind = ARC_CCW if ccw else ARC_CW
    height = top - z
    sweep = 2 * math.pi * height / pitch if height > 0 else 0.0
    if sweep / (2 * math.pi) > MAX_PASSES:
        raise StepNcError(f"a helix of pitch {pitch:.4g} mm down {height:g} mm makes more than {MAX_PASSES} turns")
    moves = []
    pieces = max(1, math.ceil(sweep / math.pi - 1e-9))
    for k in range(1, pieces + 1):
        angle = first + sign * sweep * k / pieces
        moves.append((kind, (centre[0] + radius * math.cos(angle), centre[1] + radius * math.sin(angle),
                             top - height * k / pieces), centre))
    rest = (-sweep) % (2 * math.pi)            # on round the circle at z to the start
    if rest > 1e-9 and 2 * math.pi - rest > 1e-9:
        pieces = max(1, math.ceil(rest / math.pi - 1e-9))
        end = first + sign * sweep
        for k in range(1, pieces + 1):
            angle = end + sign * rest * k / pieces
            point = (centre[0] + radius * math.cos(angle), centre[1] + radius * math.sin(angle), z)
            if k == pieces:
                point = (float(start[0]), float(start[1]), z)
            moves.append((kind, point, centre))
    else:
        moves[-1] = (kind, (float(start[0]), float(start[1]), z), centre)
    return moves


def _segment_inside(region: CrossSection | None, a, b) -> bool:
    """Whether the straight move a -> b stays in ``region`` (tested every 0.2 mm)."""
    if region is None:
        return False
    count = max(2, math.ceil(np.linalg.norm(np.subtract(b, a)) / 0.2) + 1)
    return bool(rg.contains_points(region, np.linspace(a, b, count)).all())


def split_outside(chains: list, region: CrossSection) -> list:
    """Cut the chains where a step between rows leaves the region (a chord across a rounded
    inside corner), so the tool goes round instead of through the allowance."""
    grown = round_offset(region, LINK_TOLERANCE)
    pieces = []
    for chain in chains:
        start = 0
        for k in range(1, len(chain) - 1):
            if not _segment_inside(grown, chain[k], chain[k + 1]):
                pieces.append(chain[start:k + 1])
                start = k + 1
        pieces.append(chain[start:])
    return [piece for piece in pieces if len(piece) >= 2]


def _ramp(start, toward, top, z, angle) -> list:
    """Zigzag ramp down along start -> toward at ``angle`` degrees (or steeper), back at start."""
    segment = np.asarray(toward, float) - start
    room = np.linalg.norm(segment)
    run = (top - z) / math.tan(math.radians(angle))  # horizontal travel the angle needs
    legs = 2 * max(1, math.ceil(run / (2 * room) - 1e-9))
    far = start + segment / room * (run / legs)  # legs are chosen so this stays within the segment
    return [(FEED, (*(far if k % 2 == 0 else start), top - (top - z) * (k + 1) / legs), None) for k in range(legs)]


def _reversed(moves, before) -> list:
    """The same path travelled backwards: from the last end point back to ``before``."""
    points = [tuple(before)] + [end for _, end, _ in moves]
    flipped = {ARC_CW: ARC_CCW, ARC_CCW: ARC_CW}
    return [(flipped.get(kind, kind), points[i], centre) for i, (kind, _, centre) in reversed(list(enumerate(moves)))]


def cut_levels(top: float, floor: float, step: float | None) -> list:
    """Cutting levels below ``top`` down to ``floor``, evenly spaced and at most ``step`` apart."""
    height = top - floor
    if height <= 1e-9:
        return []
    layers = height / step if step else 1.0        # inf for a step of a denormal size (2.2e-311)
    if layers - 1e-9 > MAX_PASSES:
        shown = f"{math.ceil(layers - 1e-9)}" if math.isfinite(layers) else f"{Decimal(height) / Decimal(step):.3g}"
        raise StepNcError(f"{height:g} mm cut {step:g} mm at a time needs {shown} layers (more than {MAX_PASSES}): "
                          "check axial_cutting_depth")
    count = max(1, math.ceil(layers - 1e-9))
    return [top - height * k / count for k in range(1, count + 1)]


def iso_ratio(value: float) -> float:
    """An ISO 14649 ratio (positive_ratio_measure: 0.5 for half), as the reader checked it: the
    reader refuses one above 1 by name (an overlap, a DRILLING_TYPE_STRATEGY reduction), so no
    value is read as a percentage here."""
    if not 0 < value <= 1:
        raise ValueError(f"an ISO 14649 ratio must be above 0 and at most 1, got {value!r} (the reader checks it)")
    return value


def stepover_of(diameter: float, overlap: float | None, radial: float | None) -> float:
    """From the overlap (a ratio of the diameter) and the radial cutting depth: the smaller
    when both are given."""
    candidates = []
    if overlap is not None:
        candidates.append(diameter * (1 - iso_ratio(overlap)))
    if radial:
        candidates.append(radial)
    stepover = min(candidates) if candidates else diameter * DEFAULT_STEPOVER_RATIO
    if stepover < MIN_STEPOVER:
        raise StepNcError(f"stepover {stepover:g} mm (overlap {overlap}, radial depth {radial}) is below "
                          f"{MIN_STEPOVER:g} mm")
    return stepover


def round_offset(region: CrossSection, delta: float) -> CrossSection:
    """Round-join offset with arcs within CHORD_TOLERANCE (finer than region.offset, so finishing
    passes keep the tool edge on the wall to a few microns)."""
    if delta == 0:
        return region
    radius = abs(delta)
    segments = 720 if radius <= CHORD_TOLERANCE else min(
        3600, max(8, math.ceil(math.pi / math.acos(1 - CHORD_TOLERANCE / radius))))
    return region.offset(delta, JoinType.Round, 2.0, segments)


def is_empty(region: CrossSection) -> bool:
    return region.area() < rg.MIN_AREA
