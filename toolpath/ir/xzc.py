"""The X-Z-C machine family's operation: a turn-mill centre turning the part on C, its turret's
driven tool moving in X (the radius from the axis) and Z, no Y.

A :class:`TurnMillOperation` is an :class:`~.program.Operation` whose moves are machine positions
(X, 0, Z) with C in ``rotary``, and whose tool points along one of the turret's two directions.
Posts of the ``xzc`` family (and the APT CL data post) read it; the turn-mill planner
(``toolpath/operations/turnmill``) makes it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import kinematics
from .program import RAPID, Operation, ProgramError

TOOL_DIRECTIONS = ("radial", "axial")   # the turret tools of an X-Z-C turn-mill centre


@dataclass
class TurnMillOperation(Operation):
    """An X-Z-C operation: ``xyz`` = (X, 0, Z) of the tool tip, X the radius from the axis,
    ``rotary = {"c": degrees}``.  ``direction`` is the turret tool: "radial" (along machine X,
    pointing at the axis) or "axial" (along Z, pointing down).  Lengths and cycle times are
    measured in part coordinates, where the tool actually cuts, along the curve the tool tip traces
    (:func:`kinematics.traced_lengths`, the one convention of every C move)."""

    direction: str = "radial"

    def validate(self):
        super().validate()
        if self.direction not in TOOL_DIRECTIONS:
            raise ProgramError(f"operation {self.name!r}: direction must be one of {TOOL_DIRECTIONS}")
        if set(self.rotary) != {"c"}:
            raise ProgramError(f"operation {self.name!r}: an X-Z-C operation moves exactly the C axis")
        if np.any(self.xyz[:, 1] != 0):
            raise ProgramError(f"operation {self.name!r}: the machine has no Y axis (Y must be 0)")

    def part_start(self) -> np.ndarray:
        """Where the tool tip is before the first move, in part coordinates (3,)."""
        return kinematics.machine_to_part(self.start, self.rotary["c"][:1])[0]

    def part_points(self) -> np.ndarray:
        """Tool-tip positions in part coordinates."""
        return kinematics.part_points(self)

    def tool_axes(self) -> np.ndarray:
        """Unit tool-axis vectors (tip towards holder) in part coordinates."""
        if self.direction == "axial":
            return np.tile([0.0, 0.0, 1.0], (len(self), 1))
        return kinematics.radial_axes(self.rotary["c"])

    def ball_centres(self) -> np.ndarray:
        return self.part_points() + self.tool.radius * self.tool_axes()

    def cycle_time(self, rapid_rate: float) -> float:
        """Estimated seconds: cutting blocks timed as the post's G93 F words time them
        (:func:`kinematics.block_minutes`), rapids at ``rapid_rate`` mm/min."""
        lengths = self.move_lengths()
        cutting = self.kind != RAPID
        minutes = kinematics.block_minutes(lengths[cutting], self.feed[cutting]).sum()
        return float(minutes * 60.0 + lengths[~cutting].sum() / rapid_rate * 60.0)
