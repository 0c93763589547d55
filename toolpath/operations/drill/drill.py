"""Drilling: holes straight down with a drill, as G0/G1 moves and, said alongside, as the drilling
cycle those moves are (:class:`..ir.cycles.DrillCycle`), so a post whose control has canned cycles
writes G81/G82/G83 and every other post and the simulation read the moves.

A hole (the canned cycles' motion, :mod:`..ir.cycles`): rapid in XY at the clearance plane (the
cycle's initial Z), rapid down to the R plane ``approach_gap`` above the stock's top, feed to the
full depth (``peck`` 0), or peck: feed ``peck`` mm at a time from the R plane, rapid back to the R
plane after each peck to clear the chips and rapid down again to ``peck_gap`` above the depth
reached; at the full depth dwell ``dwell`` seconds (0: none), then rapid up to the clearance plane
(``retract`` "initial", G98) or to the R plane (``retract`` "r", G99: the next hole's XY move is
made there).  ``depth`` is to the drill's tip; a through hole needs the point's length more than
the stock (``Tool`` kind "drill": its point angle is the shape's, :mod:`..ir.tools`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...ir.cycles import DrillCycle
from ...ir.errors import MAX_REACH_MM, InputError
from ...ir.program import Operation, PathBuilder, Tool
from ..fields import FINITE, Fields, one_of, positive, zero_or_more


class DrillError(InputError):
    """Holes or settings that cannot be drilled; the message names the hole or the setting."""


RETRACTS = ("initial", "r")
# The settings each within its own bounds, checked in this order (DrillSettings.check relates them between).
FIELDS = Fields(FINITE, (*map(positive, ("depth", "rpm", "feed")),
                         *map(zero_or_more, ("peck", "peck_gap", "approach_gap", "dwell", "breakthrough",
                                             "min_diameter", "max_diameter"))))
RETRACT = Fields(FINITE, (one_of("retract", RETRACTS),))
HELIX_FIELDS = Fields(FINITE, tuple(map(positive, ("mill_rpm", "mill_feed", "helix_pitch"))))
SPOT_FIELDS = Fields(FINITE, (positive("spot_depth"),))


@dataclass(frozen=True)
class DrillSettings:
    tool: Tool = field(default_factory=lambda: Tool(4, "drill", 5.0, flute_length=40.0, name="5 mm drill"))
    depth: float = 10.0          # below the stock's top, to the tip (mm); holes found in a mesh bring their own
    peck: float = 3.0            # deepest feed of one peck (mm); 0: no pecking
    peck_gap: float = 0.5        # how far above the last depth the next peck starts feeding (mm)
    dwell: float = 0.0           # seconds at the bottom (a drill without pecks: G82)
    retract: str = "initial"     # between holes: "initial" (the clearance plane, G98) or "r" (the R plane, G99)
    rpm: float = 3000.0
    feed: float = 150.0          # mm/min down the hole
    approach_gap: float = 2.0    # above the stock's top where feeding starts: the R plane (mm)
    clearance_z: float = 20.0
    safe_z: float = 20.0
    breakthrough: float = 0.5    # below a through hole's bottom, beyond the drill's point (mm)
    order: str = "shortest"      # "shortest" (nearest neighbour + 2-opt) or "given"
    min_diameter: float = 0.0    # holes found in the model: only those at least this wide (mm)
    max_diameter: float = 0.0    # ... and at most this wide (0: no limit)
    helix: bool = False          # mill holes wider than the drill with a helix of an end mill
    mill: Tool = field(default_factory=lambda: Tool(5, "flat", 6.0, flute_length=25.0, name="6 mm end mill"))
    mill_rpm: float = 12000.0
    mill_feed: float = 800.0
    helix_pitch: float = 1.0     # mm down per turn of the helix
    spot: bool = False           # a spot drill (or chamfer) pass at every hole first
    spot_tool: Tool = field(default_factory=lambda: Tool(6, "drill", 10.0, flute_length=20.0, name="10 mm spot drill",
                                                         label="spot drill"))
    spot_depth: float = 1.0      # to the spot tool's tip (mm)

    def check(self) -> None:
        if self.tool.shape.kind != "drill":
            raise DrillError(f"drilling needs a drill, not a {self.tool.describe()}")
        FIELDS.check(self, "drilling", DrillError)
        if self.peck > 0 and self.dwell > 0:
            raise DrillError("drilling: dwell is for holes drilled without pecks (peck = 0); "
                             f"got peck {self.peck:g} mm and dwell {self.dwell:g} s")
        RETRACT.check(self, "drilling", DrillError)
        if self.order not in ("shortest", "given"):
            raise DrillError(f"drilling: order must be 'shortest' or 'given', got {self.order!r}")
        if self.max_diameter and self.max_diameter < self.min_diameter:
            raise DrillError(f"drilling: max_diameter {self.max_diameter:g} mm is below min_diameter "
                             f"{self.min_diameter:g} mm")
        if self.depth > self.tool.flute_length:
            raise DrillError(f"drilling: depth {self.depth:g} mm is deeper than the {self.tool.describe()}'s "
                             f"{self.tool.flute_length:g} mm flutes")
        if not self.approach_gap < self.clearance_z <= self.safe_z:
            raise DrillError(f"drilling: the approach gap {self.approach_gap:g} mm, clearance plane "
                             f"{self.clearance_z:g} mm and safe Z {self.safe_z:g} mm must rise in that order")
        if self.helix:
            if self.mill.shape.kind != "flat":
                raise DrillError(f"helix milling needs a flat end mill, not a {self.mill.describe()}")
            HELIX_FIELDS.check(self, "helix milling", DrillError)
        if self.spot and self.spot_tool.shape.kind != "drill":
            raise DrillError(f"spot drilling needs a pointed drill that plunges, not a {self.spot_tool.describe()}")
        if self.spot:
            SPOT_FIELDS.check(self, "spot drilling", DrillError)

    def point_length(self) -> float:
        """How far the drill's point reaches below its full diameter: r / tan(half point angle)."""
        half = math.radians(self.tool.shape.tip_angle_deg) / 2
        return self.tool.radius / math.tan(half)


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
    far = np.flatnonzero(np.abs(points).max(axis=1) > MAX_REACH_MM)
    if len(far):
        raise DrillError(f"hole {int(far[0]) + 1} at {points[far[0]].tolist()} lies beyond the {MAX_REACH_MM:g} mm "
                         f"any machine reaches (a unit mistake?)")
    pair = first_coincident(points, 1e-3)
    if pair is not None:
        i, j = pair
        raise DrillError(f"holes {i + 1} and {j + 1} are the same point {points[i].tolist()}")
    return points


def first_coincident(points: np.ndarray, tolerance: float):
    """The first pair (i, j), i < j, in (i, j) order, of points closer than ``tolerance``, or None.
    Points are binned in cells of ``tolerance``: a close pair lies in one cell or two neighbouring
    ones, so only those are compared (n log n; comparing every pair took 14 s for 25,000 holes)."""
    # within MAX_REACH_MM a cell index is below 2^27 in size: two of them make one int64 key
    cells = np.floor(points / tolerance).astype(np.int64) + (1 << 27)
    keys = cells[:, 0] * (1 << 29) + cells[:, 1]
    order = np.argsort(keys, kind="stable")
    sorted_keys = keys[order]
    found = []
    for dx, dy in ((0, 0), (0, 1), (1, -1), (1, 0), (1, 1)):
        target = sorted_keys + dx * (1 << 29) + dy
        lo = np.searchsorted(sorted_keys, target, "left")
        hi = np.searchsorted(sorted_keys, target, "right")
        if (dx, dy) == (0, 0):
            lo = np.arange(len(order)) + 1          # the same cell: each pair once
        counts = np.maximum(hi - lo, 0)
        if not counts.any():
            continue
        a = np.repeat(np.arange(len(order)), counts)
        b = np.concatenate([np.arange(l, h) for l, h in zip(lo[counts > 0], hi[counts > 0])])
        a, b = order[a], order[b]
        close = np.hypot(*(points[a] - points[b]).T) < tolerance
        found += [(min(i, j), max(i, j)) for i, j in zip(a[close].tolist(), b[close].tolist())]
    return min(found) if found else None


def cycle_kind(peck: float, dwell: float) -> str:
    return "peck" if peck > 0 else ("dwell" if dwell > 0 else "drill")


def plan(holes, settings: DrillSettings = DrillSettings(), name: str = "drill", top: float = 0.0,
         depth: float | None = None, tool: Tool | None = None, rpm: float | None = None) -> Operation:
    """One operation drilling every hole in the given order to ``depth`` below ``top`` (the stock's
    top Z; None: the settings' depth), with ``tool`` (None: the settings' drill)."""
    settings.check()
    points = check_holes(holes)
    tool = tool or settings.tool
    depth = settings.depth if depth is None else depth
    if not (math.isfinite(depth) and depth > 0):
        raise DrillError(f"drilling: depth must be a positive number, got {depth!r}")
    if depth > tool.flute_length:
        raise DrillError(f"drilling: depth {depth:g} mm is deeper than the {tool.describe()}'s "
                         f"{tool.flute_length:g} mm flutes")
    bottom = top - depth
    r_z = top + settings.approach_gap
    peck = settings.peck if tool is settings.tool else 0.0
    dwell = settings.dwell if tool is settings.tool else 0.0
    between = settings.clearance_z if settings.retract == "initial" else r_z
    path = PathBuilder(settings.clearance_z, settings.feed, settings.feed, settings.approach_gap, top)
    path.rapid(points[0][0], points[0][1], settings.clearance_z)
    for index, (x, y) in enumerate(points):
        if index:
            path.rapid(x, y, between)
        path.rapid(x, y, r_z)
        reached = r_z
        while reached > bottom + 1e-9:
            target = bottom if peck <= 0 else max(bottom, reached - peck)
            if reached < r_z:                    # back down to just above the last depth
                path.rapid(x, y, min(r_z, reached + settings.peck_gap))
            path.line(x, y, target)
            reached = target
            if reached > bottom + 1e-9:
                path.rapid(x, y, r_z)            # out to clear the chips
        path.rapid(x, y, between)
    if between < settings.clearance_z:
        path.rapid(points[-1][0], points[-1][1], settings.clearance_z)
    arrays = path.arrays()
    cycle = DrillCycle(cycle_kind(peck, dwell), tuple(map(tuple, points.tolist())), settings.clearance_z, r_z,
                       bottom, settings.feed, peck, dwell, settings.retract)
    return Operation(name, tool, settings.rpm if rpm is None else rpm, arrays["kind"], arrays["xyz"],
                     arrays["feed"], clearance_z=settings.clearance_z, safe_z=settings.safe_z,
                     start=np.array([points[0][0], points[0][1], settings.safe_z]),
                     comment=f"drill {len(points)} holes {depth:g} mm deep", cycle=cycle)
