"""Profile / cut-out in the shell: for now an operation of job files.  Its object slot ``shape`` is a
closed curve, a Text or a mesh (its outlines seen from above, in the plate's work frame, so it shares
the job's work zero); ``tabs = [[x, y], ...]`` in work mm puts tabs where the user wants them; its
settings by name (:data:`SETTINGS`)."""
from __future__ import annotations

import math

import numpy as np

from ..toolpath.job import JobOperation, Setup
from ..toolpath.operations.profile import profile as core
from ..toolpath.operations.profile.kind import ProfileGeometry
from .workflow import Workflow

POST_FAMILIES = ("milling",)
# settings key -> what it is (the tool's parts and every ProfileSettings number and word)
SETTINGS = {
    "tool_number": "the end mill's tool number", "diameter": "the end mill's diameter (mm)",
    "flute_length": "the end mill's flute length (mm)", "side": "outside, inside or on",
    "climb": "true: climb milling, false: conventional", "depth": "depth below the top (mm); 0 or not given: through",
    "breakthrough": "how far below the stock a cut through goes (mm)", "step_down": "deepest step (mm)",
    "allowance": "left for the finishing pass (mm), 0: none", "rpm": "spindle speed", "feed": "cutting feed (mm/min)",
    "plunge_feed": "feed down into the cleared kerf (mm/min)", "ramp_angle": "ramp entry angle (degrees)",
    "tab_count": "tabs on every contour", "tab_spacing": "a tab every ... mm round each contour",
    "tab_width": "tab width (mm)", "tab_height": "tab height (mm)", "tab_shape": "flat or triangle",
    "lead": "arc, line or none", "lead_radius": "lead-in and lead-out radius or length (mm)",
}
WORDS = {"side", "tab_shape", "lead"}


def settings_from(entry, tabs) -> core.ProfileSettings:
    from .jobentry import JobFileError

    given = dict(entry.settings)
    for key, value in given.items():
        if key not in SETTINGS:
            raise JobFileError(f"{entry.where}: settings.{key} is not a profile setting; they are "
                               f"{', '.join(SETTINGS)}")
        if key in WORDS:
            if not isinstance(value, str):
                raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not a word")
        elif key == "climb":
            if not isinstance(value, bool):
                raise JobFileError(f"{entry.where}: settings.climb = {value!r} is not true or false")
        elif isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not a number")
    for key in ("tool_number", "tab_count"):
        if key in given and not isinstance(given[key], int):
            raise JobFileError(f"{entry.where}: settings.{key} = {given[key]!r} is not a whole number")
    default = core.ProfileSettings()
    try:
        tool = core.check_tool(given.pop("tool_number", default.tool.number),
                               given.pop("diameter", default.tool.diameter),
                               given.pop("flute_length", default.tool.flute_length))
    except core.ProfileError as error:
        raise JobFileError(f"{entry.where}: the end mill: {str(error).removeprefix('profile: tool: ')}") from None
    if given.get("depth") == 0:
        del given["depth"]                     # 0: through (the panel's way of saying "no depth")
    floats = {key: float(value) for key, value in given.items() if key not in WORDS | {"climb", "tab_count"}}
    rest = {key: value for key, value in given.items() if key in WORDS | {"climb", "tab_count"}}
    return core.ProfileSettings(tool=tool, tabs=tabs, **floats, **rest)


def read_tabs(entry) -> tuple:
    from .jobentry import JobFileError

    tabs = entry.table.get("tabs", [])
    if not isinstance(tabs, list):
        raise JobFileError(f"{entry.where}: tabs must be a list of [x, y] points in work mm")
    found = []
    for index, point in enumerate(tabs):
        if (not isinstance(point, list) or len(point) != 2 or
                any(isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) for v in point)):
            raise JobFileError(f"{entry.where}: tabs[{index}] = {point!r} is not an [x, y] point in mm")
        found.append((float(point[0]), float(point[1])))
    return tuple(found)


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's profile: objects ``shape`` (and ``plate``: the stock, default the scene's),
    ``tabs`` and settings by name.  No shape (or ``outline = "plate"``): the plate's own outline, the
    sign cut out of its board.  The work frame is the plate's, as the engraving's."""
    from . import convert
    from .jobentry import JobFileError

    objects = {slot: obj for slot, obj in entry.objects.items() if obj is not None}     # a row's empty slot
    slots = {"shape", "plate"}
    for slot in objects:
        if slot not in slots:
            raise JobFileError(f"{entry.where}: objects.{slot}: a profile's objects are shape and plate")
    outline = entry.table.get("outline")
    if outline is not None and outline != "plate":
        raise JobFileError(f"{entry.where}: outline = {outline!r}: the only outline a profile takes by name is "
                           "\"plate\" (the plate's own); give other shapes as objects.shape")
    if outline is not None and "shape" in objects:
        raise JobFileError(f"{entry.where}: give objects.shape or outline = \"plate\", not both")
    if "plate" in objects:
        scene.kezuri.stock.plate = objects["plate"]
    if scene.kezuri.stock.plate is None and "shape" not in objects:
        raise JobFileError(f"{entry.where}: no shape and no plate: give objects = {{ shape = \"...\" }} (a closed "
                           "curve, Text or mesh), or pick the plate to cut out its outline")
    try:
        plate = convert.plate_from_object(scene.kezuri.stock.plate, depsgraph, scene, scene.kezuri.stock.origin)
        convert.check_fits(plate, scene)
        if "shape" in objects:
            loops, what = convert.outlines_in_work(objects["shape"], depsgraph, plate.frame), \
                f"object {objects['shape'].name!r}"
        else:
            loops, what = [np.asarray(loop, float) for loop in plate.outline], f"the plate {plate.name!r}'s outline"
        settings = settings_from(entry, read_tabs(entry))
        settings.check(float(plate.size[2]))
    except core.ProfileError as error:
        raise JobFileError(f"{entry.where}: the profile: {str(error).removeprefix('profile: ')}") from None
    geometry = ProfileGeometry(tuple(tuple(map(tuple, loop[:, :2].tolist())) for loop in loops), float(plate.size[2]),
                               0.0, what, entry.name)
    setup = _setup(scene, post_name, plate)
    return JobOperation("profile", entry.name, settings, geometry, entry.enabled), setup, plate.frame


def _setup(scene, post_name: str, plate) -> Setup:
    from ..toolpath.operations.engrave import engrave
    from .machines import scene_machine

    machine = scene_machine(scene.kezuri.machine, POST_FAMILIES, post_name)
    from . import convert
    return Setup(name=scene.name, post=post_name, machine=machine, work_offset=scene.kezuri.machine.work_offset,
                 rapid_rate=scene.kezuri.machine.rapid_rate, stock=engrave.plate_stock(plate.outline, plate.size[2]))


def settings_group() -> type:
    """The profile's settings as panel properties (names, units and defaults of ProfileSettings)."""
    from . import kindsettings as ks

    d = core.ProfileSettings()
    return ks.settings_group("KezuriProfileSettings", {
        **ks.tool_fields(d.tool, "end mill"),
        "side": ks.choice("Side", d.side, "Which side of the outline the tool cuts", (
            ("outside", "Outside", "Cut the part out: the tool runs outside the outline"),
            ("inside", "Inside", "Cut a hole: the tool runs inside the outline"),
            ("on", "On the Line", "The tool's centre on the outline"))),
        "climb": ks.switch("Climb Milling", d.climb, "Climb milling (off: conventional)"),
        "depth": ks.length("Depth", 0.0, "Depth below the top; 0: through the stock and the breakthrough"),
        "breakthrough": ks.length("Breakthrough", d.breakthrough, "How far below the stock a cut through goes"),
        "step_down": ks.length("Step Down", d.step_down, "Deepest cut of one level"),
        "allowance": ks.length("Allowance", d.allowance, "Left for the finishing pass; 0: no finishing pass"),
        "rpm": ks.number("Spindle", d.rpm, "Spindle speed", "rpm", 0),
        "feed": ks.number("Feed", d.feed, "Cutting feed", "mm/min", 0),
        "plunge_feed": ks.number("Plunge Feed", d.plunge_feed, "Feed down the ramps", "mm/min", 0),
        "ramp_angle": ks.number("Ramp Angle", d.ramp_angle, "Slope of the ramp entry", "degrees"),
        "tab_count": ks.whole("Tabs", d.tab_count, "Tabs on every contour (0: none, or by spacing)"),
        "tab_spacing": ks.length("Tab Spacing", d.tab_spacing, "A tab every ... round each contour; 0: by count"),
        "tab_width": ks.length("Tab Width", d.tab_width, "Width of a tab along the contour"),
        "tab_height": ks.length("Tab Height", d.tab_height, "Height of a tab above the cut's bottom"),
        "tab_shape": ks.choice("Tab Shape", d.tab_shape, "The tab's profile along the contour", (
            ("flat", "Flat", "A flat top with 45 degree ends"),
            ("triangle", "Triangle", "A ridge as wide and high as the tab"))),
        "lead": ks.choice("Lead", d.lead, "How the finishing pass comes onto the contour and leaves it", (
            ("arc", "Arc", "A quarter arc in the waste"), ("line", "Line", "A line along the normal in the waste"),
            ("none", "None", "Straight onto the contour"))),
        "lead_radius": ks.length("Lead Radius", d.lead_radius, "The lead's radius or length"),
    })


PANELS = (("Cut", ("side", "climb", "depth", "breakthrough", "step_down", "allowance")),
          ("Tabs", ("tab_count", "tab_spacing", "tab_width", "tab_height", "tab_shape")),
          ("Tool & Feeds", ("tool_number", "diameter", "flute_length", "rpm", "feed", "plunge_feed", "ramp_angle")),
          ("Lead-In & Out", ("lead", "lead_radius")))

WORKFLOW = Workflow("PROFILE", "Profile", "Cut along an outline, inside, outside or on it, with tabs",
                    post_families=POST_FAMILIES, kind="profile", job_operation=job_operation,
                    settings_group=settings_group(), settings_panels=PANELS)
