"""Atomic file output: an NC file is either complete or not there at all.

Every file is written to a temporary ``.kezuri-XXXXXXXX.part`` file beside it and renamed.  A
process killed mid-write (kill -9, a crash) leaves its temporary file behind: the next write
into that folder removes ours that are older than :data:`STALE_SECONDS`, by name, and nothing
else.  A write that fails (full disk, unwritable folder, text that is not ASCII) raises
:class:`OutputError`, naming the path and the reason.
"""
from __future__ import annotations

import contextlib
import os
import re
import tempfile
import time

from ..toolpath.ir.errors import InputError

PREFIX, SUFFIX = ".kezuri-", ".part"
STALE_SECONDS = 3600.0      # a temporary file of ours this old belongs to a write that died
# mkstemp's names: the prefix, 8 characters of [a-z0-9_], the suffix (plus an extension from
# :func:`atomic_path`)
_OURS = re.compile(r"\.kezuri-[a-z0-9_]{8}\.part(\.[A-Za-z0-9]{1,8})?\Z")


class OutputError(InputError):
    """A file could not be written; the message names the path and the reason."""


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _why(error: OSError) -> str:
    return error.strerror or str(error)


def clean_stale_temporaries(folder: str, older_than: float = STALE_SECONDS) -> list:
    """Remove our temporary files (by name) in ``folder`` last modified more than ``older_than``
    seconds ago; returns their paths.  Anything it cannot list or remove is left alone."""
    removed = []
    now = time.time()
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return removed
    for entry in entries:
        if not _OURS.match(entry.name):
            continue
        try:
            if entry.is_file(follow_symlinks=False) and now - entry.stat(follow_symlinks=False).st_mtime > older_than:
                os.unlink(entry.path)
                removed.append(entry.path)
        except OSError:
            continue
    return removed


def check_folder(folder: str, given_as: str = "output folder") -> str:
    """The absolute ``folder`` if files can be written there, made or not; nothing is created.

    Raises :class:`OutputError` naming ``given_as`` and the path when it is a file, lies under a
    file, or would have to be made in a folder this process cannot write."""
    if not folder.strip():      # an unset shell variable ("$OUT"): it wrote into the working folder
        raise OutputError(f"{given_as} is empty: give the folder to write into")
    folder = os.path.abspath(folder)
    existing = folder
    while not os.path.exists(existing):
        parent = os.path.dirname(existing)
        if parent == existing:
            break
        existing = parent
    if existing == folder and not os.path.isdir(folder):
        raise OutputError(f"{given_as} {folder} is a file, not a folder")
    if not os.path.isdir(existing):
        raise OutputError(f"{given_as} {folder} cannot be made: {existing} is a file")
    if not os.access(existing, os.W_OK | os.X_OK):
        if existing == folder:
            raise OutputError(f"{given_as} {folder} cannot be written")
        raise OutputError(f"{given_as} {folder} cannot be made: {existing} cannot be written")
    return folder


def _folder_of(path: str) -> str:
    folder = os.path.dirname(path)
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as error:
        raise OutputError(f"cannot write {path}: cannot make the folder {folder} ({_why(error)})") from None
    clean_stale_temporaries(folder)
    return folder


def write_atomic(path: str, text: str | bytes) -> str:
    """Write ``text`` (ASCII) or ``bytes`` to ``path`` through a temporary file in the same folder,
    then rename.

    A crash or a full disk leaves the previous file (or none), never a half-written program.
    Raises :class:`OutputError` naming the path when it cannot write.
    """
    path = os.path.abspath(path)
    folder = _folder_of(path)
    binary = isinstance(text, bytes)
    if not binary:
        try:
            text.encode("ascii")
        except UnicodeEncodeError as error:
            raise OutputError(f"cannot write {path}: the text is not ASCII ({text[error.start:error.end]!r} at "
                              f"character {error.start})") from None
    try:
        handle, temp = tempfile.mkstemp(prefix=PREFIX, suffix=SUFFIX, dir=folder)
    except OSError as error:
        raise OutputError(f"cannot write {path}: {_why(error)}") from None
    with _renamed_onto(temp, path):
        with os.fdopen(handle, "wb" if binary else "w", **({} if binary else {"encoding": "ascii",
                                                                                 "newline": "\n"})) as stream:
            stream.write(text)
            stream.flush()
            os.fsync(stream.fileno())
    return path


@contextlib.contextmanager
def _renamed_onto(temp: str, path: str):
    """When the block has written ``temp`` without error: the usual permissions (mkstemp makes
    0600) and a rename onto ``path``; otherwise ``temp`` is removed and a write error names ``path``."""
    try:
        yield
        os.chmod(temp, 0o666 & ~_umask())
        os.replace(temp, path)
    except OSError as error:
        _remove(temp)
        raise OutputError(f"cannot write {path}: {_why(error)}") from None
    except BaseException:
        _remove(temp)
        raise


def _remove(temp: str) -> None:
    with contextlib.suppress(OSError):
        os.unlink(temp)


@contextlib.contextmanager
def atomic_path(path: str):
    """For a writer that needs a file name (Blender's renderer writing a PNG): yields a temporary
    path beside ``path`` with the same extension; when the block ends without error the file
    written there is renamed onto ``path``, otherwise it is removed.  Raises :class:`OutputError`
    naming ``path`` when the folder cannot be written or nothing was written.

        with atomic_path("out/preview.png") as temp:
            scene.render.filepath = temp
            bpy.ops.render.render(write_still=True)
    """
    path = os.path.abspath(path)
    folder = _folder_of(path)
    extension = os.path.splitext(path)[1]
    if not re.fullmatch(r"(\.[A-Za-z0-9]{1,8})?", extension):
        extension = ""
    try:
        handle, temp = tempfile.mkstemp(prefix=PREFIX, suffix=SUFFIX + extension, dir=folder)
        os.close(handle)
        os.unlink(temp)             # the writer makes it; a leftover empty file would hide a failed write
    except OSError as error:
        raise OutputError(f"cannot write {path}: {_why(error)}") from None
    with _renamed_onto(temp, path):
        yield temp
        if not os.path.isfile(temp):
            raise OutputError(f"cannot write {path}: nothing was written")


class Staging:
    """All of a run's files or none: the run writes into a hidden folder beside ``out`` (on the same
    file system), and :meth:`commit` moves every file in once all are written; :meth:`discard`
    (a failure, a refusal, a stop) removes the folder and leaves ``out`` as it was.

    ``out`` itself is made only by the commit, so a refused run leaves no empty folder behind.
    Paths the run reports point into :attr:`folder`; :meth:`final` maps them to where the files
    end up (report values and messages alike).
    """

    def __init__(self, out: str, given_as: str = "--out"):
        self.out = check_folder(out, given_as)
        anchor = self.out
        while not os.path.isdir(anchor):
            anchor = os.path.dirname(anchor)
        try:
            self.folder = tempfile.mkdtemp(prefix=".kezuri-staging-", dir=anchor)
        except OSError as error:
            raise OutputError(f"{given_as} {self.out} cannot be written: {_why(error)}") from None

    def final(self, value):
        """``value`` (a path, a message, or a report of dicts and lists) with the staging folder
        replaced by the output folder."""
        if isinstance(value, str):
            return value.replace(self.folder, self.out)
        if isinstance(value, dict):
            return {key: self.final(item) for key, item in value.items()}
        if isinstance(value, (list, tuple)):
            return type(value)(self.final(item) for item in value)
        return value

    def files(self) -> list:
        """The staged files, relative to the staging folder."""
        found = []
        for directory, _, names in os.walk(self.folder):
            found += [os.path.relpath(os.path.join(directory, name), self.folder) for name in names]
        return sorted(found)

    def commit(self) -> list:
        """Move every staged file into ``out`` (replacing files of the same name); returns the
        final paths.  Everything is checked before the first file moves."""
        moves = [(os.path.join(self.folder, rel), os.path.join(self.out, rel)) for rel in self.files()]
        for _, target in moves:
            if os.path.isdir(target):
                raise OutputError(f"cannot write {target}: a folder of that name is in the way")
        try:
            for source, target in moves:
                os.makedirs(os.path.dirname(target), exist_ok=True)
                os.replace(source, target)
        except OSError as error:
            raise OutputError(f"cannot move the files into {self.out}: {_why(error)}") from None
        finally:
            self.discard()
        return [target for _, target in moves]

    def discard(self) -> None:
        import shutil
        shutil.rmtree(self.folder, ignore_errors=True)
