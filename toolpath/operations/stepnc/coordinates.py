"""The coordinates of many CARTESIAN_POINTs at once (a POLYLINE of an explicit toolpath holds
hundreds, a big file a million): the plain case checked and converted with numpy, the reader's
point-by-point path taking every other case (and so giving its errors, in its order)."""
from __future__ import annotations

from itertools import chain

import numpy as np

from .model import MAX_LENGTH

_NUMBERS = {float, int}


def plain_coordinates(points: list) -> tuple | None:
    """((x, y, z), ...) of CARTESIAN_POINT instances that each hold three finite numbers (int or
    float, not bool) within MAX_LENGTH of the origin, as floats; None when any does not (the
    reader then reads them one by one and names the first that is wrong)."""
    rows = [p.params[1] if len(p.params) > 1 else None for p in points]
    if not all(type(row) is list and len(row) == 3 for row in rows):
        return None
    kinds = set(map(type, chain.from_iterable(rows)))
    if not kinds <= _NUMBERS:
        return None
    try:
        values = np.fromiter(chain.from_iterable(rows), float, 3 * len(rows))
    except (OverflowError, ValueError, TypeError):
        return None
    if not (np.isfinite(values).all() and (np.abs(values) <= MAX_LENGTH).all()):
        return None
    if kinds == {float}:        # the numbers themselves (a new float per number took most of the time)
        return tuple(map(tuple, rows))
    return tuple(map(tuple, values.reshape(len(rows), 3).tolist()))
