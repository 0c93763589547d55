"""Kezuri's own tool library file: TOML, one ``[[tools]]`` table per tool, every field by its plain
name (:data:`.library.FIELDS`), lengths in mm, a field left out where it is not known (stick-out,
holder diameter)::

    format = "kezuri-tools"
    version = 1
    units = "mm"

    [[tools]]
    number = 2
    kind = "ball"
    diameter = 6.0
    ...

The reader refuses what it cannot keep: an unknown key or field, another version or unit, a value
of the wrong type; the message names the file, the line of the tool's ``[[tools]]`` and the field.
"""
from __future__ import annotations

import json
import re
import tomllib

from .library import FIELDS, ToolLibrary, ToolLibraryError, tool_from_fields

FORMAT = "kezuri-tools"
VERSION = 1
HEADER_KEYS = {"format", "version", "units", "tools"}


def toml_string(text: str) -> str:
    """A TOML basic string: JSON's escapes are TOML's, and DEL must be escaped too."""
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def toml_value(value) -> str:
    if isinstance(value, str):
        return toml_string(value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def write_text(library: ToolLibrary) -> str:
    lines = ["# Kezuri CAM tool library: lengths in mm, angles in degrees (the included angle).",
             f"format = {toml_string(FORMAT)}", f"version = {VERSION}", 'units = "mm"']
    for tool in library:
        lines += ["", "[[tools]]"]
        lines += [f"{key} = {toml_value(value)}" for key, value in tool.as_dict().items() if value is not None]
    return "\n".join(lines) + "\n"


def tool_lines(text: str) -> list:
    """The line number of each ``[[tools]]`` header, in order (for messages)."""
    return [index for index, line in enumerate(text.splitlines(), 1)
            if re.match(r"\s*\[\[\s*tools\s*\]\]", line)]


def read_text(text: str, path: str) -> tuple:
    """(ToolLibrary, notes) from the file's text; ``path`` names it in messages."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ToolLibraryError(f"{path}: not a Kezuri tool library: not TOML ({error})") from None
    unknown = sorted(set(data) - HEADER_KEYS)
    if unknown:
        raise ToolLibraryError(f"{path}: unknown key {unknown[0]!r}; the file has {', '.join(sorted(HEADER_KEYS))}")
    if data.get("format") != FORMAT:
        raise ToolLibraryError(f"{path}: format = {data.get('format')!r}, not {FORMAT!r}: not a Kezuri tool library")
    version = data.get("version")
    if version != VERSION:
        raise ToolLibraryError(f"{path}: version = {version!r}; this Kezuri reads version {VERSION} (a newer "
                               "Kezuri wrote it?)")
    if data.get("units") != "mm":
        raise ToolLibraryError(f"{path}: units = {data.get('units')!r}; a Kezuri tool library is in \"mm\"")
    tables = data.get("tools", [])
    if not isinstance(tables, list):
        raise ToolLibraryError(f"{path}: tools must be [[tools]] tables")
    lines = tool_lines(text)
    tools, wheres = [], []
    for index, table in enumerate(tables):
        where = f"{path}: line {lines[index]} (tool {index + 1})" if len(lines) == len(tables) else \
            f"{path}: tool {index + 1}"
        if not isinstance(table, dict):
            raise ToolLibraryError(f"{where}: not a table")
        for key, value in table.items():
            if key in FIELDS and isinstance(value, (dict, list)):
                raise ToolLibraryError(f"{where}: {key} = {value!r} is not a single value")
        tools.append(tool_from_fields(table, where))
        wheres.append(where)
    return ToolLibrary(tools, wheres), []
