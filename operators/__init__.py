"""The Blender shell: properties, operators and panels.  The only package that imports bpy."""
from __future__ import annotations

import bpy

from . import engrave, panels, properties

CLASSES = (*engrave.CLASSES, *panels.CLASSES)


def register():
    properties.register()
    for cls in CLASSES:
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
    properties.unregister()
