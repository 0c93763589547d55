"""Drilling in the shell: for now an operation of job files only (``holes`` in work mm and the
drill's settings); its panel comes with the router operations (issue 29)."""
from __future__ import annotations

import math

from ..toolpath.ir.program import ProgramError, Tool
from ..toolpath.job import JobOperation
from ..toolpath.operations.drill import drill as core
from ..toolpath.operations.drill.kind import DrillGeometry
from .workflow import Workflow

POST_FAMILIES = ("milling",)
# settings key -> (DrillSettings field or tool part, what it is)
SETTINGS = {"tool_number": "the drill's tool number", "diameter": "the drill's diameter (mm)",
            "flute_length": "the drill's flute length (mm)", "depth": "depth below the top (mm)",
            "peck": "deepest peck (mm), 0: none", "rpm": "spindle speed", "feed": "feed down the hole (mm/min)"}


def settings_from(entry) -> core.DrillSettings:
    from .jobentry import JobFileError

    given = dict(entry.settings)
    for key, value in given.items():
        if key not in SETTINGS:
            raise JobFileError(f"{entry.where}: settings.{key} is not a drilling setting; they are "
                               f"{', '.join(SETTINGS)}")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not a number")
    if "tool_number" in given and not isinstance(given["tool_number"], int):
        raise JobFileError(f"{entry.where}: settings.tool_number = {given['tool_number']!r} is not a whole number")
    default = core.DrillSettings()
    try:
        tool = Tool(given.get("tool_number", default.tool.number), "drill",
                    float(given.get("diameter", default.tool.diameter)),
                    flute_length=float(given.get("flute_length", default.tool.flute_length)),
                    name=f"{float(given.get('diameter', default.tool.diameter)):g} mm drill")
    except ProgramError as error:
        raise JobFileError(f"{entry.where}: the drill: {error}") from None
    numbers = {key: float(given[key]) for key in ("depth", "peck", "rpm", "feed") if key in given}
    return core.DrillSettings(tool=tool, **numbers)


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's drilling: ``holes = [[x, y], ...]`` in work mm (the plate's top at Z = 0)."""
    from .jobentry import JobFileError

    if entry.objects:
        raise JobFileError(f"{entry.where}: drilling takes its holes as holes = [[x, y], ...], not objects")
    if "holes" not in entry.table:
        raise JobFileError(f"{entry.where}: no holes: give holes = [[x, y], ...] in work mm")
    try:
        holes = core.check_holes(entry.table["holes"])
        settings = settings_from(entry)
        settings.check()
    except core.DrillError as error:
        raise JobFileError(f"{entry.where}: the holes or the drill: {error}") from None
    geometry = DrillGeometry(tuple(map(tuple, holes.tolist())), 0.0)
    return JobOperation("drill", entry.name, settings, geometry, entry.enabled), None, None


WORKFLOW = Workflow("DRILL", "Drilling", "Pecked holes at given centres (job files)", post_families=POST_FAMILIES,
                    kind="drill", job_operation=job_operation)
