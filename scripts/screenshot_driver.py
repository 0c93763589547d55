"""Runs inside a real Blender window (scripts/screenshots.sh starts it under Xvfb) and takes a
screenshot of every Kezuri workflow in use: the CAM sidebar tab open, the workflow's operators
run on its built-in sample, the result in the viewport.

Blender's own screenshot operator gives a black image under Xvfb with software GL, so each
picture is taken of the X screen with ``xwd -root | convert``.
"""
import importlib
import os
import subprocess
import sys

import bpy

OUT = os.environ.get("KEZURI_SCREENSHOTS", "/tmp/screenshots")
PACKAGE = next((name for name in sys.modules if name.endswith(".kezuri") and name.startswith("bl_ext.")), None)


def module(name):
    return importlib.import_module(f"{PACKAGE}.{name}")


def view3d():
    window = bpy.context.window_manager.windows[0]
    screen = window.screen
    area = max((a for a in screen.areas if a.type == "VIEW_3D"), key=lambda a: a.width * a.height)
    region = next(r for r in area.regions if r.type == "WINDOW")
    sidebar = next(r for r in area.regions if r.type == "UI")
    return window, area, region, sidebar


def maximise_viewport():
    window, area, region, _ = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.screen.screen_full_area()


def show_cam_tab(panels_open=()):
    window, area, region, sidebar = view3d()
    space = area.spaces.active
    space.show_region_ui = True
    space.overlay.show_overlays = True
    space.shading.type = "SOLID"
    space.shading.color_type = "OBJECT"
    sidebar.active_panel_category = "CAM"
    area.tag_redraw()


def frame_all(view="TOP_TILTED"):
    window, area, region, _ = view3d()
    space = area.spaces.active
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.view3d.view_all(center=False)
    r3d = space.region_3d
    if view == "TOP_TILTED":
        from mathutils import Euler
        r3d.view_rotation = Euler((0.6, 0.0, 0.0)).to_quaternion()
        with bpy.context.temp_override(window=window, area=area, region=region):
            bpy.ops.view3d.view_all(center=False)
    area.tag_redraw()


def shoot(name):
    os.makedirs(OUT, exist_ok=True)
    path = os.path.join(OUT, f"{name}.png")
    subprocess.run(f"xwd -root -silent | convert xwd:- png:{path}", shell=True, check=True)
    print(f"screenshot {path}", flush=True)


def engrave_step():
    scene = bpy.context.scene
    samples = module("operators.samples")
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    samples.name_plate(scene)
    window, area, region, _ = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.kezuri.engrave_generate()
    show_cam_tab()
    frame_all()


def sheet_step():
    scene = bpy.context.scene
    module("operators.samples").clear_scene(scene)
    window, area, region, _ = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.kezuri.unfold_quad()
    show_cam_tab()
    frame_all()


def elbow_step():
    scene = bpy.context.scene
    module("operators.samples").clear_scene(scene)
    window, area, region, _ = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.kezuri.add_elbow()
    show_cam_tab()
    frame_all()


STEPS = [("setup", maximise_viewport, None), ("engrave", engrave_step, "engrave"),
         ("sheet", sheet_step, "sheet-metal"), ("elbow", elbow_step, "elbow")]
state = {"index": 0, "pending": None}


def tick():
    """One step per call; the screenshot of a step is taken on the next call, after a redraw."""
    if state["pending"]:
        shoot(state["pending"])
        state["pending"] = None
    if state["index"] >= len(STEPS):
        bpy.ops.wm.quit_blender()
        return None
    name, action, picture = STEPS[state["index"]]
    state["index"] += 1
    try:
        action()
    except Exception as error:  # noqa: BLE001 - report and carry on with the other workflows
        print(f"step {name} failed: {error}", flush=True)
        return 1.0
    state["pending"] = picture
    return 3.0


if PACKAGE is None:
    print("Kezuri is not installed in this Blender", flush=True)
    bpy.ops.wm.quit_blender()
else:
    bpy.context.scene.unit_settings.scale_length = 0.001
    bpy.app.timers.register(tick, first_interval=3.0)
