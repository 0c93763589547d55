"""Designs from drawing programs (SVG, DXF) in the shell: File > Import > "Kezuri design", the CAM
tab's import button, the batch options ``--svg FILE`` / ``--dxf FILE`` (``--layer``, ``--scale``)
the operation kinds' shorthands take, and a job file's ``design = "logo.svg"``.

The readers are the core's (:mod:`..toolpath.engines.svgfile`, :mod:`..toolpath.engines.dxffile`);
here a design becomes Blender curve objects: one per layer, POLY splines in Blender units (the
scene's unit scale), cyclic for the closed loops, a 2-D curve filled like a Text object so a
workflow reads it as a region; the open paths of a layer go into an object of their own, named
"... (open)".  In batch, :func:`design_loops` gives the closed loops in mm without a scene.
"""
from __future__ import annotations

import math
import os

import bpy
import numpy as np
from bpy.props import FloatProperty, StringProperty
from bpy_extras.io_utils import ImportHelper

from ..toolpath.engines import dxffile, svgfile
from ..toolpath.engines.designshapes import Design, DesignFileError
from ..toolpath.engines.textfile import named
from . import convert
from .common import run_reported
from .translations import translate_message

READERS = {".svg": "--svg", ".dxf": "--dxf"}


def read_design(path: str, option: str | None = None, scale: float | None = None, shown: str | None = None) -> Design:
    """The drawing file, read by its kind (``option``: "--svg" or "--dxf"; default: by its
    extension); ``scale``: mm per drawing unit of a DXF without units.  An error in the file
    names it as the user gave it (``shown``; default: ``option path``, or the path): the readers
    name the file by its base name before the line and element."""
    kind = option or READERS.get(os.path.splitext(path)[1].lower())
    if kind is None:
        raise DesignFileError(f"{shown or path}: not a design file: give an .svg or .dxf file")
    if kind == "--svg" and scale is not None:
        raise DesignFileError(f"--scale {scale:g}: a scale is for a DXF file without units; an SVG gives its size")
    try:
        return svgfile.read_svg(path) if kind == "--svg" else dxffile.read_dxf(path, scale=scale)
    except DesignFileError as error:
        message = str(error)
        for name in (path, os.path.basename(path)):          # the reader's name for the file, replaced
            if message.startswith(f"{name}: "):
                message = message[len(name) + 2:]
                break
        raise DesignFileError(named(shown or (f"{option} {path}" if option else path), message)) from None


def by_layer(design: Design, layers=None) -> list:
    """[(layer, shapes)] of the layers asked for (None: every layer), in the file's order; a layer
    the file does not have is an error naming the ones it has."""
    present = design.layers()
    for layer in layers or ():
        if layer not in present:
            shown = ", ".join(repr(name) for name in present if name) or "none"
            raise DesignFileError(f"{os.path.basename(design.path)}: no layer {layer!r}; its layers are {shown}")
    wanted = [name for name in present if layers is None or name in layers]
    return [(name, [s for s in design.shapes if s.layer == name]) for name in wanted]


def object_name(path: str, layer: str) -> str:
    stem = os.path.splitext(os.path.basename(path))[0]
    return f"{stem} {layer}" if layer else stem


# ----- batch ----------------------------------------------------------------------------------------

def design_arguments(parser) -> None:
    """The design options of a batch command: ``--svg FILE`` or ``--dxf FILE``, ``--layer NAME``
    (repeatable; default every layer) and ``--scale`` (mm per unit of a DXF without units)."""
    from .batchio import number

    source = parser.add_mutually_exclusive_group()
    source.add_argument("--svg", metavar="FILE", help="the design: an SVG drawing (Inkscape, Illustrator ...)")
    source.add_argument("--dxf", metavar="FILE", help="the design: an ASCII DXF drawing (R12, R2000 ...)")
    parser.add_argument("--layer", action="append", metavar="NAME",
                        help="only this layer of the design (repeat for several; default: every layer)")
    parser.add_argument("--scale", type=number("--scale", 0.0, None, lo_open=True, unit="mm"),
                        help="mm per drawing unit of a DXF file without units (default 1)")


def design_of(args) -> Design:
    """The design the options name."""
    if getattr(args, "svg", None):
        return read_design(args.svg, "--svg", getattr(args, "scale", None))
    if getattr(args, "dxf", None):
        return read_design(args.dxf, "--dxf", getattr(args, "scale", None))
    raise DesignFileError("no design: give --svg FILE or --dxf FILE")


def design_loops(args) -> list:
    """[(name, closed loops as (k, 2) arrays in mm)] of the design the options name, one entry per
    layer that has closed loops (named "file layer", or "file" outside layers)."""
    design = design_of(args)
    found = [(object_name(design.path, layer), [s.points for s in shapes if s.closed])
             for layer, shapes in by_layer(design, getattr(args, "layer", None))]
    found = [(name, loops) for name, loops in found if loops]
    if not found:
        raise DesignFileError(f"{os.path.basename(design.path)}: no closed outline in the layers asked for")
    return found


# ----- scene ----------------------------------------------------------------------------------------

def curve_object(collection, name: str, shapes: list, mm_per_unit: float, at=(0.0, 0.0)):
    """A curve object of the shapes: POLY splines in Blender units, cyclic where closed; a 2-D
    curve filled like a Text when every shape is closed."""
    curve = bpy.data.curves.new(name, type="CURVE")
    closed = all(s.closed for s in shapes)
    curve.dimensions = "2D" if closed else "3D"
    if closed:
        curve.fill_mode = "BOTH"
    for shape in shapes:
        points = np.asarray(shape.points, float) / mm_per_unit
        spline = curve.splines.new("POLY")
        spline.points.add(len(points) - 1)
        co = np.column_stack([points, np.zeros(len(points)), np.ones(len(points))])
        spline.points.foreach_set("co", co.ravel())
        spline.use_cyclic_u = shape.closed
    obj = bpy.data.objects.new(name, curve)
    obj.location = (at[0] / mm_per_unit, at[1] / mm_per_unit, 0.0)
    collection.objects.link(obj)
    return obj


def design_objects(scene, design: Design, collection=None, layers=None, at=(0.0, 0.0)) -> list:
    """Curve objects of the design in the scene (``collection``, default the scene's own), one per
    layer and one more per layer with open paths; ``at``: where the file's origin goes (mm)."""
    collection = collection or scene.collection
    mm = convert.mm_per_unit(scene)
    made = []
    for layer, shapes in by_layer(design, layers):
        name = object_name(design.path, layer)
        closed, opened = [s for s in shapes if s.closed], [s for s in shapes if not s.closed]
        if closed:
            made.append(curve_object(collection, name, closed, mm, at))
        if opened:
            made.append(curve_object(collection, f"{name} (open)", opened, mm, at))
    return made


def job_design(scene, value, where: str, base_dir: str) -> list:
    """A job file's ``design`` key: ``"logo.svg"`` or ``{ file = "logo.dxf", layer = "Cut", scale = 1.0,
    at = [x, y] }`` (beside the job file): the design's curve objects, made in the scene."""
    from .jobentry import JobFileError

    table = {"file": value} if isinstance(value, str) else value
    if not isinstance(table, dict) or not isinstance(table.get("file"), str):
        raise JobFileError(f'{where}: design must be a file name ("logo.svg") or a table with file = "..."')
    unknown = sorted(set(table) - {"file", "layer", "scale", "at"})
    if unknown:
        raise JobFileError(f"{where}: design.{unknown[0]} is not a key of a design; they are file, layer, scale, at")
    layer, scale, at = table.get("layer"), table.get("scale"), table.get("at", [0.0, 0.0])
    if layer is not None and not isinstance(layer, str):
        raise JobFileError(f"{where}: design.layer must be a layer's name")
    if scale is not None and (isinstance(scale, bool) or not isinstance(scale, (int, float))):
        raise JobFileError(f"{where}: design.scale = {scale!r} is not a number")
    if not (isinstance(at, list) and len(at) == 2 and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                          and math.isfinite(v) for v in at)):
        raise JobFileError(f"{where}: design.at = {at!r} is not [x, y] in mm")
    path = os.path.join(base_dir, table["file"])
    try:
        design = read_design(path, None, None if scale is None else float(scale), f"design.file = {table['file']!r}")
        return design_objects(scene, design, layers=None if layer is None else [layer], at=tuple(map(float, at)))
    except DesignFileError as error:
        raise JobFileError(named(where, str(error))) from None


class KEZURI_OT_import_design(bpy.types.Operator, ImportHelper):
    """Import an SVG or DXF drawing as curves (one object per layer, in mm at the scene's unit scale)"""

    bl_idname = "kezuri.import_design"
    bl_label = "Import Design"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".svg"
    filter_glob: StringProperty(default="*.svg;*.dxf;*.SVG;*.DXF", options={"HIDDEN"})
    scale: FloatProperty(name="DXF Scale", default=1.0, soft_min=0.001, soft_max=1000.0,
                         description="Millimetres per drawing unit of a DXF file without units "
                                     "(a file that gives its units is read in them)")

    def execute(self, context):
        def work():
            if not (math.isfinite(self.scale) and self.scale > 0):
                raise DesignFileError(f"DXF Scale = {self.scale:g}: give a positive number of mm per drawing unit")
            scale = None if self.scale == 1.0 or not self.filepath.lower().endswith(".dxf") else float(self.scale)
            design = read_design(self.filepath, None, scale)
            made = design_objects(context.scene, design, context.collection)
            for obj in context.selected_objects:
                obj.select_set(False)
            for obj in made:
                obj.select_set(True)
            if made:
                context.view_layer.objects.active = made[0]
            for note in design.notes[:5]:
                self.report({"WARNING"}, translate_message(note))
            loops = sum(s.closed for s in design.shapes)
            self.report({"INFO"}, translate_message(
                f"Imported {loops} closed and {len(design.shapes) - loops} open path(s) from "
                f"{os.path.basename(self.filepath)}"))
            return {"FINISHED"}
        return run_reported(self, work)


def menu_import(self, context):
    self.layout.operator(KEZURI_OT_import_design.bl_idname, text="Kezuri design (.svg/.dxf)")


CLASSES = (KEZURI_OT_import_design,)
MENUS = ((bpy.types.TOPBAR_MT_file_import, menu_import),)
