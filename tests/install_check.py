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
BUNDLED = ("manifold3d", "trimesh", "embreex", "numba", "llvmlite")


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
import numba  # noqa: E402
import trimesh  # noqa: E402

result["manifold3d"] = manifold3d.__file__
result["trimesh"] = trimesh.__file__
result["numba"] = numba.__file__
package = "bl_ext.user_default.kezuri"
result["registered"] = hasattr(bpy.types.Scene, "kezuri")
samples = importlib.import_module(package + ".operators.samples")
scene = bpy.context.scene
samples.clear_scene(scene)
samples.set_millimetres(scene)
samples.name_plate(scene)
result["engrave_generate"] = sorted(bpy.ops.kezuri.engrave_generate())
result["kezuri_objects"] = len(bpy.data.collections["Kezuri"].objects)
result["simulate"] = sorted(bpy.ops.kezuri.simulate(workflow="ENGRAVE"))
# Every other workflow's main operator on its sample.
samples.clear_scene(scene)
samples.rotary_block(scene)
result["rotary_generate"] = sorted(bpy.ops.kezuri.rotary_generate())
samples.clear_scene(scene)
fixture = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fixtures", "iso14649", "ex1.stp")
result["import_stepnc"] = sorted(bpy.ops.kezuri.import_stepnc(filepath=fixture))
result["stepnc_generate"] = sorted(bpy.ops.kezuri.stepnc_generate())
samples.clear_scene(scene)
samples.turnmill_part(scene)
result["turnmill_generate"] = sorted(bpy.ops.kezuri.turnmill_generate())
samples.clear_scene(scene)
result["unfold_quad"] = sorted(bpy.ops.kezuri.unfold_quad())
result["add_elbow"] = sorted(bpy.ops.kezuri.add_elbow())
# The exact simulation as the UI runs it: in a child process, from the installed copy.
common = importlib.import_module(package + ".operators.common")
program = importlib.import_module(package + ".toolpath.ir.program")
slot = program.Operation("slot", program.Tool(1, "flat", 2.0), 10000, [program.FEED, program.FEED],
                         [[2.0, 5.0, -1.0], [8.0, 5.0, -1.0]], [300.0, 300.0], start=[2.0, 5.0, 5.0])
job = common.ProcessJob(common.CoreCall("toolpath.simulate", "simulate", {
    "program_or_operations": [slot], "stock": (0, 0, -5, 10, 10, 0), "engine": "manifold", "cell": 0.5}))
while not job.step():
    pass
result["process_job_volume"] = job.result().solid.volume()
# Preferences: an old preference file's tool list moves into the one tool library (tools.toml in the
# user config folder under BLENDER_USER_RESOURCES); the Engrave menu's operator takes tools from there.
prefs = bpy.context.preferences.addons[package].preferences
old = prefs.tools.add()
old.name, old.kind, old.diameter, old.number = "8 mm ball", "ball", 8.0, 17
result["move_old_tools"] = sorted(bpy.ops.kezuri.move_old_tools())
result["old_tools_after"] = len(prefs.tools)
toolstore = importlib.import_module(package + ".operators.toolstore")
result["library_path"] = toolstore.library_path()
moved = toolstore.load().get(17)
result["moved_tool"] = [moved.kind, moved.diameter, moved.name]
bpy.ops.kezuri.use_library_tool(slot="rough", number=17)
result["rough_from_library"] = [scene.kezuri.engrave.rough_diameter, scene.kezuri.engrave.rough_tool_number]
# A library tool the roughing cannot use is refused, naming it, and nothing is taken.
try:
    bpy.ops.kezuri.use_library_tool(slot="rough", number=7)          # the presets' 90 degree V-bit
    result["bad_library_tool"] = "FINISHED"
except RuntimeError as error:               # bpy.ops raises on an ERROR report
    result["bad_library_tool"] = str(error)
result["rough_after_bad"] = [scene.kezuri.engrave.rough_diameter, scene.kezuri.engrave.rough_tool_number]
prefs.default_post = "grbl"
preferences_module = importlib.import_module(package + ".operators.preferences")
result["scene_post"] = preferences_module.scene_post(scene)
bpy.ops.preferences.addon_disable(module=package)
result["registered_after_disable"] = hasattr(bpy.types.Scene, "kezuri")
print("RESULT " + json.dumps(result))
