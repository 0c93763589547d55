"""C-X-Z rotary-table posts (W2): the board turns on C, the bit moves in X (= -R) and Z.

Moves come from :mod:`toolpath.operations.rotary.rotary`: xyz = (X word, 0, tool-tip Z), rotary["c"] in
degrees (continuous), feed in mm/min along the path on the part (frames, move lengths and
the table's timing: :mod:`toolpath.ir.kinematics`).  Cutting moves are written
in inverse-time feed, ``G93``, with ``F`` = 1 / minutes for the block on every G01 (both
controllers require it there), so a move that turns the table is timed by the distance the
bit travels over the wood and never read as degrees per minute.  ``G94`` is restored after
every operation.  Rapids are ``G00``.  Words are written in the paper's order
``X-R C<deg> Z<z>``, modal (only when they change).  The header carries the cycle-time
estimate (true path lengths, the table's speed limit, rapids at the program's rapid rate).

Flavours:

* ``LinuxCNCRotaryPost`` (.ngc): checked by LinuxCNC's ``rs274`` in the tests; ``G64 P0.01``
  blending, ``G43 H<n>``, C to 4 decimals.
* ``FanucRotaryPost`` (.nc): for a milling-type Fanuc control with the inverse-time option
  and C set as a rotary axis without roll-over (C may run past 360): ``%`` / ``O0001``
  frame, 3 decimals on every axis and always a decimal point, ``T01 M06``,
  ``G43 Z.. H01``, no ``G64``, ends ``G91 G28 Z0.`` (no X/Y reference return: the machine
  has no Y, and X homes outside the board).  Fanuc reads G93 F 0.001..9999.999 only: the
  planner merges moves too short to time (:func:`toolpath.ir.program.merge_short_moves`) and the
  timing floor (:data:`toolpath.ir.kinematics.SHORTEST_BLOCK_MINUTES`) keeps every F below 9000;
  a word still out of range raises :class:`PostError` naming the operation and the move.
"""
from __future__ import annotations

import numpy as np

from ..toolpath.ir.kinematics import DEFAULT_MAX_TABLE_RPM, cycle_time, inverse_time_feed
from ..toolpath.ir.program import MoveKind, Operation, Program
from .fanuc import FANUC_MILL_LIMITS, FanucPost
from .gcode import GcodePost, PostError, comment_text, fmt
from .linuxcnc import LINUXCNC_LIMITS, LinuxCNCPost

RAPID, FEED = int(MoveKind.RAPID), int(MoveKind.FEED)     # the IR's move kinds


class RotaryCXZPost(GcodePost):
    """The C-X-Z writer; a flavour mixes this in front of its milling post for the hooks
    (preamble, tool change, length offset, ending)."""

    angle_decimals = 4
    feed_decimals = 4

    def __init__(self, work_offset: str | None = None, max_table_rpm: float = DEFAULT_MAX_TABLE_RPM,
                 machine=None):
        super().__init__(work_offset, machine=machine)
        self.max_table_rpm = max_table_rpm

    def a(self, value: float) -> str:
        return fmt(value, self.angle_decimals)

    def check(self, program: Program):
        for op in program.operations:
            what = f"operation {op.name!r}"
            if op.texture is not None:
                raise PostError(f"{what} carries a texture; the {self.name} post writes C-X-Z pockets only")
            if set(op.rotary) != {"c"}:
                raise PostError(f"{what}: the {self.name} post needs C positions for every move "
                                f"(got rotary axes {sorted(op.rotary)}); plan it with toolpath.operations.rotary.rotary")
            if np.any((op.kind != RAPID) & (op.kind != FEED)):
                raise PostError(f"{what} has arcs; a C-X-Z machine cuts straight X/C/Z moves only")
            if np.any(op.xyz[:, 0] > 1e-9) or op.start[0] > 1e-9:
                raise PostError(f"{what}: X must stay on the negative side of the rotation centre (X = -R)")
            if np.any(np.abs(op.xyz[:, 1]) > 1e-9):
                raise PostError(f"{what}: the machine has no Y axis; Y must be 0")

    conventions = ("(MACHINE: C-X-Z ROTARY TABLE. X = -R FROM THE AXIS. +C TURNS THE TABLE CLOCKWISE SEEN FROM THE "
                   "TOOL)", "(FEED: G93 INVERSE TIME, F = 1/MIN FROM THE PATH LENGTH ON THE PART. Z = TOOL TIP)")

    def operation_seconds(self, op: Operation, rapid_rate: float) -> float:
        """The table's speed limit counts too."""
        return cycle_time(op, rapid_rate, self.max_table_rpm)

    def to_text(self, program: Program) -> str:
        work_offset = self.frame_offset = self.work_offset or program.work_offset
        lines = self.opening(program)
        tool = None
        for index, op in enumerate(program.operations):
            lines.append(f"(OPERATION {index + 1}: {comment_text(op.name)})")
            if op.tool != tool:
                lines += self.tool_change(op, tool is None)
                lines += self.after_load(op, tool is None)       # Z first, then X and C
                tool = op.tool
            lines.append(f"G00 G90 {work_offset} X{self.n(op.start[0])} C{self.a(op.rotary['c'][0])} "
                         f"{self.spindle_on(op)}")
            lines += self.length_offset(op)
            lines.append("G93")
            lines += self.rotary_moves(op)
            lines += ["G94", f"G00 Z{self.n(op.safe_z)}"]
        lines += self.ending(program)
        self.check_machine(program)      # after the control's word ranges: those name the move
        body = "\n".join(lines) + "\n"
        return f"%\n{body}%\n" if self.percent_wrapped else body

    def rotary_moves(self, op: Operation) -> list:
        """Modal X C Z blocks; every G01 carries its inverse-time F; unchanged blocks dropped."""
        inverse_time = inverse_time_feed(op, self.max_table_rpm)
        self.check_limits(op, inverse_time)
        last = {"X": self.n(op.start[0]), "C": self.a(op.rotary["c"][0]), "Z": self.n(op.start[2])}
        lines, mode = [], None
        for kind, x, z, c, f in zip(op.kind.tolist(), op.xyz[:, 0].tolist(), op.xyz[:, 2].tolist(),
                                    op.rotary["c"].tolist(), inverse_time.tolist()):
            words = {"X": self.n(x), "C": self.a(c), "Z": self.n(z)}
            motion = [f"{axis}{text}" for axis, text in words.items() if text != last[axis]]
            if not motion:
                continue
            code = "G00" if kind == RAPID else "G01"
            block = ([code] if code != mode else []) + motion
            if kind != RAPID:
                block.append(f"F{fmt(f, self.feed_decimals)}")
            lines.append(" ".join(block))
            mode = code
            last = words
        return lines


class LinuxCNCRotaryPost(RotaryCXZPost, LinuxCNCPost):
    name = "linuxcnc-cxz"
    choice = "linuxcnc"
    label = "LinuxCNC"
    label_ja = "LinuxCNC"
    description = "X Z C words, G93 inverse-time feed (.ngc)"
    description_ja = "X Z C ワード、G93 逆時間送り（.ngc）"
    family = "cxz"
    order = 10
    extension = ".ngc"
    decimals = 4
    limits = LINUXCNC_LIMITS
    default_machine = "wood-lathe-cxz-linuxcnc"


class FanucRotaryPost(RotaryCXZPost, FanucPost):
    name = "fanuc-cxz"
    choice = "fanuc"
    label = "Fanuc"
    label_ja = "FANUC"
    description = "Fanuc flavour of the same program (.nc)"
    description_ja = "同じプログラムのFANUC版（.nc）"
    family = "cxz"
    order = 20
    extension = ".nc"
    decimals = 3
    angle_decimals = 3
    feed_decimals = 3
    limits = FANUC_MILL_LIMITS       # a milling-type Fanuc control with the inverse-time option

    def preamble(self, program):
        return ["G21 G17 G40 G49 G80 G90 G94"]

    default_machine = "wood-lathe-cxz"

    def ending(self, program):
        return ["M05", *self.lift(), "M30"]
