"""The fast path of the Part 21 reader: the DATA section's plain instances by one compiled regex.

A big file (explicit toolpaths: a million CARTESIAN_POINTs and POLYLINEs) is nearly all instances
of one plain form, ``#id= NAME(params);`` whose parameters are numbers, references, simple strings,
enumerations, ``$``, ``*`` and flat lists of those.  One compiled regex (:data:`INSTANCE_RE`)
recognises such an instance whole, and only then are its tokens turned into values; nothing is
kept per token but the values.  Everything else (the header, comments, complex instances, typed
parameters, strings with escapes, deeper lists) goes statement by statement to the exact reader
(:mod:`.part21`'s token parser), which also has the last word on every error: whenever this
path meets something wrong or unusual (an undefined reference, a duplicate id, a syntax error,
several DATA sections), it gives up and the exact reader parses the whole text again, so errors
and their positions are the exact reader's.  The regex accepts only what the exact reader
accepts, and tokenises it the same way (numbers need a digit before the point, an exponent only
after it; see part21's scanner), so both give equal values.
"""
from __future__ import annotations

import re

_WS = r"[ \t\r\n]*+"
_NUMBER = r"(?>[+-]?[0-9]+(?:\.[0-9]*(?:[eE][+-]?[0-9]+)?)?)"
_SCALAR = rf"(?:\#[0-9]+|{_NUMBER}|'[^'\\\r\n]*'|\.[A-Za-z_][A-Za-z0-9_]*\.|[$*])"
_FLAT = rf"\({_WS}(?:{_SCALAR}{_WS}(?:,{_WS}{_SCALAR}{_WS})*)?\)"
_PARAM = rf"(?:{_SCALAR}|{_FLAT})"
# the common shape: a string and a flat list of numbers (CARTESIAN_POINT, DIRECTION) or of
# references (POLYLINE), whose values are read by splitting
_NUMBERS = rf"{_NUMBER}(?:{_WS},{_WS}{_NUMBER})*"
_REFS = rf"\#[0-9]+(?:{_WS},{_WS}\#[0-9]+)*"
# groups: id, entity name, then either the string, the numbers or the references of the common
# shape, or all the parameters between the outer parentheses
INSTANCE_RE = re.compile(
    rf"{_WS}\#([0-9]+){_WS}={_WS}([A-Za-z_][A-Za-z0-9_]*){_WS}\("
    rf"(?:{_WS}'([^'\\\r\n]*)'{_WS},{_WS}\({_WS}(?:({_NUMBERS})|({_REFS})){_WS}\){_WS}"
    rf"|({_WS}(?:{_PARAM}{_WS}(?:,{_WS}{_PARAM}{_WS})*)?))\){_WS};")
# the tokens of other parameters INSTANCE_RE has matched (white space and commas fall between them)
_TOKEN_RE = re.compile(r"[()]|'[^']*'|[^\s,()]+")
# a statement up to its ';' (strings and comments may hold ';'); None if a string or comment is open
_STATEMENT_RE = re.compile(r"(?:[^;'/]++|'[^']*+'|/\*.*?\*/|/)*+;", re.DOTALL)
_SEPARATORS = r"(?:[ \t\r\n]|/\*.*?\*/)*"
_DATA_RE = re.compile(rf"{_SEPARATORS}DATA\b", re.DOTALL | re.IGNORECASE)
_ENDSEC_RE = re.compile(rf"{_SEPARATORS}ENDSEC[ \t\r\n]*;", re.DOTALL)
_END_RE = re.compile(rf"{_SEPARATORS}END-ISO-10303-21[ \t\r\n]*;{_SEPARATORS}\Z", re.DOTALL)
MAX_RUN = 5_000     # statements read together by the exact reader (its token list stays small)
MINI_HEAD = "ISO-10303-21;HEADER;ENDSEC;DATA;"      # one line: a statement's own lines count from 1
MINI_TAIL = "ENDSEC;END-ISO-10303-21;"


class GiveUp(Exception):
    """Something this path does not read: the exact reader parses the whole text."""


def parse(text: str, exact, kinds):
    """The parsed file, or :class:`GiveUp`.

    ``exact(text, references)`` is the exact reader (raising on errors; ``references=False``
    leaves references to undefined instances unchecked); ``kinds`` gives the value types
    (``Ref``, ``Enum``, ``Instance``, ``UNSET``, ``DERIVED``, ``iter_refs``) of :mod:`.part21`."""
    if text.startswith("\ufeff"):
        text = text[1:]
    start = _data_start(text)
    result = _exact_part(text[:start] + MINI_TAIL, exact, True)
    if len(result.data_sections) != 1 or result.instances:
        raise GiveUp
    instances = result.instances
    refs: list = []
    lines = _Lines(text, start)
    tokens = _Tokens(kinds, refs)
    Instance, Ref = kinds.Instance, kinds.Ref
    pos = start
    match = INSTANCE_RE.match
    odd = 0
    while True:
        # one instance at a time from where the last ended (a search ahead would rescan the rest
        # of the text after every statement the exact reader takes)
        while (m := match(text, pos)) is not None:
            ident, name, label, numbers, ids, body = m.groups()
            ident = int(ident)
            if ident in instances:
                raise GiveUp
            if numbers is not None:
                items = numbers.split(",")
                if numbers.count(".") == len(items):
                    params = [label, list(map(float, items))]
                else:
                    params = [label, [float(x) if "." in x else int(x) for x in items]]
            elif ids is not None:
                ids = list(map(int, ids.replace("#", "").split(",")))
                refs += ids
                params = [label, list(map(Ref, ids))]
            else:
                params = tokens(_TOKEN_RE.findall(body))
            instances[ident] = Instance(ident, name.upper(), params, lines.at(m.start(1)))
            pos = m.end()
        # statements the regex does not take, up to the next it does (or ENDSEC), read together
        # by the exact reader (one by one, a file of them took twice as long as the exact reader)
        first, count = pos, 0
        while True:
            statement = _STATEMENT_RE.match(text, pos)
            if statement is None:
                raise GiveUp
            ended = _ENDSEC_RE.fullmatch(statement.group(0)) is not None
            if ended:
                break
            pos, count = statement.end(), count + 1
            if count >= MAX_RUN or match(text, pos) is not None:
                break
        if count:
            _statements(text[first:pos], count, exact, kinds, lines.at(first), instances, refs)
            odd += count
            if odd > MAX_RUN and 2 * odd > len(instances):
                raise GiveUp        # mostly statements the regex does not take: the exact reader is quicker
        if ended:
            break
    if not _END_RE.match(text, statement.end()) or not instances.keys() >= set(refs):
        raise GiveUp
    return result


def _data_start(text: str) -> int:
    """Where the first DATA section's instances begin: after its ``DATA;`` statement."""
    pos = 0
    while True:
        statement = _STATEMENT_RE.match(text, pos)
        if statement is None or statement.end() == pos:
            raise GiveUp
        pos = statement.end()
        if _DATA_RE.match(statement.group(0)):
            return pos


class _Lines:
    """Line numbers of positions met in ascending order (line breaks: LF, CR LF or a CR alone;
    positions never split a CR LF: they are at a '#' or a statement's start)."""

    def __init__(self, text: str, start: int):
        self.text, self.carriage = text, "\r" in text
        self.line, self.counted = 1, 0
        self.at(start)

    def at(self, pos: int) -> int:
        text, start = self.text, self.counted
        n = text.count("\n", start, pos)
        if self.carriage:
            n += text.count("\r", start, pos) - text.count("\r\n", start, pos)
        self.line += n
        self.counted = pos
        return self.line


def _exact_part(text: str, exact, references: bool):
    try:
        return exact(text, references)
    except Exception:
        raise GiveUp from None


def _statements(statements: str, count: int, exact, kinds, line: int, instances: dict, refs: list) -> None:
    """The ``count`` instances of statements that begin on ``line``, read by the exact reader, into
    ``instances``; the ids they refer to into ``refs``."""
    part = _exact_part(MINI_HEAD + statements + MINI_TAIL, exact, False)
    if len(part.data_sections) != 1 or len(part.instances) != count:
        raise GiveUp
    for ident, instance in part.instances.items():
        if ident in instances:
            raise GiveUp
        instance.line += line - 1
        instances[ident] = instance
        refs.extend(ref.id for ref in kinds.iter_refs(instance))


class _Tokens:
    """Tokens of parameters INSTANCE_RE has matched -> values, as part21's parser makes them;
    the ids referred to are added to ``refs``."""

    def __init__(self, kinds, refs: list):
        self.kinds = kinds
        self.refs = refs

    def __call__(self, tokens: list) -> list:
        Ref, Enum, unset, derived = self.kinds.Ref, self.kinds.Enum, self.kinds.UNSET, self.kinds.DERIVED
        add_ref = self.refs.append
        top = current = []
        outer = None
        for tok in tokens:
            c = tok[0]
            if c == "#":
                ident = int(tok[1:])
                add_ref(ident)
                current.append(Ref(ident))
            elif c == "'":
                current.append(tok[1:-1])
            elif c == "(":
                outer, current = current, []
                outer.append(current)
            elif c == ")":
                current = outer
            elif c == "$":
                current.append(unset)
            elif c == ".":
                name = tok[1:-1].upper()
                current.append(True if name == "T" else False if name == "F" else Enum(name))
            elif c == "*":
                current.append(derived)
            else:
                current.append(float(tok) if "." in tok else int(tok))
        return top
