"""Headless preview pictures (Workbench): the stock and the toolpaths, seen from above.

Wire meshes do not render, so each toolpath preview is copied into a temporary curve with a
small bevel for the picture and removed afterwards; the scene is left as it was.
"""
from __future__ import annotations

import math

import bpy
import numpy as np
from mathutils import Vector

from .convert import mm_per_unit


def _wire_to_curve(obj, radius_units: float):
    """A bevelled curve through the edges of a wire mesh (consecutive-vertex runs)."""
    mesh = obj.data
    count = len(mesh.vertices)
    co = np.empty(count * 3)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3) @ np.array(obj.matrix_world)[:3, :3].T + np.array(obj.matrix_world)[:3, 3]
    edges = np.empty(len(mesh.edges) * 2, dtype=np.int64)
    mesh.edges.foreach_get("vertices", edges)
    edges = edges.reshape(-1, 2)
    curve = bpy.data.curves.new(obj.name + " (render)", type="CURVE")
    curve.dimensions = "3D"
    curve.bevel_depth = radius_units
    curve.bevel_resolution = 1
    # Edges were made along runs of consecutive vertices: a gap in the numbering starts a new run.
    if len(edges):
        breaks = np.flatnonzero(edges[1:, 0] != edges[:-1, 1]) + 1
        for run in np.split(edges, breaks):
            indices = np.append(run[:, 0], run[-1, 1])
            spline = curve.splines.new("POLY")
            spline.points.add(len(indices) - 1)
            pts = np.hstack([co[indices], np.ones((len(indices), 1))])
            spline.points.foreach_set("co", pts.ravel())
    render_obj = bpy.data.objects.new(curve.name, curve)
    render_obj.color = obj.color
    return render_obj


def render_preview(scene, solids, wires, path: str, resolution=(1200, 800), tube_mm: float = 0.35,
                   see_through: bool = True):
    """Render ``solids`` (meshes shown as they are) and ``wires`` (toolpath previews) to ``path``.

    ``see_through`` renders the solids half transparent, so toolpaths below the stock's top
    (all of them, before simulation) stay visible."""
    unit = 1.0 / mm_per_unit(scene)
    temp_collection = bpy.data.collections.new("Kezuri preview render")
    scene.collection.children.link(temp_collection)
    temporary = [_wire_to_curve(obj, tube_mm * unit) for obj in wires]
    for obj in temporary:
        temp_collection.objects.link(obj)
    shown = set(solids) | set(temporary)
    hidden = [o for o in scene.objects if o not in shown and not o.hide_render]
    for obj in hidden:
        obj.hide_render = True
    camera_data = bpy.data.cameras.new("Kezuri preview camera")
    camera = bpy.data.objects.new("Kezuri preview camera", camera_data)
    temp_collection.objects.link(camera)
    previous_camera = scene.camera
    try:
        corners = [obj.matrix_world @ Vector(c) for obj in shown for c in obj.bound_box]
        lo = Vector((min(c.x for c in corners), min(c.y for c in corners), min(c.z for c in corners)))
        hi = Vector((max(c.x for c in corners), max(c.y for c in corners), max(c.z for c in corners)))
        centre = (lo + hi) / 2
        size = max(hi.x - lo.x, (hi.y - lo.y) * resolution[0] / resolution[1], 1e-6)
        tilt = math.radians(35)
        distance = size * 2
        camera.location = centre + Vector((0, -math.sin(tilt) * distance, math.cos(tilt) * distance))
        camera.rotation_euler = (tilt, 0, 0)
        camera_data.type = "ORTHO"
        camera_data.ortho_scale = size * 1.08
        camera_data.clip_end = distance * 4
        scene.camera = camera
        render = scene.render
        render.engine = "BLENDER_WORKBENCH"
        render.resolution_x, render.resolution_y = resolution
        render.resolution_percentage = 100
        render.image_settings.file_format = "PNG"
        render.filepath = path
        shading = scene.display.shading
        shading.light = "STUDIO"
        shading.color_type = "OBJECT"
        shading.show_cavity = True
        shading.show_xray = see_through
        shading.xray_alpha = 0.55
        bpy.ops.render.render(write_still=True)
    finally:
        scene.camera = previous_camera
        for obj in hidden:
            obj.hide_render = False
        for obj in temporary + [camera]:
            data = obj.data
            bpy.data.objects.remove(obj, do_unlink=True)
            if isinstance(data, bpy.types.Curve):
                bpy.data.curves.remove(data)
            elif isinstance(data, bpy.types.Camera):
                bpy.data.cameras.remove(data)
        bpy.data.collections.remove(temp_collection)
    return path
