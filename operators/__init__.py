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


def unregister():
    translations.unregister()
    for menu, draw in reversed(MENUS):
        menu.remove(draw)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
    properties.unregister()
