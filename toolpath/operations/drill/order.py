"""The order holes are visited in: a short tour (nearest neighbour, then 2-opt).

The tour is an open path from the hole nearest ``start``.  2-opt reverses a stretch of the tour
whenever that shortens it (the two links at its ends swapped), until no reversal helps or
``passes`` sweeps are done; it never lengthens the nearest neighbour's tour.
"""
from __future__ import annotations

import numpy as np


def tour_length(points: np.ndarray, order) -> float:
    p = np.asarray(points, float)[list(order)]
    return float(np.hypot(*np.diff(p, axis=0).T).sum()) if len(p) > 1 else 0.0


def short_order(points, start=None, passes: int = 50) -> np.ndarray:
    """Indices of ``points`` (n, 2) in a short visiting order."""
    p = np.asarray(points, float).reshape(-1, 2)
    n = len(p)
    if n < 3:
        if n == 2 and start is not None and np.hypot(*(p[1] - start)) < np.hypot(*(p[0] - start)):
            return np.array([1, 0])
        return np.arange(n)
    left = np.ones(n, bool)
    current = 0 if start is None else int(np.argmin(np.hypot(*(p - np.asarray(start, float)).T)))
    order = [current]
    left[current] = False
    for _ in range(n - 1):
        d = np.hypot(*(p - p[current]).T)
        d[~left] = np.inf
        current = int(np.argmin(d))
        order.append(current)
        left[current] = False
    order = np.array(order)
    for _ in range(passes):
        improved = False
        for i in range(0, n - 2):
            q = p[order]
            a, b = q[i], q[i + 1]
            c, d = q[i + 2:], np.vstack([q[i + 3:], [[np.nan, np.nan]]])
            before = np.hypot(*(b - a)) + np.where(np.isnan(d[:, 0]), 0.0, np.hypot(*(d - c).T))
            after = np.hypot(*(c - a).T) + np.where(np.isnan(d[:, 0]), 0.0, np.hypot(*(d - b).T))
            gain = before - after
            j = int(np.argmax(gain))
            if gain[j] > 1e-9:                 # reverse order[i + 1 .. i + 2 + j]
                end = i + 2 + j
                order[i + 1:end + 1] = order[i + 1:end + 1][::-1]
                improved = True
        if not improved:
            break
    return order
