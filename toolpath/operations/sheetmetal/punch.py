"""Turret-punch simulation (SPEC W5 + W6): read an Amada program back, punch it out of a blank, check the part.

``read_amada`` parses the NC text itself (it shares no code with :mod:`..post.amada_punch`, whose
docstring defines the words).  Assumed of the controller: a round punch, and the hits of a G69 / G79
line spaced evenly from its start to its end, both included, as few as keep them at most Q apart.

``simulate_punching`` subtracts the hits from a blank with ``manifold3d.CrossSection``.  Each hit is
a regular polygon inscribed within ``tolerance`` of the punch circle (the error is material left,
never a false gouge), with corners on the circle ahead, behind and to both sides of its line: hits
closer than the diameter cut through; hits exactly one diameter apart leave a web of no width,
which holds the part.  The hits of one line closer than a diameter are united in closed form
(:func:`_chain`: the same corners, and the cusps between neighbours exactly), so a program's
union is of its lines, not of every hit.
"""
from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass, replace

import numpy as np
from manifold3d import CrossSection, OpType

from ...engines import region as rg
from ...ir.errors import InputError

_WORD = re.compile(r"([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")
_NEEDS = {"G92": "XY", "G72": "XY", "G69": "IJPQT", "G79": "IJPQDT"}
ENDS = ("G50", "M30")
# Limits of a real turret punch, checked before anything is punched (20,000 hits on four lines
# take about 2 s to simulate, mostly manifold3d's booleans on the 40k-corner outlines).
MIN_PITCH = 0.1             # mm: a nibbling pitch below this is a slip (Q0, Q0.001), not a part
MAX_HITS = 20_000           # hits in one program: at ~5 hits/s, over an hour of punching
_CHUNK = 1 << 20            # point x segment pairs per numpy block in the distance searches
DISC_BATCH = 500            # hits united at once between progress reports (and cancel points)


def line_steps(length, pitch: float):
    """Steps between the hits of a line ``length`` long at ``pitch``: as few as keep them at most
    ``pitch`` apart (the hits are both ends and the points between).  The 1e-9: 0.7 / 0.1 is 7,
    not 8."""
    return np.maximum(0, np.ceil(np.asarray(length, float) / pitch - 1e-9)).astype(int)


def hit_count(contour, pitch: float) -> int:
    """The hits a controller makes nibbling round the closed ``contour`` (k, 2) at ``pitch``
    (:func:`line_steps` on every line, both ends included, as :func:`read_amada` spaces them)."""
    pts = np.asarray(contour, float)
    return int((line_steps(np.hypot(*(np.roll(pts, -1, axis=0) - pts).T), pitch) + 1).sum())


class PunchError(InputError):
    """A punch program or setting the simulation cannot use; the message names the line."""


@dataclass
class PunchProgram:
    """The hits of a program, in program coordinates.

    ``hits`` (k, 2) punch centres; per hit its NC line (1-based) in ``lines``, the direction of
    that line in ``angles`` (degrees) and the turret station in ``stations``.
    ``punch_diameter``: |P| of the lines, None when they are tool-centre paths (P0);
    ``thickness``: D of the G79 lines, None without any; ``origin``: G92 X, Y or None."""

    hits: np.ndarray
    lines: np.ndarray
    angles: np.ndarray
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
    codes = [(a, v) for a, v in pairs if a in "GM"]
    if len(codes) != 1:
        raise PunchError(f"line {number}: expected one G or M code, got {text.strip()!r}")
    address, value = codes[0]
    code = address + (str(int(float(value))).zfill(2) if float(value).is_integer() else value)
    words = {}
    for a, v in pairs:
        if a in "GM":
            continue
        if a in words:
            raise PunchError(f"line {number}: {a} given twice in {text.strip()!r}")
        words[a] = float(v)
    return code, words


def _direction(degrees: float) -> np.ndarray:
    """Unit vector ``degrees`` counter-clockwise from +X, exact on the axes (J90.00 runs straight up)."""
    quarter, rest = divmod(degrees, 90.0)
    if rest == 0:
        return np.array(((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(quarter) % 4])
    angle = math.radians(degrees)
    return np.array([math.cos(angle), math.sin(angle)])


def read_amada(text: str) -> PunchProgram:
    """The hits of an Amada turret-punch program (see the module notes); raises PunchError naming
    the line for anything else."""
    if not isinstance(text, str):
        raise PunchError("a punch program must be text")
    hits, lines, angles, stations, diameters, thickness = [], [], [], [], set(), None
    origin, point, ended, count = None, None, False, 0
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
            continue
        if code == "G72":
            point = np.array([words["X"], words["Y"]])
            continue
        if point is None:
            raise PunchError(f"line {number}: {code} before any G72 reference point")
        length, pitch, p = words["I"], words["Q"], words["P"]
        if length < 0 or pitch <= 0:
            raise PunchError(f"line {number}: I (length) must be >= 0 and Q (pitch) > 0, got {raw.strip()!r}")
        if pitch < MIN_PITCH:
            raise PunchError(f"line {number}: the pitch Q{pitch:g} is below the {MIN_PITCH} mm a turret punch "
                             f"nibbles at (give Q from {MIN_PITCH} mm up): {raw.strip()!r}")
        if not words["T"].is_integer():
            raise PunchError(f"line {number}: cannot read {raw.strip()!r}")
        if code == "G79":
            thickness = words["D"]
            if thickness <= 0:
                raise PunchError(f"line {number}: D (thickness) must be > 0, got {raw.strip()!r}")
        steps = int(line_steps(length, pitch))
        count += steps + 1
        if count > MAX_HITS:
            raise PunchError(f"line {number}: the program has more than {MAX_HITS} hits by this line (at most "
                             f"{MAX_HITS} are simulated): check the pitches Q")
        along = _direction(words["J"])
        left = np.array([-along[1], along[0]])
        t = np.linspace(0.0, length, steps + 1)
        hits.append(point + t[:, None] * along + left * (p / 2))
        lines += [number] * (steps + 1)
        angles += [words["J"]] * (steps + 1)
        stations += [int(words["T"])] * (steps + 1)
        if p != 0:
            diameters.add(abs(p))
    if not ended:
        raise PunchError("the program has no end (G50 or M30)")
    if not hits:
        raise PunchError("the program punches nothing: no G69 or G79 line")
    if len(diameters) > 1:
        raise PunchError(f"the lines give different tool diameters {sorted(diameters)}: one punch is simulated")
    return PunchProgram(np.vstack(hits), np.array(lines), np.array(angles, float), np.array(stations),
                        diameters.pop() if diameters else None, thickness, origin)


def nibbling_scallop(diameter: float, pitch: float) -> float:
    """The cusp height r - sqrt(r^2 - (pitch/2)^2) (r = diameter / 2) that two hits ``pitch``
    apart on a straight line leave standing between them, measured from the line their discs
    touch.  At a pitch of the diameter or more the hits no longer overlap and r is returned
    (the whole radius stands, and the part is held by webs)."""
    if not (math.isfinite(diameter) and math.isfinite(pitch) and diameter > 0 and pitch >= 0):
        raise PunchError("the scallop needs a diameter > 0 and a pitch >= 0")
    r = diameter / 2
    if pitch >= diameter:
        return r
    return r - math.sqrt(r * r - (pitch / 2) ** 2)


@dataclass
class Gouge:
    """A hit that bites into the part: its NC line, the deepest point of that line's bites and
    how far inside the pattern it lies."""

    line: int
    depth_mm: float
    xy: tuple
    message: str
    line_mm: float = 0.0        # the length of that NC line, first hit to last


@dataclass
class PunchResult:
    """What the punching left.  ``part`` is the piece holding the pattern (the frame itself when
    the part is not separated), ``sheet`` everything left of the blank, ``skeleton`` the sheet
    without the part; ``part_outline`` the part's loops (outer CCW, holes CW).
    ``max_scallop_mm``: how far the separated part's boundary stands outside the pattern (None
    without a pattern or a separated part); ``max_gouge_mm``: how far it lies inside the pattern
    beyond ``tolerance`` (0 when nowhere), with one finding per biting NC line in ``gouges``,
    deepest first."""

    hits: int
    pieces: int
    part_separated: bool
    part_area_mm2: float
    pattern_area_mm2: float | None
    removed_area_mm2: float
    max_scallop_mm: float | None
    max_gouge_mm: float
    gouges: list
    part_outline: list
    part: CrossSection
    sheet: CrossSection
    skeleton: CrossSection
    punch_diameter: float
    tolerance: float
    seconds: float
    joints: int = 0                 # micro-joints the job left (0: the part is meant to fall free)
    held_by_joints: bool = False    # the part stays in the sheet by its joints alone (the intended result)
    joint_widths_mm: list = None    # the web each joint leaves, from the program's hits


def _number(value) -> float:
    """``value`` as a finite float, or NaN (for the caller's own message)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        return math.nan
    return math.nan if isinstance(value, bool) or not math.isfinite(v) else v


def _boxes_meet(a, b) -> bool:
    return a[0] <= b[2] and b[0] <= a[2] and a[1] <= b[3] and b[1] <= a[3]


def _pattern(pattern) -> np.ndarray:
    try:
        pts = np.asarray(pattern, dtype=float)
    except (TypeError, ValueError):
        pts = np.empty(0)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise PunchError("pattern: an outline must be a list of (x, y) points")
    try:
        return rg.validate_loop(pts, "pattern")
    except InputError as error:
        raise PunchError(str(error)) from None


def _segment_distances(points: np.ndarray, loop: np.ndarray) -> np.ndarray:
    """Distance of each point (n, 2) to the closed polyline ``loop`` (m, 2): one segment at a time
    over all the points, x and y apart (the same sums in the same order as an (n, m, 2) block,
    so the same numbers to the last bit, in a fifth of the time: the block's temporaries were
    the elbow bench's largest cost)."""
    points = np.asarray(points, float).reshape(-1, 2)
    px, py = np.ascontiguousarray(points[:, 0]), np.ascontiguousarray(points[:, 1])
    d = np.roll(loop, -1, axis=0) - loop
    dd = np.maximum((d * d).sum(axis=1), 1e-300)
    best = np.full(len(points), np.inf)
    for (ax, ay), (dx, dy), length in zip(loop.tolist(), d.tolist(), dd.tolist()):
        ux, uy = px - ax, py - ay
        t = np.clip((ux * dx + uy * dy) / length, 0.0, 1.0)
        gx = px - (ax + t * dx)
        gy = py - (ay + t * dy)
        np.minimum(best, gx * gx + gy * gy, out=best)
    return np.sqrt(best)


def _nearest_hits(points: np.ndarray, program: PunchProgram) -> np.ndarray:
    """Index of the hit nearest to each point.  A line's hits are evenly spaced from its first to
    its last, so the nearest of them follows from the projection on that segment; then the
    nearest line's wins."""
    first = np.flatnonzero(np.r_[True, program.lines[1:] != program.lines[:-1]])
    steps = np.r_[first[1:], len(program.lines)] - 1 - first
    a = program.hits[first]
    ab = program.hits[first + steps] - a
    out = np.empty(len(points), dtype=int)
    block = max(1, _CHUNK // len(first))
    for start in range(0, len(points), block):
        p = points[start:start + block, None, :]
        t = ((p - a) * ab).sum(axis=2) / np.maximum((ab * ab).sum(axis=1), 1e-300)
        k = first + np.clip(np.rint(t * steps), 0, steps).astype(int)
        nearest = ((p - program.hits[k]) ** 2).sum(axis=2).argmin(axis=1)
        out[start:start + block] = k[np.arange(len(k)), nearest]
    return out


class PunchCancelled(Exception):
    """The progress callback asked to stop (returned False)."""


def _reporter(progress):
    """``progress(fraction, text)`` that raises :class:`PunchCancelled` when the callback returns False."""
    def report(fraction: float, text: str = "") -> None:
        if progress is not None and progress(fraction, text) is False:
            raise PunchCancelled("punching simulation cancelled")
    return report


def _arc(centres: np.ndarray, u: np.ndarray, v: np.ndarray, r: float, a0: float, a1: float,
         step: float) -> np.ndarray:
    """Points of the arc from angle ``a0`` to ``a1`` (counter-clockwise, from ``u`` towards
    ``v``) round each of ``centres`` (c, 2): its two ends and the corners of the ``step``-gon
    with a corner on ``u`` that lie between them (the corners a lone hit's disc has): (c, m, 2)."""
    grid = step * np.arange(math.ceil(a0 / step), math.floor(a1 / step) + 1)
    grid = grid[(grid > a0 + 1e-9) & (grid < a1 - 1e-9)]
    theta = np.concatenate([[a0], grid, [a1]])
    ring = r * (np.cos(theta)[:, None] * u + np.sin(theta)[:, None] * v)
    return centres[:, None, :] + ring[None, :, :]


def _chain(centres: np.ndarray, r: float, step: float) -> np.ndarray | None:
    """The outline (counter-clockwise) of the union of discs of radius ``r`` round ``centres``
    (k + 1 >= 2 of them) spaced evenly along a straight line less than a diameter apart, or None
    when they are not.  Its corners are the cusps where neighbouring circles cross, exactly, and
    between them the corners of each hit's ``step``-radian polygon turned to the line (those of
    :func:`_discs`'s lone hits), so the union is inscribed as before, cusps made exact.

    With ``u`` along the line and ``v`` to its left, neighbours cross at angle alpha =
    acos(p / 2r) from ``u``: the last disc's cap runs from -(pi - alpha) to pi - alpha, each inner
    disc's arc from alpha to pi - alpha on the left side, the first disc's cap from alpha to
    2 pi - alpha, and the inner discs' arcs from pi + alpha to 2 pi - alpha on the right side."""
    k = len(centres) - 1
    length = float(np.hypot(*(centres[-1] - centres[0])))
    if length <= 0:
        return None
    p = length / k
    u = (centres[-1] - centres[0]) / length
    v = np.array([-u[1], u[0]])
    even = centres[0] + np.arange(k + 1)[:, None] * (p * u)
    if p >= 2 * r * (1 - 1e-9) or np.abs(centres - even).max() > 1e-9 * max(1.0, length):
        return None
    alpha = math.acos(p / (2 * r))
    inner = centres[1:-1]
    parts = [_arc(centres[-1:], u, v, r, alpha - math.pi, math.pi - alpha, step)[0],
             _arc(inner[::-1], u, v, r, alpha, math.pi - alpha, step)[:, 1:].reshape(-1, 2),
             _arc(centres[:1], u, v, r, alpha, 2 * math.pi - alpha, step)[0, 1:],
             _arc(inner, u, v, r, math.pi + alpha, 2 * math.pi - alpha, step)[:, 1:].reshape(-1, 2)]
    return np.vstack(parts)[:-1]          # the last corner is the first again


def _discs(program: PunchProgram, r: float, tolerance: float, progress=None) -> CrossSection:
    """The union of the hit discs, inscribed within ``tolerance``.  The hits of a line closer
    than a diameter are one outline (:func:`_chain`: corners on the circles and at the cusps,
    exactly); any other hit is a 4m-gon with a corner ahead.  United DISC_BATCH hits at a time
    (a line split at a batch's edge: its two chains overlap), with a progress report (and a
    chance to cancel) before each batch."""
    report = _reporter(progress)
    n = 4 * math.ceil(rg.circle_segments(r, tolerance) / 4)
    step = 2 * math.pi / n
    disc = CrossSection.circle(r, n)
    turned = {}
    parts = []
    for start in range(0, len(program.hits), DISC_BATCH):
        report(start / len(program.hits), "punching")
        hits = program.hits[start:start + DISC_BATCH]
        lines = program.lines[start:start + DISC_BATCH]
        angles = program.angles[start:start + DISC_BATCH]
        cuts = np.flatnonzero(np.r_[True, lines[1:] != lines[:-1], True])
        pieces = []
        for a, b in zip(cuts[:-1], cuts[1:]):
            outline = _chain(hits[a:b], r, step) if b - a > 1 else None
            if outline is not None:
                pieces.append(CrossSection([outline]))
                continue
            for (x, y), angle in zip(hits[a:b], angles[a:b]):
                if angle not in turned:
                    turned[angle] = disc.rotate(float(angle))
                pieces.append(turned[angle].translate((float(x), float(y))))
        parts.append(pieces[0] if len(pieces) == 1 else CrossSection.batch_boolean(pieces, OpType.Add))
    united = parts[0] if len(parts) == 1 else CrossSection.batch_boolean(parts, OpType.Add)
    report(1.0, "punching")
    return united


def _quarter(points: np.ndarray) -> np.ndarray:
    """Points (..., 2) turned a quarter counter-clockwise: (x, y) -> (-y, x), exactly."""
    points = np.asarray(points, float)
    return np.stack([-points[..., 1], points[..., 0]], axis=-1)


def _unquarter(points: np.ndarray) -> np.ndarray:
    """The inverse of :func:`_quarter`: (x, y) -> (y, -x)."""
    points = np.asarray(points, float)
    return np.stack([points[..., 1], -points[..., 0]], axis=-1)


_UNQUARTER = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])     # the same, for a CrossSection


def _gouges(boundary: np.ndarray, bite: np.ndarray, program: PunchProgram, tolerance: float,
            back=None) -> list:
    """One finding per NC line whose hits bite deeper than ``tolerance``, deepest first; ``back``
    maps the points to the program's coordinates (the simulation's frame may be turned)."""
    deep = np.flatnonzero(bite > tolerance)
    line = program.lines[_nearest_hits(boundary[deep], program)]
    findings = []
    for number in np.unique(line):
        mine = deep[line == number]
        worst = mine[np.argmax(bite[mine])]
        x, y = boundary[worst] if back is None else back(boundary[worst])
        depth = float(bite[worst])
        ends = program.hits[program.lines == number]
        findings.append(Gouge(int(number), depth, (float(x), float(y)),
                              f"line {number}: a hit bites {depth:.3f} mm into the part at ({x:.2f}, {y:.2f})",
                              float(np.hypot(*(ends[-1] - ends[0])))))
    return sorted(findings, key=lambda g: (-g.depth_mm, g.line))


def _joint_cuts(joints: np.ndarray, r: float) -> CrossSection:
    """The webs of the micro-joints, each as the strip between its two hits (centre to centre,
    and half a radius into each hit) one radius either side of their line: cut, the part is
    released exactly where its joints would break."""
    strips = []
    for c1, c2 in joints:
        u = (c2 - c1) / max(float(np.hypot(*(c2 - c1))), 1e-12)
        v = np.array([-u[1], u[0]])
        a, b = c1 - u * (r / 2), c2 + u * (r / 2)
        strips.append(CrossSection([np.array([a - v * r, b - v * r, b + v * r, a + v * r])]))
    return strips[0] if len(strips) == 1 else CrossSection.batch_boolean(strips, OpType.Add)


def _pattern_piece(pieces, shape):
    px0, py0, px1, py1 = shape.bounds()
    overlap = [(p ^ shape).area() if _boxes_meet(p.bounds(), (px0, py0, px1, py1)) else 0.0 for p in pieces]
    if max(overlap) <= 0:
        raise PunchError("the pattern does not overlap what is left of the sheet: "
                         "are the pattern and the program in the same coordinates?")
    return pieces[int(np.argmax(overlap))]


def simulate_punching(program_or_text, *, punch_diameter: float | None = None, pattern=None,
                      margin: float | None = None, tolerance: float = 0.01, progress=None,
                      joints=None) -> PunchResult:
    """Punch every hit of the program out of a blank and measure what is left.  The part is the
    piece holding most of the pattern; it is separated when it is not the frame round the blank.

    ``program_or_text``: the NC text or a :class:`PunchProgram`.  ``punch_diameter`` is needed
    when the lines are tool-centre paths (P0) and must agree with |P| (within the program's
    0.01 mm) otherwise.  ``pattern``: the flat pattern (k, 2) the part must match, before tool
    compensation, in the program's coordinates; without it the part is the largest piece that
    is not the frame, and there are no scallops or gouges to measure.  ``margin``: blank round
    the hits beyond the punch radius (default the diameter).  ``tolerance``: the discs' chord
    error and the depth below which a bite is not a gouge (mm).  ``progress``: optional
    callable(fraction, text) called while the hits are punched; returning False cancels
    (:class:`PunchCancelled`).  ``joints`` (j, 2, 2): the two hits either side of each micro-joint
    the job left; the part held by them alone is ``held_by_joints`` (measured on the part as it
    comes out when they break), ``part_separated`` says whether it fell free with them."""
    started = time.perf_counter()
    program = read_amada(program_or_text) if isinstance(program_or_text, str) else program_or_text
    if not isinstance(program, PunchProgram):
        raise PunchError("simulate_punching needs the NC text or a PunchProgram")
    if len(program.hits) == 0:
        raise PunchError("the program punches nothing: no G69 or G79 line")
    if punch_diameter is None:
        if program.punch_diameter is None:
            raise PunchError("the program's lines are tool-centre paths (P0): give the punch diameter")
        punch_diameter = program.punch_diameter
    d = _number(punch_diameter)
    if not d > 0:
        raise PunchError(f"punch diameter must be a number > 0, got {punch_diameter!r}")
    if program.punch_diameter is not None and abs(program.punch_diameter - d) > 0.005 + 1e-9:
        raise PunchError(f"punch diameter {d:g} does not match the program's P {program.punch_diameter:g}")
    tol = _number(tolerance)
    if not 0 < tol < d / 4:
        raise PunchError(f"tolerance must be > 0 and well under the punch radius, got {tolerance!r}")
    margin = d if margin is None else _number(margin)
    if not margin > 0:
        raise PunchError("margin must be a number > 0")
    outline = None if pattern is None else _pattern(pattern)

    # Clipper's sweep (manifold's CrossSection booleans) runs along Y: when the hits lie along X, every
    # sweep line crosses the discs of a whole side, and the thinner the strip the more of them (an
    # elbow piece of a 400 mm pipe, 1257 mm along X: 3.6x as long as turned upright at 60 pieces, 4.7x
    # at 120).  Such a program is punched turned a quarter, exactly, and the results turned back.
    turned = bool(np.ptp(program.hits[:, 0]) > np.ptp(program.hits[:, 1]))
    if turned:
        program = replace(program, hits=_quarter(program.hits), angles=program.angles + 90.0)
        outline = None if outline is None else _quarter(outline)
    r = d / 2
    hits = program.hits
    x0, y0 = hits.min(axis=0) - r - margin
    x1, y1 = hits.max(axis=0) + r + margin
    blank = rg.rectangle(x0, y0, x1, y1)
    pairs = np.zeros((0, 2, 2)) if joints is None else np.asarray(joints, dtype=float).reshape(-1, 2, 2)
    if not np.all(np.isfinite(pairs)):
        raise PunchError("joints: every joint is two finite hit centres")
    if len(pairs) and outline is None:
        raise PunchError("joints need the pattern: the part held by them is the piece holding the pattern")
    if turned:
        pairs = _quarter(pairs)
    sheet = blank - _discs(program, r, tol, progress)

    def is_frame(piece):      # the margin keeps the frame whole round the blank: the only piece at its edges
        return np.allclose(piece.bounds(), (x0, y0, x1, y1), atol=1e-6)

    pieces = rg.components(sheet)
    shape = None if outline is None else CrossSection([outline])
    widths = []
    if len(pairs):
        near = _nearest_hits(pairs.reshape(-1, 2), program)
        ends = program.hits[near].reshape(-1, 2, 2)
        widths = [round(float(np.hypot(*(b - a))) - d, 4) for a, b in ends]
        released = rg.components(sheet - _joint_cuts(pairs, r))
        part = _pattern_piece(released, shape)
        # the cuts take nothing of the part but the cusps between hits (it lies a radius from the
        # hits' line): fallen free, it is a loose piece of the sheet as punched as well
        area = part.area()
        fell = any(not is_frame(p) and p.area() >= 0.9 * area for p in pieces)
        pieces = released
    elif outline is None:
        loose = [p for p in pieces if not is_frame(p)]
        part = loose[0] if loose else CrossSection()
        fell = part.area() > 0
    else:
        part = _pattern_piece(pieces, shape)
        fell = part.area() > 0 and not is_frame(part)
    separated = part.area() > 0 and not is_frame(part)
    held = bool(len(pairs) and separated and not fell)
    loops = rg.loops(part)

    scallop, gouge, findings = None, 0.0, []
    if outline is not None:
        boundary = np.vstack(loops)
        gap = _segment_distances(boundary, outline)
        inside = rg.contains_points(shape, boundary)
        bite = np.where(inside, gap, 0.0)
        if separated:
            scallop = float(gap[~inside].max()) if (~inside).any() else 0.0
        findings = _gouges(boundary, bite, program, tol, _unquarter if turned else None)
        gouge = findings[0].depth_mm if findings else 0.0
    skeleton = CrossSection.compose([p for p in pieces if p is not part])
    if turned:
        loops = [_unquarter(loop) for loop in loops]
        part, sheet, skeleton = (c.transform(_UNQUARTER) for c in (part, sheet, skeleton))

    return PunchResult(
        hits=len(hits), pieces=len(pieces), part_separated=bool(fell), part_area_mm2=rg.area(part),
        pattern_area_mm2=None if outline is None else abs(rg.signed_area(outline)),
        removed_area_mm2=rg.area(blank) - rg.area(sheet), max_scallop_mm=scallop, max_gouge_mm=gouge,
        gouges=findings, part_outline=loops, part=part, sheet=sheet,
        skeleton=skeleton,
        punch_diameter=d, tolerance=tol, seconds=time.perf_counter() - started,
        joints=len(pairs), held_by_joints=held, joint_widths_mm=widths)

