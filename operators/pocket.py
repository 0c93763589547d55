"""Pocketing in the shell: for now an operation of job files (its panel comes later): the object
in the ``region`` slot (closed curves, a Text, mesh faces; seen from above, read even-odd so inner
loops are islands) in the plate's work frame, and the pocket's settings by name."""
from __future__ import annotations

import math

from ..toolpath.ir.program import ProgramError
from ..toolpath.job import JobOperation, Setup
from ..toolpath.operations.pocket import pocket as core
from ..toolpath.operations.pocket.kind import PocketGeometry, PocketKind
from . import convert
from .workflow import Workflow

POST_FAMILIES = ("milling",)
NUMBERS = ("depth", "step_down", "stepover", "angle", "helix_diameter", "ramp_angle", "wall_allowance",
           "floor_allowance", "rest_stepover", "rest_step_down", "rest_rpm", "rest_feed", "rpm", "feed",
           "entry_feed", "clearance_z", "safe_z")
WORDS = ("strategy", "entry")
SWITCHES = ("finish_walls", "finish_floor")
TOOL = ("tool_number", "diameter", "flute_length", "rest_tool_number", "rest_diameter", "rest_flute_length")
SETTINGS = NUMBERS + WORDS + SWITCHES + TOOL


def settings_from(entry) -> core.PocketSettings:
    """The pocket's settings from a job file's ``settings`` table, each checked by name."""
    from .jobentry import JobFileError

    given = dict(entry.settings)
    for key, value in given.items():
        if key not in SETTINGS:
            raise JobFileError(f"{entry.where}: settings.{key} is not a pocket setting; they are {', '.join(SETTINGS)}")
        if key in WORDS:
            if not isinstance(value, str):
                raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not a word")
        elif key in SWITCHES:
            if not isinstance(value, bool):
                raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not true or false")
        elif isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not a number")
    for key in ("tool_number", "rest_tool_number"):
        if key in given and not isinstance(given[key], int):
            raise JobFileError(f"{entry.where}: settings.{key} = {given[key]!r} is not a whole number")
    default = core.PocketSettings()
    try:
        tool = core.end_mill(given.get("tool_number", default.tool.number),
                             float(given.get("diameter", default.tool.diameter)),
                             float(given.get("flute_length", default.tool.flute_length)))
        rest = None
        if "rest_diameter" in given:
            rest = core.end_mill(given.get("rest_tool_number", tool.number + 1), float(given["rest_diameter"]),
                                 float(given.get("rest_flute_length", tool.flute_length)))
        elif "rest_tool_number" in given or "rest_flute_length" in given:
            raise JobFileError(f"{entry.where}: rest machining needs settings.rest_diameter")
    except ProgramError as error:
        raise JobFileError(f"{entry.where}: the end mill: {error}") from None
    values = {key: given[key] for key in WORDS + SWITCHES if key in given}
    values.update({key: float(given[key]) for key in NUMBERS if key in given})
    return core.PocketSettings(tool=tool, rest_tool=rest, **values)


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's pocket: objects ``region`` (and ``plate``: the stock, default the CAM panel's),
    the settings by name; geometry in work mm in the plate's frame (the plate's top at Z = 0)."""
    from .jobentry import JobFileError
    from .machines import scene_machine

    slots = ("region", "plate")
    for slot in entry.objects:
        if slot not in slots:
            raise JobFileError(f"{entry.where}: objects.{slot}: a pocket's objects are {', '.join(slots)}")
    if "region" not in entry.objects:
        raise JobFileError(f"{entry.where}: no region: give objects = {{ region = \"<curve, Text or mesh>\" }}")
    settings = scene.kezuri
    plate = convert.plate_from_object(entry.objects.get("plate", settings.stock.plate), depsgraph, scene,
                                      settings.stock.origin)
    convert.check_fits(plate, scene)
    obj = entry.objects["region"]
    loops = convert.outlines_in_work(obj, depsgraph, plate.frame)
    pocket_settings = settings_from(entry)
    try:
        pocket_settings.check(f"pocket {entry.name!r}")
        core.region_of(loops, f"pocket {entry.name!r} (object {obj.name!r})")
    except core.PocketError as error:
        raise JobFileError(f"{entry.where}: the pocket: {error}") from None
    geometry = PocketGeometry(tuple(loops), entry.name, 0.0, tuple(plate.outline), float(plate.size[2]))
    stock = PocketKind.stock(geometry, None, pocket_settings)
    machine = scene_machine(settings.machine, POST_FAMILIES, post_name)
    setup = Setup(name=scene.name, post=post_name, machine=machine,
                  work_offset=settings.machine.work_offset, rapid_rate=settings.machine.rapid_rate, stock=stock)
    return JobOperation("pocket", entry.name, pocket_settings, geometry, entry.enabled), setup, plate.frame


WORKFLOW = Workflow("POCKET", "Pocket", "Clear closed regions with islands to a flat floor (job files)",
                    post_families=POST_FAMILIES, kind="pocket", job_operation=job_operation)
