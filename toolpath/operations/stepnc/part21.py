"""ISO 10303-21 (STEP Part 21) exchange structure: the values and the reader.

A Part 21 file is ``ISO-10303-21;``, a ``HEADER;`` section of entities without ids
(FILE_DESCRIPTION, FILE_NAME, FILE_SCHEMA), one or more ``DATA;`` sections of numbered
instances ``#12=NAME(params);`` or complex instances ``#12=(A(..)B(..));``, and
``END-ISO-10303-21;``.  This module knows nothing about any EXPRESS schema: it turns the
text into plain Python values and back.

Parameter values map to Python as follows:

=====================  ==========================================
Part 21                Python
=====================  ==========================================
``12``                 ``int``
``12.``, ``1.5E-3``    ``float``
``'it''s'``            ``str`` (escapes decoded)
``.RIGHT.``            ``Enum("RIGHT")``
``.T.`` / ``.F.``      ``True`` / ``False``
``.U.``                ``UNKNOWN`` (which is ``Enum("U")``)
``$``                  ``UNSET``
``*``                  ``DERIVED``
``#42``                ``Ref(42)``
``(a, b)``             ``list``
``LENGTH_MEASURE(5.)`` ``Typed("LENGTH_MEASURE", 5.0)``
=====================  ==========================================

Type names, keywords and enumeration values are upper-cased on reading (the standard
requires upper case; lower case is tolerated).  In strings, line breaks and the print
directives ``\\N\\`` ``\\F\\`` are not part of the value, and a backslash that starts no
escape is kept as is (Windows paths in FILE_NAME).  Binary values (``"0F3"``) and the
edition 3 additions (ANCHOR, REFERENCE and SIGNATURE sections, ``@`` value instances,
``#NAME`` constants) are rejected with a :class:`Part21Error`.

The writer (``write_part21``, ``Part21Writer``, ``format_real`` ...) is :mod:`part21_writer`.
"""
from __future__ import annotations

import bisect
import gc
import itertools
import numbers
import re
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any, Iterator, NoReturn, Union

from ...ir.errors import InputError
from ...engines.textfile import read_text
from . import part21_scan

__all__ = [
    "Part21Error", "Ref", "Enum", "Typed", "Unset", "Derived", "UNSET", "DERIVED", "UNKNOWN",
    "Entity", "Instance", "ComplexInstance", "Part21File", "parse_part21", "read_part21", "iter_refs",
]


# --------------------------------------------------------------------------- values


class Part21Error(InputError):
    """A syntax or consistency error, located by 1-based line and column."""

    def __init__(self, message: str, line: int, column: int, instance_id: int | None = None):
        self.message = message
        self.line = line
        self.column = column
        self.instance_id = instance_id
        super().__init__(message, line, column, instance_id)

    def __str__(self) -> str:
        where = f"line {self.line}, column {self.column}"
        if self.instance_id is not None:
            where += f" (#{self.instance_id})"
        return f"{where}: {self.message}"


@dataclass(frozen=True)
class Ref:
    """A reference ``#id`` to an entity instance."""

    id: int

    def __repr__(self) -> str:
        return f"#{self.id}"


@dataclass(frozen=True)
class Enum:
    """An enumeration value such as ``.RIGHT.`` (name stored without the dots)."""

    name: str

    def __repr__(self) -> str:
        return f".{self.name}."


@dataclass(frozen=True)
class Typed:
    """A typed parameter such as ``LENGTH_MEASURE(5.)``: a defined type and its value."""

    type_name: str
    value: Any


@dataclass(frozen=True)
class Unset:
    """``$``: the attribute has no value.  Use the :data:`UNSET` constant."""

    def __repr__(self) -> str:
        return "UNSET"


@dataclass(frozen=True)
class Derived:
    """``*``: the value is derived (redeclared attribute).  Use :data:`DERIVED`."""

    def __repr__(self) -> str:
        return "DERIVED"


UNSET = Unset()
DERIVED = Derived()
UNKNOWN = Enum("U")  # the LOGICAL value .U.


@dataclass
class Entity:
    """A header entity, e.g. ``FILE_NAME(...)``.  ``line`` is ignored by ``==``."""

    type_name: str
    params: list
    line: int = field(default=0, compare=False)


@dataclass
class Instance:
    """A simple entity instance ``#id=TYPE_NAME(params);``.  ``line`` is ignored by ``==``."""

    id: int
    type_name: str
    params: list
    line: int = field(default=0, compare=False)

    @property
    def ref(self) -> Ref:
        return Ref(self.id)

    @property
    def type_names(self) -> tuple[str, ...]:
        return (self.type_name,)

    def params_of(self, type_name: str) -> list:
        """The parameters if this instance is of ``type_name`` (same API as complex ones)."""
        if type_name.upper() != self.type_name:
            raise KeyError(f"#{self.id} is {self.type_name}, not {type_name.upper()}")
        return self.params


@dataclass
class ComplexInstance:
    """A complex instance ``#id=(A(..)B(..));``: ``parts`` is a list of (type_name, params).

    Part 21 writes the parts in alphabetical order of their type names; the order read
    is kept as is.
    """

    id: int
    parts: list[tuple[str, list]]
    line: int = field(default=0, compare=False)

    @property
    def ref(self) -> Ref:
        return Ref(self.id)

    @property
    def type_names(self) -> tuple[str, ...]:
        return tuple(name for name, _ in self.parts)

    def params_of(self, type_name: str) -> list:
        """The parameters of the part named ``type_name``."""
        wanted = type_name.upper()
        for name, params in self.parts:
            if name == wanted:
                return params
        raise KeyError(f"#{self.id} has no part {wanted} (parts: {', '.join(self.type_names)})")


AnyInstance = Union[Instance, ComplexInstance]


def iter_refs(value: Any) -> Iterator[Ref]:
    """Every :class:`Ref` inside a value, a parameter list or an instance, depth first."""
    if isinstance(value, Ref):
        yield value
    elif isinstance(value, (list, tuple)):
        for item in value:
            yield from iter_refs(item)
    elif isinstance(value, Typed):
        yield from iter_refs(value.value)
    elif isinstance(value, Instance):
        yield from iter_refs(value.params)
    elif isinstance(value, ComplexInstance):
        for _, params in value.parts:
            yield from iter_refs(params)


@dataclass
class Part21File:
    """A parsed (or assembled) exchange structure.

    ``instances`` maps id to instance over all DATA sections.  ``data_sections`` holds
    the parameters of each ``DATA(...)`` header (``[]`` for a bare ``DATA;``); the
    writer always writes a single bare ``DATA;`` section.
    """

    header: list[Entity] = field(default_factory=list)
    instances: dict[int, AnyInstance] = field(default_factory=dict)
    data_sections: list[list] = field(default_factory=list)

    def header_entity(self, type_name: str) -> Entity | None:
        wanted = type_name.upper()
        for entity in self.header:
            if entity.type_name == wanted:
                return entity
        return None

    @property
    def schema(self) -> list[str]:
        """The schema names of FILE_SCHEMA, e.g. ``['MACHINING_SCHEMA', 'MILLING_SCHEMA']``."""
        entity = self.header_entity("FILE_SCHEMA")
        if entity is None or not entity.params or not isinstance(entity.params[0], list):
            return []
        return [name for name in entity.params[0] if isinstance(name, str)]

    def get(self, ref_or_id: Ref | int) -> AnyInstance:
        key = ref_or_id.id if isinstance(ref_or_id, Ref) else ref_or_id
        try:
            return self.instances[key]
        except KeyError:
            raise KeyError(f"no instance #{key}") from None

    def resolve(self, value: Any) -> Any:
        """A Ref becomes its instance; lists are resolved item by item; others unchanged."""
        if isinstance(value, Ref):
            return self.get(value)
        if isinstance(value, list):
            return [self.resolve(item) for item in value]
        return value

    def by_type(self, type_name: str) -> list[AnyInstance]:
        """Instances of ``type_name`` (complex ones included if they have that part), by id."""
        wanted = type_name.upper()
        return [self.instances[i] for i in sorted(self.instances)
                if wanted in self.instances[i].type_names]


# --------------------------------------------------------------------------- scanner

# Each match is (separators, token).  Separators (white space, comments, the print
# directives \N\ and \F\) are consumed possessively so they never backtrack; the last
# token alternative takes any single character, so the matches tile the whole text and
# a token list plus the separator lengths give every token's position.  A single
# character token that is not punctuation, a digit or a letter is a lexical error,
# reported when the parser reaches it (see _Parser.bad_token).
_SCAN_RE = re.compile(r"""
 ((?:[ \t\r\n\f\v]|\\[NF]\\|/\*.*?\*/)*+)
 (  [=;(),$*]
  | \#[0-9]+
  | [+-]?[0-9]+(?:\.[0-9]*(?:[eE][+-]?[0-9]+)?)?
  | '[^']*(?:''[^']*)*'
  | \.[A-Za-z_][A-Za-z0-9_]*\.
  | (?:END-)?ISO-10303-21
  | !?[A-Za-z_][A-Za-z0-9_]*
  | .
  | \Z
 )""", re.VERBOSE | re.DOTALL)

_PUNCT = frozenset("=;(),$*")
_DIGITS = frozenset("0123456789")
_NUMBER_START = frozenset("0123456789+-")
_LETTERS = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_")
_MAGIC = ("ISO-10303-21", "END-ISO-10303-21")
_SECTIONS_ED3 = ("ANCHOR", "REFERENCE", "SIGNATURE")

_SPECIAL_IN_STRING = re.compile(r"['\\\r\n]")
_ESCAPE_RE = re.compile(r"""\\(?:
   (?P<backslash>\\)
 | S\\(?P<s>''|.)
 | P(?P<page>[A-I])\\
 | X\\(?P<x>[0-9A-Fa-f]{2})
 | X2\\(?P<x2>[0-9A-Fa-f]*)\\X0\\
 | X4\\(?P<x4>[0-9A-Fa-f]*)\\X0\\
 | (?P<print>[NF])\\
)""", re.VERBOSE | re.DOTALL)


class _StringError(Exception):
    """A malformed escape at ``offset`` in a string body; the parser adds the position."""

    def __init__(self, message: str, offset: int):
        super().__init__(message)
        self.message = message
        self.offset = offset


def _fail(message: str, offset: int) -> NoReturn:
    raise _StringError(message, offset)


def _decode_string(raw: str) -> str:
    """Decode the body of a Part 21 string (without the outer quotes).

    Malformed escapes raise :class:`_StringError`.  Line breaks
    and the print directives ``\\N\\`` ``\\F\\`` are not part of the value.  A backslash
    that starts no known directive is kept literally (Windows paths in FILE_NAME).
    """
    if "'" not in raw and "\\" not in raw and "\n" not in raw and "\r" not in raw:
        return raw
    out: list[str] = []
    page = 1  # ISO 8859 part used by \S\
    i = 0
    while True:
        m = _SPECIAL_IN_STRING.search(raw, i)
        if m is None:
            out.append(raw[i:])
            return "".join(out)
        j = m.start()
        out.append(raw[i:j])
        c = raw[j]
        if c == "'":  # the scanner guarantees it is doubled
            out.append("'")
            i = j + 2
            continue
        if c in "\r\n":
            i = j + 1
            continue
        e = _ESCAPE_RE.match(raw, j)
        if e is None:
            if raw.startswith(("\\X2\\", "\\X4\\"), j):
                _fail(f"unterminated or malformed {raw[j:j + 4]} escape (expected hex digits and \\X0\\)", j)
            if raw.startswith("\\X\\", j):
                _fail("\\X\\ must be followed by two hex digits", j)
            out.append("\\")
            i = j + 1
            continue
        kind = e.lastgroup
        if kind == "backslash":
            out.append("\\")
        elif kind == "s":
            code = ord(e.group("s")[0]) + 128
            if code > 255:
                _fail("\\S\\ must be followed by a basic character", j)
            out.append(bytes([code]).decode(f"iso8859-{page}", errors="replace"))
        elif kind == "page":
            page = ord(e.group("page")) - ord("A") + 1
        elif kind == "x":
            out.append(chr(int(e.group("x"), 16)))
        elif kind == "x2":
            digits = e.group("x2")
            if len(digits) % 4:
                _fail("\\X2\\ needs groups of 4 hex digits", j)
            out.append(bytes.fromhex(digits).decode("utf-16-be", errors="surrogatepass"))
        elif kind == "x4":
            digits = e.group("x4")
            if len(digits) % 8:
                _fail("\\X4\\ needs groups of 8 hex digits", j)
            for k in range(0, len(digits), 8):
                code = int(digits[k:k + 8], 16)
                if code > 0x10FFFF:
                    _fail(f"\\X4\\ code {digits[k:k + 8]} is beyond Unicode", j)
                out.append(chr(code))
        # kind == "print": \N\ or \F\, ignored
        i = e.end()


MAX_NESTING = 100   # lists inside lists: real files nest a few levels; deeper is refused, not a RecursionError


class _Parser:
    """Scan the whole text into token strings, then recursive descent over them.

    Tokens are kept as their source text and converted where the grammar uses them;
    positions are computed only for errors and instance line numbers.
    """

    def __init__(self, text: str):
        if text.startswith("\ufeff"):
            text = text[1:]
        self.text = text
        # the last character of each line break: LF, CR LF, or a CR alone (a file with CR line
        # ends was all "line 1, column 3929")
        self.newlines = [m.end() - 1 for m in re.finditer("\r\n|\r|\n", text)]
        pairs = _SCAN_RE.findall(text)
        while pairs and pairs[-1][1] == "":
            pairs.pop()
        self.toks: list[str] = [tok for _, tok in pairs]
        self.toks.append("")  # end of file
        self.ends = list(itertools.accumulate(map(len, map("".join, pairs))))
        self.ends.append(len(text))
        self.i = 0
        self.instance_id: int | None = None
        self.ref_sites: list[int] = []  # token indices of references, checked at the end
        self.instance_starts: list[tuple[int, int]] = []  # (token index, id), ascending
        self.depth = 0  # lists being read, one inside the other

    # ---- positions and errors

    def pos(self, k: int) -> int:
        return self.ends[k] - len(self.toks[k])

    def where(self, pos: int) -> tuple[int, int]:
        line = bisect.bisect_left(self.newlines, pos)  # newlines before pos
        start = self.newlines[line - 1] + 1 if line else 0
        return line + 1, pos - start + 1

    def fail(self, message: str, pos: int, instance_id: int | None) -> NoReturn:
        line, column = self.where(pos)
        raise Part21Error(message, line, column, instance_id)

    def fail_at(self, k: int, expected: str) -> NoReturn:
        """Report token k: its own lexical error if it has one, else what was expected."""
        message = self.bad_token(k) or f"expected {expected}, found {self.describe(k)}"
        self.fail(message, self.pos(k), self.instance_id)

    def describe(self, k: int) -> str:
        tok = self.toks[k]
        if tok == "":
            return "end of file"
        return repr(tok if len(tok) <= 30 else tok[:27] + "...")

    def bad_token(self, k: int) -> str | None:
        tok = self.toks[k]
        if len(tok) != 1 or tok in _PUNCT or tok in _DIGITS or tok in _LETTERS:
            return None
        after = self.text[self.pos(k) + 1:self.pos(k) + 2]
        if tok == "'":
            return "unterminated string"
        if tok == "/" and after == "*":
            return "unterminated comment"
        if tok == '"':
            return 'binary values ("...") are not supported'
        if tok == "." and after in _DIGITS:
            return "a real needs a digit before the decimal point (write 0.5, not .5)"
        if tok == "@" or (tok == "#" and after in _LETTERS):
            return f"{tok}{after}...: edition 3 value and constant names are not supported"
        if tok.isprintable() and not tok.isspace():
            return f"unexpected character {tok!r}"
        return f"unexpected character U+{ord(tok):04X}"

    # ---- token helpers

    def expect(self, tok: str, what: str | None = None) -> None:
        if self.toks[self.i] != tok:
            self.fail_at(self.i, what or repr(tok))
        self.i += 1

    def is_keyword(self, k: int) -> bool:
        tok = self.toks[k]
        return (tok[:1] in _LETTERS or (tok[:1] == "!" and len(tok) > 1)) and tok not in _MAGIC

    def at_keyword(self, *names: str) -> bool:
        return self.is_keyword(self.i) and self.toks[self.i].upper() in names

    def keyword(self, what: str = "an entity name") -> str:
        if not self.is_keyword(self.i):
            self.fail_at(self.i, what)
        self.i += 1
        return self.toks[self.i - 1].upper()

    # ---- grammar

    def parse_file(self, references: bool = True) -> Part21File:
        result = Part21File()
        self.expect("ISO-10303-21", "'ISO-10303-21;' at the start of the file")
        self.expect(";")
        if not self.at_keyword("HEADER"):
            self.fail_at(self.i, "'HEADER;'")
        self.i += 1
        self.expect(";")
        result.header = self.parse_header()
        self.reject_edition3_section()
        if not self.at_keyword("DATA"):
            self.fail_at(self.i, "'DATA;'")
        while self.at_keyword("DATA"):
            self.i += 1
            params: list = []
            if self.toks[self.i] == "(":
                params = self.parse_list()
            self.expect(";")
            result.data_sections.append(params)
            self.parse_data(result.instances)
            self.reject_edition3_section()
        self.expect("END-ISO-10303-21", "'END-ISO-10303-21;' or another 'DATA;' section")
        self.expect(";")
        if self.toks[self.i] != "":
            self.fail_at(self.i, "nothing after 'END-ISO-10303-21;'")
        if references:
            self.check_references(result)
        return result

    def reject_edition3_section(self) -> None:
        if self.at_keyword(*_SECTIONS_ED3):
            name = self.toks[self.i].upper()
            self.fail(f"{name} sections (Part 21 edition 3) are not supported", self.pos(self.i), None)

    def parse_header(self) -> list[Entity]:
        header = []
        while not self.at_keyword("ENDSEC"):
            if self.at_keyword("DATA") or self.toks[self.i] in _MAGIC or self.toks[self.i] == "":
                self.fail(f"missing 'ENDSEC;' of the header before {self.describe(self.i)}",
                          self.pos(self.i), None)
            pos = self.pos(self.i)
            name = self.keyword("a header entity or 'ENDSEC;'")
            if self.toks[self.i] != "(":
                self.fail_at(self.i, "'('")
            params = self.parse_list()
            self.expect(";")
            header.append(Entity(name, params, self.where(pos)[0]))
        self.i += 1
        self.expect(";")
        return header

    def parse_data(self, instances: dict[int, AnyInstance]) -> None:
        toks = self.toks
        while toks[self.i][:1] == "#" and len(toks[self.i]) > 1:
            k = self.i
            ident = int(toks[k][1:])
            self.instance_id = ident
            line = self.where(self.pos(k))[0]
            if ident in instances:
                self.fail(f"duplicate instance #{ident} (first defined on line {instances[ident].line})",
                          self.pos(k), ident)
            self.instance_starts.append((k, ident))
            self.i += 1
            self.expect("=")
            if toks[self.i] == "(":
                self.i += 1
                parts = []
                while self.is_keyword(self.i):
                    name = self.keyword()
                    if toks[self.i] != "(":
                        self.fail_at(self.i, "'('")
                    parts.append((name, self.parse_list()))
                if not parts:
                    self.fail_at(self.i, "an entity name in the complex instance")
                self.expect(")", "')' or another entity name of the complex instance")
                instance: AnyInstance = ComplexInstance(ident, parts, line)
            else:
                name = self.keyword("an entity name or '('")
                if toks[self.i] != "(":
                    self.fail_at(self.i, "'('")
                instance = Instance(ident, name, self.parse_list(), line)
            self.expect(";")
            instances[ident] = instance
            self.instance_id = None
        if self.at_keyword("ENDSEC"):
            self.i += 1
            self.expect(";")
        elif toks[self.i] in _MAGIC or toks[self.i] == "" or self.at_keyword("DATA"):
            self.fail(f"missing 'ENDSEC;' before {self.describe(self.i)}", self.pos(self.i), None)
        else:
            self.fail_at(self.i, "an instance '#n=' or 'ENDSEC;'")

    def parse_list(self) -> list:
        """``( [param {, param}] )``; the current token is '('.  Scalars are inlined
        here because this loop handles nearly every token of a file."""
        toks = self.toks
        i = self.i + 1
        items: list = []
        append = items.append
        if toks[i] == ")":
            self.i = i + 1
            return items
        self.depth += 1
        if self.depth > MAX_NESTING:
            self.fail(f"lists nested more than {MAX_NESTING} deep", self.pos(self.i), self.instance_id)
        while True:
            tok = toks[i]
            c = tok[:1]
            if c == "#" and len(tok) > 1:
                self.ref_sites.append(i)
                append(Ref(int(tok[1:])))
                i += 1
            elif c in _NUMBER_START and (len(tok) > 1 or c in _DIGITS):
                append(float(tok) if "." in tok else int(tok))
                i += 1
            elif c == "$":
                append(UNSET)
                i += 1
            elif c == "'" and len(tok) > 1:
                append(self.string(i))
                i += 1
            elif c == "." and len(tok) > 1:
                name = tok[1:-1].upper()
                append(True if name == "T" else False if name == "F" else Enum(name))
                i += 1
            elif c == "(":
                self.i = i
                append(self.parse_list())
                i = self.i
            elif c == "*":
                append(DERIVED)
                i += 1
            elif c in _LETTERS or (c == "!" and len(tok) > 1):
                append(self.typed(i))
                i = self.i
            else:
                self.fail_at(i, "a parameter value")
            tok = toks[i]
            i += 1
            if tok == ",":
                continue
            if tok == ")":
                self.i = i
                self.depth -= 1
                return items
            self.fail_at(i - 1, "',' or ')'")

    def typed(self, k: int) -> Typed:
        """``NAME(value)`` at token k; leaves self.i after the closing ')'."""
        name = self.toks[k].upper()
        if self.toks[k + 1] != "(":
            self.fail_at(k + 1, f"'(' after {name}")
        self.i = k + 1
        values = self.parse_list()
        if len(values) != 1:
            self.fail(f"typed parameter {name} needs exactly one value, found {len(values)}",
                      self.pos(k), self.instance_id)
        return Typed(name, values[0])

    def string(self, k: int) -> str:
        try:
            return _decode_string(self.toks[k][1:-1])
        except _StringError as error:
            self.fail(error.message, self.pos(k) + 1 + error.offset, self.instance_id)

    def check_references(self, result: Part21File) -> None:
        instances, toks = result.instances, self.toks
        for k in self.ref_sites:
            target = int(toks[k][1:])
            if target not in instances:
                self.fail(f"reference to undefined instance #{target}", self.pos(k), self.owner(k))

    def owner(self, k: int) -> int | None:
        """The id of the instance whose text holds token k (None in the header)."""
        n = bisect.bisect_right(self.instance_starts, (k, float("inf")))
        return self.instance_starts[n - 1][1] if n else None


def parse_part21(text: str, fast: bool = True) -> Part21File:
    """Parse a whole exchange structure.  Raises :class:`Part21Error`.

    The plain instances that make up a big file are read by one compiled regex (see
    :mod:`.part21_scan`); the rest, and every error, by the token parser here.  ``fast=False``:
    the token parser alone (the same result, slower; kept for the bench)."""
    # The parse allocates many small lists that all stay alive; the cyclic garbage
    # collector would rescan them over and over (about a quarter of the time).
    first = _SCAN_RE.match(text.removeprefix("\ufeff"))
    if first.group(2) != "ISO-10303-21":
        # not an exchange structure from its first token on (a binary file, say): the error comes
        # from that token alone; the whole text was scanned first, 6.5 GB and 33 s for 50 MB of NULs
        _exact(text.removeprefix("\ufeff")[:first.end() + 1])
    gc_was_enabled = gc.isenabled()
    gc.disable()
    try:
        if fast:
            try:
                return part21_scan.parse(text, _exact, _KINDS)
            except part21_scan.GiveUp:
                pass
        return _exact(text)
    finally:
        if gc_was_enabled:
            gc.enable()


def _exact(text: str, references: bool = True) -> Part21File:
    return _Parser(text).parse_file(references)


_KINDS = SimpleNamespace(Ref=Ref, Enum=Enum, Instance=Instance, UNSET=UNSET, DERIVED=DERIVED, iter_refs=iter_refs)


def read_part21(path) -> Part21File:
    """Read and parse a file (UTF-8, falling back to ISO 8859-1 for old 8-bit files)."""
    return parse_part21(read_text(path))
