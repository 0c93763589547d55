"""Chamfers at round holes: the V-bit along a circle inside each hole, as G2/G3 arcs.

In the plane across the hole's edge it is the edge chamfer of :mod:`.chamfer` (the same ``width``,
``depth = width / tan(theta / 2)``, tip ``tip_gap`` below the chamfer, axis ``offset = tip_gap *
tan(theta / 2)`` into the waste): the waste is the hole, so the bit's axis runs on a circle of radius

    rho = D / 2 - offset

about the hole's centre (D its diameter), its tip ``depth + tip_gap`` below the top.  It comes down
on a helix of whole counter-clockwise turns on that circle from the approach height (a V-bit does
not plunge; climb milling with the spindle turning clockwise, the material outside the circle on the
bit's right), at most :data:`chamfer.RAMP_PER_MM` mm along the circle per mm down, goes once round
at the tip's depth and rises straight up out of its own groove.

The cone must not reach the hole's far wall: at the top it is ``width + offset`` round the axis,
and the far wall is ``rho + D / 2`` from it, so a hole needs D >= width + 2 offset; and rho > 0.
"""
from __future__ import annotations

import math

import numpy as np

from ...ir.program import Operation, PathBuilder
from .chamfer import RAMP_PER_MM, ChamferError, ChamferSettings


def check_holes(holes) -> np.ndarray:
    """(n, 3) array of (x, y, diameter) in mm, or a ChamferError naming the entry."""
    rows = []
    for index, hole in enumerate(holes):
        values = list(hole) if isinstance(hole, (list, tuple, np.ndarray)) else None
        if (values is None or len(values) != 3 or any(isinstance(v, bool) for v in values)
                or not all(isinstance(v, (int, float, np.floating, np.integer)) and math.isfinite(v) for v in values)):
            raise ChamferError(f"chamfer: holes[{index}] = {hole!r} is not [x, y, diameter] in mm")
        if not values[2] > 0:
            raise ChamferError(f"chamfer: holes[{index}]: the diameter must be more than 0 mm, got {values[2]!r}")
        rows.append([float(v) for v in values])
    if not rows:
        raise ChamferError("chamfer: no holes: give holes = [[x, y, diameter], ...] in work mm")
    return np.array(rows, float)


def circle_radius(diameter: float, settings: ChamferSettings, where: str) -> float:
    """The radius of the circle the bit's axis follows in a hole of ``diameter`` (checked)."""
    width, _, offset, _ = settings.geometry()
    rho = diameter / 2 - offset
    if rho <= 1e-3:
        raise ChamferError(f"chamfer: {where} is {diameter:g} mm: with the tip {settings.tip_gap:g} mm below the "
                           f"chamfer the V-bit's axis would run {offset:g} mm in from its edge, past the centre; "
                           "make tip_gap smaller")
    if width + 2 * offset > diameter + 1e-9:
        raise ChamferError(f"chamfer: {where} is {diameter:g} mm, narrower than the {width:g} mm chamfer's V-bit "
                           f"({width + 2 * offset:g} mm across the hole at the top): it would cut the far side")
    return rho


def plan_holes(holes, settings: ChamferSettings = ChamferSettings(), name: str = "hole chamfers",
               top: float = 0.0) -> Operation:
    """One operation chamfering the top edge of each hole (x, y, diameter) of ``holes``."""
    settings.check()
    holes = check_holes(holes)
    width, depth, _, tip = settings.geometry()
    z = top - tip
    gap_z = top + settings.approach_gap
    path = PathBuilder(settings.clearance_z, settings.feed, settings.plunge_feed, settings.approach_gap, top)
    first = None
    for x, y, diameter in holes:
        rho = circle_radius(diameter, settings, f"the hole at X{x:g} Y{y:g}")
        sx = x + rho
        first = first or (sx, y)
        path.retract()
        path.rapid(sx, y, settings.clearance_z)
        path.rapid(sx, y, gap_z)
        turns = max(1, math.ceil(RAMP_PER_MM * (gap_z - z) / (2 * math.pi * rho) - 1e-9))
        for turn in range(1, turns + 1):
            path.arc(sx, y, gap_z + (z - gap_z) * turn / turns, x, y, clockwise=False, feed=settings.plunge_feed)
        path.arc(sx, y, z, x, y, clockwise=False)          # once round at the tip's depth
        path.retract()
    arrays = path.arrays()
    return Operation(name, settings.tool, settings.rpm, arrays["kind"], arrays["xyz"], arrays["feed"],
                     center=arrays["center"], clearance_z=settings.clearance_z, safe_z=settings.safe_z,
                     start=np.array([first[0], first[1], settings.safe_z]),
                     comment=f"chamfer {len(holes)} holes {width:g} mm wide, {depth:g} mm deep")
