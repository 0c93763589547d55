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
    area = view3d()[1]
    area.spaces.active.show_region_ui = True


def click_cam_tab():
    """Blender 4.3 cannot set the sidebar tab from Python: click it.  The tabs (Tool, View, CAM)
    run down the sidebar's right edge; CAM is the third, about 115 px below the sidebar's top."""
    window, area, region, sidebar = view3d()
    try:
        sidebar.active_panel_category = "CAM"
        return
    except AttributeError:
        pass
    x = sidebar.x + sidebar.width - 9
    y = window.height - (sidebar.y + sidebar.height) + 115
    subprocess.run(["xdotool", "mousemove", str(x), str(y), "click", "1", "mousemove", "800", "500"], check=True)


def only_panels(*prefixes):
    """Show only the Machine panel and the panels of one workflow (so the picture shows them
    without scrolling): the others are unregistered for this picture and registered again after."""
    panels = module("operators.panels")
    for cls in reversed(panels.CLASSES):
        if cls.is_registered:
            bpy.utils.unregister_class(cls)
    for cls in panels.CLASSES:
        if cls.__name__ == "KEZURI_PT_machine" or cls.__name__.startswith(prefixes):
            bpy.utils.register_class(cls)


def show_cam_tab(color_type="OBJECT"):
    """Sidebar open on CAM; Solid shading by object colour, or by the colour attribute ("VERTEX":
    the simulated stock by depth, the turn-mill reach)."""
    window, area, region, sidebar = view3d()
    space = area.spaces.active
    space.show_region_ui = True
    space.overlay.show_overlays = True
    space.shading.type = "SOLID"
    space.shading.color_type = color_type
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
    scene.kezuri.engrave.show_rapids = False     # a cleaner picture: the cuts only
    window, area, region, _ = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.kezuri.engrave_generate()
    only_panels("KEZURI_PT_engrave")
    show_cam_tab()
    frame_all()


def sheet_step():
    scene = bpy.context.scene
    module("operators.samples").clear_scene(scene)
    window, area, region, _ = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.kezuri.unfold_quad()
    only_panels("KEZURI_PT_sheet")
    show_cam_tab()
    frame_all()


def elbow_step():
    scene = bpy.context.scene
    module("operators.samples").clear_scene(scene)
    window, area, region, _ = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.kezuri.add_elbow()
    only_panels("KEZURI_PT_sheet")
    show_cam_tab()
    frame_all()


def run_in_view(operator, *args, **kwargs):
    window, area, region, _ = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        operator(*args, **kwargs)


def simulate_step():
    scene = bpy.context.scene
    samples = module("operators.samples")
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    samples.name_plate(scene)
    run_in_view(bpy.ops.kezuri.simulate, workflow="ENGRAVE")
    scene.kezuri.stock.plate.hide_set(True)
    scene.objects["Letters"].hide_set(True)
    only_panels("KEZURI_PT_simulate")
    show_cam_tab("VERTEX")
    frame_all()


def rotary_step():
    scene = bpy.context.scene
    samples = module("operators.samples")
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    samples.rotary_block(scene)
    bpy.context.view_layer.objects.active = scene.objects["bowl"]
    run_in_view(bpy.ops.kezuri.rotary_generate)
    only_panels("KEZURI_PT_rotary")
    show_cam_tab()
    frame_all()


def stepnc_step():
    scene = bpy.context.scene
    samples = module("operators.samples")
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    stepnc = module("toolpath.stepnc")
    program = module("toolpath.program")
    pockets = [stepnc.PocketSpec("POCKET1", ((10, 10), (50, 10), (50, 40), (10, 40)), 8.0),
               stepnc.PocketSpec("POCKET2", ((65, 15), (110, 15), (110, 35), (85, 35), (85, 70), (65, 70)), 5.0)]
    path = os.path.join(OUT, "sample.stp")
    os.makedirs(OUT, exist_ok=True)
    with open(path, "w") as stream:
        stream.write(stepnc.pockets_to_part21(((0, 0, -20), (120, 80, 0)), pockets,
                                              program.Tool(1, "flat", 6.0, flute_length=20.0), name="SAMPLE PLATE"))
    run_in_view(bpy.ops.kezuri.import_stepnc, filepath=path)
    scene.kezuri.stepnc.active_step = 1
    run_in_view(bpy.ops.kezuri.stepnc_generate)
    only_panels("KEZURI_PT_stepnc")
    show_cam_tab()
    frame_all()


def turnmill_step():
    scene = bpy.context.scene
    samples = module("operators.samples")
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    samples.turnmill_part(scene)
    run_in_view(bpy.ops.kezuri.turnmill_classify)
    only_panels("KEZURI_PT_turnmill")
    show_cam_tab("VERTEX")
    frame_all()


def turnmill_simulate_step():
    """The sample bar carved by the radial and axial tools, coloured by operation."""
    scene = bpy.context.scene
    run_in_view(bpy.ops.kezuri.simulate, workflow="TURNMILL")
    scene.kezuri.turnmill.part.hide_set(True)
    for obj in scene.objects:
        if obj.name.startswith("Kezuri Turn-Mill"):
            obj.hide_set(True)
    scene.kezuri.simulation.colour_by = "OPERATION"
    only_panels("KEZURI_PT_simulate")
    show_cam_tab("VERTEX")
    frame_all()


def japanese_step():
    """The interface in Japanese: the sheet-metal panel after Unfold, and a report message built
    with an f-string checked to come out in Japanese (the bpy wheel has no locales to check it)."""
    view = bpy.context.preferences.view
    view.language = "ja_JP"
    view.use_translate_interface = view.use_translate_tooltips = view.use_translate_reports = True
    translations = module("operators.translations")
    message = translations.translate_message("stock radius must be > 0, got -1")
    # ascii(): the chroot's stdout may not take Japanese
    print("japanese reports: " + ("ok " if message == "素材の半径は0より大きくしてください（指定値 -1）" else "failed ")
          + ascii(message), flush=True)
    sheet_step()


def english_step():
    view = bpy.context.preferences.view
    view.language = "en_US"
    view.use_translate_reports = False


def simulated_objects():
    return [o.name for o in bpy.context.scene.objects if o.name.startswith("Kezuri Simulated")]


def start_long_simulation():
    """The exact (manifold) simulation of the name plate, invoked as from the panel's button: it
    runs in steps from a timer, with the progress in the status bar."""
    scene = bpy.context.scene
    samples = module("operators.samples")
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    samples.name_plate(scene)
    scene.kezuri.simulation.engine = "manifold"
    only_panels("KEZURI_PT_simulate")
    show_cam_tab()
    frame_all()
    run_in_view(bpy.ops.kezuri.simulate, "INVOKE_DEFAULT", workflow="ENGRAVE")


def press_escape():
    """Esc in the viewport cancels the running simulation: nothing may be left in the scene."""
    window, area, _, _ = view3d()
    x, y = area.x + area.width // 2, window.height - (area.y + area.height // 2)
    subprocess.run(["xdotool", "mousemove", str(x), str(y), "key", "Escape"], check=True)


def check_cancelled():
    left = simulated_objects()
    print("modal simulation: cancel " + ("ok, nothing left in the scene" if not left else f"failed: {left}"),
          flush=True)
    bpy.context.scene.kezuri.simulation.engine = "heightfield"
    run_in_view(bpy.ops.kezuri.simulate, "INVOKE_DEFAULT", workflow="ENGRAVE")


def check_finished():
    state.setdefault("waited", 0)
    if module("operators.common").SteppedOperator.running and state["waited"] < 40:   # still cutting
        state["waited"] += 1
        STEPS.insert(state["index"], ("modal finished", check_finished, None))
        return
    made = simulated_objects()
    print("modal simulation: run to the end " + ("ok" if made else "failed: no simulated stock"), flush=True)


STEPS = [("setup", maximise_viewport, None), ("cam tab", click_cam_tab, None), ("engrave", engrave_step, "engrave"),
         ("simulate", simulate_step, "simulate"), ("rotary", rotary_step, "rotary"),
         ("stepnc", stepnc_step, "stepnc"), ("turnmill", turnmill_step, "turnmill"),
         ("turnmill simulate", turnmill_simulate_step, "simulate-turnmill"),
         ("sheet", sheet_step, "sheet-metal"), ("elbow", elbow_step, "elbow"),
         ("japanese", japanese_step, "sheet-metal-ja"), ("english", english_step, None),
         ("modal start", start_long_simulation, "simulate-running"), ("modal cancel", press_escape, None),
         ("modal restart", check_cancelled, None), ("modal finished", check_finished, None)]
state = {"index": 0, "pending": None}


def tick():
    """One step per call; the screenshot of a step is taken on the next call, after a redraw."""
    if state["pending"]:
        shoot(state["pending"])
        state["pending"] = None
    if state["index"] >= len(STEPS):
        only_panels("KEZURI_PT")                 # every panel back, so the extension unregisters cleanly
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
