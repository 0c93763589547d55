"""ISO 10303-21 (STEP Part 21) exchange structure: the writer.

Python values (as :mod:`part21` reads them) back to Part 21 text: :func:`write_part21` for a
whole file, :class:`Part21Writer` to build one instance by instance, and the value formatting
(:func:`format_real`, :func:`format_string`, :func:`format_value`).
"""
from __future__ import annotations

import math
import numbers
import re
from typing import Any, Iterable, Mapping

from .part21 import (AnyInstance, ComplexInstance, Derived, Entity, Enum, Instance, Part21File, Ref, Typed, Unset, iter_refs)

__all__ = ["Part21Writer", "write_part21", "make_header", "format_real", "format_string", "format_value"]

_KEYWORD_RE = re.compile(r"!?[A-Z_][A-Z0-9_]*\Z")
_ENUM_RE = re.compile(r"[A-Z_][A-Z0-9_]*\Z")
_PLAIN_RE = re.compile(r"[ -&(-\[\]-~]*\Z")  # printable ASCII except ' and \

DEFAULT_SCHEMA = ("MACHINING_SCHEMA", "MILLING_SCHEMA")  # ISO 14649-10/-11


def format_real(x: float) -> str:
    """A Part 21 real: always a decimal point, shortest text that reads back exactly.

    ``5.0 -> '5.'``, ``0.05 -> '0.05'``, ``-12.0 -> '-12.'``, ``1e-07 -> '1.E-07'``.
    """
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"Part 21 cannot represent the real {x!r}")
    mantissa, _, exponent = repr(x).partition("e")
    if "." not in mantissa:
        mantissa += "."
    mantissa = mantissa.rstrip("0")
    return mantissa + ("E" + exponent if exponent else "")


def format_string(s: str) -> str:
    """A quoted Part 21 string; non-ASCII and control characters use \\X\\, \\X2\\, \\X4\\."""
    if _PLAIN_RE.match(s):
        return "'" + s + "'"
    out = ["'"]
    i, n = 0, len(s)
    while i < n:
        c = s[i]
        code = ord(c)
        if c == "'":
            out.append("''")
        elif c == "\\":
            out.append("\\\\")
        elif 0x20 <= code <= 0x7E:
            out.append(c)
        elif code <= 0xFF:
            out.append(f"\\X\\{code:02X}")
        else:
            wide = code > 0xFFFF
            j = i
            while j < n and ord(s[j]) > 0xFF and (ord(s[j]) > 0xFFFF) == wide:
                j += 1
            if wide:
                out.append("\\X4\\" + "".join(f"{ord(ch):08X}" for ch in s[i:j]) + "\\X0\\")
            else:
                out.append("\\X2\\" + "".join(f"{ord(ch):04X}" for ch in s[i:j]) + "\\X0\\")
            i = j
            continue
        i += 1
    out.append("'")
    return "".join(out)


def format_value(value: Any) -> str:
    """One parameter value as Part 21 text (see the module docstring for the mapping)."""
    if isinstance(value, bool):
        return ".T." if value else ".F."
    if isinstance(value, Ref):
        if not isinstance(value.id, int) or value.id <= 0:
            raise ValueError(f"bad instance id in {value!r}")
        return f"#{value.id}"
    if isinstance(value, str):
        return format_string(value)
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return format_real(value)
    if isinstance(value, (list, tuple)):
        return "(" + ",".join(format_value(item) for item in value) + ")"
    if isinstance(value, Enum):
        if not _ENUM_RE.match(value.name):
            raise ValueError(f"bad enumeration name {value.name!r}")
        return f".{value.name}."
    if isinstance(value, Unset):
        return "$"
    if isinstance(value, Derived):
        return "*"
    if isinstance(value, Typed):
        return _check_keyword(value.type_name) + "(" + format_value(value.value) + ")"
    if value is None:
        raise TypeError("None is not a Part 21 value; use UNSET for '$'")
    raise TypeError(f"cannot write {type(value).__name__} {value!r} as a Part 21 value")


def _check_keyword(name: str) -> str:
    if not isinstance(name, str) or not _KEYWORD_RE.match(name):
        raise ValueError(f"bad Part 21 type name {name!r} (upper case letters, digits, '_')")
    return name


def _record(type_name: str, params: list) -> str:
    return _check_keyword(type_name) + "(" + ",".join(format_value(p) for p in params) + ")"


def make_header(description: Iterable[str] = ("",), name: str = "", time_stamp: str = "",
                author: Iterable[str] = ("",), organization: Iterable[str] = ("",),
                preprocessor_version: str = "Kezuri CAM part21",
                originating_system: str = "Kezuri CAM", authorization: str = "",
                schema: Iterable[str] = DEFAULT_SCHEMA,
                implementation_level: str = "2;1") -> list[Entity]:
    """The three mandatory header entities.  No timestamp unless one is passed in."""
    def non_empty(items):  # the header lists are LIST [1:?]
        items = [str(item) for item in items]
        return items or [""]
    return [
        Entity("FILE_DESCRIPTION", [non_empty(description), implementation_level]),
        Entity("FILE_NAME", [name, time_stamp, non_empty(author), non_empty(organization),
                             preprocessor_version, originating_system, authorization]),
        Entity("FILE_SCHEMA", [non_empty(schema)]),
    ]


_REQUIRED_HEADER = ("FILE_DESCRIPTION", "FILE_NAME", "FILE_SCHEMA")


def write_part21(source: Part21File | Mapping[int, AnyInstance] | Iterable[AnyInstance],
                 header: list[Entity] | None = None) -> str:
    """Part 21 text for a file, an ``{id: instance}`` mapping or an iterable of instances.

    The header is ``header`` if given, else the file's own, else :func:`make_header`'s
    default; a missing mandatory entity is filled in from the default, and the three
    are written first in the standard order.  Instances are written in id order, one
    per line.  Raises ValueError for duplicate ids or references to undefined instances.
    """
    if isinstance(source, Part21File):
        instances = list(source.instances.values())
        if header is None:
            header = source.header
    elif isinstance(source, Mapping):
        instances = list(source.values())
    else:
        instances = list(source)
    if not header:
        header = make_header()

    default = {e.type_name: e for e in make_header()}
    given = {}
    for entity in header:
        given.setdefault(entity.type_name, entity)
    ordered = [given.get(name, default[name]) for name in _REQUIRED_HEADER]
    ordered += [e for e in header if e.type_name not in _REQUIRED_HEADER]

    ids = {}
    for inst in instances:
        if not isinstance(inst.id, int) or isinstance(inst.id, bool) or inst.id <= 0:
            raise ValueError(f"bad instance id {inst.id!r}")
        if inst.id in ids:
            raise ValueError(f"duplicate instance #{inst.id}")
        ids[inst.id] = inst
    for inst in instances:
        for ref in iter_refs(inst):
            if ref.id not in ids:
                raise ValueError(f"#{inst.id} refers to #{ref.id}, which is not defined")

    lines = ["ISO-10303-21;", "HEADER;"]
    lines += [_record(e.type_name, e.params) + ";" for e in ordered]
    lines += ["ENDSEC;", "DATA;"]
    for ident in sorted(ids):
        inst = ids[ident]
        if isinstance(inst, ComplexInstance):
            if not inst.parts:
                raise ValueError(f"complex instance #{ident} has no parts")
            body = "(" + "".join(_record(name, params) for name, params in inst.parts) + ")"
        else:
            body = _record(inst.type_name, inst.params)
        lines.append(f"#{ident}={body};")
    lines += ["ENDSEC;", "END-ISO-10303-21;", ""]
    return "\n".join(lines)


def _normalize(value: Any) -> Any:
    """Builder input to the values the reader returns: tuples become lists, numpy
    scalars become int/float; anything not writable raises now, at the ``add`` call."""
    if isinstance(value, bool):
        return value
    if isinstance(value, (list, tuple)):
        return [_normalize(item) for item in value]
    if isinstance(value, Typed):
        return Typed(_check_keyword(value.type_name), _normalize(value.value))
    if isinstance(value, (str, Ref, Enum, Unset, Derived)):
        format_value(value)  # validates names and ids
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        format_real(value)  # rejects nan and inf
        return float(value)
    format_value(value)  # raises a TypeError naming the value
    return value


class Part21Writer:
    """Build a file instance by instance; ids are numbered from ``start``.

    ``add`` returns the new instance's Ref, to be passed as a parameter of later
    instances.  For a reference to an instance not yet built (a top-down layout or a
    cycle), take an id with ``reserve()`` and fill it in later with ``define()``.
    Pass reals as floats: ``5`` is written as the integer ``5``, ``5.0`` as ``5.``.
    """

    def __init__(self, start: int = 1):
        self.instances: dict[int, AnyInstance] = {}
        self._reserved: set[int] = set()
        self._next = start

    def reserve(self) -> Ref:
        ref = Ref(self._next)
        self._next += 1
        self._reserved.add(ref.id)
        return ref

    def define(self, ref: Ref, type_name: str, *params: Any) -> Ref:
        """Fill in an id taken with :meth:`reserve`."""
        if ref.id not in self._reserved:
            raise ValueError(f"{ref!r} was not reserved or is already defined")
        instance = Instance(ref.id, _check_keyword(type_name), [_normalize(p) for p in params])
        self._reserved.discard(ref.id)
        self.instances[ref.id] = instance
        return ref

    def add(self, type_name: str, *params: Any) -> Ref:
        # Validate before numbering so that a rejected call uses up no id.
        instance = Instance(self._next, _check_keyword(type_name), [_normalize(p) for p in params])
        return self._store(instance)

    def add_complex(self, parts: Iterable[tuple[str, Iterable[Any]]]) -> Ref:
        """A complex instance; pass the parts in alphabetical order as Part 21 requires."""
        parts = [(_check_keyword(name), [_normalize(p) for p in params]) for name, params in parts]
        if not parts:
            raise ValueError("a complex instance needs at least one part")
        return self._store(ComplexInstance(self._next, parts))

    def _store(self, instance: AnyInstance) -> Ref:
        self.instances[instance.id] = instance
        self._next += 1
        return instance.ref

    def file(self, **header_fields: Any) -> Part21File:
        """The file so far; ``header_fields`` are the arguments of :func:`make_header`."""
        if self._reserved:
            missing = ", ".join(f"#{i}" for i in sorted(self._reserved))
            raise ValueError(f"reserved but never defined: {missing}")
        return Part21File(header=make_header(**header_fields),
                          instances=dict(sorted(self.instances.items())), data_sections=[[]])

    def text(self, **header_fields: Any) -> str:
        """Part 21 text; e.g. ``text(description=('pocket',), schema=('MACHINING_SCHEMA',))``."""
        return write_part21(self.file(**header_fields))
