"""Extension preferences: default post and output folder, and the shop's tool library.

Saved with Blender's user preferences, so they follow the user from file to file.
"""
from __future__ import annotations

import bpy
from bpy.props import CollectionProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from .limits import LIBRARY, SettingError, check_library_tool, soft_limits
from .properties import WORK_OFFSET_ITEMS, post_items, post_number
from .translations import translate_message

ADDON_ID = __package__.rpartition(".")[0]   # "kezuri", or "bl_ext.<repo>.kezuri" once installed

TOOL_KIND_ITEMS = [
    ("ball", "Ball End Mill", "Ball-nose end mill"),
    ("flat", "Flat End Mill", "Square end mill"),
    ("bull", "Bull Nose", "End mill with a corner radius"),
    ("drill", "Drill", "Twist drill"),
    ("vbit", "V-Bit", "Engraving V-bit"),
]


class KezuriLibraryTool(bpy.types.PropertyGroup):
    name: StringProperty(name="Name", default="Tool")
    # soft limits only (limits.LIBRARY): a hard one would clamp a bad value without a word
    number: IntProperty(name="Number", default=1, description="Tool (pocket) number, T word",
                        **soft_limits(LIBRARY["number"]))
    kind: EnumProperty(name="Type", items=TOOL_KIND_ITEMS, default="flat")
    diameter: FloatProperty(name="Diameter", default=6.0, description="Cutting diameter (mm)",
                            **soft_limits(LIBRARY["diameter"]))
    corner_radius: FloatProperty(name="Corner Radius", default=0.0, description="Bull nose radius (mm)",
                                 **soft_limits(LIBRARY["corner_radius"]))
    flute_length: FloatProperty(name="Flute Length", default=20.0, description="Cutting length (mm)",
                                **soft_limits(LIBRARY["flute_length"]))


class KEZURI_UL_tools(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_property, index=0, flt_flag=0):
        row = layout.row(align=True)
        row.label(text=f"T{item.number}")
        row.prop(item, "name", text="", emboss=False)
        row.label(text=f"{item.diameter:g} mm {item.kind}")


class KezuriPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON_ID

    default_post: EnumProperty(name="Default Post", items=post_items("milling"), default=post_number("fanuc"),
                               description="Controller a new job is exported for")
    default_work_offset: EnumProperty(name="Default Work Offset", items=WORK_OFFSET_ITEMS, default="G54")
    output_dir: StringProperty(name="Output Folder", subtype="DIR_PATH", default="//nc/",
                               description="Where NC programs go unless the scene says otherwise "
                                           "(// = beside the .blend file)")
    tools: CollectionProperty(type=KezuriLibraryTool)
    active_tool: IntProperty(default=0)

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(self, "default_post")
        layout.prop(self, "default_work_offset")
        layout.prop(self, "output_dir")
        layout.label(text="Tool Library")
        row = layout.row()
        row.template_list("KEZURI_UL_tools", "", self, "tools", self, "active_tool", rows=4)
        column = row.column(align=True)
        column.operator("kezuri.tool_add", icon="ADD", text="")
        column.operator("kezuri.tool_remove", icon="REMOVE", text="")
        if 0 <= self.active_tool < len(self.tools):
            tool = self.tools[self.active_tool]
            for name in ("name", "number", "kind", "diameter", "corner_radius", "flute_length"):
                layout.prop(tool, name)


def preferences(context=None):
    """The extension's preferences, or None when it is not registered as an add-on (pytest)."""
    context = context or bpy.context
    addon = context.preferences.addons.get(ADDON_ID)
    return addon.preferences if addon is not None else None


def scene_post(scene, context=None) -> str:
    """The scene's post, with "Preferences Default" resolved."""
    post = scene.kezuri.machine.post
    if post != "DEFAULT":
        return post
    prefs = preferences(context)
    return prefs.default_post if prefs is not None else "fanuc"


def scene_output_dir(scene, context=None) -> str:
    folder = scene.kezuri.machine.output_dir
    if not folder:
        prefs = preferences(context)
        folder = prefs.output_dir if prefs is not None else "//nc/"
    return bpy.path.abspath(folder)


class KEZURI_OT_tool_add(bpy.types.Operator):
    """Add a tool to the library"""

    bl_idname = "kezuri.tool_add"
    bl_label = "Add Tool"
    bl_options = {"REGISTER"}

    def execute(self, context):
        prefs = preferences(context)
        if prefs is None:
            self.report({"ERROR"}, translate_message("Kezuri preferences are not available"))
            return {"CANCELLED"}
        tool = prefs.tools.add()
        tool.number = max((t.number for t in prefs.tools), default=0) + 1
        tool.name = f"Tool {tool.number}"
        prefs.active_tool = len(prefs.tools) - 1
        context.preferences.is_dirty = True
        return {"FINISHED"}


class KEZURI_OT_tool_remove(bpy.types.Operator):
    """Remove the selected tool from the library"""

    bl_idname = "kezuri.tool_remove"
    bl_label = "Remove Tool"
    bl_options = {"REGISTER"}

    @classmethod
    def poll(cls, context):
        prefs = preferences(context)
        if prefs is None or not (0 <= prefs.active_tool < len(prefs.tools)):
            cls.poll_message_set("Select a tool in the library first")
            return False
        return True

    def execute(self, context):
        prefs = preferences(context)
        prefs.tools.remove(prefs.active_tool)
        prefs.active_tool = min(prefs.active_tool, len(prefs.tools) - 1)
        context.preferences.is_dirty = True
        return {"FINISHED"}


class KEZURI_OT_use_library_tool(bpy.types.Operator):
    """Use a tool from the library for the engraving's roughing ball or finishing flat"""

    bl_idname = "kezuri.use_library_tool"
    bl_label = "Use Library Tool"
    bl_options = {"REGISTER", "UNDO"}

    slot: EnumProperty(name="For", items=[("rough", "Roughing Ball", ""), ("finish", "Finishing Flat", "")])
    index: IntProperty(name="Library Index", default=0)

    def execute(self, context):
        prefs = preferences(context)
        if prefs is None or not 0 <= self.index < len(prefs.tools):
            self.report({"ERROR"}, translate_message("No such tool in the library"))
            return {"CANCELLED"}
        tool = prefs.tools[self.index]
        try:
            check_library_tool(tool)
        except SettingError as error:
            self.report({"ERROR"}, translate_message(str(error)))
            return {"CANCELLED"}
        wanted = "ball" if self.slot == "rough" else "flat"
        if tool.kind != wanted:
            self.report({"ERROR"},
                        translate_message(f"{tool.name} is a {tool.kind}; the {self.slot}ing tool must be a {wanted}"))
            return {"CANCELLED"}
        engrave = context.scene.kezuri.engrave
        setattr(engrave, f"{self.slot}_diameter", tool.diameter)
        setattr(engrave, f"{self.slot}_tool_number", tool.number)
        return {"FINISHED"}


class KEZURI_MT_library_tools(bpy.types.Menu):
    bl_idname = "KEZURI_MT_library_tools"
    bl_label = "Tool Library"

    def draw(self, context):
        prefs = preferences(context)
        if prefs is None or not len(prefs.tools):
            self.layout.label(text="The tool library is empty (Preferences > Add-ons > Kezuri CAM)")
            return
        for index, tool in enumerate(prefs.tools):
            slot = "rough" if tool.kind == "ball" else "finish"
            op = self.layout.operator("kezuri.use_library_tool", text=f"T{tool.number} {tool.name} "
                                                                      f"({tool.diameter:g} mm {tool.kind})")
            op.slot, op.index = slot, index


CLASSES = (KezuriLibraryTool, KEZURI_UL_tools, KezuriPreferences, KEZURI_OT_tool_add, KEZURI_OT_tool_remove,
           KEZURI_OT_use_library_tool, KEZURI_MT_library_tools)
