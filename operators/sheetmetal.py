"""W5 in Blender: twisted quads and pipe elbows unfolded, turret-punch NC, DXF and SVG.

The quad's corners live in ``scene.kezuri.sheet.corners`` (mm): typed in the panel, taken from a
selected quad face, or imported from a CADKEY .CDL file.  ``run_unfold`` and ``run_elbow`` are the
job functions the operators, batch.py and the tests share.
"""
from __future__ import annotations

import os
import time
from dataclasses import dataclass

import bpy
import numpy as np
from bpy.props import BoolProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from .. import post as posts
from ..post import flat_export, write_atomic
from ..toolpath.ir import machine
from ..toolpath.job import Job, JobOperation, Setup, plan_job
from ..toolpath.operations.sheetmetal import nibbling, placement, punch
from ..toolpath.operations.sheetmetal.kind import PunchGeometry, PunchSettings
from ..toolpath.operations.sheetmetal import unfold as core
from ..toolpath.ir.errors import InputError
from ..toolpath.engines.textfile import read_text
from . import convert, gate
from .common import run_reported
from .limits import SettingError, check_group
from .properties import ELBOW_SETTINGS, UNFOLD_SETTINGS, copies
from .translations import translate_message
from .workflow import BatchCommand, Workflow

PREFIX = "Kezuri Sheet"
ELBOW_PREFIX = "Kezuri Elbow"
GAP_MM = 20.0   # flat patterns are laid out this far beside the part
POST_FAMILIES = ("punch",)
PUNCH_POST = "amada-04p"
ALLOW_DESCRIPTION = ("Write the programs even if the punching simulation finds a part that stays in the sheet "
                     "or a hit biting into the part")


SETUP_NAMES = {"sheet_origin": "G92 Origin", "sheet_size": "Sheet", "clamps": "Clamps", "joints": "Micro-Joints",
               "joint_width": "Joint Width"}


def parse_clamps(text: str, width: float, depth: float, name: str = "Clamps") -> tuple:
    """Clamps from their centres along the clamped edge, "200, 700" (mm); none from an empty text."""
    found = []
    for item in str(text).replace(";", ",").split(","):
        if not item.strip():
            continue
        try:
            x = float(item)
        except ValueError:
            raise SettingError(f"{name}: {item.strip()!r} is not a number of mm (give clamp centres like "
                               f"\"200, 700\")") from None
        if not (abs(x) < 1e5):
            raise SettingError(f"{name}: {item.strip()!r} is not a position on the sheet")
        found.append(machine.Clamp(x, width, depth))
    return tuple(found)


def punch_profile(props, names: dict = SETUP_NAMES) -> machine.MachineProfile:
    """The Amada 04P preset with the sheet, G92 origin and clamps the panel (or batch) gives."""
    check_group(props, "sheet", ["sheet_origin", "sheet_size", "clamp_width", "clamp_depth", "joints", "joint_width"])
    clamps = parse_clamps(props.clamps, props.clamp_width, props.clamp_depth, names["clamps"])
    return machine.preset(PUNCH_POST).replace(sheet_origin=tuple(props.sheet_origin), clamps=clamps,
                                              sheet_max=tuple(props.sheet_size))


@dataclass
class PunchJob:
    """One part's program on the sheet: where it sits, its nibbling lines and their simulation."""

    nc: str
    punched: punch.PunchResult
    placement: placement.Placement
    nibbling: nibbling.Nibbling
    offset: np.ndarray          # added to the pattern's coordinates to put it on the sheet


def punch_settings(props) -> PunchSettings:
    """The punch program's settings from the sheet panel (or batch's options)."""
    return PunchSettings(props.station, props.tool_diameter, props.pitch, props.thickness, props.joints,
                         props.joint_width)


def punch_job(pattern, props, profile=None) -> PunchJob:
    """Plan the flat ``pattern`` as a job of one punching operation (its tool-centre contour placed
    on the sheet clear of the clamps, nibbled round: merged lines, micro-joints, each hit once),
    write the program and punch it out of the sheet."""
    profile = punch_profile(props) if profile is None else profile
    setup = Setup(name="punch", post=PUNCH_POST, machine=profile)
    operation = JobOperation("punch", "punch", punch_settings(props), PunchGeometry(np.asarray(pattern)))
    plan = plan_job(Job(setup, (operation,))).parts[0].result
    nc = posts.create(POST_FAMILIES, PUNCH_POST).to_text(plan.program)
    punched = punch.simulate_punching(nc, punch_diameter=props.tool_diameter, pattern=plan.pattern,
                                      joints=plan.nibbling.joints)
    return PunchJob(nc, punched, plan.placement, plan.nibbling, plan.offset)


def placement_report(jobs: list) -> dict:
    """The report's ``sheet`` entry: where each part sits, the clamps, the joints."""
    first = jobs[0].placement
    return {
        "sheet_mm": list(first.sheet),
        "clamp_zones": [[round(v, 3) for v in z] for z in first.zones],
        "parts": [{"where": j.placement.where, "offset": [round(v, 3) for v in j.placement.offset],
                   "hits_within": [round(v, 3) for v in j.placement.envelope],
                   "lines": len(j.nibbling.lines), "merged_points": j.nibbling.merged,
                   "joints": len(j.nibbling.joints), "joint_width_mm": round(j.nibbling.joint_width, 4),
                   "joint_webs_mm": j.punched.joint_widths_mm} for j in jobs],
    }


@dataclass
class UnfoldJob:
    quad: core.TwistedQuad
    contour: np.ndarray        # tool-centre contour around the flat pattern (mm)
    nc: str                    # the turret-punch program
    punched: punch.PunchResult  # that program read back and punched out of the sheet
    punching: PunchJob = None  # where it sits on the sheet, its lines and joints


def corners_mm(props) -> np.ndarray:
    check_group(props, "sheet", ["corners"])
    return np.array(props.corners, float).reshape(4, 3)


# How messages name the settings: the panel and its labels, or batch's command and options.
PANEL_NAMES = {"where": "Sheet Metal", "pitch": "Nibbling Pitch", "tool_diameter": "Tool Diameter",
               "corners": "Quad corners (mm)", "diameter": "Pipe Diameter"}
UNFOLD_NAMES = {"where": "unfold", "pitch": "--pitch", "tool_diameter": "--tool-diameter",
                "corners": "--corners, --cdl or --blend"}
ELBOW_NAMES = {"where": "elbow", "pitch": "Nibbling Pitch", "tool_diameter": "Tool Diameter", "diameter": "--diameter"}


def check_pitch(props, names: dict = PANEL_NAMES) -> None:
    """The nibbling pitch against the punch: hits a diameter or more apart leave webs between
    them, and the part never falls out of the sheet."""
    if props.pitch >= props.tool_diameter:
        raise SettingError(f"{names['where']}: {names['pitch']} = {props.pitch:g} mm must be less than "
                           f"{names['tool_diameter']} = {props.tool_diameter:g} mm: hits a diameter or more apart "
                           f"leave webs, and the part stays in the sheet")


def check_contour(contour: np.ndarray, props, what: str, names: dict = PANEL_NAMES) -> None:
    """A cut contour the turret punch can run, before its program is written: within the
    coordinates the control addresses, and within the hits one program may have.  ``what``:
    the setting that made the contour, as the user gave it."""
    reach = posts.find(POST_FAMILIES, PUNCH_POST).limits.coordinate
    extent = float(np.abs(contour).max())
    if extent > reach:
        size = np.ptp(contour, axis=0)
        raise SettingError(f"{names['where']}: {what}: the cut contour is {size[0]:.1f} x {size[1]:.1f} mm and "
                           f"reaches {extent:.1f} mm from the program's origin, beyond the {reach:.2f} mm the "
                           f"turret punch control addresses")
    hits = punch.hit_count(contour, props.pitch)
    if hits > punch.MAX_HITS:
        raise SettingError(f"{names['where']}: {names['pitch']} = {props.pitch:g} mm: {what} takes {hits} hits, "
                           f"more than the {punch.MAX_HITS} one program may have; raise the pitch")


def word_error(resolution: float, line_mm: float) -> float:
    """How far the NC words alone can put a hit of a line ``line_mm`` long off its exact place:
    its start (X, Y) rounded to ``resolution`` mm and its direction (J) to ``resolution`` degrees."""
    return resolution / 2 * 2 ** 0.5 + line_mm * np.sin(np.radians(resolution / 2))


def punch_gate(results: list, allow: bool) -> dict:
    """The export gate of a punching job: a part that stays in the sheet other than by the
    micro-joints the job left (held by them is the intended result), a part that falls free
    though joints were asked for, or a hit biting into
    the part deeper than the simulation's tolerance and what the NC words' two decimals can put
    it off by (:func:`word_error`), is not written unless ``allow``.  Returns the report's
    ``gate`` entry; raises :class:`gate.GateRefused`."""
    started = time.perf_counter()
    resolution = posts.find(POST_FAMILIES, PUNCH_POST).limits.resolution
    findings = []
    for index, result in enumerate(results, start=1):
        which = f"piece {index}: " if len(results) > 1 else ""
        if result.joints and result.part_separated:
            findings.append({"kind": "joints do not hold", "piece": index, "line": None, "depth_mm": None,
                             "message": f"{which}the part falls free: its {result.joints} micro-joint(s) leave no web"})
        elif not result.part_separated and not result.held_by_joints:
            findings.append({"kind": "part in sheet", "piece": index, "line": None, "depth_mm": None,
                             "message": f"{which}the part stays in the sheet (webs between the hits)"})
        findings += [{"kind": "gouge", "piece": index, "line": g.line, "depth_mm": round(g.depth_mm, 4),
                      "message": which + g.message}
                     for g in result.gouges if g.depth_mm > result.tolerance + word_error(resolution, g.line_mm)]
    report = {"findings": findings, "overridden": False, "seconds": round(time.perf_counter() - started, 3)}
    if findings:
        if not allow:
            listed = "; ".join(f["message"] for f in findings[:5])
            more = f" (and {len(findings) - 5} more)" if len(findings) > 5 else ""
            raise gate.GateRefused(f"not written: the punching simulation found {len(findings)} fault(s): "
                                   f"{listed}{more}. Fix the job, or override knowingly (batch: --allow-findings; "
                                   f"panel: Write Despite Findings in the export's file browser)", findings)
        report["overridden"] = True
    return report


def run_unfold(corners, props, names: dict = PANEL_NAMES) -> UnfoldJob:
    check_group(props, "sheet", list(UNFOLD_SETTINGS))
    check_pitch(props, names)
    quad = core.unfold_twisted_quad(corners, props.divisions, props.direction)
    contour = core.compensate_outline(quad.pattern.outline, props.tool_diameter)
    check_contour(contour, props, f"the flat pattern of {names['corners']}", names)
    job = punch_job(quad.pattern.outline, props)
    return UnfoldJob(quad, contour, job.nc, job.punched, job)


def punch_report(results: list, thickness: float) -> dict:
    """The ``simulation`` entry of a batch report for one or more punched parts."""
    gouges = [{"line": g.line, "depth_mm": round(g.depth_mm, 4), "xy": [round(v, 3) for v in g.xy],
               "message": g.message, "part": index + 1}
              for index, result in enumerate(results) for g in result.gouges]
    removed = sum(r.removed_area_mm2 for r in results)
    return {
        "engine": "crosssection",
        "tolerance_mm": results[0].tolerance,
        "seconds": round(sum(r.seconds for r in results), 3),
        "hits": sum(r.hits for r in results),
        "parts_separated": [r.part_separated for r in results],
        "held_by_joints": [r.held_by_joints for r in results],
        "part_area_mm2": [round(r.part_area_mm2, 2) for r in results],
        "pattern_area_mm2": [round(r.pattern_area_mm2, 2) for r in results],
        "removed_area_mm2": round(removed, 2),
        "removed_volume_mm3": round(removed * thickness, 1),
        "max_scallop_mm": round(max(r.max_scallop_mm or 0.0 for r in results), 4),
        "gouges": gouges,
        "max_gouge_mm": round(max(r.max_gouge_mm for r in results), 4),
        "rapid_collisions": [],
    }


def punch_warnings(results: list) -> list:
    """What the punching simulation found that the shop must hear about."""
    warnings = []
    for index, result in enumerate(results):
        which = f"part {index + 1}: " if len(results) > 1 else ""
        if result.joints and result.part_separated:
            warnings.append(f"{which}the part falls free: its micro-joints leave no web")
        elif not result.part_separated and not result.held_by_joints:
            warnings.append(f"{which}the part stays in the sheet: hits further apart than the punch leave webs "
                            f"(lower the pitch below the {result.punch_diameter:g} mm punch)")
        warnings += [f"{which}{g.message}" for g in result.gouges]
    return warnings


def unfold_files(job: UnfoldJob, base_path: str) -> list:
    """NC (.nc), DXF and SVG beside each other; each written atomically."""
    outline = job.quad.pattern.outline
    bends = job.quad.pattern.bend_lines()
    stem = os.path.splitext(base_path)[0]
    files = [write_atomic(stem + posts.extension(POST_FAMILIES, PUNCH_POST), job.nc),
             write_atomic(stem + ".dxf", flat_export.to_dxf([outline], punch_paths=[job.contour], bend_lines=bends)),
             write_atomic(stem + ".svg", flat_export.to_svg([outline], punch_paths=[job.contour], bend_lines=bends))]
    return files


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


def run_elbow(props, names: dict = PANEL_NAMES) -> core.Elbow:
    check_group(props, "sheet", [*ELBOW_SETTINGS, "tool_diameter", "thickness", "pitch", "station"])
    check_pitch(props, names)
    return core.unfold_elbow(props.elbow_angle, props.elbow_radius, props.elbow_diameter, props.elbow_pieces)


def elbow_layout(elbow: core.Elbow) -> list:
    """Each piece's flat outline (mm), placed one above the other with a gap."""
    placed, y = [], 0.0
    for piece in elbow.pieces:
        outline = np.asarray(piece.outline, float)
        outline = outline - [0.0, outline[:, 1].min() - y]
        placed.append(outline)
        y = outline[:, 1].max() + GAP_MM / 2
    return placed


def elbow_punching(elbow: core.Elbow, props, names: dict = PANEL_NAMES) -> list:
    """Per piece: (turret-punch program, its punching simulation), with the sheet panel's punch.
    Each piece is punched from a sheet of its own, its pattern's lower left corner at the
    program's origin (as the first piece of the layout)."""
    contours = []
    for index, piece in enumerate(elbow.pieces, start=1):
        outline = np.asarray(piece.outline, float)
        outline = outline - outline.min(axis=0)
        contour = core.compensate_outline(outline, props.tool_diameter)
        check_contour(contour, props, f"piece {index} of {names['diameter']} = {elbow.diameter:g} mm", names)
        contours.append((outline, contour))
    jobs = []
    profile = punch_profile(props)
    for index, (outline, contour) in enumerate(contours, start=1):
        try:
            job = punch_job(outline, props, profile)
        except InputError as error:     # which piece's program: the message's line is that program's
            raise core.UnfoldError(f"elbow piece {index} of {len(elbow.pieces)}: {error}") from None
        jobs.append((job.nc, job.punched, job))
    return jobs


def elbow_files(elbow: core.Elbow, base_path: str, props, punching: list | None = None) -> list:
    """DXF and SVG of all the pieces, and one turret-punch program per piece (<stem>-1.nc ...).
    Every text is made (and every piece's program punched, unless ``punching`` from
    :func:`elbow_punching` is given) before the first file is written."""
    stem = os.path.splitext(base_path)[0]
    outlines = elbow_layout(elbow)
    punch_paths = [core.compensate_outline(outline, props.tool_diameter) for outline in outlines]
    punching = elbow_punching(elbow, props) if punching is None else punching
    extension = posts.extension(POST_FAMILIES, PUNCH_POST)
    texts = [(stem + ".dxf", flat_export.to_dxf(outlines, punch_paths=punch_paths)),
             (stem + ".svg", flat_export.to_svg(outlines, punch_paths=punch_paths))]
    texts += [(f"{stem}-{index}{extension}", nc) for index, (nc, *_) in enumerate(punching, start=1)]
    return [write_atomic(path, text) for path, text in texts]


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


class KEZURI_OT_sheet_export(bpy.types.Operator, ExportHelper):
    """Write the turret-punch program (.nc) with the flat pattern as DXF and SVG beside it"""

    bl_idname = "kezuri.sheet_export"
    bl_label = "Export Punch NC, DXF, SVG"
    bl_options = {"REGISTER"}

    filename_ext = ".nc"
    filter_glob: StringProperty(default="*.nc", options={"HIDDEN"})
    allow_findings: BoolProperty(name="Write Despite Findings", default=False, description=ALLOW_DESCRIPTION)

    def execute(self, context):
        def work():
            job = run_unfold(corners_mm(context.scene.kezuri.sheet), context.scene.kezuri.sheet)
            punch_gate([job.punched], self.allow_findings)
            files = unfold_files(job, self.filepath)
            self.report({"INFO"}, translate_message("Wrote " + ", ".join(os.path.basename(f) for f in files)))
            return {"FINISHED"}
        return run_reported(self, work)


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


class KEZURI_OT_elbow_export(bpy.types.Operator, ExportHelper):
    """Write the elbow pieces' flat patterns as DXF and SVG, and a turret-punch program per piece"""

    bl_idname = "kezuri.elbow_export"
    bl_label = "Export Elbow Patterns"
    bl_options = {"REGISTER"}

    filename_ext = ".dxf"
    filter_glob: StringProperty(default="*.dxf;*.svg", options={"HIDDEN"})
    allow_findings: BoolProperty(name="Write Despite Findings", default=False, description=ALLOW_DESCRIPTION)

    def execute(self, context):
        def work():
            sheet = context.scene.kezuri.sheet
            elbow = run_elbow(sheet)
            punching = elbow_punching(elbow, sheet)
            punch_gate([punched for _, punched, _ in punching], self.allow_findings)
            files = elbow_files(elbow, self.filepath, sheet, punching)
            self.report({"INFO"}, translate_message("Wrote " + ", ".join(os.path.basename(f) for f in files)))
            return {"FINISHED"}
        return run_reported(self, work)


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


def read_cdl_file(path: str):
    """The quad's corners of a CDL file (:func:`textfile.read_text`: UTF-8 or latin-1)."""
    return core.read_cdl(read_text(path))


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
    from . import batchio, preview

    scene = batchio.open_blend(args.blend)
    sheet = scene.kezuri.sheet
    for option in ("divisions", "direction", "tool_diameter", "thickness", "pitch", "station"):
        if getattr(args, option) is not None:
            batchio.set_exactly(sheet, option, getattr(args, option), "--" + option.replace("_", "-"))
    apply_sheet_arguments(args, sheet)
    if args.cdl:
        if not os.path.isfile(args.cdl):
            raise FileNotFoundError(f"no such CDL file: {args.cdl}")
        corners = check_corners(read_cdl_file(args.cdl), f"--cdl {args.cdl}")
    elif args.corners:
        corners = check_corners(parse_corners(args.corners), "--corners")
    else:
        corners = corners_mm(sheet)
    job = run_unfold(corners, sheet, UNFOLD_NAMES)
    gate_report = punch_gate([job.punched], args.allow_findings)
    files = unfold_files(job, os.path.join(args.out, "unfold.nc"))
    if batchio.shown():
        show_unfold(scene, job)
    pattern = job.quad.pattern
    png = preview.sheet_png(os.path.join(args.out, "unfold.png"),
                            [dict(outline=pattern.outline, bends=[(s[0], s[1]) for s in pattern.bend_lines()], contour=job.contour,
                                  name="FLAT PATTERN")], "UNFOLD: FLAT PATTERN, BEND LINES, PUNCH PATH")
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
    from . import batchio, preview

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
    png = preview.sheet_png(os.path.join(args.out, "elbow.png"),
                            [dict(outline=outline, contour=core.compensate_outline(outline, sheet.tool_diameter),
                                  name=f"PIECE {index}") for index, outline in enumerate(elbow_layout(result), 1)],
                            "ELBOW: FLAT PATTERNS AND PUNCH PATHS")
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
