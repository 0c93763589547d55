"""Profile / cut-out: a flat end mill cuts along a shape's outlines, outside, inside or on them,
down to a depth (by default through the stock onto the spoil board), holding the part with tabs.

How it cuts each contour (contours nested inside others first: holes before the outer cut-out):

* Roughing: the tool centre runs at the tool radius + ``allowance`` off the outline, in equal
  step-downs of at most ``step_down`` (:func:`ramp.levels`), each level entered on a ramp of
  ``ramp_angle`` along the contour itself (:func:`ramp.ramped_passes`): the end mill never feeds
  straight down into material.  The first ramp starts at the stock's top.
* Tabs (:mod:`.tabs`): the tool centre keeps over each tab; its ends fall at 45 degrees.
* Finishing (``allowance`` > 0): one full-depth pass at the tool radius.  The tool goes down in
  the roughed kerf (its disc inside what roughing cleared), moves out to the lead-in's start in
  the waste and comes onto the contour along the lead-in (a quarter arc tangent to it, or a line
  along its normal), runs once round and leaves along the lead-out.  Without an allowance the
  last roughing level is the finishing one and leaves along the lead-out.
* Leads sit in the waste (outside an outside profile, inside an inside one), at the place of the
  contour farthest from its tabs and corners where they fit without touching the part.

Climb milling (spindle M03) keeps the part on the tool's right: clockwise round an outside
contour, counter-clockwise inside a hole.  Straight moves only (arcs are walked in chords).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...engines import ramp
from ...engines import region as rg
from ...ir.program import Operation, PathBuilder, ProgramError, Tool
from ..fields import NUMBER, Field, Fields, one_of, positive, zero_or_more
from . import contours as ct
from . import tabs as tb
from .contours import ProfileError

SIDES = ("outside", "inside", "on")
TAB_SHAPES = ("flat", "triangle")
LEADS = ("arc", "line", "none")
KEEP_MARGIN = 0.02      # mm inside the part where the design layer starts to keep material
KEEP_BAND = 1.0         # mm: how wide the band of the part's edge the design layer keeps is
MAX_LEVELS = 1000      # step-downs: more than this is a step_down typed wrong, not a job
STAND = 0.05            # mm above the cut's bottom the part's edge must reach (it is not cut through)
# The settings each within its own bounds, checked in this order (ProfileSettings.check then relates them).
FIELDS = Fields(NUMBER, (
    one_of("side", SIDES), one_of("tab_shape", TAB_SHAPES), one_of("lead", LEADS),
    *map(positive, ("step_down", "rpm", "feed", "plunge_feed", "tab_width", "tab_height")),
    *map(zero_or_more, ("breakthrough", "allowance", "tab_spacing", "lead_radius", "approach_gap")),
    Field("ramp_angle", low=0.0, above=True, high=ramp.MAX_ANGLE, unit="degrees"),
    Field("clearance_z"), Field("safe_z")))


def _default_tool() -> Tool:
    return Tool(5, "flat", 6.0, flute_length=25.0, name="6 mm end mill")


@dataclass(frozen=True)
class ProfileSettings:
    """Every number of a profile (mm, mm/min, rpm, degrees).  ``depth`` None: through the stock
    and ``breakthrough`` more into the spoil board.  Tabs: ``tab_count`` on every contour, or
    every ``tab_spacing`` mm round it, or at the points ``tabs`` ((x, y), ...) snapped to the
    nearest contour."""

    tool: Tool = field(default_factory=_default_tool)
    side: str = "outside"
    climb: bool = True
    depth: float | None = None
    breakthrough: float = 0.3
    step_down: float = 3.0
    allowance: float = 0.0
    rpm: float = 18000.0
    feed: float = 1500.0
    plunge_feed: float = 300.0
    # 3 degrees: the low end of the 2-5 degrees a standard end mill ramps at (carbide-tooling.com,
    # "Ramping Angle Calculator"), as the engraving's band finishing uses
    ramp_angle: float = 3.0
    tab_count: int = 0
    tab_spacing: float = 0.0
    tab_width: float = 8.0
    tab_height: float = 3.0
    tab_shape: str = "flat"
    tabs: tuple = ()
    lead: str = "arc"
    lead_radius: float = 3.0
    clearance_z: float = 20.0
    safe_z: float = 20.0
    approach_gap: float = 2.0

    def check(self, thickness: float) -> None:
        if self.tool.shape.kind != "flat":
            raise ProfileError(f"profile: tool: a profile is cut with a flat end mill, not a {self.tool.describe()}")
        FIELDS.check(self, "profile", ProfileError)
        if isinstance(self.tab_count, bool) or not isinstance(self.tab_count, int) or self.tab_count < 0:
            raise ProfileError(f"profile: tab_count must be a whole number 0 or more, got {self.tab_count!r}")
        if self.tab_count and self.tab_spacing:
            raise ProfileError("profile: give tab_count or tab_spacing, not both")
        if self.tabs and (self.tab_count or self.tab_spacing):
            raise ProfileError("profile: give tab positions (tabs) or tab_count / tab_spacing, not both")
        if self.step_down > self.tool.diameter + 1e-9:
            raise ProfileError(f"profile: step_down {self.step_down:g} mm is more than the {self.tool.describe()}'s "
                               "diameter: it would break")
        if self.side == "on" and self.allowance:
            raise ProfileError("profile: allowance leaves material beside the outline: give it with side inside "
                               "or outside, not on")
        if not (math.isfinite(thickness) and thickness > 0):
            raise ProfileError(f"profile: the stock's thickness must be more than 0 mm, got {thickness!r}")
        depth = self.cut_depth(thickness)
        if not (math.isfinite(depth) and depth > 0):
            raise ProfileError(f"profile: depth must be more than 0 mm, got {self.depth!r}")
        if depth > thickness + self.breakthrough + 1e-9:
            raise ProfileError(f"profile: depth {depth:g} mm goes deeper than the {thickness:g} mm stock and its "
                               f"{self.breakthrough:g} mm breakthrough: into the table")
        if depth / self.step_down > MAX_LEVELS:
            raise ProfileError(f"profile: step_down {self.step_down:g} mm makes more than {MAX_LEVELS} levels down "
                               f"{depth:g} mm")
        if depth > self.tool.flute_length + 1e-9:
            raise ProfileError(f"profile: depth {depth:g} mm is deeper than the {self.tool.describe()}'s "
                               f"{self.tool.flute_length:g} mm flutes")
        if not self.approach_gap < self.clearance_z <= self.safe_z:
            raise ProfileError(f"profile: approach_gap {self.approach_gap:g} mm, clearance_z {self.clearance_z:g} mm "
                               f"and safe_z {self.safe_z:g} mm must rise in that order")
        if self.tab_count or self.tab_spacing or self.tabs:
            bottom_depth = min(depth, thickness)
            if self.tab_height >= bottom_depth:
                raise ProfileError(f"profile: tab_height {self.tab_height:g} mm reaches the stock's top (the cut "
                                   f"is {bottom_depth:g} mm deep there)")
            for index, point in enumerate(self.tabs):
                try:
                    x, y = (float(v) for v in point)
                except (TypeError, ValueError):
                    raise ProfileError(f"profile: tabs[{index}] must be an (x, y) pair in mm, got {point!r}") from None
                if not (math.isfinite(x) and math.isfinite(y)):
                    raise ProfileError(f"profile: tabs[{index}] has a coordinate that is not a number: {point!r}")

    def cut_depth(self, thickness: float) -> float:
        return thickness + self.breakthrough if self.depth is None else float(self.depth)


@dataclass
class ProfileResult:
    """What the plan made: the operation; ``loops`` the finishing tool-centre loops in cutting
    order; ``tabs`` the tab centres (x, y) on them; ``floor`` the cut's bottom Z; ``tab_top`` the
    tabs' top Z; ``region`` the shape (a CrossSection); ``warnings``."""

    operation: Operation
    loops: list
    tabs: list
    floor: float
    tab_top: float
    region: object
    warnings: list
    entries: list


def _lead(point, tangent, normal, radius: float, kind: str, into: bool) -> np.ndarray:
    """Lead points (k, 2) ending (``into``) or starting at ``point`` on the contour."""
    if radius <= 0:
        return np.array([point])
    if kind == "line":
        far = point + radius * normal
        return np.array([far, point]) if into else np.array([point, far])
    count = max(4, math.ceil(rg.circle_segments(radius, 0.01) / 4))
    centre = point + radius * normal
    phi = np.linspace(-math.pi / 2, 0.0, count + 1) if into else np.linspace(0.0, math.pi / 2, count + 1)
    return centre + radius * (np.cos(phi)[:, None] * -normal + np.sin(phi)[:, None] * tangent)


def _waste_normal(tangent, climb: bool) -> np.ndarray:
    left = np.array([-tangent[1], tangent[0]])
    return left if climb else -left


def _allowed(side: str, region, radius: float):
    """A test of tool-centre points (k, 2): True where the tool does not touch the part."""
    if side == "inside":
        room = ct.offset(region, -(radius - 0.005))
        return lambda pts: rg.contains_points(room, pts)
    grown = ct.offset(region, radius - 0.005) if side == "outside" else ct.offset(region, -0.005)
    return lambda pts: ~rg.contains_points(grown, pts)


def _entry(path, centres, shape, zones, settings, allowed, lead_room) -> float:
    """The arclength of the contour where the leads go: the free place farthest from tabs and
    corners whose leads do not touch the part."""
    perimeter = float(ct.lengths(path)[-1])
    grid = np.linspace(0.0, perimeter, max(64, min(2000, int(perimeter / 0.5))), endpoint=False)

    def gap(items):
        found = np.full(len(grid), np.inf)
        for centre, half in items:
            found = np.minimum(found, np.abs((grid - centre + perimeter / 2) % perimeter - perimeter / 2) - half)
        return found
    off_tabs = gap([(c, shape.reach) for c in centres])
    score = np.minimum(off_tabs, gap(zones))
    for index in np.argsort(-score, kind="stable"):
        if off_tabs[index] < lead_room:
            continue
        point, tangent = ct.at(path, grid[index])
        normal = _waste_normal(tangent, settings.climb)
        pts = np.vstack([_lead(point, tangent, normal, settings.lead_radius, settings.lead, True),
                         _lead(point, tangent, normal, settings.lead_radius, settings.lead, False)])
        if settings.lead == "none" or allowed(pts).all():
            return float(grid[index])
    raise ProfileError(f"profile: lead_radius {settings.lead_radius:g} mm: the {settings.lead} lead does not fit in "
                       "the waste beside a contour away from its tabs: make lead_radius smaller or lead none")


def _lap_points(path: np.ndarray, levels: list, angle: float, top: float, centres: list, shape) -> tuple:
    """Ramped step-downs round the closed ``path`` (starting at its first point), lifted over the
    tabs, ending back at the start at the last level: (points (k, 3), arclengths)."""
    perimeter = float(ct.lengths(path)[-1])
    points = ramp.ramped_passes(path, levels, angle, top)
    steps = np.hypot(*np.diff(points[:, :2], axis=0).T)
    along = np.concatenate([[0.0], np.cumsum(steps)])
    finish = ct.lengths(path)
    rest = perimeter - along[-1] % perimeter
    if rest > 1e-6 and rest < perimeter - 1e-6:      # walk on to the start at the last level
        s0 = along[-1] % perimeter
        inner = finish[(finish > s0 + 1e-9) & (finish < perimeter - 1e-9)]
        xy = np.column_stack([np.interp(np.append(inner, perimeter), finish, path[:, 0]),
                              np.interp(np.append(inner, perimeter), finish, path[:, 1])])
        points = np.vstack([points, np.column_stack([xy, np.full(len(xy), levels[-1])])])
        along = np.concatenate([along, along[-1] + np.append(inner, perimeter) - s0])
    lifted = tb.lift(points, along % perimeter, perimeter, centres, shape)
    return lifted, along


def plan(loops, settings: ProfileSettings = ProfileSettings(), thickness: float = 20.0, top: float = 0.0,
         name: str = "profile", what: str = "shape") -> ProfileResult:
    """Plan the profile of the closed outlines ``loops`` ((k, 2) arrays in work mm, read even-odd)
    on a stock ``thickness`` mm thick whose top is at ``top``; ``what`` names the shape in messages."""
    settings.check(thickness)
    tool = settings.tool
    r = tool.radius
    region, clean = ct.shape_region(loops, what)
    floor = top - settings.cut_depth(thickness)
    bottom = top - thickness
    part_left = settings.side != "inside"
    sign = -1.0 if settings.side == "inside" else 1.0
    finish_offset = 0.0 if settings.side == "on" else sign * r
    rough_offset = 0.0 if settings.side == "on" else sign * (r + settings.allowance)
    finish = ct.offset(region, finish_offset)
    rough = ct.offset(region, rough_offset)
    count = len(rg.loops(region))
    for shape_, label in ((finish, "finishing"), (rough, "roughing")):
        if len(rg.loops(shape_)) != count:
            if settings.side == "inside":
                raise ProfileError(f"profile: the {tool.describe()} does not fit inside every contour of {what} "
                                   f"for its {label} pass: give a smaller tool or a larger outline")
            raise ProfileError(f"profile: contours of {what} lie closer together than the {tool.describe()} can "
                               f"pass between, or a hole of it is narrower ({label} pass): give a smaller tool or "
                               "move them apart")
    finish_loops = ct.directed(finish, part_left, settings.climb)
    rough_loops = ct.directed(rough, part_left, settings.climb)
    order = ct.nesting_order(finish_loops, (0.0, 0.0))
    levels = ramp.levels(floor, settings.step_down, top)
    shape = tb.shape_of(settings.tab_width, settings.tab_height, settings.tab_shape == "triangle", r, floor, bottom)
    corner_points = ct.corners(clean)
    zones = [tb.clearance(path, corner_points, finish_offset, r) for path in finish_loops]
    if settings.tabs:
        centres = tb.snapped(finish_loops, settings.tabs, zones, shape)
    else:
        centres = []
        for k, path in enumerate(finish_loops):
            perimeter = float(ct.lengths(path)[-1])
            n = settings.tab_count or (max(1, round(perimeter / settings.tab_spacing)) if settings.tab_spacing else 0)
            centres.append(tb.spread(path, n, zones[k], shape, f"contour {k + 1} of {what}"))
    allowed = _allowed(settings.side, region, r)
    lead_room = settings.lead_radius + 1.0       # the lead-in reaches back a radius along the contour
    builder = PathBuilder(settings.clearance_z, settings.feed, settings.plunge_feed, settings.approach_gap, top)
    done_loops, done_tabs, entries = [], [], []
    for k in order:
        path = finish_loops[k]
        s_entry = _entry(path, centres[k], shape, zones[k], settings, allowed, lead_room)
        path = ct.started_at(path, s_entry)
        mine = [(c - s_entry) % float(ct.lengths(path)[-1]) for c in centres[k]]
        point, tangent = path[0], ct.at(path, 1e-6)[1]
        normal = _waste_normal(tangent, settings.climb)
        done_tabs += [ct.at(path, c)[0] for c in mine]
        entries.append(point.copy())
        finishing = settings.allowance > 0
        # roughing: the nearest loop of the roughing offset, started beside the entry
        rpath = min(rough_loops, key=lambda loop: ct.nearest(loop, point)[1])
        s_rough, _, _ = ct.nearest(rpath, point)
        rpath = ct.started_at(rpath, s_rough)
        rtabs = [ct.nearest(rpath, ct.at(path, c)[0])[0] for c in mine]
        rpath = ct.with_points(rpath, tb.stations(rtabs, shape, levels))
        rpath = ct.started_at(rpath, 0.0)
        points, _ = _lap_points(rpath, levels, settings.ramp_angle, top, rtabs, shape)
        builder.retract()
        builder.rapid(points[0, 0], points[0, 1], settings.clearance_z)
        builder.rapid(points[0, 0], points[0, 1], top + settings.approach_gap)
        builder.line(points[0, 0], points[0, 1], top, settings.plunge_feed)
        builder.polyline(points[1:])
        if finishing:
            builder.retract()
            lead_in = _lead(point, tangent, normal, settings.lead_radius, settings.lead, True)
            start = lead_in[0] if settings.lead != "none" else point + settings.allowance * normal
            _, _, q = ct.nearest(rpath, start)
            builder.rapid(q[0], q[1], settings.clearance_z)
            builder.rapid(q[0], q[1], top + settings.approach_gap)
            builder.line(q[0], q[1], floor, settings.plunge_feed)
            if settings.lead == "none":
                builder.line(point[0], point[1], floor)
            else:
                builder.line(start[0], start[1], floor)
                builder.polyline(np.column_stack([lead_in[1:], np.full(len(lead_in) - 1, floor)]))
            fpath = ct.with_points(path, tb.stations(mine, shape, [floor]))
            fpath = ct.started_at(fpath, 0.0)
            along = ct.lengths(fpath)
            lap = tb.lift(np.column_stack([fpath, np.full(len(fpath), floor)]), along % along[-1], along[-1], mine,
                          shape)
            builder.polyline(lap[1:])
        if settings.lead != "none":
            out = _lead(point, tangent, normal, settings.lead_radius, settings.lead, False)
            builder.polyline(np.column_stack([out[1:], np.full(len(out) - 1, floor)]))
        builder.retract()
        done_loops.append(path)
    arrays = builder.arrays()
    first = arrays["xyz"][0]
    op = Operation(name, tool, settings.rpm, arrays["kind"], arrays["xyz"], arrays["feed"],
                   clearance_z=settings.clearance_z, safe_z=settings.safe_z,
                   start=np.array([first[0], first[1], settings.safe_z]),
                   comment=f"profile {settings.side} {settings.cut_depth(thickness):g} mm deep")
    warnings = []
    if floor <= bottom + 1e-9:
        if not any(centres):
            warnings.append(f"profile {name!r}: no tabs and cut through: the part comes loose on the last pass")
        else:
            for k in order:
                if not centres[k]:
                    warnings.append(f"profile {name!r}: contour {k + 1} has no tabs and is cut through: its piece "
                                    "comes loose on the last pass")
    return ProfileResult(op, done_loops, done_tabs, floor, shape.top, region, warnings, entries)


def check_tool(number, diameter, flute_length) -> Tool:
    """The flat end mill of a job file's settings, or a ProfileError naming what is wrong."""
    try:
        return Tool(number, "flat", float(diameter), flute_length=float(flute_length),
                    name=f"{float(diameter):g} mm end mill")
    except ProgramError as error:
        raise ProfileError(f"profile: tool: {error}") from None
