"""W3: ISO 14649 (STEP-NC) workplans -> Program, and pockets -> ISO 14649 (seed 002).

An ISO 14649 WORKPLAN is an ordered list of MACHINING_WORKINGSTEPs, each naming what to cut
(``its_feature``) and how (``its_operation``).  :func:`to_program` makes one Operation per
workingstep, in workplan order (nested workplans flattened) or in an order the caller gives.
Every operation moves the same way: rapid at the security plane to above the start, rapid down
to the retract plane, approach (PLUNGE_TOOLAXIS / PLUNGE_RAMP / PLUNGE_HELIX) to the cut, the
TWO5D strategy (BIDIRECTIONAL, UNIDIRECTIONAL, CONTOUR_PARALLEL) layer by layer, retract.

The paper's point is roughing and finishing of closed pockets in any order: finishing plans its
region from the pocket and the *roughing workingsteps' parameters* (their tool and
allowance_side/allowance_bottom), never from what happens to precede it, so swapping two
workingsteps swaps their NC blocks and changes nothing else.  Pocket roughing clears the outline
offset inward by allowance_side (BIDIRECTIONAL zigzag plus one ring along the offset outline, so
the reach is exact, or CONTOUR_PARALLEL rings) in layers down to depth + allowance_bottom.
Pocket finishing cuts contour-parallel rings over the part roughing left along the walls at every
layer, and the whole floor at the layers below the rough floor.

Coordinates are the workpiece's (the work offset); lengths in mm, feed in mm/min, spindle in rpm.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np
from manifold3d import CrossSection, JoinType

from .. import region as rg
from ..errors import InputError
from ..program import ARC_CCW, ARC_CW, FEED, Operation, PathBuilder, Program, Tool
from .model import (
    CHORD_TOLERANCE, DRILLING_TOOL_BODIES, Bidirectional, BottomAndSideMilling, ClosedPocket, ContourParallel,
    CuttingTool, DrillingOperation, PlanarFace, PlaneMilling, PlungeHelix, PlungeRamp, Project, RoundHole,
    StepNcError, Unidirectional, Workingstep, read_project,
)
from .inprocess import InProcessStock
from .part21 import UNSET, Enum, parse_part21, read_part21
from .part21_writer import Part21Writer

# Rapids stop this far (mm) above the level already cut, and feeding starts there.
APPROACH_GAP = 2.0
# A facing stroke starts and ends this far (mm) beyond the tool radius outside the face.
FACING_RUNOUT = 2.0
# Guards against values that would run for hours (a mistyped 1.E-9 radial depth): no stepover below
# MIN_STEPOVER mm, no more than MAX_PASSES layers or contour passes in one operation.
MIN_STEPOVER = 0.01
MAX_PASSES = 5000
# Stepover as a ratio of the tool diameter when the strategy gives neither overlap nor radial depth.
DEFAULT_STEPOVER_RATIO = 0.5
# A move at cutting depth between two paths is allowed when it stays this close (mm) to the region.
LINK_TOLERANCE = 0.01
# A through hole is drilled through: the drill's full diameter passes the stock bottom by this much (mm)
# beyond the point's length.
BREAKTHROUGH_CLEARANCE = 2.0
# Drill point when the file gives no tool_top_angle: the usual 118 degrees included angle.  ISO 14649's
# tool_top_angle is measured from the plane square to the axis (ex1's drill: 31 = (180 - 118) / 2).
DEFAULT_TOOL_TOP_ANGLE = 31.0
POINTED_DRILL_BODIES = ("TWIST_DRILL", "TAPERED_DRILL")
THROUGH_CONDITIONS = ("THROUGH_BOTTOM_CONDITION", "THROUGH_POCKET_BOTTOM_CONDITION")
# What a tool body is called in the NC comments (Tool.describe); bodies not listed use the IR kind's name.
BODY_LABELS = {"TWIST_DRILL": "twist drill", "TAPERED_DRILL": "drill", "CENTER_DRILL": "centre drill",
               "REAMER": "reamer", "TAPERED_REAMER": "reamer", "TAP": "tap", "COUNTERSINK": "countersink",
               "COUNTERBORE": "counterbore", "FACEMILL": "face mill"}
# A feature may reach this far (mm) below the stock bottom before it is refused (rounding in the file).
DEPTH_TOLERANCE = 1e-6


@dataclass(frozen=True)
class LoadedWorkplan:
    """What :func:`load_workplan` returns: the model, its workingsteps in workplan order (nested
    workplans flattened, unsupported ones left out) and the warnings about what was left out."""

    project: Project
    workingsteps: tuple
    warnings: tuple

    def workingstep(self, ident: int) -> Workingstep:
        for step in self.workingsteps:
            if step.id == ident:
                return step
        raise KeyError(f"no workingstep #{ident}")


def load_workplan(source) -> LoadedWorkplan:
    """Read an ISO 14649 file, from a path or from its Part 21 text.

    Raises Part21Error for a syntax error or a reference to an undefined instance and
    StepNcError for malformed ISO 14649 data; both name the instance.
    """
    if isinstance(source, str) and "ISO-10303-21;" in source:
        part21 = parse_part21(source)
    else:
        part21 = read_part21(os.fspath(source))
    project, warnings = read_project(part21)
    return LoadedWorkplan(project, tuple(project.main_workplan.workingsteps()), tuple(warnings))


# --------------------------------------------------------------------------- workplan -> Program


def to_program(model: LoadedWorkplan, order=None, enabled=None, name: str | None = None) -> Program:
    """The NC program of a workplan: one Operation per enabled workingstep, named after it.

    order:   workingstep instance ids in the order to machine them (every workingstep once);
             default the workplan's order.
    enabled: the ids to machine; default all.
    Tool numbers follow the first use in the workplan's own order, so reordering does not
    renumber tools.  Warnings (skipped entities, finishing before its roughing) go into
    ``Program.notes``.
    """
    steps = {step.id: step for step in model.workingsteps}
    if order is None:
        sequence = list(model.workingsteps)
    else:
        order = list(order)
        missing = sorted(set(steps) - set(order))
        unknown = sorted(set(order) - set(steps))
        if missing or unknown or len(order) != len(steps):
            raise StepNcError(f"order must list every workingstep once; missing {missing}, unknown {unknown}, "
                             f"given {order}")
        sequence = [steps[ident] for ident in order]
    enabled = set(steps) if enabled is None else set(enabled)
    numbers = {}
    for step in model.workingsteps:
        numbers.setdefault(step.its_operation.its_tool.id, len(numbers) + 1)
    position = {step.id: index for index, step in enumerate(sequence)}
    notes = list(model.warnings)
    bottom, source = stock_bottom(model)
    if bottom is None:
        notes.append("the stock bottom is unknown (no workpiece BLOCK and no through feature): feature depths "
                     "are not checked against the stock")
    operations = []
    stock = in_process_stock(model)
    for step in sequence:
        if step.id not in enabled:
            continue
        roughings = _roughings_of(step, model.workingsteps)
        for rough in roughings:
            if rough.id not in enabled or position[rough.id] > position[step.id]:
                notes.append(f"workingstep #{step.id} '{step.its_id}' assumes roughing #{rough.id} "
                             f"'{rough.its_id}' was done before it")
        try:
            if bottom is not None:
                check_depth(step, bottom, source)
            tool = tool_for(step.its_operation.its_tool, numbers[step.its_operation.its_tool.id])
            operation = plan_workingstep(step, tool, [rough.its_operation for rough in roughings], notes, stock)
        except InputError as error:
            raise StepNcError(f"workingstep #{step.id} '{step.its_id}': {error}") from None
        if operation is not None:
            operations.append(operation)
            stock.cut(operation)
    return Program(name or model.project.its_id or "STEP-NC", operations, notes=notes)


# Without a workpiece BLOCK, the in-process stock covers the features and this much (mm) around them;
# beyond it the material is taken as high as the highest feature top.
UNKNOWN_STOCK_MARGIN = 50.0


def in_process_stock(model: LoadedWorkplan) -> InProcessStock:
    """The material before the first workingstep: the workpieces' BLOCKs (nothing outside them), or
    when the file gives none, material up to the highest feature top everywhere."""
    boxes = [w.its_bounding_geometry.box() for w in model.project.its_workpieces
             if w.its_bounding_geometry is not None]
    if boxes:
        low = np.min([box[0] for box in boxes], axis=0)
        high = np.max([box[1] for box in boxes], axis=0)
        return InProcessStock(low[0], low[1], high[0], high[1], float(high[2]))
    features = {step.its_feature.id: step.its_feature for step in model.workingsteps}.values()
    top = max((feature.top_z for feature in features), default=0.0)
    points = [_feature_xy(feature) for feature in features]
    points = np.vstack([p for p in points if p is not None] or [np.zeros((1, 2))])
    (x0, y0), (x1, y1) = points.min(axis=0) - UNKNOWN_STOCK_MARGIN, points.max(axis=0) + UNKNOWN_STOCK_MARGIN
    return InProcessStock(x0, y0, x1, y1, top, outside=top)


def _feature_xy(feature):
    """Points (k, 2) around a feature in XY, or None."""
    if isinstance(feature, ClosedPocket):
        return np.asarray(feature.outline(), float)[:, :2]
    if isinstance(feature, PlanarFace):
        return np.asarray(feature.corners(), float)[:, :2]
    if isinstance(feature, RoundHole):
        return np.asarray(feature.centre, float)[None, :] + np.array([[-1, -1], [1, 1]]) * feature.diameter / 2
    return None


def stock_bottom(model: LoadedWorkplan) -> tuple:
    """(Z of the stock bottom, where it comes from), or (None, None) when the file does not say.

    From the workpieces' bounding BLOCKs if there are any; otherwise from the through features
    (a through hole's depth plane is the bottom of the stock it goes through), the deepest one.
    """
    boxes = [w.its_bounding_geometry for w in model.project.its_workpieces if w.its_bounding_geometry is not None]
    if boxes:
        block = min(boxes, key=lambda b: b.box()[0][2])
        return float(block.box()[0][2]), f"the bottom of workpiece BLOCK #{block.id}"
    through = [step.its_feature for step in model.workingsteps
               if getattr(step.its_feature, "bottom_condition", None) in THROUGH_CONDITIONS]
    if through:
        feature = min(through, key=lambda f: f.bottom_z)
        return feature.bottom_z, f"the depth of through feature #{feature.id} '{feature.its_id}'"
    return None, None


def check_depth(step: Workingstep, bottom: float, source: str):
    """Refuse a workingstep that would cut below the stock bottom (a through feature's own
    breakthrough below its depth plane is planned, not refused)."""
    feature, operation = step.its_feature, step.its_operation
    depth = feature.bottom_z
    what = "depth"
    if isinstance(operation, DrillingOperation) and operation.cutting_depth is not None:
        depth, what = feature.top_z - operation.cutting_depth, f"cutting_depth {operation.cutting_depth:g}"
        if getattr(feature, "bottom_condition", None) in THROUGH_CONDITIONS:
            return   # the file asks for this much breakthrough
    if depth < bottom - DEPTH_TOLERANCE:
        raise StepNcError(f"{type(feature).__name__} #{feature.id} '{feature.its_id}': its {what} reaches Z "
                          f"{depth:g}, {bottom - depth:g} mm below the stock bottom (Z {bottom:g}, {source}); "
                          "correct the feature depth or the stock")


def _roughings_of(step: Workingstep, workingsteps) -> list:
    """The roughing workingsteps of a finishing workingstep's feature (same operation family)."""
    operation = step.its_operation
    if not isinstance(operation, (PlaneMilling, BottomAndSideMilling)) or not operation.finishing:
        return []
    return [other for other in workingsteps
            if other.its_feature.id == step.its_feature.id and type(other.its_operation) is type(operation)
            and not other.its_operation.finishing]


def tool_for(tool: CuttingTool, number: int) -> Tool:
    """The IR tool of an ISO 14649 cutting tool."""
    body = tool.its_tool_body
    dimension = body.dimension
    corner = dimension.edge_radius or 0.0
    if body.type_name == "BALL_ENDMILL":
        kind, corner = "ball", dimension.diameter / 2
    elif body.type_name in DRILLING_TOOL_BODIES:
        kind = "drill"
    else:
        kind = "bull" if corner > 0 else "flat"
    extra = {"flute_length": dimension.cutting_edge_length} if dimension.cutting_edge_length else {}
    return Tool(number, kind, dimension.diameter, min(corner, dimension.diameter / 2), name=tool.its_id,
                label=BODY_LABELS.get(body.type_name, ""), **extra)


def feed_and_speed(operation, tool: Tool) -> tuple:
    """(feed mm/min, spindle rpm, clockwise) from MILLING_TECHNOLOGY; the spindle may come from
    the cutting speed and the feed from the feed per tooth."""
    technology = operation.its_technology
    rpm = technology.spindle_rpm
    if rpm is None and technology.cutspeed:
        rpm = technology.cutspeed * 60000.0 / (math.pi * tool.diameter)
    if rpm is None:
        raise StepNcError(f"#{technology.id} MILLING_TECHNOLOGY: neither spindle nor cutspeed is given")
    if not rpm > 0:
        given = (f"spindle {technology.spindle:g} rev/s" if technology.spindle_rpm is not None
                 else f"cutspeed {technology.cutspeed:g} m/s")
        raise StepNcError(f"#{technology.id} MILLING_TECHNOLOGY: spindle speed {rpm:g} rpm ({given}); a cutting "
                          "operation needs a turning spindle")
    feed = technology.feed_mm_min
    teeth = operation.its_tool.its_tool_body.number_of_teeth
    if feed is None and technology.feedrate_per_tooth and teeth:
        feed = technology.feedrate_per_tooth * teeth * rpm
    if not feed or feed <= 0:
        raise StepNcError(f"#{technology.id} MILLING_TECHNOLOGY: no positive feedrate (nor feedrate_per_tooth "
                          "with a known number of teeth)")
    return feed, rpm, technology.spindle_clockwise


def plan_workingstep(step: Workingstep, tool: Tool, roughings: list, notes: list,
                     stock: InProcessStock | None = None) -> Operation | None:
    """The Operation of one workingstep; None (with a note) when it cannot be machined.

    ``roughings`` are the roughing operations of the same feature, used by finishing.  ``stock``
    is the material the workingsteps before it leave (approaches stop above it); None: the
    workingstep assumes what it assumes (its roughings done, the feature top the stock top).
    """
    operation, feature = step.its_operation, step.its_feature
    safe_z = float(step.its_secplane.position.location[2])
    if safe_z <= feature.top_z:
        raise StepNcError(f"#{step.id} MACHINING_WORKINGSTEP: its security plane (Z {safe_z:g}) is not above "
                          f"the feature #{feature.id} (Z {feature.top_z:g})")
    clearance_z = safe_z
    if operation.retract_plane is not None:
        if operation.retract_plane <= 0:
            raise StepNcError(f"#{operation.id} {operation.type_name}: retract_plane {operation.retract_plane:g} "
                              "must be above the feature (positive)")
        clearance_z = min(safe_z, feature.top_z + operation.retract_plane)
    if stock is not None and stock.highest() + APPROACH_GAP > clearance_z:
        # A retract plane over a feature below material not cut yet (a hole in a pocket floor
        # drilled before the pocket): travel above the material instead.
        clearance_z = min(safe_z, stock.highest() + APPROACH_GAP)
    feed, rpm, clockwise = feed_and_speed(operation, tool)

    def skip(reason):
        notes.append(f"workingstep #{step.id} '{step.its_id}' skipped: {reason}")

    if isinstance(operation, DrillingOperation) and isinstance(feature, RoundHole):
        motion = _hole(operation, feature, tool, clearance_z, feed, skip, stock)
    elif isinstance(operation, PlaneMilling) and isinstance(feature, PlanarFace):
        motion = _face(operation, feature, tool, clearance_z, feed, roughings, skip, stock)
    elif isinstance(operation, BottomAndSideMilling) and isinstance(feature, ClosedPocket):
        if operation.finishing:
            motion = _pocket_finishing(operation, feature, tool, clearance_z, feed, clockwise, roughings, skip,
                                       stock)
        else:
            motion = _pocket_roughing(operation, feature, tool, clearance_z, feed, clockwise, skip, stock)
    else:
        skip(f"{operation.type_name} #{operation.id} on a {type(feature).__name__} #{feature.id} "
             "is not supported")
        return None
    if motion is None:
        return None
    if motion.path.position is None:
        skip("nothing to cut (the feature has no depth left for this operation)")
        return None
    notes += [f"workingstep #{step.id} '{step.its_id}': {note}" for note in motion.notes]
    functions = operation.its_machine_functions
    return motion.operation(step.its_id, tool, rpm, clockwise, safe_z, bool(functions and functions.coolant),
                            f"#{step.id} {operation.type_name} {operation.its_id}")


# --------------------------------------------------------------------------- motion


class _Motion:
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
        self.region = None if region is None else _offset(region, LINK_TOLERANCE)  # None: never link
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
                self.path.line(points[0][0], points[0][1], z)
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
        """Full counter-clockwise turns through ``start``, centred where the circle fits the region."""
        if radius <= 0:
            return []
        turns = max(1, math.ceil((top - z) / (2 * math.pi * radius * math.tan(math.radians(angle))) - 1e-9))
        circle = np.linspace(0, 2 * math.pi, 64, endpoint=False)
        for direction in ((1, 0), (0, 1), (-1, 0), (0, -1)):
            centre = start + radius * np.array(direction, float)
            ring = centre + radius * np.column_stack([np.cos(circle), np.sin(circle)])
            if self.region is None or rg.contains_points(self.region, ring).all():
                return [(ARC_CCW, (start[0], start[1], top - (top - z) * k / turns), centre)
                        for k in range(1, turns + 1)]
        return []

    def operation(self, name, tool, rpm, clockwise, safe_z, coolant, comment) -> Operation:
        self.leave()
        x, y, _ = self.path.position
        self.path.rapid(x, y, safe_z)
        arrays = self.path.arrays()
        first = arrays["xyz"][0]
        return Operation(name=name, tool=tool, spindle_rpm=rpm, spindle_cw=clockwise,
                         clearance_z=self.clearance_z, safe_z=safe_z, start=[first[0], first[1], safe_z],
                         coolant=coolant, comment=comment, **arrays)


def _segment_inside(region: CrossSection | None, a, b) -> bool:
    """Whether the straight move a -> b stays in ``region`` (tested every 0.2 mm)."""
    if region is None:
        return False
    count = max(2, math.ceil(np.linalg.norm(np.subtract(b, a)) / 0.2) + 1)
    return bool(rg.contains_points(region, np.linspace(a, b, count)).all())


def _split_outside(chains: list, region: CrossSection) -> list:
    """Cut the chains where a step between rows leaves the region (a chord across a rounded
    inside corner), so the tool goes round instead of through the allowance."""
    grown = _offset(region, LINK_TOLERANCE)
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


def _levels(top: float, floor: float, step: float | None) -> list:
    """Cutting levels below ``top`` down to ``floor``, evenly spaced and at most ``step`` apart."""
    height = top - floor
    if height <= 1e-9:
        return []
    count = max(1, math.ceil(height / step - 1e-9)) if step else 1
    if count > MAX_PASSES:
        raise StepNcError(f"{height:g} mm cut {step:g} mm at a time needs {count} layers (more than {MAX_PASSES}): "
                          "check axial_cutting_depth")
    return [top - height * k / count for k in range(1, count + 1)]


def _ratio(value: float) -> float:
    """ISO 14649 ratios run 0..1; values above 1 are read as percent, as older files (the
    original Example 1) wrote them."""
    return value / 100 if value > 1 else value


def _stepover(diameter: float, overlap: float | None, radial: float | None) -> float:
    """From the overlap (a ratio of the diameter) and the radial cutting depth: the smaller
    when both are given."""
    candidates = []
    if overlap is not None:
        candidates.append(diameter * (1 - _ratio(overlap)))
    if radial:
        candidates.append(radial)
    stepover = min(candidates) if candidates else diameter * DEFAULT_STEPOVER_RATIO
    if stepover < MIN_STEPOVER:
        raise StepNcError(f"stepover {stepover:g} mm (overlap {overlap}, radial depth {radial}) is below "
                          f"{MIN_STEPOVER} mm")
    return stepover


# --------------------------------------------------------------------------- regions


def _offset(region: CrossSection, delta: float) -> CrossSection:
    """Round-join offset with arcs within CHORD_TOLERANCE (finer than region.offset, so finishing
    passes keep the tool edge on the wall to a few microns)."""
    if delta == 0:
        return region
    radius = abs(delta)
    segments = 720 if radius <= CHORD_TOLERANCE else min(
        3600, max(8, math.ceil(math.pi / math.acos(1 - CHORD_TOLERANCE / radius))))
    return region.offset(delta, JoinType.Round, 2.0, segments)


def _empty(region: CrossSection) -> bool:
    return region.area() < rg.MIN_AREA


def centre_region(pocket: ClosedPocket, distance: float) -> CrossSection:
    """Where a tool centre stays ``distance`` (tool radius + allowance) inside the pocket walls.

    The pocket's vertical edges are rounded to the orthogonal radius R.  A disc of radius
    distance >= R inside the outline is inside the rounded pocket too, so then the outline is
    offset once; otherwise the outline shrunk by R grows by R - distance.  One offset instead of
    three keeps the corners free of the slivers that polygonal arcs leave when offset again.
    """
    region = rg.from_loops([pocket.outline()], f"pocket #{pocket.id} '{pocket.its_id}'")
    radius = pocket.orthogonal_radius or 0.0
    if distance >= radius:
        return _offset(region, -distance)
    return _offset(_offset(region, -radius), radius - distance)


def pocket_region(pocket: ClosedPocket) -> CrossSection:
    """The pocket in world XY, its vertical edges rounded to the orthogonal radius."""
    return centre_region(pocket, 0.0)


def roughing_reach(pocket: ClosedPocket, roughing: BottomAndSideMilling) -> CrossSection:
    """What a roughing operation's tool reaches: the pocket less allowance_side, and less the
    round corners a tool of that radius leaves."""
    radius = roughing.its_tool.its_tool_body.dimension.diameter / 2
    return _offset(centre_region(pocket, radius + (roughing.allowance_side or 0.0)), radius)


def finishing_leftover(pocket: ClosedPocket, roughings: list) -> CrossSection:
    """The part of the pocket the roughing operations leave along the walls (the region pocket
    finishing cuts above the rough floor)."""
    region = pocket_region(pocket)
    for roughing in roughings:
        region = region - roughing_reach(pocket, roughing)
    return region


def _rings(region: CrossSection, distances, counter_clockwise: bool, start_xy) -> list:
    """Closed loops of the region offset inward by each distance, in the given order, each
    started near the end of the one before and run in the given direction."""
    rings = []
    here = np.asarray(start_xy, float)
    for distance in distances:
        loops = [np.vstack([loop, loop[:1]]) for loop in rg.loops(_offset(region, -distance))]
        for loop, index in rg.order_loops_nearest(loops, here):
            loop = rg.rotate_closed(loop, index)
            ccw = rg.signed_area(loop[:-1]) > 0
            rings.append(loop if ccw == counter_clockwise else loop[::-1])
            here = rings[-1][-1]
    return rings


def _ring_distances(region: CrossSection, stepover: float) -> list:
    """0, stepover, 2 stepover, ... while the region offset inward by it is not empty."""
    distances = []
    while not _empty(_offset(region, -len(distances) * stepover)):
        distances.append(len(distances) * stepover)
        if len(distances) > MAX_PASSES:
            raise StepNcError(f"more than {MAX_PASSES} contour passes at a {stepover:g} mm stepover")
    return distances


def _counter_clockwise(strategy, spindle_clockwise: bool) -> bool:
    """Ring direction: CONTOUR_PARALLEL's own; otherwise climb milling along the pocket wall."""
    if isinstance(strategy, ContourParallel):
        return strategy.rotation_direction == "CCW"
    return spindle_clockwise


def _raster_angle(strategy, pocket: ClosedPocket) -> float:
    """Degrees from +X of the feed direction (feature coordinates; default the feature's x axis)."""
    local = strategy.feed_direction or (1.0, 0.0, 0.0)
    world = pocket.feature_placement.direction_to_parent(local)
    return math.degrees(math.atan2(world[1], world[0]))


def _fill(region: CrossSection, strategy, stepover: float, radius: float, pocket: ClosedPocket,
          spindle_clockwise: bool) -> list:
    """Tool-centre paths that clear ``region``: a zigzag or strokes plus a ring along its outline,
    or CONTOUR_PARALLEL rings from the inside out (their spacing at most the tool radius, so
    nothing stands in the middle)."""
    ccw = _counter_clockwise(strategy, spindle_clockwise)
    if isinstance(strategy, ContourParallel):
        distances = _ring_distances(region, min(stepover, radius))
        return _rings(region, distances[::-1], ccw, rg.centroid(region))
    angle = _raster_angle(strategy, pocket)
    if isinstance(strategy, Bidirectional):
        turn = 180.0 if strategy.stepover_direction == "RIGHT" else 0.0
        chains = _split_outside(rg.zigzag(region, stepover, angle + turn), region)
    else:
        feed = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
        chains = []
        for chain in rg.zigzag(region, stepover, angle):
            for stroke in chain.reshape(-1, 2, 2):
                chains.append(stroke if (stroke[1] - stroke[0]) @ feed >= 0 else stroke[::-1])
    return chains + _rings(region, [0.0], ccw, chains[-1][-1] if chains else rg.centroid(region))


# --------------------------------------------------------------------------- features


def _face(operation: PlaneMilling, face: PlanarFace, tool: Tool, clearance_z, feed, roughings, skip, stock=None):
    """Facing strokes layer by layer; finishing starts below what roughing of the face left."""
    strategy = operation.its_machining_strategy or Bidirectional(None, None, None, None, None)
    if isinstance(strategy, ContourParallel):
        skip("CONTOUR_PARALLEL facing of a PLANAR_FACE is not supported")
        return None
    stepover = _stepover(tool.diameter, strategy.overlap, None)
    floor = face.bottom_z + (operation.allowance_bottom or 0.0)
    start = face.top_z
    if roughings:
        start = min(face.bottom_z + (rough.allowance_bottom or 0.0) for rough in roughings)
    strokes = _facing_strokes(face, strategy, tool.radius, stepover)
    if isinstance(strategy, Bidirectional):
        paths = [np.vstack([s if k % 2 == 0 else s[::-1] for k, s in enumerate(strokes)])]
    else:
        paths = strokes
    motion = _Motion(clearance_z, feed, operation.approach, operation.retract, stock=stock, radius=tool.radius)
    cleared = start
    for z in _levels(start, floor, operation.axial_cutting_depth or tool.flute_length):
        motion.cut(paths, z, cleared)
        cleared = z
    return motion


def _facing_strokes(face: PlanarFace, strategy, radius: float, stepover: float) -> list:
    """Straight strokes (each a (2, 2) array) along the feed direction over the face, the first on
    the right, stepping left (or the other way for stepover_direction RIGHT).  The tool runs
    out past both ends, and the outer strokes overhang the sides by the overlap width."""
    local = strategy.feed_direction or face.course_of_travel.its_direction
    direction = face.feature_placement.direction_to_parent(local)[:2]
    direction = direction / np.linalg.norm(direction)
    left = np.array([-direction[1], direction[0]])
    corners = face.corners()
    along, across = corners @ direction, corners @ left
    start, end = along.min() - radius - FACING_RUNOUT, along.max() + radius + FACING_RUNOUT
    overhang = max(0.0, 2 * radius - stepover)
    first, last = across.min() + radius - overhang, across.max() - radius + overhang
    if last <= first:
        offsets = np.array([(across.min() + across.max()) / 2])
    else:
        count = math.ceil((last - first) / stepover - 1e-9) + 1
        if count > MAX_PASSES:
            raise StepNcError(f"planar face #{face.id}: {count} facing strokes (more than {MAX_PASSES}) at a "
                              f"{stepover:g} mm stepover")
        offsets = np.linspace(first, last, count)
    if getattr(strategy, "stepover_direction", None) == "RIGHT":
        offsets = offsets[::-1]
    return [np.array([start * direction + o * left, end * direction + o * left]) for o in offsets]


def _pocket_roughing(operation, pocket, tool, clearance_z, feed, spindle_clockwise, skip, stock=None):
    """The pocket less the allowances, cleared layer by layer."""
    strategy = operation.its_machining_strategy or Bidirectional(None, None, None, None, None)
    centres = centre_region(pocket, tool.radius + (operation.allowance_side or 0.0))
    if _empty(centres):
        skip(f"the {tool.diameter:g} mm tool with allowance {operation.allowance_side or 0:g} mm does not fit "
             f"in pocket #{pocket.id}")
        return None
    stepover = _stepover(tool.diameter, strategy.overlap, operation.radial_cutting_depth)
    paths = _fill(centres, strategy, stepover, tool.radius, pocket, spindle_clockwise)
    motion = _Motion(clearance_z, feed, operation.approach, operation.retract, centres, stock, tool.radius)
    floor = pocket.bottom_z + (operation.allowance_bottom or 0.0)
    cleared = pocket.top_z
    for z in _levels(pocket.top_z, floor, operation.axial_cutting_depth or tool.flute_length):
        motion.cut(paths, z, cleared, link=not isinstance(strategy, Unidirectional))
        cleared = z
    return motion


def _pocket_finishing(operation, pocket, tool, clearance_z, feed, spindle_clockwise, roughings, skip, stock=None):
    """Rings over what roughing left along the walls at every layer; the whole floor below the
    rough floor (everything at every layer when nothing roughs the pocket)."""
    strategy = operation.its_machining_strategy or ContourParallel(None, None, "CCW", None)
    centres = centre_region(pocket, tool.radius + (operation.allowance_side or 0.0))
    if _empty(centres):
        skip(f"the {tool.diameter:g} mm tool does not fit in pocket #{pocket.id}")
        return None
    stepover = _stepover(tool.diameter, strategy.overlap, operation.radial_cutting_depth)
    floor_paths = _fill(centres, strategy, stepover, tool.radius, pocket, spindle_clockwise)
    rough_floor = pocket.bottom_z
    wall_paths = floor_paths
    if roughings:
        rough_floor = min(pocket.bottom_z + (rough.allowance_bottom or 0.0) for rough in roughings)
        leftover = finishing_leftover(pocket, roughings)
        distances = []
        while _sweeps(centres, len(distances) * stepover, tool.radius, leftover):
            distances.append(len(distances) * stepover)
            if len(distances) > MAX_PASSES:
                raise StepNcError(f"more than {MAX_PASSES} finishing passes at a {stepover:g} mm stepover")
        ccw = _counter_clockwise(strategy, spindle_clockwise)
        wall_paths = _rings(centres, (distances or [0.0])[::-1], ccw, rg.centroid(centres))
    motion = _Motion(clearance_z, feed, operation.approach, operation.retract, centres, stock, tool.radius)
    if (pocket.planar_radius or 0.0) > tool.corner_radius + 1e-9:
        motion.notes.append(f"the floor fillet R{pocket.planar_radius:g} is cut with the tool's corner "
                            f"radius R{tool.corner_radius:g}")
    floor = pocket.bottom_z + (operation.allowance_bottom or 0.0)
    cleared = pocket.top_z
    for z in _levels(pocket.top_z, floor, operation.axial_cutting_depth or tool.flute_length):
        below_rough_floor = z < rough_floor - 1e-9
        motion.cut(floor_paths if below_rough_floor else wall_paths, z, cleared,
                   link=not (below_rough_floor and isinstance(strategy, Unidirectional)))
        cleared = z
    return motion


def _sweeps(centres: CrossSection, distance: float, radius: float, leftover: CrossSection) -> bool:
    """Does the ring ``distance`` inside the centre region sweep over any of ``leftover``?"""
    ring_region = _offset(centres, -distance)
    if _empty(ring_region):
        return False
    swept = _offset(ring_region, radius) - _offset(ring_region, -radius)
    return (swept ^ leftover).area() > rg.MIN_AREA


def drill_breakthrough(tool: CuttingTool) -> float:
    """How far below a through hole's bottom the drill tip goes so the full diameter clears it:
    the point's length, radius * tan(tool_top_angle), plus BREAKTHROUGH_CLEARANCE."""
    dimension = tool.its_tool_body.dimension
    angle = dimension.tool_top_angle if dimension.tool_top_angle is not None else DEFAULT_TOOL_TOP_ANGLE
    if not 0 <= angle < 90:
        raise StepNcError(f"#{tool.id} MILLING_CUTTING_TOOL '{tool.its_id}': tool_top_angle {angle:g} degrees "
                          "is not a drill point (0 <= angle < 90, measured from the plane square to the axis)")
    return dimension.diameter / 2 * math.tan(math.radians(angle)) + BREAKTHROUGH_CLEARANCE


def _hole(operation: DrillingOperation, hole: RoundHole, tool: Tool, clearance_z, feed, skip, stock=None):
    """A straight feed to depth at the hole centre (no canned cycle, so every post can write it);
    DRILLING_TYPE_STRATEGY's reduced feeds over the first and last depths are honoured."""
    if operation.cutting_depth is None and operation.type_name == "CENTER_DRILLING":
        skip("CENTER_DRILLING needs a cutting_depth (the hole's depth is not the centre drill's)")
        return None
    x, y = hole.centre
    top = hole.top_z
    bottom = top - operation.cutting_depth if operation.cutting_depth is not None else hole.bottom_z
    breakthrough = 0.0
    why = ""
    if operation.cutting_depth is None and hole.bottom_condition in THROUGH_CONDITIONS \
            and operation.type_name == "DRILLING":
        if operation.overcut_length is not None:
            breakthrough, why = operation.overcut_length, "the operation's overcut_length"
        elif operation.its_tool.its_tool_body.type_name in POINTED_DRILL_BODIES:
            breakthrough = drill_breakthrough(operation.its_tool)
            why = f"point length + {BREAKTHROUGH_CLEARANCE:g} mm"
        bottom -= breakthrough
    motion = _Motion(clearance_z, feed, stock=stock, radius=tool.radius)
    if breakthrough:
        motion.notes.append(f"through hole: the drill goes {breakthrough:.3f} mm below the hole bottom "
                            f"({why}) to Z {bottom:.3f}")
    entry = motion.entry_height((x, y), top)
    motion.path.rapid(x, y, clearance_z)
    if entry < clearance_z:
        motion.path.rapid(x, y, entry)
    stops = [(bottom, feed)]
    strategy = operation.its_machining_strategy
    if strategy is not None:
        if strategy.depth_of_end and strategy.reduced_feed_at_end:
            stops = [(bottom + strategy.depth_of_end, feed), (bottom, feed * _ratio(strategy.reduced_feed_at_end))]
        if strategy.depth_of_start and strategy.reduced_feed_at_start:
            stops.insert(0, (max(top - strategy.depth_of_start, bottom), feed * _ratio(strategy.reduced_feed_at_start)))
        if strategy.reduced_cut_at_start or strategy.reduced_cut_at_end:
            motion.notes.append("the reduced spindle speeds of DRILLING_TYPE_STRATEGY are not written "
                                "(one spindle speed per operation)")
    if operation.dwell_time_bottom:
        motion.notes.append(f"no dwell of {operation.dwell_time_bottom:g} s at the bottom (not written)")
    if operation.spindle_stop_at_bottom:
        motion.notes.append("the spindle is not stopped at the bottom (not written); the reamer is fed out")
    for z, rate in stops:
        if z < motion.path.position[2] - 1e-9:
            motion.path.line(x, y, z, rate)
    # REAMING pulls out at feed unless told otherwise: a rapid exit would mark the bore.
    retract = operation.feed_on_retract or (1.0 if operation.type_name == "REAMING" else None)
    if retract:
        motion.path.line(x, y, entry, feed * retract)
    motion.path.retract()
    return motion


# --------------------------------------------------------------------------- pockets -> ISO 14649


@dataclass(frozen=True)
class PocketSpec:
    """A pocket to write: a closed outline in XY (mm, at the stock top), its depth below the
    top, and optionally the radius of its vertical corners (orthogonal_radius)."""

    name: str
    outline: tuple
    depth: float
    corner_radius: float = 0.0


def _as_rectangle(outline: np.ndarray):
    """(centre, unit x, length, width) when the outline is a rectangle, else None."""
    if len(outline) != 4:
        return None
    edges = np.roll(outline, -1, axis=0) - outline
    lengths = np.linalg.norm(edges, axis=1)
    for k in range(4):
        if abs(edges[k] @ edges[(k + 1) % 4]) > 1e-9 * lengths[k] * lengths[(k + 1) % 4]:
            return None
    return outline.mean(axis=0), edges[0] / lengths[0], float(lengths[0]), float(lengths[1])


def pockets_to_part21(stock_box, pockets, tool: Tool, *, feed: float = 600.0, spindle_rpm: float = 10000.0,
                      axial_depth: float | None = None, allowance_side: float = 0.5,
                      allowance_bottom: float = 0.2, overlap: float = 0.5, ramp_angle: float = 5.0,
                      retract_height: float = 5.0, security_height: float = 10.0,
                      name: str = "KEZURI POCKETS") -> str:
    """An ISO 14649 file (Part 21 text) that roughs and finishes each pocket in turn.

    stock_box: ((xmin, ymin, zmin), (xmax, ymax, zmax)) of the stock, written as a BLOCK; the
    pockets start at its top.  Per pocket: a CLOSED_POCKET with a RECTANGULAR_CLOSED_PROFILE
    (when the outline is a rectangle) or a GENERAL_CLOSED_PROFILE POLYLINE, a roughing
    workingstep (BOTTOM_AND_SIDE_ROUGH_MILLING, BIDIRECTIONAL along X, ``overlap`` a ratio of
    the tool diameter, leaving the allowances) and a finishing one (CONTOUR_PARALLEL, climb).
    Both plunge on a ramp of ``ramp_angle`` degrees (0: straight down the tool axis) and cut
    layers of ``axial_depth`` (default: the tool radius).  Heights are above the stock top.
    """
    (x0, y0, z0), (x1, y1, z1) = (tuple(map(float, corner)) for corner in stock_box)
    if not (x1 > x0 and y1 > y0 and z1 > z0):
        raise StepNcError(f"stock box {stock_box} has no volume: give (min corner, max corner)")
    if tool.kind not in ("flat", "ball", "bull"):
        raise StepNcError(f"pockets need an end mill, not a {tool.kind}")
    for value, what in ((feed, "feed"), (spindle_rpm, "spindle speed"), (retract_height, "retract height"),
                        (security_height, "security height")):
        if not (math.isfinite(value) and value > 0):
            raise StepNcError(f"{what} must be a positive number, got {value}")
    if not 0 <= overlap < 1:
        raise StepNcError(f"overlap is a ratio of the tool diameter, 0 <= overlap < 1; got {overlap}")
    if not 0 <= ramp_angle <= 90:
        raise StepNcError(f"ramp angle must be 0..90 degrees, got {ramp_angle}")
    axial_depth = tool.radius if axial_depth is None else axial_depth
    pockets = list(pockets)
    for pocket in pockets:
        rg.validate_loop(pocket.outline, f"pocket {pocket.name!r}")
        if not 0 < pocket.depth <= z1 - z0:
            raise StepNcError(f"pocket {pocket.name!r}: depth {pocket.depth} must be above 0 and at most the stock "
                             f"height {z1 - z0:g}")
        if pocket.corner_radius < 0:
            raise StepNcError(f"pocket {pocket.name!r}: corner radius must not be negative")

    w = Part21Writer()
    project, workplan, workpiece = w.reserve(), w.reserve(), w.reserve()
    tolerance = w.add("PLUS_MINUS_VALUE", 0.01, 0.01, 3)

    def placement(label, location, x_axis=(1.0, 0.0)):
        return w.add("AXIS2_PLACEMENT_3D", label, w.add("CARTESIAN_POINT", label, [float(v) for v in location]),
                     w.add("DIRECTION", "AXIS", [0.0, 0.0, 1.0]),
                     w.add("DIRECTION", "REF_DIRECTION", [float(x_axis[0]), float(x_axis[1]), 0.0]))

    def length(value):
        return w.add("TOLERANCED_LENGTH_MEASURE", float(value), tolerance)

    origin = placement("ORIGIN", (0.0, 0.0, 0.0))
    secplane = w.add("PLANE", "SECURITY PLANE", placement("SECURITY PLANE", (0.0, 0.0, z1 + security_height)))
    block = w.add("BLOCK", "STOCK", placement("STOCK", (x0, y0, z0)), x1 - x0, y1 - y0, z1 - z0)
    w.define(workpiece, "WORKPIECE", "STOCK", UNSET, UNSET, UNSET, UNSET, block, [])
    setup = w.add("SETUP", "SETUP", origin, secplane, [w.add("WORKPIECE_SETUP", workpiece, origin, UNSET, UNSET, [])])
    body = {"flat": "ENDMILL", "ball": "BALL_ENDMILL", "bull": "BULLNOSE_ENDMILL"}[tool.kind]
    dimension = w.add("MILLING_TOOL_DIMENSION", float(tool.diameter), UNSET, UNSET, float(tool.flute_length),
                      float(tool.corner_radius), UNSET, UNSET)
    # The IR tool has no gauge length: the cutting component records the flute length.
    cutting_tool = w.add("MILLING_CUTTING_TOOL", tool.name or tool.describe(),
                         w.add(body, dimension, UNSET, UNSET, UNSET, UNSET),
                         [w.add("CUTTING_COMPONENT", float(tool.flute_length), UNSET, UNSET, UNSET, UNSET)],
                         UNSET, UNSET, UNSET)
    technology = w.add("MILLING_TECHNOLOGY", feed / 60000.0, Enum("TCP"), UNSET, -spindle_rpm / 60.0, UNSET,
                       False, False, False, UNSET)
    functions = w.add("MILLING_MACHINE_FUNCTIONS", False, UNSET, UNSET, False, UNSET, [], False, UNSET, UNSET, [])
    approach = w.add("PLUNGE_RAMP", UNSET, float(ramp_angle)) if ramp_angle else w.add("PLUNGE_TOOLAXIS", UNSET)
    bottom = w.add("PLANAR_POCKET_BOTTOM_CONDITION")
    rough_strategy = w.add("BIDIRECTIONAL", float(overlap), True, w.add("DIRECTION", "FEED", [1.0, 0.0, 0.0]),
                           Enum("LEFT"), UNSET)
    finish_strategy = w.add("CONTOUR_PARALLEL", float(overlap), True, Enum("CCW"), Enum("CLIMB"))

    steps = []
    for pocket in pockets:
        outline = np.asarray(pocket.outline, float)[:, :2]
        if np.allclose(outline[0], outline[-1]):
            outline = outline[:-1]
        rectangle = _as_rectangle(outline)
        if rectangle is not None:
            centre, x_axis, profile_length, profile_width = rectangle
            where = placement(pocket.name, (centre[0], centre[1], z1), x_axis)
            profile = w.add("RECTANGULAR_CLOSED_PROFILE", UNSET, length(profile_width), length(profile_length))
        else:
            where = placement(pocket.name, (0.0, 0.0, z1))
            corners = [w.add("CARTESIAN_POINT", "", [float(x), float(y), 0.0]) for x, y in outline]
            profile = w.add("GENERAL_CLOSED_PROFILE", UNSET, w.add("POLYLINE", pocket.name, corners + corners[:1]))
        depth = w.add("PLANE", f"DEPTH {pocket.name}", placement(f"DEPTH {pocket.name}", (0.0, 0.0, -pocket.depth)))
        rough, finish = w.reserve(), w.reserve()
        feature = w.add("CLOSED_POCKET", pocket.name, workpiece, [rough, finish], where, depth, [], UNSET, bottom,
                        UNSET, length(pocket.corner_radius) if pocket.corner_radius else UNSET, profile)
        w.define(rough, "BOTTOM_AND_SIDE_ROUGH_MILLING", UNSET, UNSET, f"ROUGH {pocket.name}", float(retract_height),
                 UNSET, cutting_tool, technology, functions, UNSET, approach, UNSET, rough_strategy,
                 float(axial_depth), UNSET, float(allowance_side), float(allowance_bottom))
        w.define(finish, "BOTTOM_AND_SIDE_FINISH_MILLING", UNSET, UNSET, f"FINISH {pocket.name}",
                 float(retract_height), UNSET, cutting_tool, technology, functions, UNSET, approach, UNSET,
                 finish_strategy, float(axial_depth), UNSET, UNSET, UNSET)
        steps.append(w.add("MACHINING_WORKINGSTEP", f"WS ROUGH {pocket.name}", secplane, feature, rough, UNSET))
        steps.append(w.add("MACHINING_WORKINGSTEP", f"WS FINISH {pocket.name}", secplane, feature, finish, UNSET))
    w.define(workplan, "WORKPLAN", "MAIN WORKPLAN", steps, UNSET, setup, UNSET)
    w.define(project, "PROJECT", name, workplan, [workpiece], UNSET, UNSET, UNSET)
    return w.text(description=(f"ISO 14649 workplan: {len(pockets)} pockets, rough and finish",), name=name)
