"""Chamfer / deburr in the shell: an operation of job files and the job list.  ``objects = { edges =
"Outline" }`` names a curve, Text or mesh whose closed outlines (seen from above, in the stock
plate's work frame) have their top edges chamfered with a V-bit; round holes (``holes = [[x, y,
diameter], ...]`` or ``objects.holes``) are chamfered along circles; settings by name (:data:`SETTINGS`)."""
from __future__ import annotations

import math

from ..toolpath.ir.program import ProgramError, Tool
from ..toolpath.job import JobOperation
from ..toolpath.operations.chamfer import chamfer as core
from ..toolpath.operations.chamfer import holes as hole_circles
from ..toolpath.operations.chamfer.kind import ChamferGeometry
from .workflow import Workflow

POST_FAMILIES = ("milling",)
SETTINGS = {"tool_number": "the V-bit's tool number", "diameter": "the V-bit's diameter (mm)",
            "flute_length": "the V-bit's flute length (mm)", "width": "across the top (mm)",
            "depth": "down the wall (mm)", "tip_gap": "the tip below the chamfer (mm)", "rpm": "spindle speed",
            "feed": "feed (mm/min)", "plunge_feed": "feed down the entry ramp (mm/min)"}


def settings_from(entry) -> core.ChamferSettings:
    from .jobentry import JobFileError

    given = dict(entry.settings)
    for key, value in given.items():
        if key not in SETTINGS:
            raise JobFileError(f"{entry.where}: settings.{key} is not a chamfer setting; they are "
                               f"{', '.join(SETTINGS)}")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not a number")
    if "tool_number" in given and not isinstance(given["tool_number"], int):
        raise JobFileError(f"{entry.where}: settings.tool_number = {given['tool_number']!r} is not a whole number")
    default = core.ChamferSettings()
    try:
        diameter = float(given.get("diameter", default.tool.diameter))
        tool = Tool(given.get("tool_number", default.tool.number), "vbit", diameter,
                    flute_length=float(given.get("flute_length", default.tool.flute_length)),
                    name=f"{diameter:g} mm V-bit")
    except ProgramError as error:
        raise JobFileError(f"{entry.where}: the V-bit: {error}") from None
    numbers = {key: float(given[key]) for key in ("width", "depth", "tip_gap", "rpm", "feed", "plunge_feed")
               if key in given}
    if "depth" in numbers and "width" not in numbers:
        numbers["width"] = 0.0                  # the depth given: the width follows from it
    return core.ChamferSettings(tool=tool, **numbers)


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's chamfer: ``objects = { edges = "<curve, Text or mesh>" }`` (its outlines' top
    edges), and/or round holes: ``holes = [[x, y, diameter], ...]`` in work mm or ``objects = { holes =
    "<curve or mesh>" }`` (its circles or cylindrical holes, found as the drilling finds them)."""
    from . import convert
    from .drill import holes_of
    from .jobentry import JobFileError

    objects = {slot: obj for slot, obj in entry.objects.items() if obj is not None}     # a row's empty slot
    unknown = [slot for slot in objects if slot not in ("edges", "holes")]
    if unknown:
        raise JobFileError(f"{entry.where}: objects.{unknown[0]}: a chamfer takes objects.edges (a curve, Text "
                           "or mesh) and objects.holes (a curve or mesh with round holes)")
    if "holes" in objects and "holes" in entry.table:
        raise JobFileError(f"{entry.where}: give the holes as holes = [[x, y, diameter], ...] or as objects.holes, "
                           "not both")
    if "edges" not in objects and "holes" not in objects and "holes" not in entry.table:
        raise JobFileError(f"{entry.where}: no edges: give objects = {{ edges = \"<curve, Text or mesh>\" }} or "
                           "holes = [[x, y, diameter], ...]")
    try:
        settings = settings_from(entry)
        settings.check()
        loops, holes = [], ()
        if "edges" in objects:
            plate = convert.plate_from_object(scene.kezuri.stock.plate, depsgraph, scene, scene.kezuri.stock.origin)
            loops = convert.outlines_in_work(objects["edges"], depsgraph, plate.frame)
            core.tool_paths(loops, settings)
        if "holes" in objects:
            found = holes_of(objects["holes"], depsgraph, scene, 0.01, entry.where)
            holes = tuple((float(x), float(y), float(d)) for (x, y), d in zip(found.holes, found.diameters))
        elif "holes" in entry.table:
            if not isinstance(entry.table["holes"], list):
                raise JobFileError(f"{entry.where}: holes must be a list of [x, y, diameter] in work mm")
            holes = tuple(map(tuple, hole_circles.check_holes(entry.table["holes"]).tolist()))
        for x, y, diameter in holes:
            hole_circles.circle_radius(diameter, settings, f"the hole at X{x:g} Y{y:g}")
    except core.ChamferError as error:
        raise JobFileError(f"{entry.where}: the edges or the V-bit: {error}") from None
    geometry = ChamferGeometry(tuple(loops), 0.0, holes)
    return JobOperation("chamfer", entry.name, settings, geometry, entry.enabled), None, None


def settings_group() -> type:
    """The chamfer's settings as panel properties (names, units and defaults of ChamferSettings)."""
    from . import kindsettings as ks

    d = core.ChamferSettings()
    return ks.settings_group("KezuriChamferSettings", {
        **ks.tool_fields(d.tool, "V-bit"),
        "width": ks.length("Width", d.width, "Across the top, from the edge into the material; 0: from the depth"),
        "depth": ks.length("Depth", d.depth, "Down the wall; 0: from the width"),
        "tip_gap": ks.length("Tip Gap", d.tip_gap, "The tip below the chamfer, in the waste"),
        "rpm": ks.number("Spindle", d.rpm, "Spindle speed", "rpm", 0),
        "feed": ks.number("Feed", d.feed, "Cutting feed", "mm/min", 0),
        "plunge_feed": ks.number("Plunge Feed", d.plunge_feed, "Feed down the ramps", "mm/min", 0),
    })


PANELS = (("Chamfer", ("width", "depth", "tip_gap")),
          ("Tool & Feeds", ("tool_number", "diameter", "flute_length", "rpm", "feed", "plunge_feed")))

WORKFLOW = Workflow("CHAMFER", "Chamfer", "V-bit chamfer along the top edges of closed outlines and round holes",
                    post_families=POST_FAMILIES, kind="chamfer", job_operation=job_operation,
                    settings_group=settings_group(), settings_panels=PANELS)
