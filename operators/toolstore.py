"""Where the tool library lives: one file in the user's Blender config folder
(``bpy.utils.user_resource('CONFIG', path="kezuri")/tools.toml``), outside the extension's folder, so
removing or updating the add-on keeps it; the environment variable ``KEZURI_TOOL_LIBRARY`` names
another file (batch runs, tests).  Reading and writing are :mod:`..toolpath.tooling.store`'s."""
from __future__ import annotations

import os

from ..toolpath.tooling import store
from ..toolpath.tooling.library import ToolLibraryError

ENV = "KEZURI_TOOL_LIBRARY"


def library_path() -> str:
    given = os.environ.get(ENV, "").strip()
    if given:
        return os.path.abspath(os.path.expanduser(given))
    import bpy

    folder = bpy.utils.user_resource("CONFIG", path="kezuri")      # made when the library is first written
    return os.path.join(folder, store.FILE_NAME)


def load():
    """The tool library (the presets, written, on a first run)."""
    return store.load(library_path())


def save(library) -> str:
    return store.save(library_path(), library)


def library_or_none():
    """The user's tool library, or None when there is no file yet (nothing is written here) or
    it cannot be read."""
    path = library_path()
    if not os.path.isfile(path):
        return None
    try:
        return store.load(path)
    except ToolLibraryError:
        return None


def tool_makes(tools, library=False) -> dict:
    """{tool number: (flutes, tool material)} for the program tools ``tools`` that the user's
    library holds as the same tool (number, kind and diameter); for the feeds check.  ``library``:
    the library already read (None: there is none), else it is read here."""
    if library is False:
        library = library_or_none()
    found = {}
    for tool in tools if library is not None else ():
        entry = library.find(tool.number)
        if (entry is not None and entry.to_ir_tool().kind == tool.kind
                and abs(entry.diameter - float(tool.diameter)) <= 1e-6):
            found[tool.number] = (entry.flutes, entry.material)
    return found


def stick_outs(entries, library=False) -> dict:
    """{tool number: stick-out (mm)} for a report's ``operations`` whose tool the user's library has
    as the same tool (its number, kind and diameter) with a measured stick-out; for the setup sheet.
    Nothing when there is no library file yet (nothing is written here) or it cannot be read (the
    sheet then shows the stick-out as not known, as before).  ``library``: the library already
    read (None: there is none), else it is read here."""
    if library is False:
        library = library_or_none()
    if library is None:
        return {}
    found = {}
    for entry in entries or ():
        number, diameter = entry.get("tool_number"), entry.get("tool_diameter_mm")
        tool = library.find(number) if isinstance(number, int) and not isinstance(number, bool) else None
        if tool is None or tool.stick_out is None or not isinstance(diameter, (int, float)):
            continue
        if tool.to_ir_tool().kind == entry.get("tool_kind") and abs(tool.diameter - float(diameter)) <= 1e-6:
            found[number] = tool.stick_out
    return found
