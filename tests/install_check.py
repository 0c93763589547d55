"""Run in a fresh process with BLENDER_USER_RESOURCES set: install the built extension zip the
way a user does, prove manifold3d and trimesh come from the wheels bundled in it, run each
workflow's main operator from the installed copy, then disable it.  Prints one JSON line."""
import importlib
import importlib.abc
import importlib.machinery
import json
import os
import sys

USER = os.environ["BLENDER_USER_RESOURCES"]
BUNDLED = ("manifold3d", "trimesh", "embreex")


class OnlyBundled(importlib.abc.MetaPathFinder):
    """The test venv has manifold3d and trimesh too: hide them, so only the bundled ones load."""

    def find_spec(self, name, path, target=None):
        if name.split(".")[0] in BUNDLED and path is None:
            inside = [p for p in sys.path if p.startswith(USER)]
            spec = importlib.machinery.PathFinder.find_spec(name, inside)
            if spec is None:
                raise ImportError(f"{name} is not bundled with the installed extension")
            return spec
        return None


sys.meta_path.insert(0, OnlyBundled())
import bpy  # noqa: E402

result = {}
status = bpy.ops.extensions.package_install_files(filepath=sys.argv[1], repo="user_default",
                                                  enable_on_install=True)
result["install"] = sorted(status)
import manifold3d  # noqa: E402
import trimesh  # noqa: E402

result["manifold3d"] = manifold3d.__file__
result["trimesh"] = trimesh.__file__
package = "bl_ext.user_default.kezuri"
result["registered"] = hasattr(bpy.types.Scene, "kezuri")
samples = importlib.import_module(package + ".operators.samples")
scene = bpy.context.scene
samples.clear_scene(scene)
samples.set_millimetres(scene)
samples.name_plate(scene)
result["engrave_generate"] = sorted(bpy.ops.kezuri.engrave_generate())
result["kezuri_objects"] = len(bpy.data.collections["Kezuri"].objects)
# Preferences: the tool library and the default post.
prefs = bpy.context.preferences.addons[package].preferences
bpy.ops.kezuri.tool_add()
tool = prefs.tools[-1]
tool.kind, tool.diameter, tool.number = "ball", 8.0, 7
bpy.ops.kezuri.use_library_tool(slot="rough", index=len(prefs.tools) - 1)
result["rough_from_library"] = [scene.kezuri.engrave.rough_diameter, scene.kezuri.engrave.rough_tool_number]
prefs.default_post = "grbl"
preferences_module = importlib.import_module(package + ".operators.preferences")
result["scene_post"] = preferences_module.scene_post(scene)
bpy.ops.preferences.addon_disable(module=package)
result["registered_after_disable"] = hasattr(bpy.types.Scene, "kezuri")
print("RESULT " + json.dumps(result))
