"""W1: plan and bake the full built-in name-plate job (core only, letters taken from Blender once)."""
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


def run():
    from kezuri.toolpath import engrave

    plate, letters = sample_inputs()
    result = engrave.plan(plate, letters)
    baked, depths = engrave.bake(result.program)
    moves = sum(len(op) for op in baked.operations)
    seconds = best_of(5, lambda: engrave.bake(engrave.plan(plate, letters).program))
    return [{"name": "engrave: sample name plate, plan + bake (200 x 100 mm)", "seconds": seconds,
             "target_s": 0.2, "notes": f"{moves} moves, {len(depths)} gouges; best of 5, one core"}]
