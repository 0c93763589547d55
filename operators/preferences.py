"""Extension preferences: default post and output folder, and where the shop's tool library is.

Saved with Blender's user preferences, so they follow the user from file to file.  The tool
library itself is one file (:mod:`.toolstore`), edited in the CAM tab's Tool Library panel; the
old list these preferences once held (:mod:`.oldtools`) is moved into it on start-up.
"""
from __future__ import annotations

import bpy
from bpy.props import CollectionProperty, EnumProperty, IntProperty, StringProperty

from ..toolpath.ir.errors import InputError
from . import oldtools, toolstore
from .properties import WORK_OFFSET_ITEMS, post_items, post_number
from .translations import translate_message

ADDON_ID = __package__.rpartition(".")[0]   # "kezuri", or "bl_ext.<repo>.kezuri" once installed

class KezuriPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON_ID

    default_post: EnumProperty(name="Default Post", items=post_items("milling"), default=post_number("fanuc"),
                               description="Controller a new job is exported for")
    default_work_offset: EnumProperty(name="Default Work Offset", items=WORK_OFFSET_ITEMS, default="G54")
    output_dir: StringProperty(name="Output Folder", subtype="DIR_PATH", default="//nc/",
                               description="Where NC programs go unless the scene says otherwise "
                                           "(// = beside the .blend file)")
    # the old tool list, never drawn: kept registered so old preference files load (see oldtools)
    tools: CollectionProperty(type=oldtools.KezuriLibraryTool)
    active_tool: IntProperty(default=0)

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(self, "default_post")
        layout.prop(self, "default_work_offset")
        layout.prop(self, "output_dir")
        box = layout.box()
        box.label(text="Tool Library", icon="TOOL_SETTINGS")
        box.label(text=toolstore.library_path(), translate=False)
        box.label(text="Edit it in the 3D Viewport's sidebar: CAM > Tool Library")


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


class KEZURI_OT_move_old_tools(bpy.types.Operator):
    """Move the tools of the preferences' old tool list into the tool library file"""

    bl_idname = "kezuri.move_old_tools"
    bl_label = "Move Old Preference Tools"
    bl_options = {"REGISTER", "INTERNAL"}

    def execute(self, context):
        prefs = preferences(context)
        if prefs is None:
            self.report({"ERROR"}, translate_message("Kezuri preferences are not available"))
            return {"CANCELLED"}
        try:
            infos, warnings = oldtools.move_old_tools(prefs.tools, toolstore.library_path())
        except (InputError, OSError) as error:
            self.report({"WARNING"}, translate_message(str(error)))
            return {"CANCELLED"}
        for message in warnings:
            self.report({"WARNING"}, translate_message(message))
        for message in infos:
            self.report({"INFO"}, translate_message(message))
        if infos:
            prefs.active_tool = 0
            context.preferences.is_dirty = True          # saved with the preferences: the list stays empty
        return {"FINISHED"}


def move_at_startup() -> None:
    """Run :class:`KEZURI_OT_move_old_tools` when the preferences still hold old tools (its
    reports go to the status bar and the Info editor)."""
    prefs = preferences()
    if prefs is not None and len(prefs.tools):
        try:
            bpy.ops.kezuri.move_old_tools()
        except RuntimeError as error:               # an ERROR report; said on the console
            print(f"Kezuri: {error}")


CLASSES = (oldtools.KezuriLibraryTool, KezuriPreferences, KEZURI_OT_move_old_tools)
