"""A tool file's text: read whole, checked to be a text file of a sensible size."""
from __future__ import annotations

import os

from ..engines.textfile import named, os_reason
from .library import ToolLibraryError

MAX_BYTES = 20_000_000      # a tool library is kilobytes; more is not one


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
        raise ToolLibraryError(named(path, os_reason(error))) from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        line = data[:error.start].count(b"\n") + 1
        raise ToolLibraryError(f"{path}: line {line}: not UTF-8 text") from None
