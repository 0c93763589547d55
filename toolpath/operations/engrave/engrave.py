"""W1: gouge-texture engraving of a name plate (seed 000, Watanabe).

Three operations, as the paper cuts a horizontal name plate:

1. Roughing: a ball end mill clears the plate face around the letters with a zigzag raster;
   along the raster, every ``spacing`` mm of travel the tool goes to a new random depth
   (the "chisel-mark" texture), moving in straight lines between them.
2. Band finishing: a small flat end mill clears a band of ``band_width`` around every
   letter at one depth, so the letters stand out crisply.  Each ring of the band is cut down
   to that depth in step-downs of at most ``band_step_down`` (default 1 x the 1 mm tool's
   diameter), every level entered on a ramp of ``band_ramp_angle`` along the ring
   (:mod:`ramp`): the flat end mill never feeds straight down into the plate.
3. Burr contour: the ball runs once along the border between texture and band.

The roughing operation is planned untextured (at the base depth) and carries a
:class:`GougeTexture`.  :func:`bake` applies the texture with a seeded generator (the
preview shows exactly what will be cut); the Fanuc post can instead emit the paper's
controller macro, which draws the digits from the millisecond clock at run time.

The depth rule (SPEC W1): a digit d in 0..9; k = d for d <= 4 (shallower than the base),
k = d - 5 for d >= 5 (deeper); depth = base +/- quantum * round(k * amplitude / (4 * quantum)).
With the paper's values (base -2.0, quantum 0.2, amplitude 0.8) that is base +/- 0.2 k,
depths -2.8..-1.2 on a 0.2 grid, and d = 5 gives exactly the base (the paper's macro
tested ``#28 GT 5`` and sent d = 5 to -1.0; we use GE).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from . import glyphs
from ...engines import finetext, ramp
from ...engines import region as rg
from ...ir.program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, PathBuilder, Program, Tool
from ...ir.program import GOUGE_MOTIONS, EngraveError, GougeTexture  # noqa: F401  (the texture lives in the IR)


# A row whose length is a whole number of gouges to within this (mm) gets its last gouge:
# float32 scene geometry must not add or drop a gouge and shift every depth after it.
TRAVEL_TOLERANCE = 1e-4


@dataclass(frozen=True)
class EngraveSettings:
    """Every number of the job, with the paper's values as defaults (mm, mm/min, rpm)."""

    rough_tool: Tool = Tool(2, "ball", 6.0, name="roughing ball")
    finish_tool: Tool = Tool(3, "flat", 1.0, name="band finishing")
    stepover: float = 3.0
    raster_angle: float = 0.0
    letter_clearance: float = 4.0   # roughing tool centre keeps this far from the letters
    band_width: float = 4.0
    band_depth: float = -2.0
    band_stepover: float = 0.5
    band_step_down: float = 1.0     # at most 1 x D of the flat end mill per level
    # 3 degrees: the low end of the 2-5 degrees a standard end mill ramps at (carbide-tooling.com,
    # "Ramping Angle Calculator": "standard end mills have a maximum ramping angle of 2-5 degrees
    # depending on the number of flutes and the core diameter"); a 1 mm tool's core is thin
    band_ramp_angle: float = 3.0
    burr_depth: float = -2.0
    texture: GougeTexture = GougeTexture()
    rough_rpm: float = 6000.0
    finish_rpm: float = 12000.0
    rough_feed: float = 1200.0
    finish_feed: float = 600.0
    plunge_feed: float = 300.0
    clearance_z: float = 20.0
    safe_z: float = 20.0                 # the frames lift by the machine profile; this is the operation's own
    approach_gap: float = 2.0
    climb: bool = True

    def validate(self):
        numbers = {k: getattr(self, k) for k in ("stepover", "raster_angle", "letter_clearance", "band_width",
                                                 "band_depth", "band_stepover", "band_step_down",
                                                 "band_ramp_angle", "burr_depth", "rough_rpm",
                                                 "finish_rpm", "rough_feed", "finish_feed", "plunge_feed",
                                                 "clearance_z", "safe_z", "approach_gap")}
        for name, value in numbers.items():
            if not math.isfinite(value):
                raise EngraveError(f"{name.replace('_', ' ')} must be a finite number, got {value}")
        for name in ("stepover", "band_stepover", "band_step_down", "band_width", "rough_feed", "finish_feed",
                     "plunge_feed"):
            if numbers[name] <= 0:
                raise EngraveError(f"{name.replace('_', ' ')} must be greater than zero, got {numbers[name]:g}")
        if self.stepover > self.rough_tool.diameter:
            raise EngraveError(f"stepover {self.stepover:g} mm is wider than the {self.rough_tool.diameter:g} mm "
                               "roughing tool: ridges would be left standing")
        if self.letter_clearance < self.rough_tool.radius:
            raise EngraveError(f"letter clearance {self.letter_clearance:g} mm is less than the roughing tool radius "
                               f"{self.rough_tool.radius:g} mm: the ball would cut into the letters")
        if self.finish_tool.diameter > self.band_width:
            raise EngraveError(f"the {self.finish_tool.diameter:g} mm finishing tool is wider than the "
                               f"{self.band_width:g} mm band")
        if self.band_step_down > self.finish_tool.diameter + 1e-9:
            raise EngraveError(f"band step down {self.band_step_down:g} mm is more than the "
                               f"{self.finish_tool.diameter:g} mm finishing tool's diameter: a small flat end mill "
                               "takes at most 1 x its diameter in depth per pass")
        if not 0 < self.band_ramp_angle <= ramp.MAX_ANGLE:
            raise EngraveError(f"band ramp angle must be more than 0 and at most {ramp.MAX_ANGLE:g} degrees, got "
                               f"{self.band_ramp_angle:g}")
        if self.band_depth >= 0 or self.burr_depth >= 0:
            raise EngraveError("band and burr depths must be below the plate top (negative Z)")
        if not 0 < self.approach_gap < self.clearance_z <= self.safe_z:
            raise EngraveError("heights must satisfy 0 < approach gap < clearance plane <= safe Z")


@dataclass
class EngraveResult:
    program: Program                       # roughing untextured, carrying its GougeTexture
    warnings: list = field(default_factory=list)
    # [{operation, area_mm2, at: [x, y], letters: object name, character: the Text's character or None}]
    skipped: list = field(default_factory=list)
    texture_area_mm2: float = 0.0
    band_area_mm2: float = 0.0
    corner_leftover_mm2: float = 0.0    # left by round tools in sharp inside corners
    letters: list = field(default_factory=list)   # the letters as planned: [(object name, loops)]
    texts: dict = field(default_factory=dict)     # {object name: text} of the Text objects
    # the characters too fine for the band finishing tool: [{operation, letters, char, index,
    # missed_mm2, narrowest_mm, height_mm, min_height_mm, at}] (:mod:`finetext`)
    too_fine: list = field(default_factory=list)


def plan(plate_loops, letters, settings: EngraveSettings = EngraveSettings(), name: str = "engrave",
         progress=None, plate_thickness: float | None = None, texts: dict | None = None,
         characters=None) -> EngraveResult:
    """Plan the three operations.

    plate_loops: closed loops (mm, work XY; the plate top is Z = 0) of the plate face.
    letters:     [(object_name, [loop, ...]), ...]: each object's closed outlines (glyphs with
                 their counters, even-odd).
    progress:    optional callable(fraction, text).
    plate_thickness: mm; every cut (the deepest gouge, the band and burr depths) must stay above
                 the plate's bottom, Z = -thickness.  None: not checked (the caller does not know).
    texts:       {object_name: its text} for the letters objects that are Text objects, so a region
                 left uncut is named by its character where that can be told (:mod:`glyphs`).
    characters:  [(object_name, character, index, loops), ...]: each character of a Text object
                 on its own (its place in the text, its outline), so a character too fine for the
                 band finishing tool is named (:mod:`finetext`); objects not listed are split
                 into glyphs by :func:`glyphs.cells`.
    """
    settings.validate()
    if plate_thickness is not None:
        if not (isinstance(plate_thickness, (int, float)) and math.isfinite(plate_thickness) and plate_thickness > 0):
            raise EngraveError(f"plate thickness must be a positive number of mm, got {plate_thickness!r}")
        texture = settings.texture
        for setting, depth in ((f"base depth {texture.base_depth:g} mm - amplitude {texture.amplitude:g} mm",
                                texture.deepest),
                               (f"band depth {settings.band_depth:g} mm", settings.band_depth),
                               (f"burr depth {settings.burr_depth:g} mm", settings.burr_depth)):
            if depth <= -plate_thickness:
                raise EngraveError(f"{setting} cuts to Z {depth:g}, through the {plate_thickness:g} mm plate "
                                   f"(its bottom is Z {-plate_thickness:g}); make the cut shallower than the plate "
                                   "thickness")
    report = progress or (lambda fraction, text: None)
    plate = rg.from_loops(plate_loops, "plate")
    if not letters:
        raise EngraveError("no letters: select a Text, curve or mesh object to engrave around")
    letter_regions = []
    for object_name, loops in letters:
        region = rg.from_loops(loops, f"letters {object_name!r}")
        if not rg.is_inside(region, plate):
            raise EngraveError(f"letters {object_name!r} reach outside the plate")
        letter_regions.append(region)
    glyphs = letter_regions[0]
    for region in letter_regions[1:]:
        glyphs = glyphs + region
    result = EngraveResult(Program(name, []), letters=list(letters), texts=dict(texts or {}))

    report(0.05, "roughing raster")
    rough = _roughing(plate, glyphs, settings, result)
    report(0.5, "band finishing")
    band = _band_finishing(plate, glyphs, settings, result)
    report(0.75, "fine text")
    _report_too_fine(result, band_region(plate, glyphs, settings), settings, characters or [])
    report(0.85, "burr contour")
    burr = _burr_contour(plate, glyphs, settings)
    result.program.operations = [op for op in (rough, band, burr) if op is not None]
    if not result.program.operations:
        raise EngraveError("nothing to cut: the letters leave no room on the plate for the tools")
    report(1.0, "done")
    return result


def _builder(settings: EngraveSettings, feed: float) -> PathBuilder:
    return PathBuilder(settings.clearance_z, feed, settings.plunge_feed, settings.approach_gap)


def _finish(builder: PathBuilder, settings, name, tool, rpm, texture=None) -> Operation | None:
    if builder.position is None:
        return None
    builder.retract()
    arrays = builder.arrays()
    first = arrays["xyz"][0]
    return Operation(name=name, tool=tool, spindle_rpm=rpm, clearance_z=settings.clearance_z,
                     safe_z=settings.safe_z, start=np.array([first[0], first[1], settings.safe_z]),
                     texture=texture, **arrays)


def _report_skipped(result, operation, target, reached):
    """Warn about islands of ``target`` the tool cannot enter at all (e.g. a counter narrower than
    the tool), naming the letters object and, where it can be told, the character it lies in
    (the warnings become NOTE lines of the NC header).  What a round tool leaves in sharp inside
    corners is not an island: it is summed into ``corner_leftover_mm2`` instead."""
    for piece in rg.components(target):
        if rg.area(piece ^ reached) > rg.MIN_AREA:
            result.corner_leftover_mm2 += rg.area(piece - reached)
            continue
        x, y = rg.centroid(piece)
        name = glyphs.owner(result.letters, (x, y))
        loops = next((loops for object_name, loops in result.letters if object_name == name), [])
        character = glyphs.character_at(loops, result.texts.get(name), (x, y)) if loops else None
        result.skipped.append({"operation": operation, "area_mm2": round(rg.area(piece), 3),
                               "at": [round(x, 2), round(y, 2)], "letters": name, "character": character})
        area = rg.area(piece)
        if character is not None:
            result.warnings.append(f"{operation}: the tool is too big to enter a gap of {area:.2f} mm^2 in "
                                   f"{glyphs.describe(character)} of letters {name!r} near X{x:.1f} Y{y:.1f}; it is "
                                   "left uncut")
        else:
            result.warnings.append(f"{operation}: the tool is too big to enter a gap of {area:.2f} mm^2 in letters "
                                   f"{name!r} near X{x:.1f} Y{y:.1f}; it is left uncut")


def _roughing(plate, glyphs, settings, result) -> Operation | None:
    tool = settings.rough_tool
    centre_region = plate - rg.offset(glyphs, settings.letter_clearance)
    texture_area = plate - rg.offset(glyphs, settings.band_width)
    result.texture_area_mm2 = rg.area(texture_area)
    chains = rg.zigzag(centre_region, settings.stepover, settings.raster_angle)
    reached = rg.offset(centre_region, tool.radius) if chains else rg.CrossSection()
    _report_skipped(result, "roughing", texture_area, reached)
    builder = _builder(settings, settings.rough_feed)
    z = settings.texture.base_depth
    for chain in chains:
        builder.plunge(chain[0, 0], chain[0, 1], z)
        for x, y in chain[1:]:
            builder.line(x, y, z)
    texture = dataclasses.replace(settings.texture, raster_angle=settings.raster_angle)
    return _finish(builder, settings, "roughing (gouge texture)", tool, settings.rough_rpm, texture)


def band_region(plate, glyphs, settings):
    """What the band finishing cuts: ``band_width`` around the letters, on the plate."""
    return (rg.offset(glyphs, settings.band_width) - glyphs) ^ plate


def _report_too_fine(result, band, settings, characters):
    """Name each character whose gaps the band finishing tool cannot enter (strokes that would
    come out fused), with the height at which it would (:func:`finetext.check`)."""
    given = {}
    for object_name, character, index, loops in characters:
        given.setdefault(object_name, []).append((character, index, tuple(loops)))
    owners, cells = [], []
    for object_name, loops in result.letters:
        for character, index, outline in given.get(object_name) or glyphs.cells(loops, result.texts.get(object_name)):
            owners.append((object_name, character, index))
            cells.append(finetext.Character(character, len(cells), outline))
    tool = settings.finish_tool
    for found in finetext.check(cells, band, tool.diameter):
        object_name, character, index = owners[found.index]
        result.too_fine.append({"operation": "band finishing", "letters": object_name,
                                **found.as_dict(), "char": character, "index": index})
        what = glyphs.describe(character) if character is not None else f"glyph {index + 1}"
        lost = (f"the band finishing's {tool.diameter:g} mm tool is too big for {what} of letters {object_name!r}: "
                f"{found.missed_mm2:.2f} mm^2 between its strokes is left uncut")
        if found.min_height_mm is None:
            result.warnings.append(f"{lost}; no text up to {finetext.MAX_SCALE:g} times as tall lets the tool in: "
                                   "use a smaller tool")
        else:
            result.warnings.append(f"{lost} (gaps {found.narrowest_mm:.2f} mm wide); make it at least "
                                   f"{found.min_height_mm:.1f} mm tall (now {found.height_mm:.1f} mm)")


def _band_finishing(plate, glyphs, settings, result) -> Operation | None:
    tool = settings.finish_tool
    r = tool.radius
    band = band_region(plate, glyphs, settings)
    result.band_area_mm2 = rg.area(band)
    # Rings from the outside of the band inward, so the last pass finishes the letter walls.
    distances = list(np.arange(settings.band_width - r, r - 1e-9, -settings.band_stepover))
    if not distances or abs(distances[-1] - r) > 1e-9:
        distances.append(r)
    centre_region = rg.offset(glyphs, settings.band_width - r) - rg.offset(glyphs, r)
    centre_region = centre_region ^ plate
    _report_skipped(result, "band finishing", band, rg.offset(centre_region, r))
    builder = _builder(settings, settings.finish_feed)
    here = (0.0, 0.0)
    depths = ramp.levels(settings.band_depth, settings.band_step_down)
    for d in distances:
        rings = [loop for _, loop in rg.contour_rings(glyphs, [d], clip=plate)]
        for loop, start_index in rg.order_loops_nearest(rings, here):
            path = _directed(loop, start_index, settings.climb)
            # fed down to the plate's top only, then ramped along the ring to each level
            moves = ramp.ramped_passes(path, depths, settings.band_ramp_angle)
            builder.plunge(*moves[0])
            builder.polyline(moves[1:])
            here = builder.position[:2]
    return _finish(builder, settings, "band finishing", tool, settings.finish_rpm)


def _directed(loop: np.ndarray, start_index: int, climb: bool) -> np.ndarray:
    """Orient a ring for climb milling around the letters (spindle M03) and start it near the tool.

    Rings come out of the offset with outer boundaries counter-clockwise; the tool runs
    outside the letters there, so climb milling (material on the right) means clockwise.
    """
    closed = np.allclose(loop[0], loop[-1])
    if closed:
        loop = rg.rotate_closed(loop, start_index)
    return loop[::-1] if climb else loop


def _burr_contour(plate, glyphs, settings) -> Operation | None:
    builder = _builder(settings, settings.rough_feed)
    rings = [loop for _, loop in rg.contour_rings(glyphs, [settings.band_width], clip=plate)]
    for loop, start_index in rg.order_loops_nearest(rings, (0.0, 0.0)):
        path = _directed(loop, start_index, settings.climb)
        builder.plunge(path[0, 0], path[0, 1], settings.burr_depth)
        for x, y in path[1:]:
            builder.line(x, y, settings.burr_depth)
    return _finish(builder, settings, "burr contour", settings.rough_tool, settings.rough_rpm)


# ----------------------------------------------------------------------------------------
# The texture itself
# ----------------------------------------------------------------------------------------

def digits_from_seed(seed: int):
    """An endless stream of digits 0..9 from a seeded generator (same seed, same program)."""
    rng = np.random.default_rng(seed)
    while True:
        yield from (int(d) for d in rng.integers(0, 10, size=1024))


def bake(program: Program, digits=None) -> tuple[Program, list]:
    """Apply every operation's GougeTexture.

    Returns the textured program (textures removed) and the list of gouge target depths in
    cutting order.  ``digits`` is an iterator of 0..9 (default: from each texture's seed);
    passing the clock's last digits reproduces what the controller macro cuts.
    """
    operations, depths = [], []
    for op in program.operations:
        if op.texture is None:
            operations.append(op)
            continue
        stream = digits if digits is not None else digits_from_seed(op.texture.seed)
        jitter_rng = np.random.default_rng((op.texture.seed, 1))
        textured, op_depths = apply_texture(op, op.texture, stream, jitter_rng)
        operations.append(textured)
        depths += op_depths
    return Program(program.name, operations, program.units, program.work_offset, program.rapid_rate,
                   list(program.notes)), depths


def apply_texture(op: Operation, texture: GougeTexture, digits, jitter_rng=None) -> tuple[Operation, list]:
    """Texture the straight cutting moves of ``op`` that run along the raster at constant Z.

    Mirrors, move by move, what the fixed O7023 macro does on the controller:
      - rapids, arcs and moves that change Z pass through unchanged;
      - a move with no travel along the raster (a stepover) is cut at the current depth;
      - a move travelling ``spacing`` or less along the raster is cut at the current depth;
      - a longer move is cut in pieces: at every ``spacing`` of travel a new depth is drawn,
        reached by a straight line (scoop: dive first, then push up); the remainder to the
        end point stays at the last depth.
    The raster direction is the operation's ``raster_angle`` (texture spacing is measured
    along it); the macro mode supports only the X direction.
    """
    angle = math.radians(texture.raster_angle)
    direction = np.array([math.cos(angle), math.sin(angle)])
    kinds, points, feeds, centres = [], [], [], []
    depths = []
    position = np.array(op.start, float)
    z_now = position[2]
    spacing = texture.spacing

    def emit(kind, xyz, feed, centre=(np.nan, np.nan, np.nan)):
        kinds.append(kind)
        points.append(np.asarray(xyz, float))
        feeds.append(feed)
        centres.append(centre)

    for kind, target, feed, centre in zip(op.kind, op.xyz, op.feed, op.center):
        if kind in (RAPID, ARC_CW, ARC_CCW) or abs(target[2] - position[2]) > 1e-9:
            emit(kind, target, feed, centre)
            position = target.copy()
            z_now = target[2]
            continue
        travel = float(np.dot(target[:2] - position[:2], direction))
        if abs(travel) <= spacing:
            emit(FEED, (target[0], target[1], z_now), feed)
            position = target.copy()
            continue
        along = 0.0
        start = position.copy()
        while True:
            step = spacing
            if texture.spacing_jitter and jitter_rng is not None:
                step = spacing * (1 + texture.spacing_jitter * jitter_rng.uniform(-1, 1))
            if along + step > abs(travel) + TRAVEL_TOLERANCE:
                break
            previous_along = along
            along += step
            z_next = float(texture.depth(next(digits)))
            depths.append(z_next)
            piece_end = start[:2] + (target[:2] - start[:2]) * min(1.0, along / abs(travel))
            if texture.motion == "scoop":
                dive_at = previous_along + step * texture.scoop_dive
                dive_xy = start[:2] + (target[:2] - start[:2]) * (dive_at / abs(travel))
                emit(FEED, (dive_xy[0], dive_xy[1], z_next), feed)
                z_next = min(texture.shallowest, z_next + texture.amplitude)
            emit(FEED, (piece_end[0], piece_end[1], z_next), feed)
            z_now = z_next
        if abs(travel) - along > TRAVEL_TOLERANCE:
            emit(FEED, (target[0], target[1], z_now), feed)
        position = target.copy()
    textured = op.replace(kind=np.array(kinds, np.int8), xyz=np.array(points).reshape(-1, 3),
                          feed=np.array(feeds, float), center=np.array(centres, float).reshape(-1, 3),
                          texture=None)
    return textured, depths


# Offsets are polygons within region.ARC_TOLERANCE of the true curve: a keep region is checked
# this much inside its outline, so chord sag is not reported as a gouge.
KEEP_MARGIN = 2 * rg.ARC_TOLERANCE


def simulation_limits(letter_loops, program: Program, band_depth: float) -> dict:
    """The design limits the simulation checks an engraving against (keyword arguments of
    ``simulate.simulate``): nothing below the deepest planned cut anywhere (``design``), and the
    letters (``letter_loops``: (k, 2) arrays, work mm) left standing to the plate's top."""
    keep = rg.offset(rg.from_loops(list(letter_loops), "letters"), -KEEP_MARGIN)
    texture = program.operations[0].texture if program.operations else None
    floor = min(texture.deepest, band_depth) if texture is not None else band_depth
    return {"design": floor - KEEP_MARGIN, "keep_regions": [[np.asarray(loop) for loop in keep.to_polygons()]]}


def plate_stock(outline_loops, thickness: float):
    """The plate as the simulation's stock: the box around its top outline, top at Z = 0."""
    from ...simulate import BoxStock

    points = np.vstack(outline_loops)
    (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
    return BoxStock(float(x0), float(y0), -float(thickness), float(x1), float(y1), 0.0)
