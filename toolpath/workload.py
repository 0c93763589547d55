"""Work estimates before planning: what each operation kind would make, refused past a stated limit.

Every operation kind estimates up front, from its settings and the size of its geometry, the
quantity that drives its planning time and memory (tool positions dropped on a mesh, gouges, ring
passes, path points, hits, classification samples, bytes of a file), and :func:`toolpath.job.plan_job`
asks every switched-on operation for its estimate before planning any of them.  An estimate over
its limit is refused (:class:`WorkloadError`) naming the operation, the settings that drive it with
their values, the estimate against the limit, and the value of the setting that would bring it
under the limit.  The estimates are lower bounds or close to the real count (they never refuse a
job that would plan in reasonable time for a reason the numbers do not show).

The limits (:data:`LIMITS`) are measured on this project's planning, on a 2-core machine:
 - the drop cutter places about 1e5 tool positions a second on a 40k-face relief (carve's
   samples: 4e4-8e4 positions, 1-7 s), so 2e7 positions is about 3-20 minutes and 1-2 GB;
 - a program past 1e7 moves is hundreds of MB of NC text, more than a control's memory holds;
 - the rotary C unwrapping runs out of memory past 5e6 path points (issue 27's measurement);
 - engraving cuts about 6e4 gouges a second (2e6: about half a minute before the check) and
   5e5 mm of band path a second (a 1 km band: 20 s);
 - the pocket and profile limit, 1e7 mm (10 km) of path, is 140 hours of cutting at 1.2 m/min;
 - the limits of chamfer points, drill holes and pecks and turn-mill samples are set far above
   any real job (a sign's outline has 1e4 points, a drilled panel 1e3 holes, the turn-mill
   sample 2e4 samples), not measured at their edge;
 - the shortest drilling order compares pairs of holes: 2,000 holes in 2 s, 8,000 in 32 s, so
   20,000 is about 3 minutes;
 - a Part 21 file past 200 MB is not a workplan (the largest AP238 examples are a few MB);
 - an NC program simulated as it is (``batch.py simulate --nc``) is read and cut in about 370
   bytes and 3.7 microseconds of CPU a move (bench/scaling.json, 2026-11-27: a raster of 1e6
   moves, one a line, peaked at 518 MB against 149 MB at the start, in 3.7 s), so 1e7 lines is
   about 4 GB and 40 s; no post of this project writes more (carve roughing's 1e7 moves), and
   counting the lines is a moment (a line holds at most one move: an upper side for the moves).
Pure: numbers in, numbers or an error out.  Units: mm.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .ir.errors import InputError


class WorkloadError(InputError):
    """More work than this machine can plan: the message names the setting, the estimate and the limit."""


@dataclass(frozen=True)
class Limit:
    quantity: str       # what is counted, plural ("tool positions")
    most: float         # the largest count planned
    verb: str = "plan"  # what the machine does with it: "plan" or "simulate" ("this machine can plan")


LIMITS = {
    "carve finishing": Limit("tool positions", 2e7),
    "carve roughing": Limit("moves", 1e7),
    "engrave gouges": Limit("gouges", 2e6),
    "engrave band": Limit("mm of path", 1e7),
    "pocket path": Limit("mm of path", 1e7),
    "profile path": Limit("mm of path", 1e7),
    "chamfer points": Limit("outline points", 2e6),
    "drill holes": Limit("holes", 1e6),
    "drill order": Limit("holes to order", 20_000),
    "drill pecks": Limit("pecks", 1e6),
    "rotary points": Limit("path points", 5e6),
    "stepnc bytes": Limit("bytes", 2e8),
    "nc lines": Limit("lines", 1e7, "simulate"),
    "turnmill samples": Limit("classification samples", 5e6),
}


@dataclass(frozen=True)
class Estimate:
    key: str            # of LIMITS
    amount: float

    @property
    def limit(self) -> Limit:
        return LIMITS[self.key]

    @property
    def over(self) -> bool:
        return self.amount > self.limit.most


def count(n: float) -> str:
    """``41,000`` below a million, ``4.1e9`` above (never a 17-digit float)."""
    if not math.isfinite(n):
        return "infinitely many"
    if n < 1e6:
        return f"{n:,.0f}"
    mantissa, exponent = f"{n:.2g}".split("e")
    return f"{mantissa}e{int(exponent)}"


def check(estimate: Estimate, what: str, advice: str) -> Estimate:
    """Refuse ``estimate`` past its limit: ``what`` is the operation and the settings that drive it,
    ``advice`` what to change."""
    if estimate.over and estimate.limit.verb == "simulate":
        raise WorkloadError(f"{what} is about {count(estimate.amount)} {estimate.limit.quantity}, over the "
                            f"{count(estimate.limit.most)} this machine can simulate; {advice}")
    if estimate.over:
        raise WorkloadError(f"{what} is about {count(estimate.amount)} {estimate.limit.quantity}, over the "
                            f"{count(estimate.limit.most)} this machine can plan; {advice}")
    return estimate


def at_least(value: float) -> str:
    """A setting's smallest workable value, rounded up to two significant digits (``0.015``)."""
    if value <= 0 or not math.isfinite(value):
        return f"{value:g}"
    digits = 1 - math.floor(math.log10(value))
    rounded = math.ceil(value * 10 ** digits - 1e-9) / 10 ** digits
    return f"{rounded:g}"


def outline_measures(loops) -> tuple:
    """(area, perimeter, points) of closed loops ((k, 2) point lists), areas added without sign
    (an island's counts too: an estimate's upper side)."""
    area = perimeter = 0.0
    points = 0
    for loop in loops:
        p = np.asarray(loop, float).reshape(-1, 2)
        if len(p) == 0 or not np.isfinite(p).all():
            continue
        q = np.roll(p, -1, axis=0)
        area += abs(float(np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]))) / 2.0
        perimeter += float(np.hypot(*(q - p).T).sum())
        points += len(p)
    return area, perimeter, points


def raster_extent(width: float, height: float, angle_deg: float) -> tuple:
    """(across, along) a raster at ``angle_deg`` from +X covering a width x height box."""
    c, s = abs(math.cos(math.radians(angle_deg))), abs(math.sin(math.radians(angle_deg)))
    return width * s + height * c, width * c + height * s


def ball_stepover(radius: float, scallop: float) -> float:
    """Stepover of a ball of ``radius`` leaving ``scallop`` on a level surface (the carve rule)."""
    return 2.0 * math.sqrt(max(2.0 * radius * scallop - scallop * scallop, 0.0))


def carve(name: str, size: tuple, stock_above: float, settings) -> list:
    """``size``: the design's (width, depth, height) in mm.  The finishing raster drops the ball at
    least every sample spacing along lines at most the level-surface stepover apart; roughing
    clears the whole box at every level through the stock above the design."""
    width, depth, height = size
    where = f"carve {name!r}"
    r = settings.finish_tool.radius
    flat = ball_stepover(r, settings.scallop)
    across, along = raster_extent(width + 1.4 * r, depth + 1.4 * r, settings.raster_angle)
    estimates = []
    if flat > 0 and settings.sample_spacing > 0:
        lines = across / flat + 1
        positions = lines * (along / settings.sample_spacing + 1)
        # the spacing s that brings lines x (along / s + 1) to the limit (before, along x across / (flat x
        # limit) left the +1s out: just over the limit it advised the spacing already given)
        room = LIMITS["carve finishing"].most / lines - 1
        advice = (f"raise sample spacing to {at_least(along / room)} mm or more, or the scallop" if room > 0
                  else "raise the scallop")
        estimates.append(check(Estimate("carve finishing", positions),
                               f"{where}: the finishing raster at scallop {settings.scallop:g} mm and sample "
                               f"spacing {settings.sample_spacing:g} mm", advice))
    if settings.rough and settings.rough_stepover > 0 and settings.step_down > 0:
        spacing = min(settings.sample_spacing * 2, settings.rough_tool.radius / 2)
        across, along = raster_extent(width, depth, settings.raster_angle + 90.0)
        per_level = (across / settings.rough_stepover + 1) * (along / spacing + 1)
        levels = math.floor(stock_above / settings.step_down)
        most = LIMITS["carve roughing"].most
        estimates.append(check(Estimate("carve roughing", per_level * levels),
                               f"{where}: the roughing through {stock_above:g} mm of stock above the design at step "
                               f"down {settings.step_down:g} mm ({count(levels)} levels)",
                               f"raise step down to {at_least(stock_above * per_level / most)} mm or more, "
                               f"or give less stock above the design"))
    return estimates


def engrave(name: str, texture_area: float, letters_perimeter: float, settings) -> list:
    """Gouges: the roughing raster's length over the plate (area / stepover) cut into gouges every
    texture spacing.  Band: rings every band stepover across the band, each ramped down level by
    level round the letters' outlines (``letters_perimeter``, mm)."""
    texture = settings.texture
    where = f"engrave {name!r}"
    estimates = []
    if settings.stepover > 0 and texture.spacing > 0:
        gouges = texture_area / settings.stepover / texture.spacing
        most = LIMITS["engrave gouges"].most
        estimates.append(check(Estimate("engrave gouges", gouges),
                               f"{where}: the gouge texture at stepover {settings.stepover:g} mm and spacing "
                               f"{texture.spacing:g} mm over {texture_area:.0f} mm2",
                               f"raise stepover to {at_least(texture_area / texture.spacing / most)} mm or more"))
    if letters_perimeter > 0 and settings.band_stepover > 0 and settings.band_step_down > 0:
        rings = max(settings.band_width - 2 * settings.finish_tool.radius, 0.0) / settings.band_stepover + 1
        levels = math.ceil(abs(settings.band_depth) / settings.band_step_down)
        most = LIMITS["engrave band"].most
        estimates.append(check(Estimate("engrave band", rings * levels * letters_perimeter),
                               f"{where}: the band finishing at band stepover {settings.band_stepover:g} mm and "
                               f"band step down {settings.band_step_down:g} mm ({count(rings)} rings, "
                               f"{count(levels)} levels round {letters_perimeter:.0f} mm of letter outlines)",
                               "raise band stepover or band step down"))
    return estimates


def pocket(name: str, area: float, depth: float, settings) -> list:
    """Cut path: the area swept every stepover, at every level of step down."""
    if settings.stepover <= 0 or settings.step_down <= 0:
        return []
    levels = max(math.ceil(depth / settings.step_down), 1)
    path = area / settings.stepover * levels
    return [check(Estimate("pocket path", path),
                  f"pocket {name!r}: {area:.0f} mm2 at stepover {settings.stepover:g} mm and step down "
                  f"{settings.step_down:g} mm ({count(levels)} levels)",
                  f"raise stepover to {at_least(area * levels / LIMITS['pocket path'].most)} mm or more, "
                  f"or the step down")]


def profile(name: str, perimeter: float, depth: float, settings) -> list:
    """Cut path: the outline's length at every level of step down."""
    if settings.step_down <= 0 or depth <= 0:
        return []
    levels = max(math.ceil(depth / settings.step_down), 1)
    return [check(Estimate("profile path", perimeter * levels),
                  f"profile {name!r}: {perimeter:.0f} mm of outline at step down {settings.step_down:g} mm "
                  f"({count(levels)} levels)",
                  f"raise step down to {at_least(perimeter * depth / LIMITS['profile path'].most)} mm or more")]


def chamfer(name: str, points: int) -> list:
    return [check(Estimate("chamfer points", points), f"chamfer {name!r}: the drawing",
                  "simplify the drawing (fewer points)")]


def drill(name: str, holes: int, depth: float, settings) -> list:
    """Holes (the shortest order compares pairs of them) and pecks (each hole's depth / peck)."""
    where = f"drill {name!r}"
    estimates = [check(Estimate("drill holes", holes), f"{where}: the drawing's holes",
                       "split the holes into several operations")]
    if settings.order == "shortest":
        estimates.append(check(Estimate("drill order", holes), f"{where}: the shortest order of its holes",
                               "set the order to 'given' (the drawing's), or split the holes into several "
                               "operations"))
    if settings.peck > 0:
        pecks = holes * math.ceil(depth / settings.peck)
        estimates.append(check(Estimate("drill pecks", pecks),
                               f"{where}: {count(holes)} holes {depth:g} mm deep at peck {settings.peck:g} mm",
                               f"raise peck to {at_least(holes * depth / LIMITS['drill pecks'].most)} mm or more"))
    return estimates


def rotary(name: str, area: float, perimeter: float, depth: float, settings, bowl: bool = False) -> list:
    """A pocket's path points: roughing rings over the area at every level (a bowl's levels narrow
    with depth: half the area on average), the floor spiral over the area, the wall passes round
    the outline down the depth, a point every spacing."""
    if min(settings.spacing, settings.stepover, settings.roughing_stepover, settings.step_down,
           settings.wall_stepover) <= 0:
        return []
    levels = max(math.ceil(depth / settings.step_down), 1)
    length = area / settings.roughing_stepover * levels * (0.5 if bowl else 1.0) + area / settings.stepover \
        + perimeter * depth / settings.wall_stepover
    return [check(Estimate("rotary points", length / settings.spacing),
                  f"pocket {name!r}: the toolpath at a spacing of {settings.spacing:g} mm and a step down of "
                  f"{settings.step_down:g} mm",
                  f"raise spacing to {at_least(length / LIMITS['rotary points'].most)} mm or more")]


def stepnc(name: str, size: int) -> list:
    return [check(Estimate("stepnc bytes", size), f"the STEP-NC file {name!r}",
                  "a workplan is a few MB: check that this is the file meant")]


def nc_lines(text: str) -> int:
    """The lines of an NC program's text, ended by LF, CR LF or CR (as the NC reader reads them;
    a last line without its end counts)."""
    ends = max(text.count("\n"), text.count("\r"))
    return ends + (0 if not text or text.endswith(("\n", "\r")) else 1)


def nc_program(name: str, lines: int) -> list:
    """An NC program simulated as it is: its lines (:func:`nc_lines`), each at most one move."""
    return [check(Estimate("nc lines", lines), f"the NC file {name!r}",
                  "split it into files of fewer lines, or write it with a coarser stepover or tolerance")]


def turnmill(name: str, face_areas, settings) -> list:
    """Classification samples: each face cut into k x k sub-triangles, k = sqrt(2 area) / sample
    spacing held to 2..16 (the rule of engines.meshrays.face_samples, counted here without
    making the points)."""
    spacing = settings.sample_spacing
    if not (spacing > 0):
        return []
    areas = np.asarray(face_areas, float)
    areas = areas[np.isfinite(areas) & (areas > 0)]
    k = np.clip(np.ceil(np.sqrt(2.0 * areas) / spacing), 2, 16)
    samples = float((k * k).sum())
    most = LIMITS["turnmill samples"].most
    coarsest = math.sqrt(2.0 * float(areas.sum()) / most)
    # every face has at least 2 x 2 samples: past a quarter of the limit in faces no spacing will do
    # (before, the advice named a spacing finer than the one given)
    advice = (f"use a mesh of at most {count(most // 4)} faces (each face is sampled at least 4 times)"
              if 4 * len(areas) > most else
              f"raise sample spacing to {at_least(coarsest)} mm or more, or use a mesh of fewer faces")
    return [check(Estimate("turnmill samples", samples),
                  f"turn-mill {name!r}: {count(len(areas))} faces at sample spacing {spacing:g} mm", advice)]
