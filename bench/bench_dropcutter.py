"""Drop cutter: a 20,480-face sphere (radius 40 mm), a 6 mm ball, a 420 x 420 grid at 0.2 mm,
our kernels side by side with OpenCAMLib's BatchDropCutter on the same triangles and points.

OpenCAMLib is bench-only (``pip install -r bench/requirements.txt``); without it the row says
so and the heights are compared with the numpy path instead.  Seconds are wall time; the notes
give CPU seconds (all threads: OpenCAMLib runs OpenMP threads), the issue's measure.
``KEZURI_BENCH_OCL_STRIDE=k`` runs OpenCAMLib on every k-th grid point only (its time is then
scaled up) when the full grid is too slow for the machine.
"""
from __future__ import annotations

import os
import time

import numpy as np

RADIUS, TOOL_DIAMETER, CELL, N = 40.0, 6.0, 0.2, 420
FLOOR = -100.0


def _sphere():
    import trimesh

    sphere = trimesh.creation.icosphere(subdivisions=5, radius=RADIUS)
    return np.asarray(sphere.vertices, float), np.asarray(sphere.faces, np.int64)


def _timed(work):
    wall, cpu = time.perf_counter(), time.process_time()
    value = work()
    return value, time.perf_counter() - wall, time.process_time() - cpu


def _ocl_child(path):
    """In a process of its own (OpenCAMLib's OpenMP and numba's threads crash when they share
    one): drop the cutter on the points saved in ``path`` and save the heights and times."""
    import opencamlib as ocl

    data = np.load(path)
    surface = ocl.STLSurf()
    for tri in data["vertices"][data["faces"]]:
        surface.addTriangle(ocl.Triangle(*[ocl.Point(*map(float, p)) for p in tri]))
    batch = ocl.BatchDropCutter()
    batch.setSTL(surface)
    cutter = ocl.BallCutter(TOOL_DIAMETER, 50.0)     # kept alive: OpenCAMLib holds only a pointer to it
    batch.setCutter(cutter)
    for x, y in data["xy"]:
        batch.appendPoint(ocl.CLPoint(float(x), float(y), FLOOR))
    _, wall, cpu = _timed(batch.run)
    np.savez(path, z=np.array([p.z for p in batch.getCLPoints()]), times=np.array([wall, cpu]))


def _ocl(vertices, faces, xy):
    import subprocess
    import sys
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "points.npz")
        np.savez(path, vertices=vertices, faces=faces, xy=xy)
        subprocess.run([sys.executable, os.path.abspath(__file__), path], check=True)
        done = np.load(path)
        return done["z"], float(done["times"][0]), float(done["times"][1])


def run():
    from kezuri.toolpath.engines import dropcutter as dc
    from kezuri.toolpath.ir.program import Tool

    vertices, faces = _sphere()
    tool = Tool(1, "ball", TOOL_DIAMETER)
    x = (np.arange(N) + 0.5) * CELL - N * CELL / 2
    gx, gy = np.meshgrid(x, x, indexing="ij")
    xy = np.column_stack([gx.ravel(), gy.ravel()])

    def ours(kernel, points=xy):
        return dc.DropCutter(vertices, faces, tool, floor=FLOOR, kernel=kernel).points(points)

    ours("numba")                                   # compile (or load the cache) once
    runs = [_timed(lambda: ours("numba")) for _ in range(3)]
    z, wall, cpu = min(runs, key=lambda r: r[1])
    cpu = min(r[2] for r in runs)
    rows = [{"name": "dropcutter: 20,480-face sphere, 6 mm ball, 420 x 420 at 0.2 mm (numba)", "seconds": wall,
             "target_s": None, "cpu_s": cpu, "notes": f"{cpu:.2f} s CPU, build included"}]
    stride = 7
    z_np, wall_np, cpu_np = _timed(lambda: ours("numpy", xy[::stride]))
    agree_np = float(np.max(np.abs(z_np - z[::stride])))
    rows.append({"name": "dropcutter: the same (numpy path)", "seconds": wall_np * stride, "target_s": None,
                 "cpu_s": cpu_np * stride,
                 "notes": f"every {stride}th point timed, x{stride}; max |dz| vs numba {agree_np:.1e} mm"})
    try:
        import opencamlib  # noqa: F401
    except ImportError:
        rows.append({"name": "dropcutter: OpenCAMLib BatchDropCutter", "seconds": float("nan"),
                     "notes": "opencamlib not installed (pip install -r bench/requirements.txt)"})
        return rows
    ocl_stride = int(os.environ.get("KEZURI_BENCH_OCL_STRIDE", "1"))
    z_ocl, wall_ocl, cpu_ocl = _ocl(vertices, faces, xy[::ocl_stride])
    wall_ocl *= ocl_stride
    cpu_ocl *= ocl_stride
    diff = float(np.max(np.abs(z_ocl - z[::ocl_stride])))
    rows.append({"name": "dropcutter: OpenCAMLib 2023.1.11 BatchDropCutter, the same", "seconds": wall_ocl,
                 "target_s": None, "cpu_s": cpu_ocl,
                 "notes": (f"{cpu_ocl:.1f} s CPU; ours {cpu_ocl / cpu:.0f}x less CPU, {wall_ocl / wall:.0f}x less "
                           f"wall; max |dz| {diff:.1e} mm (target 1e-3 mm, 100x)"
                           + (f"; every {ocl_stride}th point, scaled" if ocl_stride > 1 else ""))})
    return rows


if __name__ == "__main__":
    import sys

    _ocl_child(sys.argv[1])
