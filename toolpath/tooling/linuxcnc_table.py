"""LinuxCNC tool tables (``tool.tbl``), as LinuxCNC's manual describes them ("Tool Compensation",
section Tool Table Format): one tool a line, words of a letter and a number in any order, then
an optional comment after ``;``::

    T1 P1 D6.0 Z+0.0 ;6 mm ball

    T  tool number        P  pocket            D  diameter
    X Y Z A B C U V W     offsets              I J Q  lathe front/back angle, orientation

The table is in the machine's units (the INI's LINEAR_UNITS), which the file does not say:
``units="inch"`` reads and writes D in inches.  A table holds only the number and the diameter;
what Kezuri knows besides (kind, angle, flutes, lengths, material, vendor) is kept in the comment
after the tool's name, as ``kezuri{...}`` (JSON, lengths always in mm), so a table Kezuri wrote
reads back field by field.  A tool without it is read with its kind taken from the comment's words
(ball, bull, V-bit, drill, engrav...; otherwise a flat end mill) and the other fields at their
defaults, and a note says so.  P, Z and the other offsets belong to the machine (measured on it):
they are not kept, and the export writes P = T and no offsets.
"""
from __future__ import annotations

import dataclasses
import json
import math
import re

from .library import DRILL_POINT_DEG, FIELDS, LibraryTool, ToolLibrary, ToolLibraryError, tool_from_fields

LETTERS = set("TPXYZABCUVWDIJQ")
WHOLE = set("TPQ")
UNITS = {"mm": 1.0, "inch": 25.4}
TAG = "kezuri"
DEFAULTS = {f.name: f.default for f in dataclasses.fields(LibraryTool)}
GUESSES = (("bull", "bull"), ("ball", "ball"), ("v-bit", "vbit"), ("vbit", "vbit"), ("v bit", "vbit"),
           ("engrav", "engraver"), ("drill", "drill"))


def unit_scale(units: str) -> float:
    if units not in UNITS:
        raise ToolLibraryError(f"tool table units {units!r} are not one of {', '.join(UNITS)}")
    return UNITS[units]


def words_of(code: str, where: str) -> dict:
    words = {}
    for token in code.split():
        letter, number = token[:1].upper(), token[1:]
        if letter not in LETTERS:
            raise ToolLibraryError(f"{where}: {token!r} is not a tool table word (T P X Y Z A B C U V W D I J Q)")
        if letter in words:
            raise ToolLibraryError(f"{where}: {letter} is given twice")
        try:
            value = float(number)
        except ValueError:
            raise ToolLibraryError(f"{where}: {token!r}: {number!r} is not a number") from None
        if not math.isfinite(value):
            raise ToolLibraryError(f"{where}: {token!r} is not a finite number")
        if letter in WHOLE:
            if value != int(value):
                raise ToolLibraryError(f"{where}: {token!r}: {letter} must be a whole number")
            value = int(value)
        words[letter] = value
    return words


def split_comment(comment: str, where: str) -> tuple:
    """(name, the kezuri fields or None) of a comment."""
    at = comment.find(TAG + "{")
    if at < 0:
        return comment.strip(), None
    try:
        fields = json.loads(comment[at + len(TAG):])
    except json.JSONDecodeError as error:
        raise ToolLibraryError(f"{where}: the comment's {TAG}{{...}} is not JSON ({error.msg} at column "
                               f"{at + len(TAG) + error.pos + 1} of the comment)") from None
    if not isinstance(fields, dict):
        raise ToolLibraryError(f"{where}: the comment's {TAG}{{...}} is not a table of fields")
    return comment[:at].strip(), fields


def guessed_kind(name: str) -> str:
    lower = name.lower()
    for word, kind in GUESSES:
        if word in lower:
            return kind
    return "flat"


def read_text(text: str, path: str, units: str = "mm") -> tuple:
    """(ToolLibrary, notes) from a tool table's text."""
    scale = unit_scale(units)
    tools, wheres, notes = [], [], []
    for number, line in enumerate(text.splitlines(), 1):
        where = f"{path}: line {number}"
        code, _, comment = line.partition(";")
        if not code.strip():
            continue                        # a blank line or a comment line
        words = words_of(code, where)
        if "T" not in words:
            raise ToolLibraryError(f"{where}: no T word (tool number)")
        where = f"{path}: line {number} (T{words['T']})"
        if "D" not in words:
            raise ToolLibraryError(f"{where}: no D word: the tool's diameter is missing")
        name, tagged = split_comment(comment, where)
        if tagged is not None:
            fields = {**tagged, "number": words["T"], "diameter": words["D"] * scale, "name": name}
            if "diameter" in tagged or "number" in tagged:
                raise ToolLibraryError(f"{where}: the comment's {TAG}{{...}} repeats number or diameter "
                                       "(the T and D words give them)")
        else:
            kind = guessed_kind(name)
            fields = {"number": words["T"], "kind": kind, "diameter": words["D"] * scale, "name": name}
            if kind in ("vbit", "engraver"):
                fields["angle"] = 90.0
            angle = fields.get("angle", DRILL_POINT_DEG if kind == "drill" else None)
            notes.append(f"{where}: only the number and diameter are in the table: taken as a {kind} from the "
                         f"comment (angle {'-' if angle is None else f'{angle:g}°'}); flutes, lengths and material "
                         "at their defaults")
        unknown = sorted(set(fields) - set(FIELDS))
        if unknown:
            raise ToolLibraryError(f"{where}: the comment's {TAG}{{...}} has an unknown field {unknown[0]!r}")
        tools.append(tool_from_fields(fields, where))
        wheres.append(where)
    return ToolLibrary(tools, wheres), notes


def number_text(value: float) -> str:
    """The shortest text that reads back as the same float, without an exponent."""
    text = repr(float(value))
    if "e" in text:
        text = f"{value:.12f}".rstrip("0").rstrip(".")
    return text.removesuffix(".0")


def write_text(library: ToolLibrary, units: str = "mm") -> str:
    scale = unit_scale(units)
    for tool in names_survive(library):
        raise ToolLibraryError(f"T{tool.number}: its name {tool.name!r} cannot stand in a tool table's comment "
                               "(line breaks, spaces at the ends or in runs, or 'kezuri{'): rename it first")
    lines = [f";Kezuri CAM tool library: D in {units}; the kezuri{{...}} fields in mm"]
    for tool in library:
        fields = {key: value for key, value in tool.as_dict().items()
                  if key not in ("number", "diameter", "name") and value != DEFAULTS[key]}
        if tool.kind == "ball":
            fields.pop("corner_radius", None)       # a ball's is its radius
        lines.append(f"T{tool.number} P{tool.number} D{number_text(tool.diameter / scale)} ;"
                     f"{tool.name + ' ' if tool.name else ''}{TAG}{json.dumps(fields, ensure_ascii=False, separators=(',', ':'))}")
    return "\n".join(lines) + "\n"


def names_survive(library: ToolLibrary) -> list:
    """The tools whose names a table cannot hold as they are (line breaks, runs of spaces, the tag)."""
    return [t for t in library if t.name != " ".join(t.name.split()) or re.search(TAG + r"\{", t.name)]
