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


VALUE_TYPES = {"BOOLEAN", "INT", "FLOAT", "STRING", "ENUM"}


def setting_names(group) -> list:
    """The settings of a panel's property group: its values (not its object pointers)."""
    return [prop.identifier for prop in group.bl_rna.properties
            if prop.identifier not in ("rna_type", "name") and prop.type in VALUE_TYPES]


def apply_settings(group, entry: JobEntry, skip=()) -> None:
    """The entry's settings into a panel's property group, each checked: an unknown name or a
    value the property does not hold as given is an error naming it.  A setting the entry does
    not name is set back to its default first (what another operation or the .blend left there
    does not leak in), so an entry means the same in a fresh scene and in the panel's."""
    from .batchio import set_exactly
    from .limits import check_group

    for key in setting_names(group):
        if key not in skip and key not in entry.settings:
            group.property_unset(key)
    for key, value in entry.settings.items():
        if key in skip:
            continue
        if key not in group.bl_rna.properties or key == "rna_type":
            raise JobFileError(f"{entry.where}: settings.{key} is not a setting of {entry.kind}")
        try:
            if group.bl_rna.properties[key].type == "BOOLEAN" and isinstance(value, bool):
                setattr(group, key, value)              # a switch (set_exactly takes numbers and words)
            else:
                set_exactly(group, key, value, f"{entry.where}: settings.{key}")
        except (TypeError, ValueError) as error:       # a word a menu does not hold, a text for a number
            raise JobFileError(f"{entry.where}: settings.{key} = {value!r}: {error}") from None
    if not getattr(group, "checked_by_kind", False):     # a router kind's own checks refuse its values
        check_group(group, entry.kind)


def settings_of(group, skip=(), keep=()) -> dict:
    """The group's settings that differ from their defaults, and those named in ``keep`` whatever
    their value, by property name (what :func:`apply_settings` puts back): floats as the shortest
    text their single-precision property holds (0.3, not 0.30000001192092896)."""
    import numpy as np

    found = {}
    for key in setting_names(group):
        prop = group.bl_rna.properties[key]
        if key in skip or getattr(prop, "is_array", False) or prop.is_hidden:
            continue
        value = getattr(group, key)
        if prop.type == "FLOAT":
            value = float(str(np.float32(value)))
            if value == float(str(np.float32(prop.default))) and key not in keep:
                continue
        elif value == prop.default and key not in keep:
            continue
        found[key] = value
    return found
