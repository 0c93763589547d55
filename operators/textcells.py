"""The characters of a Text object one by one, in work mm, where they stand in the text.

Blender gives a Text object's outline as one mesh; which face belongs to which character is
told by giving every character its own material slot in a copy of the text (its per-character
format keeps the place of each glyph: alignment, kerning and lines are those of the original),
so the faces come out numbered by character (``material_index``).  The copy is removed again.
"""
from __future__ import annotations

import bpy
import numpy as np

from ..toolpath.engines import region
from . import convert

MAX_CHARACTERS = 200        # a longer text is a paragraph, not a name on a plate: not split
AREA_AGREEMENT = 0.01       # the characters together must cover the object's outline within 1 %


def character_outlines(obj, depsgraph, frame, letter_loops) -> list:
    """[(character, index in the text, (loop, ...)), ...] of a Text object ``obj`` in work mm, or
    [] when it is not a Text, too long, or its characters do not add up to ``letter_loops`` (the
    object's outline as planned: a modifier changed it, for one)."""
    if obj.type != "FONT" or not obj.data.body.strip() or len(obj.data.body) > MAX_CHARACTERS:
        return []
    local, faces, materials = character_faces(obj.data)
    world = convert.placed(local, np.array(obj.evaluated_get(depsgraph).matrix_world))
    found = outlines_by_character(obj.data.body, frame.to_work(world)[:, :2], faces, materials, obj.name)
    if not found or not _agrees(found, letter_loops):
        return []
    return found


def character_faces(data) -> tuple:
    """A Text's curve data as a mesh whose faces are numbered by character: (vertices (n, 3) in
    the curve's own coordinates, faces (vertex index lists), each face's material index, the
    character's place in the body + 1)."""
    body = data.body
    data = data.copy()
    try:
        data.materials.clear()
        for _ in range(len(body) + 1):
            data.materials.append(None)
        for index, character_format in enumerate(data.body_format):
            character_format.material_index = index + 1
        temp = bpy.data.objects.new("Kezuri characters", data)
        try:
            mesh = temp.to_mesh()
            count = len(mesh.vertices)
            local = np.empty(count * 3)
            mesh.vertices.foreach_get("co", local)
            materials = np.empty(len(mesh.polygons), dtype=np.int64)
            mesh.polygons.foreach_get("material_index", materials)
            faces = [list(p.vertices) for p in mesh.polygons]
        finally:
            temp.to_mesh_clear()
            bpy.data.objects.remove(temp)
    finally:
        bpy.data.curves.remove(data)
    return local.reshape(count, 3), faces, materials


def outlines_by_character(body: str, points, faces, materials, name: str) -> list:
    """[(character, index, (loop, ...)), ...] from :func:`character_faces`' faces (``points``:
    their vertices in work mm, (n, 2)); [] when they cannot be told apart."""
    found = []
    try:
        for slot in sorted(set(np.asarray(materials).tolist()) - {0}):
            index = slot - 1
            if index >= len(body):
                return []
            shape = region.union_of_faces([points[faces[k]] for k in np.nonzero(materials == slot)[0]],
                                          f"character {index + 1} of {name!r}")
            found.append((body[index], index, tuple(region.loops(shape))))
    except region.RegionError:         # a glyph of no area: the characters are not told apart, nothing fails
        return []
    return found


def _agrees(found, letter_loops) -> bool:
    whole = region.from_loops(list(letter_loops), "letters")
    parts = region.from_loops([loop for _, _, loops in found for loop in loops], "characters")
    differ = (whole - parts).area() + (parts - whole).area()
    return differ <= AREA_AGREEMENT * whole.area()
