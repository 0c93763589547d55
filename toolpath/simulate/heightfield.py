"""The height field engine: the stock as a grid of columns, cut by the regions of
families.py chain by chain, with the compiled kernels (kernel.py) or numpy."""
from __future__ import annotations

import math

import numpy as np

from ..engines.compiled import kernel_module

from .families import Family, families_of, family_columns
from .meshtop import mesh_top
from .paths import Chain
from .stock import (MAX_CELLS, TOUCH_TOLERANCE, BoxStock, CylinderStock, HeightField, CellTooFine, SimulationCancelled, SimulationError)

_PAIR_BATCH = 32768        # (item, grid column) pairs per numpy batch
_CELL_CHUNK = 1 << 17      # cells per evaluation chunk, in reused buffers
_COMMON_RUNS = 1024        # runs of one length this many get a chunk without padding


def grid_of(stock, cell: float) -> tuple:
    """(x0, y0, x1, y1, nx, ny): the area the stock's height field covers and its columns of
    ``cell`` mm, counted without making any; more than :data:`MAX_CELLS` raises
    :class:`CellTooFine` (so a caller can refuse a cell before reading a long program)."""
    if isinstance(stock, BoxStock):
        x0, y0, x1, y1 = stock.x0, stock.y0, stock.x1, stock.y1
    else:
        x0 = y0 = -stock.radius
        x1 = y1 = stock.radius
    nx = max(1, math.ceil((x1 - x0) / cell - 1e-9))
    ny = max(1, math.ceil((y1 - y0) / cell - 1e-9))
    if nx * ny > MAX_CELLS:     # counts as :.4g: a 1e-300 mm cell gave a message of 600 digits
        raise CellTooFine(f"a {cell:g} mm cell gives {nx:.4g} x {ny:.4g} cells over the stock (more than "
                              f"{MAX_CELLS}); use a coarser cell")
    return x0, y0, x1, y1, nx, ny


def stock_grid(stock, cell: float) -> HeightField:
    """The uncut stock as a height field of ``cell`` mm columns (a curved plate's top read from its
    surface mesh; outside a bar's circle no material)."""
    x0, y0, x1, y1, nx, ny = grid_of(stock, cell)
    hf = HeightField(x0, y0, (x1 - x0) / nx, (y1 - y0) / ny, np.full((nx, ny), stock.top, np.float32),
                     np.ones((nx, ny), bool), stock.top, stock.bottom)
    if getattr(stock, "surface", None):
        vertices, faces = np.asarray(stock.surface[0], float), np.asarray(stock.surface[1], np.int64)
        top = mesh_top(hf, vertices, faces)
        gaps = ~np.isfinite(top)
        if gaps.any():      # cell centres on a triangle's edge: drop a point there
            from ..engines.dropcutter import DropCutter
            from ..ir.program import Tool

            gx, gy = np.meshgrid(hf.x(), hf.y(), indexing="ij")
            top[gaps] = DropCutter(vertices, faces, Tool(0, "flat", 0.002), bucket=1.0).points(
                np.column_stack([gx[gaps], gy[gaps]]))
        if not np.all(np.isfinite(top)):
            raise SimulationError("the stock's top surface does not cover the plate")
        hf.heights[:] = np.clip(top, stock.bottom, stock.top)
        object.__setattr__(hf, "initial", hf.heights.copy())
    if isinstance(stock, CylinderStock):
        hf.inside = np.hypot(hf.x()[:, None], hf.y()[None, :]) <= stock.radius
        hf.heights[~hf.inside] = -np.inf    # no material: nothing to cut or touch
    return hf


def compiled_kernels(kernel: str):
    """The compiled kernels module for ``kernel`` ("auto", "numba", "numpy"), or None for numpy
    (see :mod:`toolpath.engines.compiled`)."""
    return kernel_module(kernel, f"{__package__}.kernel", SimulationError, "numba kernel")


class _Scratch:
    """Buffers reused for every chunk of cells: fresh temporaries of this size would cost more
    in page faults than the arithmetic done in them."""

    def __init__(self):
        self.size = 0
        self.width = 0

    def views(self, width: int, runs: int):
        need = runs * width
        if need > self.size:
            self.size = max(need, _CELL_CHUNK)
            self.float = [np.empty(self.size, np.float32) for _ in range(2)]
            self.index = np.empty(self.size, np.int64)
            self.pad = np.empty(self.size, bool)
        if width > self.width:
            self.width = width
            self.j = np.arange(width)[:, None]
            self.jf = self.j.astype(np.float32)
        out, tmp = (f[:need].reshape(width, runs) for f in self.float)
        return out, tmp, self.index[:need].reshape(width, runs), self.pad[:need].reshape(width, runs)


def _cells(hf: HeightField, family: Family, scratch: _Scratch):
    """Yield (family batch, item index per run, cell index, values) for every cell of every
    item, chunk by chunk.

    A chunk is a block of column runs of one length (or padded to a multiple of 8) laid out
    run-minor, so per-run constants broadcast along contiguous rows.  Padding has value +inf
    and an index up to ``ny + 8`` past the run's start (possibly past the grid: index a buffer
    with that margin).  The arrays live in ``scratch`` and are overwritten by the next chunk."""
    ny = hf.shape[1]
    c0, ncol = family_columns(hf, family)
    items = np.flatnonzero(ncol)
    if not len(items):
        return
    # Batches of items with about _PAIR_BATCH (item, column) pairs each.
    cum = np.cumsum(ncol[items])
    cuts = np.searchsorted(cum, np.arange(_PAIR_BATCH, cum[-1], _PAIR_BATCH), side="right")
    for sel in np.split(items, cuts):
        if not len(sel):
            continue
        batch = family.take(sel)
        n = ncol[sel]
        k = np.repeat(np.arange(len(sel)), n)
        col = np.arange(len(k)) - np.repeat(np.cumsum(n) - n, n) + c0[sel][k]
        dx = hf.x0 + (col + 0.5) * hf.cell_x - batch.ox[k]
        oy = batch.oy[k]
        parts = []
        for lo, hi in batch.intervals(k, dx):
            r0 = np.clip(np.ceil((oy + lo - hf.y0) / hf.cell_y - 0.5), 0, ny).astype(np.int64)
            r1 = np.clip(np.floor((oy + hi - hf.y0) / hf.cell_y - 0.5), -1, ny - 1).astype(np.int64)
            count = r1 - r0 + 1
            use = count > 0
            parts.append((k[use], col[use], dx[use], r0[use], count[use], oy[use]))
        k, col, dx, r0, count, oy = (np.concatenate(p) for p in zip(*parts))
        if not len(k):
            continue
        start = col * ny + r0
        dy0 = hf.y0 + (r0 + 0.5) * hf.cell_y - oy
        # Runs of one length together; lengths that fewer than _COMMON_RUNS runs share are
        # padded to a multiple of 8 cells instead (a raster's bands mostly share a few lengths).
        lengths, runs_of = np.unique(count, return_counts=True)
        common = np.isin(count, lengths[runs_of >= _COMMON_RUNS])
        width = np.where(common, count, 8 * ((count + 7) // 8))
        for w in np.unique(width).tolist():
            group = np.flatnonzero(width == w)
            step = max(1, _CELL_CHUNK // w)
            for g in range(0, len(group), step):
                runs = group[g:g + step]
                out, tmp, index, pad = scratch.views(w, len(runs))
                batch.values(k[runs], dx[runs], dy0[runs], hf.cell_y, scratch.jf[:w], out, tmp)
                if count[runs].min() < w:
                    np.greater_equal(scratch.j[:w], count[runs][None, :], out=pad)
                    np.copyto(out, np.inf, where=pad)
                np.add(scratch.j[:w], start[runs][None, :], out=index)
                yield batch, k[runs], index.reshape(-1), out.reshape(-1)


def _runs(chain: Chain, families: list, longest: int = 5000):
    """Split the chain into runs of segments applied together (at most ``longest``, so progress
    is reported); every checked segment that reaches below the stock top is a run of its own,
    tested against the material before it is applied."""
    m = len(chain.move)
    reaching = np.zeros(m, bool)
    for fam in families:
        reaching[fam.segment] = True
    checked = np.flatnonzero(chain.checked & reaching)
    edges = np.unique(np.concatenate([np.arange(0, m, longest), [m], checked, checked + 1]))
    return [(int(a), int(b), bool(b - a == 1 and chain.checked[a] and reaching[a]))
            for a, b in zip(edges[:-1], edges[1:])]


class Simulation:
    """The height field engine: runs the chains in order and records what it finds.

    ``kernels``: the compiled kernels module, or None for the numpy kernel.  Checked moves
    always take the numpy path (they are few, and must be measured before they cut)."""

    def __init__(self, hf: HeightField, tolerance: float, progress=None, kernels=None):
        self.hf = hf
        self.tolerance = tolerance
        self.progress = progress
        self.kernels = kernels
        self.touches = []       # (chain, segment, depth, xy) of checked moves that met material
        self.scratch = _Scratch()

    def run(self, chains: list):
        nx, ny = self.hf.shape
        flat = np.full(nx * ny + ny + 8, np.inf, np.float32)    # margin for the runs' padding
        flat[:nx * ny] = self.hf.heights.reshape(-1)
        in_place = self.hf.heights.dtype == np.float32
        if in_place:        # the heights become a view of the buffer cut in: no second grid in memory
            self.hf.heights = flat[:nx * ny].reshape(nx, ny)
        total = sum(len(ch.move) for ch in chains) or 1
        done = 0
        operation = np.full(nx * ny, -1, np.int16)
        for chain in chains:
            rows = self._rows(chain)        # the grid rows the chain can lower: the rest is not copied
            before = flat[rows].copy()
            families = families_of(chain, self.hf.top, self.tolerance)
            for a, b, checked in _runs(chain, families):
                parts = [fam.take(slice(*np.searchsorted(fam.segment, [a, b]))) for fam in families]
                if checked:
                    self._checked(flat, chain, a, parts)
                elif self.kernels is not None:
                    for fam in parts:
                        fam.cut(self.kernels, flat, self.hf)
                else:
                    for fam in parts:
                        for _, _, index, values in _cells(self.hf, fam, self.scratch):
                            np.minimum.at(flat, index, values)
                done += b - a
                if self.progress is not None and self.progress(done / total) is False:
                    raise SimulationCancelled("simulation cancelled")
            operation[rows][flat[rows] < before] = chain.op_index
        if not in_place:
            self.hf.heights[...] = flat[:nx * ny].reshape(nx, ny)
        self.hf.operation = operation.reshape(nx, ny)

    def _rows(self, chain) -> slice:
        """The part of the flat grid (whole rows of constant x) within the tool's radius and two
        cells of the chain's points: all it can cut (every family lies within the radius of the
        tip's path); the whole grid for a radial tool or points that are not finite."""
        nx, ny = self.hf.shape
        x = chain.points[:, 0]
        if chain.radial or not len(x) or not np.isfinite(x).all():
            return slice(0, nx * ny)
        reach = float(chain.tool.radius)
        i0 = max(0, math.floor((float(x.min()) - reach - self.hf.x0) / self.hf.cell_x) - 2)
        i1 = min(nx, math.ceil((float(x.max()) + reach - self.hf.x0) / self.hf.cell_x) + 2)
        return slice(i0 * ny, max(i0, i1) * ny)

    def _checked(self, flat, chain, segment, families):
        """Apply one checked move, recording it if it reaches into the material as it is
        before the move."""
        cells = [(index.copy(), values.copy()) for fam in families
                 for _, _, index, values in _cells(self.hf, fam, self.scratch)]
        if not cells:
            return
        index = np.concatenate([c[0] for c in cells])
        values = np.concatenate([c[1] for c in cells])
        depth = flat[index] - values
        worst = int(np.argmax(depth))
        if depth[worst] > TOUCH_TOLERANCE:
            i, j = divmod(int(index[worst]), self.hf.shape[1])
            xy = (float(self.hf.x0 + (i + 0.5) * self.hf.cell_x), float(self.hf.y0 + (j + 0.5) * self.hf.cell_y))
            self.touches.append((chain, segment, float(depth[worst]), xy))
        np.minimum.at(flat, index, values)


def lowest_move(chains: list, hf: HeightField, i: int, j: int, tolerance: float):
    """(chain, segment, value) of the move that went lowest over cell (i, j)."""
    probe = HeightField(hf.x0 + i * hf.cell_x, hf.y0 + j * hf.cell_y, hf.cell_x, hf.cell_y,
                        np.zeros((1, 1), np.float32), np.ones((1, 1), bool), hf.top, hf.bottom)
    scratch = _Scratch()
    best = (None, -1, np.inf)
    for chain in chains:
        for fam in families_of(chain, hf.top, tolerance):
            for batch, k, index, values in _cells(probe, fam, scratch):
                w = int(np.argmin(values))
                if values[w] < best[2]:
                    best = (chain, int(batch.segment[k[w % len(k)]]), float(values[w]))
    return best
