"""The tool library's file formats by name, and which one a file is in (its extension or the
name given): ``kezuri`` (.toml, Kezuri's own), ``tbl`` (a LinuxCNC tool table), ``fusion`` (a
Fusion 360 tool library, .json / .tools)."""
from __future__ import annotations

import os

from . import fusion_library, kezuri_format, linuxcnc_table
from .library import ToolLibrary, ToolLibraryError

EXTENSIONS = {"kezuri": (".toml",), "tbl": (".tbl",), "fusion": (".json", ".tools")}
NAMES = tuple(EXTENSIONS)
MAX_BYTES = 20_000_000      # a tool library is kilobytes; more is not one


def format_of(path: str, given: str | None = None) -> str:
    """The format named, else the one the file's extension says."""
    if given is not None:
        if given not in EXTENSIONS:
            raise ToolLibraryError(f"tool library format {given!r} is not one of {', '.join(NAMES)}")
        return given
    extension = os.path.splitext(path)[1].lower()
    for name, extensions in EXTENSIONS.items():
        if extension in extensions:
            return name
    known = ", ".join(f"{e} ({n})" for n, exts in EXTENSIONS.items() for e in exts)
    raise ToolLibraryError(f"{path}: which tool library format is {extension or 'a file without extension'}? "
                           f"Known: {known}; or name the format")


def parse(text: str, path: str, fmt: str, units: str = "mm") -> tuple:
    """(ToolLibrary, notes) from a file's text in format ``fmt``."""
    if fmt == "tbl":
        return linuxcnc_table.read_text(text, path, units)
    if units != "mm":
        raise ToolLibraryError(f"{path}: units are given by the {fmt} file itself; --units is for tool tables")
    if fmt == "fusion":
        return fusion_library.read_text(text, path)
    return kezuri_format.read_text(text, path)


def render(library: ToolLibrary, fmt: str, units: str = "mm") -> str:
    if fmt == "tbl":
        return linuxcnc_table.write_text(library, units)
    if units != "mm":
        raise ToolLibraryError(f"a {fmt} file is written in mm; units are for tool tables")
    if fmt == "fusion":
        return fusion_library.write_text(library)
    return kezuri_format.write_text(library)


def read_text_file(path: str) -> str:
    """The file's text; a missing, unreadable, huge or non-UTF-8 file is an error naming it."""
    try:
        size = os.path.getsize(path)
        if size > MAX_BYTES:
            raise ToolLibraryError(f"{path}: {size} bytes is not a tool library (at most {MAX_BYTES})")
        with open(path, "rb") as stream:
            data = stream.read()
    except FileNotFoundError:
        raise ToolLibraryError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise ToolLibraryError(f"{path}: a folder, not a tool library file") from None
    except OSError as error:
        raise ToolLibraryError(f"{path}: cannot be read ({error.strerror})") from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        line = data[:error.start].count(b"\n") + 1
        raise ToolLibraryError(f"{path}: line {line}: not UTF-8 text") from None


def read_path(path: str, fmt: str | None = None, units: str = "mm") -> tuple:
    """(ToolLibrary, notes) from a file, its format from ``fmt`` or its extension."""
    fmt = format_of(path, fmt)
    return parse(read_text_file(path), path, fmt, units)
