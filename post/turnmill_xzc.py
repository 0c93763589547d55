"""NC for a turn-mill centre moving X, Z and C (no Y), from :class:`TurnMillOperation` s.

Each operation is one turret tool, radial or axial.  Its block:

    (OPERATION 1: RADIAL ROUGHING)
    (TURRET: RADIAL TOOL, T1 6 MM BALL END MILL [RADIAL])
    G28 U0. W0.                      home before indexing the turret
    T0101                            select the station (tool and offset)
    G19                              milling plane of the tool: radial G19, axial G17
    M154                             C axis on: the main spindle becomes a positioning axis
    M133 P4000                       driven tool on, forward, at 4000 rpm
    G00 X89. Z2. C0.                 the safe corner outside the stock
    G93                              inverse-time feed for the X-Z-C moves
    G01 X81.6 Z-15. C12.5 F3.2 ...
    G98                              back to feed per minute
    M135                             driven tool off
    M155                             C axis off

Words are written in machine terms.  X is the tool tip's distance from the axis: a diameter by
default, as lathes program X; ``x_diameter=False`` writes the radius.  Z is the tool tip.  C is
the part angle brought to the tool, in degrees, unwrapped (continuous, never a jump of more than
180 degrees between blocks).

Feed: with C turning during a cut, a feed per minute would be applied to the linear axes alone
and the cutting speed at the part would be wrong.  So cutting moves are written in inverse time
(G93): F = 1 / minutes for the block, from the part-space length at the programmed feed, never
more than 9000 (a block takes at least :data:`toolpath.ir.kinematics.SHORTEST_BLOCK_MINUTES`; the
planner merges shorter moves first).
``inverse_time=False`` writes plain feeds per minute, for controls that handle rotary feed
themselves.

The default codes are Haas-style lathe codes.  G93 is an option on many lathe controls; where
it is missing, set ``inverse_time=False``.  Check the codes against the machine's programming
manual, and pass a :class:`TurnMillCodes` with the machine's own:

    C axis on / off        M154 / M155
    driven tool fwd / rev  M133 P<rpm> / M134 P<rpm>, stop M135
    tool select            T<station><offset>, both two digits
    planes                 radial G19 (Y-Z, side milling), axial G17 (X-Y, face milling)
    feed modes             inverse time G93, per minute G98
    home                   G28 U0. W0.

:class:`TurnMillLinuxCNCPost` is the checking variant.  LinuxCNC's rs274 interpreter can run its
output: X Z C words only, G0/G1, X as a radius, standard M3/M5/M6, and the machine-specific
switches written as comments.

Output is deterministic: the same program gives byte-identical text.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..toolpath.ir.kinematics import block_minutes
from ..toolpath.ir.program import MoveKind, Operation, Program, TurnMillOperation
from . import words
from .gcode import GcodePost, PostError, comment_text, fmt
from .linuxcnc import LINUXCNC_LIMITS
from .registry import ControllerLimits

RAPID, FEED = int(MoveKind.RAPID), int(MoveKind.FEED)     # the IR's move kinds

# Fanuc 0i-T / 16/18-T style lathe control, metric, IS-B; the turn-mill codes (M154, M133 ...) are the
# machine builder's, not Fanuc's, and the G93 range is that of the Fanuc inverse-time option.
TURNMILL_LIMITS = ControllerLimits(
    feed_per_minute=(0.001, 240000.0), inverse_time_feed=(0.001, 9999.999), spindle_rpm=(0, 99999),
    tool_number=(1, 99), length_offset=None, sequence_number=(1, 99999), program_number=(1, 9999),
    coordinate=99999.999, resolution=0.001, decimal_point=True, inverse_time_every_block=True, tool_changer=True,
    tool_change=("M135", "M155", "G28 U0. W0.", "T.... (station and offset)", "G19/G17", "M154", "M133 P.."),
    program_start=("%", "O....", "G21 G18 G40 G80"), program_end=("G28 U0. W0.", "M30", "%"),
    source=("FANUC Series 0i-TD/0i-TF and 16/18-TC Operator's Manual (lathe system): program configuration "
            "(O 1..9999, % frame, M30), tool function T + 2-digit offset, reference position return G28 U W, "
            "X in diameter (parameter DIA), IS-B 8 digits 0.001 mm with decimal point; G93 inverse time "
            "F 0.001..9999.999 as for the M series (B-62764EN 5); driven-tool and C-axis M codes per machine "
            "builder"))


@dataclass(frozen=True)
class TurnMillCodes:
    """The machine-specific words; ``{station}`` and ``{rpm}`` are filled in.  An empty string
    writes nothing."""

    preamble: str = "G21 G18 G40 G80"
    home: str = "G28 U0. W0."
    tool_select: str = "T{station:02d}{station:02d}"
    radial_plane: str = "G19"
    axial_plane: str = "G17"
    c_axis_on: str = "M154"
    c_axis_off: str = "M155"
    tool_on_cw: str = "M133 P{rpm}"
    tool_on_ccw: str = "M134 P{rpm}"
    tool_off: str = "M135"
    inverse_time: str = "G93"
    per_minute: str = "G98"
    program_end: str = "M30"


LINUXCNC_CODES = TurnMillCodes(
    preamble="G21 G17 G40 G49 G80 G90 G94", home="G49", tool_select="T{station} M06 G43 H{station}",
    c_axis_on="(C AXIS ON: SPINDLE IN POSITIONING MODE)", c_axis_off="(C AXIS OFF)",
    tool_on_cw="S{rpm} M03", tool_on_ccw="S{rpm} M04", tool_off="M05", inverse_time="G93", per_minute="G94",
    program_end="M30")


class TurnMillXZCPost(GcodePost):
    """Program of :class:`TurnMillOperation` s -> X-Z-C NC text."""

    name = "turnmill-xzc"
    choice = "xzc"
    label = "Turn-Mill X-Z-C"
    label_ja = "複合加工機 X-Z-C"
    description = "X (diameter), Z, C words with the machine's C-axis and turret codes"
    description_ja = "X（直径値）、Z、C ワードと、機械のC軸・タレット用コード"
    family = "xzc"
    order = 10
    extension = ".nc"
    decimals = 3
    program_number = "O0001"
    limits = TURNMILL_LIMITS

    def __init__(self, codes: TurnMillCodes | None = None, x_diameter: bool = True, inverse_time: bool = True):
        super().__init__(None)
        self.codes = TurnMillCodes() if codes is None else codes
        self.x_diameter = x_diameter
        self.inverse_time = inverse_time

    def check(self, program: Program):
        for op in program.operations:
            if not isinstance(op, TurnMillOperation):
                raise PostError(f"operation {op.name!r} is not an X-Z-C turn-mill operation (it has no radial/axial "
                                f"tool direction): plan it with toolpath.operations.turnmill.turnmill")
            if not np.all(np.isin(op.kind, (RAPID, FEED))):
                raise PostError(f"operation {op.name!r} has arc moves; the {self.name} post writes straight moves only")

    def _lines(self, *codes: str) -> list:
        return [code for code in codes if code]

    def header(self, program: Program) -> list:
        lines = super().header(program)
        lines.insert(3, f"(X: TOOL TIP {'DIAMETER' if self.x_diameter else 'RADIUS'}, Z: TOOL TIP, "
                        f"C: PART ANGLE AT THE TOOL IN DEGREES)")
        return lines

    def tool_change(self, op: Operation, first: bool, index: bool = True) -> list:
        """Home, index the turret (only when the station changes: ``index``), plane, C axis on,
        driven tool on.  The previous operation has already stopped the driven tool."""
        c = self.codes
        plane = c.radial_plane if op.direction == "radial" else c.axial_plane
        spindle = (c.tool_on_cw if op.spindle_cw else c.tool_on_ccw).format(rpm=int(round(op.spindle_rpm)))
        select = (c.home, c.tool_select.format(station=op.tool.number)) if index else ()
        return self._lines(f"(TURRET: {op.direction.upper()} TOOL, {comment_text(op.tool.describe())})", *select,
                           plane, c.c_axis_on, spindle)

    def operation_end(self, op: Operation) -> list:
        return self._lines(self.codes.tool_off, self.codes.c_axis_off)

    def ending(self, program: Program) -> list:
        return self._lines(self.codes.home, self.codes.program_end)

    def preamble(self, program: Program) -> list:
        return self._lines(self.codes.preamble)

    def to_text(self, program: Program) -> str:
        lines = self.opening(program)
        station = None
        for index, op in enumerate(program.operations):
            lines.append(f"(OPERATION {index + 1}: {comment_text(op.name)})")
            lines += self.tool_change(op, index == 0, index=op.tool.number != station)
            station = op.tool.number
            lines += self.operation_moves(op)
            lines += self.operation_end(op)
        lines += self.ending(program)
        body = "\n".join(lines) + "\n"
        return f"%\n{body}%\n" if self.percent_wrapped else body

    def operation_moves(self, op: Operation) -> list:
        """The rapid to the operation's start, then its moves: modal X/Z/C, G00/G01 when the mode
        changes, F on every cutting block in inverse time (modal otherwise).  Moves that round to no
        motion are dropped."""
        scale = 2.0 if self.x_diameter else 1.0
        c_values = op.rotary["c"]
        lines = [f"G00 X{self.n(op.start[0] * scale)} Z{self.n(op.start[2])} C{self.n(c_values[0])}"]
        if self.inverse_time:
            lines.append(self.codes.inverse_time)
        lengths = op.move_lengths()
        cutting = op.kind == FEED
        inverse_time = np.where(cutting, 1.0 / block_minutes(lengths, np.where(cutting, op.feed, 1.0)),
                                np.nan)
        scaled = op.replace(xyz=op.xyz * [scale, 1.0, 1.0], start=op.start * [scale, 1.0, 1.0])
        self.check_limits(scaled, inverse_time if self.inverse_time else None)
        lines += self._blocks(op, scale, c_values, inverse_time)
        if self.inverse_time:
            lines.append(self.codes.per_minute)
        return lines

    def _blocks(self, op: Operation, scale: float, c_values, inverse_time) -> list:
        """The moves' blocks, vectorised (:mod:`.words`): a word where its text differs from the
        previous move's (the start for the first); a move with none is dropped; G00/G01 where the
        mode differs from the last written block's (G00 before the first); on cutting blocks F in
        inverse time every block, or per minute when its text differs from the last cutting block's."""
        n = len(op)
        if not n:
            return []
        kind = op.kind.astype(np.intp)
        columns, write = [], []
        for letter, start, values in (("X", op.start[0] * scale, op.xyz[:, 0] * scale), ("Z", op.start[2], op.xyz[:, 2]),
                                      ("C", c_values[0], c_values)):
            texts, ids = words.column(np.concatenate([[start], values]), self.n, self.many)
            write.append(ids[1:] != ids[:-1])
            columns.append((letter, texts, ids[1:]))
        emitted = write[0] | write[1] | write[2]
        previous = words.previous_where(emitted)
        rapid = kind == RAPID
        mode_before = np.where(previous < 0, True, rapid[np.maximum(previous, 0)])   # G00 before the first block
        code_written = emitted & (rapid != mode_before)
        out = [np.array(["G01", "G00", ""], dtype=object)[np.where(code_written, rapid.astype(np.intp), 2)]]
        out += [words.prefixed(letter, texts, ids, w) for (letter, texts, ids), w in zip(columns, write)]
        cutting = emitted & (kind == FEED)
        if self.inverse_time:
            texts, ids = words.column(np.where(cutting, inverse_time, 0.0), lambda value: fmt(value, 3),
                                      lambda many: words.trimmed(many, 3))
            out.append(words.prefixed("F", texts, ids, cutting))
        else:
            texts, ids = words.column(op.feed, lambda value: fmt(value, 1), lambda many: words.trimmed(many, 1))
            last_cut = words.previous_where(cutting)
            out.append(words.prefixed("F", texts, ids, cutting & ((last_cut < 0) | (ids != ids[np.maximum(last_cut, 0)]))))
        return words.join_words([column[emitted] for column in out])

class TurnMillLinuxCNCPost(TurnMillXZCPost):
    """The checking variant: LinuxCNC words only, X as a radius, machine switches as comments."""

    name = "turnmill-linuxcnc"
    choice = "linuxcnc"
    label = "LinuxCNC X-Z-C"
    label_ja = "LinuxCNC X-Z-C"
    description = "X (radius), Z, C words only"
    description_ja = "X（半径値）、Z、C ワードのみ"
    order = 20
    extension = ".ngc"
    decimals = 4
    program_number = None
    limits = LINUXCNC_LIMITS

    def __init__(self, inverse_time: bool = True):
        super().__init__(LINUXCNC_CODES, x_diameter=False, inverse_time=inverse_time)
