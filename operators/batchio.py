"""What every workflow's batch command shares: the scene to work on, and rounding for reports."""
from __future__ import annotations

import os

from .convert import SceneInputError


def open_blend(path: str | None):
    """The scene to work on: the given .blend's, or a fresh empty one in millimetres."""
    import bpy

    from . import samples
    if path:
        if not os.path.isfile(path):
            raise FileNotFoundError(f"no such .blend file: {path}")
        try:
            bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path))
        except RuntimeError as error:
            raise SceneInputError(f"--blend {path}: not a .blend file Blender can open ({error})") from None
        return bpy.context.scene
    scene = bpy.context.scene
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    return scene


def rounded(array, digits: int = 6):
    import numpy as np
    return np.round(np.asarray(array, float), digits).tolist()
