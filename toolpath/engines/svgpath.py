"""SVG geometry in user units: path data (``d``) and ``transform`` lists, flattened into polylines.

Path data follows the grammar of SVG 1.1 section 8.3.9 (kept by SVG 2, section 9.3.9): the
commands M/m L/l H/h V/v C/c S/s Q/q T/t A/a Z/z, a command's parameters repeated without
repeating the letter (after a moveto, further pairs are linetos), numbers such as ``1e-3`` and
``-.5.5`` (two numbers: a number ends where another cannot go on), and an arc's two flags as
single digits that may touch what follows (``a10 10 0 1015 15``: flags 1 and 0, then 15 15).
Elliptical arcs are turned into centre form as the SVG 1.1 implementation notes say (F.6.5, radii
scaled up when too small, F.6.6).  Transforms are the six of SVG 1.1 section 7.6.  Curves are
flattened in user units within a tolerance the caller gives in those units.
"""
from __future__ import annotations

import math
import re

import numpy as np

from .designshapes import MAX_SEGMENTS, DesignFileError, arc_points

NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
SEPARATORS = re.compile(r"[\s,]*")
COMMANDS = "MmZzLlHhVvCcSsQqTtAa"
# each command's parameters: n a number, f a flag
PARAMETERS = {"m": "nn", "l": "nn", "h": "n", "v": "n", "c": "nnnnnn", "s": "nnnn", "q": "nnnn", "t": "nn",
              "a": "nnnffnn", "z": ""}


class PathData:
    """Reads one ``d`` attribute; ``where`` names the element for errors; ``tolerance`` is the
    chord error allowed, in user units; ``budget`` (a designshapes.PointBudget) counts points."""

    def __init__(self, text: str, where: str, tolerance: float, budget):
        self.text, self.where, self.tolerance, self.budget = text, where, tolerance, budget
        self.pos = 0

    def fail(self, problem: str):
        shown = self.text[max(0, self.pos - 12):self.pos + 12].strip()
        raise DesignFileError(f"{self.where}: path data: {problem} at character {self.pos + 1} (near {shown!r})")

    def skip(self) -> None:
        self.pos = SEPARATORS.match(self.text, self.pos).end()

    def number(self) -> float:
        self.skip()
        match = NUMBER.match(self.text, self.pos)
        if match is None:
            self.fail("a number is missing" if self.pos >= len(self.text) or self.text[self.pos] in COMMANDS
                      else f"{self.text[self.pos]!r} is not a number")
        value = float(match.group())
        if not math.isfinite(value):
            self.fail(f"the number {match.group()} is too large")
        self.pos = match.end()
        return value

    def flag(self) -> bool:
        self.skip()
        if self.pos >= len(self.text) or self.text[self.pos] not in "01":
            self.fail("an arc flag must be 0 or 1")
        self.pos += 1
        return self.text[self.pos - 1] == "1"

    def subpaths(self) -> list:
        """[(points (k, 2) user units, closed)] of the path data."""
        found, points, start = [], [], None
        x = y = 0.0
        command, last, control = None, "", None
        count = 0

        def finish(closed: bool):
            if len(points) >= 2 or (closed and len(points) >= 1):
                found.append((np.array(points, float), closed))

        while True:
            self.skip()
            if self.pos >= len(self.text):
                break
            char = self.text[self.pos]
            if char in COMMANDS:
                command = char
                self.pos += 1
            elif command is None:
                self.fail("path data must begin with a moveto (M or m)")
            elif command in "Zz":
                self.fail("a number after Z (a new subpath begins with M)")
            elif char not in "+-.0123456789":
                self.fail(f"{char!r} is neither a command nor a number")
            lower = command.lower()
            relative = command.islower()
            values = [self.flag() if kind == "f" else self.number() for kind in PARAMETERS[lower]]
            if lower == "z":
                if points:
                    finish(True)
                    points = []
                if start is not None:
                    x, y = start
                last, control = "z", None
                continue
            if lower == "m":
                finish(False)
                x, y = (x + values[0], y + values[1]) if relative else (values[0], values[1])
                points, start = [(x, y)], (x, y)
                command = "l" if relative else "L"          # further pairs are linetos
                last, control = "m", None
                continue
            if not points:                                  # drawing on after Z: from the subpath's start
                if start is None:
                    self.fail("path data must begin with a moveto (M or m)")
                points = [start]
            ox, oy = (x, y) if relative else (0.0, 0.0)
            new = None
            if lower == "l":
                x, y = ox + values[0], oy + values[1]
            elif lower == "h":
                x = (x if relative else 0.0) + values[0]
            elif lower == "v":
                y = (y if relative else 0.0) + values[0]
            elif lower in "cs":
                if lower == "c":
                    c1 = (ox + values[0], oy + values[1])
                    rest = values[2:]
                else:
                    c1 = (2 * x - control[0], 2 * y - control[1]) if last in "cs" and control else (x, y)
                    rest = values
                c2, end = (ox + rest[0], oy + rest[1]), (ox + rest[2], oy + rest[3])
                new = bezier(np.array([(x, y), c1, c2, end]), self.tolerance)
                control, (x, y) = c2, end
            elif lower in "qt":
                if lower == "q":
                    c1, end = (ox + values[0], oy + values[1]), (ox + values[2], oy + values[3])
                else:
                    c1 = (2 * x - control[0], 2 * y - control[1]) if last in "qt" and control else (x, y)
                    end = (ox + values[0], oy + values[1])
                new = bezier(np.array([(x, y), c1, end]), self.tolerance)
                control, (x, y) = c1, end
            else:   # a
                end = (ox + values[5], oy + values[6])
                new = elliptical_arc((x, y), values[0], values[1], values[2], values[3], values[4], end,
                                     self.tolerance)
                x, y = end
            if new is None:
                points.append((x, y))
                count += 1
            else:
                points.extend(new.tolist())
                count += len(new)
            if lower not in "csqt":
                control = None
            last = lower
            if count >= 4096:
                self.budget.spend(count, self.where)
                count = 0
        finish(False)
        self.budget.spend(count, self.where)
        return found


def bezier(control: np.ndarray, tolerance: float) -> np.ndarray:
    """A quadratic or cubic Bezier's points after its first, on the curve, evenly in its parameter:
    n segments keep the chord error below max|B''| / (8 n^2), and |B''| is at most d (d - 1)
    times the largest second difference of the control points."""
    degree = len(control) - 1
    second = np.diff(control, n=2, axis=0)
    bound = degree * (degree - 1) * float(np.hypot(second[:, 0], second[:, 1]).max())
    n = int(min(max(1, math.ceil(math.sqrt(bound / (8 * tolerance)))), MAX_SEGMENTS)) if bound > 0 else 1
    t = np.arange(1, n + 1)[:, None] / n
    if degree == 2:
        return (1 - t) ** 2 * control[0] + 2 * (1 - t) * t * control[1] + t ** 2 * control[2]
    return ((1 - t) ** 3 * control[0] + 3 * (1 - t) ** 2 * t * control[1] + 3 * (1 - t) * t ** 2 * control[2]
            + t ** 3 * control[3])


def vector_angle(ux: float, uy: float, vx: float, vy: float) -> float:
    return math.atan2(ux * vy - uy * vx, ux * vx + uy * vy)


def elliptical_arc(start, rx: float, ry: float, rotation_deg: float, large: bool, sweep: bool, end,
                   tolerance: float):
    """The points after ``start`` of an SVG arc (endpoint form), or None when it is a straight line
    (a zero radius, F.6.6) or nothing (the end is the start, F.6.2)."""
    (x1, y1), (x2, y2) = start, end
    if x1 == x2 and y1 == y2:
        return np.empty((0, 2))
    rx, ry = abs(rx), abs(ry)
    chord = math.hypot(x2 - x1, y2 - y1)
    if min(rx, ry) <= 1e-9 * chord or chord <= 1e-12 * max(rx, ry, 1.0):
        return None          # a zero radius is a line (F.6.6); radii this small or a chord this short draw one

    phi = math.radians(rotation_deg % 360.0)
    c, s = math.cos(phi), math.sin(phi)
    dx, dy = (x1 - x2) / 2, (y1 - y2) / 2
    x1p, y1p = c * dx + s * dy, -s * dx + c * dy
    scale = (x1p / rx) ** 2 + (y1p / ry) ** 2
    if scale > 1:                                            # radii too small: scaled up (F.6.6)
        rx, ry = rx * math.sqrt(scale), ry * math.sqrt(scale)
    numerator = (rx * ry) ** 2 - (rx * y1p) ** 2 - (ry * x1p) ** 2
    denominator = (rx * y1p) ** 2 + (ry * x1p) ** 2
    if not denominator > 0 or not math.isfinite(numerator):
        return None
    root = math.sqrt(max(0.0, numerator / denominator)) * (-1.0 if large == sweep else 1.0)
    cxp, cyp = root * rx * y1p / ry, -root * ry * x1p / rx
    cx, cy = c * cxp - s * cyp + (x1 + x2) / 2, s * cxp + c * cyp + (y1 + y2) / 2
    theta = vector_angle(1.0, 0.0, (x1p - cxp) / rx, (y1p - cyp) / ry)
    delta = vector_angle((x1p - cxp) / rx, (y1p - cyp) / ry, (-x1p - cxp) / rx, (-y1p - cyp) / ry)
    if not sweep and delta > 0:
        delta -= 2 * math.pi
    elif sweep and delta < 0:
        delta += 2 * math.pi
    points = arc_points(cx, cy, rx, ry, phi, theta, delta, tolerance, with_start=False)
    points[-1] = (x2, y2)
    return points


TRANSFORM = re.compile(r"[\s,]*(matrix|translate|scale|rotate|skewX|skewY)\s*\(([^()]*)\)")


def transform_matrix(text: str, where: str) -> np.ndarray:
    """The 3 x 3 matrix of a ``transform`` attribute (its transforms applied right to left)."""
    matrix = np.eye(3)
    pos = 0
    text = text or ""
    while SEPARATORS.match(text, pos).end() < len(text):
        match = TRANSFORM.match(text, pos)
        if match is None:
            raise DesignFileError(f"{where}: transform {text!r}: cannot read it from character {pos + 1}")
        name, inside = match.group(1), match.group(2)
        numbers = NUMBER.findall(inside)
        if NUMBER.sub("", inside).strip(" \t\r\n,"):
            raise DesignFileError(f"{where}: transform {text!r}: {name}({inside}) holds something not a number")
        args = [float(v) for v in numbers]
        if not all(math.isfinite(v) for v in args):
            raise DesignFileError(f"{where}: transform {text!r}: a number is too large")
        matrix = matrix @ one_transform(name, args, text, where)
        pos = match.end()
    return matrix


ARGUMENT_COUNTS = {"matrix": (6,), "translate": (1, 2), "scale": (1, 2), "rotate": (1, 3), "skewX": (1,),
                   "skewY": (1,)}


def one_transform(name: str, args: list, text: str, where: str) -> np.ndarray:
    if len(args) not in ARGUMENT_COUNTS[name]:
        raise DesignFileError(f"{where}: transform {text!r}: {name} takes "
                              f"{' or '.join(map(str, ARGUMENT_COUNTS[name]))} numbers, got {len(args)}")
    m = np.eye(3)
    if name == "matrix":
        a, b, c, d, e, f = args
        m[:2] = [[a, c, e], [b, d, f]]
    elif name == "translate":
        m[0, 2], m[1, 2] = args[0], args[1] if len(args) > 1 else 0.0
    elif name == "scale":
        m[0, 0], m[1, 1] = args[0], args[1] if len(args) > 1 else args[0]
    elif name == "rotate":
        angle = math.radians(args[0])
        c, s = math.cos(angle), math.sin(angle)
        m[:2, :2] = [[c, -s], [s, c]]
        if len(args) == 3:
            cx, cy = args[1], args[2]
            m[0, 2], m[1, 2] = cx - c * cx + s * cy, cy - s * cx - c * cy
    elif name == "skewX":
        m[0, 1] = math.tan(math.radians(args[0]))
    else:
        m[1, 0] = math.tan(math.radians(args[0]))
    return m
