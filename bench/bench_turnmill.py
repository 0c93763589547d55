"""W4: classification rays per second on a 100k-face mesh, 4 samples per face, each engine."""
from __future__ import annotations

import time

import numpy as np


def run():
    import trimesh

    from kezuri.toolpath import turnmill

    sphere = trimesh.creation.icosphere(subdivisions=6, radius=40.0)       # 81,920 faces
    box = trimesh.creation.box((30, 30, 30))
    box.apply_translation((0, 0, 60))
    mesh = trimesh.util.concatenate([sphere, box])                          # a shadow above the sphere
    vertices, faces = np.asarray(mesh.vertices), np.asarray(mesh.faces)
    triangles = vertices[faces]
    # 4 samples per face: the centroid and the midpoints towards each corner.
    centroid = triangles.mean(axis=1)
    samples = np.vstack([centroid] + [(centroid + triangles[:, k]) / 2 for k in range(3)])
    directions = samples.copy()
    directions[:, 2] = 0.0
    directions /= np.maximum(np.linalg.norm(directions, axis=1, keepdims=True), 1e-12)
    origins = samples + directions * 1e-4
    rows = []
    engines = [("trimesh", turnmill.TrimeshRayEngine(vertices, faces))]
    try:
        from kezuri.operators.turnmill import BVHRayEngine
        engines.append(("Blender BVH", BVHRayEngine(vertices, faces)))
    except ImportError:
        pass
    for name, engine in engines:
        started = time.perf_counter()
        engine.intersects_any(origins[:100], directions[:100])      # builds the acceleration structure
        build = time.perf_counter() - started
        started = time.perf_counter()
        engine.intersects_any(origins, directions)
        seconds = time.perf_counter() - started
        backend = getattr(engine, "backend", name)
        rows.append({"name": f"turnmill: {len(origins) / 1e3:.0f}k rays on {len(faces) / 1e3:.0f}k faces, {name}",
                     "seconds": seconds, "notes": f"{len(origins) / seconds / 1e6:.2f} M rays/s ({backend}), "
                                                   f"after {build:.2f} s building; target 1 M rays/s with embreex"})
    return rows
