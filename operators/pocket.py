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
        for key in ("rest_diameter", "rest_tool_number", "rest_flute_length"):
            if given.get(key) == 0:
                del given[key]          # 0: no rest machining / the next tool number / the main tool's flutes
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
    objects = {slot: obj for slot, obj in entry.objects.items() if obj is not None}     # a row's empty slot
    for slot in objects:
        if slot not in slots:
            raise JobFileError(f"{entry.where}: objects.{slot}: a pocket's objects are {', '.join(slots)}")
    if "region" not in objects:
        raise JobFileError(f"{entry.where}: no region: give objects = {{ region = \"<curve, Text or mesh>\" }}")
    settings = scene.kezuri
    plate = convert.plate_from_object(objects.get("plate", settings.stock.plate), depsgraph, scene,
                                      settings.stock.origin)
    convert.check_fits(plate, scene)
    obj = objects["region"]
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


def settings_group() -> type:
    """The pocket's settings as panel properties (names, units and defaults of PocketSettings)."""
    from . import kindsettings as ks

    d = core.PocketSettings()
    return ks.settings_group("KezuriPocketSettings", {
        **ks.tool_fields(d.tool, "end mill"),
        "depth": ks.length("Depth", d.depth, "Depth of the floor below the top"),
        "step_down": ks.length("Step Down", d.step_down, "Deepest cut of one level"),
        "stepover": ks.length("Stepover", d.stepover, "Between neighbouring paths, at most the diameter"),
        "strategy": ks.choice("Strategy", d.strategy, "How the region is cleared", (
            ("offset", "Offset", "Rings from the inside out along the walls"),
            ("zigzag", "Zigzag", "A raster at the angle, then a ring along the walls"))),
        "angle": ks.number("Angle", d.angle, "Zigzag: direction of the raster from +X", "degrees"),
        "entry": ks.choice("Entry", d.entry, "How each level is entered", (
            ("helix", "Helix", "A helix inside the region (a ramp where none fits)"),
            ("ramp", "Ramp", "A ramp along the path"))),
        "helix_diameter": ks.length("Helix Diameter", d.helix_diameter, "Of the helix the tool's centre follows"),
        "ramp_angle": ks.number("Ramp Angle", d.ramp_angle, "Slope of the helix and the ramps", "degrees"),
        "finish_walls": ks.switch("Finish Walls", d.finish_walls, "A ring along every wall at the end"),
        "wall_allowance": ks.length("Wall Allowance", d.wall_allowance, "Left on the walls by roughing"),
        "finish_floor": ks.switch("Finish Floor", d.finish_floor, "A pass over the floor at the full depth"),
        "floor_allowance": ks.length("Floor Allowance", d.floor_allowance, "Left on the floor by roughing"),
        "rpm": ks.number("Spindle", d.rpm, "Spindle speed", "rpm", 0),
        "feed": ks.number("Feed", d.feed, "Cutting feed", "mm/min", 0),
        "entry_feed": ks.number("Entry Feed", d.entry_feed, "Feed down the helices and ramps", "mm/min", 0),
        "clearance_z": ks.length("Clearance Plane", d.clearance_z, "Height of rapid moves between cuts"),
        "safe_z": ks.length("Safe Z", d.safe_z, "Height where the operation starts and ends"),
        "rest_diameter": ks.length("Rest Diameter", 0.0, "A smaller end mill for what the tool cannot reach; "
                                                         "0: no rest machining"),
        "rest_tool_number": ks.whole("Rest Tool", 0, "The rest end mill's tool number; 0: the next after the tool's"),
        "rest_flute_length": ks.length("Rest Flutes", 0.0, "The rest end mill's flute length; 0: the tool's"),
        "rest_stepover": ks.length("Rest Stepover", d.rest_stepover, "Between the rest end mill's paths"),
        "rest_step_down": ks.length("Rest Step Down", d.rest_step_down, "The rest end mill's deepest cut"),
        "rest_rpm": ks.number("Rest Spindle", d.rest_rpm, "The rest end mill's spindle speed", "rpm", 0),
        "rest_feed": ks.number("Rest Feed", d.rest_feed, "The rest end mill's feed", "mm/min", 0),
    })


PANELS = (("Clearing", ("depth", "step_down", "stepover", "strategy", "angle", "entry", "helix_diameter",
                        "ramp_angle")),
          ("Finishing", ("finish_walls", "wall_allowance", "finish_floor", "floor_allowance")),
          ("Tool & Feeds", ("tool_number", "diameter", "flute_length", "rpm", "feed", "entry_feed", "clearance_z",
                            "safe_z")),
          ("Rest Machining", ("rest_diameter", "rest_tool_number", "rest_flute_length", "rest_stepover",
                              "rest_step_down", "rest_rpm", "rest_feed")))

WORKFLOW = Workflow("POCKET", "Pocket", "Clear closed regions with islands to a flat floor",
                    post_families=POST_FAMILIES, kind="pocket", job_operation=job_operation,
                    settings_group=settings_group(), settings_panels=PANELS)
