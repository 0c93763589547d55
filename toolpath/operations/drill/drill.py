"""Drilling: pecked holes at given centres, straight down with a drill (G0/G1 moves, no canned
cycle, so every post and every simulation reads them the same way).

A hole: rapid to the clearance plane above it, rapid to the approach gap above the stock's top,
then pecks: feed down by at most ``peck`` mm, rapid back up to the approach gap to clear the
chips, rapid down to ``peck_gap`` above the last depth reached, feed the next peck; at the full
depth the drill dwells no time and rapids out to the clearance plane.  ``depth`` is to the drill's
tip; a through hole needs the point's length more than the stock (``Tool`` kind "drill": its point
angle is the shape's, :mod:`..ir.tools`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...ir.errors import InputError
from ...ir.program import Operation, PathBuilder, Tool


class DrillError(InputError):
    """Holes or settings that cannot be drilled; the message names the hole or the setting."""


@dataclass(frozen=True)
class DrillSettings:
    tool: Tool = field(default_factory=lambda: Tool(4, "drill", 5.0, flute_length=40.0, name="5 mm drill"))
    depth: float = 10.0          # below the stock's top, to the tip (mm)
    peck: float = 3.0            # deepest feed of one peck (mm); 0: no pecking
    peck_gap: float = 0.5        # how far above the last depth the next peck starts feeding (mm)
    rpm: float = 3000.0
    feed: float = 150.0          # mm/min down the hole
    approach_gap: float = 2.0    # above the stock's top where feeding starts (mm)
    clearance_z: float = 20.0
    safe_z: float = 20.0

    def check(self) -> None:
        if self.tool.shape.kind != "drill":
            raise DrillError(f"drilling needs a drill, not a {self.tool.describe()}")
        for name in ("depth", "rpm", "feed"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise DrillError(f"drilling: {name} must be a positive number, got {value!r}")
        for name in ("peck", "peck_gap", "approach_gap"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0):
                raise DrillError(f"drilling: {name} must be 0 or more, got {value!r}")
        if self.depth > self.tool.flute_length:
            raise DrillError(f"drilling: depth {self.depth:g} mm is deeper than the {self.tool.describe()}'s "
                             f"{self.tool.flute_length:g} mm flutes")
        if not self.approach_gap < self.clearance_z <= self.safe_z:
            raise DrillError(f"drilling: the approach gap {self.approach_gap:g} mm, clearance plane "
                             f"{self.clearance_z:g} mm and safe Z {self.safe_z:g} mm must rise in that order")


def check_holes(holes) -> np.ndarray:
    """(n, 2) finite hole centres in work mm, no two within 1 micron (the same hole twice)."""
    try:
        points = np.asarray(holes, dtype=float)
    except (TypeError, ValueError):
        raise DrillError(f"holes must be (x, y) pairs in mm, got {holes!r}") from None
    if points.ndim != 2 or points.shape[1] != 2 or not len(points):
        raise DrillError(f"holes must be a list of (x, y) pairs in mm, got shape {points.shape}")
    bad = np.flatnonzero(~np.isfinite(points).all(axis=1))
    if len(bad):
        raise DrillError(f"hole {int(bad[0]) + 1} has a coordinate that is not a number: {points[bad[0]].tolist()}")
    for i in range(len(points)):
        near = np.flatnonzero(np.hypot(*(points[i + 1:] - points[i]).T) < 1e-3)
        if len(near):
            raise DrillError(f"holes {i + 1} and {i + 2 + int(near[0])} are the same point {points[i].tolist()}")
    return points


def plan(holes, settings: DrillSettings = DrillSettings(), name: str = "drill", top: float = 0.0) -> Operation:
    """One operation drilling every hole in the given order; ``top``: the stock's top Z."""
    settings.check()
    points = check_holes(holes)
    bottom = top - settings.depth
    path = PathBuilder(settings.clearance_z, settings.feed, settings.feed, settings.approach_gap, top)
    start = top + settings.approach_gap
    for x, y in points:
        path.retract()
        path.rapid(x, y, settings.clearance_z)
        path.rapid(x, y, start)
        reached = start
        while reached > bottom + 1e-9:
            target = bottom if settings.peck <= 0 else max(bottom, min(reached, top) - settings.peck)
            if reached < start:                  # back down to just above the last depth
                path.rapid(x, y, min(start, reached + settings.peck_gap))
            path.line(x, y, target)
            reached = target
            if reached > bottom + 1e-9:
                path.rapid(x, y, start)          # out to clear the chips
        path.rapid(x, y, settings.clearance_z)
    arrays = path.arrays()
    return Operation(name, settings.tool, settings.rpm, arrays["kind"], arrays["xyz"], arrays["feed"],
                     clearance_z=settings.clearance_z, safe_z=settings.safe_z,
                     start=np.array([points[0][0], points[0][1], settings.safe_z]),
                     comment=f"drill {len(points)} holes {settings.depth:g} mm deep")
