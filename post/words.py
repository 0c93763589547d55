"""Word formatting for whole columns of moves at once.

A post writes 10^5 moves; formatting every number with a Python call per value costs seconds.
Coordinates repeat a lot (a raster's X values, a pass's Z), so a column is formatted once per
distinct value with the post's own scalar formatter (the text is the same, byte for byte, as
the scalar writer gives) and the texts are given back with an integer id per move: two moves
have the same id exactly when their words read the same, which is what modal posts compare.
"""
from __future__ import annotations

from typing import Callable

import numpy as np


def column(values, text_of: Callable[[float], str], many: Callable[[list], list] | None = None) -> tuple:
    """(texts, ids) for a 1-d array of floats: ``texts`` an object array of the distinct words,
    ``ids`` (n,) int indices into it, equal exactly where ``text_of`` gives the same text.
    ``many``: ``text_of`` for a whole list of values at once (the same texts, faster), if the post
    has one (:func:`fixed`, :func:`trimmed`)."""
    values = np.ascontiguousarray(values, dtype=float).reshape(-1)
    if not len(values):
        return np.empty(0, dtype=object), np.empty(0, dtype=np.intp)
    distinct, inverse = np.unique(values, return_inverse=True)   # sorted; NaN (rapids' feeds) last
    words = np.array(many(distinct.tolist()) if many is not None else [text_of(value) for value in distinct.tolist()],
                     dtype=object)
    # rounding to a fixed number of decimals is monotonic, so values that read the same are
    # neighbours in sorted order ("-0." and "0." are one text, and so neighbours too)
    new = np.ones(len(words), bool)
    new[1:] = words[1:] != words[:-1]
    texts = words[new]
    return texts, (np.cumsum(new) - 1)[inverse.reshape(-1)]


def fixed(values: list, decimals: int) -> list:
    """``f"{value:.{decimals}f}"`` of every float of ``values``, formatted in one printf-style
    call (``"%.4f" % value`` rounds and writes exactly as the f-string does)."""
    if not len(values):
        return []
    return ((f"%.{decimals}f\n" * len(values)) % tuple(values)).split("\n")[:-1]


def trimmed(values: list, decimals: int) -> list:
    """:func:`.gcode.fmt` of every float of ``values``: ``106.`` / ``-2.5`` / ``0.125``."""
    texts = [text.rstrip("0") for text in fixed(values, decimals)]
    return [("0." if text in ("-0.", "-.") else text) for text in texts]


def previous_where(mask: np.ndarray) -> np.ndarray:
    """For each index i, the largest j < i with ``mask[j]``, or -1."""
    n = len(mask)
    marked = np.where(mask, np.arange(n), -1)
    last = np.maximum.accumulate(marked) if n else marked
    return np.concatenate([[-1], last[:-1]]).astype(np.intp) if n else last.astype(np.intp)


def join_words(columns: list) -> list:
    """Lines from word columns: each column an object array of words ("" for none), joined with
    single spaces, empty words skipped."""
    if not columns or not len(columns[0]):
        return []
    spaced = np.full(len(columns[0]), "", dtype=object)
    for words in columns:
        present = words != ""
        spaced[present] = spaced[present] + (" " + words[present])
    return [line[1:] for line in spaced.tolist()]


def prefixed(letter: str, texts: np.ndarray, ids: np.ndarray, write: np.ndarray) -> np.ndarray:
    """``letter + text`` where ``write``, "" elsewhere, as an object array."""
    words = np.array([letter + text for text in texts.tolist()] + [""], dtype=object)
    return words[np.where(write, ids, len(texts))]
