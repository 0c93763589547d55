"""NC for an Amada turret punch press (04P-style controller): a closed flat contour cut by nibbling.

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

The sheet-metal workflows write :func:`lines_to_text`: the lines as nibbled by
``toolpath/operations/sheetmetal/nibbling.py`` (collinear pieces merged, each hit once, gaps at the micro-joints), with
comment lines after the G92 block saying where the part's hits lie on the sheet, the clamps' dead
zones and the joints.  Comments are in parentheses, as Fanuc-built controls take them (control
out / control in); a control that does not would need them left out.

Program end: G50 by default, the Amada turret-punch program end (home return: the carriage goes back
to the position set by G92 so the sheet can be unloaded), which is what these punching programs end
with rather than the milling M30; ``end_code="M30"`` is offered for controllers set up otherwise.
Check against the machine's programming manual before the first run.
"""
from __future__ import annotations

import math

import numpy as np

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
TOOL_SIDES = ("left", "right", "outside", "inside")
END_CODES = ("G50", "M30")


def _num(value: float) -> str:
    text = f"{value:.2f}"
    return "0.00" if text == "-0.00" else text


def _positive(value, what: str, allow_zero: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise PostError(f"{what} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        raise PostError(f"{what} must be a finite number {'>= 0' if allow_zero else '> 0'}, got {value!r}")
    return v


def contour_points(contour) -> np.ndarray:
    """Clean (k, 2) points of a closed contour: repeated closing point and duplicates removed."""
    pts = np.asarray(contour, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise PostError(f"a contour must be a list of (x, y) points, got shape {pts.shape}")
    if not np.all(np.isfinite(pts)):
        raise PostError("contour has a non-finite coordinate (NaN or infinity)")
    keep = [0]
    for i in range(1, len(pts)):
        if np.hypot(*(pts[i] - pts[keep[-1]])) > 1e-9:
            keep.append(i)
    pts = pts[keep]
    if len(pts) > 1 and np.hypot(*(pts[0] - pts[-1])) <= 1e-9:
        pts = pts[:-1]
    if len(pts) < 3:
        raise PostError("a closed contour needs at least 3 distinct points")
    return pts


def segments(contour):
    """(start (k, 2), length (k,), angle in degrees (k,)) of every segment, the last closing the loop."""
    pts = contour_points(contour)
    delta = np.roll(pts, -1, axis=0) - pts
    length = np.hypot(delta[:, 0], delta[:, 1])
    angle = np.degrees(np.arctan2(delta[:, 1], delta[:, 0]))
    return pts, length, angle


def _offset_word(tool_diameter: float, tool_side: str, pts: np.ndarray) -> float:
    if tool_diameter == 0.0:
        return 0.0
    if tool_side not in TOOL_SIDES:
        raise PostError(f"tool side must be one of {TOOL_SIDES}, got {tool_side!r}")
    x, y = pts[:, 0], pts[:, 1]
    ccw = float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)) > 0
    if tool_side in ("outside", "inside"):
        # travelling CCW the outside is on the right
        left = (tool_side == "outside") != ccw
    else:
        left = tool_side == "left"
    return tool_diameter if left else -tool_diameter


def to_text(contour, *, station: int, pitch: float, thickness: float, tool_diameter: float = 0.0,
            tool_side: str = "outside", origin=(1000.0, 1040.0), end_code: str = "G50", notes=()) -> str:
    """The NC program that nibbles (or punches) round ``contour``, one G72 + G69/G79 per segment.

    ``contour``: closed 2-D polygon in sheet coordinates (mm).  With ``tool_diameter`` 0 it is taken
    as the tool-centre path already (compensated, P0); otherwise the controller offsets the tool by
    its radius to ``tool_side``: "left" / "right" of travel, or "outside" / "inside" of the contour.
    """
    pts, length, angle = segments(contour)
    q, t, ox, oy = _frame(station, pitch, thickness, end_code, origin, len(pts))
    tool_diameter = _positive(tool_diameter, "tool diameter", allow_zero=True)
    short = np.flatnonzero(length < MIN_SEGMENT)
    if len(short):
        raise PostError(f"segment {int(short[0]) + 1} is {length[short[0]]:.4f} mm long, "
                             f"shorter than the {MIN_SEGMENT} mm output resolution")
    _check_reach(pts, length)
    return _write(pts, length, angle, q=q, t=t, p=_offset_word(tool_diameter, tool_side, pts), station=station,
                  origin=(ox, oy), end_code=end_code, notes=notes)


def lines_to_text(lines, *, station: int, pitch: float, thickness: float, origin=(1000.0, 1040.0),
                  end_code: str = "G50", notes=()) -> str:
    """The NC program punching ``lines`` (k, 2, 2): each the first and the last hit of one G69/G79
    line, tool-centre coordinates (P0).  The lines need not join (a micro-joint leaves a gap, and a
    line stops one hit short of a corner the next line punches).  ``notes``: comment lines written
    after the G92 block (where the part sits on the sheet, the clamps, the joints)."""
    arr = np.asarray(lines, dtype=float)
    if arr.ndim != 3 or arr.shape[1:] != (2, 2) or len(arr) == 0:
        raise PostError(f"lines must be (first hit, last hit) pairs of (x, y), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise PostError("a line has a non-finite coordinate (NaN or infinity)")
    q, t, ox, oy = _frame(station, pitch, thickness, end_code, origin, len(arr))
    delta = arr[:, 1] - arr[:, 0]
    length = np.hypot(delta[:, 0], delta[:, 1])
    angle = np.degrees(np.arctan2(delta[:, 1], delta[:, 0]))
    _check_reach(arr[:, 0], length)
    short = np.flatnonzero(length < MIN_SEGMENT)
    if len(short):
        raise PostError(f"line {int(short[0]) + 1} is {length[short[0]]:.4f} mm long, shorter than the "
                        f"{MIN_SEGMENT} mm output resolution")
    return _write(arr[:, 0], length, angle, q=q, t=t, p=0.0, station=station, origin=(ox, oy),
                  end_code=end_code, notes=notes)


def _frame(station, pitch, thickness, end_code, origin, count):
    station_ok = isinstance(station, (int, np.integer)) and not isinstance(station, bool)
    if not station_ok or not 1 <= station <= 999:
        raise PostError(f"turret station must be an integer 1..999, got {station!r}")
    q = _positive(pitch, "nibbling pitch Q")
    t = _positive(thickness, "sheet thickness")
    if end_code not in END_CODES:
        raise PostError(f"end code must be one of {END_CODES}, got {end_code!r}")
    ox, oy = (float(v) for v in origin)
    if not (math.isfinite(ox) and math.isfinite(oy)):
        raise PostError("G92 origin must be finite")
    if count > 999:
        raise PostError(f"{count} lines do not fit sequence numbers N001..N999")
    reach = AMADA_04P_LIMITS.coordinate
    for word, value in (("G92 X", ox), ("G92 Y", oy)):
        if abs(value) > reach:
            raise PostError(f"{word}{_num(value)}: beyond the {reach:.2f} mm the control addresses")
    if t > THICK_SHEET and q < t:
        raise PostError(f"G79 punching line: pitch Q {q} must be at least the thickness {t} mm")
    return q, t, ox, oy


def _check_reach(pts, length):
    reach = AMADA_04P_LIMITS.coordinate
    far = np.flatnonzero((np.abs(pts) > reach).any(axis=1) | (length > reach))
    if len(far):
        (x, y), i = pts[far[0]], int(far[0])
        raise PostError(f"corner {i + 1} of the contour, G72 X{_num(x)} Y{_num(y)} (the line from it "
                        f"{length[i]:.2f} mm long), is beyond the {reach:.2f} mm the control addresses: "
                        f"the part does not fit the machine")


def _comment(text: str) -> str:
    """A comment block: upper case, no parentheses inside (they would end it)."""
    return "(" + str(text).upper().replace("(", "[").replace(")", "]") + ")"


def _write(starts, length, angle, *, q, t, p, station, origin, end_code, notes) -> str:
    thick = t > THICK_SHEET
    lines = [f"N000 G92 X{_num(origin[0])} Y{_num(origin[1])}"]
    lines += [_comment(note) for note in notes]
    for i, ((x, y), m, theta) in enumerate(zip(starts, length, angle), start=1):
        j = _num(theta)
        if j == "-180.00":
            j = "180.00"
        lines.append(f"N{i:03d} G72 X{_num(x)} Y{_num(y)}")
        if thick:
            lines.append(f"G79 I{_num(m)} J{j} P{_num(p)} Q{_num(q)} D{_num(t)} T{station:03d}")
        else:
            lines.append(f"G69 I{_num(m)} J{j} P{_num(p)} Q{_num(q)} T{station:03d}")
    lines.append(end_code)
    return "\n".join(lines) + "\n"


class AmadaPunchPost(Post):
    """The registry's entry for this file: the turret punch writes contours, not Programs."""

    name = "amada-04p"
    label = "Amada Turret Punch (04P)"
    label_ja = "アマダ タレットパンチ（04P）"
    description = "Amada 04P-style turret punch: G92 origin, G72 pattern point, G69 nibbling / G79 punching lines"
    description_ja = "アマダ04P系タレットパンチ：G92 原点、G72 基準点、G69 ニブリング／G79 パンチング"
    family = "punch"
    extension = ".nc"
    limits = AMADA_04P_LIMITS

    def __init__(self, **options):
        self.options = options

    def to_text(self, contour) -> str:
        return to_text(contour, **self.options)

    def lines_to_text(self, lines, notes=()) -> str:
        return lines_to_text(lines, notes=notes, **self.options)
