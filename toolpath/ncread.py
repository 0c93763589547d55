"""Read the G-code our posts write (LinuxCNC / Fanuc dialect) back into the IR, for simulation.

What it understands: G0 G1 G2 G3 with X Y Z C I J (R is refused), G90/G91, G20/G21, G17,
G93/G94 (feeds do not matter to a simulation), comments in parentheses or after ``;``,
N numbers, ``%`` and ``O`` lines; every other word is ignored.  Each move remembers its line,
so a finding can name the NC line.
"""
from __future__ import annotations

import re

import numpy as np

from .errors import InputError
from .program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, Tool
from .tools import SHAPES

WORD = re.compile(r"([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")


class NCReadError(InputError):
    """A line of the NC file the reader cannot follow; the message names it."""


def read_nc(text: str, tool: Tool, name: str = "NC program") -> tuple:
    """(Operation, line number of every move).  Coordinates in mm (G20 programs are converted)."""
    position = {"X": 0.0, "Y": 0.0, "Z": 0.0, "C": 0.0}
    mode, absolute, scale = None, True, 1.0
    kinds, points, centres, c_values, lines = [], [], [], [], []
    saw_c = False
    for number, raw in enumerate(text.splitlines(), start=1):
        line = re.sub(r"\([^)]*\)", "", raw.split(";")[0]).strip().upper()
        if not line or line.startswith(("%", "O")):
            continue
        if "(" in line or ")" in line:
            raise NCReadError(f"line {number}: unbalanced parenthesis in {raw.strip()!r}")
        words = WORD.findall(line)
        if not words and line:
            raise NCReadError(f"line {number}: no G-code words in {raw.strip()!r}")
        values = {}
        for letter, value in words:
            if letter == "G":
                code = float(value)
                if code in (0, 1, 2, 3):
                    mode = int(code)
                elif code == 90:
                    absolute = True
                elif code == 91:
                    absolute = False
                elif code == 20:
                    scale = 25.4
                elif code == 21:
                    scale = 1.0
            else:
                values[letter] = float(value)
        if "R" in values and mode in (2, 3):
            raise NCReadError(f"line {number}: R-format arcs are not supported; use I and J")
        axes = [a for a in ("X", "Y", "Z", "C") if a in values]
        if not axes:
            continue
        if mode is None:
            raise NCReadError(f"line {number}: a move before any G0/G1/G2/G3")
        before = dict(position)
        for axis in axes:
            value = values[axis] * (scale if axis != "C" else 1.0)
            position[axis] = value if absolute else position[axis] + value
        saw_c = saw_c or "C" in values
        kind = (RAPID, FEED, ARC_CW, ARC_CCW)[mode]
        centre = (np.nan, np.nan, np.nan)
        if kind in (ARC_CW, ARC_CCW):
            if "I" not in values and "J" not in values:
                raise NCReadError(f"line {number}: an arc needs I and J")
            centre = (before["X"] + values.get("I", 0.0) * scale, before["Y"] + values.get("J", 0.0) * scale,
                      position["Z"])
        kinds.append(kind)
        points.append((position["X"], position["Y"], position["Z"]))
        centres.append(centre)
        c_values.append(position["C"])
        lines.append(number)
    if not kinds:
        raise NCReadError("the NC file has no moves")
    feed = np.where(np.array(kinds) == RAPID, np.nan, 1000.0)
    rotary = {"c": np.array(c_values)} if saw_c else {}
    # The tool is taken to start where the first move ends: nothing is known of where it was.
    op = Operation(name, tool, 0.0, kinds, points, feed, center=centres, rotary=rotary, start=np.array(points[0]))
    return op, lines


def parse_tool(text: str) -> Tool:
    """``ball:6``, ``flat:3`` or ``bull:10,2`` (diameter, corner radius in mm)."""
    kind, _, sizes = text.partition(":")
    try:
        numbers = [float(v) for v in sizes.split(",")]
    except ValueError:
        raise NCReadError(f"--tool {text!r}: give ball:D, flat:D or bull:D,R") from None
    shape = SHAPES.get(kind)
    # end mills only; a bull nose's corner radius is its second size
    if shape is None or shape.pointed or not numbers or shape.corner_given != (len(numbers) == 2):
        raise NCReadError(f"--tool {text!r}: give ball:D, flat:D or bull:D,R")
    return Tool(1, kind, numbers[0], corner_radius=numbers[1] if shape.corner_given else 0.0)
