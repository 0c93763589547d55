"""The move kinds and their colours: the one table the batch pictures (:mod:`.picture_jobs`) and
the viewport's toolpath preview (the shell's ``operators/pathview.py``) both read.

A move is a cut, a plunge, a link (a feed move between cuts) or a rapid (what each is:
:func:`.picture_jobs.move_roles`); what a job leaves uncut is marked in :data:`UNCUT_COLOUR`.
Colours are 8-bit sRGB, as a PNG stores them.  Blender's colour properties (a material's
viewport colour, an object's colour) hold scene-linear values, and its Solid shading shows them
through the colour configuration's default view, not the scene's AgX (Blender's
``draw_color_management.cc``, ``viewport_settings_apply``; the default view of the sRGB display
in Blender 5.0's ``config.ocio`` is Standard): :func:`linear_rgba` decodes the sRGB bytes, so
the viewport draws a move kind in the picture's colour (under its lighting).
"""
from __future__ import annotations

import numpy as np

CUT, PLUNGE, LINK, RAPID_ROLE = 0, 1, 2, 3
ROLES = ("cut", "plunge", "link", "rapid")          # indexed by CUT, PLUNGE, LINK, RAPID_ROLE
ROLE_COLOURS = {"cut": (25, 95, 225), "plunge": (220, 30, 30), "link": (10, 160, 60), "rapid": (200, 40, 200)}
ROLE_LABELS = {"cut": "CUT", "plunge": "PLUNGE", "link": "LINK (FEED BETWEEN CUTS)", "rapid": "RAPID (DASHED)"}
UNCUT_COLOUR = (235, 20, 20)


def srgb_to_linear(values) -> np.ndarray:
    """sRGB-encoded values 0..1 to linear light (the sRGB transfer function, IEC 61966-2-1:
    c / 12.92 up to 0.04045, ((c + 0.055) / 1.055) ** 2.4 above)."""
    c = np.asarray(values, float)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_rgba(role: str) -> tuple:
    """The colour of move kind ``role`` (one of :data:`ROLES`) as scene-linear RGBA, alpha 1."""
    return tuple(float(v) for v in srgb_to_linear(np.asarray(ROLE_COLOURS[role]) / 255.0)) + (1.0,)
