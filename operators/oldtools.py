"""The add-on preferences' old tool list, moved into the tool library file once.

Before there was one tool library (``tools.toml``, :mod:`.toolstore`), the preferences held a list
of their own (``KezuriPreferences.tools``, saved in userpref.blend).  The property stays registered,
never drawn, only so a preference file that holds such a list still loads (Blender keeps a stored
property it does not know, but Python cannot read it back from add-on preferences).  On start-up
:func:`move_old_tools` puts each tool of it into the library, unless the library holds that number
as another tool: then nothing is overwritten, the tool is named in a message and written to
``tools-not-moved.toml`` beside the library (to import with "Replace Same Numbers" or renumber);
a tool that is no tool (a 0 mm diameter, a bull nose without its corner radius) is named with its
fields.  Then the list is emptied, so a second run finds nothing and changes nothing.
"""
from __future__ import annotations

import os

import bpy
from bpy.props import EnumProperty, FloatProperty, IntProperty, StringProperty

from ..toolpath.ir.tools import TIP_ANGLE_DEG
from ..toolpath.tooling import store
from ..toolpath.tooling.library import LibraryTool, ToolLibrary, ToolLibraryError
from .limits import LIBRARY, soft_limits

NOT_MOVED = "tools-not-moved.toml"
TOOL_KIND_ITEMS = [            # the old list's kinds, in its order (a stored enum is its index)
    ("ball", "Ball End Mill", "Ball-nose end mill"),
    ("flat", "Flat End Mill", "Square end mill"),
    ("bull", "Bull Nose", "End mill with a corner radius"),
    ("drill", "Drill", "Twist drill"),
    ("vbit", "V-Bit", "Engraving V-bit"),
]


class KezuriLibraryTool(bpy.types.PropertyGroup):
    # the old list's tool, as it was (its stored fields must keep their names and kinds)
    name: StringProperty(name="Name", default="Tool")
    number: IntProperty(name="Number", default=1, description="Tool (pocket) number, T word",
                        **soft_limits(LIBRARY["number"]))
    kind: EnumProperty(name="Type", items=TOOL_KIND_ITEMS, default="flat")
    diameter: FloatProperty(name="Diameter", default=6.0, description="Cutting diameter (mm)",
                            **soft_limits(LIBRARY["diameter"]))
    corner_radius: FloatProperty(name="Corner Radius", default=0.0, description="Bull nose radius (mm)",
                                 **soft_limits(LIBRARY["corner_radius"]))
    flute_length: FloatProperty(name="Flute Length", default=20.0, description="Cutting length (mm)",
                                **soft_limits(LIBRARY["flute_length"]))


def typed(value: float) -> float:
    """A float32 property's value as the decimals typed (6 digits: 6.35, not 6.349999904632568)."""
    import numpy as np

    return float(f"{float(np.float32(value)):.6g}")


def old_fields(item) -> str:
    return (f"'{item.name}' (T{item.number}, {item.kind}, diameter {typed(item.diameter):g} mm, corner radius "
            f"{typed(item.corner_radius):g} mm, flute length {typed(item.flute_length):g} mm)")


def library_tool(item) -> tuple:
    """(the old list's tool as a library tool, a note or "").  A V-bit had no angle there: it
    comes in at the 90° the engraving V-bit is planned for, and the note says so."""
    kind, note, angle = item.kind, "", None
    if kind == "vbit":
        angle = TIP_ANGLE_DEG["vbit"]
        note = (f"T{item.number} '{item.name}': the preferences' list held no V-bit angle; it came in as "
                f"{angle:g}°, check it in CAM > Tool Library")
    tool = LibraryTool(item.number, kind, typed(item.diameter), corner_radius=typed(item.corner_radius),
                       angle=angle, flute_length=typed(item.flute_length), name=item.name)
    return tool, note


def move_old_tools(old, path: str) -> tuple:
    """Move the tools of the collection ``old`` (the preferences' ``tools``) into the library file
    ``path``; empty ``old``.  Returns (info messages, warning messages); nothing when ``old`` is
    empty.  With no file yet, the presets are the start, less those under the old tools' numbers."""
    if not len(old):
        return [], []
    infos, warnings, converted = [], [], []
    for item in old:
        try:
            converted.append(library_tool(item))
        except ToolLibraryError as error:
            warnings.append(f"The preferences' tool {old_fields(item)} is no tool and was not moved: {error}; "
                            "type it in CAM > Tool Library")
    if os.path.exists(path):
        library = store.load(path)          # an unreadable file is an error: nothing is moved or emptied
    else:
        taken = {tool.number for tool, _ in converted}
        library = ToolLibrary([t for t in store.SEEDS if t.number not in taken])
    before, moved, same, kept = library, [], 0, []
    for tool, note in converted:
        there = library.find(tool.number)
        if there == tool:
            same += 1
            continue
        if there is not None:
            warnings.append(f"The preferences' tool {tool.describe()} was not moved: the tool library has "
                            f"T{tool.number} as {there.describe()}, which was kept")
            if all(k.number != tool.number for k in kept):     # two old tools under one number: the first
                kept.append(tool)
            continue
        library = library.with_tool(tool)
        moved.append(tool.number)
        if note:
            warnings.append(note)
    if library != before or not os.path.exists(path):
        store.save(path, library)
    if kept:
        aside = os.path.join(os.path.dirname(os.path.abspath(path)), NOT_MOVED)
        if os.path.exists(aside):
            kept = list(store.load(aside).merged(ToolLibrary(kept), replace=True)[0])
        store.save(aside, ToolLibrary(kept))
        warnings.append(f"The tools not moved are in {aside} (import it with Replace Same Numbers, or renumber)")
    shown = ", ".join(f"T{n}" for n in moved) or "none"
    infos.append(f"Moved {len(moved)} tools ({shown}) from the add-on preferences into the tool library {path}; "
                 f"{same} were there already")
    old.clear()
    return infos, warnings
