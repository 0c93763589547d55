"""Where a workplan's features and stock are, as solids and boxes (work mm): what the viewport
shows and what the simulation cuts."""
from __future__ import annotations

import numpy as np

from ...engines.meshdata import prism
from .features import ClosedPocket, PlanarFace, RoundHole, Slot


def feature_solid(feature):
    """Vertices and faces of a prism showing where a feature removes material, or None for a
    feature of a kind not drawn."""
    top, bottom = feature.top_z, feature.bottom_z
    if isinstance(feature, (ClosedPocket, Slot)):
        outline = np.asarray(feature.outline(), float)[:, :2]
    elif isinstance(feature, PlanarFace):
        outline = np.asarray(feature.corners(), float)
    elif isinstance(feature, RoundHole):
        angles = np.linspace(0, 2 * np.pi, 48, endpoint=False)
        outline = np.column_stack([np.cos(angles), np.sin(angles)]) * feature.diameter / 2 + feature.centre
    else:
        return None
    if abs(top - bottom) < 1e-9:
        bottom = top - 0.1
    return prism(outline, top, bottom)


def block_of(loaded):
    """The workpiece's BLOCK as ((x0, y0, z0), (x1, y1, z1)), or None when the file gives none."""
    workpieces = getattr(loaded.project, "its_workpieces", None)
    workpiece = workpieces[0] if workpieces else None
    block = getattr(workpiece, "its_bounding_geometry", None) if workpiece is not None else None
    return block.box() if block is not None else None


def stock_box(loaded, program):
    """The workpiece's BLOCK when the file gives one, else a box around the features and the
    cuts (a tool radius beyond them), from the lowest cut to the highest feature top."""
    from ...simulate import BoxStock

    box = block_of(loaded)
    if box is not None:
        (x0, y0, z0), (x1, y1, z1) = box
        return BoxStock(x0, y0, z0, x1, y1, z1)
    from .workplan import stock_bottom

    cuts = np.vstack([op.xyz[op.kind != 0] for op in program.operations])
    margin = max(op.tool.radius for op in program.operations) + 1.0
    top = max(step.its_feature.top_z for step in loaded.workingsteps)
    (x0, y0, z0), (x1, y1, _) = cuts.min(axis=0), cuts.max(axis=0)
    bottom, _ = stock_bottom(loaded)           # a through feature's depth plane is the stock's bottom
    if bottom is None or not bottom < top:
        bottom = min(z0, top) - 1.0
    return BoxStock(x0 - margin, y0 - margin, bottom, x1 + margin, y1 + margin, top)


def fixture_clearance(loaded) -> float:
    """How far below the stock's bottom the workplan's own rule takes a drill through a through
    hole (point length + clearance, :func:`workplan.drill_breakthrough`): the simulation accepts that
    much; a file asking for more (its overcut_length) is a finding the user must confirm."""
    from .workplan import MILLED_BREAKTHROUGH, POINTED_DRILL_BODIES, THROUGH_CONDITIONS, drill_breakthrough

    depths = []
    for step in loaded.workingsteps:
        if getattr(step.its_feature, "bottom_condition", None) not in THROUGH_CONDITIONS:
            continue
        operation = step.its_operation
        pointed = operation.its_tool.its_tool_body.type_name in POINTED_DRILL_BODIES
        if getattr(operation, "type_name", None) in ("DRILLING", "FREEFORM_OPERATION") and pointed:
            depths.append(drill_breakthrough(operation.its_tool))    # a drill's own path (NIST's ex1E) too
        elif getattr(operation, "type_name", None) != "DRILLING":
            # a through hole milled to size goes MILLED_BREAKTHROUGH below its bottom
            depths.append(MILLED_BREAKTHROUGH)
    return max(depths, default=0.0) + 0.01
