"""Pocketing: any closed region (loops read even-odd, so a loop inside another is an island)
cleared to a flat floor with a flat end mill.

The operation of the main tool roughs the region shrunk by the wall allowance down to the floor
less the floor allowance, in step-downs, by offset rings from the inside out (climb milling with
a clockwise spindle) or by a zigzag at an angle; then a floor pass at the full depth over the
same area takes the floor allowance, and a ring along every wall (ramped down along itself, step
by step) takes the wall allowance.  Every path is entered on a helix inside the region where one
fits, else on a ramp along the path (:mod:`.clearing`); never straight down.

Rest machining with a smaller tool is a second operation: it cuts only the region less what the
main tool's clearing covered (the region's opening by the main tool's radius: every disc of that
radius inside the region), by region booleans; its tool centres stay within its radius of that
rest.  Moves are straight lines; arcs are fitted by the posts' common step.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from manifold3d import CrossSection, FillRule

from ...engines import ramp
from ...engines import region as rg
from ...ir.errors import MAX_REACH_MM, InputError
from ...ir.program import Operation, Tool
from ..fields import NUMBER, Field, Fields, one_of, positive, zero_or_more
from ..stepnc.motion import round_offset
from .clearing import ClearingError, Cutter, offset_rings, zigzag_chains

STRATEGIES = ("offset", "zigzag")
ENTRIES = ("helix", "ramp")
REST_DUST = 0.01          # mm: slivers of the rest narrower than this are the offsets' chord error
MAX_CROSSING_POINTS = 20000
MIN_STEP = 0.01           # mm: the finest stepover and step-down (finer is a typing slip, and runs for hours)
MAX_LEVELS = 1000         # step-down levels in one pocket
MIN_RAMP_ANGLE = 0.5      # degrees: a shallower ramp travels over 100 mm per mm of depth
MIN_HELIX = 0.1           # mm: the smallest helix diameter (0: no helix)
MAX_TRAVEL = 5.0e6        # mm of cutting in one operation (5 km: days at any feed) is a typing slip
# The settings each within its own bounds, checked in this order (PocketSettings.check then relates them);
# the helix's diameter after the levels.
FIELDS = Fields(NUMBER, (
    *map(positive, ("depth", "step_down", "stepover", "rpm", "feed", "entry_feed", "rest_stepover",
                    "rest_step_down", "rest_rpm", "rest_feed")),
    *map(zero_or_more, ("helix_diameter", "wall_allowance", "floor_allowance")),
    one_of("strategy", STRATEGIES), one_of("entry", ENTRIES),
    Field("ramp_angle", low=MIN_RAMP_ANGLE, high=ramp.MAX_ANGLE, unit="degrees"),
    *(Field(name, low=MIN_STEP, unit="mm") for name in ("stepover", "step_down", "rest_stepover", "rest_step_down")),
    Field("clearance_z"), Field("safe_z"), Field("angle")))
HELIX = Fields(NUMBER, (Field("helix_diameter", low=MIN_HELIX, high=MAX_REACH_MM, unit="mm", zero="no helix"),))


class PocketError(InputError):
    """A region or settings that cannot be pocketed; the message names the pocket and the setting."""


def end_mill(number: int, diameter: float, flute_length: float = 22.0) -> Tool:
    return Tool(number, "flat", diameter, flute_length=flute_length, name=f"{diameter:g} mm end mill")


@dataclass(frozen=True)
class PocketSettings:
    tool: Tool = field(default_factory=lambda: end_mill(5, 6.0))
    depth: float = 5.0              # below the stock's top (mm)
    step_down: float = 2.0          # deepest cut of one level (mm)
    stepover: float = 2.4           # between neighbouring paths (mm), at most the diameter
    strategy: str = "offset"        # "offset": rings from the inside out; "zigzag": a raster at ``angle``
    angle: float = 0.0              # zigzag: degrees from +X
    entry: str = "helix"            # "helix" (a ramp along the path where it does not fit) or "ramp"
    helix_diameter: float = 4.0     # of the helix the tool centre follows (mm)
    ramp_angle: float = 3.0         # degrees from horizontal, of the helix and the ramps
    finish_walls: bool = False      # a ring along every wall at the end, ramped down level by level
    wall_allowance: float = 0.0     # left on the walls by roughing (mm)
    finish_floor: bool = False      # a pass over the floor at the full depth
    floor_allowance: float = 0.0    # left on the floor by roughing (mm)
    rest_tool: Tool | None = None   # a smaller flat end mill for what the main tool cannot reach
    rest_stepover: float = 0.8
    rest_step_down: float = 1.0
    rest_rpm: float = 20000.0
    rest_feed: float = 500.0
    rpm: float = 18000.0
    feed: float = 1200.0            # mm/min
    entry_feed: float = 400.0       # mm/min down helices and ramps
    clearance_z: float = 5.0
    safe_z: float = 20.0

    def check(self, what: str = "pocket") -> None:
        tools = [("tool", self.tool)] + ([("rest_tool", self.rest_tool)] if self.rest_tool is not None else [])
        for name, tool in tools:
            if not isinstance(tool, Tool) or tool.kind != "flat":
                raise PocketError(f"{what}: {name} must be a flat end mill, not a "
                                  f"{tool.describe() if isinstance(tool, Tool) else repr(tool)}")
        FIELDS.check(self, what, PocketError)
        for name, step in (("step_down", self.step_down), ("rest_step_down", self.rest_step_down)):
            if self.depth / step > MAX_LEVELS:
                raise PocketError(f"{what}: depth {self.depth:g} mm at a {name} of {step:g} mm makes more than "
                                  f"{MAX_LEVELS} levels")
        HELIX.check(self, what, PocketError)
        if self.stepover > self.tool.diameter:
            raise PocketError(f"{what}: stepover {self.stepover:g} mm is more than the {self.tool.describe()}'s "
                              f"diameter: material would stand between the paths")
        if self.rest_tool is not None and self.rest_stepover > self.rest_tool.diameter:
            raise PocketError(f"{what}: rest_stepover {self.rest_stepover:g} mm is more than the "
                              f"{self.rest_tool.describe()}'s diameter")
        if self.depth > self.tool.flute_length:
            raise PocketError(f"{what}: depth {self.depth:g} mm is deeper than the {self.tool.describe()}'s "
                              f"{self.tool.flute_length:g} mm flutes")
        if self.rest_tool is not None:
            if self.rest_tool.diameter >= self.tool.diameter:
                raise PocketError(f"{what}: rest_tool ({self.rest_tool.describe()}) must be smaller than the "
                                  f"tool ({self.tool.describe()})")
            if self.depth > self.rest_tool.flute_length:
                raise PocketError(f"{what}: depth {self.depth:g} mm is deeper than the rest tool's "
                                  f"{self.rest_tool.flute_length:g} mm flutes")
            if self.rest_tool.number == self.tool.number:
                raise PocketError(f"{what}: rest_tool and tool have the same tool number {self.tool.number}")
        for name, finish in (("wall_allowance", "finish_walls"), ("floor_allowance", "finish_floor")):
            if getattr(self, name) > 0 and not getattr(self, finish):
                raise PocketError(f"{what}: {name} {getattr(self, name):g} mm is left by roughing but {finish} is "
                                  f"off: no pass would take it")
        if self.wall_allowance >= self.tool.radius:
            raise PocketError(f"{what}: wall_allowance {self.wall_allowance:g} mm must be less than the tool's "
                              f"radius {self.tool.radius:g} mm (one finishing ring takes it)")
        if self.floor_allowance >= self.depth:
            raise PocketError(f"{what}: floor_allowance {self.floor_allowance:g} mm must be less than the depth "
                              f"{self.depth:g} mm")
        if not 0 < self.clearance_z <= self.safe_z:
            raise PocketError(f"{what}: clearance_z {self.clearance_z:g} mm and safe_z {self.safe_z:g} mm must be "
                              "above the stock's top and rise in that order")


@dataclass
class PocketResult:
    operations: list            # the main tool's Operation, then the rest tool's (if any)
    region: CrossSection        # the pocket
    covered: CrossSection | None    # what the main tool clears (with rest machining)
    rest: CrossSection | None   # the region less what the main tool covered (rest machining's target)
    warnings: list


def crossing_point(points: np.ndarray):
    """Where two non-neighbouring edges of the closed loop cross, or None."""
    if len(points) > MAX_CROSSING_POINTS:
        return None
    a, b = points, np.roll(points, -1, axis=0)
    d = b - a
    n = len(points)
    for i in range(n):
        j = np.arange(i + 2, n if i else n - 1)
        if not len(j):
            continue
        denom = d[i, 0] * d[j, 1] - d[i, 1] * d[j, 0]
        rel = a[j] - a[i]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (rel[:, 0] * d[j, 1] - rel[:, 1] * d[j, 0]) / denom
            u = (rel[:, 0] * d[i, 1] - rel[:, 1] * d[i, 0]) / denom
        hit = np.flatnonzero((np.abs(denom) > 1e-15) & (t >= 0) & (t <= 1) & (u >= 0) & (u <= 1))
        if len(hit):
            return a[i] + d[i] * t[hit[0]]
    return None


def region_of(loops, what: str = "pocket") -> CrossSection:
    """The region of closed loops read even-odd; an open, degenerate or self-crossing loop is
    refused by its number."""
    if isinstance(loops, np.ndarray) and loops.ndim == 2:
        loops = [loops]
    try:
        loops = list(loops)
    except TypeError:
        raise PocketError(f"{what}: the region must be a list of closed loops of (x, y) points") from None
    if not loops:
        raise PocketError(f"{what}: the region has no closed loop")
    clean = []
    for number, loop in enumerate(loops, 1):
        try:
            points = rg.validate_loop(loop, f"{what}: loop {number}")
        except rg.RegionError as error:
            raise PocketError(str(error)) from None
        except (TypeError, ValueError):
            raise PocketError(f"{what}: loop {number} is not a list of (x, y) points") from None
        alone = CrossSection([points], FillRule.EvenOdd).area()
        if max(alone, abs(rg.signed_area(points))) < rg.MIN_AREA:
            raise PocketError(f"{what}: loop {number} encloses no area (less than {rg.MIN_AREA:g} mm^2)")
        if abs(alone - abs(rg.signed_area(points))) > 1e-6 * alone + 1e-9:
            place = crossing_point(points)
            if place is None:
                raise PocketError(f"{what}: loop {number} crosses itself: draw it as separate closed loops")
            raise PocketError(f"{what}: loop {number} crosses itself at X{place[0]:.3f} Y{place[1]:.3f}: draw it as "
                              "separate closed loops")
        clean.append(points)
    region = CrossSection(clean, FillRule.EvenOdd)
    if region.area() < rg.MIN_AREA:
        raise PocketError(f"{what}: the loops enclose no area (even-odd: each loop inside another is an island)")
    return region


def _chains(centres: CrossSection, strategy: str, stepover: float, radius: float, angle: float, what: str,
            warnings: list, levels: int) -> list:
    """The clearing paths, refused when the operation would cut more than MAX_TRAVEL mm."""
    rows = (centres.bounds()[3] - centres.bounds()[1] + centres.bounds()[2] - centres.bounds()[0]) / stepover
    if centres.area() / stepover * levels > MAX_TRAVEL or rows > rg.MAX_ROWS:
        raise PocketError(f"{what}: a stepover of {stepover:g} mm over {levels} levels cuts more than "
                          f"{MAX_TRAVEL / 1e6:g} km: raise the stepover or the step-down")
    if strategy == "zigzag":
        return zigzag_chains(centres, stepover, angle)
    spacing = stepover
    if stepover > radius:
        spacing = radius
        warnings.append(f"{what}: offset rings {radius:g} mm apart (the tool's radius), not the stepover "
                        f"{stepover:g} mm: rings further apart leave material between them")
    return offset_rings(centres, spacing)


def _operation(name, tool, rpm, arrays, cutter, settings, comment) -> Operation:
    first = arrays["xyz"][0]
    return Operation(name, tool, rpm, arrays["kind"], arrays["xyz"], arrays["feed"],
                     clearance_z=settings.clearance_z, safe_z=settings.safe_z,
                     start=np.array([first[0], first[1], settings.safe_z]), comment=comment,
                     links=cutter.path.links())


def plan(loops, settings: PocketSettings = PocketSettings(), name: str = "pocket", top: float = 0.0,
         progress=None) -> PocketResult:
    """Plan the pocket (see the module notes); ``top``: the stock's top Z; ``name`` names it in
    messages and in the operations."""
    what = f"pocket {name!r}"
    settings.check(what)
    region = region_of(loops, what)
    tool, radius, warnings = settings.tool, settings.tool.radius, []
    floor = top - settings.depth
    centres = round_offset(region, -(radius + settings.wall_allowance))
    if centres.area() < rg.MIN_AREA:
        (x0, y0), (x1, y1) = region.bounds()[:2], region.bounds()[2:]
        if settings.wall_allowance > 0:
            raise PocketError(f"{what}: the {tool.diameter:g} mm end mill with the {settings.wall_allowance:g} mm wall "
                              f"allowance does not fit in the region (X{x0:.2f}..{x1:.2f} Y{y0:.2f}..{y1:.2f})")
        raise PocketError(f"{what}: the {tool.diameter:g} mm end mill does not fit in the region "
                          f"(X{x0:.2f}..{x1:.2f} Y{y0:.2f}..{y1:.2f})")
    helix = settings.helix_diameter / 2 if settings.entry == "helix" else 0.0
    cutter = Cutter(centres, settings.clearance_z, settings.feed, settings.entry_feed, helix, settings.ramp_angle,
                    radius, what, tool.diameter, settings.helix_diameter)
    rough_floor = floor + settings.floor_allowance
    levels = ramp.levels(rough_floor, settings.step_down, top)
    chains = _chains(centres, settings.strategy, settings.stepover, radius, settings.angle, what, warnings,
                     len(levels) + 2)
    try:
        cutter.cut(chains, levels, top)
        if progress is not None:
            progress(0.4)
        if settings.finish_floor:
            cutter.cut(chains, [floor], rough_floor)
        if settings.finish_walls:
            walls = round_offset(region, -radius)
            cutter.walls(walls, ramp.levels(floor, settings.step_down, top), top)
    except ClearingError as error:
        raise PocketError(str(error)) from None
    if cutter.cut_nothing():
        raise PocketError(cutter.refusal)
    warnings += cutter.notes
    arrays = cutter.finish(settings.safe_z)
    operations = [_operation(name, tool, settings.rpm, arrays, cutter, settings,
                             f"pocket {settings.depth:g} mm deep, {settings.strategy}")]
    covered, rest = None, None
    if settings.rest_tool is not None:
        covered = round_offset(round_offset(region, -radius), radius)
        rest = _rest(region, covered, settings, name, top, warnings, operations)
    return PocketResult(operations, region, covered, rest, warnings)


def _rest(region, covered, settings: PocketSettings, name: str, top: float, warnings: list, operations: list):
    """The rest machining operation (appended to ``operations``); returns the rest region."""
    what = f"pocket {name!r}"
    tool = settings.rest_tool
    rest = round_offset(round_offset(region - covered, -REST_DUST), REST_DUST)
    centres = round_offset(region, -tool.radius) ^ round_offset(rest, tool.radius)
    if rest.area() < rg.MIN_AREA or centres.area() < rg.MIN_AREA:
        warnings.append(f"{what}: rest machining: the {tool.diameter:g} mm end mill finds nothing the "
                        f"{settings.tool.diameter:g} mm one left")
        return rest
    cutter = Cutter(centres, settings.clearance_z, settings.rest_feed, settings.entry_feed, 0.0, settings.ramp_angle,
                    tool.radius, f"{what} (rest machining)", tool.diameter, 0.0)
    levels = ramp.levels(top - settings.depth, settings.rest_step_down, top)
    chains = _chains(centres, settings.strategy, settings.rest_stepover, tool.radius, settings.angle, what, warnings,
                     len(levels))
    try:
        cutter.cut(chains, levels, top)
    except ClearingError as error:
        raise PocketError(str(error)) from None
    warnings += cutter.notes
    if cutter.cut_nothing():
        return rest
    arrays = cutter.finish(settings.safe_z)
    operations.append(_operation(f"{name} rest", tool, settings.rest_rpm, arrays, cutter, settings,
                                 f"rest machining after the {settings.tool.diameter:g} mm end mill"))
    return rest
