"""Reading the text files users bring (NC programs, Part 21, CADKEY CDL): one rule for all, and
one way of saying why a path the user gave cannot be read as a file."""
from __future__ import annotations

import errno
import os
import stat

# what the file system's refusal means, in the user's words (the OS's "[Errno 40] ..." is not)
REASONS = {
    errno.ENOENT: "no such file",
    errno.ENOTDIR: "no such file (a part of the path is a file, not a folder)",
    errno.ELOOP: "a symbolic link that leads round in a loop, to no file",
    errno.ENAMETOOLONG: "the path is too long for the file system",
    errno.EACCES: "not readable (permission denied)",
    errno.EPERM: "not readable (permission denied)",
}


def os_reason(error: OSError) -> str:
    """Why the file could not be read, from the file system's error, without its errno text."""
    if isinstance(error, IsADirectoryError):
        return "a folder, not a file"
    return REASONS.get(error.errno, f"cannot be read ({error.strerror or error})")


def file_problem(path: str, what: str = "a file") -> str | None:
    """Why ``path`` cannot be read as a file (missing, a folder, a path under a file, a symbolic link
    loop, too long, a device or pipe a read would hang on), or None when it can."""
    try:
        mode = os.stat(path).st_mode
    except OSError as error:
        return os_reason(error)
    except ValueError:                      # a NUL character in the path
        return "not a path (it holds a NUL character)"
    if stat.S_ISDIR(mode):
        return f"a folder, not {what}"
    if not stat.S_ISREG(mode):
        return f"not a regular file (a device or a pipe), not {what}"
    return None


def named(shown: str, message: str) -> str:
    """``message`` under the name the user gave the file (``--cdl parts/q.cdl``, a job file's key
    and its value), as every error about a file the user gave is shown (the Japanese interface
    translates the message after the name: translations.japanese_message)."""
    return f"{shown}: {message}"


def refusal(shown: str, path: str, what: str = "a file") -> str | None:
    """The error naming the file as ``shown`` when ``path`` cannot be read as a file (see
    :func:`file_problem`), or None when it can."""
    problem = file_problem(path, what)
    return None if problem is None else named(shown, problem)


def read_text(path) -> str:
    """The file's text: UTF-8 (a byte-order mark dropped: it hid a CDL's first LINE word), UTF-16
    when a byte-order mark says so (Windows Notepad's "Unicode"), or, when UTF-8 fails, ISO 8859-1
    (old 8-bit files; Shift-JIS comments keep at least their line breaks, which is all the readers
    need of a comment)."""
    with open(path, "rb") as handle:
        data = handle.read()
    if data[:2] in (b"\xff\xfe", b"\xfe\xff"):
        try:
            return data.decode("utf-16")
        except UnicodeDecodeError:
            pass
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return data.decode("latin-1")
