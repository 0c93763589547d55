"""W1: plan and bake the full built-in name-plate job (core only, letters taken from Blender once); the
gate's letter fill over a big sign, scan lines beside the per-cell test it replaced."""
from __future__ import annotations

from timing import best_of



def sample_inputs():
    import bpy

    import kezuri
    from kezuri.operators import convert, samples
    if not hasattr(bpy.types.Scene, "kezuri"):
        kezuri.register()
    scene = bpy.context.scene
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    plate_obj, letters_obj = samples.name_plate(scene)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    plate = convert.plate_from_object(plate_obj, depsgraph, scene)
    letters = [(letters_obj.name, convert.outlines_in_work(letters_obj, depsgraph, plate.frame))]
    return plate.outline, letters


def plan_rows():
    from kezuri.toolpath.operations.engrave import engrave

    plate, letters = sample_inputs()
    result = engrave.plan(plate, letters)
    baked, depths = engrave.bake(result.program)
    moves = sum(len(op) for op in baked.operations)
    seconds = best_of(5, lambda: engrave.bake(engrave.plan(plate, letters).program))
    return [{"name": "engrave: sample name plate, plan + bake (200 x 100 mm)", "seconds": seconds,
             "target_s": 0.2, "notes": f"{moves} moves, {len(depths)} gouges; best of 5, one core"}]


def sign_fill_rows(scale: float = 4.0, cell: float = 0.1):
    """The export gate's design heights over a big sign: which grid cells lie inside the letters.
    Scan lines (``region.grid_inside``, what the gate uses) and the point-in-polygon test of every
    cell (``region.contains_points`` over a meshgrid, what it used before), side by side on the
    same grid; CPU seconds and peak memory (tracemalloc sees numpy's arrays)."""
    import time
    import tracemalloc

    import numpy as np

    from kezuri.toolpath.engines import region

    _, letters = sample_inputs()
    loops = [np.asarray(loop, float) * scale for _, object_loops in letters for loop in object_loops]
    area = region.from_loops(loops, "letters")
    x0, y0, x1, y1 = area.bounds()
    xs = np.arange(-100 * scale + cell / 2, 100 * scale, cell)
    ys = np.arange(-50 * scale + cell / 2, 50 * scale, cell)
    xs, ys = xs[(xs >= x0) & (xs <= x1)], ys[(ys >= y0) & (ys <= y1)]

    def scan():
        return region.grid_inside(area, xs, ys)

    def per_point():
        gx, gy = np.meshgrid(xs, ys, indexing="ij")
        return region.contains_points(area, np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape)

    rows, masks = [], []
    for label, work in (("scan lines", scan), ("point in polygon per cell (before)", per_point)):
        tracemalloc.start()
        started = time.process_time()
        masks.append(work())
        seconds = time.process_time() - started
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        rows.append({"name": f"engrave gate: letters of a {200 * scale:g} x {100 * scale:g} mm sign at {cell} mm, "
                             f"{label}", "seconds": seconds,
                     "notes": f"{len(xs) * len(ys) / 1e6:.1f} M cells, peak {peak / 1e9:.2f} GB, CPU s"})
    rows[0]["notes"] += "; same cells as before: " + ("yes" if (masks[0] == masks[1]).all() else "NO")
    return rows


def run():
    return plan_rows() + sign_fill_rows()
