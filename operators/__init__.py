"""The Blender shell: properties, operators and panels.  The only package that imports bpy."""
from __future__ import annotations

import bpy

from . import (engrave, panels, preferences, properties, rotary, sheetmetal, simulate, stepnc, translations,
               turnmill)

CLASSES = (*preferences.CLASSES, *engrave.CLASSES, *rotary.CLASSES, *stepnc.CLASSES, *turnmill.CLASSES,
           *sheetmetal.CLASSES, *simulate.CLASSES, *panels.CLASSES)
MENUS = (*stepnc.MENUS, *sheetmetal.MENUS)


def register():
    properties.register()
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
