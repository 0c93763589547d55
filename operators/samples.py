"""Built-in sample parts, built in the scene, for the demo, batch runs and tests."""
from __future__ import annotations

import bpy


def clear_scene(scene):
    """Remove every object and put the scene's Kezuri settings back to their defaults."""
    for obj in list(scene.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for curve in [c for c in bpy.data.curves if c.users == 0]:
        bpy.data.curves.remove(curve)
    for collection in list(scene.collection.children):
        bpy.data.collections.remove(collection)
    settings = scene.kezuri
    groups = [getattr(settings, p.identifier) for p in settings.bl_rna.properties
              if p.type == "POINTER" and p.identifier != "rna_type"]
    for group in groups:
        for prop in group.bl_rna.properties:
            if prop.identifier != "rna_type":
                group.property_unset(prop.identifier)


def set_millimetres(scene):
    scene.unit_settings.system = "METRIC"
    scene.unit_settings.scale_length = 0.001
    scene.unit_settings.length_unit = "MILLIMETERS"


def box_mesh(name: str, x0, y0, z0, x1, y1, z1):
    verts = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
             (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    return mesh


def name_plate(scene, word: str = "Kezuri", unit_mm: float = 1.0):
    """A 200 x 100 x 20 mm plate (top at Z = 0) with ``word`` in Blender's default font.

    ``unit_mm`` is how many millimetres one Blender unit is: 1.0 for a millimetre scene,
    1000.0 for a metre scene; the geometry is the same physical size either way.
    """
    s = 1.0 / unit_mm
    plate = bpy.data.objects.new("Plate", box_mesh("Plate", -100 * s, -50 * s, -20 * s, 100 * s, 50 * s, 0.0))
    plate.color = (0.85, 0.72, 0.52, 1.0)
    scene.collection.objects.link(plate)
    curve = bpy.data.curves.new("Letters", type="FONT")
    curve.body = word
    curve.size = 48 * s
    curve.align_x = "CENTER"
    curve.align_y = "CENTER"
    letters = bpy.data.objects.new("Letters", curve)
    letters.location.z = 0.05 * s  # just above the plate top, so the viewport shows it cleanly
    letters.color = (0.3, 0.2, 0.1, 1.0)
    scene.collection.objects.link(letters)
    settings = scene.kezuri
    settings.stock.plate = plate
    settings.engrave.letters = letters
    return plate, letters


def name_plate_cut_out(scene, word: str = "Kezuri"):
    """The name plate with ``Outline``, a closed curve 190 x 90 mm with 8 mm round corners centred
    on the plate: the sign cut out of the 200 x 100 mm board (the job file nameplate-cut-out.toml)."""
    import numpy as np

    plate, letters = name_plate(scene, word)
    corners = ((87.0, 37.0, 0.0), (-87.0, 37.0, 0.5), (-87.0, -37.0, 1.0), (87.0, -37.0, 1.5))
    points = []
    for cx, cy, start in corners:
        angles = np.pi * (start + np.linspace(0.0, 0.5, 13))
        points += [(cx + 8.0 * np.cos(a), cy + 8.0 * np.sin(a)) for a in angles]
    curve = bpy.data.curves.new("Outline", type="CURVE")
    spline = curve.splines.new("POLY")
    spline.points.add(len(points) - 1)
    spline.points.foreach_set("co", np.array([(x, y, 0.05, 1.0) for x, y in points]).ravel())
    spline.use_cyclic_u = True
    outline = bpy.data.objects.new("Outline", curve)
    scene.collection.objects.link(outline)
    return plate, letters, outline


def rotary_block(scene):
    """The paper's bento block: 105 x 105 x 30 mm (top at Z = 0, centred on the rotation axis)
    with three non-circular pockets as closed curves: slanted walls, vertical walls, a bowl."""
    import numpy as np

    from ..toolpath.operations.rotary import rotary

    block, pockets = rotary.sample_job()
    hx, hy = block.size_x / 2, block.size_y / 2
    plate = bpy.data.objects.new("Block", box_mesh("Block", -hx, -hy, -block.thickness, hx, hy, 0.0))
    plate.color = (0.85, 0.72, 0.52, 1.0)
    scene.collection.objects.link(plate)
    scene.kezuri.stock.plate = plate
    objects = []
    for pocket in pockets:
        curve = bpy.data.curves.new(pocket.name, type="CURVE")
        spline = curve.splines.new("POLY")
        outline = np.asarray(pocket.outline, float)
        spline.points.add(len(outline) - 1)
        spline.points.foreach_set("co", np.column_stack([outline, np.full(len(outline), 0.05),
                                                         np.ones(len(outline))]).ravel())
        spline.use_cyclic_u = True
        obj = bpy.data.objects.new(pocket.name, curve)
        scene.collection.objects.link(obj)
        props = obj.kezuri_pocket
        props.enabled, props.depth, props.wall_angle, props.bottom = True, pocket.depth, pocket.wall_angle_deg, \
            pocket.bottom
        if pocket.sphere_radius:
            props.sphere_radius = pocket.sphere_radius
        objects.append(obj)
    return plate, objects


def turnmill_part(scene):
    """An 85 mm chemical-wood bar, 60 mm long (end face at Z = 0), with a flat and a groove on its
    side and two pockets in its end face, one of them exactly 20 mm wide."""
    from ..toolpath.operations.turnmill import turnmill

    vertices, faces, stock = turnmill.sample_part()
    mesh = bpy.data.meshes.new("Turned part")
    mesh.from_pydata(vertices.tolist(), [], faces.tolist())
    mesh.update()
    part = bpy.data.objects.new("Turned part", mesh)
    part.color = (0.85, 0.72, 0.52, 1.0)
    scene.collection.objects.link(part)
    props = scene.kezuri.turnmill
    props.part = part
    props.stock_radius, props.stock_z_min, props.stock_z_max = stock.radius, stock.z_min, stock.z_max
    return part


# The built-in scenes a job file may start from ([setup] sample = ...)
SCENES = {"name_plate": name_plate, "name_plate_cut_out": name_plate_cut_out, "rotary_block": rotary_block,
          "turnmill_part": turnmill_part}
