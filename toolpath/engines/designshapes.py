"""What the drawing-file readers (:mod:`.svgfile`, :mod:`.dxffile`) give: a :class:`Design`, its
:class:`Shape` s in work mm (Y up), and the geometry both readers share: arcs flattened within a
chord tolerance, open pieces joined end to end into closed loops, the limits a file must keep.

A shape is a polyline: ``closed`` (a loop; the first point not repeated) or open.  A full circle
keeps its centre and radius (``circle``), so a drilling can recognise a hole without fitting one.
Every error is a :class:`DesignFileError` naming the file, the element or entity and its line.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np

from ..ir.errors import MAX_REACH_MM, InputError
from .textfile import refusal

# Pieces whose ends lie this close (mm) are one point: a laser shop's LINEs meet to 1e-6 mm, a
# drawing rounded to 0.01 mm on export still closes.
JOIN_TOLERANCE = 0.01
# Points one design may have after flattening: a detailed logo has 10^4..10^5; more is a scan or a
# hatch exported as vectors, not something to cut (and would take minutes to plan).
MAX_POINTS = 500_000
# Segments one curve is flattened into at most (a 1 km arc within 0.01 mm would want 10^5).
MAX_SEGMENTS = 20_000
# A drawing file larger than this (bytes) is not a cutting design.
MAX_FILE_BYTES = 100_000_000


class DesignFileError(InputError):
    """A drawing file (SVG, DXF) that cannot be read: the message names the file, the element or
    entity, and its line."""


def checked_file(path: str) -> str:
    """The file's name, once it is a file of at most MAX_FILE_BYTES (else DesignFileError)."""
    name = os.path.basename(path)
    problem = refusal(path, path, "a drawing file")
    if problem:
        raise DesignFileError(problem)
    if os.path.getsize(path) > MAX_FILE_BYTES:
        raise DesignFileError(f"{name}: {os.path.getsize(path)} bytes, more than a drawing of "
                              f"{MAX_FILE_BYTES} bytes is refused")
    return name


@dataclass(frozen=True)
class Shape:
    """One polyline of a design: ``points`` (k, 2) in mm, Y up; ``closed`` (a loop, first point not
    repeated); ``layer`` ("" outside any layer); ``source`` (the element or entity and its line);
    ``circle`` ((cx, cy, r) in mm when the shape is a full circle, else None)."""

    points: np.ndarray
    closed: bool
    layer: str
    source: str
    circle: tuple | None = None


@dataclass(frozen=True)
class Design:
    """A drawing file read: its shapes in file order and ``notes`` (what was skipped and why:
    texts, images, unknown entities, pieces that stayed open)."""

    path: str
    shapes: tuple
    notes: tuple = ()

    def layers(self) -> list:
        """The layer names in the order they first appear."""
        return list(dict.fromkeys(shape.layer for shape in self.shapes))

    def loops(self, layer: str | None = None) -> list:
        """The closed loops ((k, 2) arrays, mm) of one layer, or of every layer."""
        return [s.points for s in self.shapes if s.closed and (layer is None or s.layer == layer)]

    def open_paths(self, layer: str | None = None) -> list:
        return [s.points for s in self.shapes if not s.closed and (layer is None or s.layer == layer)]


def arc_segments(radius: float, sweep: float, tolerance: float) -> int:
    """Chords for an arc of ``radius`` turning ``sweep`` radians so no chord strays more than
    ``tolerance`` from the arc: each chord spans at most 2 acos(1 - tol / r)."""
    r, sweep = abs(radius), abs(sweep)
    if r <= tolerance or sweep == 0:
        return 1
    step = 2.0 * math.acos(1.0 - tolerance / r)
    if step <= 0 or sweep / step >= MAX_SEGMENTS:       # a tolerance below the float's resolution at r
        return MAX_SEGMENTS
    return int(max(1, math.ceil(sweep / step)))


def arc_points(cx: float, cy: float, rx: float, ry: float, rotation: float, start: float, sweep: float,
               tolerance: float, with_start: bool = True) -> np.ndarray:
    """Points on an elliptical arc (centre, radii, x-axis ``rotation`` and angles in radians,
    ``sweep`` signed: > 0 counter-clockwise), the chords within ``tolerance`` of it."""
    n = arc_segments(max(abs(rx), abs(ry)), sweep, tolerance)
    t = start + sweep * np.arange(0 if with_start else 1, n + 1) / n
    x, y = rx * np.cos(t), ry * np.sin(t)
    c, s = math.cos(rotation), math.sin(rotation)
    return np.column_stack([cx + c * x - s * y, cy + s * x + c * y])


def circle_points(cx: float, cy: float, r: float, tolerance: float) -> np.ndarray:
    """A full circle as a closed loop (first point not repeated), counter-clockwise."""
    return arc_points(cx, cy, r, r, 0.0, 0.0, 2 * math.pi, tolerance)[:-1]


def bulge_points(p0, p1, bulge: float, tolerance: float) -> np.ndarray:
    """The arc from ``p0`` to ``p1`` of a DXF bulge (tan of a quarter of the included angle,
    > 0 counter-clockwise), without its first point: the chords within ``tolerance``."""
    (x0, y0), (x1, y1) = p0, p1
    chord = math.hypot(x1 - x0, y1 - y0)
    if bulge == 0 or chord == 0:
        return np.array([[x1, y1]], float)
    angle = 4.0 * math.atan(bulge)                      # included angle, signed
    radius = chord / (2.0 * math.sin(abs(angle) / 2.0))
    # the centre lies on the chord's perpendicular bisector, r cos(angle / 2) from the midpoint: to the
    # left of the chord for a counter-clockwise arc of less than a half turn (cos < 0 beyond it)
    mx, my = (x0 + x1) / 2, (y0 + y1) / 2
    nx, ny = -(y1 - y0) / chord, (x1 - x0) / chord
    along = radius * math.cos(abs(angle) / 2.0) * (1.0 if bulge > 0 else -1.0)
    cx, cy = mx + along * nx, my + along * ny
    start = math.atan2(y0 - cy, x0 - cx)
    points = arc_points(cx, cy, radius, radius, 0.0, start, angle, tolerance, with_start=False)
    points[-1] = (x1, y1)
    return points


def singular_values(matrix: np.ndarray) -> tuple[float, float]:
    """(largest, smallest) stretch of the matrix's 2 x 2 part, in closed form: the square roots of
    (E +- sqrt(E^2 - 4 det^2)) / 2 with E the sum of the squared entries."""
    a, b, c, d = (float(v) for v in (matrix[0, 0], matrix[0, 1], matrix[1, 0], matrix[1, 1]))
    energy, det = a * a + b * b + c * c + d * d, a * d - b * c
    root = math.sqrt(max(0.0, energy * energy - 4 * det * det))
    return math.sqrt((energy + root) / 2), math.sqrt(max(0.0, (energy - root) / 2))


def largest_scale(matrix: np.ndarray) -> float:
    """How much the matrix stretches a length at most."""
    return singular_values(matrix)[0]


def is_similarity(matrix: np.ndarray) -> bool:
    """Whether the matrix keeps circles circles (a rotation, uniform scale, shift, mirror)."""
    big, small = singular_values(matrix)
    return big - small <= 1e-9 * max(1.0, big)


def applied(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    points = np.asarray(points, float).reshape(-1, 2)
    return points @ matrix[:2, :2].T + matrix[:2, 2]


def checked_points(points, where: str) -> np.ndarray:
    """The points as a (k, 2) float array: finite and within MAX_REACH_MM, else an error naming
    ``where``."""
    pts = np.asarray(points, float).reshape(-1, 2)
    if not np.all(np.isfinite(pts)):
        raise DesignFileError(f"{where}: a coordinate is not a finite number (NaN or infinity)")
    if len(pts) and float(np.abs(pts).max()) > MAX_REACH_MM:
        raise DesignFileError(f"{where}: a point lies {float(np.abs(pts).max()):g} mm from the origin (more than "
                              f"{MAX_REACH_MM:g} mm): are the units right?")
    return pts


def without_repeats(points: np.ndarray) -> np.ndarray:
    """Consecutive duplicate points dropped (a zero-length segment)."""
    if len(points) < 2:
        return points
    keep = np.ones(len(points), bool)
    keep[1:] = np.any(np.abs(np.diff(points, axis=0)) > 1e-9, axis=1)
    return points[keep]


def finished(points, closed: bool, layer: str, source: str, circle=None, tolerance: float = JOIN_TOLERANCE):
    """A Shape of the points (checked; repeats dropped; an open piece whose ends meet within
    ``tolerance`` closed), or None when fewer than 2 distinct points are left."""
    pts = without_repeats(checked_points(points, source))
    if len(pts) > 2 and np.hypot(*(pts[-1] - pts[0])) <= tolerance:
        pts, closed = pts[:-1], True
    if closed and len(pts) < 3:
        closed = False
    if len(pts) < 2:
        return None
    return Shape(pts, closed, layer, source, circle)


class PointBudget:
    """Counts the points a design has made so far and refuses the file past MAX_POINTS."""

    def __init__(self, path: str, limit: int = MAX_POINTS):
        self.path, self.limit, self.count = path, limit, 0

    def spend(self, count: int, where: str) -> None:
        self.count += int(count)
        if self.count > self.limit:
            raise DesignFileError(f"{where}: the design has more than {self.limit} points after flattening; "
                                  "simplify it in the drawing program")


def join_open(shapes: list, tolerance: float = JOIN_TOLERANCE) -> tuple[list, list]:
    """Open shapes of one layer joined end to end (either direction) into longer pieces, closed
    where the chain comes back to its start within ``tolerance``: (shapes, notes).  Ends are found
    through a grid of cells ``tolerance`` wide, so a laser shop's 10^4 LINEs join in linear time."""
    if not shapes:
        return [], []
    ends = np.array([[s.points[0], s.points[-1]] for s in shapes], float)        # (n, 2, 2)
    cells: dict = {}
    keys = np.floor(ends / tolerance).astype(np.int64)
    for index in range(len(shapes)):
        for end in (0, 1):
            cells.setdefault((int(keys[index, end, 0]), int(keys[index, end, 1])), []).append((index, end))
    used = np.zeros(len(shapes), bool)

    def partner(point, exclude):
        """An unused piece with an end within ``tolerance`` of the point: (index, end) or None.
        Used ends are dropped from the cells' tails as they are met, so a pile of duplicate lines
        on one spot (common in laser DXFs) does not make this quadratic."""
        kx, ky = (int(v) for v in np.floor(point / tolerance))
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                entries = cells.get((kx + dx, ky + dy))
                while entries and used[entries[-1][0]]:
                    entries.pop()
                for index, end in reversed(entries or ()):
                    if not used[index] and index != exclude and \
                            math.hypot(*(ends[index, end] - point)) <= tolerance:
                        return index, end
        return None

    joined = []
    for first in range(len(shapes)):
        if used[first]:
            continue
        used[first] = True
        chain, sources = [shapes[first].points], [shapes[first].source]
        for direction in (1, -1):              # grow at the tail, then at the head
            while True:
                tip = chain[-1][-1] if direction == 1 else chain[0][0]
                if len(chain) > 1 or len(chain[0]) > 2:
                    if math.hypot(*(chain[-1][-1] - chain[0][0])) <= tolerance:
                        break
                found = partner(tip, first)
                if found is None:
                    break
                index, end = found
                used[index] = True
                piece = shapes[index].points
                if direction == 1:
                    chain.append((piece if end == 0 else piece[::-1])[1:])
                else:
                    chain.insert(0, (piece if end == 1 else piece[::-1])[:-1])
                sources.append(shapes[index].source)
        points = np.vstack(chain)
        source = sources[0] if len(sources) == 1 else f"{sources[0]} and {len(sources) - 1} more"
        shape = finished(points, False, shapes[first].layer, source, tolerance=tolerance)
        if shape is not None:
            joined.append(shape)
    notes = [f"{s.source}: an open piece (its ends do not meet another's within {tolerance:g} mm)"
             for s in joined if not s.closed]
    return joined, notes


def joined_by_layer(shapes: list, tolerance: float = JOIN_TOLERANCE) -> tuple[list, list]:
    """Closed shapes as they are, open ones joined within each layer: (shapes, notes)."""
    result, notes = [s for s in shapes if s.closed], []
    for layer in dict.fromkeys(s.layer for s in shapes):
        pieces, found = join_open([s for s in shapes if not s.closed and s.layer == layer], tolerance)
        result += pieces
        notes += found
    return result, notes
