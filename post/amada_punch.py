"""NC for an Amada turret punch press (04P-style controller): lines of hits nibbling a flat part out.

Program layout (after the seed paper's Table 2)::

    N000 G92 X1000.00 Y1040.00                      sheet coordinate system (origin position)
    N001 G72 X0.93 Y147.66                          pattern reference point = segment start
    G69 I20.29 J-5.32 P0.00 Q2.00 T302              nibbling line from that point
    ...
    G50                                             end of program: home return, work released

G69 (nibbling line): I = length (mm), J = angle in degrees from +X, + = counter-clockwise,
P = tool diameter with the offset side (+ = tool to the left of travel, - = right, 0 = the contour
is already the tool-centre path), Q = nibbling pitch, T = turret station (3 digits).  When the sheet is
thicker than 3.2 mm the punching line G79 is used instead, with D = thickness, and the pitch must be
at least the thickness.

Number format: two decimals everywhere, address and value written together (the spaces and the
suppressed leading zero in the paper, "X .93", are N88-BASIC PRINT artefacts, not controller syntax),
sequence numbers N000..N999.  The angle comes from atan2, so all four quadrants and vertical segments
are right (the seed's ATN(dy/dx) loses the quadrant and divides by zero on vertical segments).

The post writes a :class:`~..toolpath.ir.program.PunchProgram`: each line of its operations (made by
``toolpath/operations/sheetmetal/nibbling.py``: collinear pieces merged, each hit once, gaps at the
micro-joints) as one G72 + G69/G79 pair, P from the operation's compensation (0: the lines are the
punch centre's path), and the program's notes as comment lines after the G92 block (where the part's
hits lie on the sheet, the clamps' dead zones and the joints).  Comments are in parentheses, as
Fanuc-built controls take them (control out / control in); a control that does not would need them
left out.

Program end: G50 by default, the Amada turret-punch program end (home return: the carriage goes back
to the position set by G92 so the sheet can be unloaded), which is what these punching programs end
with rather than the milling M30; ``end_code="M30"`` is offered for controllers set up otherwise.
Check against the machine's programming manual before the first run.
"""
from __future__ import annotations

import numpy as np

from ..toolpath.ir.program import PunchProgram
from .gcode import PostError
from .registry import ControllerLimits, Post

AMADA_04P_LIMITS = ControllerLimits(
    tool_number=(1, 999), sequence_number=(0, 999), coordinate=9999.99, resolution=0.01, decimal_point=True,
    tool_changer=False, tool_change=("T... on the G69/G79 block (turret station, 3 digits)",),
    program_start=("N000 G92 X.. Y..",), program_end=("G50",),
    source=("Amada 04P turret punch programming conventions as published with the seed paper's Table 2: "
            "N000..N999, G92 origin, G72 pattern point, G69 nibbling / G79 punching line, 2 decimals, "
            "T 3 digits, G50 program end"))

THICK_SHEET = 3.2          # mm: above this, G79 punching line instead of G69 nibbling
MIN_SEGMENT = 0.01         # mm: the output resolution; shorter segments cannot be written
END_CODES = ("G50", "M30")


def _num(value: float) -> str:
    text = f"{value:.2f}"
    return "0.00" if text == "-0.00" else text


def to_text(program: PunchProgram, end_code: str = "G50") -> str:
    """The NC program punching every line of ``program``'s operations, one G72 + G69/G79 per line,
    the lines numbered N001.. in order; ``program.notes`` as comment lines after the G92 block."""
    if not isinstance(program, PunchProgram):
        raise PostError(f"the turret punch writes a PunchProgram (lines of hits), got {type(program).__name__}")
    program.validate()
    if end_code not in END_CODES:
        raise PostError(f"end code must be one of {END_CODES}, got {end_code!r}")
    count = program.line_count()
    if count > 999:
        raise PostError(f"{count} lines do not fit sequence numbers N001..N999")
    reach = AMADA_04P_LIMITS.coordinate
    for word, value in zip(("G92 X", "G92 Y"), program.origin):
        if abs(value) > reach:
            raise PostError(f"{word}{_num(value)}: beyond the {reach:.2f} mm the control addresses")
    text = [f"N000 G92 X{_num(program.origin[0])} Y{_num(program.origin[1])}"]
    text += [_comment(note) for note in program.notes]
    number = 0
    for op in program.operations:
        if op.thickness > THICK_SHEET and op.pitch < op.thickness:
            raise PostError(f"G79 punching line: pitch Q {op.pitch:g} must be at least the thickness {op.thickness:g} mm")
        starts, length, angle = op.lines[:, 0], op.lengths(), op.angles()
        _check_reach(starts, length, number)
        short = np.flatnonzero(length < MIN_SEGMENT)
        if len(short):
            raise PostError(f"line {number + int(short[0]) + 1} is {length[short[0]]:.4f} mm long, shorter than the "
                            f"{MIN_SEGMENT} mm output resolution")
        p = {"none": 0.0, "left": op.punch_diameter, "right": -op.punch_diameter}[op.compensation]
        text += _lines(starts, length, angle, number, op, p)
        number += len(op)
    text.append(end_code)
    return "\n".join(text) + "\n"


def _check_reach(pts, length, number: int = 0):
    reach = AMADA_04P_LIMITS.coordinate
    far = np.flatnonzero((np.abs(pts) > reach).any(axis=1) | (length > reach))
    if len(far):
        (x, y), i = pts[far[0]], int(far[0])
        raise PostError(f"corner {number + i + 1} of the contour, G72 X{_num(x)} Y{_num(y)} (the line from it "
                        f"{length[i]:.2f} mm long), is beyond the {reach:.2f} mm the control addresses: "
                        f"the part does not fit the machine")


def _comment(text: str) -> str:
    """A comment block: upper case, no parentheses inside (they would end it)."""
    return "(" + str(text).upper().replace("(", "[").replace(")", "]") + ")"


def _lines(starts, length, angle, number: int, op, p: float) -> list:
    """The G72 + G69 (G79 on a sheet thicker than 3.2 mm) blocks of ``op``'s lines, numbered from ``number`` + 1."""
    thick = op.thickness > THICK_SHEET
    q, t = _num(op.pitch), _num(op.thickness)
    out = []
    for i, ((x, y), m, theta) in enumerate(zip(starts, length, angle), start=number + 1):
        j = _num(theta)
        if j == "-180.00":
            j = "180.00"
        out.append(f"N{i:03d} G72 X{_num(x)} Y{_num(y)}")
        if thick:
            out.append(f"G79 I{_num(m)} J{j} P{_num(p)} Q{q} D{t} T{op.station:03d}")
        else:
            out.append(f"G69 I{_num(m)} J{j} P{_num(p)} Q{q} T{op.station:03d}")
    return out


class AmadaPunchPost(Post):
    """The registry's entry for this file: a :class:`PunchProgram` -> Amada 04P NC text."""

    name = "amada-04p"
    label = "Amada Turret Punch (04P)"
    label_ja = "アマダ タレットパンチ（04P）"
    description = "Amada 04P-style turret punch: G92 origin, G72 pattern point, G69 nibbling / G79 punching lines"
    description_ja = "アマダ04P系タレットパンチ：G92 原点、G72 基準点、G69 ニブリング／G79 パンチング"
    family = "punch"
    extension = ".nc"
    limits = AMADA_04P_LIMITS

    def __init__(self, end_code: str = "G50"):
        if end_code not in END_CODES:
            raise PostError(f"end code must be one of {END_CODES}, got {end_code!r}")
        self.end_code = end_code

    def to_text(self, program: PunchProgram) -> str:
        return to_text(program, self.end_code)
