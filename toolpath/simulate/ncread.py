"""Read the G-code our posts write (LinuxCNC / Fanuc dialect) back into the IR, for simulation.

Strict like a control: a line it cannot follow stops the reading with the line number, the
line and the reason, never a guess.

What it follows: G0 G1 G2 G3 with X Y Z C I J (R is refused), the drilling cycles G81, G82 and
G83 with G98/G99 and G80 as LinuxCNC runs them (:data:`CYCLES`), G90/G91, G20/G21, G17,
N numbers, ``%`` and ``O`` lines (a ``%`` after the program's first block ends it, as on
LinuxCNC and a Fanuc tape), comments in parentheses (a ``;`` inside is comment text) or after
``;``, spaces anywhere in a block (``X 1 0 . 5`` is ``X10.5``, as controls read it), lines
ended by LF, CR LF or CR (nothing else: a form feed, or U+0085 in a UTF-8 comment read as
latin-1, is no line break).  Arcs are checked as LinuxCNC checks them (its interpreter's
tolerances, interp_internal.hh): the end may lie off the start's circle by at most
0.02*sqrt(2) mm (0.002*sqrt(2) inch under G20) unless that is also within 0.1 % of the radius,
and never by more than 100 times that; a radius under 0.00127 mm (I0 J0) is refused.

The spindle is followed as LinuxCNC's interpreter does (its canonical output): ``S`` sets the
speed, ``M3``/``M4`` start it, ``M5`` stops it, and so does a tool change ``M6`` and the program
end; in one block the speed is set first, then the tool changed, then the spindle started or
stopped, then the tool moved.  Every move is read with the spindle state it runs at; the result
is split into :attr:`NCRead.runs` where a cutting move's spindle differs from the one before,
so each run is one :class:`Operation` with its own ``spindle_rpm`` (0: stopped), and the
simulation's "cuts with the spindle at 0 rpm" names the move that does.

What it deliberately ignores, because it does not change where the tool goes (feeds, coolant,
pauses, tool length offsets, work offsets, path blending, comments ...), is listed in the
result's ``ignored`` (:class:`NCRead`), so a report can say so.  Everything else (G92
offsets, G68 rotation, G38 probing, the other canned cycles (G73, G74, G76, G84..G89), G41/G42 cutter compensation,
other planes, macros, block delete ``/`` (whether the line runs depends on the control's switch),
two codes of one modal group in a block (G90 G91), unknown M codes, words it does not know, malformed numbers such as
``XNAN``, ``X-``, ``X1.2.3``, ``X2E1``) is refused.
"""
from __future__ import annotations

import math
import re

import numpy as np

from ..ir.errors import MAX_REACH_MM, InputError
from ..ir.program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, Tool
from ..ir.tools import SHAPES
# LinuxCNC's arc tolerances (interp_internal.hh) are ncplain's, which checks arcs too
from .ncplain import (ARC_RELATIVE_TOLERANCE, ARC_TOLERANCE_INCH, ARC_TOLERANCE_MM, MIN_ARC_RADIUS_INCH, PLAIN,
                      ROW_OTHER, LineNumbers, MoveStore, plain_moves)

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)")
_VALUE = re.compile(r"\s*([-+]?[0-9.]*)")
_END_CODES = ("M2", "M30")


# Codes that do not move the tool, read and set aside (listed in NCRead.ignored).
IGNORED_CODES = {
    "G4": "dwell", "G17": "XY plane (the only one read)", "G40": "cutter compensation off",
    "G43": "tool length offset (coordinates are read as the tool tip)", "G49": "tool length offset off",
    "G54": "work offset (coordinates are read in the program's frame)", "G55": "work offset",
    "G56": "work offset", "G57": "work offset", "G58": "work offset", "G59": "work offset",
    "G61": "exact path mode", "G61.1": "exact stop mode", "G64": "path blending",
    "G91.1": "incremental arc centres (the default)", "G93": "inverse-time feed", "G94": "feed per minute",
    "G97": "spindle rpm mode",
    "M0": "program pause", "M1": "optional pause",
    "M6": "tool change (every move is simulated with the one tool given)", "M7": "mist coolant on",
    "M8": "coolant on", "M9": "coolant off",
}
# Codes the reader follows.
MOTION = {"G0": 0, "G1": 1, "G2": 2, "G3": 3}
MODES = {"G20", "G21", "G90", "G91", "G28", "G53"} | set(MOTION)
# The spindle codes followed (LinuxCNC's modal group 7; M6 stops the spindle before the change,
# rs274 writes STOP_SPINDLE_TURNING before CHANGE_TOOL): the direction each sets, None = stopped.
SPINDLE = {"M3": True, "M4": False, "M5": None}
# Refused with a reason a user can act on.
REFUSED = {
    "G92": "sets a coordinate offset, which the reader does not follow",
    "G92.1": "resets coordinate offsets, which the reader does not follow",
    "G92.2": "suspends coordinate offsets, which the reader does not follow",
    "G92.3": "restores coordinate offsets, which the reader does not follow",
    "G52": "sets a local coordinate offset, which the reader does not follow",
    "G68": "rotates the coordinate system, which the reader does not follow",
    "G69": "cancels a coordinate rotation, which the reader does not follow",
    "G41": "cutter radius compensation is not simulated",
    "G42": "cutter radius compensation is not simulated",
    "G41.1": "cutter radius compensation is not simulated",
    "G42.1": "cutter radius compensation is not simulated",
    "G18": "selects another plane; only the XY plane (G17) is read",
    "G19": "selects another plane; only the XY plane (G17) is read",
    "G90.1": "sets absolute arc centres, which the reader does not follow (use incremental I, J)",
    "G66": "macro calls are not simulated", "G66.1": "macro calls are not simulated",
    "G65": "macro calls are not simulated", "G67": "macro calls are not simulated",
    "G33": "threading is not simulated", "G33.1": "tapping is not simulated",
    "G5": "splines are not simulated", "G5.1": "splines are not simulated", "G5.2": "NURBS are not simulated",
    "G10": "changes tool or offset tables, which the reader does not follow",
    "G28.1": "sets the reference point, which the reader does not know",
    "G30": "returns to a reference point the reader does not know",
    "G95": "feed per revolution is not simulated", "G96": "constant surface speed is not simulated",
    "M98": "subprogram calls are not simulated", "M99": "subprogram returns are not simulated",
}
REFUSED.update({f"G38.{k}": "probing moves are not simulated" for k in range(2, 6)})
REFUSED.update({f"G{k}": "canned cycles other than G81, G82 and G83 are not simulated"
                for k in (73, 74, 76, 84, 85, 86, 87, 88, 89)})
# The drilling cycles followed, as LinuxCNC runs them (its G-code reference, G81-G83, G98/G99):
# rapid to the hole's XY (after rising to R if below it), rapid to R, feed to Z (G83: in pecks of
# Q, each followed by a rapid out to R and a rapid back down to PECK_CLEARANCE above the depth
# reached), then rapid out to R (G99) or to the Z the cycle started from (G98, when above R).
CYCLES = ("G81", "G82", "G83")
RETRACTS = ("G98", "G99")
PECK_CLEARANCE_MM = 0.254      # LinuxCNC's G83 rapid back down: 0.010 inch above the last depth
AXES = ("X", "Y", "Z", "C")
# Words that go with a code it reads or ignores; any other address is refused.
WORD_USE = {"F": "feed", "T": "tool number", "H": "tool length offset number"}


# The longest line read (characters): 50 MB of NULs as one line took 10 s and 830 MB to refuse.
# A line of a megabyte of words is still read, and refused for what is wrong in it (test_hostile).
MAX_LINE_CHARS = 4_000_000


class NCReadError(InputError):
    """A line of the NC file the reader cannot follow; the message names it."""


class NCRead(tuple):
    """What :func:`read_nc` returns: ``(operation, lines)`` as before (it unpacks as a pair),
    plus ``ignored``: what the reader read and set aside, one entry per code or word, as
    {"code", "meaning", "count", "first_line"}, in order of first appearance; ``runs``: the
    moves split where the spindle of a cutting move changes, as [(Operation, lines)], each
    with the spindle its cutting moves run at (what the simulation checks).  The whole
    ``operation``'s ``spindle_rpm`` is the lowest any cutting move runs at."""

    def __new__(cls, operation, lines, ignored, runs=None):
        self = super().__new__(cls, (operation, lines))
        self.ignored = ignored
        self.runs = runs if runs is not None else [(operation, lines)]
        return self

    @property
    def operation(self):
        return self[0]

    @property
    def lines(self):
        return self[1]


def _code(letter: str, value: str) -> str:
    """G01 -> G1, G38.2 -> G38.2, M08 -> M8 (a signed number is no code: G-1 stays G-1)."""
    number = float(value)
    if value[0] in "+-":
        return f"{letter}{value}"
    return f"{letter}{int(number)}" if number.is_integer() else f"{letter}{f'{number:.4f}'.rstrip('0')}"


def _shown(raw: str) -> str:
    """The line as a message quotes it: at most 120 characters (a 1 MB block stayed one line of 1 MB)."""
    text = raw.strip()
    return repr(text if len(text) <= 120 else text[:117] + "...")


def _words(line: str, number: int, raw: str) -> list:
    """[(letter, text of the number)] of one block; malformed words raise NCReadError."""
    words, i = [], 0
    while i < len(line):
        if line[i].isspace():
            i += 1
            continue
        letter = line[i]
        if not ("A" <= letter <= "Z"):
            raise NCReadError(f"line {number}: {line[i:i + 12]!r} is not a word (a letter and a number) in "
                              f"{_shown(raw)}")
        match = _VALUE.match(line, i + 1)
        text, end = match.group(1), match.end()
        if not text:
            after = line[end:end + 8].strip()
            if after:
                raise NCReadError(f"line {number}: {letter} is not followed by a number (found {after!r}) in "
                                  f"{_shown(raw)}")
            raise NCReadError(f"line {number}: {letter} is not followed by a number in {_shown(raw)}")
        if not NUMBER.fullmatch(text):
            raise NCReadError(f"line {number}: {letter}{text} is not a number G-code can have in {_shown(raw)}")
        if end < len(line) and line[end] == "E" and end + 1 < len(line) and line[end + 1] in "0123456789+-":
            raise NCReadError(f"line {number}: {letter}{text}E...: exponents are not allowed in G-code numbers, "
                              f"in {_shown(raw)}")
        if not math.isfinite(float(text)):
            raise NCReadError(f"line {number}: {letter}{text} is out of range in {_shown(raw)}")
        words.append((letter, text))
        i = end
    return words


def _strip_comments(raw: str, number: int, comments: list) -> str:
    """The line without its comments, upper case: a comment runs from ``(`` to the next ``)``
    (a ``;`` inside it is comment text), or from a ``;`` outside parentheses to the end of the
    line.  Spaces and tabs are taken out, as LinuxCNC and Fanuc controls do (``X 1 0 . 5`` is
    ``X10.5``)."""
    kept, i, commented = [], 0, False
    while i < len(raw):
        char = raw[i]
        if char == "(":
            close = raw.find(")", i + 1)
            if close < 0 or "(" in raw[i + 1:close]:
                raise NCReadError(f"line {number}: unbalanced or nested parenthesis in {_shown(raw)}")
            commented, i = True, close + 1
            continue
        if char == ")":
            raise NCReadError(f"line {number}: unbalanced or nested parenthesis in {_shown(raw)}")
        if char == ";":
            commented = True
            break
        if char not in " \t":
            kept.append(char)
        i += 1
    if commented:
        comments.append(number)
    return "".join(kept).strip().upper()


def _check_arc(number: int, raw: str, start, end, centre, inch: bool) -> None:
    """LinuxCNC's rule for centre-format arcs (see the module notes), in mm."""
    r1 = math.hypot(start[0] - centre[0], start[1] - centre[1])
    r2 = math.hypot(end[0] - centre[0], end[1] - centre[1])
    scale = 25.4 if inch else 1.0
    if r1 < MIN_ARC_RADIUS_INCH * 25.4 or r2 < MIN_ARC_RADIUS_INCH * 25.4:
        raise NCReadError(f"line {number}: the arc has no radius (its centre is its start or end point) in "
                          f"{_shown(raw)}")
    tolerance = (ARC_TOLERANCE_INCH if inch else ARC_TOLERANCE_MM) * scale
    error = abs(r1 - r2)
    if error > 100 * tolerance or (error > tolerance and error / max(r1, r2) > ARC_RELATIVE_TOLERANCE):
        raise NCReadError(f"line {number}: the arc's end lies {error:.4f} mm off its circle (radius {r1:.4f} mm "
                          f"at the start, {r2:.4f} mm at the end; LinuxCNC allows {tolerance:.4f} mm) in "
                          f"{_shown(raw)}")


class _Reader:
    """The reader's state between lines, and one line at a time (:meth:`block`); the plain
    lines of a run are followed in bulk by :func:`ncplain.plain_moves` from the same state."""

    def __init__(self):
        self.position = {"X": 0.0, "Y": 0.0, "Z": 0.0, "C": 0.0}
        self.known = set()
        self.mode, self.absolute, self.scale = None, True, 1.0
        self.retract, self.cycle_start_z, self.cycle = "G98", None, {}   # G98/G99; the Z a cycle started from; its R, Z, Q
        self.speed, self.direction = 0.0, None      # the S in effect, the direction (None: stopped)
        self.feed_rate, self.feed_line = None, None     # the F in effect and the line that set it
        self.saw_c = False
        self.started = False
        self.ignored: dict = {}
        self.comments: list = []
        self.moves = MoveStore()

    def ignore(self, code, meaning, number, count=1):
        entry = self.ignored.setdefault(code, {"code": code, "meaning": meaning, "count": 0, "first_line": number})
        entry["count"] += count

    def move(self, kind, z, centre, number):
        self.moves.append(kind, (self.position["X"], self.position["Y"], z), centre, self.position["C"], number,
                          self.speed if self.direction is not None else 0.0, self.direction is not False)

    def block(self, number: int, raw: str) -> bool:
        """Follow line ``number``; True when it ends the program."""
        if len(raw) > MAX_LINE_CHARS:     # a binary file as one line: its comments were stripped a character at a time
            raise NCReadError(f"line {number} is {len(raw)} characters long, more than the {MAX_LINE_CHARS} this reader "
                              "takes (an NC block is a few dozen): is it an NC program?")
        line = _strip_comments(raw, number, self.comments)
        if line.startswith("%"):
            if self.started:     # the closing %: the end of the program (LinuxCNC, and the end of the tape on a Fanuc)
                return True
            return False
        if not line:
            return False
        self.started = True
        if re.fullmatch(r"O\d+", line):
            return False
        if line.startswith("/"):
            raise NCReadError(f"line {number}: a block delete '/' is not followed (whether the control skips the "
                              f"line depends on its Block Delete switch): {_shown(raw)}")
        words = _words(line, number, raw)
        if words and words[0][0] == "N":
            if not words[0][1].isdigit():
                raise NCReadError(f"line {number}: N{words[0][1]} is not a sequence number in {_shown(raw)}")
            words = words[1:]
        values, codes = {}, []
        for letter, value in words:
            if letter in "GM":
                codes.append(_code(letter, value))
            elif letter in values:
                raise NCReadError(f"line {number}: {letter} is given twice in {_shown(raw)}")
            else:
                values[letter] = float(value)
        motions = [c for c in codes if c in MOTION or c in CYCLES or c == "G80"]
        if len(motions) > 1:
            raise NCReadError(f"line {number}: {' and '.join(motions)} are both motions in {_shown(raw)}")
        spindle = [c for c in codes if c in SPINDLE]
        for group in (("G90", "G91"), ("G20", "G21"), tuple(spindle[:2])):
            if len(group) == 2 and all(code in codes for code in group):
                raise NCReadError(f"line {number}: {group[0]} and {group[1]} are in one modal group, so one block "
                                  f"cannot have both: {_shown(raw)}")
        block_scale = 25.4 if "G20" in codes else 1.0 if "G21" in codes else self.scale
        for letter in [a for a in AXES if a in values] + [w for w in "IJ" if w in values]:
            if abs(values[letter]) * (block_scale if letter != "C" else 1.0) > MAX_REACH_MM:
                raise NCReadError(f"line {number}: {letter}{values[letter]:.6g} lies beyond the {MAX_REACH_MM:g} mm "
                                  f"any machine reaches: {_shown(raw)}")
        if "F" in values:
            if values["F"] < 0:
                raise NCReadError(f"line {number}: F{values['F']:g} is a negative feed, which no control takes: "
                                  f"{_shown(raw)}")
            self.feed_rate, self.feed_line = values["F"], number
        if "P" in values and "G4" in codes and values["P"] < 0:
            raise NCReadError(f"line {number}: G4 P{values['P']:g} is a negative dwell: {_shown(raw)}")
        # LinuxCNC's order of execution in a block: S, then the tool change M6, then M3/M4/M5
        if "S" in values:
            if values["S"] < 0:
                raise NCReadError(f"line {number}: S{values['S']:g} is not a spindle speed: {_shown(raw)}")
            self.speed = values["S"]
        if "M6" in codes:
            self.direction = None
        if spindle:
            self.direction = SPINDLE[spindle[0]]
        home = lift = False
        for code in codes:
            if code in REFUSED:
                raise NCReadError(f"line {number}: {code} {REFUSED[code]}: {_shown(raw)}")
            if code in MOTION:
                self.mode = MOTION[code]
            elif code in CYCLES:
                if self.mode not in CYCLES:
                    self.cycle_start_z = self.position["Z"]
                self.mode = code
            elif code == "G80":
                self.mode = None
            elif code in RETRACTS:
                self.retract = code
            elif code == "G90":
                self.absolute = True
            elif code == "G91":
                self.absolute = False
            elif code == "G20":
                self.scale = 25.4
            elif code == "G21":
                self.scale = 1.0
            elif code == "G28":
                home = True
            elif code == "G53":
                lift = True
            elif code in _END_CODES or code in SPINDLE:
                pass
            elif code in IGNORED_CODES:
                self.ignore(code, IGNORED_CODES[code], number)
            else:
                raise NCReadError(f"line {number}: {code} is not a code this reader knows: {_shown(raw)}")
        for letter in values:
            if letter in AXES or letter in "IJS":
                continue
            if letter in WORD_USE:
                self.ignore(letter, WORD_USE[letter], number)
            elif letter == "P" and any(c in ("G4", "G64") for c in codes):
                continue
            elif letter in "RQP" and self.mode in CYCLES:
                continue
            elif letter == "R" and self.mode in (2, 3) and not home:
                raise NCReadError(f"line {number}: R-format arcs are not supported; use I and J: {_shown(raw)}")
            else:
                raise NCReadError(f"line {number}: the {letter} word is not supported here: {_shown(raw)}")
        ends = [c for c in codes if c in _END_CODES]
        axes = [a for a in AXES if a in values]
        if home:
            # G28 goes home through the point its words give: only "through where it is" can be
            # followed (G91 G28 Z0), and home itself is not self.known: the tool stays put.
            if self.absolute or any(values[a] != 0 for a in axes):
                raise NCReadError(f"line {number}: G28 is followed only as G91 G28 with zero words (home is not "
                                  f"known to the reader): {_shown(raw)}")
            self.ignore("G28", "return to the reference point (not simulated: the tool is taken to stay put)", number)
            if ends:
                return True
            return False
        if lift:
            # G53 moves in machine coordinates, which the reader does not know; a Z-only move is the
            # posts' lift to the top of travel (before XY after a start or a tool load), followed as
            # the tool staying put: any XY move after it is still checked at the height it had.
            if [a for a in axes if a != "Z"] or "I" in values or "J" in values:
                raise NCReadError(f"line {number}: G53 moves in machine coordinates, which the reader does not "
                                  f"know (only a Z lift is followed): {_shown(raw)}")
            self.ignore("G53", "lift in machine coordinates (not simulated: the tool is taken to stay put)", number)
            if ends:
                return True
            return False
        if self.mode in CYCLES and (axes or any(w in values for w in "RQ")):
            if not self.absolute:
                raise NCReadError(f"line {number}: a drilling cycle in incremental mode (G91) is not followed: "
                                  f"{_shown(raw)}")
            if "C" in values:
                raise NCReadError(f"line {number}: a drilling cycle with a C word is not followed: {_shown(raw)}")
            for word in "ZRQ":
                if word in values:
                    self.cycle[word] = values[word] * self.scale
            if "Z" not in self.cycle or "R" not in self.cycle:
                raise NCReadError(f"line {number}: {self.mode} needs its Z (the bottom) and R (the retract plane) "
                                  f"words: {_shown(raw)}")
            if self.mode == "G83" and not self.cycle.get("Q", 0) > 0:
                raise NCReadError(f"line {number}: G83 needs a peck Q greater than 0: {_shown(raw)}")
            if self.mode == "G82" and values.get("P", 0) < 0:
                raise NCReadError(f"line {number}: G82 P{values['P']:g} is a negative dwell: {_shown(raw)}")
            if self.cycle["Z"] > self.cycle["R"]:
                raise NCReadError(f"line {number}: the cycle's bottom Z{self.cycle['Z']:g} lies above its R plane "
                                  f"R{self.cycle['R']:g}: {_shown(raw)}")
            if self.feed_line is None or not self.feed_rate:
                raise NCReadError(f"line {number}: {self.mode} with no feed in effect (a control refuses a cutting move "
                                  f"without a feed): {_shown(raw)}")
            if not any(a in values for a in "XY") and not self.moves.count:
                raise NCReadError(f"line {number}: a drilling cycle before the tool's XY position is known: "
                                  f"{_shown(raw)}")
            x = values["X"] * self.scale if "X" in values else self.position["X"]
            y = values["Y"] * self.scale if "Y" in values else self.position["Y"]
            r_plane, bottom = self.cycle["R"], self.cycle["Z"]

            def go(kind, z, xy=None):
                self.position["X"], self.position["Y"] = (x, y) if xy is None else xy
                self.position["Z"] = z
                self.move(kind, z, (np.nan, np.nan, np.nan), number)

            if self.position["Z"] < r_plane:          # below R: up to it first (LinuxCNC's preliminary motion)
                go(RAPID, r_plane, (self.position["X"], self.position["Y"]))
            go(RAPID, self.position["Z"])              # over the hole at the height it is at
            go(RAPID, r_plane)
            if self.mode == "G83":
                depth = r_plane
                while depth > bottom + 1e-9:
                    if depth < r_plane:
                        go(RAPID, depth + PECK_CLEARANCE_MM)
                    depth = max(bottom, depth - self.cycle["Q"])
                    go(FEED, depth)
                    if depth > bottom + 1e-9:
                        go(RAPID, r_plane)
            else:
                go(FEED, bottom)
            top = r_plane if self.retract == "G99" else max(r_plane, self.cycle_start_z if self.cycle_start_z is not None else r_plane)
            go(RAPID, top)
            self.known.update(("X", "Y", "Z"))
            if ends:
                return True
            return False
        if ("I" in values or "J" in values) and (self.mode not in (2, 3) or not axes):
            raise NCReadError(f"line {number}: I or J without an arc move in {_shown(raw)}")
        if axes:
            if self.mode is None:
                raise NCReadError(f"line {number}: a move before any G0/G1/G2/G3: {_shown(raw)}")
            if not self.absolute and not self.moves.count:
                unknown = [a for a in axes if a not in self.known]
                if unknown:
                    raise NCReadError(f"line {number}: an incremental (G91) move before any absolute position of "
                                      f"{', '.join(unknown)}: {_shown(raw)}")
            before = dict(self.position)
            for axis in axes:
                value = values[axis] * (self.scale if axis != "C" else 1.0)
                self.position[axis] = value if self.absolute else self.position[axis] + value
            kind = (RAPID, FEED, ARC_CW, ARC_CCW)[self.mode]
            if kind != RAPID and self.feed_line is None:
                raise NCReadError(f"line {number}: a G{self.mode} move with no F word before it (a control refuses a "
                                  f"cutting move without a feed): {_shown(raw)}")
            if kind != RAPID and not self.feed_rate:
                raise NCReadError(f"line {number}: a G{self.mode} move with F0 in effect since line {self.feed_line} (a control "
                                  f"refuses a cutting move without a feed): {_shown(raw)}")
            centre = (np.nan, np.nan, np.nan)
            if kind in (ARC_CW, ARC_CCW):
                if "I" not in values and "J" not in values:
                    raise NCReadError(f"line {number}: an arc needs I and J: {_shown(raw)}")
                if not self.moves.count:
                    raise NCReadError(f"line {number}: an arc before the tool's XY position is known: "
                                      f"{_shown(raw)}")
                centre = (before["X"] + values.get("I", 0.0) * self.scale, before["Y"] + values.get("J", 0.0) * self.scale,
                          self.position["Z"])
                _check_arc(number, raw, (before["X"], before["Y"]), (self.position["X"], self.position["Y"]), centre,
                           self.scale != 1.0)
            self.saw_c = self.saw_c or "C" in values
            self.known.update(axes)
            self.move(kind, self.position["Z"], centre, number)
        if ends:
            return True
        return False


# lines per bulk call at most, and at first after a line the bulk reader left to block()
BULK_LINES, BULK_FIRST = 65536, 64
CHUNK_CHARS = 1 << 21        # text read per regular-expression pass


def _chunks(text: str):
    """(first line number, lines, rows of ncplain.PLAIN or None, end offset) of consecutive
    pieces of ``text``, each ending at a line break."""
    number, at = 1, 0
    while True:
        end = text.find("\n", at + CHUNK_CHARS) if at + CHUNK_CHARS < len(text) else -1
        piece = text[at:] if end < 0 else text[at:end]
        lines = piece.split("\n")
        rows = PLAIN.findall(piece)
        yield number, lines, (rows if len(rows) == len(lines) else None), (len(text) if end < 0 else end)
        if end < 0:
            return
        number, at = number + len(lines), end + 1


def _read_lines(reader: _Reader, first: int, lines: list, rows) -> bool:
    """Follow ``lines`` (line ``first`` on): runs of plain lines in bulk, the others one at a
    time; True when the program ends among them."""
    if rows is None:
        plain = np.zeros(len(lines), bool)
    else:
        plain = np.fromiter((row[ROW_OTHER] == "" for row in rows), bool, len(rows))
    others = np.flatnonzero(~plain)
    k, window = 0, BULK_LINES
    while k < len(lines):
        if plain[k]:
            stop = min(int(others[np.searchsorted(others, k)]) if len(others) and others[-1] > k else len(lines),
                       k + window)
            done = plain_moves(reader, rows[k:stop], first + k)
            k += done
            window = min(BULK_LINES, 2 * window) if k == stop else max(BULK_FIRST, 2 * done)
            if k == stop:
                continue
        if reader.block(first + k, lines[k]):
            return True
        k += 1
    return False


def read_nc(text: str, tool: Tool, name: str = "NC program", progress=None, bulk: bool = True) -> NCRead:
    """(Operation, line number of every move) with ``.ignored`` (see :class:`NCRead`).
    Coordinates in mm (G20 programs are converted).  ``progress``: optional callable(fraction),
    called after every piece of about 2 MB of text is read (a place to cancel).

    Plain lines are followed in bulk (:mod:`ncplain`), every other line one at a time
    (:meth:`_Reader.block`), with the same result; ``bulk=False`` follows every line one at a
    time (what the tests compare the bulk reading with)."""
    if not isinstance(text, str):
        raise NCReadError("the NC program must be text")
    # lines end at LF, CR LF or CR only: str.splitlines would also break at form feeds and at
    # U+0085, a byte of many UTF-8 kanji read as latin-1 (工 of 工具 in a comment), and shift the numbers
    if "\r" in text:
        text = text.replace("\r\n", "\n").replace("\r", "\n")
    reader = _Reader()
    for first, lines, rows, end in _chunks(text):
        ended = _read_lines(reader, first, lines, rows if bulk else None)
        if progress is not None:
            progress(1.0 if ended else end / max(len(text), 1))
        if ended:
            break
    return _result(reader, tool, name)


def _result(reader: _Reader, tool: Tool, name: str) -> NCRead:
    ignored = reader.ignored
    if reader.comments:
        ignored = {"(": {"code": "comment", "meaning": "comments", "count": len(set(reader.comments)),
                         "first_line": min(reader.comments)}, **ignored}
    if not reader.moves.count:
        raise NCReadError("the NC file has no moves")
    moves = reader.moves.arrays()
    kinds, speeds, turning = moves["kind"], moves["speed"], moves["turning"]
    feed = np.where(kinds == RAPID, np.nan, 1000.0)
    rotary = {"c": moves["c"]} if reader.saw_c else {}
    cutting = np.flatnonzero(kinds != RAPID)
    slowest = float(speeds[cutting].min()) if len(cutting) else float(speeds[-1])
    clockwise = bool(turning[cutting[0]]) if len(cutting) else True
    points = moves["point"]
    # The tool is taken to start where the first move ends: nothing is known of where it was.
    op = Operation(name, tool, slowest, kinds, points, feed, center=moves["centre"], rotary=rotary,
                   start=points[0].copy(), spindle_cw=clockwise)
    lines = LineNumbers(moves["line"])
    return NCRead(op, lines, sorted(ignored.values(), key=lambda e: e["first_line"]),
                  _spindle_runs(op, lines, speeds, turning, cutting))


def _spindle_runs(op: Operation, lines: LineNumbers, speeds: np.ndarray, turning: np.ndarray, cutting) -> list:
    """[(Operation, lines)]: ``op`` cut where a cutting move runs at another spindle (speed or
    direction) than the cutting move before it; rapids go with the run they lie in."""
    changed = (speeds[cutting[1:]] != speeds[cutting[:-1]]) | (turning[cutting[1:]] != turning[cutting[:-1]])
    starts = [0] + [int(i) for i in cutting[1:][changed]]
    if len(starts) == 1:
        return [(op, lines)]
    runs = []
    for a, b in zip(starts, starts[1:] + [len(op)]):
        inside = cutting[(cutting >= a) & (cutting < b)]
        first = int(inside[0]) if len(inside) else a
        where = f"line {lines[a]}" if b - a == 1 else f"lines {lines[a]}-{lines[b - 1]}"
        part = op.replace(name=f"{op.name} {where}", spindle_rpm=float(speeds[first]),
                          spindle_cw=bool(turning[first]), kind=op.kind[a:b], xyz=op.xyz[a:b], feed=op.feed[a:b],
                          center=op.center[a:b], rotary={k: v[a:b] for k, v in op.rotary.items()},
                          start=op.xyz[a - 1] if a else op.start, links=None)
        runs.append((part, lines[a:b]))
    return runs


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
    if not all(math.isfinite(v) and v > 0 for v in numbers) or (len(numbers) == 2 and numbers[1] > numbers[0] / 2):
        raise NCReadError(f"--tool {text!r}: sizes must be finite numbers > 0, the corner radius at most half the "
                          "diameter")
    return Tool(1, kind, numbers[0], corner_radius=numbers[1] if shape.corner_given else 0.0)
