"""Explicit toolpaths: FREEFORM_OPERATION's CUTTER_LOCATION_TRAJECTORYs and RAPID_MOVEMENTs -> moves.

The trajectories are converted as they are, the way NIST's ISO 14649 interpreter reads them
(its ex1E file): the points of an operation's toolpath are in the coordinates of the workingstep's
feature (the drill path of a hole at X20 Y60 runs along X0 Y0), a RAPID_MOVEMENT's in the
workpiece's; a POLYLINE is straight feed moves, a TRIMMED_CURVE on a LINE one move, on a CIRCLE an
arc (G2/G3) and on a HELIX a helical arc, turns and all; COMPOSITE_CURVEs chain their segments.
A trajectory with its own MILLING_TECHNOLOGY feeds at its feed, one without it at the operation's;
its_speed .RAPID. and a RAPID_MOVEMENT are rapids.  The spindle speed is the operation's: a
trajectory's other speed is reported, not written (one spindle speed per operation).

Before the first trajectory the tool rapids at the clearance plane above its first point and down
to that point, stopping APPROACH_GAP above the material when the point is lower (the rest is fed);
after the last it retracts.  A RAPID_MOVEMENT after the workingstep continues from where it ended.
"""
from __future__ import annotations

import math

import numpy as np

from ...ir.program import ARC_CCW, ARC_CW, FEED, RAPID
from .errors import StepNcError, UnsupportedEntity
from .geometry import BSplineCurve, CompositeCurve, Helix, Line, Polyline, TrimmedCurve
from .motion import Motion
from .technology import MissingTechnology, feed_and_speed

# A helix or circle is cut in arcs of at most this sweep (degrees); every post writes them as G2/G3.
MAX_ARC_SWEEP = 180.0
# A helix of more turns than this is refused (a mistyped pitch, not hours of circles).
MAX_TURNS = 1000
# The trajectories of one operation must join within this distance (mm).
JOIN_TOLERANCE = 1e-3


def curve_moves(curve) -> tuple:
    """(start point, [(kind, end, centre)]) of a curve, in its own coordinates; kind FEED or an arc."""
    if isinstance(curve, (Polyline, BSplineCurve)):
        points = curve.sample()
        return points[0], [(FEED, p, None) for p in points[1:]]
    if isinstance(curve, CompositeCurve):
        start, moves = None, []
        for segment in curve.segments:
            first, own = curve_moves(segment.parent_curve)
            if not segment.same_sense:
                first, own = _reverse(first, own)
            if start is None:
                start = first
            elif np.linalg.norm(np.asarray(first) - np.asarray(moves[-1][1] if moves else start)) > JOIN_TOLERANCE:
                raise StepNcError(f"#{curve.id} COMPOSITE_CURVE: a segment starts away from the end of the one "
                                  "before it")
            moves += own
        return start, moves
    if isinstance(curve, TrimmedCurve):
        basis = curve.basis_curve
        if isinstance(basis, Line):
            points = curve.sample()
            return points[0], [(FEED, points[-1], None)]
        if not isinstance(curve.trim_1, tuple) or not isinstance(curve.trim_2, tuple):
            raise UnsupportedEntity("TRIMMED_CURVE", curve.id, "an arc or helix trimmed by parameter values in a "
                                    "toolpath (give the trim points)")
        return _turning(curve, basis)
    raise UnsupportedEntity(type(curve).__name__.upper(), curve.id, "as a toolpath curve")


def _turning(curve: TrimmedCurve, basis) -> tuple:
    """A trimmed CIRCLE or HELIX about a vertical axis as arcs of at most MAX_ARC_SWEEP."""
    centre, x_axis, y_axis = basis.frame()
    axis = np.cross(x_axis, y_axis)
    if abs(abs(axis[2]) - 1.0) > 1e-9:
        raise UnsupportedEntity(type(basis).__name__.upper(), basis.id, "an arc or helix that does not turn about "
                                "the Z axis")
    start, end = np.array(curve.trim_1, float), np.array(curve.trim_2, float)
    a0 = math.atan2((start - centre) @ y_axis, (start - centre) @ x_axis)
    a1 = math.atan2((end - centre) @ y_axis, (end - centre) @ x_axis)
    if isinstance(basis, Helix):
        if abs(basis.pitch) < 1e-12:
            raise StepNcError(f"#{basis.id} HELIX: the pitch is zero")
        sweep = 2 * math.pi * ((end - start) @ axis) / basis.pitch          # along the parameter
        if (sweep > 0) != curve.sense_agreement and abs(sweep) > 1e-9:
            if curve.sense_agreement:
                raise StepNcError(f"#{curve.id} TRIMMED_CURVE: sense_agreement .T. contradicts the pitch of the "
                                  f"HELIX #{basis.id} (its second point is below its first)")
            raise StepNcError(f"#{curve.id} TRIMMED_CURVE: sense_agreement .F. contradicts the pitch of the "
                              f"HELIX #{basis.id} (its second point is above its first)")
        if abs(((sweep - (a1 - a0)) / (2 * math.pi)) - round((sweep - (a1 - a0)) / (2 * math.pi))) > 1e-3:
            raise StepNcError(f"#{curve.id} TRIMMED_CURVE: its points are not on the HELIX #{basis.id} "
                              "(angle and height disagree)")
    else:
        sweep = (a1 - a0) % (2 * math.pi) if curve.sense_agreement else -((a0 - a1) % (2 * math.pi))
        if abs(sweep) < 1e-9:
            sweep = 2 * math.pi if curve.sense_agreement else -2 * math.pi
    radius = np.linalg.norm((start - centre) - ((start - centre) @ axis) * axis)
    reach = np.linalg.norm((end - centre) - ((end - centre) @ axis) * axis)
    if basis.radius <= 1e-6 or max(abs(radius - basis.radius), abs(reach - basis.radius)) > JOIN_TOLERANCE:
        raise StepNcError(f"#{curve.id} TRIMMED_CURVE: its points lie {radius:.4g} and {reach:.4g} mm from the axis "
                          f"of #{basis.id}, whose radius is {basis.radius:g} mm")
    if abs(sweep) > MAX_TURNS * 2 * math.pi:
        raise StepNcError(f"#{curve.id} TRIMMED_CURVE: {abs(sweep) / (2 * math.pi):.6g} turns about #{basis.id}, "
                          f"more than {MAX_TURNS}")
    count = max(1, math.ceil(abs(math.degrees(sweep)) / MAX_ARC_SWEEP - 1e-9))
    counter_clockwise = (sweep > 0) == (axis[2] > 0)
    moves = []
    rise = (end - start) @ axis
    for k in range(1, count + 1):
        angle = a0 + sweep * k / count
        point = (centre + radius * (math.cos(angle) * x_axis + math.sin(angle) * y_axis)
                 + ((start - centre) @ axis + rise * k / count) * axis)
        if k == count:
            point = end
        moves.append((ARC_CCW if counter_clockwise else ARC_CW, point, centre + ((point - centre) @ axis) * axis))
    return start, moves


def _reverse(start, moves) -> tuple:
    points = [np.asarray(start)] + [np.asarray(end) for _, end, _ in moves]
    flipped = {FEED: FEED, ARC_CW: ARC_CCW, ARC_CCW: ARC_CW}
    back = [(flipped[kind], points[i], centre) for i, (kind, _, centre) in reversed(list(enumerate(moves)))]
    return points[-1], back


def trajectory_moves(trajectory) -> tuple:
    start, moves = curve_moves(trajectory.basiccurve)
    return (start, moves) if trajectory.forward else _reverse(start, moves)


def plan_freeform(step, tool, clearance_z, stock=None):
    """A Motion with the explicit toolpaths of a FREEFORM_OPERATION workingstep and the RAPID_MOVEMENTs
    after it."""
    operation, frame = step.its_operation, step.its_feature.feature_placement
    motion = Motion(clearance_z, None, stock=stock, radius=tool.radius)
    notes_of_step = motion.notes.append
    path = motion.path
    rpm = feed_and_speed(operation, tool, [], need_feed=False)[1]
    for index, trajectory in enumerate(operation.its_toolpath):
        points = _polyline_points(trajectory)
        if points is None:
            start, moves = trajectory_moves(trajectory)
        else:               # straight feed moves through the points: kept as one array
            start, moves = points[0], points[1:]
        start = frame.to_parent([start])[0]
        feed = math.nan if trajectory.rapid else _feed(trajectory, operation, tool, rpm, notes_of_step)
        if index == 0:      # fed in (when the start is below the material) at the first cutting trajectory's feed
            cutting = next((t for t in operation.its_toolpath if not t.rapid), None)
            _enter(motion, start, step.its_feature.top_z,
                   lambda: _feed(cutting, operation, tool, rpm, None) if cutting is not None else
                   _feed(None, operation, tool, rpm, None))
        elif np.linalg.norm(np.asarray(path.position) - start) > JOIN_TOLERANCE:
            notes_of_step(f"trajectory #{trajectory.id} starts {np.linalg.norm(np.asarray(path.position) - start):.4g}"
                          " mm from the end of the one before it: joined by a straight feed move")
            path.line(*start, feed=feed if not trajectory.rapid else _feed(None, operation, tool, rpm, None,
                                                                               trajectory))
        _add(path, moves, frame, feed)
    for rapid in step.rapids_after:
        for trajectory in rapid.its_toolpath:
            start, moves = trajectory_moves(trajectory)
            if np.linalg.norm(np.asarray(path.position) - start) > JOIN_TOLERANCE:
                path.rapid(*start)
            for kind, end, _ in moves:
                if kind != FEED:
                    raise UnsupportedEntity("RAPID_MOVEMENT", rapid.id, "an arc in a rapid movement")
                path.rapid(*end)
    return motion


def _enter(motion, start, feature_top, entry_feed):
    """Rapid above the first point; when it lies below the material, rapid to APPROACH_GAP above the
    material and feed the rest at ``entry_feed()`` (mm/min)."""
    path = motion.path
    path.rapid(start[0], start[1], motion.clearance_z)
    top = motion.entry_height(start[:2], feature_top)
    if start[2] >= top - 1e-9:
        if start[2] < motion.clearance_z - 1e-9:
            path.rapid(*start)
        return
    if top < motion.clearance_z - 1e-9:
        path.rapid(start[0], start[1], top)
    path.line(*start, feed=entry_feed())


def _polyline_points(trajectory) -> np.ndarray | None:
    """The (n, 3) points of a trajectory along a POLYLINE, in the order it is cut (None for other
    curves): its moves are what :func:`trajectory_moves` makes of it, without a tuple per point."""
    curve = trajectory.basiccurve
    if not isinstance(curve, Polyline):
        return None
    points = curve.sample()
    return points if trajectory.forward else np.ascontiguousarray(points[::-1])


def _add(path, moves, frame, feed):
    if isinstance(moves, np.ndarray):       # a POLYLINE's end points
        ends = frame.to_parent(moves) if len(moves) else ()
        if not math.isnan(feed):
            if len(moves):
                path.polyline(ends, feed=feed)
            return
        moves = [(FEED, None, None)] * len(moves)
    else:
        # every end point into the workpiece's frame at once (one placement per curve; point by
        # point this was most of the time of reading a big file of explicit toolpaths)
        ends = frame.to_parent([end for _, end, _ in moves]) if moves else ()
    for (kind, _, centre), end in zip(moves, ends):
        if math.isnan(feed):
            if kind != FEED:
                raise UnsupportedEntity("TRIMMED_CURVE", 0, "an arc at rapid speed (G0 is straight)")
            path.rapid(*end)
        elif kind == FEED:
            path.line(*end, feed=feed)
        else:
            centre = frame.to_parent([centre])[0]
            path.arc(*end, centre[0], centre[1], clockwise=kind == ARC_CW, feed=feed)


def _feed(trajectory, operation, tool, rpm, note, why=None) -> float:
    """The feed (mm/min) of a trajectory, where NIST's files state it (ex1E): its own its_technology's
    (MILLING_TECHNOLOGY feedrate, or feedrate_per_tooth x teeth x rpm), else the FREEFORM_OPERATION's
    its_technology's.  Neither: StepNcError naming the instances and attributes that are missing.
    ``why``: the trajectory a feed move is made for when ``trajectory`` is not it (a join)."""
    own = None if trajectory is None else trajectory.its_technology
    if own is not None and note is not None and own.spindle_rpm is not None and abs(own.spindle_rpm - rpm) > 1e-6:
        note(f"trajectory #{trajectory.id} asks for S{own.spindle_rpm:g}; the operation's S{rpm:g} is written (one "
             "spindle speed per operation)")
    teeth = operation.its_tool.its_tool_body.number_of_teeth
    for technology in (own, operation.its_technology):
        if technology is None:
            continue
        if technology.feed_mm_min and technology.feed_mm_min > 0:
            return technology.feed_mm_min
        if technology.feedrate_per_tooth and teeth:
            return technology.feedrate_per_tooth * teeth * rpm
    where = trajectory or why
    first = (f"#{where.id} CUTTER_LOCATION_TRAJECTORY: " if where is not None else "") + (
        f"its_technology #{own.id} MILLING_TECHNOLOGY gives no feedrate (attribute 1) nor feedrate_per_tooth "
        "(attribute 5) with the tool's number_of_teeth" if own is not None else "its_technology (attribute 4) is unset")
    op_tech = operation.its_technology
    raise MissingTechnology(f"{first}, and #{operation.id} FREEFORM_OPERATION's its_technology #{op_tech.id} "
                      f"MILLING_TECHNOLOGY gives no feedrate (attribute 1) nor feedrate_per_tooth (attribute 5) with "
                      f"#{operation.its_tool.its_tool_body.id} {operation.its_tool.its_tool_body.type_name}'s "
                      "number_of_teeth: no feed for its cutting moves")


__all__ = ["plan_freeform", "curve_moves", "trajectory_moves", "RAPID"]
