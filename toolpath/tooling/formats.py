"""The tool library's file formats by name, and which one a file is in (its extension or the
name given): ``kezuri`` (.toml, Kezuri's own), ``tbl`` (a LinuxCNC tool table), ``fusion`` (a
Fusion 360 tool library, .json / .tools), ``freecad`` (a FreeCAD library .fctl and its .fctb bits)."""
from __future__ import annotations

import os

from . import freecad_library, fusion_library, kezuri_format, linuxcnc_table
from .library import ToolLibrary, ToolLibraryError
from .textfile import read_text_file

EXTENSIONS = {"kezuri": (".toml",), "tbl": (".tbl",), "fusion": (".json", ".tools"), "freecad": (".fctl",)}
NAMES = tuple(EXTENSIONS)


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
    if fmt == "freecad":
        raise ToolLibraryError(f"{path}: a FreeCAD library is read with its bit files: read it from its path")
    return kezuri_format.read_text(text, path)


def render(library: ToolLibrary, fmt: str, units: str = "mm") -> str:
    if fmt == "tbl":
        return linuxcnc_table.write_text(library, units)
    if units != "mm":
        raise ToolLibraryError(f"a {fmt} file is written in mm; units are for tool tables")
    if fmt == "fusion":
        return fusion_library.write_text(library)
    if fmt == "freecad":
        raise ToolLibraryError("a FreeCAD library is several files: export it to a .fctl path")
    return kezuri_format.write_text(library)


def read_path(path: str, fmt: str | None = None, units: str = "mm") -> tuple:
    """(ToolLibrary, notes) from a file, its format from ``fmt`` or its extension."""
    fmt = format_of(path, fmt)
    if fmt == "freecad":
        if units != "mm":
            raise ToolLibraryError(f"{path}: units are given by the {fmt} file itself; --units is for tool tables")
        return freecad_library.read_path(path)
    return parse(read_text_file(path), path, fmt, units)


def read_import(path: str, fmt: str | None = None, units: str = "mm") -> tuple:
    """:func:`read_path` of a file to merge into the library: one without a tool (an empty table,
    say) is refused naming it, not imported as nothing."""
    incoming, notes = read_path(path, fmt, units)
    if not len(incoming):
        raise ToolLibraryError(f"{path}: no tools in it: nothing to import")
    return incoming, notes


def files_for(path: str, library: ToolLibrary, fmt: str | None = None, units: str = "mm") -> list:
    """[(file, text)] an export to ``path`` writes (a FreeCAD library writes its bit files too)."""
    fmt = format_of(path, fmt)
    if fmt == "freecad":
        if units != "mm":
            raise ToolLibraryError(f"a {fmt} file is written in mm; units are for tool tables")
        return freecad_library.files_of(path, library)
    return [(path, render(library, fmt, units))]
