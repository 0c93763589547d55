"""A small, independent interpreter for the Fanuc Custom Macro B subset our Fanuc post writes.

Tests use it to *execute* a controller-macro NC program (a main program with a modal
``G66.1 P7023`` call plus the macro ``O7023``) and check the motion it produces, instead of
comparing text.  It is deliberately strict: anything outside the subset raises
:class:`MacroError` naming the file line and block, so a post that starts writing
something new fails loudly here rather than on a machine.

Usage::

    run = run_program(text, clock=[1234, 1250, ...], start=(0, 0, 100))
    run.moves          # list[Move], absolute work coordinates
    run.var(500)       # final value of #500 (None = vacant)
    run.clock_reads    # how many times #3001 was read

Structure: ``_strip_comment`` / ``_parse_block`` turn each line into a ``_Block`` (the
tokenizer and recursive-descent ``_Parser`` compile expressions into closures once), and
``_Interpreter`` executes blocks with a stack of call frames.

Supported (see the module tests for worked examples):

* Several programs in one text (``O0001 ... M30``, ``O7023 ... M99``); ``%`` lines and
  ``(comments)`` are skipped, spaces are ignored, a trailing ``;`` is dropped.  Blocks
  before the first ``O`` line form program O0000.  The first program is the main program
  unless ``main=`` says otherwise.
* Variables: ``#0`` (always vacant), locals ``#1..#33`` (one set per macro call level),
  common ``#100..#199`` and ``#500..#999``, ``#3000`` (writing raises :class:`MacroAlarm`),
  ``#3001`` (millisecond clock: every *read* takes the next value from the caller's
  ``clock`` iterable; writes are only recorded in ``MacroRun.clock_writes``), ``#4001``
  (modal group 1: 0..3; refused under G66.1, see below), ``#4003`` (90/91), ``#4006``
  (20/21), ``#4014`` (54..59), ``#4109`` (F), ``#4111`` (H), ``#4119`` (S), ``#4120`` (T), ``#5001..#5003`` (end point
  of the previous block, absolute work coordinates).  Indirect ``#[expr]`` works.
* Vacancy as on Fanuc: a vacant value in an address word omits the word; ``#i=#j`` copies
  vacancy; any arithmetic treats vacant as 0 (so ``#24+#25`` of two vacant variables is
  0, and ``-#1`` is 0); ``EQ``/``NE`` tell vacant from 0 (``#1EQ#0`` is true only for a
  vacant ``#1``); ``GT GE LT LE`` treat vacant as 0.
* Expressions: ``[ ]`` (at most 5 levels, as on the control), ``+ - * /``, FIX (towards
  zero), FUP (away from zero), ROUND (half away from zero), ABS, SQRT, SIN, COS, TAN
  (degrees); comparisons EQ NE GT GE LT LE; ``AND OR XOR`` only between bracketed
  conditions (Fanuc precedence: ``[#1GT0]AND[#2GT0]``).  Comparisons are exact float
  comparisons.
* Statements: ``#i=expr``, ``IF[c]GOTOn``, ``IF[c]THEN#i=expr``, ``GOTOn`` (n may be an
  expression), ``WHILE[c]DOm ... ENDm`` (m = 1..3, also a bare ``DOm``), ``N`` numbers.
* Words: G00 G01 G02 G03 (XY plane, I/J or R), G04 (P or X, recorded), G17, G20/G21
  (recorded only: no unit conversion), G28 (see ``home``), G40 G49 G80 G94, G43 H,
  G54..G59 (recorded; coordinates stay work coordinates), G90/G91, G65, G66.1, G67,
  X Y Z I J R F S T H, M00 M01 M02 M03 M04 M05 M06 M08 M09 M19 M30, M98 P [L], M99.
* ``significant_digits=8`` models a control that keeps about 8 significant decimal digits:
  every value stored in a variable is rounded to that many significant digits (expressions
  are evaluated in double precision in between).  Default None: no rounding.
* Numbers are taken at face value: ``X106`` is 106.0 mm (the "no decimal point means
  least input increment" rule is NOT implemented; our post always writes a point).
* ``G65 P.. <args>`` and ``G66.1 P.. <args>`` use argument specification I
  (A B C I J K D E F H M Q R S T U V W X Y Z -> #1.. #26; G L N O P are not arguments).  Under
  G66.1 every later block of the calling level that has any word (not macro statements, not
  ``N``-only or comment-only lines) is not executed itself but calls the macro with its words
  as arguments.  The G66.1 block itself also calls the macro with its own arguments (those
  arguments are not remembered for later calls).  ``G67`` cancels.  Blocks inside the called
  macro are never modal-called.
* Modal state is global across call levels, as on the control: a ``G00`` executed in the
  macro is still active when the caller continues.

Refused, because the manual leaves the behaviour to the machine (strict on purpose: a program
that depends on one of these cuts differently on different controls):

* a G66.1 call (the G66.1 block or a block under it) without an X, Y or Z word: whether a block
  with no move calls the macro is not settled;
* a G66.1 call while the modal motion is G00, G02 or G03, and any G code in a block under
  G66.1: the block's G codes are not arguments, and whether the control executes them before
  the call is not stated, so the macro would have to guess a rapid from a cut;
* reading ``#4001..#4130`` (modal information "up to the preceding block") in a macro called by
  G66.1 or in a program that macro calls: which block precedes a block turned into a call is
  not stated;
* an argument letter that is an axis address of the simulated machine (``axes=``, e.g. "XYZB"),
  other than X, Y, Z (the move's own end point): whether the control passes it to the macro or
  moves the axis is a machine matter.

Not supported (raise MacroError): G18/G19, cutter compensation G41/G42, canned cycles,
G66 (move-triggered modal call), argument specification II, G65 with L other than 1,
block delete ``/``, other system variables.  Arc end points must be within
``ARC_TOLERANCE`` of the circle.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Callable, Iterable, Mapping

__all__ = ["MacroError", "MacroAlarm", "Move", "Event", "MacroRun", "run_program", "parse_programs",
           "eval_expression", "ARG_VARS", "ARC_TOLERANCE"]

ARC_TOLERANCE = 0.01        # mm: start and end radius of an arc may differ by this much
MAX_BRACKET_DEPTH = 5       # Fanuc allows 5 levels of [ ] including function brackets

# Argument specification I: address -> local variable number.
ARG_VARS = {"A": 1, "B": 2, "C": 3, "I": 4, "J": 5, "K": 6, "D": 7, "E": 8, "F": 9, "H": 11,
            "M": 13, "Q": 17, "R": 18, "S": 19, "T": 20, "U": 21, "V": 22, "W": 23,
            "X": 24, "Y": 25, "Z": 26}

KNOWN_M = {0, 1, 2, 3, 4, 5, 6, 8, 9, 19, 30, 98, 99}
_ORDINARY_LETTERS = set("XYZIJRFSTHPL")
_SYSTEM_READ = {3001, 4001, 4003, 4006, 4014, 4109, 4111, 4119, 4120, 5001, 5002, 5003}


# --------------------------------------------------------------------------------------------
# Public result types
# --------------------------------------------------------------------------------------------
class MacroError(Exception):
    """Anything the interpreter refuses; ``line`` is the 1-based line in the text, ``text`` the block."""

    def __init__(self, message: str, line: int | None = None, text: str | None = None):
        self.message, self.line, self.text = message, line, text
        where = f"line {line}: " if line is not None else ""
        block = f" in block `{text}`" if text else ""
        super().__init__(f"{where}{message}{block}")


class MacroAlarm(MacroError):
    """The program assigned ``#3000`` (a macro alarm); ``number`` and ``alarm_message`` are its values."""

    def __init__(self, number: float, alarm_message: str, line=None, text=None):
        self.number, self.alarm_message = number, alarm_message
        super().__init__(f"macro alarm #3000={number:g} ({alarm_message})", line, text)


@dataclass(frozen=True)
class Move:
    """One executed motion, end point in absolute work coordinates.

    ``kind`` is "rapid", "feed", "cw" or "ccw".  For arcs ``i, j`` are the centre offsets from
    the start point (Fanuc I/J; R-form arcs are converted), else None.  ``feed`` is the modal
    F for cutting moves and None for rapids.  ``line`` is the text line of the block that
    moved; ``main_line`` the line of the main-program block being executed at the time
    (for a modal-called macro: the calling block).
    """

    kind: str
    x: float
    y: float
    z: float
    i: float | None = None
    j: float | None = None
    feed: float | None = None
    line: int = 0
    start: tuple = (0.0, 0.0, 0.0)
    main_line: int = 0

    @property
    def end(self) -> tuple:
        return (self.x, self.y, self.z)

    @property
    def center(self) -> tuple | None:
        """Arc centre (x, y) in absolute coordinates, None for straight moves."""
        if self.i is None:
            return None
        return (self.start[0] + self.i, self.start[1] + self.j)


@dataclass(frozen=True)
class Event:
    """A non-motion happening: kind "M", "T", "S", "G04", "G28", "G43" or "WCS"; value is the number."""

    kind: str
    value: float | None
    line: int


@dataclass
class MacroRun:
    """What a run produced."""

    moves: list
    events: list
    common: dict            # final #100..#999 (vacant ones absent)
    locals: dict            # final #1..#33 of the main program level
    position: tuple         # final X, Y, Z
    modal: dict             # final modal state (motion, absolute, wcs, feed, ...)
    clock_reads: int
    clock_writes: list      # values assigned to #3001, in order
    blocks_executed: int
    ended_by: str           # "M30", "M02" or "end" (ran off the end of the main program)

    def var(self, number: int) -> float | None:
        """Final value of a common or main-level local variable (None if vacant)."""
        return (self.locals if 1 <= number <= 33 else self.common).get(number)

    def xyz(self) -> list:
        """End points of all moves as a list of (x, y, z)."""
        return [m.end for m in self.moves]


# --------------------------------------------------------------------------------------------
# Values and helpers
# --------------------------------------------------------------------------------------------
def _num(v):
    """Arithmetic value: vacant counts as 0; a condition is not a number."""
    if v is None:
        return 0.0
    if type(v) is bool:
        raise MacroError("a condition is used where a number is expected")
    return v


def _fix(v):
    return float(math.trunc(v))


def _fup(v):
    return float(math.copysign(math.ceil(abs(v)), v)) if v else 0.0


def _round(v):
    return float(math.copysign(math.floor(abs(v) + 0.5), v)) if v else 0.0


def _sqrt(v):
    if v < 0:
        raise MacroError(f"SQRT of a negative number ({v:g})")
    return math.sqrt(v)


_FUNCS = {"FIX": _fix, "FUP": _fup, "ROUND": _round, "ABS": abs, "SQRT": _sqrt,
          "SIN": lambda v: math.sin(math.radians(v)), "COS": lambda v: math.cos(math.radians(v)),
          "TAN": lambda v: math.tan(math.radians(v))}
_CMPS = ("EQ", "NE", "GT", "GE", "LT", "LE")
_KEYWORDS = sorted(list(_FUNCS) + list(_CMPS) + ["AND", "OR", "XOR"], key=len, reverse=True)


def _compare(op, a, b):
    if type(a) is bool or type(b) is bool:
        raise MacroError("a condition cannot be compared")
    if op in ("EQ", "NE"):
        same = (a is None and b is None) if (a is None or b is None) else a == b
        return same if op == "EQ" else not same
    a, b = _num(a), _num(b)
    return {"GT": a > b, "GE": a >= b, "LT": a < b, "LE": a <= b}[op]


def _logic(op, a, b):
    if type(a) is not bool or type(b) is not bool:
        raise MacroError(f"{op} is only supported between bracketed conditions, e.g. [#1GT0]{op}[#2GT0]")
    return {"AND": a and b, "OR": a or b, "XOR": a != b}[op]


def _div(a, b):
    if b == 0:
        raise MacroError("division by zero")
    return a / b


def _integer(v, what):
    """A value that must be a whole number (variable numbers, N, P, M...)."""
    v = _num(v)
    r = round(v)
    if abs(v - r) > 1e-6:
        raise MacroError(f"{what} must be a whole number, got {v:g}")
    return int(r)


def _gcode(v) -> str:
    """G word value -> canonical text: 1.0 -> "1", 66.1 -> "66.1"."""
    tenths = round(v * 10)
    if abs(v * 10 - tenths) > 1e-6 or tenths < 0:
        raise MacroError(f"G{v:g} is not a G code")
    return str(tenths // 10) if tenths % 10 == 0 else f"{tenths // 10}.{tenths % 10}"


def _check_var_number(n: int):
    ok = (n == 0 or 1 <= n <= 33 or 100 <= n <= 199 or 500 <= n <= 999 or n == 3000
          or n in _SYSTEM_READ)
    if not ok:
        raise MacroError(f"variable #{n} is not supported")


# --------------------------------------------------------------------------------------------
# Parsing: comments, expressions (recursive descent, compiled to closures), blocks
# --------------------------------------------------------------------------------------------
def _strip_comment(raw: str, line: int) -> tuple:
    """Remove ``(...)`` comments; return (code, comment text)."""
    code, comment, depth, buf = [], [], 0, []
    for ch in raw:
        if ch == "(":
            if depth:
                raise MacroError("nested '(' in a comment", line, raw.strip())
            depth, buf = 1, []
        elif ch == ")":
            if not depth:
                raise MacroError("')' without '('", line, raw.strip())
            depth = 0
            comment.append("".join(buf))
        elif depth:
            buf.append(ch)
        else:
            code.append(ch)
    if depth:
        raise MacroError("unclosed comment '('", line, raw.strip())
    return "".join(code), " ".join(comment)


def _check_brackets(s: str):
    depth = 0
    for ch in s:
        if ch == "[":
            depth += 1
            if depth > MAX_BRACKET_DEPTH:
                raise MacroError(f"brackets nested deeper than {MAX_BRACKET_DEPTH} levels")
        elif ch == "]":
            depth -= 1
            if depth < 0:
                raise MacroError("unbalanced brackets: ']' without '['")
    if depth:
        raise MacroError("unbalanced brackets: '[' without ']'")


_NUMBER = re.compile(r"\d+\.?\d*|\.\d+")


class _Parser:
    """Recursive-descent parser over one compact (upper case, no spaces) block.

    Grammar (Fanuc precedence; every method returns a closure ``f(interp) -> value``)::

        condition := sum [ CMP sum ]
        sum       := term { (+ | - | OR | XOR) term }
        term      := unary { (* | / | AND) unary }
        unary     := (+ | -) unary | primary
        primary   := number | '#' varref | '[' condition ']' | FUNC '[' condition ']'
        varref    := digits | '[' condition ']'
    """

    def __init__(self, s: str, pos: int = 0):
        self.s, self.pos = s, pos

    # -- tokens ------------------------------------------------------------------------------
    def peek(self) -> str:
        return self.s[self.pos] if self.pos < len(self.s) else ""

    def at_end(self) -> bool:
        return self.pos >= len(self.s)

    def accept(self, tok: str) -> bool:
        if self.s.startswith(tok, self.pos):
            self.pos += len(tok)
            return True
        return False

    def expect(self, tok: str, what: str):
        if not self.accept(tok):
            found = self.s[self.pos:] or "end of block"
            raise MacroError(f"expected {what} ('{tok}'), found '{found}'")

    def keyword(self) -> str | None:
        for kw in _KEYWORDS:
            if self.s.startswith(kw, self.pos):
                return kw
        return None

    def number(self) -> float | None:
        m = _NUMBER.match(self.s, self.pos)
        if not m:
            return None
        self.pos = m.end()
        return float(m.group())

    def integer(self, what: str) -> int:
        m = re.compile(r"\d+").match(self.s, self.pos)
        if not m:
            raise MacroError(f"expected {what}")
        self.pos = m.end()
        return int(m.group())

    # -- expressions -------------------------------------------------------------------------
    def condition(self):
        left = self.sum()
        kw = self.keyword()
        if kw in _CMPS:
            self.pos += len(kw)
            right = self.sum()
            if self.keyword() in _CMPS:
                raise MacroError("comparisons cannot be chained; use brackets and AND/OR")
            return lambda it: _compare(kw, left(it), right(it))
        return left

    def sum(self):
        left = self.term()
        while True:
            if self.accept("+"):
                right = self.term()
                left = (lambda a, b: lambda it: _num(a(it)) + _num(b(it)))(left, right)
            elif self.accept("-"):
                right = self.term()
                left = (lambda a, b: lambda it: _num(a(it)) - _num(b(it)))(left, right)
            elif self.keyword() in ("OR", "XOR"):
                op = self.keyword()
                self.pos += len(op)
                right = self.term()
                left = (lambda a, b, op: lambda it: _logic(op, a(it), b(it)))(left, right, op)
            else:
                return left

    def term(self):
        left = self.unary()
        while True:
            if self.accept("*"):
                right = self.unary()
                left = (lambda a, b: lambda it: _num(a(it)) * _num(b(it)))(left, right)
            elif self.accept("/"):
                right = self.unary()
                left = (lambda a, b: lambda it: _div(_num(a(it)), _num(b(it))))(left, right)
            elif self.keyword() == "AND":
                self.pos += 3
                right = self.unary()
                left = (lambda a, b: lambda it: _logic("AND", a(it), b(it)))(left, right)
            else:
                return left

    def unary(self):
        if self.accept("-"):
            inner = self.unary()
            return lambda it: -_num(inner(it))
        if self.accept("+"):
            inner = self.unary()
            return lambda it: _num(inner(it))
        return self.primary()

    def primary(self):
        v = self.number()
        if v is not None:
            return lambda it: v
        if self.accept("#"):
            return self.varref()
        if self.accept("["):
            inner = self.condition()
            self.expect("]", "closing bracket")
            return inner
        kw = self.keyword()
        if kw in _FUNCS:
            self.pos += len(kw)
            self.expect("[", f"'[' after {kw}")
            arg = self.condition()
            self.expect("]", "closing bracket")
            fn = _FUNCS[kw]
            return lambda it: fn(_num(arg(it)))
        found = self.s[self.pos:] or "end of block"
        raise MacroError(f"expected a value, found '{found}'")

    def varref(self):
        """After '#': a constant variable number or an indirect ``#[expr]``."""
        if self.accept("["):
            index = self.condition()
            self.expect("]", "closing bracket")
            return lambda it: it.read_var(_integer(index(it), "variable number"))
        n = self.integer("a variable number after '#'")
        _check_var_number(n)
        return lambda it: it.read_var(n)

    def target(self):
        """Assignment target after '#': returns a closure giving the variable number."""
        if self.accept("["):
            index = self.condition()
            self.expect("]", "closing bracket")
            return lambda it: _integer(index(it), "variable number")
        n = self.integer("a variable number after '#'")
        _check_var_number(n)
        return lambda it: n

    def address_value(self, letter: str):
        """The value of an address word: [sign] number | [sign] #var | [sign] [expr]."""
        sign = -1.0 if self.peek() == "-" else 1.0
        if self.peek() in "+-" and self.peek():
            self.pos += 1
        ch = self.peek()
        if ch == "#":
            self.pos += 1
            f = self.varref()
        elif ch == "[":
            f = self.primary()
        else:
            v = self.number()
            if v is None:
                raise MacroError(f"address {letter} has no value")
            v *= sign
            return lambda it: v
        if sign < 0:
            return lambda it: -_num(f(it))
        return f


@dataclass
class _Block:
    """One parsed block.  ``kind``: words, assign, if_goto, if_then, goto, while, end."""

    line: int
    text: str
    comment: str
    n: int | None
    kind: str
    words: list = field(default_factory=list)     # [(letter, closure)]
    target: Callable | None = None
    value: Callable | None = None
    cond: Callable | None = None
    loop: int | None = None
    match: int | None = None                        # index of the matching WHILE/END


def _parse_assignment(p: _Parser, blk: _Block):
    p.expect("#", "'#'")
    blk.target = p.target()
    p.expect("=", "'='")
    blk.value = p.condition()


def _parse_block(compact: str, line: int, text: str, comment: str) -> _Block:
    """Parse one block (already without comments and spaces, upper case)."""
    try:
        if compact.startswith("/"):
            raise MacroError("block delete '/' is not supported")
        _check_brackets(compact)
        p = _Parser(compact)
        n = None
        if p.peek() == "N":
            p.pos += 1
            n = p.integer("a sequence number after N")
        blk = _Block(line, text, comment, n, "words")
        rest = compact[p.pos:]
        if rest.startswith("#"):
            blk.kind = "assign"
            _parse_assignment(p, blk)
        elif rest.startswith("IF"):
            p.pos += 2
            p.expect("[", "'[' after IF")
            blk.cond = p.condition()
            p.expect("]", "closing bracket of the IF condition")
            if p.accept("GOTO"):
                blk.kind = "if_goto"
                blk.value = p.condition()
            elif p.accept("THEN"):
                blk.kind = "if_then"
                _parse_assignment(p, blk)
            else:
                raise MacroError("IF[...] must be followed by GOTO or THEN")
        elif rest.startswith("GOTO"):
            p.pos += 4
            blk.kind = "goto"
            blk.value = p.condition()
        elif rest.startswith("WHILE"):
            p.pos += 5
            p.expect("[", "'[' after WHILE")
            blk.cond = p.condition()
            p.expect("]", "closing bracket of the WHILE condition")
            p.expect("DO", "DO after WHILE[...]")
            blk.kind, blk.loop = "while", p.integer("a loop number after DO")
        elif re.fullmatch(r"DO\d+", rest):
            blk.kind, blk.loop = "while", int(rest[2:])
            p.pos = len(compact)
        elif rest.startswith("END"):
            p.pos += 3
            blk.kind, blk.loop = "end", p.integer("a loop number after END")
        else:
            while not p.at_end():
                ch = p.peek()
                if not ("A" <= ch <= "Z"):
                    raise MacroError(f"unexpected '{compact[p.pos:]}'")
                if ch in "NO":
                    raise MacroError(f"address {ch} is not allowed inside a block")
                p.pos += 1
                blk.words.append((ch, p.address_value(ch)))
        if not p.at_end():
            raise MacroError(f"unexpected '{compact[p.pos:]}' at the end of the block")
        if blk.loop is not None and not 1 <= blk.loop <= 3:
            raise MacroError(f"loop number must be 1..3, got {blk.loop}")
        return blk
    except MacroError as e:
        if e.line is None:
            raise MacroError(e.message, line, text) from None
        raise


@dataclass
class _Program:
    number: int
    line: int
    blocks: list = field(default_factory=list)
    labels: dict = field(default_factory=dict)      # N number -> [block index]

    def finish(self):
        """Index sequence numbers and pair WHILE/DO with END."""
        stack = []
        for k, b in enumerate(self.blocks):
            if b.n is not None:
                self.labels.setdefault(b.n, []).append(k)
            if b.kind == "while":
                stack.append(k)
            elif b.kind == "end":
                if not stack or self.blocks[stack[-1]].loop != b.loop:
                    raise MacroError(f"END{b.loop} without a matching DO{b.loop}", b.line, b.text)
                k0 = stack.pop()
                self.blocks[k0].match, b.match = k, k0
        if stack:
            b = self.blocks[stack[-1]]
            raise MacroError(f"DO{b.loop} without a matching END{b.loop}", b.line, b.text)


def parse_programs(text: str) -> dict:
    """Split a text into programs: {program number: _Program}, in file order."""
    programs: dict = {}
    current = None
    for line, raw in enumerate(text.splitlines(), 1):
        code, comment = _strip_comment(raw, line)
        compact = re.sub(r"\s+", "", code).upper()
        if compact.endswith(";"):
            compact = compact[:-1]
        if not compact or compact.startswith("%"):
            continue
        m = re.fullmatch(r"O(\d+)", compact)
        if m:
            number = int(m.group(1))
            if number in programs:
                raise MacroError(f"program O{number:04d} is defined twice", line, raw.strip())
            current = programs[number] = _Program(number, line)
            continue
        if compact.startswith("O"):
            raise MacroError("a program number line must hold only O<number>", line, raw.strip())
        if current is None:
            current = programs[0] = _Program(0, line)
        current.blocks.append(_parse_block(compact, line, raw.strip(), comment))
    for prog in programs.values():
        prog.finish()
    return programs


# --------------------------------------------------------------------------------------------
# Execution
# --------------------------------------------------------------------------------------------
class _Frame:
    """One level of execution: a program, its program counter and its local variables."""

    __slots__ = ("program", "pc", "locals", "kind", "repeat", "modal_called")

    def __init__(self, program, locals_, kind, repeat=1, modal_called=False):
        self.program, self.pc, self.locals, self.kind, self.repeat = program, 0, locals_, kind, repeat
        self.modal_called = modal_called        # a macro called by G66.1 (or a program it called)


class _Interpreter:
    """Executes parsed programs block by block."""

    def __init__(self, programs: dict, main: int | None, clock, start, max_blocks: int,
                 variables: Mapping | None, home: Mapping | None, max_call_depth: int,
                 significant_digits: int | None = None, axes: str = "XYZ"):
        if not programs:
            raise MacroError("no program in the text")
        self.programs = programs
        main = next(iter(programs)) if main is None else main
        self.clock = iter(clock) if clock is not None else None
        self.clock_reads = 0
        self.clock_writes: list = []
        self.pos = [float(v) for v in start]
        self.max_blocks = max_blocks
        self.home = {k.upper(): float(v) for k, v in (home or {}).items()}
        self.max_call_depth = max_call_depth
        if significant_digits is not None and not (isinstance(significant_digits, int) and significant_digits >= 1):
            raise MacroError(f"significant_digits must be a positive integer, got {significant_digits!r}")
        self.significant_digits = significant_digits
        if not (isinstance(axes, str) and set("XYZ") <= set(axes) and set(axes) <= set("XYZABCUVW")
                and len(set(axes)) == len(axes)):
            raise MacroError(f"axes must name the machine's axis addresses, X Y Z and any of A B C U V W, "
                             f"each once; got {axes!r}")
        self.axes = axes
        self.common: dict = {}
        main_locals: dict = {}
        for n, v in (variables or {}).items():
            (main_locals if 1 <= n <= 33 else self.common)[n] = None if v is None else float(v)
            if not (1 <= n <= 33 or 100 <= n <= 199 or 500 <= n <= 999):
                raise MacroError(f"cannot preset variable #{n}")
        self.stack = [_Frame(self._program(main), main_locals, "main")]
        # modal state (Fanuc power-on defaults)
        self.motion = 0
        self.absolute = True
        self.metric = True
        self.wcs = 54
        self.feed = None
        self.spindle = None
        self.tool = None
        self.h = None
        self.modal_call = None          # (program number, frame it belongs to)
        self.moves: list = []
        self.events: list = []
        self.blocks_executed = 0
        self.ended_by = None
        self.block = None

    # -- variables ---------------------------------------------------------------------------
    def read_var(self, n: int):
        if n == 0:
            return None
        if 1 <= n <= 33:
            return self.stack[-1].locals.get(n)
        if 100 <= n <= 199 or 500 <= n <= 999:
            return self.common.get(n)
        if n == 3001:
            if self.clock is None:
                raise MacroError("#3001 read but no clock sequence was supplied")
            try:
                value = next(self.clock)
            except StopIteration:
                raise MacroError(f"the clock sequence ran out after {self.clock_reads} reads of #3001") from None
            self.clock_reads += 1
            return float(value)
        if 5001 <= n <= 5003:
            return self.pos[n - 5001]
        if 4001 <= n <= 4130 and any(f.modal_called for f in self.stack):
            raise MacroError(f"#{n} read in a macro called by G66.1: the manual gives #4001..#4130 as the "
                             "modal information up to the preceding block, and which block that is for a "
                             "block turned into a call (its G codes not executed) is left to the control")
        system = {4001: self.motion, 4003: 90 if self.absolute else 91, 4006: 21 if self.metric else 20,
                  4014: self.wcs, 4109: self.feed, 4111: self.h, 4119: self.spindle, 4120: self.tool}
        if n in system:
            v = system[n]
            return None if v is None else float(v)
        raise MacroError(f"variable #{n} is not supported")

    def write_var(self, n: int, v):
        if type(v) is bool:
            raise MacroError("a condition cannot be assigned to a variable")
        if 1 <= n <= 33:
            store = self.stack[-1].locals
        elif 100 <= n <= 199 or 500 <= n <= 999:
            store = self.common
        elif n == 3000:
            raise MacroAlarm(_num(v), self.block.comment if self.block else "")
        elif n == 3001:
            self.clock_writes.append(v)
            return
        else:
            raise MacroError(f"variable #{n} cannot be assigned")
        if v is None:
            store.pop(n, None)
        elif self.significant_digits is not None:
            store[n] = float(f"{float(v):.{self.significant_digits - 1}e}")
        else:
            store[n] = float(v)

    # -- main loop ---------------------------------------------------------------------------
    def run(self) -> MacroRun:
        while self.ended_by is None:
            frame = self.stack[-1]
            blocks = frame.program.blocks
            if frame.pc >= len(blocks):
                if frame.kind == "main":
                    self.ended_by = "end"
                    break
                last = blocks[-1] if blocks else None
                raise MacroError(f"program O{frame.program.number:04d} ends without M99",
                                 last.line if last else frame.program.line, last.text if last else None)
            blk = blocks[frame.pc]
            frame.pc += 1
            self.blocks_executed += 1
            self.block = blk
            if self.blocks_executed > self.max_blocks:
                raise MacroError(f"more than max_blocks={self.max_blocks} blocks executed (runaway loop?)",
                                 blk.line, blk.text)
            try:
                self._execute(blk, frame)
            except MacroError as e:
                if e.line is None:
                    if isinstance(e, MacroAlarm):
                        raise MacroAlarm(e.number, e.alarm_message, blk.line, blk.text) from None
                    raise MacroError(e.message, blk.line, blk.text) from None
                raise
        main = self.stack[0]
        return MacroRun(
            moves=self.moves, events=self.events, common=dict(self.common), locals=dict(main.locals),
            position=tuple(self.pos),
            modal={"motion": self.motion, "absolute": self.absolute, "metric": self.metric, "wcs": self.wcs,
                   "feed": self.feed, "spindle": self.spindle, "tool": self.tool, "h": self.h,
                   "modal_call": None if self.modal_call is None else self.modal_call[0]},
            clock_reads=self.clock_reads, clock_writes=self.clock_writes,
            blocks_executed=self.blocks_executed, ended_by=self.ended_by)

    def _execute(self, blk: _Block, frame: _Frame):
        kind = blk.kind
        if kind == "words":
            self._words(blk, frame)
        elif kind == "assign":
            self.write_var(blk.target(self), blk.value(self))
        elif kind in ("if_goto", "if_then"):
            c = blk.cond(self)
            if type(c) is not bool:
                raise MacroError("IF[...] needs a condition (EQ NE GT GE LT LE)")
            if c and kind == "if_goto":
                self._goto(blk.value(self), frame)
            elif c:
                self.write_var(blk.target(self), blk.value(self))
        elif kind == "goto":
            self._goto(blk.value(self), frame)
        elif kind == "while":
            if blk.cond is not None:
                c = blk.cond(self)
                if type(c) is not bool:
                    raise MacroError("WHILE[...] needs a condition (EQ NE GT GE LT LE)")
                if not c:
                    frame.pc = blk.match + 1
        elif kind == "end":
            frame.pc = blk.match

    def _goto(self, value, frame: _Frame):
        n = _integer(value, "GOTO target")
        where = frame.program.labels.get(n)
        if not where:
            raise MacroError(f"GOTO{n}: no block N{n} in program O{frame.program.number:04d}")
        if len(where) > 1:
            raise MacroError(f"GOTO{n}: N{n} appears {len(where)} times in O{frame.program.number:04d}")
        frame.pc = where[0]

    def _program(self, number: int) -> _Program:
        prog = self.programs.get(number)
        if prog is None:
            raise MacroError(f"program O{number:04d} not found")
        return prog

    # -- word blocks -------------------------------------------------------------------------
    def _words(self, blk: _Block, frame: _Frame):
        words = []
        for letter, fn in blk.words:
            v = fn(self)
            if type(v) is bool:
                raise MacroError(f"address {letter} has a condition as its value")
            if v is not None:               # vacant: the word is omitted
                words.append((letter, float(v)))
        gcodes = [_gcode(v) for letter, v in words if letter == "G"]
        if self.modal_call is not None and self.modal_call[1] is frame and blk.words and "67" not in gcodes:
            return self._modal_called_block(words)
        if "65" in gcodes or "66.1" in gcodes:
            return self._call_block(words, gcodes, frame)
        self._ordinary_block(blk, words, gcodes)

    def _apply_modal_g(self, g: str) -> bool:
        """Apply a plain modal G code; False if ``g`` is not one."""
        if g in ("0", "1", "2", "3"):
            self.motion = int(g)
        elif g in ("90", "91"):
            self.absolute = g == "90"
        elif g in ("20", "21"):
            self.metric = g == "21"
        elif g in ("54", "55", "56", "57", "58", "59"):
            self.wcs = int(g)
            self.events.append(Event("WCS", float(g), self.block.line))
        elif g in ("17", "40", "49", "80", "94"):
            pass
        elif g in ("18", "19", "41", "42", "66"):
            raise MacroError(f"G{g} is not supported by this interpreter")
        else:
            return False
        return True

    def _arguments(self, words, skip: str) -> dict:
        args = {}
        for letter, v in words:
            if letter in skip:
                continue
            if letter not in ARG_VARS:
                raise MacroError(f"address {letter} cannot be a macro argument")
            if letter in self.axes and letter not in "XYZ":
                raise MacroError(f"address {letter} is an axis of this machine (axes {self.axes}): whether a "
                                 "call passes it as an argument or moves the axis is left to the control")
            n = ARG_VARS[letter]
            if n in args:
                raise MacroError(f"address {letter} given twice (argument specification II is not supported)")
            args[n] = v
        return args

    def _call_macro(self, number: int, args: dict, modal: bool = False):
        prog = self._program(number)
        depth = sum(1 for f in self.stack if f.kind == "macro")
        if depth >= self.max_call_depth:
            raise MacroError(f"macro calls nested deeper than {self.max_call_depth} levels")
        inherited = any(f.modal_called for f in self.stack)
        self.stack.append(_Frame(prog, dict(args), "macro", modal_called=modal or inherited))

    def _check_modal_call(self, args: dict, what: str):
        """What a G66.1 call may be here: a G01 block with a move (an X, Y or Z word)."""
        if not any(ARG_VARS[a] in args for a in "XYZ"):
            raise MacroError(f"{what} without an X, Y or Z word: whether a block with no move calls the "
                             "macro is left to the control (give the call a move, or cancel with G67)")
        if self.motion != 1:
            name = {0: "G00 (a rapid)", 2: "G02 (an arc)", 3: "G03 (an arc)"}[self.motion]
            raise MacroError(f"{what} in {name}: the macro would have to tell a rapid or an arc from a cut; "
                             "only G01 blocks may be called (G67 before a rapid or an arc)")

    def _call_block(self, words, gcodes, frame):
        """A G65 or G66.1 block: P program, optional L, the rest are arguments."""
        if len(gcodes) != 1:
            raise MacroError("G65/G66.1 must be the only G code in its block")
        g = gcodes[0]
        values = dict((letter, v) for letter, v in words if letter in "PL")
        if "P" not in values:
            raise MacroError(f"G{g} without P (program number)")
        if values.get("L", 1.0) != 1.0:
            raise MacroError("G65 with a repeat count L is not supported")
        number = _integer(values["P"], "program number P")
        args = self._arguments(words, "GPL")
        if g == "66.1":
            if self.modal_call is not None:
                raise MacroError("G66.1 while a modal call is already active")
            self._program(number)
            self._check_modal_call(args, "a G66.1 block")
            self.modal_call = (number, frame)
        self._call_macro(number, args, modal=g == "66.1")

    def _modal_called_block(self, words):
        """Under G66.1: the block is not executed; its words become the macro's arguments."""
        for letter, v in words:
            if letter == "G":
                raise MacroError(f"G{_gcode(v)} in a block under G66.1: whether the control executes it or "
                                 "only hands the block to the macro is left to the control (G67 first)")
            elif letter == "M" and v in (2.0, 30.0, 98.0, 99.0):
                raise MacroError(f"M{v:02.0f} while the G66.1 modal call is active (cancel with G67 first)")
        args = self._arguments(words, "G")
        self._check_modal_call(args, "a block under G66.1")
        self._call_macro(self.modal_call[0], args, modal=True)

    def _ordinary_block(self, blk: _Block, words, gcodes):
        w, mcodes = {}, []
        for letter, v in words:
            if letter == "G":
                continue
            if letter == "M":
                mcodes.append(_integer(v, "M code"))
                continue
            if letter not in _ORDINARY_LETTERS:
                raise MacroError(f"address {letter} is not supported here")
            if letter in w:
                raise MacroError(f"address {letter} given twice")
            w[letter] = v
        special = None
        for g in gcodes:
            if self._apply_modal_g(g):
                continue
            if g in ("4", "28"):
                if special:
                    raise MacroError(f"G{special} and G{g} in one block")
                special = g
            elif g == "43":
                self.events.append(Event("G43", w.get("H", self.h), blk.line))
            elif g == "67":
                self.modal_call = None
            else:
                raise MacroError(f"G{g} is not supported by this interpreter")
        for m in mcodes:
            if m not in KNOWN_M:
                raise MacroError(f"M{m:02d} is not supported by this interpreter")
        if "P" in w and special != "4" and 98 not in mcodes:
            raise MacroError("address P without G04, G65, G66.1 or M98")
        if "L" in w and 98 not in mcodes:
            raise MacroError("address L without M98")
        if "F" in w:
            self.feed = w["F"]
        if "S" in w:
            self.spindle = w["S"]
            self.events.append(Event("S", w["S"], blk.line))
        if "T" in w:
            self.tool = _integer(w["T"], "T")
            self.events.append(Event("T", float(self.tool), blk.line))
        if "H" in w:
            self.h = _integer(w["H"], "H")
        if special == "4":
            if any(a in w for a in "YZIJR"):
                raise MacroError("G04 takes only P or X")
            self.events.append(Event("G04", w.get("P", w.get("X")), blk.line))
        elif special == "28":
            self._g28(w, blk)
        else:
            self._motion(w, blk)
        for m in mcodes:
            if m not in (98, 99):
                self.events.append(Event("M", float(m), blk.line))
            if m in (2, 30):
                self.ended_by = f"M{m:02d}"
            elif m == 98:
                if "P" not in w:
                    raise MacroError("M98 without P")
                repeat = _integer(w.get("L", 1.0), "L")
                frame = self.stack[-1]
                if sum(1 for f in self.stack if f.kind == "sub") >= 10:
                    raise MacroError("M98 subprograms nested deeper than 10 levels")
                if repeat > 0:
                    self.stack.append(_Frame(self._program(_integer(w["P"], "P")), frame.locals, "sub", repeat))
            elif m == 99:
                self._return()

    def _return(self):
        frame = self.stack[-1]
        if frame.kind == "main":
            raise MacroError("M99 in the main program")
        if frame.kind == "sub" and frame.repeat > 1:
            frame.repeat -= 1
            frame.pc = 0
            return
        self.stack.pop()

    # -- motion ------------------------------------------------------------------------------
    def _target(self, w) -> list:
        target = list(self.pos)
        for k, a in enumerate("XYZ"):
            if a in w:
                target[k] = w[a] if self.absolute else self.pos[k] + w[a]
        return target

    def _emit(self, kind, target, blk, i=None, j=None):
        feed = None
        if kind != "rapid":
            if self.feed is None or self.feed <= 0:
                raise MacroError("cutting move without a feed rate F")
            feed = self.feed
        main = self.stack[0]
        main_line = main.program.blocks[main.pc - 1].line if main.pc else blk.line
        self.moves.append(Move(kind, target[0], target[1], target[2], i, j, feed, blk.line,
                               tuple(self.pos), main_line))
        self.pos = list(target)

    def _motion(self, w, blk):
        has_axes = any(a in w for a in "XYZ")
        arc_words = [a for a in "IJR" if a in w]
        if not has_axes and not arc_words:
            return
        if self.motion in (0, 1):
            if arc_words:
                raise MacroError(f"{'/'.join(arc_words)} in a G0{self.motion} block")
            self._emit("rapid" if self.motion == 0 else "feed", self._target(w), blk)
            return
        target = self._target(w)
        sx, sy = self.pos[0], self.pos[1]
        ex, ey = target[0], target[1]
        if "R" in w:
            if "I" in w or "J" in w:
                raise MacroError("an arc with both R and I/J")
            i, j = self._r_centre(w["R"], sx, sy, ex, ey)
        elif arc_words:
            i, j = w.get("I", 0.0), w.get("J", 0.0)
        else:
            raise MacroError(f"G0{self.motion} without I, J or R")
        r0 = math.hypot(i, j)
        r1 = math.hypot(sx + i - ex, sy + j - ey)
        if r0 == 0 or abs(r0 - r1) > ARC_TOLERANCE:
            raise MacroError(f"arc end point is not on the circle (start radius {r0:.4f}, end radius {r1:.4f})")
        self._emit("cw" if self.motion == 2 else "ccw", target, blk, i, j)

    def _r_centre(self, r, sx, sy, ex, ey):
        """Centre offsets (I, J) of an R-form arc: R > 0 the short way, R < 0 the long way."""
        dx, dy = ex - sx, ey - sy
        d = math.hypot(dx, dy)
        if d == 0:
            raise MacroError("an R arc cannot be a full circle")
        h2 = r * r - d * d / 4
        if h2 < 0:
            if d / 2 - abs(r) > ARC_TOLERANCE:
                raise MacroError(f"R{r:g} is too small for a chord of {d:.4f}")
            h2 = 0.0
        h = math.sqrt(h2)
        side = 1.0 if self.motion == 3 else -1.0     # short CCW arc: centre left of the chord
        if r < 0:
            side = -side
        cx = (sx + ex) / 2 + side * h * (-dy / d)
        cy = (sy + ey) / 2 + side * h * (dx / d)
        return cx - sx, cy - sy

    def _g28(self, w, blk):
        """G28: rapid to the intermediate point, then to ``home`` for the axes that have one."""
        axes = [a for a in "XYZ" if a in w]
        if any(a in w for a in "IJR"):
            raise MacroError("G28 takes only X, Y, Z")
        self.events.append(Event("G28", None, blk.line))
        mid = self._target(w)
        if mid != self.pos:
            self._emit("rapid", mid, blk)
        home = list(self.pos)
        for k, a in enumerate("XYZ"):
            if a in axes and a in self.home:
                home[k] = self.home[a]
        if home != self.pos:
            self._emit("rapid", home, blk)


# --------------------------------------------------------------------------------------------
# Entry points
# --------------------------------------------------------------------------------------------
def run_program(text: str, clock: Iterable | None = None, start=(0.0, 0.0, 0.0),
                max_blocks: int = 10_000_000, *, variables: Mapping | None = None,
                home: Mapping | None = None, main: int | None = None,
                max_call_depth: int = 4, significant_digits: int | None = None, axes: str = "XYZ") -> MacroRun:
    """Execute a Fanuc program text and return what it did.

    clock       values returned by successive reads of #3001 (milliseconds); None: reading it is an error
    start       machine position (work coordinates) before the first block
    max_blocks  executed blocks (all levels) before the run is declared a runaway
    variables   initial values, e.g. {500: 2.0}; locals #1..#33 preset the main program level
    home        G28 home per axis in work coordinates, e.g. {"Z": 150.0}; axes without one stay
                at the intermediate point (G28 is always recorded as an Event)
    main        program number to start with (default: the first program in the text)
    max_call_depth  G65/G66.1 nesting limit (4 on a Series 16i/18i, 5 on later controls)
    significant_digits  round every stored value to this many significant digits (None: exact)
    axes        the simulated machine's axis addresses, e.g. "XYZB" for a machine with a B axis: a
                macro argument that is one of them (other than X, Y, Z) is refused
    """
    programs = parse_programs(text)
    return _Interpreter(programs, main, clock, start, max_blocks, variables, home, max_call_depth,
                        significant_digits, axes).run()


def eval_expression(expr: str, variables: Mapping | None = None, clock: Iterable | None = None):
    """Evaluate one expression or condition, e.g. ``eval_expression("FIX[#1/10]", {1: 37})`` -> 3.0.

    Returns a float, None (vacant) or a bool (for a condition).
    """
    compact = re.sub(r"\s+", "", expr).upper()
    try:
        _check_brackets(compact)
        p = _Parser(compact)
        fn = p.condition()
        if not p.at_end():
            raise MacroError(f"unexpected '{compact[p.pos:]}'")
    except MacroError as e:
        raise MacroError(e.message, None, expr) from None
    it = _Interpreter({0: _Program(0, 0)}, None, clock, (0.0, 0.0, 0.0), 1, variables, None, 4)
    return fn(it)
