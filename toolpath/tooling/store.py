"""The tool library's file: one Kezuri tool library (:mod:`.kezuri_format`) at a path the shell
chooses (the user's Blender config folder, outside the extension, so removing the add-on keeps it).

Every write first copies the file as it was to ``<file>.bak1`` (the older copies move on to
``.bak2`` ... ``.bak5``; the oldest goes), then writes the new text to a temporary file beside it
and moves that over the file (``os.replace``: a reader sees the old file or the new one, never half
of one).  The text is read back before it is written: a library the file would not give back the
same is never written.  A file that cannot be read is an error naming it, and is left as it is
(no preset ever overwrites a user's file); a missing file is made with the presets (:data:`SEEDS`).
"""
from __future__ import annotations

import os
import shutil
import tempfile

from . import kezuri_format
from .textfile import read_text_file
from .library import LibraryTool, ToolLibrary, ToolLibraryError

FILE_NAME = "tools.toml"
BACKUPS = 5

# The presets a first run writes: the tools the sample workflows cut with (their defaults), and
# the common V-bits and drills.  Stick-outs are typical values: measure yours.
SEEDS = ToolLibrary([
    LibraryTool(1, "flat", 6.0, flutes=2, flute_length=20.0, stick_out=30.0, name="6 mm roughing end mill"),
    LibraryTool(2, "ball", 6.0, flutes=2, flute_length=20.0, stick_out=30.0, name="6 mm ball end mill"),
    LibraryTool(3, "flat", 1.0, flutes=2, flute_length=4.0, stick_out=15.0, name="1 mm end mill"),
    LibraryTool(4, "drill", 5.0, angle=118.0, flutes=2, flute_length=40.0, stick_out=50.0, material="hss",
                name="5 mm drill"),
    LibraryTool(5, "flat", 6.0, flutes=2, flute_length=25.0, stick_out=35.0, name="6 mm end mill"),
    LibraryTool(6, "drill", 10.0, angle=90.0, flutes=2, flute_length=20.0, stick_out=30.0, material="hss",
                name="10 mm spot drill"),
    LibraryTool(7, "vbit", 12.0, angle=90.0, flutes=2, flute_length=10.0, stick_out=25.0, name="90° V-bit"),
    LibraryTool(8, "vbit", 6.0, angle=60.0, flutes=2, flute_length=8.0, stick_out=22.0, name="60° V-bit"),
    LibraryTool(9, "ball", 3.0, flutes=2, flute_length=12.0, stick_out=22.0, name="3 mm ball end mill"),
    LibraryTool(10, "drill", 3.0, angle=118.0, flutes=2, flute_length=30.0, stick_out=40.0, material="hss",
                name="3 mm drill"),
    LibraryTool(11, "drill", 8.0, angle=118.0, flutes=2, flute_length=50.0, stick_out=60.0, material="hss",
                name="8 mm drill"),
])


def backups_of(path: str) -> list:
    return [f"{path}.bak{index}" for index in range(1, BACKUPS + 1)]


def load(path: str) -> ToolLibrary:
    """The library in the file; the presets, written there, when there is no file yet."""
    if not os.path.exists(path):
        save(path, SEEDS)
        return SEEDS
    try:
        library, _ = kezuri_format.read_text(read_text_file(path), path)
    except ToolLibraryError as error:
        kept = [b for b in backups_of(path) if os.path.exists(b)]
        hint = f"; its backups: {', '.join(kept)}" if kept else ""
        raise ToolLibraryError(f"the tool library cannot be read, and is left as it is: {error}{hint}") from None
    return library


def rotate_backups(path: str) -> None:
    names = backups_of(path)
    if os.path.exists(names[-1]):
        os.remove(names[-1])
    for older, newer in zip(reversed(names[1:]), reversed(names[:-1])):
        if os.path.exists(newer):
            os.replace(newer, older)
    shutil.copy2(path, names[0])


def replace_atomically(path: str, text: str, prefix: str) -> None:
    """Write ``text`` (UTF-8) to a temporary file beside ``path`` (its name starting ``prefix``), to
    the disk, then rename it onto ``path``: the file is the old one or the new one, never half of it.
    The temporary file goes on any failure; an OSError is the caller's to name."""
    handle, temporary = tempfile.mkstemp(prefix=prefix, suffix=".tmp", dir=os.path.dirname(os.path.abspath(path)))
    try:
        with os.fdopen(handle, "w", encoding="utf-8", newline="\n") as stream:
            stream.write(text)
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise


def save(path: str, library: ToolLibrary) -> str:
    """Write the library to ``path`` (backed up, atomically); returns the path."""
    text = kezuri_format.write_text(library)
    again, _ = kezuri_format.read_text(text, path)
    if again != library:
        raise ToolLibraryError(f"{path}: the library would not read back as it is; nothing was written")
    try:
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
        if os.path.exists(path):
            rotate_backups(path)
        replace_atomically(path, text, ".tools-")
    except OSError as error:
        raise ToolLibraryError(f"{path}: the tool library cannot be written ({error.strerror or error}); "
                               "the file is as it was") from None
    return path


def write_export(path: str, text: str) -> str:
    """An exported file, written atomically (no backups: it is the user's copy)."""
    try:
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
        replace_atomically(path, text, ".kezuri-")
    except OSError as error:
        raise ToolLibraryError(f"{path}: cannot be written ({error.strerror or error})") from None
    return path
