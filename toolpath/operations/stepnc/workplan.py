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
import re

import numpy as np
from manifold3d import CrossSection

from ...engines import region as rg
from ...ir.errors import InputError
from ...ir.program import ARC_CW, Operation, Program, Tool
from .freeform import plan_freeform
from .hole_bottoms import DEFAULT_TOOL_TOP_ANGLE, flat_bottom_notes, through_bottom_notes  # noqa: F401
from .inprocess import InProcessStock
from .errors import StepNcError
from .features import ClosedPocket, PlanarFace, RoundHole, Slot
from .model import Workingstep
from .process import Bidirectional, BottomAndSideMilling, ContourBidirectional, ContourParallel, CuttingTool, DrillingOperation, FreeformOperation, PlaneMilling, PlungeHelix, PlungeRamp, Unidirectional
from .loaded import LoadedWorkplan, load_workplan, workplan_from_text, workplan_of  # noqa: F401 (re-exported)
from .motion import (APPROACH_GAP, DEFAULT_STEPOVER_RATIO, LINK_TOLERANCE, MAX_PASSES, MIN_STEPOVER, Motion, cut_levels, helix_moves,
                     helix_pitch, is_empty, iso_ratio, round_offset, split_outside, stepover_of)
from .fit import check_fit
from .pockets import PocketSpec, pockets_to_part21  # noqa: F401 (re-exported)
from .technology import MissingTechnology, feed_and_speed  # noqa: F401 (re-exported)
from .tools import BODY_LABELS, tool_for, tool_numbering, tool_numbers  # noqa: F401 (re-exported)

# A facing stroke starts and ends this far (mm) beyond the tool radius outside the face.
FACING_RUNOUT = 2.0
# A through hole is drilled through: the drill's full diameter passes the stock bottom by this much (mm)
# beyond the point's length.
BREAKTHROUGH_CLEARANCE = 2.0
POINTED_DRILL_BODIES = ("TWIST_DRILL", "TAPERED_DRILL")
THROUGH_CONDITIONS = ("THROUGH_BOTTOM_CONDITION", "THROUGH_POCKET_BOTTOM_CONDITION")
# A feature may reach this far (mm) below the stock bottom before it is refused (rounding in the file).
DEPTH_TOLERANCE = 1e-6


# --------------------------------------------------------------------------- workplan -> Program


def to_program(model: LoadedWorkplan, order=None, enabled=None, name: str | None = None, progress=None) -> Program:
    """The NC program of a workplan: one Operation per enabled workingstep, named after it.

    order:   workingstep instance ids in the order to machine them (every workingstep once);
             default the workplan's order.
    enabled: the ids to machine; default all.
    Tool numbers are the file's where its tool identifiers are numbers, else follow the first use
    in the workplan's own order (:func:`.tools.tool_numbering`), so reordering does not renumber
    tools.  Warnings (skipped entities, finishing before its roughing) go into
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
    numbering = tool_numbering(model.workingsteps)
    numbers = numbering.numbers
    position = {step.id: index for index, step in enumerate(sequence)}
    notes = list(model.warnings) + list(numbering.notes)
    bottom, source = stock_bottom(model)
    if bottom is None:
        notes.append("the stock bottom is unknown (no workpiece BLOCK and no through feature): feature depths "
                     "are not checked against the stock")
    elif source.startswith("the depth of through feature"):      # no BLOCK: said, never silent
        notes += through_bottom_notes([step.its_feature for step in model.workingsteps if getattr(
            step.its_feature, "bottom_condition", None) in THROUGH_CONDITIONS], bottom)
    operations = []
    stock = in_process_stock(model)
    for index, step in enumerate(sequence):
        if progress is not None:        # (fraction, text); what it raises (the panel's Esc) stops the conversion
            progress(index / len(sequence), f"workingstep #{step.id}")
        if step.id not in enabled:
            notes.append(f"workingstep #{step.id} '{step.its_id}' skipped: switched off (left out of the order to cut)")
            continue
        roughings = _roughings_of(step, model.workingsteps)
        for rough in roughings:
            if rough.id not in enabled or position[rough.id] > position[step.id]:
                notes.append(f"workingstep #{step.id} '{step.its_id}' assumes roughing #{rough.id} "
                             f"'{rough.its_id}' was done before it")
        try:
            check_fit(step)
            if bottom is not None:
                check_depth(step, bottom, source)
            tool = tool_for(step.its_operation.its_tool, numbers[step.its_operation.its_tool.id])
            operation = plan_workingstep(step, tool, [rough.its_operation for rough in roughings], notes, stock)
        except InputError as error:
            raise StepNcError(f"workingstep #{step.id} '{step.its_id}': {error}") from None
        if operation is not None:
            operations.append(operation)
            stock.cut(operation)
    notes += flat_bottom_notes(model.workingsteps, {op.source_id for op in operations})
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
    if isinstance(feature, (ClosedPocket, Slot)):
        return np.asarray(feature.outline(), float)[:, :2]
    if isinstance(feature, PlanarFace):
        return np.asarray(feature.corners(), float)[:, :2]
    if isinstance(feature, RoundHole):
        return np.asarray(feature.centre, float)[None, :] + np.array([[-1, -1], [1, 1]]) * feature.diameter / 2
    return None


def nothing_to_machine(notes) -> str:
    """Why a file gives nothing to cut: the reason of every workingstep left out (from the
    warnings of :func:`load_workplan` or the notes of :func:`to_program`)."""
    reasons = [note for note in notes if " skipped" in note] or list(notes)
    if not reasons:
        return "the workplan has no workingstep"
    return "no workingstep can be machined: " + "; ".join(reasons)


SKIPPED = re.compile(r"^workingstep #(\d+) '(.*)' skipped: (.*)$", re.DOTALL)


def skipped_workingsteps(notes) -> list:
    """[{"id", "name", "reason"}] of every workingstep the notes say was not cut (unsupported in the
    file, not plannable, or switched off), in the notes' order."""
    found = []
    for note in notes:
        match = SKIPPED.match(note)
        if match:
            found.append({"id": int(match.group(1)), "name": match.group(2), "reason": match.group(3)})
    return found


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
            # the file asks for breakthrough: up to what a drill's point needs to clear the stock bottom
            # (other tools: the clearance alone), the fixture's clearance under a through hole
            pointed = operation.type_name == "DRILLING" and \
                operation.its_tool.its_tool_body.type_name in POINTED_DRILL_BODIES
            bottom -= drill_breakthrough(operation.its_tool) if pointed else BREAKTHROUGH_CLEARANCE
            source += " and the breakthrough"
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
    def skip(reason):
        notes.append(f"workingstep #{step.id} '{step.its_id}' skipped: {reason}")

    checks: list = []
    try:
        feed, rpm, clockwise = feed_and_speed(operation, tool, checks,
                                              need_feed=not isinstance(operation, FreeformOperation))
    except MissingTechnology as error:
        skip(str(error))
        return None
    notes += [f"workingstep #{step.id} '{step.its_id}': {note}" for note in checks]

    if isinstance(operation, FreeformOperation):
        try:
            motion = plan_freeform(step, tool, clearance_z, stock)
        except MissingTechnology as error:      # no feed where NIST's files state it: the step, not the file
            skip(str(error))
            return None
    elif isinstance(operation, DrillingOperation) and isinstance(feature, RoundHole):
        motion = _hole(operation, feature, tool, clearance_z, feed, skip, stock)
    elif isinstance(operation, PlaneMilling) and isinstance(feature, PlanarFace):
        motion = _face(operation, feature, tool, clearance_z, feed, roughings, skip, stock)
    elif isinstance(operation, BottomAndSideMilling) and isinstance(feature, ClosedPocket):
        if operation.finishing:
            motion = _pocket_finishing(operation, feature, tool, clearance_z, feed, clockwise, roughings, skip,
                                       stock)
        else:
            motion = _pocket_roughing(operation, feature, tool, clearance_z, feed, clockwise, skip, stock)
    elif isinstance(operation, BottomAndSideMilling) and isinstance(feature, Slot) \
            and _slot_is_tool_wide(feature, tool, operation):
        motion = _slot_centreline(operation, feature, tool, clearance_z, feed, skip, stock)
    elif isinstance(operation, BottomAndSideMilling) and isinstance(feature, Slot):
        if operation.finishing:     # a slot wider than the tool: cut as the pocket its outline is
            motion = _pocket_finishing(operation, feature, tool, clearance_z, feed, clockwise, roughings, skip,
                                       stock)
        else:
            motion = _pocket_roughing(operation, feature, tool, clearance_z, feed, clockwise, skip, stock)
    elif isinstance(operation, BottomAndSideMilling) and isinstance(feature, RoundHole):
        motion = _hole_milling(operation, feature, tool, clearance_z, feed, clockwise, roughings, skip, stock)
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
    if not isinstance(operation, FreeformOperation):
        notes += [f"rapid movement #{rapid.id} '{rapid.its_id}' after workingstep #{step.id} left out: the path "
                  "planned for the workingstep makes its own links" for rapid in step.rapids_after]
    functions = operation.its_machine_functions
    return motion.operation(step.its_id, tool, rpm, clockwise, safe_z, bool(functions and functions.coolant),
                            f"#{step.id} {operation.type_name} {operation.its_id}", step.id)


# --------------------------------------------------------------------------- regions



def centre_region(pocket: ClosedPocket, distance: float) -> CrossSection:
    """Where a tool centre stays ``distance`` (tool radius + allowance) inside the pocket walls.

    The pocket's vertical edges are rounded to the orthogonal radius R.  A disc of radius
    distance >= R inside the outline is inside the rounded pocket too, so then the outline is
    offset once; otherwise the outline shrunk by R grows by R - distance.  One offset instead of
    three keeps the corners free of the slivers that polygonal arcs leave when offset again.
    """
    region = pocket.region() if isinstance(pocket, Slot) else \
        rg.from_loops([pocket.outline()], f"pocket #{pocket.id} '{pocket.its_id}'")
    radius = pocket.orthogonal_radius or 0.0
    if distance >= radius:
        return round_offset(region, -distance)
    return round_offset(round_offset(region, -radius), radius - distance)


def pocket_region(pocket: ClosedPocket) -> CrossSection:
    """The pocket in world XY, its vertical edges rounded to the orthogonal radius."""
    return centre_region(pocket, 0.0)


def roughing_reach(pocket: ClosedPocket, roughing: BottomAndSideMilling) -> CrossSection:
    """What a roughing operation's tool reaches: the pocket less allowance_side, and less the
    round corners a tool of that radius leaves."""
    radius = roughing.its_tool.its_tool_body.dimension.diameter / 2
    return round_offset(centre_region(pocket, radius + (roughing.allowance_side or 0.0)), radius)


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
        loops = [np.vstack([loop, loop[:1]]) for loop in rg.loops(round_offset(region, -distance))]
        for loop, index in rg.order_loops_nearest(loops, here):
            loop = rg.rotate_closed(loop, index)
            ccw = rg.signed_area(loop[:-1]) > 0
            rings.append(loop if ccw == counter_clockwise else loop[::-1])
            here = rings[-1][-1]
    return rings


def _ring_distances(region: CrossSection, stepover: float) -> list:
    """0, stepover, 2 stepover, ... while the region offset inward by it is not empty."""
    distances = []
    while not is_empty(round_offset(region, -len(distances) * stepover)):
        distances.append(len(distances) * stepover)
        if len(distances) > MAX_PASSES:
            raise StepNcError(f"more than {MAX_PASSES} contour passes at a {stepover:g} mm stepover")
    return distances


def _counter_clockwise(strategy, spindle_clockwise: bool) -> bool:
    """Ring direction: CONTOUR_PARALLEL's (CONTOUR_BIDIRECTIONAL's) own; a CONTOUR_BIDIRECTIONAL's spiral_cutmode;
    otherwise climb milling along the pocket wall."""
    if getattr(strategy, "rotation_direction", None) in ("CW", "CCW"):
        return strategy.rotation_direction == "CCW"
    if getattr(strategy, "spiral_cutmode", None) == "CONVENTIONAL":
        return not spindle_clockwise
    return spindle_clockwise


def _raster_angle(strategy, pocket: ClosedPocket) -> float:
    """Degrees from +X of the feed direction (feature coordinates; default the feature's x axis)."""
    local = strategy.feed_direction or getattr(pocket, "course", (1.0, 0.0, 0.0))   # a slot: along it
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
    if isinstance(strategy, ContourBidirectional) and strategy.contour_first:     # the contour, then the zigzag
        ring = _rings(region, [0.0], ccw, rg.centroid(region))
        turn = 180.0 if strategy.stepover_direction == "RIGHT" else 0.0
        return ring + split_outside(rg.zigzag(region, stepover, angle + turn), region)
    if isinstance(strategy, Bidirectional):
        turn = 180.0 if strategy.stepover_direction == "RIGHT" else 0.0
        chains = split_outside(rg.zigzag(region, stepover, angle + turn), region)
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
    stepover = stepover_of(tool.diameter, strategy.overlap, None)
    floor = face.bottom_z + (operation.allowance_bottom or 0.0)
    start = face.top_z
    if roughings:
        start = min(face.bottom_z + (rough.allowance_bottom or 0.0) for rough in roughings)
    strokes = _facing_strokes(face, strategy, tool.radius, stepover)
    if isinstance(strategy, Bidirectional):
        paths = [np.vstack([s if k % 2 == 0 else s[::-1] for k, s in enumerate(strokes)])]
    else:
        paths = strokes
    motion = Motion(clearance_z, feed, operation.approach, operation.retract, stock=stock, radius=tool.radius)
    if isinstance(strategy, ContourBidirectional):
        motion.notes.append(f"{'CONTOUR_BIDIRECTIONAL' if strategy.contour_first else 'BIDIRECTIONAL_CONTOUR'}: no "
                            f"contour pass on planar face #{face.id}, its strokes run out past the face's edges")
    cleared = start
    for z in cut_levels(start, floor, operation.axial_cutting_depth or tool.flute_length):
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
    if is_empty(centres):
        skip(f"the {tool.diameter:g} mm tool with allowance {operation.allowance_side or 0:g} mm does not fit "
             f"in pocket #{pocket.id}")
        return None
    stepover = stepover_of(tool.diameter, strategy.overlap, operation.radial_cutting_depth)
    paths = _fill(centres, strategy, stepover, tool.radius, pocket, spindle_clockwise)
    motion = Motion(clearance_z, feed, operation.approach, operation.retract, centres, stock, tool.radius)
    floor = pocket.bottom_z + (operation.allowance_bottom or 0.0)
    cleared = pocket.top_z
    for z in cut_levels(pocket.top_z, floor, operation.axial_cutting_depth or tool.flute_length):
        motion.cut(paths, z, cleared, link=not isinstance(strategy, Unidirectional))
        cleared = z
    return motion


def _pocket_finishing(operation, pocket, tool, clearance_z, feed, spindle_clockwise, roughings, skip, stock=None):
    """Rings over what roughing left along the walls at every layer; the whole floor below the
    rough floor (everything at every layer when nothing roughs the pocket)."""
    strategy = operation.its_machining_strategy or ContourParallel(None, None, "CCW", None)
    centres = centre_region(pocket, tool.radius + (operation.allowance_side or 0.0))
    if is_empty(centres):
        skip(f"the {tool.diameter:g} mm tool does not fit in pocket #{pocket.id}")
        return None
    stepover = stepover_of(tool.diameter, strategy.overlap, operation.radial_cutting_depth)
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
    motion = Motion(clearance_z, feed, operation.approach, operation.retract, centres, stock, tool.radius)
    if (pocket.planar_radius or 0.0) > tool.corner_radius + 1e-9:
        motion.notes.append(f"the floor fillet R{pocket.planar_radius:g} is cut with the tool's corner "
                            f"radius R{tool.corner_radius:g}")
    floor = pocket.bottom_z + (operation.allowance_bottom or 0.0)
    cleared = pocket.top_z
    for z in cut_levels(pocket.top_z, floor, operation.axial_cutting_depth or tool.flute_length):
        below_rough_floor = z < rough_floor - 1e-9
        motion.cut(floor_paths if below_rough_floor else wall_paths, z, cleared,
                   link=not (below_rough_floor and isinstance(strategy, Unidirectional)))
        cleared = z
    return motion


def _sweeps(centres: CrossSection, distance: float, radius: float, leftover: CrossSection) -> bool:
    """Does the ring ``distance`` inside the centre region sweep over any of ``leftover``?"""
    ring_region = round_offset(centres, -distance)
    if is_empty(ring_region):
        return False
    swept = round_offset(ring_region, radius) - round_offset(ring_region, -radius)
    return (swept ^ leftover).area() > rg.MIN_AREA


# A slot at most this much (mm) wider than the tool (plus twice allowance_side) is cut along its centre line.
SLOT_FIT = 1e-3


def _slot_is_tool_wide(slot: Slot, tool: Tool, operation: BottomAndSideMilling) -> bool:
    return slot.width - 2 * (tool.radius + (operation.allowance_side or 0.0)) <= SLOT_FIT


def _slot_centreline(operation: BottomAndSideMilling, slot: Slot, tool: Tool, clearance_z, feed, skip, stock=None):
    """A slot as wide as the tool: layer by layer along its centre line, back and forth.  At an open
    end the tool runs out until it is clear of the part (radius + FACING_RUNOUT); at a radiused end it
    stops at the end's centre (the tool makes the half circle); at a flat end its edge stops on the end
    (the corners keep the tool's radius, noted)."""
    if tool.kind == "drill":
        skip(f"a {tool.label or 'drill'} cannot mill slot #{slot.id}: give an end mill")
        return None
    allowance = operation.allowance_side or 0.0
    if slot.width - 2 * (tool.radius + allowance) < -SLOT_FIT:
        skip(f"the {tool.diameter:g} mm tool (allowance {allowance:g} mm) is wider than the {slot.width:g} mm "
             f"slot #{slot.id}")
        return None
    reach = {"OPEN_SLOT_END_TYPE": tool.radius + FACING_RUNOUT, "RADIUSED_SLOT_END_TYPE": 0.0,
             "FLAT_SLOT_END_TYPE": -tool.radius - allowance}
    line = slot.centreline()
    if not slot.closed:
        line = _stretched(line, reach[slot.ends[0]], reach[slot.ends[1]])
    if line is None:
        skip(f"slot #{slot.id} is shorter than the {tool.diameter:g} mm tool")
        return None
    motion = Motion(clearance_z, feed, operation.approach, operation.retract, stock=stock, radius=tool.radius)
    if "FLAT_SLOT_END_TYPE" in slot.ends:
        motion.notes.append(f"the flat end of slot #{slot.id} keeps the tool's radius R{tool.radius:g} in its corners")
    floor = slot.bottom_z + (operation.allowance_bottom or 0.0)
    forward = [line]
    backward = forward if slot.closed else [line[::-1]]     # round a closed slot always the same way
    cleared = slot.top_z
    for index, z in enumerate(cut_levels(slot.top_z, floor, operation.axial_cutting_depth or tool.radius)):
        paths, other = (forward, backward) if index % 2 == 0 else (backward, forward)
        motion.cut(paths, z, cleared)
        motion.levels[(id(other), 0)] = z     # the next layer starts where this one ended, cut to z
        cleared = z
    return motion


def _stretched(line, before: float, after: float):
    """A polyline lengthened (positive) or shortened (negative) at its ends along itself; None when
    nothing is left."""
    line = np.asarray(line, float)
    for _ in range(2):
        amount = before
        if amount >= 0:
            tangent = line[0] - line[1]
            line = np.vstack([line[0] + tangent / np.linalg.norm(tangent) * amount, line[1:]])
        else:
            amount = -amount
            while len(line) >= 2:
                step = np.linalg.norm(line[1] - line[0])
                if step > amount + 1e-9:
                    line = np.vstack([line[0] + (line[1] - line[0]) * amount / step, line[1:]])
                    break
                amount -= step
                line = line[1:]
            if len(line) < 2:
                return None
        line, before = line[::-1], after
    return line


# Hole bottoms an end mill cuts; a milled through hole goes this far (mm) below the hole bottom unless the
# operation gives an overcut_length.
MILLED_HOLE_BOTTOMS = ("FLAT_HOLE_BOTTOM", "") + THROUGH_CONDITIONS
# A helical entry of more turns than this a layer is on a circle too small for its angle to mean anything.
MAX_HELIX_TURNS = 100
MILLED_BREAKTHROUGH = 1.0


def _hole_milling(operation: BottomAndSideMilling, hole: RoundHole, tool: Tool, clearance_z, feed,
                  spindle_clockwise, roughings, skip, stock=None):
    """BOTTOM_AND_SIDE_ROUGH/FINISH_MILLING of a ROUND_HOLE by helical interpolation.

    The tool centre runs on circles about the hole's axis, the outer one R - r - allowance_side
    from it.  Each layer (axial_cutting_depth, default the tool radius) starts with one helical turn
    down on the innermost circle and then steps out circle by circle (the stepover at most the
    tool radius, the innermost circle within the tool radius of the axis, so no core stands).  A hole
    at most twice the tool's diameter is one circle: plain helical interpolation.  Finishing after
    roughing runs only the outer circle above the rough floor and every circle below it."""
    if tool.kind == "drill":
        skip(f"a {tool.label or 'drill'} cannot mill hole #{hole.id} sideways: give an end mill")
        return None
    if hole.bottom_condition not in MILLED_HOLE_BOTTOMS:
        skip(f"hole #{hole.id} has a {hole.bottom_condition}: only flat and through hole bottoms are milled")
        return None
    outer = hole.diameter / 2 - tool.radius - (operation.allowance_side or 0.0)
    if outer < 1e-3:
        skip(f"the {tool.diameter:g} mm tool (allowance {operation.allowance_side or 0:g} mm) does not fit in the "
             f"{hole.diameter:g} mm hole #{hole.id} with room to interpolate: drill or bore it")
        return None
    strategy = operation.its_machining_strategy
    overlap = getattr(strategy, "overlap", None)
    stepover = min(stepover_of(tool.diameter, overlap, operation.radial_cutting_depth), tool.radius)
    count = max(0, math.ceil((outer - tool.radius) / stepover - 1e-9))
    radii = [outer - k * stepover for k in range(count, -1, -1)] if count else [outer]   # innermost first
    ccw = strategy.rotation_direction == "CCW" if isinstance(strategy, ContourParallel) else spindle_clockwise
    floor = hole.bottom_z + (operation.allowance_bottom or 0.0)
    if hole.bottom_condition in THROUGH_CONDITIONS:
        overcut = getattr(operation, "overcut_length", None)
        floor = hole.bottom_z - (overcut if overcut is not None else MILLED_BREAKTHROUGH)
    rough_floor = math.inf          # no roughing: every layer is below it (all circles)
    if roughings:
        rough_floor = min(hole.bottom_z + (rough.allowance_bottom or 0.0) for rough in roughings)
    cx, cy = hole.centre
    approach = operation.approach
    angle = approach.angle if isinstance(approach, (PlungeHelix, PlungeRamp)) and 0 < approach.angle < 90 else None
    motion = Motion(clearance_z, feed, stock=stock, radius=tool.radius)
    if angle is not None:
        motion.notes.append(f"hole #{hole.id}: helical entry at the file's {angle:g} degrees (pitch = pi x circle "
                            f"diameter x tan {angle:g}: {helix_pitch(radii[0], angle):.3f} mm a turn on the "
                            f"{2 * radii[0]:g} mm circle)")
    path = motion.path
    step = operation.axial_cutting_depth or tool.radius
    levels = cut_levels(hole.top_z, floor, step)
    rings = radii
    for index, z in enumerate(levels):
        rings = radii if z < rough_floor - 1e-9 else radii[-1:]
        start = (cx + rings[0], cy)
        if index == 0:
            top = motion.entry_height(start, hole.top_z)
            path.rapid(*start, clearance_z)
            if top < clearance_z - 1e-9:
                path.rapid(*start, top)
        else:
            if abs(path.position[0] - start[0]) > 1e-9:
                path.line(*start, path.position[2])      # back in to the first circle, inside the cut
            top = path.position[2]
        steep = angle is not None and (top - z) / helix_pitch(rings[0], angle) > MAX_HELIX_TURNS
        if steep and not any("too small for" in note for note in motion.notes):
            motion.notes.append(f"hole #{hole.id}: the {2 * rings[0]:.3g} mm circle is too small for a {angle:g} degree "
                                f"helix (more than {MAX_HELIX_TURNS} turns a layer): one turn per layer there")
        if angle is not None and not steep:               # down at the file's ramp angle
            for kind, end, _ in helix_moves((cx, cy), start, top, z, helix_pitch(rings[0], angle), ccw):
                path.arc(*end, cx, cy, clockwise=kind == ARC_CW)
        else:                                             # a turn per axial step down to the layer
            turns = max(1, math.ceil((top - z) / step - 1e-9))
            for k in range(1, turns + 1):
                path.arc(*start, top - (top - z) * k / turns, cx, cy, clockwise=not ccw)
        path.arc(*start, z, cx, cy, clockwise=not ccw)    # the layer's full circle
        for radius in rings[1:]:
            path.line(cx + radius, cy, z)
            path.arc(cx + radius, cy, z, cx, cy, clockwise=not ccw)
    if rings is radii and path.position is not None:     # the whole disc is cleared: off the wall to the axis
        path.line(cx, cy, path.position[2])
    path.retract()
    return motion


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
    motion = Motion(clearance_z, feed, stock=stock, radius=tool.radius)
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
            stops = [(bottom + strategy.depth_of_end, feed), (bottom, feed * iso_ratio(strategy.reduced_feed_at_end))]
        if strategy.depth_of_start and strategy.reduced_feed_at_start:
            stops.insert(0, (max(top - strategy.depth_of_start, bottom), feed * iso_ratio(strategy.reduced_feed_at_start)))
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
