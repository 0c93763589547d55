"""The in-process stock of a workplan: how high the material can still be, anywhere, after the
operations made so far (work mm).

Approach and retract moves ask it where the material is, so a rapid stops APPROACH_GAP above
what is really left instead of above the level the workingstep assumes (finishing before its
roughing, a hole at the bottom of a pocket not cut yet, any order the workplan list allows).

It is a grid of columns, each holding an *upper bound* of the material's height anywhere in its
square: a move lowers a column only when the whole square lies within the tool's reach
(distance to the move <= R - cell * sqrt(2) / 2, arcs less their chord error), and only to the
height the tool's rim reaches there (the tip plus the tool's rise at its full radius: the corner
radius, a drill's point) and the higher end of the move.  So :meth:`top_under` never says less
material than there is; it may say more (narrow grooves a tool leaves between its strokes, the
rim of every cut), which only makes an approach start higher.
"""
from __future__ import annotations

import math

import numpy as np

from ...engines import compiled
from ...ir.program import ARC_CCW, ARC_CW, RAPID, arc_sweep
from .errors import StepNcError

# Columns this wide (mm); a grid of more than MAX_COLUMNS columns is made coarser.
CELL = 0.25
MAX_COLUMNS = 2_000_000
# Arcs are followed by chords this close (mm) to them.
ARC_CHORD = 0.005


class InProcessStock:
    """Material heights over the box x0..x1, y0..y1 starting at ``top``.  Outside the box the
    material is ``outside`` (None: nothing there, the box is the stock; a number: unknown stock
    that high).  ``kernel``: how the columns are lowered, "numba" (compiled, :mod:`.inprocess_kernel`),
    "numpy" (a segment at a time, the reference) or "auto" (numba where it can be imported); both
    give the same heights."""

    def __init__(self, x0, y0, x1, y1, top: float, outside: float | None = None, cell: float = CELL,
                 kernel: str = "auto"):
        self.kernel = compiled.kernel_module(kernel, f"{__package__}.inprocess_kernel", StepNcError,
                                             "in-process stock kernel")
        area = max(x1 - x0, cell) * max(y1 - y0, cell)
        cell = max(cell, math.sqrt(area / MAX_COLUMNS))
        self.cell = cell
        self.x0, self.y0 = float(x0), float(y0)
        self.nx = max(1, math.ceil((x1 - x0) / cell))
        self.ny = max(1, math.ceil((y1 - y0) / cell))
        self.top = float(top)
        self.outside = outside
        self.heights = np.full((self.nx, self.ny), self.top)
        self.margin = cell * math.sqrt(0.5)   # from a column's centre to its corners
        self.pending: list = []               # operations cut but not drawn yet (drawn when asked)

    def _centres(self, lo: float, hi: float, origin: float, count: int) -> tuple:
        """Index range [i0, i1) of the columns whose centres lie in [lo, hi] along one axis."""
        i0 = max(0, math.ceil((lo - origin) / self.cell - 0.5))
        i1 = min(count, math.floor((hi - origin) / self.cell - 0.5) + 1)
        return i0, i1

    def top_under(self, x: float, y: float, radius: float) -> float:
        """The highest the material can be anywhere under a disc of ``radius`` at (x, y)."""
        self._draw()
        reach = radius + self.margin
        i0, i1 = self._centres(x - reach, x + reach, self.x0, self.nx)
        j0, j1 = self._centres(y - reach, y + reach, self.y0, self.ny)
        best = -math.inf
        if i1 > i0 and j1 > j0:
            cx = self.x0 + (np.arange(i0, i1) + 0.5) * self.cell
            cy = self.y0 + (np.arange(j0, j1) + 0.5) * self.cell
            inside = (cx[:, None] - x) ** 2 + (cy[None, :] - y) ** 2 <= reach * reach
            if inside.any():
                best = float(self.heights[i0:i1, j0:j1][inside].max())
        if self.outside is not None:
            grid_x1, grid_y1 = self.x0 + self.nx * self.cell, self.y0 + self.ny * self.cell
            if x - radius < self.x0 or y - radius < self.y0 or x + radius > grid_x1 or y + radius > grid_y1:
                best = max(best, self.outside)
        return best

    def highest(self) -> float:
        """The highest the material can be anywhere."""
        self._draw()
        return max(float(self.heights.max()), -math.inf if self.outside is None else self.outside)

    def cut(self, operation) -> None:
        """Take away what the operation's cutting moves clear (drawn when next asked)."""
        self.pending.append(operation)

    def _draw(self) -> None:
        while self.pending:
            self._draw_operation(self.pending.pop(0))

    def _draw_operation(self, operation) -> None:
        """Lower the columns the operation's cutting moves clear.  A path repeated layer after
        layer is drawn once, at its lowest layer."""
        tool = operation.tool
        rise = float(tool.shape.height_at(tool.radius))
        starts = operation.start_points()
        arcs = (operation.kind == ARC_CW) | (operation.kind == ARC_CCW)
        lines = np.flatnonzero((operation.kind != RAPID) & ~arcs)
        a, b = starts[lines], operation.xyz[lines]
        # rows: ax, ay, bx, by, z (the higher end), reach
        segments = [np.column_stack([a[:, :2], b[:, :2], np.maximum(a[:, 2], b[:, 2]),
                                     np.full(len(lines), tool.radius)])]
        for k in np.flatnonzero(arcs):
            points, chord = _arc_points(starts[k], operation.xyz[k], operation.center[k],
                                        operation.kind[k] == ARC_CW)
            segments.append(np.column_stack([points[:-1, :2], points[1:, :2],
                                             np.maximum(points[:-1, 2], points[1:, 2]),
                                             np.full(len(points) - 1, tool.radius - chord)]))
        rows = np.vstack(segments)
        if not len(rows):
            return
        rows = rows[np.lexsort((rows[:, 4], *np.round(rows[:, [5, 3, 2, 1, 0]], 6).T))]
        keys = np.round(rows[:, [0, 1, 2, 3, 5]], 6)
        first = np.ones(len(rows), bool)
        first[1:] = np.any(keys[1:] != keys[:-1], axis=1)
        rows = rows[first]
        if self.kernel is not None:
            z, reach = rows[:, 4] + rise, rows[:, 5] - self.margin
            live = reach > 0
            ax, ay, bx, by = (np.ascontiguousarray(rows[live, k]) for k in range(4))
            self.kernel.lower(self.heights, self.x0, self.y0, self.cell, ax, ay, bx, by, z[live], reach[live])
            return
        for ax, ay, bx, by, z, reach in rows:
            self._segment((ax, ay), (bx, by), z + rise, reach)

    def _segment(self, a, b, z: float, radius: float) -> None:
        """Columns whose squares lie within ``radius`` of the XY segment a-b go down to z."""
        reach = radius - self.margin
        if reach <= 0:
            return
        i0, i1 = self._centres(min(a[0], b[0]) - reach, max(a[0], b[0]) + reach, self.x0, self.nx)
        j0, j1 = self._centres(min(a[1], b[1]) - reach, max(a[1], b[1]) + reach, self.y0, self.ny)
        if i1 <= i0 or j1 <= j0:
            return
        block = self.heights[i0:i1, j0:j1]
        if block.max() <= z:
            return
        cx = self.x0 + (np.arange(i0, i1) + 0.5) * self.cell
        cy = self.y0 + (np.arange(j0, j1) + 0.5) * self.cell
        px, py = cx[:, None] - a[0], cy[None, :] - a[1]
        dx, dy = b[0] - a[0], b[1] - a[1]
        length2 = dx * dx + dy * dy
        if length2 > 1e-18:
            t = np.clip((px * dx + py * dy) / length2, 0.0, 1.0)
            px, py = px - t * dx, py - t * dy
        covered = px * px + py * py <= reach * reach
        block[covered & (block > z)] = z


def _arc_points(a, b, centre, clockwise: bool) -> tuple:
    """Points along an XY arc from a to b (Z linear), and the chords' largest distance from it."""
    ca = np.asarray(a[:2]) - centre[:2]
    r = float(np.hypot(*ca))
    sweep = float(arc_sweep(np.array([a[:2]]), np.array([b[:2]]), np.array([centre[:2]]), np.array([clockwise]))[0])
    step = 2 * math.acos(max(-1.0, 1 - ARC_CHORD / r)) if r > ARC_CHORD else math.pi / 2
    count = max(2, math.ceil(abs(sweep) / step) + 1)
    angles = math.atan2(ca[1], ca[0]) + np.linspace(0, sweep, count)
    points = np.column_stack([centre[0] + r * np.cos(angles), centre[1] + r * np.sin(angles),
                              np.linspace(a[2], b[2], count)])
    chord = r * (1 - math.cos(abs(sweep) / (count - 1) / 2))
    return points, chord
