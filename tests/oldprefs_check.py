"""Run in a fresh process with BLENDER_USER_RESOURCES set (Kezuri linked in its scripts/addons as
``kezuri``) and KEZURI_TOOL_LIBRARY naming the library file.  ``save``: enable the add-on, fill the
preferences' old tool list as an older Kezuri did and write userpref.blend.  ``load``: read
userpref.blend (which enables the add-on again), run the start-up move, save the preferences.
Prints one JSON line."""
import json
import sys

import bpy

import addon_utils  # noqa: E402  (on sys.path once bpy is imported)

result = {}
prefs_of = bpy.context.preferences.addons
if sys.argv[1] == "save":
    addon_utils.enable("kezuri", default_set=True)
    prefs = prefs_of["kezuri"].preferences
    for name, number, kind, diameter, corner in (("8 mm ball", 17, "ball", 8.0, 0.0), ("Bull", 20, "bull", 10.0, 1.5),
                                                 ("Shop flat", 1, "flat", 6.35, 0.0)):
        tool = prefs.tools.add()
        tool.name, tool.number, tool.kind, tool.diameter, tool.corner_radius = name, number, kind, diameter, corner
else:
    result["read"] = sorted(bpy.ops.wm.read_userpref())
    prefs = prefs_of["kezuri"].preferences
    result["old_tools"] = [[t.name, t.number, t.kind, round(t.diameter, 4), round(t.corner_radius, 4)]
                           for t in prefs.tools]
    sys.modules["kezuri.operators.preferences"].move_at_startup()
    result["old_tools_after"] = len(prefs.tools)
result["save"] = sorted(bpy.ops.wm.save_userpref())
print("RESULT " + json.dumps(result))
