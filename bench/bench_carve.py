"""Carving: the built-in wave relief (120 x 80 mm, 38k triangles), roughing + finishing at a
0.02 mm scallop (core only, numba drop cutter)."""
from __future__ import annotations

from timing import best_of


def run():
    from kezuri.toolpath.operations.carve import carve, carve_samples

    vertices, faces = carve_samples.wave_relief()
    result = carve.plan(vertices, faces)
    best = best_of(2, lambda: carve.plan(vertices, faces))
    moves = sum(len(op) for op in result.program.operations)
    return [{"name": "carve: wave relief, Z-level roughing + ball finishing at 0.02 mm scallop", "seconds": best,
             "target_s": None, "notes": f"{len(faces)} triangles, {moves} moves, stepover {result.stepover:.3f} mm"}]
