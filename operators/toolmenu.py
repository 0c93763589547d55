"""The Engrave panel's Tool Library menu (CAM > Engrave > Gouge Texture): the tool library's ball
end mills for the roughing ball and flat end mills for the band's finishing, from the same library
the CAM tab's Tool Library panel shows (its rows, edits not yet saved included, else the file)."""
from __future__ import annotations

import bpy
from bpy.props import EnumProperty, IntProperty

from ..toolpath.ir.errors import InputError
from .jobtools import SLOTS
from .translations import iface, translate_message

# the kind each of the engraving's slots takes (a job file's tools table reads the same)
SLOT_KINDS = {slot: kinds[0] for slot, (_, _, _, kinds, _) in SLOTS["engrave"].items()}


class KEZURI_OT_use_library_tool(bpy.types.Operator):
    """Use a tool from the library for the engraving's roughing ball or finishing flat"""

    bl_idname = "kezuri.use_library_tool"
    bl_label = "Use Library Tool"
    bl_options = {"REGISTER", "UNDO"}

    slot: EnumProperty(name="For", items=[("rough", "Roughing Ball", ""), ("finish", "Finishing Flat", "")])
    number: IntProperty(name="Tool Number", default=1, description="The library tool's number (T word)")

    def execute(self, context):
        from . import jobtools
        from .toollib import shown_library

        try:
            values = jobtools.tool_settings({"tools": {self.slot: self.number}}, "engrave", {}, "Tool Library",
                                            lambda: shown_library(context))
        except (InputError, OSError) as error:
            self.report({"ERROR"}, translate_message(str(error)))
            return {"CANCELLED"}
        engrave = context.scene.kezuri.engrave
        for key, value in values.items():
            setattr(engrave, key, value)
        return {"FINISHED"}


def offered(library) -> list:
    """(slot, tool) for each library tool the engraving can use, in number order."""
    slots = {kind: slot for slot, kind in SLOT_KINDS.items()}
    return [(slots[tool.kind], tool) for tool in library if tool.kind in slots]


class KEZURI_MT_library_tools(bpy.types.Menu):
    bl_idname = "KEZURI_MT_library_tools"
    bl_label = "Tool Library"

    def draw(self, context):
        from .toollib import shown_library

        layout = self.layout
        try:
            tools = offered(shown_library(context))
        except (InputError, OSError) as error:
            layout.label(text=translate_message(str(error)), icon="ERROR", translate=False)
            return
        if not tools:
            layout.label(text="The tool library has no ball or flat end mill (CAM > Tool Library)")
            return
        for slot, tool in tools:
            text = f"{iface('Roughing' if slot == 'rough' else 'Finishing')}: {tool.describe()}"
            button = layout.operator("kezuri.use_library_tool", text=text, translate=False)
            button.slot, button.number = slot, tool.number


CLASSES = (KEZURI_OT_use_library_tool, KEZURI_MT_library_tools)
