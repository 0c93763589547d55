"""W6: material-removal simulation on a finishing raster (200 x 100 mm, 6 mm ball, 100k moves).

Rows: the height field engine at 0.1 and 0.05 mm cells, with the compiled (numba) kernel and,
beside it, the pure-numpy kernel it falls back to; the straightforward exact numpy method
(every move's capsule evaluated over its bounding box) timed on a subset and scaled; the
manifold engine on the first 1k and 10k moves of the same raster.  The targets (issue #7) are
for the default kernel, numba; its compile time is not counted (a warm-up run comes first,
and numba caches the compiled kernels on disk).
"""
from __future__ import annotations

import time

import numpy as np

from timing import best_of

STOCK = (0.0, 0.0, -20.0, 200.0, 100.0, 0.0)


def raster(moves: int = 100_000, seed: int = 0):
    """A zigzag finishing pass over a smooth random surface: rows along X every 0.5 mm,
    points every 0.4 mm, Z from a sum of seeded sinusoids (about -5..-1 mm)."""
    from kezuri.toolpath.ir.program import FEED, Operation, Tool

    rng = np.random.default_rng(seed)
    rows = 200
    per_row = moves // rows
    xs = np.linspace(0.0, 200.0, per_row)
    waves = [(rng.uniform(0.2, 0.6), rng.uniform(0.05, 0.3), rng.uniform(0.05, 0.3), rng.uniform(0, 2 * np.pi))
             for _ in range(4)]
    points = []
    for row, y in enumerate(np.linspace(0.0, 100.0, rows)):
        x = xs if row % 2 == 0 else xs[::-1]
        z = -3.0 + sum(a * np.sin(kx * x + ky * y + phase) for a, kx, ky, phase in waves)
        points.append(np.column_stack([x, np.full_like(x, y), z]))
    points = np.vstack(points)
    n = len(points)
    return Operation("raster", Tool(1, "ball", 6.0), 12000, np.full(n, FEED), points, np.full(n, 2000.0),
                     start=np.array([0.0, 0.0, 5.0]))


def first_moves(op, n: int):
    return op.replace(kind=op.kind[:n], xyz=op.xyz[:n], feed=op.feed[:n], center=op.center[:n])


def naive_exact(op, cell: float) -> np.ndarray:
    """The straightforward exact method: for each move, the ball's capsule (both end spheres
    and the cylinder between them) over the move's bounding box, min'ed into the grid."""
    x0, y0, _, x1, y1, top = STOCK
    nx, ny = int(round((x1 - x0) / cell)), int(round((y1 - y0) / cell))
    heights = np.full((nx, ny), top)
    xs = x0 + (np.arange(nx) + 0.5) * cell
    ys = y0 + (np.arange(ny) + 0.5) * cell
    r = op.tool.radius
    for a, b in zip(op.start_points(), op.xyz):
        i0, i1 = np.searchsorted(xs, [min(a[0], b[0]) - r, max(a[0], b[0]) + r])
        j0, j1 = np.searchsorted(ys, [min(a[1], b[1]) - r, max(a[1], b[1]) + r])
        px = xs[i0:i1, None] - a[0]
        py = ys[None, j0:j1] - a[1]
        d = b - a
        lowest = np.full((i1 - i0, j1 - j0), np.inf)
        for cx, cy, cz in ((0.0, 0.0, a[2]), (d[0], d[1], b[2])):
            w = r * r - (px - cx) ** 2 - (py - cy) ** 2
            lowest = np.minimum(lowest, np.where(w >= 0, cz + r - np.sqrt(np.maximum(w, 0)), np.inf))
        l2 = d[0] ** 2 + d[1] ** 2
        if l2 > 1e-12:
            l = np.sqrt(l2)
            big = np.linalg.norm(d)
            q = (px * d[0] + py * d[1]) / l
            e2 = px ** 2 + py ** 2 - q ** 2
            rho = np.sqrt(np.maximum(r * r - e2, 0))
            foot = q - rho * d[2] / big
            cylinder = a[2] + r + q * d[2] / l - rho * big / l
            lowest = np.minimum(lowest, np.where((e2 <= r * r) & (foot >= 0) & (foot <= l), cylinder, np.inf))
        heights[i0:i1, j0:j1] = np.minimum(heights[i0:i1, j0:j1], lowest)
    return heights


def run():
    from kezuri.toolpath import simulate as sim
    from kezuri.toolpath.simulate import sweep
    from kezuri.toolpath.ir.program import Tool

    op = raster()
    rows = []
    for kernel in ("numba", "numpy"):
        sim.simulate(first_moves(op, 2000), STOCK, cell=0.5, kernel=kernel)      # warm up (and compile)
    for cell, target in ((0.1, 0.5), (0.05, 1.5)):
        for kernel, repeats, what in (("numba", 5, "compiled kernel (numba), one thread"),
                                      ("numpy", 2, "pure numpy kernel (the fallback), one thread")):
            seconds = best_of(repeats, lambda: sim.simulate(op, STOCK, cell=cell, kernel=kernel))
            rows.append({"name": f"simulate: height field ({kernel}), 100k moves, {cell} mm cells",
                         "seconds": seconds, "target_s": target if kernel == "numba" else None,
                         "notes": f"exact ball envelope, {what}; best of {repeats}"})
    for tool, what in ((Tool(4, "vbit", 6.0), "90 degree V-bit: the cone's flank and rim, exact"),
                       (Tool(7, "bull", 6.0, corner_radius=1.0),
                        "bull nose 6 mm, corner 1 mm; no level moves here: its torus a ring of spheres")):
        shaped = op.replace(tool=tool)
        sim.simulate(first_moves(shaped, 2000), STOCK, cell=0.5)                  # warm up (and compile)
        seconds = best_of(3, lambda: sim.simulate(shaped, STOCK, cell=0.1))
        rows.append({"name": f"simulate: height field (numba), 100k moves, 0.1 mm cells, {tool.kind}",
                     "seconds": seconds, "target_s": None, "notes": f"{what}; best of 3"})
    subset = 5000
    part = first_moves(op, subset)
    seconds = best_of(1, lambda: naive_exact(part, 0.1)) * len(op) / subset
    rows.append({"name": "simulate: naive exact numpy per move, 100k moves, 0.1 mm (scaled)", "seconds": seconds,
                 "target_s": None, "notes": f"baseline; measured on the first {subset} moves, x{len(op) // subset}"})
    for moves in (1000, 10_000):
        part = first_moves(op, moves)
        started = time.perf_counter()
        result = sim.simulate(part, STOCK, engine="manifold", cell=0.5)
        seconds = time.perf_counter() - started
        rows.append({"name": f"simulate: manifold, {moves // 1000}k moves", "seconds": seconds, "target_s": None,
                     "notes": f"tolerance {result.tolerance} mm, runs swept as tubes (sweep.py), pieces subtracted "
                              f"every {sweep.CHUNK_TRIANGLES} triangles, {result.solid.num_tri()} triangles; "
                              "includes the 0.5 mm height-field safety pass"})
    return rows
