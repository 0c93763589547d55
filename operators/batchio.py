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
            raise FileNotFoundError(f"--blend {path}: no such .blend file")
        try:
            bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path))
        except RuntimeError as error:
            reason = str(error).strip().removeprefix("Error:").strip()
            raise SceneInputError(f"--blend {path}: not a .blend file Blender can open ({reason})") from None
        return bpy.context.scene
    scene = bpy.context.scene
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    return scene


def shown() -> bool:
    """Whether batch's results are put in the scene as objects: only when Blender has a window to
    show them (``blender file.blend --python batch.py -- ...``).  In background mode the scene is
    thrown away at exit and the pictures are drawn from the arrays, so those objects would be
    time spent for nobody."""
    import bpy
    return not bpy.app.background


def rounded(array, digits: int = 6):
    import numpy as np
    return np.round(np.asarray(array, float), digits).tolist()


# ----- batch arguments, checked against their meaning -------------------------------------------

def number(option: str, lo=None, hi=None, *, integer: bool = False, lo_open: bool = False, unit: str = "",
           limit=None):
    """An argparse ``type`` that takes a finite number within [lo, hi] (``lo_open``: lo excluded),
    or the range ``limit`` of ``limits.RANGES`` (so batch and the panel share one table),
    and refuses anything else naming the option, the value given and the range: never a value the
    scene would silently clamp to another job."""
    import argparse
    import math

    if limit is not None:
        lo, hi, lo_open, integer, unit = limit.lo, limit.hi, limit.lo_open, limit.integer, limit.unit
    kind = "an integer" if integer else "a number"
    low = "" if lo is None else (f"{lo:g} <" if lo_open else f"{lo:g} <=")
    high = "" if hi is None else f"<= {hi:g}"
    allowed = " ".join(part for part in (low, option.lstrip("-"), high) if part) + (f" {unit}" if unit else "")

    def parse(text: str):
        try:
            value = int(text) if integer else float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not {kind} (allowed: {allowed})") from None
        if not math.isfinite(value) or (lo is not None and (value <= lo if lo_open else value < lo)) or \
                (hi is not None and value > hi):
            raise argparse.ArgumentTypeError(f"{text} is outside the allowed range {allowed}")
        return value
    parse.__name__ = option
    return parse


def set_exactly(group, name: str, value, option: str) -> None:
    """Set a scene setting from a batch argument and make sure it took the value as given (Blender
    clamps to a property's limits without a word)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise SceneInputError(f"{option}: {value!r} is not a value")
    setattr(group, name, value)
    held = getattr(group, name)
    if isinstance(value, float) or isinstance(held, float):
        same = abs(float(held) - float(value)) <= 1e-6 * max(1.0, abs(float(value)))
    else:
        same = held == value
    if not same:
        raise SceneInputError(f"{option} {value}: the setting would hold {held} instead; give a value the "
                              f"setting allows")


def write_stl(path: str, vertices, faces) -> str:
    """A binary STL of (vertices mm, faces) written through temp + rename (the mesh a job was
    machined against, ``design.stl``, for other tools to check the cut)."""
    import trimesh

    from ..post.output import write_atomic

    data = trimesh.exchange.stl.export_stl(trimesh.Trimesh(vertices, faces, process=False))
    return write_atomic(path, data)
