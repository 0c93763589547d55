"""Text too fine for a V-carve's clearing tool: with a maximum depth the end mill clears the flat
floor (the carved region shrunk by r_max = (max_depth - shift) x tan(angle / 2)); where strokes are
too narrow for it the V-bit's tip traces the floor and ridges stand.  Each character owning such a
gap is named (:func:`..engines.finetext.check` on the flat floor with the end mill's diameter),
with a height at which the end mill reaches every flat: the floor of a text s times as tall is the
s-times design shrunk by the same r_max, not the floor scaled, so the height comes from the carved
region itself with a tool of the end mill's diameter plus the V-bit's width at max depth (2 r_max):
a stroke that wide leaves the end mill a floor it fits in.

Characters: (character, index in the text, loops) in work mm, as the shell tells them from a Text;
without them the design's glyphs are numbered left to right (:func:`..engrave.glyphs.cells`).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ...engines import finetext
from ...engines import region as rg
from ..engrave import glyphs

OPERATION = "clearing"


def mirrored_characters(characters, middle: float) -> list:
    """The characters mirrored about the vertical line x = middle / 2 (a male plug's design)."""
    return [(char, index, tuple(np.column_stack([middle - np.asarray(loop)[:, 0], np.asarray(loop)[:, 1]])[::-1]
                                for loop in loops)) for char, index, loops in characters]


def too_fine(characters, design, carved, flat, settings, limit: float, letters: str, what: str) -> tuple:
    """(too_fine: [{operation, letters, char, index, missed_mm2, narrowest_mm, height_mm,
    min_height_mm, at}], warnings) for the clearing tool on ``flat``; ``limit`` is r_max.
    ``missed_mm2`` and ``at``: the floor left to the V-bit now; ``narrowest_mm``: the narrowest
    stroke (the gap the end mill must enter, in the design); ``min_height_mm``: a height at which
    every stroke is the end mill's diameter + 2 r_max wide (None: not within finetext.MAX_SCALE)."""
    tool = settings.clear_tool
    if tool is None or flat is None:
        return [], []
    characters = list(characters) if characters else glyphs.cells(rg.loops(design), None)
    cells = [finetext.Character(char, k, tuple(loops)) for k, (char, _, loops) in enumerate(characters) if loops]
    places = [(char, index) for char, index, loops in characters if loops]
    now = finetext.check(cells, flat, tool.diameter)
    if not now:
        return [], []
    sizing = {found.index: found for found in finetext.check(cells, carved, tool.diameter + 2 * limit)}
    found_list, warnings = [], []
    for found in now:
        char, index = places[found.index]
        sized = sizing.get(found.index)
        height = sized.min_height_mm if sized is not None else found.min_height_mm
        # the narrowest stroke of the design (the end mill fits the floor of one dc + 2 r_max wide)
        narrowest = sized.narrowest_mm if sized is not None else found.narrowest_mm + 2 * limit
        found = dataclasses.replace(found, narrowest_mm=narrowest, min_height_mm=height)
        entry = {"operation": OPERATION, "letters": letters, **found.as_dict(), "char": char, "index": index}
        found_list.append(entry)
        name = glyphs.describe(char) if char is not None else f"glyph {index + 1}"
        lost = (f"{what}: the clearing's {tool.diameter:g} mm end mill is too big for {name} of {letters}: "
                f"{found.missed_mm2:.2f} mm^2 of the flat floor at max depth {settings.max_depth:g} mm is left to the "
                f"V-bit's tip (strokes {found.narrowest_mm:.2f} mm wide; the end mill needs {tool.diameter + 2 * limit:.2f} mm)")
        if height is None:
            warnings.append(f"{lost}; no text up to {finetext.MAX_SCALE:g} times as tall lets the end mill in: use a "
                            "smaller end mill or a smaller max depth")
        else:
            warnings.append(f"{lost}; make it at least {height:.1f} mm tall (now {found.height_mm:.1f} mm), or use a "
                            "smaller end mill or a smaller max depth")
    return found_list, warnings
