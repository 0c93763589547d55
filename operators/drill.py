"""Drilling in the shell: an operation of job files.  The holes are ``holes = [[x, y], ...]`` in
work mm, or found in a scene object: ``objects = { holes = "Mounting" }`` names a curve (its closed
curves that are circles: centre and diameter) or a mesh (its vertical cylindrical holes: centre,
diameter, depth, through or blind), in the plate's work frame (the stock's plate, its top Z 0).
Settings by name (:data:`SETTINGS`); its panel comes with the router operations (issue 29)."""
from __future__ import annotations

import math

import numpy as np

from ..toolpath.engines import meshdata
from ..toolpath.ir.program import ProgramError, Tool
from ..toolpath.job import JobOperation
from ..toolpath.operations.drill import drill as core
from ..toolpath.operations.drill import holes as found_holes
from ..toolpath.operations.drill.kind import DrillGeometry
from .workflow import Workflow

POST_FAMILIES = ("milling",)
NUMBERS = {"tool_number": "the drill's tool number", "diameter": "the drill's diameter (mm)",
           "flute_length": "the drill's flute length (mm)", "depth": "depth below the top (mm)",
           "peck": "deepest peck (mm), 0: none", "dwell": "seconds at the bottom (no pecks)",
           "rpm": "spindle speed", "feed": "feed down the hole (mm/min)",
           "breakthrough": "below a through hole (mm)", "min_diameter": "holes found: at least (mm)",
           "max_diameter": "holes found: at most (mm), 0: any", "tolerance": "circle fit (mm)",
           "mill_tool_number": "the end mill's tool number", "mill_diameter": "the end mill's diameter (mm)",
           "mill_flute_length": "the end mill's flute length (mm)", "mill_rpm": "end mill speed",
           "mill_feed": "end mill feed (mm/min)", "helix_pitch": "helix: down per turn (mm)",
           "spot_depth": "spot pass depth (mm)", "spot_tool_number": "the spot drill's tool number",
           "spot_diameter": "the spot drill's diameter (mm)"}
SWITCHES = {"helix": "mill holes wider than the drill", "spot": "a spot drill pass first"}
CHOICES = {"retract": core.RETRACTS, "order": ("shortest", "given")}
SETTINGS = {**NUMBERS, **SWITCHES, **{key: "/".join(values) for key, values in CHOICES.items()}}
WHOLE = ("tool_number", "mill_tool_number", "spot_tool_number")


def settings_from(entry) -> tuple:
    """(DrillSettings, circle tolerance) from the entry's settings, each checked by name."""
    from .jobentry import JobFileError

    given = dict(entry.settings)
    for key, value in given.items():
        if key not in SETTINGS:
            raise JobFileError(f"{entry.where}: settings.{key} is not a drilling setting; they are "
                               f"{', '.join(SETTINGS)}")
        if key in SWITCHES:
            if not isinstance(value, bool):
                raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not true or false")
        elif key in CHOICES:
            if value not in CHOICES[key]:
                raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not one of "
                                   f"{', '.join(CHOICES[key])}")
        elif isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not a number")
    for key in WHOLE:
        if key in given and not isinstance(given[key], int):
            raise JobFileError(f"{entry.where}: settings.{key} = {given[key]!r} is not a whole number")
    default = core.DrillSettings()
    try:
        diameter = float(given.get("diameter", default.tool.diameter))
        tool = Tool(given.get("tool_number", default.tool.number), "drill", diameter,
                    flute_length=float(given.get("flute_length", default.tool.flute_length)),
                    name=f"{diameter:g} mm drill")
        mill_diameter = float(given.get("mill_diameter", default.mill.diameter))
        mill = Tool(given.get("mill_tool_number", default.mill.number), "flat", mill_diameter,
                    flute_length=float(given.get("mill_flute_length", default.mill.flute_length)),
                    name=f"{mill_diameter:g} mm end mill")
        spot_diameter = float(given.get("spot_diameter", default.spot_tool.diameter))
        spot = Tool(given.get("spot_tool_number", default.spot_tool.number), "drill", spot_diameter,
                    flute_length=default.spot_tool.flute_length, name=f"{spot_diameter:g} mm spot drill",
                    label="spot drill")
    except ProgramError as error:
        raise JobFileError(f"{entry.where}: the drill: {error}") from None
    numbers = {key: float(given[key]) for key in ("depth", "peck", "dwell", "rpm", "feed", "breakthrough",
                                                   "min_diameter", "max_diameter", "mill_rpm", "mill_feed",
                                                   "helix_pitch", "spot_depth") if key in given}
    others = {key: given[key] for key in (*SWITCHES, *CHOICES) if key in given}
    return (core.DrillSettings(tool=tool, mill=mill, spot_tool=spot, **numbers, **others),
            float(given.get("tolerance", 0.01)))


def holes_of(obj, depsgraph, scene, tolerance: float, where: str) -> DrillGeometry:
    """The holes a curve or mesh object holds, in the stock plate's work frame."""
    from . import convert
    from .jobentry import JobFileError

    plate = convert.plate_from_object(scene.kezuri.stock.plate, depsgraph, scene, scene.kezuri.stock.origin)
    if obj.type in {"CURVE", "FONT"}:
        loops = convert.outlines_in_work(obj, depsgraph, plate.frame)
        found = found_holes.circles_in_curves(loops, tolerance)
        if not found:
            raise JobFileError(f"{where}: objects.holes = {obj.name!r} has no closed curve that is a circle "
                               f"(within {tolerance:g} mm)")
    elif obj.type == "MESH":
        vertices, polygons, _ = convert.evaluated_mesh_arrays(obj, depsgraph)
        triangles, _ = meshdata.triangulated(polygons)
        found = found_holes.cylinder_holes(plate.frame.to_work(vertices), triangles, tolerance)
        if not found:
            raise JobFileError(f"{where}: objects.holes = {obj.name!r} has no vertical cylindrical hole "
                               f"(within {tolerance:g} mm)")
    else:
        raise JobFileError(f"{where}: objects.holes = {obj.name!r} is a {obj.type.lower()}; use a curve or a mesh")
    bottom = -float(plate.size[2])
    return DrillGeometry(tuple((h.x, h.y) for h in found), 0.0, tuple(h.diameter for h in found),
                         tuple(h.bottom for h in found) if obj.type == "MESH" else None,
                         tuple(h.through for h in found) if obj.type == "MESH" else None, bottom)


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's drilling: ``holes = [[x, y], ...]`` in work mm (the plate's top at Z = 0), or
    ``objects = { holes = "<curve or mesh>" }``."""
    from .jobentry import JobFileError

    objects = {slot: obj for slot, obj in entry.objects.items() if obj is not None}     # a row's empty slot
    unknown = [slot for slot in objects if slot != "holes"]
    if unknown:
        raise JobFileError(f"{entry.where}: objects.{unknown[0]}: drilling takes objects.holes (a curve or a mesh)")
    if "holes" in objects and "holes" in entry.table:
        raise JobFileError(f"{entry.where}: give the holes as holes = [[x, y], ...] or as objects.holes, not both")
    if "holes" not in objects and "holes" not in entry.table:
        raise JobFileError(f"{entry.where}: no holes: give holes = [[x, y], ...] in work mm")
    try:
        settings, tolerance = settings_from(entry)
        settings.check()
        if "holes" in objects:
            geometry = holes_of(objects["holes"], depsgraph, scene, tolerance, entry.where)
        else:
            points = core.check_holes(entry.table["holes"])
            geometry = DrillGeometry(tuple(map(tuple, points.tolist())), 0.0)
    except core.DrillError as error:
        raise JobFileError(f"{entry.where}: the holes or the drill: {error}") from None
    return JobOperation("drill", entry.name, settings, geometry, entry.enabled), None, None


def settings_group() -> type:
    """The drilling's settings as panel properties (names, units and defaults of DrillSettings)."""
    from . import kindsettings as ks

    d = core.DrillSettings()
    return ks.settings_group("KezuriDrillSettings", {
        **ks.tool_fields(d.tool, "drill"),
        "depth": ks.length("Depth", d.depth, "Depth to the tip below the top (holes found in a mesh bring their own)"),
        "peck": ks.length("Peck", d.peck, "Deepest feed of one peck; 0: no pecking"),
        "dwell": ks.number("Dwell", d.dwell, "Time at the bottom of a hole drilled without pecks", "s", 2),
        "retract": ks.choice("Retract", d.retract, "Where the drill goes between holes", (
            ("initial", "Initial Level", "The clearance plane (G98)"), ("r", "R Plane", "The R plane (G99)"))),
        "order": ks.choice("Order", d.order, "The order the holes are drilled in", (
            ("shortest", "Shortest", "Nearest neighbour, then 2-opt"), ("given", "As Given", "As listed"))),
        "rpm": ks.number("Spindle", d.rpm, "Spindle speed", "rpm", 0),
        "feed": ks.number("Feed", d.feed, "Feed down the hole", "mm/min", 0),
        "breakthrough": ks.length("Breakthrough", d.breakthrough, "Below a through hole, beyond the drill's point"),
        "min_diameter": ks.length("Min Diameter", d.min_diameter, "Holes found in the model: only those this wide"),
        "max_diameter": ks.length("Max Diameter", d.max_diameter, "Holes found in the model: at most this wide; "
                                                                  "0: any"),
        "tolerance": ks.length("Tolerance", 0.01, "How far a found circle's points may lie off the circle"),
        "helix": ks.switch("Helix Milling", d.helix, "Mill holes wider than the drill along a helix"),
        "mill_tool_number": ks.whole("Mill Tool", d.mill.number, "The end mill's tool number (T word)"),
        "mill_diameter": ks.length("Mill Diameter", d.mill.diameter, "The end mill's diameter"),
        "mill_flute_length": ks.length("Mill Flutes", d.mill.flute_length, "The end mill's flute length"),
        "mill_rpm": ks.number("Mill Spindle", d.mill_rpm, "The end mill's spindle speed", "rpm", 0),
        "mill_feed": ks.number("Mill Feed", d.mill_feed, "The end mill's feed", "mm/min", 0),
        "helix_pitch": ks.length("Helix Pitch", d.helix_pitch, "Down per turn of the helix"),
        "spot": ks.switch("Spot Drill", d.spot, "A spot drill pass at every hole first"),
        "spot_depth": ks.length("Spot Depth", d.spot_depth, "To the spot drill's tip"),
        "spot_tool_number": ks.whole("Spot Tool", d.spot_tool.number, "The spot drill's tool number (T word)"),
        "spot_diameter": ks.length("Spot Diameter", d.spot_tool.diameter, "The spot drill's diameter"),
    })


PANELS = (("Holes", ("depth", "peck", "dwell", "retract", "order", "breakthrough", "min_diameter", "max_diameter",
                     "tolerance")),
          ("Drill & Feeds", ("tool_number", "diameter", "flute_length", "rpm", "feed")),
          ("Helix & Spot", ("helix", "mill_tool_number", "mill_diameter", "mill_flute_length", "mill_rpm", "mill_feed",
                            "helix_pitch", "spot", "spot_depth", "spot_tool_number", "spot_diameter")))

WORKFLOW = Workflow("DRILL", "Drilling", "Holes at given centres or found in curves and meshes",
                    post_families=POST_FAMILIES, kind="drill", job_operation=job_operation,
                    settings_group=settings_group(), settings_panels=PANELS)
