"""Runs inside a real Blender window (scripts/screenshots.sh starts it under Xvfb with
``--enable-event-simulate``) and uses the CAM tab as a user does: every press is a mouse or key
event at a place on the screen (``Window.event_simulate``, as Blender's own ui_simulate tests
do), every export goes through the file browser, and the written file is compared with what
batch wrote for the same sample (``KEZURI_BATCH``, the ``batch.py demo`` folder).

Where the buttons are is read off the screen: a grab of the X screen (``xwd``) is scanned down the
sidebar for button rows (the widget grey across the layout's width); the big Generate and
Simulate buttons are the rows 1.4 times as tall.  Then the label-width check of
tests/sidebar_fit.py runs against the real sidebar's width, in English and Japanese.

Output lines (scripts/screenshots.sh keeps them): ``screenshot``, ``click``, ``export``, ``fit``,
``modal``, ``japanese``, ``failed``.
"""
import importlib
import os
import subprocess
import sys
import time

import bpy
import numpy as np

OUT = os.environ.get("KEZURI_SCREENSHOTS", "/tmp/screenshots")
BATCH = os.environ.get("KEZURI_BATCH", "/tmp/blender-demo")
EXPORTS = os.environ.get("KEZURI_EXPORTS", "/tmp/kezuri-exports")
PACKAGE = next((name for name in sys.modules if name.endswith(".kezuri") and name.startswith("bl_ext.")), None)
FAILURES = []


def module(name):
    return importlib.import_module(f"{PACKAGE}.{name}")


def log(text):
    print(text, flush=True)
    if text.startswith("failed") or " failed" in text:
        FAILURES.append(text)


# ----- the screen ----------------------------------------------------------------------------

def view3d():
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == "VIEW_3D"), key=lambda a: a.width * a.height)
    region = next(r for r in area.regions if r.type == "WINDOW")
    sidebar = next(r for r in area.regions if r.type == "UI")
    return window, area, region, sidebar


def grab() -> np.ndarray:
    """The X screen as an (height, width, 3) array, top row first."""
    ppm = subprocess.run("xwd -root -silent | convert xwd:- ppm:-", shell=True, check=True,
                         capture_output=True).stdout
    header, at = [], 0
    while len(header) < 4:                    # P6, width, height, maxval; "#" comments skipped
        while ppm[at:at + 1].isspace():
            at += 1
        if ppm[at:at + 1] == b"#":
            at = ppm.index(b"\n", at) + 1
            continue
        end = at
        while not ppm[end:end + 1].isspace():
            end += 1
        header.append(ppm[at:end])
        at = end
    width, height = int(header[1]), int(header[2])
    pixels = ppm[at + 1:at + 1 + width * height * 3]
    return np.frombuffer(pixels, np.uint8).reshape(height, width, 3)


def shoot(name):
    os.makedirs(OUT, exist_ok=True)
    path = os.path.join(OUT, f"{name}.png")
    subprocess.run(f"xwd -root -silent | convert xwd:- png:{path}", shell=True, check=True)
    log(f"screenshot {path}")


def button_rows(image, window, sidebar):
    """Rows of full-width buttons in the sidebar, top to bottom: (top, bottom) in window
    coordinates from the window's top.  A row is a button row where a plain button grey (the
    default theme's 84, 101 under the mouse) fills both ends of the layout (just after the icon,
    just before the right edge): the centred text stays clear of them, and a name | value row
    has the panel's background at its left end."""
    x0 = sidebar.x + 20
    x1 = sidebar.x + sidebar.width - 40        # leave the category tabs and the panel edge
    top = window.height - (sidebar.y + sidebar.height)
    strip = image[top:top + sidebar.height, x0:x1].astype(int)

    def plain_grey(part):
        return (part.max(axis=(1, 2)) - part.min(axis=(1, 2)) <= 6) & (part.mean(axis=(1, 2)) >= 75) & \
            (part.mean(axis=(1, 2)) <= 115)
    grey = plain_grey(strip[:, 18:26]) & plain_grey(strip[:, -14:-6])     # after the icon; before the edge
    rows, start = [], None
    for y, on in enumerate(list(grey) + [False]):
        if on and start is None:
            start = y
        elif not on and start is not None:
            if y - start >= 14:
                rows.append((top + start, top + y))
            start = None
    return rows


def find_buttons():
    window, _, _, sidebar = view3d()
    rows = button_rows(grab(), window, sidebar)
    ui_unit = 20 * bpy.context.preferences.system.ui_scale
    tall = [i for i, (t, b) in enumerate(rows) if b - t >= 1.2 * ui_unit]    # scale_y 1.4: 28 px, others 20
    return rows, tall


# ----- events --------------------------------------------------------------------------------

def event(kind, value="PRESS", x=None, y=None, window=None, **modifiers):
    window = window or view3d()[0]
    if x is None:
        x, y = STATE["mouse"]
    STATE["mouse"] = (x, y)
    window.event_simulate(type=kind, value=value, x=int(x), y=int(y), **modifiers)


def settle(frames=6):
    for _ in range(frames):
        yield 0.05


def click_at(x, y_from_top, what, window=None):
    """Move there, press and release the left button (y counted from the window's top)."""
    window = window or view3d()[0]
    y = window.height - y_from_top
    event("MOUSEMOVE", "NOTHING", x, y, window)
    yield from settle(2)
    event("LEFTMOUSE", "PRESS", x, y, window)
    yield 0.05
    event("LEFTMOUSE", "RELEASE", x, y, window)
    log(f"click {what} at ({int(x)}, {int(y_from_top)})")
    yield from settle()


def key(kind, window=None, **modifiers):
    event(kind, "PRESS", window=window, **modifiers)
    yield 0.02
    event(kind, "RELEASE", window=window, **modifiers)
    yield from settle(3)


def click_row(row, what, fraction=0.5):
    _, _, _, sidebar = view3d()
    x = sidebar.x + 20 + (sidebar.width - 60) * fraction
    yield from click_at(x, (row[0] + row[1]) / 2, what)


# ----- the CAM tab ---------------------------------------------------------------------------

def open_cam_tab():
    """Sidebar open (N in the viewport), then a click on the CAM tab: the tabs run down the
    sidebar's right edge; CAM is the one whose click puts the job picker at the top."""
    window, area, region, sidebar = view3d()
    if not area.spaces.active.show_region_ui:
        event("MOUSEMOVE", "NOTHING", region.x + region.width // 2, region.y + region.height // 2)
        yield from key("N")
    window, area, region, sidebar = view3d()
    x = sidebar.x + sidebar.width - 10
    for below_top in range(40, 400, 25):       # the tabs, from the top, until the picker shows
        yield from click_at(x, window.height - (sidebar.y + sidebar.height) + below_top, "sidebar tab")
        if picker_row() is not None:
            log(f"click CAM tab ok ({below_top} px below the sidebar's top)")
            return
    log("failed: no CAM tab found")


def picker_row():
    """The job picker: the first full-width widget row at the top of the CAM tab (a menu button,
    darker than the grey buttons), found by its text changing with the picked job."""
    window, _, _, sidebar = view3d()
    image = grab()
    top = window.height - (sidebar.y + sidebar.height)
    x0, x1 = sidebar.x + 20, sidebar.x + sidebar.width - 40
    strip = image[top:top + 60, x0:x1].astype(int)
    background = np.median(image[top + 2:top + 4, x0:x1].reshape(-1, 3), axis=0)
    differs = (np.abs(strip - background).sum(axis=2) > 20).mean(axis=1) > 0.85
    ys = np.nonzero(differs)[0]
    if not len(ys) or bpy.context.scene.kezuri.job is None:
        return None
    return top + int(ys[0]), top + int(ys[-1])


def pick_job(key_name):
    """Open the job picker with a click, then as a user at the keyboard: the menu opens with the
    current entry under the mouse; the arrow keys move to the wanted one, Return picks it."""
    keys = [k for k, *_ in module("operators.workflows").job_items()]
    scene = bpy.context.scene
    row = picker_row()
    if row is None:
        log("failed: job picker not found")
        return
    yield from click_row(row, "job picker")
    yield from settle(6)
    if not STATE.get("picker shot"):
        shoot("job-picker")
        STATE["picker shot"] = True
    # The menu opens below the picker with the current entry highlighted (the theme's blue);
    # entries are 23 px apart (Blender 4.3's menu rows at resolution scale 1).
    window, _, _, sidebar = view3d()
    image = grab().astype(int)
    x = int(STATE["mouse"][0])
    column = image[row[1]:row[1] + 400, x]
    blue = np.nonzero((column[:, 2] - column[:, 0] > 60))[0]
    if not len(blue):
        log("failed: the job menu did not open")
        return
    current_y = row[1] + (blue[0] + blue[-1]) / 2 if blue[-1] - blue[0] < 30 else row[1] + blue[0] + 9
    steps = keys.index(key_name) - keys.index(scene.kezuri.job)
    yield from click_at(x, current_y + 23 * steps, f"job menu entry {key_name}")
    yield from settle(6)
    if scene.kezuri.job != key_name:
        log(f"failed: the job picker shows {scene.kezuri.job}, not {key_name}")
        yield from key("ESC")


def press_big(index, what):
    """Press the ``index``-th tall button of the tab (0: the job's Generate, 1: Simulate)."""
    rows, tall = find_buttons()
    if len(tall) <= index:
        log(f"failed: no button for {what} ({len(rows)} button rows, tall {tall})")
        return None
    yield from click_row(rows[tall[index]], what)
    return rows, tall[index]


def file_browser():
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == "FILE_BROWSER":
                return window, area
    return None


PROPOSED_SUFFIX = {"engrave": "-engrave", "rotary": "-rotary", "stepnc": "-workplan", "turnmill": "-turnmill",
                   "carve": "-carve"}


def through_file_browser(directory, filename, what):
    """The file browser the button opened: type the folder and the file name, press Return."""
    for _ in range(40):
        if file_browser():
            break
        yield 0.1
    found = file_browser()
    if not found:
        log(f"failed: {what}: no file browser opened")
        return False
    window, area = found
    params = area.spaces.active.params
    # what the export proposes: <scene>-<job><the post's extension> (operators/exporting.py)
    proposed, suffix = params.filename, PROPOSED_SUFFIX.get(what)
    if suffix is not None:
        wanted = suffix + os.path.splitext(filename)[1]
        if proposed.endswith(wanted):
            log(f"export {what}: the file browser proposes {proposed}")
        else:
            log(f"failed: export {what}: the file browser proposes {proposed!r}, not a name ending {wanted!r}")
    params.directory = directory.encode()
    params.filename = filename
    yield from settle()
    centre = (area.x + area.width // 2, area.y + area.height // 2)
    event("MOUSEMOVE", "NOTHING", *centre, window=window)
    yield from settle(2)
    # Return: the press runs the export and may close the window; release only into a live one
    event("RET", "PRESS", window=window)
    yield 0.05
    if file_browser() and file_browser()[0] == window:
        event("RET", "RELEASE", window=window)
    for _ in range(600):                      # the export runs the export gate: wait for it
        if not file_browser():
            break
        yield 0.1
    return True


def press_export(what, directory, filename):
    """Export: the first full-width button under the big Generate button that opens a file
    browser (a row that opens something else is closed with Esc)."""
    rows, tall = find_buttons()
    if not tall:
        log(f"failed: {what}: no Generate button to find Export under")
        return
    for row in rows[tall[0] + 1:tall[0] + 4]:
        yield from click_row(row, f"{what} export")
        for _ in range(50):
            if file_browser():
                yield from through_file_browser(directory, filename, what)
                return
            yield 0.1
        yield from key("ESC")
    log(f"failed: {what}: no export button found")


def compare(written, batch, what):
    if not os.path.isfile(written):
        log(f"failed: export {what}: nothing written at {written}")
        return
    if not os.path.isfile(batch):
        log(f"export {what}: written {written}; no batch file {batch} to compare")
        return
    a, b = open(written, "rb").read(), open(batch, "rb").read()
    if a == b:
        log(f"export {what}: identical to batch ({len(a)} bytes)")
        return
    lines_a, lines_b = a.decode(errors="replace").splitlines(), b.decode(errors="replace").splitlines()
    first = next((i for i, (x, y) in enumerate(zip(lines_a, lines_b)) if x != y), min(len(lines_a), len(lines_b)))
    log(f"failed: export {what} differs from batch at line {first + 1}: "
        f"{lines_a[first] if first < len(lines_a) else '<end>'!r} vs {lines_b[first] if first < len(lines_b) else '<end>'!r}")


# ----- the jobs ------------------------------------------------------------------------------

def fresh(scene, build=None):
    samples = module("operators.samples")
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    if build is not None:
        build(scene)


def frame_all():
    window, area, region, _ = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.view3d.view_all(center=False)


def generate_and_export(key_name, what, filename, batch_path, picture, colours="OBJECT"):
    yield from pick_job(key_name)
    yield from settle(10)
    pressed = yield from press_big(0, f"{what} generate")
    if pressed is None:
        return
    yield from settle(20)
    view3d()[1].spaces.active.shading.color_type = colours
    frame_all()
    yield from settle(10)
    shoot(picture)
    os.makedirs(EXPORTS, exist_ok=True)
    yield from press_export(what, EXPORTS, filename)
    compare(os.path.join(EXPORTS, filename), os.path.join(BATCH, batch_path), what)


def engrave():
    scene = bpy.context.scene
    fresh(scene, module("operators.samples").name_plate)
    scene.kezuri.machine.post = "linuxcnc"           # the batch demo's post
    yield from generate_and_export("ENGRAVE", "engrave", "engrave.ngc", "engrave/engrave.ngc", "engrave")


def rotary():
    scene = bpy.context.scene
    fresh(scene, module("operators.samples").rotary_block)
    yield from generate_and_export("ROTARY", "rotary", "rotary.ngc", "rotary/rotary.ngc", "rotary")


def stepnc():
    """Import the batch demo's sample through the Import button's file browser, then the list."""
    scene = bpy.context.scene
    fresh(scene)
    scene.kezuri.machine.post = "fanuc"              # the batch demo's post
    yield from pick_job("STEPNC")
    picker = picker_row()
    rows = [r for r in find_buttons()[0] if picker is None or r[0] > picker[1]]
    if not rows:
        log("failed: stepnc: no Import button")
        return
    yield from click_row(rows[0], "stepnc import")      # the first full-width button under the picker
    yield from through_file_browser(os.path.join(BATCH, "stepnc"), "sample.stp", "stepnc import")
    log(f"stepnc import: {len(scene.kezuri.stepnc.steps)} workingsteps: "
        + "; ".join(f"{s.feature_name} {s.step} {s.tool}" for s in scene.kezuri.stepnc.steps))
    yield from generate_and_export("STEPNC", "stepnc", "stepnc.nc", "stepnc/stepnc.nc", "stepnc")


def turnmill():
    scene = bpy.context.scene
    fresh(scene, module("operators.samples").turnmill_part)
    yield from generate_and_export("TURNMILL", "turnmill", "turnmill.nc", "turnmill/turnmill.nc", "turnmill",
                                   "VERTEX")


def carve():
    """The Wave Relief sample from its button (the left half of the sample row), then Generate."""
    scene = bpy.context.scene
    fresh(scene)
    scene.kezuri.machine.post = "linuxcnc"
    yield from pick_job("CARVE")
    picker = picker_row()
    rows = [r for r in find_buttons()[0] if picker is None or r[0] > picker[1]]
    sample_row = rows[0] if rows else None      # the first full-width row: Wave Relief | Domed Plate
    if sample_row is None:
        log("failed: carve: no sample buttons")
        return
    yield from click_row(sample_row, "carve Wave Relief", fraction=0.25)
    yield from generate_and_export("CARVE", "carve", "carve.ngc", "carve/carve.ngc", "carve")


def sheet():
    scene = bpy.context.scene
    fresh(scene)
    yield from generate_and_export("SHEET", "unfold", "unfold.nc", "unfold/unfold.nc", "sheet-metal")


def simulate():
    """Simulate & Check on the name plate (the second tall button: Generate, then Simulate)."""
    scene = bpy.context.scene
    fresh(scene, module("operators.samples").name_plate)
    yield from pick_job("ENGRAVE")
    yield from press_big(1, "simulate")
    for _ in range(600):
        yield 0.1
        if not module("operators.common").SteppedOperator.running:
            break
    scene.kezuri.stock.plate.hide_set(True)
    scene.objects["Letters"].hide_set(True)
    view3d()[1].spaces.active.shading.color_type = "VERTEX"
    frame_all()
    yield from settle(10)
    shoot("simulate")


def exact_simulation():
    """The exact (manifold) simulation from the button: Esc cancels it (nothing left), pressed
    again it runs to the end, exact all the way."""
    scene = bpy.context.scene
    fresh(scene, module("operators.samples").name_plate)
    scene.kezuri.simulation.engine = "manifold"
    common = module("operators.common")
    yield from pick_job("ENGRAVE")
    yield from press_big(1, "exact simulate")
    yield from settle(20)
    shoot("simulate-running")
    window, area, _, _ = view3d()
    event("MOUSEMOVE", "NOTHING", area.x + area.width // 2, area.y + area.height // 2)
    yield from key("ESC")
    yield from settle(20)
    left = [o.name for o in scene.objects if o.name.startswith("Kezuri Simulated")]
    log("modal simulation: cancel " + ("ok, nothing left in the scene" if not left else f"failed: {left}"))
    started = time.monotonic()
    yield from press_big(1, "exact simulate again")
    while common.SteppedOperator.running and time.monotonic() - started < 900:
        yield 0.5
    made = [o.name for o in scene.objects if o.name.startswith("Kezuri Simulated")]
    log(f"modal simulation: exact run to the end {'ok' if made else 'failed: no simulated stock'} "
        f"in {time.monotonic() - started:.0f} s (engine {scene.kezuri.simulation.engine})")


def label_widths():
    """The width check of tests/sidebar_fit.py against this window's sidebar."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import sidebar_fit as fit
    _, _, _, sidebar = view3d()
    scale = bpy.context.preferences.system.ui_scale
    width = fit.layout_width(sidebar.width / scale)
    panels = module("operators.panels")
    tables = {"en": None, "ja": module("operators.translations").TRANSLATIONS["ja_JP"]}
    scene = bpy.context.scene
    context = type("Context", (), {"scene": scene, "active_object": bpy.context.active_object})()
    for language, table in tables.items():
        problems = []
        for key_name, *_ in module("operators.workflows").job_items():
            scene.kezuri.job = key_name
            problems += fit.too_wide(fit.all_texts(panels.CLASSES, context, table, width))
        log(f"fit {language}: sidebar {sidebar.width} px, layout {width:.0f} px: "
            + ("every text fits" if not problems else f"failed: {len(problems)} too wide: " + "; ".join(problems[:5])))
    yield 0.05


def japanese():
    view = bpy.context.preferences.view
    view.language = "ja_JP"
    view.use_translate_interface = view.use_translate_tooltips = view.use_translate_reports = True
    message = module("operators.translations").translate_message("stock radius must be > 0, got -1")
    log("japanese reports: " + ("ok " if message == "素材の半径は0より大きくしてください（指定値 -1）" else "failed ")
        + ascii(message))
    fresh(bpy.context.scene)
    yield from pick_job("SHEET")
    yield from settle(10)
    if (yield from press_big(0, "unfold generate (ja)")) is None:
        return
    yield from settle(20)
    frame_all()
    window, area, _, _ = view3d()                   # the mouse over the viewport: no tooltip on the panel
    event("MOUSEMOVE", "NOTHING", area.x + area.width // 3, area.y + area.height // 3)
    yield from settle(20)
    shoot("sheet-metal-ja")
    view.language = "en_US"
    view.use_translate_reports = False


def run():
    window, area, region, _ = view3d()
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.screen.screen_full_area()
    yield from settle(10)
    yield from open_cam_tab()
    for job in (engrave, simulate, rotary, stepnc, turnmill, carve, sheet, label_widths, japanese, exact_simulation):
        try:
            yield from job()
        except Exception as error:  # noqa: BLE001 - report and carry on with the other jobs
            log(f"failed: step {job.__name__}: {type(error).__name__}: {error}")


STATE = {"mouse": (800, 500), "steps": None}


def tick():
    if STATE["steps"] is None:
        STATE["steps"] = run()
    try:
        return next(STATE["steps"]) or 0.05
    except StopIteration:
        log(f"done: {len(FAILURES)} failure(s)")
    except Exception as error:  # noqa: BLE001 - a timer that raises is dropped: Blender would stay open
        import traceback
        traceback.print_exc()
        log(f"failed: the driver stopped: {type(error).__name__}: {error}")
    bpy.ops.wm.quit_blender()
    return None


if PACKAGE is None:
    print("failed: Kezuri is not installed in this Blender", flush=True)
    bpy.ops.wm.quit_blender()
elif "event_simulate" not in bpy.types.Window.bl_rna.functions or not bpy.app.use_event_simulate:
    print("failed: start Blender with --enable-event-simulate", flush=True)
    bpy.ops.wm.quit_blender()
else:
    bpy.context.scene.unit_settings.scale_length = 0.001
    bpy.app.timers.register(tick, first_interval=3.0)
