"""Pockets modelled elsewhere -> an ISO 14649 file (Part 21 text) that roughs and finishes them.
Split from workplan.py."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...engines import region as rg
from ...ir.program import Tool
from .errors import StepNcError
from .part21 import UNSET, Enum
from .tools import number_in
from .part21_writer import Part21Writer


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
            raise StepNcError(f"pocket {pocket.name!r}: depth {pocket.depth:g} must be above 0 and at most the stock "
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
    # The IR tool has no gauge length: the cutting component records the flute length.  Its identifier
    # starts with its T number, so reading the file back gives the same number (tools.tool_numbering).
    identifier = tool.describe() if not tool.name else tool.name if number_in(tool.name) == tool.number \
        else f"T{tool.number} {tool.name}"
    cutting_tool = w.add("MILLING_CUTTING_TOOL", identifier,
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
