"""APT CL data (the cutter-location source a post-processor reads), in part coordinates.

The seed paper's system is split into a main processor that writes CL data and a
post-processor that turns CL data into NC.  This writer gives the same hand-over from our
Operations.  A turn-mill program's machine X/Z/C moves are turned back into part coordinates:
the tool tip, and the tool axis as a unit vector from the tip toward the holder.  That is
(cos C, sin C, 0) for a radial tool and (0, 0, 1) for an axial tool.  A plain 3-axis operation
(no rotary axes) is written as it is, with the axis (0, 0, 1).

    PARTNO/SAMPLE
    $$ KEZURI CAM - APT CL DATA, PART COORDINATES, MM
    UNITS/MM
    MULTAX/ON
    $$ OPERATION 1: RADIAL ROUGHING - RADIAL TOOL
    CUTTER/6.0000,3.0000
    LOADTL/1
    SPINDL/RPM,4000,CLW
    FROM/44.5000,0.0000,2.0000
    RAPID
    GOTO/44.5000,0.0000,-15.0000,1.000000,0.000000,0.000000
    FEDRAT/MMPM,150.0
    GOTO/...
    SPINDL/OFF
    FINI

There is one GOTO per move, zero-length moves included, so the CL data and the IR stay
in step.  RAPID applies to the GOTO that follows it.  FEDRAT is written when the feed changes.
Lines stay within APT's 72 columns.  Output is deterministic.
"""
from __future__ import annotations

import numpy as np

from ..toolpath.ir.program import MoveKind, Operation, Program, TurnMillOperation
from . import words
from .gcode import PostError, comment_text, format_duration
from .registry import ControllerLimits, Post

RAPID, FEED = int(MoveKind.RAPID), int(MoveKind.FEED)     # the IR's move kinds


def _num(value: float, decimals: int) -> str:
    text = f"{value:.{decimals}f}"
    return text[1:] if text.startswith("-") and float(text) == 0 else text


def _nums(values: list, decimals: int) -> list:
    """:func:`_num` of every value (:func:`.words.fixed`, then no minus on a zero)."""
    negative_zero = f"-{0.0:.{decimals}f}"
    return [text[1:] if text == negative_zero else text for text in words.fixed(values, decimals)]


class CLDataPost(Post):
    """Program -> APT CL data text."""

    name = "cldata"
    label = "APT CL Data"
    label_ja = "APT CLデータ"
    description = "Cutter location data in part coordinates, for a post-processor"
    description_ja = "ポストプロセッサ用の、部品座標での工具位置（CL）データ"
    family = "cldata"
    extension = ".cls"
    limits = ControllerLimits(resolution=1e-4, source="APT CL data (ISO 3592 / ISO 4343) is read by a post-processor, "
                                                        "not a control: no word ranges; 4 decimals")

    def __init__(self, decimals: int = 4, axis_decimals: int = 6):
        self.decimals = decimals
        self.axis_decimals = axis_decimals

    def to_text(self, program: Program) -> str:
        if not program.operations:
            raise PostError("the program has no operations")
        lines = [f"PARTNO/{comment_text(program.name)[:66]}",
                 "$$ KEZURI CAM - APT CL DATA, PART COORDINATES, MM",
                 "$$ TOOL AXIS I,J,K: UNIT VECTOR FROM THE TIP TOWARD THE HOLDER",
                 f"$$ ESTIMATED CYCLE TIME: {format_duration(program.cycle_time())}",
                 "UNITS/MM", "MULTAX/ON"]
        for index, op in enumerate(program.operations):
            lines += self.operation(index, op)
        lines.append("FINI")
        return "\n".join(lines) + "\n"

    def operation(self, index: int, op: Operation) -> list:
        start, points, axes = self.part_moves(op)
        direction = getattr(op, "direction", "3-axis")
        lines = [f"$$ OPERATION {index + 1}: {comment_text(op.name)} - {direction.upper()} TOOL"[:72],
                 f"CUTTER/{_num(op.tool.diameter, 4)},{_num(op.tool.corner_radius, 4)}",
                 f"LOADTL/{op.tool.number}",
                 f"SPINDL/RPM,{int(round(op.spindle_rpm))},{'CLW' if op.spindle_cw else 'CCLW'}"]
        if op.coolant:
            lines.append("COOLNT/ON")
        lines.append("FROM/" + ",".join(_num(v, self.decimals) for v in start))
        lines += self._moves(op, points, axes)
        if op.coolant:
            lines.append("COOLNT/OFF")
        lines.append("SPINDL/OFF")
        return lines

    def _moves(self, op: Operation, points, axes) -> list:
        """One GOTO per move, RAPID before a rapid's, FEDRAT before a cutting move's whose feed
        text differs from the previous cutting move's; vectorised (:mod:`.words`)."""
        n = len(op)
        if not n:
            return []
        goto = np.full(n, "GOTO/", dtype=object)
        for index, (values, decimals) in enumerate([(points, self.decimals)] * 3 + [(axes, self.axis_decimals)] * 3):
            texts, ids = words.column(np.asarray(values, float)[:, index % 3], lambda value: _num(value, decimals),
                                      lambda many, decimals=decimals: _nums(many, decimals))
            goto = goto + ("," if index else "") + texts[ids]
        rapid = op.kind == RAPID
        texts, ids = words.column(op.feed, lambda value: _num(value, 1), lambda many: _nums(many, 1))
        last_cut = words.previous_where(~rapid)
        fedrat = ~rapid & ((last_cut < 0) | (ids != ids[np.maximum(last_cut, 0)]))
        before = words.prefixed("FEDRAT/MMPM,", texts, ids, fedrat)
        before[rapid] = "RAPID"
        both = np.empty(2 * n, dtype=object)
        both[0::2], both[1::2] = before, goto
        return [line for line in both.tolist() if line]

    def part_moves(self, op: Operation) -> tuple:
        """(start, tip points (n, 3), tool axes (n, 3)) in part coordinates."""
        if not np.all(np.isin(op.kind, (RAPID, FEED))):
            raise PostError(f"operation {op.name!r} has arc moves; the CL data writer writes GOTO points only")
        if isinstance(op, TurnMillOperation):
            return op.part_start(), op.part_points(), op.tool_axes()
        if op.rotary:
            raise PostError(f"operation {op.name!r} moves rotary axes {sorted(op.rotary)} without a tool direction; "
                            f"the CL data writer knows X-Z-C turn-mill and 3-axis operations")
        return op.start, op.xyz, np.tile([0.0, 0.0, 1.0], (len(op), 1))
