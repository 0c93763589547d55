"""Toolpath preview objects in the viewport, in the batch pictures' colours per move kind.

Each operation's path is cut where its move kind changes (cut, plunge, link, rapid:
:func:`..toolpath.pictures.picture_jobs.role_paths`) and shown as one curve object per operation
and kind, in the legend's colour (:mod:`..toolpath.pictures.legend`, the table the pictures
read): through one material per kind, made once and reused, for Blender's default Solid shading
(Color: Material), and as the object's colour for Color: Object.  The scene's Show Rapids
switch (:func:`show_rapids`) hides or shows the rapid objects of every workflow's preview
without planning again.
"""
from __future__ import annotations

import bpy

from ..toolpath.pictures import legend, picture_jobs
from ..toolpath.simulate.stock import as_stock
from . import convert

KIND = "kezuri_move_kind"       # the custom property naming a preview object's move kind
SUFFIXES = {"cut": "", "plunge": " plunges", "link": " links", "rapid": " rapids"}   # of the objects' names


def material_name(kind: str) -> str:
    return f"Kezuri {kind}"


def kind_material(kind: str):
    """The material of move kind ``kind``: the one of its name if there is one, else a new one;
    its viewport colour (and its surface's base colour, for Material Preview) the legend's."""
    colour = legend.linear_rgba(kind)
    material = bpy.data.materials.get(material_name(kind))
    if material is None:
        material = bpy.data.materials.new(material_name(kind))
    material.diffuse_color = colour
    for node in material.node_tree.nodes if material.node_tree is not None else ():
        if node.type == "BSDF_PRINCIPLED":
            node.inputs["Base Color"].default_value = colour
    return material


def show_toolpaths(scene, prefix: str, operations, stock, frame, tube_mm: float = 0.3, names=None) -> list:
    """One curve object per operation of ``operations`` and move kind, named "<prefix> <name>"
    for the cuts and "<prefix> <name> plunges / links / rapids" for the others (``names``: one
    per operation, default the operations' names), in the work ``frame``.  ``stock``: what the
    moves are classified against (a stock, a turn-mill bar or six numbers).  The rapid objects
    are hidden while the scene's Show Rapids is off."""
    stock = as_stock(stock)
    hide_rapids = not scene.kezuri.show_rapids
    objects = []
    for op, name in zip(operations, names or [op.name for op in operations]):
        runs = {}
        for role, points in picture_jobs.role_paths(op, stock):
            runs.setdefault(legend.ROLES[role], []).append(points)
        for kind in legend.ROLES:
            if kind not in runs:
                continue
            obj = convert.polyline_object(scene, f"{prefix} {name}{SUFFIXES[kind]}", runs[kind], frame,
                                          legend.linear_rgba(kind), tube_mm)
            obj.data.materials.append(kind_material(kind))
            obj[KIND] = kind
            obj.hide_viewport = hide_rapids and kind == "rapid"
            objects.append(obj)
    return objects


def show_rapids(settings, context=None):
    """The scene's Show Rapids: hide or show every preview's rapid objects (nothing is planned)."""
    for obj in bpy.data.objects:
        if obj.get(KIND) == "rapid":
            obj.hide_viewport = not settings.show_rapids
