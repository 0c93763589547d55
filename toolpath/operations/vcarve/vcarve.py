"""V-carving: a closed region (letters, curves, mesh faces; loops read even-odd) cut with a V-bit
whose tip follows the region's medial axis (:mod:`.medial`) at the depth where its cone touches
the outline: depth = start_depth + radius / tan(angle / 2), radius being the inscribed circle's.
The walls so meet the outline at the top and sharp corners run out to it at depth 0.

**Maximum depth** (what Carbide Create calls Advanced VCarve): where the depth would pass
``max_depth`` the tip stays at it.  The V-bit then runs the region's offset at
r_max = (max_depth - start_depth) * tan(angle / 2) at max depth (its cone cuts the walls there
up to the outline) and a second tool, a flat end mill (``clear_tool``), first clears that offset's
inside flat at max depth (the pocket's planner, :func:`..pocket.pocket.plan`).  The flat floor's
corners that the end mill's radius cannot reach are traced by the V-bit's tip along the medial
axis at max depth, and reported by place (what stands there is at most the V-bit's cone high).

**Inlays** (``inlay``): "female" is the V-carved pocket (a flat bottom with max_depth); "male"
is the plug: the design mirrored (about the vertical line through its middle), the waste around
it (its bounding box grown by ``waste_margin``) V-carved with the tip ``start_depth`` plus
glue_gap / sin(angle / 2) deeper, so that the plug, turned over and pressed into the pocket
until its wall at start_depth meets the pocket's top edge, stands glue_gap off every wall
(measured square to the wall), and the waste cleared flat at max_depth (the plug's height).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...engines import region as rg
from ...ir.errors import InputError
from ...ir.program import Operation, PathBuilder, ProgramError, Tool
from ..fields import NUMBER, Field, Fields, one_of, positive, zero_or_more
from ..pocket import pocket
from ..stepnc.motion import round_offset
from . import chains as ch
from . import fine, medial

INLAYS = ("none", "female", "male")
MIN_TOLERANCE = 0.001           # mm: the medial axis's sampling tolerance, finest
MAX_TOLERANCE = 0.1
# The settings each within its own bounds, checked in this order (VCarveSettings.check then relates them).
FIELDS = Fields(NUMBER, (
    *map(zero_or_more, ("max_depth", "start_depth", "glue_gap", "waste_margin")),
    zero_or_more("clear_stepover", zero="the end mill's radius"),
    *map(positive, ("clear_step_down", "clear_rpm", "clear_feed", "rpm", "feed", "entry_feed")),
    Field("tolerance", low=MIN_TOLERANCE, high=MAX_TOLERANCE, unit="mm"),
    one_of("inlay", INLAYS),
    Field("clearance_z"), Field("safe_z")))
DUST = 0.005                    # mm: floor corners narrower than this are not reported
LEFT_REPORTED = 5               # floor corners named in the warning
RIDGE_STEP = 0.05               # mm: the medial axis sampled this finely to bound what stands in them
ENTRY_SHARE = 0.8               # the entry starts this share of the first point's cone radius away: steeper
#                                 than the flank, so the cone stays inside the one it enters (a move exactly
#                                 along the flank is the height field's degenerate case, see the tests)


class VCarveError(InputError):
    """A region or settings that cannot be V-carved; the message names the operation and the setting."""


def vbit(number: int, angle: float, diameter: float, flute_length: float = 15.0) -> Tool:
    try:
        return Tool(number, "vbit", diameter, flute_length=flute_length, tip_angle=float(angle))
    except ProgramError as error:
        raise VCarveError(f"the V-bit: {error}") from None


@dataclass(frozen=True)
class VCarveSettings:
    tool: Tool = field(default_factory=lambda: vbit(3, 60.0, 12.7))
    max_depth: float = 0.0          # mm below the top; 0: no limit (the V-bit's width is then the limit)
    clear_tool: Tool | None = field(default_factory=lambda: pocket.end_mill(4, 3.175))
    clear_stepover: float = 0.0     # mm between the end mill's rings; 0: its radius (the widest offset rings clear)
    clear_step_down: float = 1.5
    clear_rpm: float = 18000.0
    clear_feed: float = 1000.0
    start_depth: float = 0.0        # the tip's depth where the radius is 0 (a male plug's start depth)
    inlay: str = "none"             # "none", "female" (the pocket), "male" (the mirrored plug)
    glue_gap: float = 0.1           # male: square to the walls, between plug and pocket (mm)
    waste_margin: float = 0.0       # male: board cleared round the plug's outline (mm; 0: twice r_max + 2)
    tolerance: float = 0.01         # mm: curves of the medial axis and the radius along it
    rpm: float = 18000.0
    feed: float = 1000.0
    entry_feed: float = 400.0
    clearance_z: float = 5.0
    safe_z: float = 20.0

    @property
    def tip_tan(self) -> float:
        return self.tool.shape.tip_tan

    def shift(self) -> float:
        """The tip's depth where the radius is 0: a male plug's start depth plus the glue gap's
        share, 0 for the female pocket (its start_depth is the plug's, checked against its flat
        bottom), start_depth for a plain V-carve."""
        if self.inlay == "male":
            half = math.radians(self.tool.shape.tip_angle_deg) / 2
            return self.start_depth + self.glue_gap / math.sin(half)
        return 0.0 if self.inlay == "female" else self.start_depth

    def check(self, what: str = "V-carve") -> None:
        if not isinstance(self.tool, Tool) or self.tool.kind != "vbit":
            raise VCarveError(f"{what}: tool must be a V-bit, not a "
                              f"{self.tool.describe() if isinstance(self.tool, Tool) else repr(self.tool)}")
        if self.clear_tool is not None and (not isinstance(self.clear_tool, Tool) or self.clear_tool.kind != "flat"):
            raise VCarveError(f"{what}: clear_tool must be a flat end mill")
        FIELDS.check(self, what, VCarveError)
        if not 0 < self.clearance_z <= self.safe_z:
            raise VCarveError(f"{what}: clearance_z {self.clearance_z:g} mm and safe_z {self.safe_z:g} mm must be "
                              "above the stock's top and rise in that order")
        if self.max_depth and self.max_depth <= max(self.shift(), self.start_depth):
            if self.inlay == "male":
                raise VCarveError(f"{what}: max_depth {self.max_depth:g} mm (the plug's height) must be more than "
                                  f"start_depth + glue_gap / sin(half angle) = {self.shift():.3f} mm")
            if self.inlay == "female":
                raise VCarveError(f"{what}: max_depth {self.max_depth:g} mm (the pocket's flat bottom) must be more "
                                  f"than start_depth {self.start_depth:g} mm, or the plug bottoms out on it")
            raise VCarveError(f"{what}: max_depth {self.max_depth:g} mm must be more than start_depth "
                              f"{self.start_depth:g} mm")
        if self.inlay == "male" and not self.max_depth:
            raise VCarveError(f"{what}: a male plug needs max_depth (how far the waste round it is cleared: the "
                              f"plug's height, more than start_depth {self.start_depth:g} mm)")
        if self.max_depth and self.max_depth > self.tool.flute_length:
            raise VCarveError(f"{what}: max_depth {self.max_depth:g} mm is deeper than the "
                              f"{self.tool.describe()}'s {self.tool.flute_length:g} mm flutes")
        if self.max_depth and self.max_depth * self.tip_tan > self.tool.radius + 1e-9:
            reach = self.tool.radius / self.tip_tan
            raise VCarveError(f"{what}: at max_depth {self.max_depth:g} mm the {self.tool.describe()}'s cone is "
                              f"{2 * self.max_depth * self.tip_tan:.3f} mm wide, more than its diameter: "
                              f"max_depth can be {reach:.3f} mm at most")


@dataclass
class VCarveResult:
    operations: list            # the end mill's clearing (with a max depth), then the V-bit's
    design: object              # the design's region as given (a male plug: mirrored)
    carved: object              # the region the V-bit carves (the design; for a male plug the waste)
    flat: object | None         # cut flat at max depth (None: no max depth reached)
    deepest: float              # mm below the top the V-bit's tip reaches
    medial: medial.MedialAxis
    warnings: list
    left: list                  # (x, y) of flat-floor corners the end mill cannot reach
    # the characters too fine for the clearing tool: [{operation, letters, char, index, missed_mm2,
    # narrowest_mm, height_mm, min_height_mm, at}] (:mod:`.fine`)
    too_fine: list = field(default_factory=list)


def mirrored(loops: list) -> list:
    """The loops mirrored about the vertical line through their bounding box's middle."""
    points = np.vstack(loops)
    middle = float(points[:, 0].min() + points[:, 0].max())
    return [np.column_stack([middle - loop[:, 0], loop[:, 1]])[::-1] for loop in loops]


def carved_region(loops, settings: VCarveSettings, what: str):
    """(design, carved): the design's region and the region the V-bit carves (see the module)."""
    try:
        design = pocket.region_of(loops, what)
    except pocket.PocketError as error:
        raise VCarveError(str(error)) from None
    if settings.inlay != "male":
        return design, design
    design = rg.from_loops(mirrored(rg.loops(design)), what)
    margin = settings.waste_margin or 2 * settings.max_depth * settings.tip_tan + 2.0
    x0, y0, x1, y1 = design.bounds()
    box = rg.from_loops([np.array([[x0 - margin, y0 - margin], [x1 + margin, y0 - margin],
                                   [x1 + margin, y1 + margin], [x0 - margin, y1 + margin]])], what)
    return design, box - design


def plan(loops, settings: VCarveSettings = VCarveSettings(), name: str = "vcarve", top: float = 0.0,
         progress=None, characters=None, letters: str = "") -> VCarveResult:
    """The V-carve of the closed ``loops`` (work mm, even-odd) from the stock's top ``top``;
    ``characters`` ((character, index, loops), ...) and ``letters`` (what they are called) name
    the characters too fine for the clearing tool (:mod:`.fine`)."""
    what = f"V-carve {name!r}"
    settings.check(what)
    if isinstance(loops, np.ndarray) and loops.ndim == 2:
        loops = [loops]
    design, carved = carved_region(loops, settings, what)
    try:
        axis = medial.medial_axis(carved, settings.tolerance, what)
    except medial.MedialError as error:
        raise VCarveError(str(error)) from None
    if progress is not None:
        progress(0.3)
    tan, shift = settings.tip_tan, settings.shift()
    widest = axis.max_radius()
    warnings, operations, left = [], [], []
    limit = (settings.max_depth - shift) * tan if settings.max_depth else math.inf
    if not settings.max_depth and widest + shift * tan > settings.tool.radius + 1e-9:
        index = int(np.argmax([r.max() for r in axis.radii]))
        x, y = axis.paths[index][int(np.argmax(axis.radii[index]))]
        reach = settings.tool.radius / tan
        raise VCarveError(f"{what}: the region is {2 * widest:.3f} mm wide at X{x:.3f} Y{y:.3f}, wider than the "
                          f"{settings.tool.describe()} can carve to a point ({settings.tool.diameter:g} mm): set "
                          f"max_depth (at most {reach:.3f} mm) with a clear_tool for the flat inside")
    pieces, above = [], []
    for points, radii in zip(axis.paths, axis.radii):
        below, over = ch.split_at(points, radii, limit)
        pieces += below
        above += over
    flat = None
    if above:
        flat = round_offset(carved, -limit)
        if flat.area() < rg.MIN_AREA:
            flat = None
    if flat is not None:
        if settings.clear_tool is None:
            raise VCarveError(f"{what}: at max_depth {settings.max_depth:g} mm a flat floor of "
                              f"{flat.area():.1f} mm^2 is left: give a clear_tool (a flat end mill) to clear it")
        operations += clearing(flat, settings, name, top, warnings)
        cleared = opening(flat, settings.clear_tool.radius)
        rest = round_offset(round_offset(flat - cleared, -DUST), DUST)
        if rest.area() > 0:
            keep = rest.offset(settings.tolerance, rg.JoinType.Round, 2.0, 16)
            # the pieces of the medial axis over the rest, traced at max depth (one point-in-region
            # test for all: the pieces densified, so a piece crossing the rest between samples counts);
            # ridge: the farthest a point of the rest lies from the flat's edge, which the tip traces
            dense = [densified(points, radii, RIDGE_STEP) for points, radii in above]
            owner = np.concatenate([np.full(len(d[0]), k) for k, d in enumerate(dense)])
            within = rg.contains_points(keep, np.vstack([d[0] for d in dense]))
            radii_all = np.concatenate([d[1] for d in dense])
            ridge = float(radii_all[within].max()) - limit if within.any() else 0.0
            for k in np.unique(owner[within]):
                points = above[k][0]
                pieces.append((points, np.full(len(points), limit)))
            left = [tuple(map(float, rg.centroid(part))) for part in rg.components(rest, 0.0)]
            shown = ", ".join(f"X{x:.2f} Y{y:.2f}" for x, y in left[:LEFT_REPORTED])
            warnings.append(f"{what}: the {settings.clear_tool.describe()} cannot reach {len(left)} part(s) of "
                            f"the flat floor at max depth ({shown}{', ...' if len(left) > LEFT_REPORTED else ''}); "
                            f"the V-bit's tip traces them, ridges up to "
                            f"{min(settings.clear_tool.radius, ridge) / tan:.2f} mm high may stand there")
    too_fine = []
    if flat is not None:
        if characters and settings.inlay == "male":
            characters = fine.mirrored_characters(characters, float(np.vstack(loops)[:, 0].min() +
                                                                    np.vstack(loops)[:, 0].max()))
        too_fine, fine_warnings = fine.too_fine(characters, design, carved, flat, settings, limit,
                                                letters or f"the design of {what}", what)
        warnings += fine_warnings
    if progress is not None:
        progress(0.6)
    walks = ch.join(pieces)
    if flat is not None:
        walks += [(np.vstack([loop, loop[:1]]), np.full(len(loop) + 1, limit)) for loop in rg.loops(flat)]
    ordered = ch.nearest_order(walks, rg.centroid(carved))
    deepest = shift + min(widest, limit) / tan
    operations.append(vbit_operation(ordered, settings, name, top, shift, tan))
    if progress is not None:
        progress(1.0)
    return VCarveResult(operations, design, carved, flat, deepest, axis, warnings, left, too_fine)


def densified(points: np.ndarray, radii: np.ndarray, step: float) -> tuple:
    """The path with points put in every ``step`` mm, the radius interpolated linearly."""
    lengths = np.hypot(*np.diff(points, axis=0).T)
    counts = np.maximum(1, np.ceil(lengths / step).astype(int))
    t = np.concatenate([np.arange(n) / n for n in counts] + [[1.0]])
    index = np.concatenate([np.full(n, i) for i, n in enumerate(counts)] + [[len(points) - 2]])
    dense = points[index] + t[:, None] * (points[index + 1] - points[index])
    return dense, radii[index] + t * (radii[index + 1] - radii[index])


def opening(region, radius: float):
    """Every disc of ``radius`` inside ``region``: what an end mill of that radius clears."""
    return round_offset(round_offset(region, -radius), radius)


def clearing(flat, settings: VCarveSettings, name: str, top: float, warnings: list) -> list:
    """The end mill's operations clearing ``flat`` at max depth (the pocket's planner)."""
    tool = settings.clear_tool
    stepover = settings.clear_stepover or tool.radius
    pocket_settings = pocket.PocketSettings(tool=tool, depth=settings.max_depth, step_down=settings.clear_step_down,
                                            stepover=stepover, rpm=settings.clear_rpm, feed=settings.clear_feed,
                                            entry_feed=settings.entry_feed, helix_diameter=0.0, entry="ramp",
                                            clearance_z=settings.clearance_z, safe_z=settings.safe_z)
    parts = []
    for part in rg.components(flat, 0.0):
        if rg.area(round_offset(part, -tool.radius)) < rg.MIN_AREA * 0.01:
            continue
        parts.append(part)
    if not parts:
        return []
    try:
        result = pocket.plan([loop for part in parts for loop in rg.loops(part)], pocket_settings,
                             name=f"{name} clearing", top=top)
    except pocket.PocketError as error:
        warnings.append(f"V-carve {name!r}: clearing the flat floor: {error}")
        return []
    warnings += result.warnings
    return list(result.operations)


def vbit_operation(ordered: list, settings: VCarveSettings, name: str, top: float, shift: float,
                   tan: float) -> Operation:
    """The V-bit's moves: each chain entered from the top on a straight line inside its first
    point's cone (no straight plunge into material), linked at depth where a chain starts where
    the one before ended."""
    path = PathBuilder(settings.clearance_z, settings.feed, settings.entry_feed, 1.0, top)
    floor = top - settings.max_depth if settings.max_depth else -math.inf
    for points, radii in ordered:
        z = np.maximum(top - shift - radii / tan, floor)
        here = path.position
        if here is not None and math.hypot(here[0] - points[0][0], here[1] - points[0][1]) < 1e-6 \
                and abs(here[2] - z[0]) < 1e-6:
            path.polyline(np.column_stack([points[1:], z[1:]]))
            continue
        depth = top - z[0]
        direction = points[1] - points[0]
        length = math.hypot(*direction)
        reach = ENTRY_SHARE * depth * tan
        entry = points[0] + direction / length * reach if length > 0 and reach > 1e-4 else points[0]
        path.retract()
        path.rapid(entry[0], entry[1], settings.clearance_z)
        path.rapid(entry[0], entry[1], path.approach_z)
        path.line(entry[0], entry[1], top, settings.entry_feed)
        if reach > 1e-4:
            path.line(points[0][0], points[0][1], z[0], settings.entry_feed)
        path.polyline(np.column_stack([points[1:], z[1:]]))
    path.retract()
    if path.position is not None:
        path.rapid(path.position[0], path.position[1], settings.safe_z)
    arrays = path.arrays()
    first = ordered[0][0][0] if ordered else (0.0, 0.0)
    comment = f"V-carve, {settings.tool.shape.tip_angle_deg:g} deg V-bit"
    if settings.max_depth:
        comment += f", max depth {settings.max_depth:g} mm"
    if settings.inlay != "none":
        comment += f", inlay {settings.inlay}"
    return Operation(name, settings.tool, settings.rpm, arrays["kind"], arrays["xyz"], arrays["feed"],
                     clearance_z=settings.clearance_z, safe_z=settings.safe_z,
                     start=np.array([first[0], first[1], settings.safe_z]), comment=comment)
