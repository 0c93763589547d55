"""The Blender shell: properties, operators and panels.  The only package that imports bpy."""
from __future__ import annotations

import bpy

from . import panels, preferences, properties, simulate, translations
from .workflows import WORKFLOWS, job_items

CLASSES = (*preferences.CLASSES, *(cls for workflow in WORKFLOWS for cls in workflow.classes), *simulate.CLASSES,
           *panels.CLASSES)
MENUS = tuple(menu for workflow in WORKFLOWS for menu in workflow.menus)


def register():
    properties.register(job_items())
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    for menu, draw in MENUS:
        menu.append(draw)
    translations.register()
    warm_kernels_in_background()


def warm_kernels_in_background():
    """In an interactive Blender, compile (or load from numba's cache) the simulation kernels on
    a background thread, so the first Simulate runs as fast as the later ones.  Batch runs
    (background mode) compile on first use instead."""
    if bpy.app.background:
        return None
    import threading

    def warm():
        from ..toolpath.warmup import warm_kernels
        try:
            warm_kernels()
        except Exception as error:      # the kernels then compile on first use: slower, not wrong
            print(f"Kezuri: the simulation kernels were not compiled ahead ({error}); "
                  "the first Simulate compiles them")
    thread = threading.Thread(target=warm, name="Kezuri kernel warm-up", daemon=True)
    thread.start()
    return thread


def unregister():
    translations.unregister()
    for menu, draw in reversed(MENUS):
        menu.remove(draw)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
    properties.unregister()
