"""W5 in Blender: twisted quads and pipe elbows unfolded, turret-punch NC, DXF and SVG.

The quad's corners live in ``scene.kezuri.sheet.corners`` (mm): typed in the panel, taken from a
selected quad face, or imported from a CADKEY .CDL file.  ``run_unfold`` and ``run_elbow``
(sheetjobs.py) are the job functions the operators, batch.py and the tests share.  The exports run
in steps (progress, Esc to cancel) and write all their files or none.
"""
from __future__ import annotations

import os
from types import SimpleNamespace

import bpy
import numpy as np
from bpy.props import BoolProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from ..toolpath.operations.sheetmetal import unfold as core
from ..toolpath.engines.textfile import named, read_text, refusal
from ..toolpath.ir.errors import InputError
from . import convert, gate
from .common import SteppedOperator, run_reported
from .exporting import SHEET_DESCRIPTION
from .limits import check_group
from .properties import ELBOW_SETTINGS, UNFOLD_SETTINGS, copies
from .sheetjobs import (ELBOW_NAMES, GAP_MM, POST_FAMILIES, UNFOLD_NAMES, UnfoldJob, check_pitch,
                        corners_mm, elbow_files, elbow_layout, elbow_punching, elbow_texts, parse_clamps,
                        placement_report, punch_gate, punch_profile, punch_report, punch_warnings, run_elbow,
                        run_unfold, share, unfold_files, unfold_texts, write_all)
from .translations import interface_language, translate_message
from .workflow import BatchCommand, Workflow

PREFIX = "Kezuri Sheet"
ELBOW_PREFIX = "Kezuri Elbow"
ALLOW_DESCRIPTION = ("Write the programs even if the punching simulation finds a part that stays in the sheet "
                     "or a hit biting into the part")


def _frame_beside(scene, part_max_x_mm: float, pattern_min_x_mm: float) -> convert.WorkFrame:
    """World placement of a flat pattern: to the right of the part, on the ground plane."""
    shift = part_max_x_mm + GAP_MM - pattern_min_x_mm
    return convert.WorkFrame(convert.mm_per_unit(scene), (shift, 0.0, 0.0))


def show_unfold(scene, job: UnfoldJob) -> list:
    convert.remove_objects(PREFIX)
    scale = convert.mm_per_unit(scene)
    pattern = job.quad.pattern
    world = convert.WorkFrame(scale, (0.0, 0.0, 0.0))
    part = convert.mesh_object(scene, f"{PREFIX} part (triangulated)", pattern.vertices_3d, pattern.triangles,
                               world, color=(0.7, 0.75, 0.8, 1.0))
    flat_frame = _frame_beside(scene, pattern.vertices_3d[:, 0].max(), job.contour[:, 0].min())
    flat = np.column_stack([pattern.vertices_2d, np.zeros(len(pattern.vertices_2d))])
    flat_obj = convert.mesh_object(scene, f"{PREFIX} flat pattern", flat, pattern.triangles, flat_frame,
                                   color=(0.85, 0.85, 0.9, 1.0))
    cut = np.column_stack([job.contour, np.zeros(len(job.contour))])
    cut_obj = convert.polyline_object(scene, f"{PREFIX} cut contour", [np.vstack([cut, cut[:1]])], flat_frame,
                                      color=(1.0, 0.3, 0.1, 1.0))
    # The punched sheet beside the flat pattern: the part that falls out, and the skeleton.
    # back from the sheet's coordinates to the pattern's along Y, so the part lines up with the flat pattern
    (x0, _, x1, _) = job.punched.sheet.bounds()
    shift_y = 0.0 if job.punching is None else -float(job.punching.offset[1])
    punched_frame = convert.WorkFrame(scale, (flat_frame.origin_mm[0] + float(job.contour[:, 0].max()) + GAP_MM - x0,
                                              shift_y, 0.0))
    thickness = float(scene.kezuri.sheet.thickness)
    pieces = []
    for name, region, colour in (("punched part", job.punched.part, (0.55, 0.75, 0.95, 1.0)),
                                 ("skeleton", job.punched.sheet - job.punched.part, (0.6, 0.6, 0.62, 1.0))):
        if region.area() > 0:
            mesh = region.extrude(thickness).translate((0.0, 0.0, -thickness)).to_mesh()
            pieces.append(convert.mesh_object(scene, f"{PREFIX} {name}", np.asarray(mesh.vert_properties)[:, :3],
                                              np.asarray(mesh.tri_verts), punched_frame, color=colour))
    return [part, flat_obj, cut_obj, *pieces]


def show_elbow(scene, elbow: core.Elbow) -> list:
    convert.remove_objects(ELBOW_PREFIX)
    scale = convert.mm_per_unit(scene)
    world = convert.WorkFrame(scale, (0.0, 0.0, 0.0))
    objects = []
    for piece in elbow.pieces:
        objects.append(convert.mesh_object(scene, f"{ELBOW_PREFIX} piece {piece.index + 1}", piece.vertices,
                                           piece.faces, world, color=(0.75, 0.78, 0.82, 1.0)))
    max_x = max(p.vertices[:, 0].max() for p in elbow.pieces)
    frame = _frame_beside(scene, max_x, 0.0)
    for piece, outline in zip(elbow.pieces, elbow_layout(elbow)):
        closed = np.column_stack([np.vstack([outline, outline[:1]]), np.zeros(len(outline) + 1)])
        objects.append(convert.polyline_object(scene, f"{ELBOW_PREFIX} pattern {piece.index + 1}", [closed], frame,
                                               color=(1.0, 0.3, 0.1, 1.0)))
    return objects


def quad_corners_from_object(obj, scene) -> np.ndarray:
    """World corners (mm) of the active mesh's selected quad face (or its only face)."""
    if obj is None or obj.type != "MESH":
        raise convert.SceneInputError("select a mesh object with a quad face (four straight edges)")
    mesh = obj.data
    faces = [p for p in mesh.polygons if p.select] or list(mesh.polygons)
    if len(faces) != 1 or len(faces[0].vertices) != 4:
        raise convert.SceneInputError(f"object {obj.name!r}: select exactly one quad face (found "
                                      f"{len(faces)} face(s), the first with {len(faces[0].vertices) if faces else 0} "
                                      "corners)")
    matrix = np.array(obj.matrix_world)
    local = np.array([mesh.vertices[i].co for i in faces[0].vertices], float)
    world = local @ matrix[:3, :3].T + matrix[:3, 3]
    return world * convert.mm_per_unit(scene)


class KEZURI_OT_unfold_quad(bpy.types.Operator):
    """Unfold the twisted quad by triangulation and lay the flat pattern beside it"""

    bl_idname = "kezuri.unfold_quad"
    bl_label = "Unfold Twisted Quad"
    bl_options = {"REGISTER", "UNDO"}
    __annotations__ = copies(UNFOLD_SETTINGS)   # the panel's settings, in the redo panel

    def invoke(self, context, event):
        sheet = context.scene.kezuri.sheet
        for name in UNFOLD_SETTINGS:
            setattr(self, name, getattr(sheet, name))
        return self.execute(context)

    def execute(self, context):
        def work():
            sheet = context.scene.kezuri.sheet
            check_group(self, "sheet", list(UNFOLD_SETTINGS))     # before the scene takes them
            for name in UNFOLD_SETTINGS:
                setattr(sheet, name, getattr(self, name))
            job = run_unfold(corners_mm(sheet), sheet)
            show_unfold(context.scene, job)
            for warning in punch_warnings([job.punched]):
                self.report({"WARNING"}, translate_message(warning))
            lengths = ", ".join(f"{v:.3f}" for v in job.quad.edge_lengths)
            self.report({"INFO"},
                        translate_message(f"Unfolded into {2 * job.quad.divisions} triangles; edges {lengths} mm"))
            return {"FINISHED"}
        return run_reported(self, work)


class KEZURI_OT_quad_from_selection(bpy.types.Operator):
    """Take the twisted quad's corners from the selected quad face of the active mesh"""

    bl_idname = "kezuri.quad_from_selection"
    bl_label = "Corners from Selected Face"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        if obj is None or obj.type != "MESH":
            cls.poll_message_set("Make a mesh with a quad face the active object")
            return False
        return True

    def execute(self, context):
        def work():
            if context.active_object.mode == "EDIT":
                context.active_object.update_from_editmode()
            corners = quad_corners_from_object(context.active_object, context.scene)
            context.scene.kezuri.sheet.corners = corners.ravel()
            self.report({"INFO"}, translate_message("Corners taken from the selected face"))
            return {"FINISHED"}
        return run_reported(self, work)


class KEZURI_OT_import_cdl(bpy.types.Operator, ImportHelper):
    """Import a twisted quad from a CADKEY CDL intermediate file (four LINE records)"""

    bl_idname = "kezuri.import_cdl"
    bl_label = "Import CADKEY CDL"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".cdl"
    filter_glob: StringProperty(default="*.cdl;*.CDL", options={"HIDDEN"})

    def execute(self, context):
        def work():
            corners = read_cdl_file(self.filepath)
            scene = context.scene
            scene.kezuri.sheet.corners = corners.ravel()
            convert.remove_objects(f"{PREFIX} imported quad")
            world = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
            convert.mesh_object(scene, f"{PREFIX} imported quad", corners, [[0, 1, 2, 3]], world,
                                color=(0.7, 0.75, 0.8, 1.0))
            self.report({"INFO"}, translate_message(f"Read the quad from {os.path.basename(self.filepath)}"))
            return {"FINISHED"}
        return run_reported(self, work)


def settings_of(props) -> SimpleNamespace:
    """A copy of the sheet settings' values (arrays as tuples), for work that runs away from the
    scene (an export in steps touches no Blender data)."""
    return SimpleNamespace(**{prop.identifier: (tuple(value) if getattr(prop, "is_array", False) else value)
                              for prop in props.bl_rna.properties if prop.identifier != "rna_type"
                              for value in [getattr(props, prop.identifier)]})


def export_work(first: str, punch, allow: bool, workflow: str, sheet_path: str, language: str | None):
    """``work(progress) -> [paths]`` of a sheet-metal export: ``punch(progress) -> (punched
    programs, texts(), placed jobs, picture() -> PNG bytes)`` (its progress the first 5-90 %), the
    gate over every program,
    then the texts made and, with a ``language`` ("en", "ja"; None: none), the setup sheet of the
    programs at ``sheet_path`` (as batch ``workflow``'s: the sheet, the gate, the programs), all
    written or none, after the last progress call (so Esc writes nothing)."""
    from .batchio import program_extensions, report_sheet
    from ..toolpath.pictures.setupsheet import program_file

    def work(progress=None) -> list:
        report = progress or (lambda fraction, text="": None)
        report(0.0, first)
        punched, texts, placed, picture = punch(share(progress, 0.05, 0.9))
        report(0.9, "checking")
        gate_report = punch_gate(punched, allow)
        made = texts()
        if language:
            programs = [program_file(os.path.basename(path), text.encode("ascii")) for path, text in made
                        if os.path.splitext(path)[1].lower() in program_extensions()]
            entries = {"workflow": workflow, "gate": gate_report, "sheet": placement_report(placed)}
            pictures = [("Result", picture())]      # batch's picture (its report's "preview")
            made.append((sheet_path, report_sheet(entries, language, programs, pictures).encode("utf-8")))
        report(1.0, "writing")
        return write_all(made)
    return work


def unfold_picture(job) -> bytes:
    """Batch ``unfold``'s picture (``unfold.png``) as PNG bytes: the flat pattern, its bend lines, the punch path."""
    from . import preview

    pattern = job.quad.pattern
    return preview.sheet_bytes([dict(outline=pattern.outline, bends=[(s[0], s[1]) for s in pattern.bend_lines()],
                                     contour=job.contour, name="FLAT PATTERN")],
                               "UNFOLD: FLAT PATTERN, BEND LINES, PUNCH PATH")


def elbow_picture(result, settings) -> bytes:
    """Batch ``elbow``'s picture (``elbow.png``) as PNG bytes: every piece's flat pattern and punch path."""
    from . import preview

    return preview.sheet_bytes([dict(outline=outline, contour=core.compensate_outline(outline, settings.tool_diameter),
                                     name=f"PIECE {index}") for index, outline in enumerate(elbow_layout(result), 1)],
                               "ELBOW: FLAT PATTERNS AND PUNCH PATHS")


def sheet_path_of(target: str) -> str:
    """Where a sheet-metal export's setup sheet goes: ``<target without extension>-setup-sheet.html``."""
    from .batchio import SHEET_NAME
    return os.path.splitext(os.path.abspath(target))[0] + "-" + SHEET_NAME


def sheet_export_request(scene, target: str, allow: bool, language: str | None = None):
    """The Sheet panel's export: the settings checked (by their panel names) and copied here, on
    the main thread; ``work(progress) -> [paths]`` unfolds, plans, punches the program out of the
    sheet, gates it and writes the NC, DXF and SVG (and the setup sheet, in ``language``), all or
    none, after its last progress call (so Esc writes nothing)."""
    props = scene.kezuri.sheet
    corners = corners_mm(props)
    check_group(props, "sheet", list(UNFOLD_SETTINGS))
    check_pitch(props)
    punch_profile(props)            # the sheet, origin and clamps, named as the panel names them
    settings = settings_of(props)

    def punch(progress):
        job = run_unfold(corners, settings, progress=progress)
        return [job.punched], lambda: unfold_texts(job, target), [job.punching], lambda: unfold_picture(job)
    return export_work("unfolding", punch, allow, "unfold", sheet_path_of(target), language)


def elbow_export_request(scene, target: str, allow: bool, language: str | None = None):
    """The Elbow panel's export, as :func:`sheet_export_request`: the elbow unfolded here (checked,
    quick), every piece's program punched in ``work(progress) -> [paths]``, then DXF, SVG, one
    program a piece and their setup sheet written, all or none."""
    props = scene.kezuri.sheet
    elbow = run_elbow(props)
    punch_profile(props)
    settings = settings_of(props)

    def punch(progress):
        punching = elbow_punching(elbow, settings, progress=progress)
        return ([punched for _, punched, _ in punching], lambda: elbow_texts(elbow, target, settings, punching),
                [job for *_, job in punching], lambda: elbow_picture(elbow, settings))
    return export_work("punching", punch, allow, "elbow", sheet_path_of(target), language)


class SheetExport(SteppedOperator, ExportHelper):
    """The Sheet and Elbow exports: after the file browser the work runs in steps with a progress
    bar and Esc to cancel, as every NC export does; from a script or in background mode at once."""

    progress_label = "export"
    setup_sheet: BoolProperty(name="Setup Sheet", default=True, description=SHEET_DESCRIPTION)

    def invoke(self, context, event):
        return ExportHelper.invoke(self, context, event)

    def sheet_language(self) -> str | None:
        """The setup sheet's language (the interface's, read on the main thread); None: no sheet."""
        return interface_language() if self.setup_sheet else None

    def execute(self, context):
        return self.start_stepped(context)

    def finish(self, context, files: list):
        self.report({"INFO"}, translate_message("Wrote " + ", ".join(os.path.basename(f) for f in files)))
        return {"FINISHED"}


class KEZURI_OT_sheet_export(SheetExport, bpy.types.Operator):
    """Write the turret-punch program (.nc) with the flat pattern as DXF and SVG beside it"""

    bl_idname = "kezuri.sheet_export"
    bl_label = "Export Punch NC, DXF, SVG"
    bl_options = {"REGISTER"}

    filename_ext = ".nc"
    filter_glob: StringProperty(default="*.nc", options={"HIDDEN"})
    allow_findings: BoolProperty(name="Write Despite Findings", default=False, description=ALLOW_DESCRIPTION)

    def prepare(self, context):
        return sheet_export_request(context.scene, self.filepath, self.allow_findings, self.sheet_language())


class KEZURI_OT_add_elbow(bpy.types.Operator):
    """Add a segmented pipe elbow and the flat pattern of every piece"""

    bl_idname = "kezuri.add_elbow"
    bl_label = "Pipe Elbow"
    bl_options = {"REGISTER", "UNDO"}

    __annotations__ = copies(ELBOW_SETTINGS)

    def invoke(self, context, event):
        for name in ELBOW_SETTINGS:
            setattr(self, name, getattr(context.scene.kezuri.sheet, name))
        return self.execute(context)

    def execute(self, context):
        def work():
            sheet = context.scene.kezuri.sheet
            check_group(self, "sheet", list(ELBOW_SETTINGS))      # before the scene takes them
            for name in ELBOW_SETTINGS:
                setattr(sheet, name, getattr(self, name))
            elbow = run_elbow(sheet)
            show_elbow(context.scene, elbow)
            self.report({"INFO"},
                        translate_message(f"Elbow of {len(elbow.pieces)} pieces, {elbow.piece_angle:.2f} deg each"))
            return {"FINISHED"}
        return run_reported(self, work)


class KEZURI_OT_elbow_export(SheetExport, bpy.types.Operator):
    """Write the elbow pieces' flat patterns as DXF and SVG, and a turret-punch program per piece"""

    bl_idname = "kezuri.elbow_export"
    bl_label = "Export Elbow Patterns"
    bl_options = {"REGISTER"}

    filename_ext = ".dxf"
    filter_glob: StringProperty(default="*.dxf;*.svg", options={"HIDDEN"})
    allow_findings: BoolProperty(name="Write Despite Findings", default=False, description=ALLOW_DESCRIPTION)

    def prepare(self, context):
        return elbow_export_request(context.scene, self.filepath, self.allow_findings, self.sheet_language())


def menu_import(self, context):
    self.layout.operator(KEZURI_OT_import_cdl.bl_idname, text="CADKEY CDL (.cdl)")


CLASSES = (KEZURI_OT_unfold_quad, KEZURI_OT_quad_from_selection, KEZURI_OT_import_cdl, KEZURI_OT_sheet_export,
           KEZURI_OT_add_elbow, KEZURI_OT_elbow_export)
MENUS = ((bpy.types.TOPBAR_MT_file_import, menu_import),)


# ----- batch: ``batch.py unfold`` and ``batch.py elbow`` -----------------------------------

def unfold_arguments(p):
    source = p.add_mutually_exclusive_group()
    source.add_argument("--cdl", help="CADKEY .CDL file with the quad's four LINE records")
    source.add_argument("--corners", help='"x,y,z;x,y,z;x,y,z;x,y,z" in mm (default: the paper\'s test quad)')
    source.add_argument("--blend", help="a .blend whose Kezuri sheet settings hold the corners")
    from .batchio import number
    from .limits import RANGES
    p.add_argument("--divisions", type=number("--divisions", limit=RANGES["sheet"]["divisions"]))
    p.add_argument("--direction", choices=["horizontal", "vertical"])
    p.add_argument("--tool-diameter", type=number("--tool-diameter", limit=RANGES["sheet"]["tool_diameter"]))
    p.add_argument("--thickness", type=number("--thickness", limit=RANGES["sheet"]["thickness"]))
    p.add_argument("--pitch", type=number("--pitch", limit=RANGES["sheet"]["pitch"]))
    p.add_argument("--station", type=number("--station", limit=RANGES["sheet"]["station"]))
    sheet_arguments(p)
    gate.allow_findings_argument(p)


def sheet_arguments(p):
    """Where the part goes on the turret punch's sheet and its micro-joints (unfold and elbow)."""
    from .batchio import number
    from .limits import RANGES
    limits = RANGES["sheet"]
    p.add_argument("--sheet-origin", help='the G92 program origin "X,Y" in mm (default: the Amada 04P preset\'s)')
    p.add_argument("--sheet-size", help='the sheet "X,Y" in mm, X along the clamped edge')
    p.add_argument("--clamps", help='clamp centres along the clamped edge, "200,700" in mm ("" for none)')
    p.add_argument("--clamp-width", type=number("--clamp-width", limit=limits["clamp_width"]))
    p.add_argument("--clamp-depth", type=number("--clamp-depth", limit=limits["clamp_depth"]))
    p.add_argument("--joints", type=number("--joints", limit=limits["joints"]),
                   help="micro-joints left on the part's outline (0: the part falls free)")
    p.add_argument("--joint-width", type=number("--joint-width", limit=limits["joint_width"]))


def _pair(text: str, option: str):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise convert.SceneInputError(f'{option}: give two numbers "X,Y" in mm, got {text!r}') from None
    if len(values) != 2 or not all(np.isfinite(values)):
        raise convert.SceneInputError(f'{option}: give two finite numbers "X,Y" in mm, got {text!r}')
    return values


def apply_sheet_arguments(args, sheet) -> None:
    from . import batchio
    from .limits import problem
    for option, name in (("sheet_origin", "sheet_origin"), ("sheet_size", "sheet_size")):
        text = getattr(args, option)
        if text is not None:
            flag = "--" + option.replace("_", "-")
            values = _pair(text, flag)
            message = problem("sheet", name, flag, tuple(values), "")
            if message:
                raise convert.SceneInputError(message)
            setattr(sheet, name, values)
    if args.clamps is not None:
        parse_clamps(args.clamps, 1.0, 1.0, "--clamps")
        sheet.clamps = args.clamps
    for option in ("clamp_width", "clamp_depth", "joints", "joint_width"):
        if getattr(args, option) is not None:
            batchio.set_exactly(sheet, option, getattr(args, option), "--" + option.replace("_", "-"))


def read_cdl_file(path: str, shown: str | None = None):
    """The quad's corners of a CDL file (:func:`textfile.read_text`: UTF-8, UTF-16 or latin-1); an
    error names the file as the user gave it (``shown``, default the path) before the reader's line."""
    shown = shown or path
    problem = refusal(shown, path, "a CDL file")
    if problem:
        raise core.UnfoldError(problem)
    try:
        return core.read_cdl(read_text(path))
    except InputError as error:
        raise core.UnfoldError(named(shown, str(error))) from None


def check_corners(corners, where: str):
    """Corners given to batch (--corners, --cdl) within the range the panel's Corners have: a CDL
    1e12 mm across reached the punch simulation and was refused there for its number of hits."""
    from .limits import RANGES
    limit = RANGES["sheet"]["corners"]
    for index, corner in enumerate(np.asarray(corners, float), start=1):
        if not all(limit.allows(v) for v in corner):
            raise convert.SceneInputError(f"{where}: corner P{index} ({corner[0]:g}, {corner[1]:g}, {corner[2]:g}) "
                                          f"is outside the allowed range {limit.text('Corners')}")
    return corners


def parse_corners(text: str):
    try:
        corners = np.array([[float(v) for v in corner.split(",")] for corner in text.split(";")])
    except ValueError:
        raise convert.SceneInputError(f"--corners: not numbers: {text!r}") from None
    if corners.shape == (4, 3) and not np.all(np.isfinite(corners)):
        raise convert.SceneInputError(f"--corners: every coordinate must be a finite number of mm, got {text!r}")
    if corners.shape != (4, 3):
        raise convert.SceneInputError(f'--corners needs four "x,y,z" corners separated by ";", got {text!r}')
    return corners


def unfold_batch(args) -> dict:
    from ..post.output import write_atomic
    from . import batchio

    scene = batchio.open_blend(args.blend)
    sheet = scene.kezuri.sheet
    for option in ("divisions", "direction", "tool_diameter", "thickness", "pitch", "station"):
        if getattr(args, option) is not None:
            batchio.set_exactly(sheet, option, getattr(args, option), "--" + option.replace("_", "-"))
    apply_sheet_arguments(args, sheet)
    if args.cdl:
        corners = check_corners(read_cdl_file(args.cdl, f"--cdl {args.cdl}"), f"--cdl {args.cdl}")
    elif args.corners:
        corners = check_corners(parse_corners(args.corners), "--corners")
    else:
        corners = corners_mm(sheet)
    job = run_unfold(corners, sheet, UNFOLD_NAMES)
    gate_report = punch_gate([job.punched], args.allow_findings)
    files = unfold_files(job, os.path.join(args.out, "unfold.nc"))
    if batchio.shown():
        show_unfold(scene, job)
    png = write_atomic(os.path.join(args.out, "unfold.png"), unfold_picture(job))
    pattern = job.quad.pattern
    rounded = batchio.rounded
    return {
        "workflow": "unfold",
        "files": files,
        "preview": png,
        "divisions": job.quad.divisions,
        "direction": job.quad.direction,
        "corners": rounded(job.quad.corners),
        "edge_lengths": rounded(job.quad.edge_lengths, 6),
        "diagonals": rounded(job.quad.diagonals, 6),
        "triangles": [{"3d": rounded(pattern.vertices_3d[t]), "2d": rounded(pattern.vertices_2d[t])}
                      for t in pattern.triangles],
        "outline": rounded(pattern.outline),
        "cut_contour": rounded(job.contour),
        "simulation": punch_report([job.punched], sheet.thickness),
        "sheet": placement_report([job.punching]),
        "gate": gate_report,
    }


def elbow_arguments(p):
    from .batchio import number
    from .limits import RANGES
    p.add_argument("--diameter", type=number("--diameter", limit=RANGES["sheet"]["elbow_diameter"]))
    p.add_argument("--bend-radius", type=number("--bend-radius", limit=RANGES["sheet"]["elbow_radius"]))
    p.add_argument("--angle", type=number("--angle", limit=RANGES["sheet"]["elbow_angle"]))
    p.add_argument("--pieces", type=number("--pieces", limit=RANGES["sheet"]["elbow_pieces"]))
    sheet_arguments(p)
    gate.allow_findings_argument(p)


def elbow_batch(args) -> dict:
    from ..post.output import write_atomic
    from . import batchio

    scene = batchio.open_blend(None)
    sheet = scene.kezuri.sheet
    for option, name in (("diameter", "elbow_diameter"), ("bend_radius", "elbow_radius"),
                         ("angle", "elbow_angle"), ("pieces", "elbow_pieces")):
        if getattr(args, option) is not None:
            batchio.set_exactly(sheet, name, getattr(args, option), "--" + option.replace("_", "-"))
    apply_sheet_arguments(args, sheet)
    result = run_elbow(sheet, ELBOW_NAMES)
    punching = elbow_punching(result, sheet, ELBOW_NAMES)
    gate_report = punch_gate([punched for _, punched, _ in punching], args.allow_findings)
    files = elbow_files(result, os.path.join(args.out, "elbow.dxf"), sheet, punching)
    if batchio.shown():
        show_elbow(scene, result)
    png = write_atomic(os.path.join(args.out, "elbow.png"), elbow_picture(result, sheet))
    rounded = batchio.rounded
    return {
        "workflow": "elbow",
        "files": files,
        "preview": png,
        "diameter": result.diameter, "bend_radius": result.bend_radius, "angle": result.bend_angle,
        "simulation": punch_report([punched for _, punched, _ in punching], sheet.thickness),
        "sheet": placement_report([job for *_, job in punching]),
        "gate": gate_report,
        "pieces": [{"index": piece.index + 1, "angle_deg": round(piece.angle, 6),
                    "outline": rounded(piece.outline),
                    "shortest_mm": round(float(piece.generatrix_lengths.min()), 6),
                    "longest_mm": round(float(piece.generatrix_lengths.max()), 6)} for piece in result.pieces],
    }


WORKFLOW = Workflow(
    "SHEET", "Sheet Metal", "Twisted quads and pipe elbows: flat patterns, turret-punch NC, DXF, SVG",
    classes=CLASSES, menus=MENUS, post_families=POST_FAMILIES,
    commands=(BatchCommand("unfold", "twisted quad: flat pattern, turret-punch NC, DXF, SVG (W5)", unfold_arguments,
                           unfold_batch),
              BatchCommand("elbow", "segmented pipe elbow: flat patterns, DXF, SVG (W5)", elbow_arguments,
                           elbow_batch)))
