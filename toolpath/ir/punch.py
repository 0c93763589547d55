"""The turret-punch machine family's program: lines of hits a round punch makes in a sheet.

A :class:`PunchOperation` is one punch (a turret station) striking along straight lines: each line
is its first and its last hit, the control spacing the hits between them evenly, as few as keep
them at most ``pitch`` apart (an Amada G69 nibbling line, G79 above 3.2 mm).  Coordinates are the
sheet's, in mm.  With ``compensation`` "none" the lines are the punch centre's path; "left" or
"right" asks the control to offset the punch by its radius to that side of travel (the lines are
then the part's edge).  A :class:`PunchProgram` is what a punch post turns into one NC file: its
operations, the sheet origin the program sets (the Amada G92), and notes the post writes as
comments.  The sheet-metal planner (``toolpath/operations/sheetmetal``) makes these; posts of the
``punch`` family read them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .errors import ProgramError

COMPENSATIONS = ("none", "left", "right")


def _number(value, what: str) -> float:
    """``value`` as a finite number > 0, or a :class:`ProgramError` naming ``what``."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ProgramError(f"{what} must be a number, got {value!r}") from None
    if not math.isfinite(number) or number <= 0:
        raise ProgramError(f"{what} must be a finite number > 0, got {value!r}")
    return number


@dataclass
class PunchOperation:
    """One turret station's hits: ``lines`` (k, 2, 2), the first and the last hit of each line, in
    the order they are punched.  ``punch_diameter`` the round punch's size, ``pitch`` the largest
    spacing between hits (the G69 Q word), ``thickness`` the sheet's, all in mm."""

    name: str
    station: int
    punch_diameter: float
    pitch: float
    thickness: float
    lines: np.ndarray
    compensation: str = "none"

    def __post_init__(self):
        try:
            self.lines = np.array(self.lines, dtype=float)       # a copy: the caller's may change
        except (TypeError, ValueError):
            raise ProgramError(f"operation {self.name!r}: lines must be (first hit, last hit) pairs of (x, y)") from None
        self.validate()

    def validate(self):
        station_ok = isinstance(self.station, (int, np.integer)) and not isinstance(self.station, bool)
        if not station_ok or not 1 <= self.station <= 999:
            raise ProgramError(f"turret station must be an integer 1..999, got {self.station!r}")
        self.punch_diameter = _number(self.punch_diameter, "punch diameter")
        self.pitch = _number(self.pitch, "nibbling pitch Q")
        self.thickness = _number(self.thickness, "sheet thickness")
        if self.lines.ndim != 3 or self.lines.shape[1:] != (2, 2) or len(self.lines) == 0:
            raise ProgramError(f"lines must be (first hit, last hit) pairs of (x, y), got shape {self.lines.shape}")
        if not np.all(np.isfinite(self.lines)):
            raise ProgramError("a line has a non-finite coordinate (NaN or infinity)")
        if self.compensation not in COMPENSATIONS:
            raise ProgramError(f"operation {self.name!r}: compensation must be one of {COMPENSATIONS}, "
                               f"got {self.compensation!r}")

    def __len__(self):
        return len(self.lines)

    def lengths(self) -> np.ndarray:
        """Each line's length, first hit to last (mm)."""
        delta = self.lines[:, 1] - self.lines[:, 0]
        return np.hypot(delta[:, 0], delta[:, 1])

    def angles(self) -> np.ndarray:
        """Each line's direction in degrees from +X, counter-clockwise positive (-180..180)."""
        delta = self.lines[:, 1] - self.lines[:, 0]
        return np.degrees(np.arctan2(delta[:, 1], delta[:, 0]))


@dataclass
class PunchProgram:
    """What a punch post turns into one NC file: ``operations`` (:class:`PunchOperation`) in order,
    ``origin`` the sheet origin the program sets (machine X, Y in mm: the Amada G92), ``notes`` lines
    the post writes as comments at the start (where the part sits on the sheet, the clamps, the joints)."""

    name: str
    operations: list
    origin: tuple = (1000.0, 1040.0)
    notes: list = field(default_factory=list)

    def __post_init__(self):
        self.validate()

    def validate(self):
        if not self.operations or not all(isinstance(op, PunchOperation) for op in self.operations):
            raise ProgramError(f"punch program {self.name!r}: its operations must be one or more PunchOperations")
        try:
            x, y = (float(v) for v in self.origin)
        except (TypeError, ValueError):
            raise ProgramError(f"G92 origin must be two numbers (x, y), got {self.origin!r}") from None
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ProgramError("G92 origin must be finite")
        self.origin = (x, y)
        for op in self.operations:
            op.validate()

    def line_count(self) -> int:
        return sum(len(op) for op in self.operations)
