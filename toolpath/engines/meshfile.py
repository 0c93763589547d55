"""Mesh files (STL, OBJ, PLY) read into arrays: the one reader of every workflow that takes a mesh
file (carve's design, engraving's curved plate, the turn-mill part, the simulation's design).

:func:`read_mesh` loads the file with trimesh as the file says (``process=False``: trimesh's
processing would drop faces with a NaN corner and merge coordinates of 1e300 mm into one vertex,
hiding what is wrong), checks it, then merges the repeated corners an STL writes once per facet.
The file's numbers are taken as millimetres; a coordinate beyond :data:`~..ir.errors.MAX_REACH_MM`
is refused as a file in other units.  What a workflow needs of the shape beyond that (a closed
mesh, outward normals, a design that is not flat) it checks itself.  Every error is a
:class:`MeshFileError` naming the option and the file as the user typed them.
"""
from __future__ import annotations

import numpy as np

from ..ir.errors import MAX_REACH_MM, InputError
from .textfile import refusal


class MeshFileError(InputError):
    """A mesh file that cannot be used; the message names the option and the file."""


def read_mesh(path: str, option: str = "--mesh") -> tuple[np.ndarray, np.ndarray]:
    """(vertices (n, 3) float in mm, faces (m, 3) int64) of the mesh file ``path``, given as
    ``option`` (such as "--mesh"): the file exists and trimesh reads it as a mesh with triangles,
    every coordinate is finite and within MAX_REACH_MM of the origin, every face names vertices
    of the file; then coincident vertices are merged."""
    import trimesh

    problem = refusal(f"{option} {path}", path, "a mesh file")
    if problem:
        raise MeshFileError(problem)
    try:
        loaded = trimesh.load(path, force="mesh", process=False)
    except Exception as error:  # noqa: BLE001 - trimesh raises many kinds for a bad file
        raise MeshFileError(f"{option} {path}: not a readable mesh ({error})") from None
    vertices = np.asarray(getattr(loaded, "vertices", np.zeros((0, 3))), dtype=float)
    faces = np.asarray(getattr(loaded, "faces", np.zeros((0, 3))))
    if vertices.ndim != 2 or vertices.shape[1] != 3 or faces.ndim != 2 or faces.shape[1] != 3 or not len(faces):
        raise MeshFileError(f"{option} {path}: the mesh has no faces")
    if not np.all(np.isfinite(vertices)):
        raise MeshFileError(f"{option} {path}: the mesh has a non-finite vertex coordinate (NaN or infinity)")
    reach = float(np.abs(vertices).max())
    if reach > MAX_REACH_MM:      # merging would round such coordinates together; carve's raster never ended
        raise MeshFileError(f"{option} {path}: the mesh reaches {reach:g} mm from the origin (more than "
                            f"{MAX_REACH_MM:g} mm): is it in other units?")
    if not np.issubdtype(faces.dtype, np.integer) or faces.min() < 0 or faces.max() >= len(vertices):
        raise MeshFileError(f"{option} {path}: a face has a vertex index outside 0..{len(vertices) - 1}")
    merged = trimesh.Trimesh(vertices, faces, process=True)   # the STL's repeated corners, one vertex each
    vertices, faces = np.asarray(merged.vertices, dtype=float), np.asarray(merged.faces, dtype=np.int64)
    if not len(faces):
        raise MeshFileError(f"{option} {path}: the mesh has no faces")
    return vertices, faces
