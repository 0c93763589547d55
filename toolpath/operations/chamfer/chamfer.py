"""Chamfer / deburr: a V-bit along the top edges of closed outlines, its flank cutting the chamfer.

The geometry, in the plane across the edge (the wall vertical, the top horizontal; the V-bit's
included angle ``theta``, so its flank leans ``theta / 2`` from the vertical).  The chamfer is the
flank's line: it meets the top at ``width`` from the edge (into the material) and the wall at
``depth`` below the top, with

    depth = width / tan(theta / 2)          (90 deg bit: depth = width, a 45 deg chamfer)

(one flank: the V-groove formula ``groove width / (2 tan(theta / 2))`` counts both flanks of a
groove, a chamfer has one).  The bit's tip runs ``tip_gap`` below the chamfer's bottom, in the
waste beside the wall, so its axis is offset from the edge, into the waste, by

    offset = tip_gap * tan(theta / 2)

and its tip is ``depth + tip_gap`` below the top: the cone's radius at depth z below the top is
(depth + tip_gap - z) tan(theta / 2), which at z = depth is the offset (the flank meets the wall
there) and at z = 0 is offset + width (the flank meets the top ``width`` into the material).  With
``tip_gap`` 0 the tip runs on the edge itself.  The cone at the top must fit the bit:
offset + width <= the bit's radius.

Which side is material: the outlines are read even-odd (an outline inside another is a hole's
edge, e.g. a drilled hole's), the offset grows the material region into the waste, and each path
runs with the material on its right (climb milling with the spindle turning clockwise).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...engines import region
from ...ir.errors import InputError
from ...ir.program import Operation, PathBuilder, Tool
from ..fields import FINITE, Fields, positive, zero_or_more


class ChamferError(InputError):
    """Outlines or settings that cannot be chamfered; the message names the setting."""


# The sizes, then (after the width or the depth is chosen) the speeds, each within its own bounds.
SIZES = Fields(FINITE, tuple(map(zero_or_more, ("width", "depth", "tip_gap"))))
SPEEDS = Fields(FINITE, tuple(map(positive, ("rpm", "feed", "plunge_feed"))))


@dataclass(frozen=True)
class ChamferSettings:
    tool: Tool = field(default_factory=lambda: Tool(7, "vbit", 12.0, flute_length=10.0, name="90 deg V-bit"))
    width: float = 1.0           # across the top, from the edge into the material (mm); 0: from depth
    depth: float = 0.0           # down the wall (mm); 0: from width
    tip_gap: float = 0.2         # the tip below the chamfer's bottom, in the waste (mm)
    rpm: float = 16000.0
    feed: float = 1200.0
    plunge_feed: float = 300.0
    approach_gap: float = 2.0
    clearance_z: float = 20.0
    safe_z: float = 20.0

    def check(self) -> None:
        shape = self.tool.shape
        if shape.kind != "vbit":
            raise ChamferError(f"chamfering needs a V-bit, not a {self.tool.describe()}")
        SIZES.check(self, "chamfer", ChamferError)
        if (self.width > 0) == (self.depth > 0):
            raise ChamferError(f"chamfer: give the width or the depth, one of them (width {self.width:g}, depth "
                               f"{self.depth:g})")
        SPEEDS.check(self, "chamfer", ChamferError)
        if not self.approach_gap < self.clearance_z <= self.safe_z:
            raise ChamferError(f"chamfer: the approach gap {self.approach_gap:g} mm, clearance plane "
                               f"{self.clearance_z:g} mm and safe Z {self.safe_z:g} mm must rise in that order")
        width, _, offset, tip = self.geometry()
        if offset + width > self.tool.radius + 1e-9:
            raise ChamferError(f"chamfer: a {width:g} mm chamfer with the tip {self.tip_gap:g} mm below it needs the "
                               f"V-bit {2 * (offset + width):g} mm wide at the top; the {self.tool.describe()} is "
                               f"{self.tool.diameter:g} mm")
        if tip > self.tool.flute_length:
            raise ChamferError(f"chamfer: the tip {tip:g} mm deep is beyond the {self.tool.describe()}'s "
                               f"{self.tool.flute_length:g} mm flutes")

    def half_tan(self) -> float:
        """tan(theta / 2) of the V-bit's included angle theta (the tool library's)."""
        return math.tan(math.radians(self.tool.shape.tip_angle_deg) / 2)

    def geometry(self) -> tuple:
        """(width, depth, offset of the tool's axis from the edge, tip depth below the top), mm."""
        t = self.half_tan()
        width = self.width if self.width > 0 else self.depth * t
        depth = width / t                                   # depth = width / tan(theta / 2)
        offset = self.tip_gap * t                           # offset = tip_gap * tan(theta / 2)
        return width, depth, offset, depth + self.tip_gap


def tool_paths(loops, settings: ChamferSettings) -> list:
    """The closed (k, 2) paths of the bit's axis, material on their right."""
    try:
        material = region.from_loops(loops, "chamfer outline")
    except region.RegionError as error:
        raise ChamferError(str(error)) from None
    _, _, offset, _ = settings.geometry()
    grown = region.offset(material, offset)
    return [loop[::-1] for loop in region.loops(grown)]          # outer CCW, holes CW: reversed


RAMP_PER_MM = 8.0     # the entry ramp's length per mm of depth (about 7 deg): a V-bit does not plunge


def ramped_lap(points: np.ndarray, top: float, z: float, ramp: float) -> np.ndarray:
    """(m, 3) feed points: once round the closed path ``points`` (k, 2) from its first point, going
    down from ``top`` to ``z`` along its first ``ramp`` mm (a whole lap at most), then the ramp's
    stretch again at ``z``, so every point of the path is cut at full depth."""
    closed = np.vstack([points, points[:1]])
    along = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
    ramp = min(ramp, float(along[-1]))
    depth = top + (z - top) * np.minimum(1.0, along / max(ramp, 1e-9))
    lap = np.column_stack([closed, depth])[1:]
    end = int(np.searchsorted(along, ramp - 1e-9))      # the first point at full depth
    again = np.column_stack([closed[1:end + 1], np.full(end, z)])
    return np.vstack([lap, again])


def plan(loops, settings: ChamferSettings = ChamferSettings(), name: str = "chamfer", top: float = 0.0) -> Operation:
    """One operation chamfering the top edges of the closed outlines ``loops`` (work mm, even-odd)."""
    settings.check()
    paths = tool_paths(loops, settings)
    width, depth, _, tip = settings.geometry()
    z = top - tip
    path = PathBuilder(settings.clearance_z, settings.feed, settings.plunge_feed, settings.approach_gap, top)
    for points, first in region.order_loops_nearest(paths, (0.0, 0.0)):
        path.plunge(*points[first], top)
        path.polyline(ramped_lap(np.roll(points, -first, axis=0), top, z, RAMP_PER_MM * tip))
        path.retract()
    arrays = path.arrays()
    first = paths[0][0] if paths else (0.0, 0.0)
    return Operation(name, settings.tool, settings.rpm, arrays["kind"], arrays["xyz"], arrays["feed"],
                     clearance_z=settings.clearance_z, safe_z=settings.safe_z,
                     start=np.array([first[0], first[1], settings.safe_z]),
                     comment=f"chamfer {width:g} mm wide, {depth:g} mm deep")
