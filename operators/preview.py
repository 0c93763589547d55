"""Batch pictures, drawn by the core's software rasteriser (:mod:`..toolpath.pictures.picture_jobs`) from
the toolpaths and the simulation's result: no renderer starts, the scene is only read.

Each picture is written through :func:`..post.output.write_atomic`: a failed write leaves no
half-written PNG.
"""
from __future__ import annotations

import numpy as np

from ..post.output import write_atomic
from ..toolpath.pictures import picture_jobs
from . import convert

SIZE = (1200, 800)
SIDE_VIEW_DEG = 72.0     # a turned bar (axis Z) seen from the side, a little from above


def object_solid(obj, frame, depsgraph=None, colour=picture_jobs.PART_COLOUR) -> tuple:
    """(vertices in work mm, triangles, colour) of a Blender object's evaluated mesh, read with
    bulk array calls (``foreach_get`` on its loop triangles)."""
    import bpy

    depsgraph = depsgraph or bpy.context.evaluated_depsgraph_get()
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        if mesh is None:
            return np.zeros((0, 3)), np.zeros((0, 3), np.int64), colour
        mesh.calc_loop_triangles()
        co = np.empty(len(mesh.vertices) * 3)
        mesh.vertices.foreach_get("co", co)
        triangles = np.empty(len(mesh.loop_triangles) * 3, np.int32)
        mesh.loop_triangles.foreach_get("vertices", triangles)
    finally:
        evaluated.to_mesh_clear()
    matrix = np.array(obj.matrix_world)
    world = convert.placed(co, matrix)
    return frame.to_work(world), triangles.reshape(-1, 3).astype(np.int64), colour


def toolpath_png(path: str, operations, stock, solids=(), title: str = "", tilt_deg: float = 35.0,
                 caption: str = "", marks=(), highlights=()) -> str:
    """The toolpaths (cut, plunge, link, rapid) over ``solids`` ([(vertices mm, faces, rgb)]);
    ``caption``: a line under the title (what was not cut); ``marks``: places left uncut,
    [(x, y, z, label)]; ``highlights``: [(vertices, faces, rgb, legend label)] drawn over the
    solids, each in the legend."""
    return write_atomic(path, toolpath_bytes(operations, stock, solids, title, tilt_deg, caption, marks, highlights))


def toolpath_bytes(operations, stock, solids=(), title: str = "", tilt_deg: float = 35.0,
                   caption: str = "", marks=(), highlights=()) -> bytes:
    """:func:`toolpath_png`'s picture as PNG bytes, in memory (a panel export's setup sheet draws
    it on the export's worker: the core's rasteriser only, no Blender data)."""
    picture = picture_jobs.toolpath_picture(list(operations), stock, list(solids), title, SIZE, tilt_deg,
                                            caption=caption, marks=marks, highlights=list(highlights))
    return picture.png()


def simulation_png(path: str, result, title: str = "", tilt_deg: float = 35.0, mesh=None, marks=()) -> str:
    """The simulated stock coloured by depth over the job's own depth range (``mesh``: the
    stock's (vertices, faces) if already built; ``marks``: places left uncut)."""
    return write_atomic(path, simulation_bytes(result, title, tilt_deg, mesh, marks))


def simulation_bytes(result, title: str = "", tilt_deg: float = 35.0, mesh=None, marks=()) -> bytes:
    """:func:`simulation_png`'s picture as PNG bytes, in memory."""
    return picture_jobs.simulation_picture(result, title, SIZE, tilt_deg, mesh=mesh, marks=marks).png()


def sheet_png(path: str, patterns, title: str = "") -> str:
    """Flat patterns from above: filled faces, dashed bend lines, cut contours."""
    return write_atomic(path, sheet_bytes(patterns, title))


def sheet_bytes(patterns, title: str = "") -> bytes:
    """:func:`sheet_png`'s picture as PNG bytes, in memory."""
    return picture_jobs.sheet_picture(patterns, title, SIZE).png()
