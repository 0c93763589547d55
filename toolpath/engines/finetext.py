"""Text too fine for a tool: per character, the gaps a round tool of diameter D cannot enter, and
the smallest text height at which it would.

The caller gives the characters (each one's outline in work mm, even-odd, with its place in the
text) and the region the tool must cut: for raised letters the waste around and inside the strokes
(engraving's band), for letters cut in (a pocket, a V-carve's flat clearing) the strokes.  What a
tool of radius r reaches of a region R is R's morphological opening, R eroded by r and dilated by
r (every point some disk of radius r inside R covers); the rest is missed.  Of the missed part,
two kinds are told apart by the walls of R a missed piece touches (:func:`_between_walls`):

- **corners**: a round tool never reaches into a sharp convex corner of R, at any size of the
  text; the piece it leaves touches one run of wall, the corner's two sides, turning through less
  than half a turn.  Engraving sums those into its corner leftover; they are not named here;
- **gaps**: a piece between two walls facing each other (a slot between two strokes, a counter
  smaller than the tool).  Scaling the text by s widens it s times, so it is reached once
  s x width >= D.

For each character owning a gap the report gives the area missed, the narrowest width (D / s*,
s* the smallest scale at which the character's gaps are all reached, found by bisection on the
scaled geometry) and the smallest text height: the character's height x s* rounded up to
:data:`HEIGHT_STEP` and checked again at that height, so the height named passes this check.

Tolerances, shares of the character's height so that they do not change with scale (specks of a
font stay specks at every height, and the height found passes): a gap smaller than :func:`dust`,
(2 % of the height)^2, is not reported (at least region.MIN_AREA, 0.01 mm^2, what the regions call
numerical dust, which is (2 % of 5 mm)^2); a missed part narrower than :func:`hairline`, 1 % of the
height, is where two contours of the font touch by design (a 0.04 mm slit between two strokes of
a 5 mm 渡 would otherwise ask for a 132 mm character).  Offsets are polygons within
region.ARC_TOLERANCE (0.01 mm) of their arcs: nothing narrower than :data:`SLIVER` (four times
that) counts, whatever the height.  The API takes plain loops and returns frozen dataclasses, for any kind that
cuts letters with a round tool (engraving's band, a V-carve's clearing tool, pocket, profile).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from manifold3d import CrossSection

from . import region as rg

MIN_GAP_AREA = rg.MIN_AREA
DUST_SHARE = 0.02           # a gap smaller than (2 % of the character's height)^2 is a speck of the font's outline
SLIVER = 4 * rg.ARC_TOLERANCE  # mm: narrower than this, a missed part is the offsets' chord error
HAIRLINE_SHARE = 0.01       # a missed part narrower than 1 % of the character's height is a hairline of the font
HEIGHT_STEP = 0.1           # mm: a text height is typed to a tenth of a millimetre
MAX_SCALE = 50.0            # a character needing more than 50 x its height is named without a height
PRECISION = 0.002           # relative precision of the bisection on the scale
DUST = 1e-4                 # mm^2: pieces of a difference smaller than this are rounding, not area
WALL_NEAR = 0.002           # mm: an edge of a missed piece this near the region's outline runs along a wall (its
                            # edges are the outline's own, to rounding; the sliver rounding of a tip is farther)
BRIDGE = 4                  # x the opening's width: a stretch off the walls shorter than this between two runs joins them
FACING = math.radians(10)   # a run of wall turning through 170 degrees or more has two walls facing each other


class FineTextError(rg.RegionError):
    """Bad input to the check: a tool of no size."""


@dataclass(frozen=True)
class Character:
    """One character of a text: ``char`` (the character), ``index`` (its place in the text),
    ``loops`` ((k, 2) arrays, work mm, even-odd: counters are holes) and ``height`` (mm, the height
    the report scales; None: the outline's own height)."""

    char: str | None
    index: int
    loops: tuple
    height: float | None = None


@dataclass(frozen=True)
class TooFine:
    """A character whose gaps the tool cannot enter: ``missed_mm2`` (area left uncut, corners not
    counted), ``narrowest_mm`` (the narrowest gap's width), ``height_mm`` (the character's height
    now), ``min_height_mm`` (the smallest height at which every gap is reached; None: more than
    :data:`MAX_SCALE` times the height) and ``at`` (x, y of its largest gap)."""

    char: str | None
    index: int
    missed_mm2: float
    narrowest_mm: float
    height_mm: float
    min_height_mm: float | None
    at: tuple

    def as_dict(self) -> dict:
        return {"char": self.char, "index": self.index, "missed_mm2": round(self.missed_mm2, 3),
                "narrowest_mm": round(self.narrowest_mm, 3), "height_mm": round(self.height_mm, 2),
                "min_height_mm": None if self.min_height_mm is None else round(self.min_height_mm, 1),
                "at": [round(self.at[0], 2), round(self.at[1], 2)]}


def region_of(shape, what: str) -> CrossSection:
    """A CrossSection as given, or the region of closed loops (even-odd)."""
    if isinstance(shape, CrossSection):
        return shape
    return rg.from_loops(list(shape), what)


def missed_gaps(cut: CrossSection, radius: float, narrow: float = SLIVER) -> CrossSection:
    """The gaps of ``cut`` a tool of ``radius`` cannot reach: its corners' leftovers and the
    missed parts narrower than ``narrow`` (mm, at least :data:`SLIVER`) taken away."""
    reached = rg.offset(rg.offset(cut, -radius), radius)
    missed = cut - reached
    if missed.area() < MIN_GAP_AREA:
        return CrossSection()
    narrow = max(narrow, SLIVER)
    missed = _solid(rg.offset(rg.offset(_solid(missed), -narrow / 2), narrow / 2))
    if missed.is_empty():
        return missed
    inner = rg.offset(cut, -WALL_NEAR)
    gaps = [piece for piece in missed.decompose() if piece.area() > DUST and _between_walls(piece, inner, narrow)]
    return CrossSection.compose(gaps) if gaps else CrossSection()


def _between_walls(piece: CrossSection, inner: CrossSection, narrow: float) -> bool:
    """Is this missed piece a gap (True) or what is left of a corner whose sides curve (False)?

    Its outline runs partly along the walls of the region to cut (edges within
    :data:`WALL_NEAR` of them: outside ``inner``, the region shrunk by that much) and partly
    along what the tool reached.  A gap touches two walls facing each other: its outline meets
    the walls in two runs or more (a slot open at both ends), in one run that turns through half a
    turn or more, less :data:`FACING` (a slot closed at one end: two walls and its end), or all
    round (a counter the tool cannot enter).  A corner is one run turning through less: its two
    sides meet at the corner's angle, and no size of the text makes a round tool reach into it.
    ``narrow``: the width the missed part was opened by (its corners are rounded that much)."""
    loop = max(rg.loops(piece), key=lambda lp: abs(rg.signed_area(lp)))
    following = np.roll(loop, -1, axis=0)
    wall = ~rg.contains_points(inner, (loop + following) / 2)
    if wall.all():
        return True
    if not wall.any():
        return False
    edges = following - loop
    lengths = np.hypot(edges[:, 0], edges[:, 1])
    # start at the longest stretch off the walls (the tool's reach): no run wraps round the start
    off = np.nonzero(~wall & np.roll(wall, 1))[0]                # where each stretch off the walls starts
    stretch = [lengths[np.arange(k, k + np.argmax(np.roll(wall, -k))) % len(wall)].sum() for k in off]
    start = int(off[int(np.argmax(stretch))])
    wall, edges, lengths = np.roll(wall, -start), np.roll(edges, -start, axis=0), np.roll(lengths, -start)
    # a short stretch off the walls between two runs is the sliver rounding of a corner of the
    # region, not the tool's reach: the runs are one
    k = 0
    while k < len(wall):
        if wall[k]:
            k += 1
            continue
        end = k
        while end < len(wall) and not wall[end]:
            end += 1
        if 0 < k and end < len(wall) and lengths[k:end].sum() < BRIDGE * narrow:
            wall[k:end] = True
        k = end
    heading = np.arctan2(edges[:, 1], edges[:, 0])
    turns = (np.diff(heading) + np.pi) % (2 * np.pi) - np.pi     # at the vertex between edge k and k + 1
    runs, turning = 0, []
    k = 0
    while k < len(wall):
        if not wall[k]:
            k += 1
            continue
        end = k
        while end < len(wall) and wall[end]:
            end += 1
        runs += 1
        # the run's turning from its first long edge to its last: the short edges at its ends are
        # the sliver rounding where the wall meets the tool's reach, bent either way
        long = np.nonzero(lengths[k:end] >= narrow)[0]
        turning.append(float(turns[k + long[0]:k + long[-1]].sum()) if len(long) else 0.0)
        k = end
    return runs >= 2 or max(turning) >= math.pi - FACING


def _solid(region: CrossSection) -> CrossSection:
    """``region`` without its pieces of (nearly) no area: a difference leaves such dust, and an
    inward offset of a dust polygon comes out as a strip of area (Clipper takes its loops as they
    wind), which would be reported as a gap."""
    pieces = [p for p in region.decompose() if p.area() > DUST]
    return CrossSection.compose(pieces) if pieces else CrossSection()


def _boxes(characters) -> np.ndarray:
    return np.array([[min(float(np.min(np.asarray(loop)[:, 0])) for loop in c.loops),
                      min(float(np.min(np.asarray(loop)[:, 1])) for loop in c.loops),
                      max(float(np.max(np.asarray(loop)[:, 0])) for loop in c.loops),
                      max(float(np.max(np.asarray(loop)[:, 1])) for loop in c.loops)] for c in characters])


def owners(boxes: np.ndarray, points: np.ndarray) -> np.ndarray:
    """For each point, the character whose box is nearest (0 inside it); inside several boxes, the
    one whose centre is nearest."""
    points = np.asarray(points, float).reshape(-1, 2)
    dx = np.maximum(np.maximum(boxes[None, :, 0] - points[:, None, 0], points[:, None, 0] - boxes[None, :, 2]), 0)
    dy = np.maximum(np.maximum(boxes[None, :, 1] - points[:, None, 1], points[:, None, 1] - boxes[None, :, 3]), 0)
    outside = np.hypot(dx, dy)
    centres = (boxes[:, :2] + boxes[:, 2:]) / 2
    to_centre = np.hypot(points[:, None, 0] - centres[None, :, 0], points[:, None, 1] - centres[None, :, 1])
    return np.argmin(outside * 1e6 + to_centre, axis=1)


def hairline(height: float) -> float:
    """The width (mm) below which a missed part of a character ``height`` mm tall is a hairline
    between two of the font's contours, not a gap: :data:`HAIRLINE_SHARE` of the height, at least
    :data:`SLIVER`."""
    return max(SLIVER, HAIRLINE_SHARE * height)


def dust(height: float) -> float:
    """The area (mm^2) below which a gap of a character ``height`` mm tall is not reported: the
    square of :data:`DUST_SHARE` of its height, at least :data:`MIN_GAP_AREA`."""
    return max(MIN_GAP_AREA, (DUST_SHARE * height) ** 2)


def _gaps_of(cut, radius, boxes, which: int, scale: float = 1.0, about=(0.0, 0.0)) -> list:
    """The gaps of ``cut`` scaled by ``scale`` about ``about`` that character ``which`` owns and
    that are not dust at that scale, as (area, (x, y) unscaled)."""
    if scale != 1.0:
        x0, y0 = about
        cut = cut.translate((-x0, -y0)).scale((scale, scale)).translate((x0, y0))
    tall = float(boxes[which, 3] - boxes[which, 1]) * scale
    pieces = rg.components(missed_gaps(cut, radius, hairline(tall)), dust(tall))
    if not pieces:
        return []
    centres = np.array([rg.centroid(p) for p in pieces])
    unscaled = (centres - np.asarray(about)) / scale + np.asarray(about)
    mine = owners(boxes, unscaled) == which
    return [(rg.area(p), tuple(unscaled[k])) for k, p in enumerate(pieces) if mine[k]]


def check(characters, cut, tool_diameter: float) -> list:
    """The characters (:class:`Character`) with gaps in ``cut`` (loops, even-odd, or a region) that
    a round tool of ``tool_diameter`` mm cannot enter, as :class:`TooFine`, in text order."""
    if not (isinstance(tool_diameter, (int, float)) and math.isfinite(tool_diameter) and tool_diameter > 0):
        raise FineTextError(f"tool diameter must be a positive number of mm, got {tool_diameter!r}")
    characters = [c for c in characters if c.loops]
    if not characters:
        return []
    cut = region_of(cut, "area to cut")
    radius = tool_diameter / 2
    boxes = _boxes(characters)
    pieces = rg.components(missed_gaps(cut, radius), MIN_GAP_AREA)
    if not pieces:
        return []
    owner = owners(boxes, np.array([rg.centroid(p) for p in pieces]))
    found = []
    for which in sorted(set(owner.tolist())):
        character = characters[which]
        window = _window(cut, boxes[which], radius)
        mine = _gaps_of(window, radius, boxes, which, 1.0, _centre(boxes, which))      # at its own tolerances
        if not mine:
            continue
        height = character.height if character.height is not None else float(boxes[which, 3] - boxes[which, 1])
        scale = _smallest_scale(window, radius, boxes, which)
        min_height = None if scale is None else _checked_height(window, radius, boxes, which, height, scale)
        narrowest = tool_diameter / scale if scale is not None else 0.0
        found.append(TooFine(character.char, character.index, sum(area for area, _ in mine), narrowest, height,
                             min_height, max(mine)[1]))
    return sorted(found, key=lambda f: f.index)


def _window(cut: CrossSection, box, radius: float) -> CrossSection:
    """``cut`` near one character: its box grown by the tool's diameter at the largest scale
    looked at, so the window's own edges lie beyond the gaps it owns."""
    margin = 2 * radius + 1.0
    return cut ^ rg.rectangle(box[0] - margin, box[1] - margin, box[2] + margin, box[3] + margin)


def _centre(boxes, which) -> tuple:
    return ((boxes[which, 0] + boxes[which, 2]) / 2, (boxes[which, 1] + boxes[which, 3]) / 2)


def _reached_at(window, radius, boxes, which, scale) -> bool:
    return not _gaps_of(window, radius, boxes, which, scale, _centre(boxes, which))


def _smallest_scale(window, radius, boxes, which) -> float | None:
    """The smallest scale (> 1) at which the character owns no gap, to :data:`PRECISION`."""
    low, high = 1.0, 2.0
    while not _reached_at(window, radius, boxes, which, high):
        low, high = high, high * 2
        if high > MAX_SCALE:
            return None
    while high / low > 1 + PRECISION:
        middle = math.sqrt(low * high)
        if _reached_at(window, radius, boxes, which, middle):
            high = middle
        else:
            low = middle
    return high


def _checked_height(window, radius, boxes, which, height, scale) -> float | None:
    """The character's height at ``scale`` rounded up to :data:`HEIGHT_STEP`, raised a step at a
    time (up to ten) until the check passes there."""
    steps = math.ceil(height * scale / HEIGHT_STEP - 1e-9)
    for _ in range(10):
        candidate = steps * HEIGHT_STEP
        if _reached_at(window, radius, boxes, which, candidate / height):
            return round(candidate, 6)
        steps += 1
    return None
