"""The IR's move kinds and arc geometry, the lowest layer of the Program: what a move is (rapid,
feed, arc clockwise, arc counter-clockwise) and the sweep of an arc.  :mod:`.program` (the
Program and its Operations) and :mod:`.arcfit` (arcs out) both stand on it."""
from __future__ import annotations

import numpy as np

RAPID, FEED, ARC_CW, ARC_CCW = 0, 1, 2, 3


def arc_sweep(a: np.ndarray, b: np.ndarray, c: np.ndarray, clockwise: np.ndarray) -> np.ndarray:
    """Signed sweep angle (radians) from a to b about c; a full circle when a == b."""
    ang_a = np.arctan2(a[:, 1] - c[:, 1], a[:, 0] - c[:, 0])
    ang_b = np.arctan2(b[:, 1] - c[:, 1], b[:, 0] - c[:, 0])
    ccw = np.mod(ang_b - ang_a, 2 * np.pi)
    cw = np.mod(ang_a - ang_b, 2 * np.pi)
    ccw = np.where(ccw < 1e-12, 2 * np.pi, ccw)
    cw = np.where(cw < 1e-12, 2 * np.pi, cw)
    return np.where(clockwise, -cw, ccw)
