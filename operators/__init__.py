"""The Blender shell: properties, operators and panels.  The only package that imports bpy."""
from __future__ import annotations

import bpy

from . import (designfile, joblist, panels, preferences, properties, simulate, suggestfeeds, toollib, toolmenu,
               translations)
from .workflows import WORKFLOWS, job_items, settings_groups

CLASSES = (*preferences.CLASSES, *(cls for workflow in WORKFLOWS for cls in workflow.classes), *simulate.CLASSES,
           *joblist.CLASSES, *designfile.CLASSES, *panels.CLASSES,
           *toollib.CLASSES, *toolmenu.CLASSES, *suggestfeeds.CLASSES)
MENUS = (*(menu for workflow in WORKFLOWS for menu in workflow.menus), *designfile.MENUS)


def register():
    properties.register(job_items(), settings_groups())
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    toollib.register_properties()
    if not bpy.app.background:          # batch runs and tests read the library when they need it
        bpy.app.timers.register(start_tool_library, first_interval=0.5)
    for menu, draw in MENUS:
        menu.append(draw)
    translations.register()
    warm_kernels_in_background()


def start_tool_library():
    """Once Blender's window is up (a timer: registering cannot touch data): move the preferences'
    old tool list into the tool library file, then read the library for the CAM tab's panel."""
    preferences.move_at_startup()
    return toollib.load_when_ready()


_WARMUP = {"job": None}


def start_warmup():
    """Compile the simulation kernels (or check numba's on-disk cache) in a child Python process
    (:class:`.common.ProcessJob`): the machine code lands in numba's cache, from which this
    process loads it at the first Simulate instead of compiling.  Not on a thread of Blender's:
    LLVM compiling beside the UI's own LLVM (Mesa's software GL) crashed Blender 4.3."""
    from .common import CoreCall, ProcessJob

    return ProcessJob(CoreCall("toolpath.engines.warmup", "warm_kernels", {}))


def warm_kernels_in_background():
    """In an interactive Blender, warm the kernels in a child process after registering, so the
    first Simulate runs as fast as the later ones.  Batch runs (background mode) compile on
    first use instead."""
    if bpy.app.background:
        return None
    try:
        job = _WARMUP["job"] = start_warmup()
    except OSError as error:                 # no child process: the kernels compile on first use
        print(f"Kezuri: the simulation kernels were not compiled ahead ({error})")
        return None

    def poll():
        if not job.step():
            return 1.0
        try:
            job.result()
        except Exception as error:      # noqa: BLE001 - then they compile on first use: slower, not wrong
            print(f"Kezuri: the simulation kernels were not compiled ahead ({str(error)[-300:]}); "
                  "the first Simulate compiles them")
        _WARMUP["job"] = None
        return None

    bpy.app.timers.register(poll, first_interval=1.0, persistent=True)
    return job


def unregister():
    if _WARMUP["job"] is not None:
        _WARMUP["job"].cancel()
        _WARMUP["job"] = None
    translations.unregister()
    for menu, draw in reversed(MENUS):
        menu.remove(draw)
    toollib.unregister_properties()
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
    properties.unregister()
