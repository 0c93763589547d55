"""A triangle mesh's upper envelope over the height field's grid: the highest point of the mesh
above each cell centre.  The design's heights for the gouge check (checks.py), a curved plate's
top (heightfield.py) and the scallop a carving left (operations/carve) are read this way."""
from __future__ import annotations

import numpy as np

from .families import halfline
from .stock import HeightField

ITEM_BATCH = 2048         # triangles per numpy batch when rasterising a mesh


def mesh_top(hf: HeightField, vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Upper envelope of a triangle mesh over the grid (a z-buffer seen from above), a new
    (nx, ny) array; cell centres on a triangle's edge belong to neither side (-inf there: nothing
    to check)."""
    top = np.full(hf.shape, -np.inf)
    flat = top.reshape(-1)
    nx, ny = hf.shape
    tri = vertices[faces]
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    area2 = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    keep = np.abs(area2) > 1e-12
    tri, area2 = tri[keep], area2[keep]
    for start in range(0, len(tri), ITEM_BATCH):
        t = tri[start:start + ITEM_BATCH]
        sign = np.sign(area2[start:start + ITEM_BATCH])
        c0 = np.clip(np.ceil((t[:, :, 0].min(1) - hf.x0) / hf.cell_x - 0.5), 0, nx).astype(np.int64)
        c1 = np.clip(np.floor((t[:, :, 0].max(1) - hf.x0) / hf.cell_x - 0.5), -1, nx - 1).astype(np.int64)
        ncol = np.maximum(c1 - c0 + 1, 0)
        k = np.repeat(np.arange(len(t)), ncol)
        col = np.arange(len(k)) - np.repeat(np.cumsum(ncol) - ncol, ncol) + c0[k]
        x = hf.x0 + (col + 0.5) * hf.cell_x
        lo = np.full(len(k), -np.inf)
        hi = np.full(len(k), np.inf)
        for e in range(3):
            # per triangle, then per column (the same numbers as gathering the corners per column)
            px, py = t[:, e, 0], t[:, e, 1]
            ex, ey = t[:, (e + 1) % 3, 0] - px, t[:, (e + 1) % 3, 1] - py
            # inside: sign * cross(q - p, X - p) >= 0, linear in y
            # Shrunk by a hair: a cell centre on a vertical wall's top edge is not held to the
            # top of the wall (it may as well be the floor's), and is left unchecked.
            e_lo, e_hi = halfline(sign[k] * (ex[k] * (-py[k]) - ey[k] * (x - px[k])) - 1e-7, (sign * ex)[k])
            lo, hi = np.maximum(lo, e_lo), np.minimum(hi, e_hi)
        r0 = np.clip(np.ceil((lo - hf.y0) / hf.cell_y - 0.5), 0, ny).astype(np.int64)
        r1 = np.clip(np.floor((hi - hf.y0) / hf.cell_y - 0.5), -1, ny - 1).astype(np.int64)
        cnt = np.maximum(r1 - r0 + 1, 0)
        total = int(cnt.sum())
        if not total:
            continue
        j = np.arange(total) - np.repeat(np.cumsum(cnt) - cnt, cnt)
        row = np.repeat(r0, cnt) + j
        ke = np.repeat(k, cnt)
        xe = np.repeat(x, cnt)
        ye = hf.y0 + (row + 0.5) * hf.cell_y
        # z on the triangle's plane (its normal once per triangle, then per cell centre)
        normal = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        p0 = t[:, 0]
        n0, n1, n2 = (np.ascontiguousarray(normal[:, axis]) for axis in range(3))
        x0, y0, z0 = (np.ascontiguousarray(p0[:, axis]) for axis in range(3))
        z = z0[ke] - (n0[ke] * (xe - x0[ke]) + n1[ke] * (ye - y0[ke])) / n2[ke]
        np.maximum.at(flat, np.repeat(col, cnt) * ny + row, z)
    return top
