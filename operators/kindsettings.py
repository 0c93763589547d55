"""Panel properties for an operation kind's job-file settings (profile, pocket, drill, chamfer).

A kind whose settings a job file gives by name (``settings = { diameter = 6.0 }``) gets one
PropertyGroup, ``scene.kezuri.<kind>``, with a property per setting: the same name, unit and
default as the kind's settings in its core package (the defaults are read from the core's
settings class, never typed twice).  The job list shows the selected row's settings in it and
reads them back as the job file's table (:mod:`.jobrows`), so the panel, the job file and batch
plan the same operation.  No hard limits: the kind's own checks refuse a bad value by name
(``checked_by_kind``), as they do a job file's.
"""
from __future__ import annotations

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty


def length(name: str, default: float, description: str):
    """A length in mm (a plain number: the NC is in mm whatever the scene's units)."""
    return FloatProperty(name=name, default=float(default), description=description + " (mm)", precision=3, step=10)


def number(name: str, default: float, description: str, unit: str, precision: int = 1):
    """A speed, feed, angle or time: its unit in the tooltip."""
    return FloatProperty(name=name, default=float(default), description=f"{description} ({unit})",
                         precision=precision, step=100)


def whole(name: str, default: int, description: str):
    return IntProperty(name=name, default=int(default), description=description)


def tool_fields(tool, what: str) -> dict:
    """A tool's number, diameter and flute length as properties (``what``: "end mill", "drill",
    "V-bit": the tooltips say whose); the keys are the job files' and the tool library's slots'."""
    return {"tool_number": whole("Tool Number", tool.number, f"The {what}'s tool number (T word)"),
            "diameter": length("Diameter", tool.diameter, f"The {what}'s diameter"),
            "flute_length": length("Flute Length", tool.flute_length, f"The {what}'s flute length")}


def switch(name: str, default: bool, description: str):
    return BoolProperty(name=name, default=bool(default), description=description)


def choice(name: str, default: str, description: str, items: tuple):
    """``items``: (word, label, tooltip) per word the job file takes (the enum's identifiers)."""
    return EnumProperty(name=name, default=default, description=description, items=list(items))


def settings_group(class_name: str, props: dict) -> type:
    """The PropertyGroup class of a kind's settings (``props``: name -> property definition)."""
    return type(class_name, (bpy.types.PropertyGroup,), {"__annotations__": dict(props), "checked_by_kind": True,
                                                          "__doc__": "An operation kind's settings (job list)"})
