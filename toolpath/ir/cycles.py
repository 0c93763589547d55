"""Drilling cycles: what an operation's moves are, said so a post may write a canned cycle.

An :class:`~.program.Operation` whose ``cycle`` is a :class:`DrillCycle` still carries every move
expanded as G0/G1 (what the simulation cuts and what a post without canned cycles writes, GRBL);
the cycle says the same motion in the terms of the controls' canned cycles, so a post whose control
has them may write G81 / G82 / G83 instead (LinuxCNC G-code reference "G81 Drilling Cycle", "G82
Drilling Cycle, Dwell", "G83 Peck Drilling Cycle", "G98/G99 Canned Cycle Return Level", "G80 Cancel
Canned Cycle"; the Fanuc 0i-M operator's manual's canned cycles use the same words).

The motion the expanded moves follow, hole by hole (as the manuals describe the cycles):
rapid in XY at ``initial_z``; rapid down to the R plane ``r_z``; feed to ``bottom_z`` (``drill``),
and there wait ``dwell`` seconds (``dwell``), or (``peck``) feed ``peck`` mm at a time from the R
plane, rapid back to the R plane after each peck and rapid down again to just above the depth
reached; then rapid up to ``initial_z`` (``retract`` "initial", G98) or to the R plane (``retract``
"r", G99, the next hole's XY move made there).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError

CYCLE_KINDS = ("drill", "dwell", "peck")
RETRACTS = ("initial", "r")


class CycleError(InputError):
    """A drilling cycle whose numbers cannot describe a cycle (the message names the number)."""


@dataclass(frozen=True)
class DrillCycle:
    """One canned cycle over ``holes`` ((n, 2) work mm, in the order drilled).  Heights in work mm
    (absolute Z); ``peck`` in mm (the G83 Q), ``dwell`` in seconds (G82 P), ``feed`` in mm/min."""

    kind: str
    holes: tuple
    initial_z: float
    r_z: float
    bottom_z: float
    feed: float
    peck: float = 0.0
    dwell: float = 0.0
    retract: str = "initial"

    def validate(self) -> None:
        if self.kind not in CYCLE_KINDS:
            raise CycleError(f"drilling cycle kind must be one of {', '.join(CYCLE_KINDS)}, got {self.kind!r}")
        if self.retract not in RETRACTS:
            raise CycleError(f"drilling cycle retract must be one of {', '.join(RETRACTS)}, got {self.retract!r}")
        for name in ("initial_z", "r_z", "bottom_z", "feed", "peck", "dwell"):
            if not math.isfinite(getattr(self, name)):
                raise CycleError(f"drilling cycle: {name} is not a number: {getattr(self, name)!r}")
        if not self.bottom_z < self.r_z <= self.initial_z:
            raise CycleError(f"drilling cycle: the bottom Z {self.bottom_z:g}, R plane {self.r_z:g} and initial Z "
                             f"{self.initial_z:g} must rise in that order")
        if not self.feed > 0:
            raise CycleError(f"drilling cycle: feed must be positive, got {self.feed:g}")
        if (self.kind == "peck") != (self.peck > 0) or self.peck < 0:
            raise CycleError(f"drilling cycle: a peck of {self.peck:g} mm does not fit a {self.kind!r} cycle "
                             "(peck > 0 with 'peck' alone)")
        if (self.kind == "dwell") != (self.dwell > 0) or self.dwell < 0:
            raise CycleError(f"drilling cycle: a dwell of {self.dwell:g} s does not fit a {self.kind!r} cycle "
                             "(dwell > 0 with 'dwell' alone)")
        holes = np.asarray(self.holes, float)
        if holes.ndim != 2 or holes.shape[1] != 2 or not len(holes) or not np.isfinite(holes).all():
            raise CycleError(f"drilling cycle: holes must be finite (x, y) pairs, got shape {holes.shape}")

    def check_moves(self, xyz: np.ndarray, kind: np.ndarray, feed_kind: int) -> None:
        """The expanded moves reach ``bottom_z`` at every hole by a feed move, and no feed move is
        anywhere else: the cycle and the moves say the same holes."""
        holes = np.asarray(self.holes, float)
        cuts = xyz[kind == feed_kind]
        for index, (x, y) in enumerate(holes):
            here = np.hypot(cuts[:, 0] - x, cuts[:, 1] - y) < 1e-6
            if not here.any() or abs(float(cuts[here, 2].min()) - self.bottom_z) > 1e-6:
                raise CycleError(f"drilling cycle: hole {index + 1} at X{x:g} Y{y:g} is not fed to Z{self.bottom_z:g} "
                                 "by the operation's moves")
        off = ~np.any(np.hypot(cuts[:, None, 0] - holes[None, :, 0], cuts[:, None, 1] - holes[None, :, 1]) < 1e-6,
                      axis=1)
        if off.any():
            raise CycleError(f"drilling cycle: a feed move at {cuts[off][0].tolist()} is at none of its holes")
