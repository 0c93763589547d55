"""Holes whose bottom the workplan does not make as the file draws it.

A ROUND_HOLE with a FLAT_HOLE_BOTTOM (or FLAT_WITH_RADIUS_HOLE_BOTTOM) drilled with a pointed drill
keeps a cone: the tip stops at the depth plane, so the full diameter reaches only
radius * tan(tool_top_angle) above it (ISO 14649's tool_top_angle is measured from the plane square
to the axis: 31 degrees is the usual 118-degree point).  The hole is flat only when a workingstep
cuts its bottom with a flat tool: BOTTOM_AND_SIDE milling of the hole with an end mill (helical
interpolation), or DRILLING with a drill whose tool_top_angle is 0.  Otherwise the NC header, the
report and the panel's warnings name the hole, how high the cone stands and what would finish it;
nothing is cut deeper than the file's depth to hide it.
"""
from __future__ import annotations

import math

from .features import RoundHole
from .process import BottomAndSideMilling, DrillingOperation

FLAT_BOTTOMS = ("FLAT_HOLE_BOTTOM", "FLAT_WITH_RADIUS_HOLE_BOTTOM")
# A drill point when the file gives no tool_top_angle (the usual 118 degrees included).
DEFAULT_TOOL_TOP_ANGLE = 31.0


def point_angle(tool) -> float:
    """tool_top_angle (degrees from the plane square to the axis) of a drilling tool."""
    angle = tool.its_tool_body.dimension.tool_top_angle
    return DEFAULT_TOOL_TOP_ANGLE if angle is None else float(angle)


def _flat_tool(tool) -> bool:
    body = tool.its_tool_body
    if body.type_name in ("ENDMILL", "FACEMILL", "BULLNOSE_ENDMILL", "TAPERED_ENDMILL"):
        return True
    return body.type_name in ("TWIST_DRILL", "TAPERED_DRILL") and point_angle(tool) == 0.0


def flat_bottom_notes(workingsteps, machined_ids) -> list:
    """A note for every flat-bottomed ROUND_HOLE that the workingsteps ``machined_ids`` drill with a
    pointed tool and none finishes flat."""
    by_hole: dict = {}
    for step in workingsteps:
        if step.id in machined_ids and isinstance(step.its_feature, RoundHole) \
                and step.its_feature.bottom_condition in FLAT_BOTTOMS:
            by_hole.setdefault(step.its_feature.id, []).append(step)
    notes = []
    for steps in by_hole.values():
        hole = steps[0].its_feature
        flat = [s for s in steps if isinstance(s.its_operation, (BottomAndSideMilling, DrillingOperation))
                and _flat_tool(s.its_operation.its_tool)]
        pointed = [s for s in steps if isinstance(s.its_operation, DrillingOperation)
                   and s.its_operation.type_name == "DRILLING" and not _flat_tool(s.its_operation.its_tool)
                   and s.its_operation.cutting_depth is None]
        if flat or not pointed:
            continue
        step = max(pointed, key=lambda s: s.its_operation.its_tool.its_tool_body.dimension.diameter)
        tool = step.its_operation.its_tool
        radius = min(tool.its_tool_body.dimension.diameter, hole.diameter) / 2
        cone = radius * math.tan(math.radians(point_angle(tool)))
        included = 180.0 - 2 * point_angle(tool)
        notes.append(f"ROUND_HOLE #{hole.id} '{hole.its_id}' has a {hole.bottom_condition} but workingstep #{step.id} "
                     f"'{step.its_id}' drills it with a {included:g} degree point: the tip stops at the depth "
                     f"(Z {hole.bottom_z:g}) and leaves a cone {cone:.3f} mm high (the full diameter reaches Z "
                     f"{hole.bottom_z + cone:.3f}); no workingstep cuts the bottom flat: add a flat end mill or "
                     "counterbore workingstep, or finish it by hand")
    return notes


def through_bottom_notes(through: list, bottom: float, tolerance: float = 1e-6) -> list:
    """Without a workpiece BLOCK the deepest through feature's depth plane is taken as the stock's
    bottom (ISO 14649: a through feature goes through the workpiece), so a mistyped depth would
    make its own stock: the notes say which feature set the bottom and how thick that makes the
    stock, and name every other through feature that ends above it (it would not go through)."""
    through = list({feature.id: feature for feature in through}.values())    # a feature of several workingsteps once
    deepest = min(through, key=lambda feature: feature.bottom_z)
    top = max(feature.top_z for feature in through)
    notes = [f"no workpiece BLOCK: the stock bottom is taken as Z {bottom:g}, the depth of the deepest through "
             f"feature #{deepest.id} '{deepest.its_id}' ({top - bottom:g} mm below its top); check the stock's "
             f"thickness, or give the workpiece its BLOCK"]
    for feature in through:
        if feature.bottom_z > bottom + tolerance:
            notes.append(f"through feature #{feature.id} '{feature.its_id}' ends at Z {feature.bottom_z:g}, "
                         f"{feature.bottom_z - bottom:g} mm above that stock bottom: it does not go through")
    return notes
