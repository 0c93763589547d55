"""The picture rasteriser's scan conversion compiled with numba (the numpy path in
:func:`.picture.rasterise` is the reference and the fallback without numba).

One pass over the triangles in order, row by row, pixel by pixel, with the same arithmetic as
the numpy path; a pixel keeps its nearest fragment, and of fragments tied for nearest the last
triangle's, which is the one the numpy path's colouring leaves on top."""
from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def scan(fx, fy, fz, live, width, height, nearest, owner):
    """Fill ``nearest`` (flat depth buffer, -inf = empty) and ``owner`` (face index, -1) from
    the (f, 3) projected corners of the ``live`` triangles."""
    for f in range(fx.shape[0]):
        if not live[f]:
            continue
        x0, x1, x2 = fx[f, 0], fx[f, 1], fx[f, 2]
        y0, y1, y2 = fy[f, 0], fy[f, 1], fy[f, 2]
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        dz1, dz2 = fz[f, 1] - fz[f, 0], fz[f, 2] - fz[f, 0]
        dx1, dx2, dy1, dy2 = x1 - x0, x2 - x0, y1 - y0, y2 - y0
        gx, gy = (dz1 * dy2 - dz2 * dy1) / area, (dz2 * dx1 - dz1 * dx2) / area
        j0 = int(min(max(math.ceil(min(y0, y1, y2) - 0.5), 0.0), float(height)))
        j1 = int(min(max(math.floor(max(y0, y1, y2) - 0.5), -1.0), float(height - 1)))
        for row in range(j0, j1 + 1):
            centre = row + 0.5
            left, right = np.inf, -np.inf
            for e in range(3):
                p, q = e, (e + 1) % 3
                yp, yq, xp, xq = fy[f, p], fy[f, q], fx[f, p], fx[f, q]
                lo, hi = min(yp, yq), max(yp, yq)
                if centre >= lo and centre <= hi and hi > lo:
                    at = xp + (centre - yp) * (xq - xp) / (yq - yp)
                    left, right = min(left, at), max(right, at)
            i0 = int(min(max(math.ceil(left - 0.5), 0.0), float(width))) if left < np.inf else width
            i1 = int(min(max(math.floor(right - 0.5), -1.0), float(width - 1))) if right > -np.inf else -1
            for column in range(i0, i1 + 1):
                depth = fz[f, 0] + gx * (column + 0.5 - x0) + gy * (centre - y0)
                k = row * width + column
                if depth >= nearest[k]:
                    nearest[k] = depth
                    owner[k] = f
