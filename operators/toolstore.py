"""Where the tool library lives: one file in the user's Blender config folder
(``bpy.utils.user_resource('CONFIG', path="kezuri")/tools.toml``), outside the extension's folder, so
removing or updating the add-on keeps it; the environment variable ``KEZURI_TOOL_LIBRARY`` names
another file (batch runs, tests).  Reading and writing are :mod:`..toolpath.tooling.store`'s."""
from __future__ import annotations

import os

from ..toolpath.tooling import store

ENV = "KEZURI_TOOL_LIBRARY"


def library_path() -> str:
    given = os.environ.get(ENV, "").strip()
    if given:
        return os.path.abspath(os.path.expanduser(given))
    import bpy

    folder = bpy.utils.user_resource("CONFIG", path="kezuri", create=True)
    return os.path.join(folder, store.FILE_NAME)


def load():
    """The tool library (the presets, written, on a first run)."""
    return store.load(library_path())


def save(library) -> str:
    return store.save(library_path(), library)
