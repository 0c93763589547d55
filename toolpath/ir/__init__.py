"""The IR: what the core hands to the posts, in one place.

A post takes from the core only what is listed here, plus :mod:`.kinematics` (machine <-> part for
rotary axes) and :mod:`.errors` (``tests/test_layering.py`` holds them to it): the Program and its
Operations with their move kinds, the per-family operation types (the X-Z-C turn-mill's, the turret
punch's program), the gouge-texture request, the machine profile and its presets, and the arc
filter every milling post runs before writing.  The modules behind these names are the IR's own
business; a post that needs something new gets it added here, so this list is the whole of what
the posts depend on.
"""
from .machine import DEFAULT_FOR_FAMILY, MachineProfile, preset
from .program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, Program
from .punch import PunchProgram
from .texture import GougeTexture
from .xzc import TurnMillOperation


def fit_program(*args, **kwargs):
    """Arcs out: :func:`.arcfit.fit_program`, imported at the first call (it brings numba, which a
    post should not load before it writes a program)."""
    from .arcfit import fit_program as fit

    return fit(*args, **kwargs)


__all__ = ["ARC_CCW", "ARC_CW", "DEFAULT_FOR_FAMILY", "FEED", "RAPID", "GougeTexture", "MachineProfile",
           "Operation", "Program", "PunchProgram", "TurnMillOperation", "fit_program", "preset"]
