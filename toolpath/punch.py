"""Turret-punch simulation (SPEC W5 + W6): read an Amada program back, punch the sheet, check the part.

Before the program goes to the press the shop wants to know that the part falls out of the
sheet, how tall the scallops between nibbling hits are, and that no hit bites into the part.

The reader is independent of :mod:`..post.amada_punch` (it parses the text): ``G92 X Y``
(origin), ``G72 X Y`` (pattern reference point), ``G69 I J P Q T`` (nibbling line: length, angle
in degrees counter-clockwise from +X, tool diameter with its side, + = left of travel, - = right,
0 = the line is the tool-centre path; pitch; station), ``G79 I J P Q D T`` (punching line, D =
thickness), and the end ``G50`` or ``M30``.  Assumed of the controller: a round punch, and hits
spaced evenly along the line, both ends included, no further apart than Q.

The sheet is a ``manifold3d.CrossSection``: a blank round the hits minus the union of the hit
discs (polygons inscribed within ``tolerance``, so the error is always material left).  The part
is the piece that holds the pattern's interior; it is separated when it is not the frame.
"""
from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass

import numpy as np
from manifold3d import CrossSection, OpType

from . import region as rg
from .errors import InputError

_WORD = re.compile(r"([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")
_NEEDS = {"G92": "XY", "G72": "XY", "G69": "IJPQT", "G79": "IJPQDT"}
ENDS = ("G50", "M30")


class PunchError(InputError):
    """A punch program or setting the simulation cannot use; the message names the line."""


@dataclass
class PunchProgram:
    """The hits of a program: centres (k, 2) in program coordinates and, per hit, the NC line
    (1-based) and station.  ``punch_diameter``: |P| of the lines (None when P0)."""

    hits: np.ndarray
    lines: np.ndarray
    stations: np.ndarray
    punch_diameter: float | None
    thickness: float | None
    origin: tuple | None


def _words(text: str, number: int) -> tuple[str, dict]:
    """(code, {address: value}) of one block, or ("", {}) for a blank or comment line."""
    body = re.sub(r"\([^)]*\)", "", text).strip().upper()
    if not body:
        return "", {}
    body = re.sub(r"^N\d+\s*", "", body)
    pairs = _WORD.findall(body)
    if re.sub(r"\s", "", body) != "".join(a + v for a, v in pairs):
        raise PunchError(f"line {number}: cannot read {text.strip()!r}")
    codes = [a + str(int(float(v))) for a, v in pairs if a in "GM"]
    if len(codes) != 1:
        raise PunchError(f"line {number}: expected one G or M code, got {text.strip()!r}")
    code = codes[0][0] + codes[0][1:].zfill(2)
    words = {}
    for a, v in pairs:
        if a in "GM":
            continue
        if a in words:
            raise PunchError(f"line {number}: {a} given twice in {text.strip()!r}")
        words[a] = float(v)
    return code, words


def read_amada(text: str) -> PunchProgram:
    """The hits of an Amada turret-punch program (see the module notes); raises PunchError naming
    the line for anything else."""
    hits, lines, stations, diameters, thickness = [], [], [], set(), None
    origin, point, ended = None, None, False
    for number, raw in enumerate(text.splitlines(), start=1):
        code, words = _words(raw, number)
        if not code:
            continue
        if ended:
            raise PunchError(f"line {number}: {raw.strip()!r} comes after the program end")
        if code in ENDS:
            if words:
                raise PunchError(f"line {number}: {code} takes no words, got {raw.strip()!r}")
            ended = True
            continue
        if code not in _NEEDS:
            raise PunchError(f"line {number}: {code} is not a turret-punch code this reader knows "
                             f"(G92, G72, G69, G79, G50, M30)")
        if set(words) != set(_NEEDS[code]):
            raise PunchError(f"line {number}: {code} needs {', '.join(_NEEDS[code])}, got {raw.strip()!r}")
        if not all(math.isfinite(v) for v in words.values()):
            raise PunchError(f"line {number}: a number is not finite in {raw.strip()!r}")
        if code == "G92":
            origin = (words["X"], words["Y"])
        elif code == "G72":
            point = np.array([words["X"], words["Y"]])
        else:
            if point is None:
                raise PunchError(f"line {number}: {code} before any G72 reference point")
            length, pitch, p = words["I"], words["Q"], words["P"]
            if length < 0 or pitch <= 0:
                raise PunchError(f"line {number}: I (length) must be >= 0 and Q (pitch) > 0, got {raw.strip()!r}")
            if code == "G79":
                thickness = words["D"]
                if thickness <= 0:
                    raise PunchError(f"line {number}: D (thickness) must be > 0, got {raw.strip()!r}")
            angle = math.radians(words["J"])
            along = np.array([math.cos(angle), math.sin(angle)])
            left = np.array([-along[1], along[0]])
            count = max(1, math.ceil(length / pitch - 1e-9))
            t = np.linspace(0.0, length, count + 1)
            hits.append(point + t[:, None] * along + left * (p / 2))
            lines += [number] * (count + 1)
            stations += [int(words["T"])] * (count + 1)
            if p != 0:
                diameters.add(abs(p))
    if not ended:
        raise PunchError("the program has no end (G50 or M30)")
    if not hits:
        raise PunchError("the program punches nothing: no G69 or G79 line")
    if len(diameters) > 1:
        raise PunchError(f"the lines give different tool diameters {sorted(diameters)}: one punch is simulated")
    return PunchProgram(np.vstack(hits), np.array(lines), np.array(stations), diameters.pop() if diameters else None,
                        thickness, origin)


def nibbling_scallop(diameter: float, pitch: float) -> float:
    """The cusp height left between two hits ``pitch`` apart on a straight line: r - sqrt(r^2 - (pitch/2)^2)."""
    r = diameter / 2
    if pitch >= diameter:
        return r
    return r - math.sqrt(r * r - (pitch / 2) ** 2)


@dataclass
class Gouge:
    """A hit that bites into the part: the deepest point, how deep, and the NC line of the hit."""

    line: int
    depth_mm: float
    xy: tuple
    message: str


@dataclass
class PunchResult:
    hits: int
    pieces: int
    part_separated: bool
    part_area_mm2: float
    pattern_area_mm2: float | None
    removed_area_mm2: float
    max_scallop_mm: float | None
    max_gouge_mm: float
    gouges: list
    part: CrossSection
    sheet: CrossSection          # what is left of the blank: the part and the skeleton
    punch_diameter: float
    tolerance: float
    seconds: float


def _pattern(pattern) -> np.ndarray:
    try:
        return rg.validate_loop(pattern, "pattern")
    except InputError as error:
        raise PunchError(str(error)) from None


def _interior_point(pattern: CrossSection) -> np.ndarray:
    """A point well inside the pattern (the deepest of a few insets that are not empty)."""
    (x0, y0), (x1, y1) = pattern.bounds()[:2], pattern.bounds()[2:]
    inset = min(x1 - x0, y1 - y0) / 4
    while inset > 1e-6:
        inner = rg.offset(pattern, -inset)
        if inner.area() > 0:
            return np.asarray(inner.to_polygons()[0], float)[0]
        inset /= 4
    return np.asarray(pattern.to_polygons()[0], float)[0]


def _distances(points: np.ndarray, loop: np.ndarray) -> np.ndarray:
    """Distance of each point to the closed polyline."""
    a, b = loop, np.roll(loop, -1, axis=0)
    best = np.full(len(points), np.inf)
    for start in range(0, len(a), 256):
        pa, pb = a[start:start + 256], b[start:start + 256]
        d = pb - pa
        t = np.clip(((points[:, None, :] - pa[None]) * d[None]).sum(-1) / np.maximum((d * d).sum(-1), 1e-300),
                    0.0, 1.0)
        gap = points[:, None, :] - (pa[None] + t[..., None] * d[None])
        best = np.minimum(best, np.sqrt((gap * gap).sum(-1)).min(axis=1))
    return best


def simulate_punching(program_or_text, *, punch_diameter: float | None = None, pattern=None,
                      margin: float | None = None, tolerance: float = 0.01) -> PunchResult:
    """Punch the sheet with the program's hits and measure the part (see the module notes).

    ``pattern``: the flat pattern the part must match (k, 2), before tool compensation; without
    it the part is the largest piece not touching the blank's edge."""
    started = time.perf_counter()
    program = read_amada(program_or_text) if isinstance(program_or_text, str) else program_or_text
    if not isinstance(program, PunchProgram):
        raise PunchError("simulate_punching needs the NC text or a PunchProgram")
    d = punch_diameter if punch_diameter is not None else program.punch_diameter
    if d is None:
        raise PunchError("the program's lines are tool-centre paths (P0): give the punch diameter")
    if not (isinstance(d, (int, float)) and math.isfinite(d) and d > 0):
        raise PunchError(f"punch diameter must be a number > 0, got {d!r}")
    if program.punch_diameter is not None and abs(program.punch_diameter - d) > 1e-6:
        raise PunchError(f"punch diameter {d} does not match the program's P {program.punch_diameter}")
    if not (isinstance(tolerance, (int, float)) and math.isfinite(tolerance) and 0 < tolerance < d / 4):
        raise PunchError(f"tolerance must be > 0 and well under the punch radius, got {tolerance!r}")
    r = d / 2
    margin = d if margin is None else float(margin)
    hits = program.hits
    (x0, y0), (x1, y1) = hits.min(axis=0) - r - margin, hits.max(axis=0) + r + margin
    blank = rg.rectangle(x0, y0, x1, y1)
    disc = CrossSection.circle(r, rg.circle_segments(r, tolerance))
    holes = CrossSection.batch_boolean([disc.translate(tuple(h)) for h in hits], OpType.Add)
    sheet = blank - holes
    pieces = rg.components(sheet)
    frame = [p for p in pieces if np.allclose(p.bounds(), (x0, y0, x1, y1), atol=1e-6)]
    loose = [p for p in pieces if not any(p is f for f in frame)]
    outline = None
    if pattern is not None:
        outline = _pattern(pattern)
        inside = _interior_point(CrossSection([outline]))
        holding = [p for p in pieces if rg.contains_points(p, inside[None, :])[0]]
        part = holding[0] if holding else CrossSection()
        separated = bool(holding) and not any(part is f for f in frame)
    else:
        part = loose[0] if loose else CrossSection()
        separated = bool(loose)
    result = PunchResult(len(hits), len(pieces), separated, rg.area(part),
                         abs(rg.signed_area(outline)) if outline is not None else None,
                         rg.area(blank) - rg.area(sheet), None, 0.0, [], part, sheet, float(d), float(tolerance), 0.0)
    if outline is not None and part.area() > 0:
        boundary = np.vstack(rg.loops(part))
        gap = _distances(boundary, outline)
        outside = ~rg.contains_points(CrossSection([outline]), boundary)
        result.max_scallop_mm = float(gap[outside].max()) if outside.any() else 0.0
        bite = np.where(outside, 0.0, gap)
        worst = int(np.argmax(bite))
        if bite[worst] > tolerance:
            xy = boundary[worst]
            hit = int(np.argmin(np.hypot(*(hits - xy).T)))
            line = int(program.lines[hit])
            result.max_gouge_mm = float(bite[worst])
            result.gouges.append(Gouge(line, float(bite[worst]), (float(xy[0]), float(xy[1])),
                                       f"line {line}: a hit bites {bite[worst]:.3f} mm into the part at "
                                       f"({xy[0]:.2f}, {xy[1]:.2f})"))
    result.seconds = time.perf_counter() - started
    return result
