"""Holes wider than the drill, milled with a flat end mill along a helix (G2/G3 arcs with Z).

The end mill's centre runs on a circle of radius ``(D - d) / 2`` about the hole's centre (D the
hole's diameter, d the mill's), so its side cuts the wall at ``D / 2``.  It enters at the R plane
and descends in whole counter-clockwise turns (climb milling inside a hole, with the spindle
turning clockwise), each turn one full-circle arc dropping an equal share of the depth, no more
than the pitch; at the bottom one more full circle at constant Z cleans the floor's edge, then the
mill feeds to the centre and rapids out.
"""
from __future__ import annotations

import math

import numpy as np

from ...ir.program import Operation, PathBuilder
from .drill import DrillError, DrillSettings

FIT = 1e-3       # mm: a hole no wider than the mill by this is cut by plunging, not a helix


def plan_helix(holes, diameters, bottoms, settings: DrillSettings, top: float = 0.0,
               name: str = "helix milling") -> Operation:
    """One operation milling each hole (x, y) of ``diameters`` down to its ``bottoms`` Z."""
    settings.check()
    mill = settings.mill
    gap_z = top + settings.approach_gap
    path = PathBuilder(settings.clearance_z, settings.mill_feed, settings.mill_feed, settings.approach_gap, top)
    points = np.asarray(holes, float).reshape(-1, 2)
    for index, ((x, y), diameter, bottom) in enumerate(zip(points, diameters, bottoms)):
        radius = (float(diameter) - mill.diameter) / 2
        if radius < FIT:
            raise DrillError(f"hole {index + 1} at X{x:g} Y{y:g}: {diameter:g} mm is not wider than the "
                             f"{mill.describe()}; drill it instead")
        if top - bottom > mill.flute_length:
            raise DrillError(f"hole {index + 1} at X{x:g} Y{y:g}: {top - bottom:g} mm deep is more than the "
                             f"{mill.describe()}'s {mill.flute_length:g} mm flutes")
        sx = x + radius
        path.retract()
        path.rapid(sx, y, settings.clearance_z)
        path.rapid(sx, y, gap_z)
        turns = max(1, math.ceil((gap_z - bottom) / settings.helix_pitch - 1e-9))
        for turn in range(1, turns + 1):
            path.arc(sx, y, gap_z + (bottom - gap_z) * turn / turns, x, y, clockwise=False)
        path.arc(sx, y, bottom, x, y, clockwise=False)          # the full circle at the bottom
        path.line(x, y, bottom)
        path.rapid(x, y, settings.clearance_z)
    arrays = path.arrays()
    return Operation(name, mill, settings.mill_rpm, arrays["kind"], arrays["xyz"], arrays["feed"],
                     center=arrays["center"], clearance_z=settings.clearance_z, safe_z=settings.safe_z,
                     start=np.array([points[0][0] + (diameters[0] - mill.diameter) / 2, points[0][1],
                                     settings.safe_z]),
                     comment=f"helix-mill {len(points)} holes")
