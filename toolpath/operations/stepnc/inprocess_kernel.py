"""The in-process stock's column lowering compiled with numba (:meth:`.inprocess.InProcessStock`'s
numpy loop, one segment at a time, is the reference and the fallback without numba).

One pass over the segments, column by column in each segment's box, with the same arithmetic as
the numpy loop (the column centre, its offset from the segment's start, the clamped projection,
the squared distance against the squared reach), so both lower the same columns to the same
heights; a column keeps the lowest height of the segments that cover it, whatever their order."""
from __future__ import annotations

import math

from numba import njit


@njit(cache=True, nogil=True)
def lower(heights, x0, y0, cell, ax, ay, bx, by, z, reach):
    """Lower ``heights`` (nx, ny), columns of ``cell`` from (x0, y0), to ``z[k]`` where the column
    centre lies within ``reach[k]`` (> 0) of the XY segment (ax, ay)-(bx, by)."""
    nx, ny = heights.shape
    for k in range(ax.shape[0]):
        r = reach[k]
        a0, a1, b0, b1, top = ax[k], ay[k], bx[k], by[k], z[k]
        i0 = max(0, math.ceil((min(a0, b0) - r - x0) / cell - 0.5))
        i1 = min(nx, math.floor((max(a0, b0) + r - x0) / cell - 0.5) + 1)
        j0 = max(0, math.ceil((min(a1, b1) - r - y0) / cell - 0.5))
        j1 = min(ny, math.floor((max(a1, b1) + r - y0) / cell - 0.5) + 1)
        dx, dy = b0 - a0, b1 - a1
        length2 = dx * dx + dy * dy
        far = r * r
        for i in range(i0, i1):
            px = (x0 + (i + 0.5) * cell) - a0
            for j in range(j0, j1):
                if heights[i, j] <= top:
                    continue
                py = (y0 + (j + 0.5) * cell) - a1
                qx, qy = px, py
                if length2 > 1e-18:
                    t = (px * dx + py * dy) / length2
                    t = min(max(t, 0.0), 1.0)
                    qx, qy = px - t * dx, py - t * dy
                if qx * qx + qy * qy <= far:
                    heights[i, j] = top
