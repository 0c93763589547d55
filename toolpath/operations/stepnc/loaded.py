"""An ISO 14649 file read into its model: :class:`LoadedWorkplan` (the project, its workingsteps in
workplan order, the warnings), from a path or from the file's Part 21 text.  The model is frozen
dataclasses: a caller that has read a text may hand its model on (:class:`.kind.StepncGeometry`'s
``loaded``) instead of having it read again."""
from __future__ import annotations

import gc
import os
from dataclasses import dataclass

from ...engines.textfile import read_text
from .model import Project, Workingstep
from .part21 import parse_part21
from .reader import read_project


@dataclass(frozen=True)
class LoadedWorkplan:
    """What :func:`load_workplan` returns: the model, its workingsteps in workplan order (nested
    workplans flattened, unsupported ones left out) and the warnings about what was left out."""

    project: Project
    workingsteps: tuple
    warnings: tuple

    def workingstep(self, ident: int) -> Workingstep:
        for step in self.workingsteps:
            if step.id == ident:
                return step
        raise KeyError(f"no workingstep #{ident}")


def load_workplan(source) -> LoadedWorkplan:
    """Read an ISO 14649 file, from a path or from its Part 21 text.

    Raises Part21Error for a syntax error or a reference to an undefined instance and
    StepNcError for malformed ISO 14649 data; both name the instance.
    """
    if isinstance(source, str) and "ISO-10303-21;" in source:
        return workplan_from_text(source)
    return workplan_from_text(read_text(os.fspath(source)))


def workplan_from_text(text: str) -> LoadedWorkplan:
    """:func:`load_workplan` of a file's Part 21 text (whatever its first lines say)."""
    # The instances and the model's tuples all stay alive while they are read: the cyclic garbage
    # collector would rescan them again and again (two thirds of the reading of a big file)
    enabled = gc.isenabled()
    gc.disable()
    try:
        return workplan_of(parse_part21(text))
    finally:
        if enabled:
            gc.enable()


def workplan_of(part21) -> LoadedWorkplan:
    project, warnings = read_project(part21)
    return LoadedWorkplan(project, tuple(project.main_workplan.workingsteps()), tuple(warnings))
