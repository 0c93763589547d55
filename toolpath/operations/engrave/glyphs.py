"""Which letters object, and which character of its text, a point of an engraving lies in.

A Text object reaches the core as outlines only (its faces merged into one region), so the
character is told from the shapes: the outline's pieces (each with its counters) are grouped
into glyphs, a piece lying over or under another (the dot of an i, an accent) joining its
column, and the glyphs, left to right, are the text's characters that are not spaces.  When
the counts do not agree (several lines, a glyph of two separate pieces side by side such as
a double quote, letters run together) the character is not known and only the object is named.
"""
from __future__ import annotations

import numpy as np

from ...engines import region as rg

OVERLAP = 0.5        # pieces share a column when their X spans overlap by this share of the narrower


def _columns(pieces: list) -> list:
    """Pieces (CrossSections) grouped into columns: [(x0, x1, [pieces])], left to right."""
    spans = sorted(((p.bounds()[0], p.bounds()[2], p) for p in pieces), key=lambda s: s[0])
    columns = []
    for x0, x1, piece in spans:
        for column in columns:
            shared = min(x1, column[1]) - max(x0, column[0])
            if shared > OVERLAP * min(x1 - x0, column[1] - column[0]):
                column[0], column[1] = min(x0, column[0]), max(x1, column[1])
                column[2].append(piece)
                break
        else:
            columns.append([x0, x1, [piece]])
    return sorted(columns, key=lambda c: c[0])


def character_at(loops, text: str | None, point) -> str | None:
    """The character of ``text`` (a Text object's body) whose glyph's outline, counters filled,
    holds ``point``; None when it cannot be told (see the module notes)."""
    if not text or "\n" in text.strip():
        return None
    characters = [c for c in text if not c.isspace()]
    columns = _columns(rg.components(rg.from_loops(loops, "letters")))
    if len(columns) != len(characters):
        return None
    x, y = float(point[0]), float(point[1])
    for character, (_, _, pieces) in zip(characters, columns):
        for piece in pieces:
            filled = rg.from_loops([loop for loop in rg.loops(piece) if rg.signed_area(loop) > 0], "glyph")
            if rg.contains_points(filled, np.array([[x, y]]))[0]:
                return character
    return None


def cells(loops, text: str | None) -> list:
    """The glyphs of one letters object, left to right, as (character, index, loops): the
    character of ``text`` and its place in it when the glyphs can be matched to the text's
    characters that are not spaces (see the module notes), else (None, the glyph's number from 0,
    loops).  Each glyph's loops are its pieces' outlines with their counters."""
    columns = _columns(rg.components(rg.from_loops(loops, "letters")))
    places = [k for k, c in enumerate(text or "") if not c.isspace()]
    known = bool(text) and "\n" not in text.strip() and len(places) == len(columns)
    found = []
    for number, (_, _, pieces) in enumerate(columns):
        outline = tuple(loop for piece in pieces for loop in rg.loops(piece))
        found.append((text[places[number]], places[number], outline) if known else (None, number, outline))
    return found


def owner(letters, point) -> str | None:
    """The name of the letters object (``[(name, loops)]``) whose outline, counters filled, holds
    ``point``, else the one nearest to it."""
    best, nearest = None, np.inf
    xy = np.array([[float(point[0]), float(point[1])]])
    for name, loops in letters:
        outer = [np.asarray(loop, float) for loop in loops]
        region = rg.from_loops(outer, "letters")
        filled = rg.from_loops([loop for loop in rg.loops(region) if rg.signed_area(loop) > 0], "letters")
        if rg.contains_points(filled, xy)[0]:
            return name
        distance = min(_distance(loop, xy[0]) for loop in outer)
        if distance < nearest:
            best, nearest = name, distance
    return best


def _distance(loop: np.ndarray, point: np.ndarray) -> float:
    """From ``point`` to the closed ``loop``'s edges."""
    a, b = loop, np.roll(loop, -1, axis=0)
    span = b - a
    t = np.clip(np.einsum("ij,ij->i", point - a, span) / np.maximum(np.einsum("ij,ij->i", span, span), 1e-30), 0, 1)
    return float(np.min(np.hypot(*(a + t[:, None] * span - point).T)))


def describe(character: str | None) -> str:
    """A character as an NC comment can carry it (upper case, ASCII): 'e' (U+0065)."""
    if character is None:
        return ""
    if character.isascii() and (character.isupper() or character.isdigit()):
        return f"'{character}'"
    return f"'{character}' (U+{ord(character):04X})"
