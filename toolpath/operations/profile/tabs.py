"""Holding tabs on a profile's contour: where they sit (spread by count or spacing, or at the user's
points snapped to the contour; never within a tool radius of a corner) and the height the tool
centre keeps over them.

A tab is measured where it is thinnest, in the middle of the kerf: ``width`` along the contour and
``height`` above the cut's bottom (the stock's bottom for a cut through).  The tool centre keeps at
the tab's top over ``width`` + the tool's diameter (a flat end mill's disc reaches a radius either
side), so the kerf's middle keeps exactly ``width``.  A flat tab's ends fall at 45 degrees (the
steepest ramp, :data:`ramp.MAX_ANGLE`): an end mill never drops straight into the material behind a
tab.  A triangular tab is a ridge ``height`` high on a ``width`` base in the kerf's middle; the tool
centre climbs and descends its flanks, which may not be steeper than 45 degrees.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...engines import ramp
from . import contours as ct
from .contours import ProfileError

FLANK = math.tan(math.radians(ramp.MAX_ANGLE))     # the flat tab's ends: mm down per mm along
SEARCH = 240                                       # start offsets tried when spreading tabs


@dataclass(frozen=True)
class TabShape:
    """The tool centre's height over one tab: ``top`` (the tab's top Z), ``floor`` (the cut's
    bottom Z), ``half`` (half the length held at the top, or the apex's half-base for a triangle),
    ``slope`` (mm down per mm along on the ends), ``triangle``."""

    top: float
    floor: float
    half: float
    slope: float
    triangle: bool
    radius: float = 0.0

    @property
    def peak(self) -> float:
        """The tool centre's highest Z: a triangle's apex is a radius of its flank above the tab's."""
        return self.top + (self.radius * self.slope if self.triangle else 0.0)

    @property
    def reach(self) -> float:
        """Half the tab's whole length along the tool centre's path (to where it meets the floor)."""
        if self.triangle:
            return (self.peak - self.floor) / self.slope
        return self.half + (self.top - self.floor) / self.slope

    def height(self, d: np.ndarray) -> np.ndarray:
        """The tool centre's lowest Z at distance ``d`` along the contour from the tab's centre."""
        d = np.abs(np.asarray(d, float))
        if self.triangle:
            return self.peak - self.slope * d
        return np.where(d <= self.half, self.top, self.top - self.slope * (d - self.half))

    def stations(self, levels) -> list:
        """Distances from the centre where the height bends or crosses a level (vertices needed
        there so straight moves follow it)."""
        out = [0.0, self.half] if not self.triangle else [0.0]
        for z in levels:
            if z < self.peak:
                out.append((self.peak - z) / self.slope if self.triangle else self.half + (self.top - z) / self.slope)
        return out


def shape_of(width: float, height: float, triangle: bool, radius: float, floor: float, bottom: float) -> TabShape:
    top = max(floor, bottom) + height
    if triangle:
        slope = 2.0 * height / width
        if slope > FLANK + 1e-9:
            raise ProfileError(f"profile: a triangular tab tab_height {height:g} mm high on tab_width {width:g} mm has "
                               f"flanks steeper than {ramp.MAX_ANGLE:g} degrees: make it at least {2 * height:g} mm wide")
        return TabShape(top, floor, width / 2 + radius, slope, True, radius)
    return TabShape(top, floor, width / 2 + radius, FLANK, False, radius)


def clearance(path: np.ndarray, corner_points: list, offset: float, radius: float) -> list:
    """(arclength, half-length) of every corner of the shape on this tool-centre path: a tab keeps
    a tool radius off the corner and off the arc the tool turns round it."""
    zones = []
    for point, turn in corner_points:
        s, dist, _ = ct.nearest(path, point)
        if dist <= abs(offset) + 0.05:
            zones.append((s, radius + abs(offset) * abs(turn) / 2))
    return zones


def _free(s: float, perimeter: float, zones: list, reach: float) -> bool:
    for centre, half in zones:
        gap = abs((s - centre + perimeter / 2) % perimeter - perimeter / 2)
        if gap < half + reach:
            return False
    return True


def spread(path: np.ndarray, count: int, zones: list, shape: TabShape, where: str) -> list:
    """``count`` tab centres (arclengths) spread evenly round the closed path, each kept off the
    corner zones, two tabs never overlapping."""
    perimeter = float(ct.lengths(path)[-1])
    if count <= 0:
        return []
    if 2 * count * shape.reach >= perimeter:
        raise ProfileError(f"profile: tab_width and tab_height make each tab {2 * shape.reach:.1f} mm long; {count} "
                           f"of them do not fit on {where} ({perimeter:.1f} mm round)")
    step = perimeter / count
    for trial in range(SEARCH):
        start = step * trial / SEARCH
        centres = [start + k * step for k in range(count)]
        if all(_free(s, perimeter, zones, shape.reach) for s in centres):
            return centres
    # slide each tab to the nearest free place, keeping them apart
    grid = np.linspace(0.0, perimeter, max(int(perimeter / 0.25), 8), endpoint=False)
    free = np.array([_free(s, perimeter, zones, shape.reach) for s in grid])
    chosen = []
    for k in range(count):
        ideal = k * step
        order = np.argsort(np.abs((grid - ideal + perimeter / 2) % perimeter - perimeter / 2))
        for index in order:
            s = float(grid[index])
            if free[index] and _free(s, perimeter, [(c, shape.reach) for c in chosen], shape.reach):
                chosen.append(s)
                break
        else:
            raise ProfileError(f"profile: {count} tab(s) do not fit on {where} ({perimeter:.1f} mm round) a tool "
                               "radius off its corners: give fewer tabs or a smaller tab_width")
    return sorted(chosen)


def snapped(paths: list, points, zones_of: list, shape: TabShape) -> list:
    """The user's tab points ((x, y), ...) on the nearest contour: a list per path of arclengths."""
    found = [[] for _ in paths]
    for index, point in enumerate(points):
        best = min(((ct.nearest(path, point), k) for k, path in enumerate(paths)), key=lambda item: item[0][1])
        (s, _, _), k = best
        perimeter = float(ct.lengths(paths[k])[-1])
        where = f"tabs[{index}] at ({float(point[0]):g}, {float(point[1]):g})"
        if 2 * shape.reach >= perimeter:
            raise ProfileError(f"profile: {where}: the tab ({2 * shape.reach:.1f} mm long with tab_width and "
                               f"tab_height) is longer than its contour ({perimeter:.1f} mm round)")
        if not _free(s, perimeter, zones_of[k], shape.reach):
            raise ProfileError(f"profile: {where} sits within a tool radius of a corner: move it along the contour")
        if not _free(s, perimeter, [(c, shape.reach) for c in found[k]], shape.reach):
            raise ProfileError(f"profile: {where} overlaps another tab: move them apart")
        found[k].append(s)
    return [sorted(item) for item in found]


def lift(points: np.ndarray, along: np.ndarray, perimeter: float, centres: list, shape: TabShape) -> np.ndarray:
    """The points (k, 3) with Z raised over the tabs (``along``: each point's arclength)."""
    if not centres:
        return points
    out = points.copy()
    for centre in centres:
        d = (along - centre + perimeter / 2) % perimeter - perimeter / 2
        near = np.abs(d) < shape.reach
        out[near, 2] = np.maximum(out[near, 2], shape.height(d[near]))
    return out


def stations(centres: list, shape: TabShape, levels) -> list:
    return [c + sign * d for c in centres for d in shape.stations(levels) for sign in (1.0, -1.0)]
