"""Headless preview pictures (Workbench): the stock and the toolpaths, seen from above.

The camera is temporary and objects not in the picture are hidden only while it renders: the
scene is left as it was.
"""
from __future__ import annotations

import math

import bpy
from mathutils import Vector

from ..post.output import atomic_path


def render_preview(scene, solids, paths, path: str, resolution=(1200, 800), see_through: bool = True,
                   color_type: str = "OBJECT"):
    """Render ``solids`` (stock, parts) and ``paths`` (toolpath curves) to ``path`` (PNG).

    ``see_through`` renders the solids half transparent, so toolpaths below the stock's top
    (all of them, before simulation) stay visible.  The picture is rendered to a temporary file
    beside ``path`` and renamed (:func:`..post.output.atomic_path`): a failed render leaves no
    half-written PNG."""
    temp_collection = bpy.data.collections.new("Kezuri preview render")
    scene.collection.children.link(temp_collection)
    shown = set(solids) | set(paths)
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
        shading = scene.display.shading
        shading.light = "STUDIO"
        shading.color_type = color_type      # "VERTEX": the colour attribute (simulated stock by depth)
        shading.show_cavity = True
        shading.show_xray = see_through
        shading.xray_alpha = 0.55
        with atomic_path(path) as temp:
            render.filepath = temp
            bpy.ops.render.render(write_still=True)
    finally:
        scene.camera = previous_camera
        for obj in hidden:
            obj.hide_render = False
        bpy.data.objects.remove(camera, do_unlink=True)
        bpy.data.cameras.remove(camera_data)
        bpy.data.collections.remove(temp_collection)
    return path
