"""What one ``[[operations]]`` table of a job file gives its operation kind's shell module: the
entry (objects, settings, the words that name it), the error every job-file problem raises, and
the settings put into a panel's property group as the panel would take them."""
from __future__ import annotations

from dataclasses import dataclass

from ..toolpath.ir.errors import InputError


class JobFileError(InputError):
    """A job file that cannot be run as written: the message names the file, the table and the key."""


@dataclass
class JobEntry:
    """One ``[[operations]]`` table, read: ``objects`` by slot (Blender objects), ``settings`` as
    typed, ``where`` the words that name it in messages."""

    name: str
    kind: str
    enabled: bool
    objects: dict
    settings: dict
    table: dict
    where: str
    base_dir: str = "."      # where the job file's relative paths start


def apply_settings(group, entry: JobEntry, skip=()) -> None:
    """The entry's settings into a panel's property group, each checked: an unknown name or a
    value the property does not hold as given is an error naming it."""
    from .batchio import set_exactly
    from .limits import check_group

    for key, value in entry.settings.items():
        if key in skip:
            continue
        if key not in group.bl_rna.properties or key == "rna_type":
            raise JobFileError(f"{entry.where}: settings.{key} is not a setting of {entry.kind}")
        set_exactly(group, key, value, f"{entry.where}: settings.{key}")
    check_group(group, entry.kind)
