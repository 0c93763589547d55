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

    unknown = [slot for slot in entry.objects if slot != "holes"]
    if unknown:
        raise JobFileError(f"{entry.where}: objects.{unknown[0]}: drilling takes objects.holes (a curve or a mesh)")
    if "holes" in entry.objects and "holes" in entry.table:
        raise JobFileError(f"{entry.where}: give the holes as holes = [[x, y], ...] or as objects.holes, not both")
    if "holes" not in entry.objects and "holes" not in entry.table:
        raise JobFileError(f"{entry.where}: no holes: give holes = [[x, y], ...] in work mm")
    try:
        settings, tolerance = settings_from(entry)
        settings.check()
        if "holes" in entry.objects:
            geometry = holes_of(entry.objects["holes"], depsgraph, scene, tolerance, entry.where)
        else:
            points = core.check_holes(entry.table["holes"])
            geometry = DrillGeometry(tuple(map(tuple, points.tolist())), 0.0)
    except core.DrillError as error:
        raise JobFileError(f"{entry.where}: the holes or the drill: {error}") from None
    return JobOperation("drill", entry.name, settings, geometry, entry.enabled), None, None


WORKFLOW = Workflow("DRILL", "Drilling", "Holes at given centres or found in curves and meshes (job files)",
                    post_families=POST_FAMILIES, kind="drill", job_operation=job_operation)
