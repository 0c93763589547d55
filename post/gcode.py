"""The ISO 6983 writer the milling posts share; dialects override a few hooks.

Output is deterministic: the same Program gives byte-identical text (no dates, no run-time
values).  Words are modal: X/Y/Z/F are written only when they change, G0/G1 only when the
motion mode changes, as CAM posts and hand-written programs both do.
"""
from __future__ import annotations


import numpy as np

from ..toolpath.ir.program import MoveKind, Operation, Program, fit_program
from . import words
from .registry import ControllerLimits, Post, PostError, default_machine

RAPID, FEED = int(MoveKind.RAPID), int(MoveKind.FEED)     # the IR's move kinds


def fmt(value: float, decimals: int) -> str:
    """``106.`` / ``-2.5`` / ``0.125``: always a decimal point (Fanuc reads ``X106`` as microns)."""
    text = f"{value:.{decimals}f}".rstrip("0")
    if text in ("-0.", "-."):
        text = "0."
    return text


def format_duration(seconds: float) -> str:
    minutes, secs = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours} H {minutes:02d} MIN {secs:02d} S" if hours else f"{minutes} MIN {secs:02d} S"


def comment_text(text: str) -> str:
    """Parentheses cannot nest in a G-code comment; keep it printable ASCII and upper case."""
    clean = "".join(ch if 32 <= ord(ch) < 127 else "?" for ch in str(text))
    return clean.replace("(", "[").replace(")", "]").upper()


def comment_lines(text: str, limit: int | None, prefix: str = "") -> list:
    """``(PREFIX: TEXT)`` as comment lines of at most ``limit`` characters (None: one line): the
    text wrapped at spaces (a word longer than a line is cut), continuation lines indented."""
    body = comment_text(text)
    first = f"({comment_text(prefix)}: " if prefix else "("
    if limit is None or len(first) + len(body) + 1 <= limit:
        return [f"{first}{body})"]
    lines, head = [], first
    words = body.split(" ")
    current = ""
    for word in words:
        room = limit - len(head) - 1
        candidate = f"{current} {word}" if current else word
        if len(candidate) <= room:
            current = candidate
            continue
        if current:
            lines.append(f"{head}{current})")
            head, current = "(  ", ""
            room = limit - len(head) - 1
        while len(word) > room:
            lines.append(f"{head}{word[:room]})")
            head, word = "(  ", word[room:]
            room = limit - len(head) - 1
        current = word
    if current or not lines:
        lines.append(f"{head}{current})")
    return lines


def fitted(lines: list, limit: int | None, post_name: str) -> list:
    """Every line within the control's ``limit``: a comment line too long is wrapped
    (:func:`comment_lines`); a block too long is refused, never cut."""
    if limit is None:
        return lines
    out = []
    for line in lines:
        if len(line) <= limit:
            out.append(line)
        elif line.startswith("(") and line.endswith(")") and line.count("(") == 1:
            out += comment_lines(line[1:-1], limit)
        else:
            raise PostError(f"the {post_name} post would write a line of {len(line)} characters, more than the "
                            f"{limit} the control reads: {line[:60]}...")
    return out


class GcodePost(Post):
    """Program -> text for one controller family.  Subclasses set the class attributes and
    override the hooks (preamble, tool change, ending)."""

    name = "iso"
    extension = ".nc"
    decimals = 3
    program_number = None        # "O0001" for Fanuc
    percent_wrapped = True

    # How this control can lift Z in the frames (machine.RETRACTS it writes); a profile asking for
    # another is refused naming the setting.
    retracts: tuple = ("machine", "clearance")
    tool_changes: tuple = ("atc", "manual")

    def __init__(self, work_offset: str | None = None, machine=None):
        self.work_offset = work_offset
        self.machine = machine if machine is not None else default_machine(type(self))
        self.frame_offset = work_offset or "G54"     # the work offset of the program being written

    # ----- hooks -------------------------------------------------------------------
    def preamble(self, program: Program) -> list:
        return ["G21 G17 G40 G49 G80 G90"]

    def lift(self) -> list:
        """Z to the safe height of the frames, before any XY (or C) move: the machine-coordinate
        retract where the profile says the machine has one, else the profile's clearance height."""
        machine = self.machine
        if machine.retract == "machine":
            return [f"G53 G00 Z{self.n(machine.machine_top_z)}"]
        if machine.retract == "clearance":
            return [f"G00 G90 {self.frame_offset} Z{self.n(machine.clearance_z)}"]
        return ["G91 G28 Z0.", "G90"]

    def tool_change(self, op: Operation, first: bool) -> list:
        return [f"T{op.tool.number} M06"]

    def after_load(self, op: Operation, first: bool) -> list:
        """After the tool load (M06, or the pause of a manual change) and before the XY move: Z
        is not known to be clear of the work, so it is lifted first."""
        return self.lift()

    def spindle_on(self, op: Operation) -> str:
        return f"S{int(round(op.spindle_rpm))} {'M03' if op.spindle_cw else 'M04'}"

    def length_offset(self, op: Operation) -> list:
        return [f"G43 H{op.tool.number} Z{self.n(op.safe_z)}"]

    def ending(self, program: Program) -> list:
        return ["M05", "G91 G28 Z0.", "G90", "M30"]

    def check_machine(self, program: Program) -> None:
        """Refuse a program the machine profile says the machine cannot run as written: a retract
        or a tool change this control's frames cannot do, a Z above what the machine reaches over
        the work zero (the operation's safe and clearance heights, any move), a spindle speed or a
        feed above the machine's.  Each message names the numbers and the setting."""
        machine = self.machine
        if machine is None:
            return
        where = f"the {self.name} post, machine {machine.label!r}"
        if machine.retract not in self.retracts:
            raise PostError(f"{where}: Retract = {machine.retract!r} is not a move this control has; choose "
                            f"{' or '.join(repr(r) for r in self.retracts)}")
        if machine.tool_change not in self.tool_changes:
            raise PostError(f"{where}: Tool Change = {machine.tool_change!r}: this post writes "
                            f"{' or '.join(repr(t) for t in self.tool_changes)} tool changes only")
        for op in program.operations:
            what = f"{self.name} post, operation {op.name!r}:"
            z_top = float(np.max(op.xyz[:, 2])) if len(op) else -np.inf
            for z, name in ((op.safe_z, "safe Z (the workflow's Safe Z, or the STEP-NC security plane)"),
                            (op.clearance_z, "clearance height (the workflow's clearance)"),
                            (float(op.start[2]), "start height"), (z_top, "highest move, Z")):
                problem = machine.reach_problem(z, f"{what} its {name}")
                if problem:
                    raise PostError(problem)
            if op.spindle_rpm > machine.max_spindle_rpm + 1e-9:
                raise PostError(f"{what} spindle speed S {op.spindle_rpm:g} is above the {machine.max_spindle_rpm:g} "
                                f"rpm of the machine {machine.label!r} (machine setting Max Spindle)")
            cutting = op.kind != RAPID
            if np.any(cutting) and float(np.max(op.feed[cutting])) > machine.max_feed + 1e-9:
                raise PostError(f"{what} feed {float(np.max(op.feed[cutting])):g} mm/min is above the "
                                f"{machine.max_feed:g} mm/min of the machine {machine.label!r} (machine setting "
                                f"Max Feed)")

    def check(self, program: Program):
        for op in program.operations:
            if op.texture is not None:
                raise PostError(f"operation {op.name!r} still carries an unbaked texture: bake it first "
                                f"(the {self.name} post writes the cut depths literally)")
            if op.rotary:
                raise PostError(f"the {self.name} post is for 3-axis milling; operation {op.name!r} "
                                f"moves rotary axes {sorted(op.rotary)}")

    # ----- the writer --------------------------------------------------------------
    def n(self, value: float) -> str:
        return fmt(value, self.decimals)

    def many(self, values: list) -> list:
        """:meth:`n` of every value of the list, in one formatting call where :meth:`n` is ours."""
        if type(self).n is not GcodePost.n:
            return [self.n(value) for value in values]
        return words.trimmed(values, self.decimals)

    # Lines the header adds after the units: a dialect's conventions worth stating in the file.
    conventions: tuple = ()
    states_machine = False      # the header names the machine profile the frames were written for

    def operation_seconds(self, op: Operation, rapid_rate: float) -> float:
        """Estimated time of one operation on this machine."""
        return op.cycle_time(rapid_rate)

    def header(self, program: Program) -> list:
        """Comment lines, each within the control's line length (``limits.max_line_length``)."""
        limit = self.limits.max_line_length
        lines = [*comment_lines(f"KEZURI CAM - {program.name}", limit), f"(POST: {comment_text(self.name)})",
                 "(UNITS: MM)", *self.conventions]
        if self.states_machine and self.machine is not None:
            lines += [f"({comment_text(line)})" for line in self.machine.describe()]
        for tool in program.tools():
            lines += comment_lines(tool.describe(), limit, "TOOL")
        total = 0.0
        for op in program.operations:
            seconds = self.operation_seconds(op, program.rapid_rate)
            total += seconds
            lines += comment_lines(f"{op.name} - T{op.tool.number} - {format_duration(seconds)}", limit, "OPERATION")
        lines.append(f"(ESTIMATED CYCLE TIME: {format_duration(total)})")
        for note in program.notes:
            lines += comment_lines(note, limit, "NOTE")
        return lines

    def opening(self, program: Program) -> list:
        """Checks, then the program number, the header comments and the preamble."""
        self.check(program)
        if not program.operations:
            raise PostError("the program has no operations")
        lines = []
        if self.program_number:
            lines.append(f"{self.program_number} ({comment_text(program.name)[:30]})")
        return lines + self.header(program) + self.preamble(program)

    def check_limits(self, op: Operation, inverse_time=None) -> None:
        """Raise :class:`PostError` naming the operation, the move and the value when a word this
        post writes for ``op`` is outside the control's ranges (:attr:`limits`): S, T, H, the
        coordinates, F under G94 (``op.feed``) or, given ``inverse_time`` (F words per move, NaN
        for rapids), F under G93."""
        limits: ControllerLimits = self.limits
        what = f"{self.name} post, operation {op.name!r}"
        limits.check_word("spindle_rpm", float(op.spindle_rpm), what)
        limits.check_word("tool_number", float(op.tool.number), what)
        limits.check_word("length_offset", float(op.tool.number), what)
        checks = [("coordinate", np.abs(op.xyz).max(axis=1) if len(op) else np.zeros(0))]
        cutting = op.kind != RAPID
        if inverse_time is None:
            checks.append(("feed_per_minute", np.where(cutting, op.feed, np.nan)))
        else:
            checks.append(("inverse_time_feed", np.where(cutting, inverse_time, np.nan)))
        for word, values in checks:
            bounds = getattr(limits, word)
            if bounds is None or not len(values):
                continue
            low, high = (-bounds, bounds) if word == "coordinate" else bounds
            bad = np.flatnonzero(~np.isnan(values) & ((values < low) | (values > high)))
            if len(bad):
                limits.check_word(word, float(values[bad[0]]), f"{what}, move {int(bad[0]) + 1}")

    def arcs_out(self, program: Program) -> Program:
        """The program as this post writes it: on a milling control that takes arcs
        (``limits.arc_end_tolerance``) and a machine whose profile has Arcs on, every polyline
        that follows a circle as a G2/G3 arc (:func:`toolpath.ir.arcfit.fit_program`, whose
        docstring says why the filter runs here), each arc's centre words chosen so the control's
        start/end radius check passes; else the program as planned."""
        limits = self.limits
        if self.family != "milling" or limits.arc_end_tolerance is None or not getattr(self.machine, "arcs", True):
            return program
        return fit_program(program, end_tolerance=limits.arc_end_tolerance, written=self.written,
                           step=10.0 ** -self.decimals)      # (numba is loaded at this first call)

    def written(self, values) -> np.ndarray:
        """The numbers ``values`` read as once written in this post's format."""
        return np.array([float(text) for text in self.many(np.asarray(values, float).reshape(-1).tolist())],
                        float)

    def to_text(self, program: Program) -> str:
        work_offset = self.frame_offset = self.work_offset or program.work_offset
        program = self.arcs_out(program)
        lines = self.opening(program)
        tool = None
        for index, op in enumerate(program.operations):
            self.check_limits(op)
            lines.append(f"(OPERATION {index + 1}: {comment_text(op.name)})")
            if tool is None or op.tool.number != tool.number:   # never a change to the tool in the spindle
                lines += self.tool_change(op, tool is None)
                lines += self.after_load(op, tool is None)
                tool = op.tool
            lines.append(f"G00 G90 {work_offset} X{self.n(op.start[0])} Y{self.n(op.start[1])} {self.spindle_on(op)}")
            lines += self.length_offset(op)
            lines += self.operation_moves(op)
            lines.append(f"G00 Z{self.n(op.safe_z)}")
        lines += self.ending(program)
        self.check_machine(program)      # after the control's word ranges: those name the move
        body = "\n".join(fitted(lines, self.limits.max_line_length, self.name)) + "\n"
        return f"%\n{body}%\n" if self.percent_wrapped else body

    # Canned drilling cycles (G81/G82/G83, G98/G99, G80): posts whose controls have them set this;
    # the others write a drilling operation's expanded moves.
    canned_cycles = False

    def operation_moves(self, op: Operation) -> list:
        if op.cycle is not None and self.canned_cycles:
            return self.cycle_moves(op)
        return self.moves(op, op.start)

    def dwell_word(self, seconds: float) -> str:
        """The P word of a G82 dwell (LinuxCNC: seconds; Fanuc overrides: milliseconds)."""
        return f"P{self.n(seconds)}"

    def cycle_moves(self, op: Operation) -> list:
        """The operation's drilling cycle as one canned cycle: Z to the initial level, the cycle's
        block at the first hole (G98/G99 return level, G81 drill, G82 with the dwell P, G83 with the
        peck Q; Z the hole's bottom and R the R plane, absolute under G90), the next holes' X Y,
        then G80 and Z back to the clearance plane.  The moves the cycle makes are the operation's
        expanded moves (:mod:`..toolpath.ir.cycles`)."""
        cycle = op.cycle
        code = {"drill": "G81", "dwell": "G82", "peck": "G83"}[cycle.kind]
        back = "G98" if cycle.retract == "initial" else "G99"
        (x, y), *rest = cycle.holes
        words = [f"{back} {code} X{self.n(x)} Y{self.n(y)} Z{self.n(cycle.bottom_z)} R{self.n(cycle.r_z)}"]
        if cycle.kind == "peck":
            words.append(f"Q{self.n(cycle.peck)}")
        if cycle.kind == "dwell":
            words.append(self.dwell_word(cycle.dwell))
        words.append(f"F{fmt(cycle.feed, 1)}")
        lines = [f"G00 Z{self.n(cycle.initial_z)}", " ".join(words)]
        lines += [f"X{self.n(hx)} Y{self.n(hy)}" for hx, hy in rest]
        return lines + ["G80", f"G00 Z{self.n(op.clearance_z)}"]

    def moves(self, op: Operation, start) -> list:
        """Modal motion blocks for the operation's moves; zero-length moves are dropped.

        Vectorised (:mod:`.words`): an axis word is written when its text differs from the
        previous move's (a dropped move reads the same as the one before it, so "previous move"
        and "previous written block" agree), on arcs X and Y always; G00/G01/G02/G03 when the
        mode changes and on every arc; F (one decimal) when its text differs from the last
        written cutting block's; I/J from the last written block's end point as written (the
        point the control measures them from)."""
        n = len(op)
        if not n:
            return []
        kind = op.kind.astype(np.intp)
        arc = (kind != RAPID) & (kind != FEED)
        start = np.asarray(start, float)
        axis_words, changed = [], []
        for axis in range(3):
            texts, ids = words.column(np.concatenate([[start[axis]], op.xyz[:, axis]]), self.n, self.many)
            changed.append(ids[1:] != ids[:-1])
            axis_words.append((texts, ids[1:]))
        write = [changed[0] | arc, changed[1] | arc, changed[2]]
        emitted = write[0] | write[1] | write[2]
        previous = words.previous_where(emitted)
        code_written = emitted & (arc | (previous < 0) | (kind != kind[np.maximum(previous, 0)]))
        codes = np.array(["G00", "G01", "G02", "G03", ""], dtype=object)[np.where(code_written, kind, 4)]
        columns = [codes] + [words.prefixed(letter, texts, ids, w)
                             for letter, (texts, ids), w in zip("XYZ", axis_words, write)]
        arcs = np.flatnonzero(arc & emitted)
        if len(arcs):
            position = np.where((previous[arcs] < 0)[:, None], start[None, :2], op.xyz[np.maximum(previous[arcs], 0), :2])
            position = self.written(position).reshape(-1, 2)
            for letter, axis in (("I", 0), ("J", 1)):
                texts, ids = words.column(op.center[arcs, axis] - position[:, axis], self.n, self.many)
                column = np.full(n, "", dtype=object)
                column[arcs] = words.prefixed(letter, texts, ids, np.ones(len(arcs), bool))
                columns.append(column)
        cutting = emitted & (kind != RAPID)
        texts, ids = words.column(op.feed, lambda value: fmt(value, 1), lambda values: words.trimmed(values, 1))
        last_cut = words.previous_where(cutting)
        feed_written = cutting & ((last_cut < 0) | (ids != ids[np.maximum(last_cut, 0)]))
        columns.append(words.prefixed("F", texts, ids, feed_written))
        return words.join_words([c[emitted] for c in columns])
