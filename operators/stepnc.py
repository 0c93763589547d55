"""W3 in Blender: import an ISO 14649 (STEP-NC) file, reorder its workingsteps, export G-code;
export pockets modelled in Blender as an ISO 14649 file.

The imported file stays the source of truth: the scene keeps its path and the workingstep
list (order and on/off); export reads the file again and converts it in the list's order.
"""
from __future__ import annotations

import os
from dataclasses import dataclass

import bpy
import numpy as np
from bpy.props import EnumProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from .. import post as posts
from ..post import write_atomic
from ..toolpath.operations import stepnc
from ..toolpath.engines.meshdata import prism
from ..toolpath.engines.textfile import file_problem, named, os_reason, read_text, refusal
from ..toolpath.job import Job, JobOperation, Setup, plan_job
from ..toolpath.ir.errors import InputError
from ..toolpath.ir.program import Tool
from ..toolpath.operations.stepnc.kind import StepncGeometry, StepncSettings
from ..toolpath.operations.stepnc.loaded import workplan_from_text
from ..toolpath.operations.stepnc.tools import tool_numbers
from ..toolpath.operations.stepnc.solids import block_of, feature_solid, stock_box
from . import convert
from . import gate
from . import pathview
from .common import SteppedOperator, run_reported
from .exporting import Exported, NCExport, ProgramSheet, stages, batch_orient_spindle, machine_post, orient_spindle_argument, warn, write_program
from .machines import batch_machine, machine_arguments, scene_machine
from .limits import check_group
from .properties import post_items, post_number
from .translations import iface, translate_message
from .workflow import BatchCommand, SimulationSetup, Workflow

POST_FAMILIES = ("milling",)

PREFIX = "Kezuri STEP-NC"
FEATURE_COLOURS = {"ClosedPocket": (0.2, 0.6, 1.0, 1.0), "PlanarFace": (0.9, 0.8, 0.2, 1.0),
                   "RoundHole": (0.9, 0.3, 0.3, 1.0)}


def describe_step(step) -> dict:
    feature, operation = step.its_feature, step.its_operation
    return {"id": step.id, "name": step.its_id, "feature": f"{type(feature).__name__} {feature.its_id}",
            "operation": type(operation).__name__ + (" (finishing)" if getattr(operation, "finishing", False) else "")}


# What a workingstep does, in the few words its row in the list has room for.
STEP_WORDS = {"PLANE_ROUGH_MILLING": "face rough", "PLANE_FINISH_MILLING": "face",
              "BOTTOM_AND_SIDE_ROUGH_MILLING": "rough", "BOTTOM_AND_SIDE_FINISH_MILLING": "finish",
              "DRILLING": "drill", "CENTER_DRILLING": "centre drill", "REAMING": "ream"}


def step_row(step, numbers: dict) -> tuple:
    """(feature, operation, tool) of a workingstep's row, e.g. ("POCKET1", "rough", "T2 Ø10"):
    the feature's name in the file, the operation in a word, the tool number and diameter."""
    operation = step.its_operation
    tool = operation.its_tool
    diameter = tool.its_tool_body.dimension.diameter
    return (step.its_feature.its_id, STEP_WORDS.get(operation.type_name, operation.type_name.lower()),
            f"T{numbers[tool.id]} Ø{diameter:g}")


INT_MAX = 2**31 - 1     # Blender's IntProperty


def fill_workplan_list(scene, path: str, loaded) -> None:
    for step in loaded.workingsteps:    # the list keeps ids as Blender ints (a Part 21 id has no bound)
        if not 0 < step.id <= INT_MAX:
            raise convert.SceneInputError(f"{path}: workingstep #{step.id}: an instance number above {INT_MAX} "
                                          f"cannot be listed in the workplan; renumber the file")
    props = scene.kezuri.stepnc
    props.filepath = path
    props.steps.clear()
    numbers = tool_numbers(loaded.workingsteps)
    for step in loaded.workingsteps:
        item = props.steps.add()
        info = describe_step(step)
        item.ident, item.name, item.feature, item.operation = info["id"], info["name"], info["feature"], \
            info["operation"]
        item.feature_name, item.step, item.tool = step_row(step, numbers)
        item.enabled = True
    props.active_step = 0


@dataclass
class WorkplanJob:
    """The planned workplan: ``part``, the job's part (its result: the file as read, the program with
    the file's notes), and ``frame``, where the work frame sits in the scene."""

    part: object
    frame: object

    @property
    def loaded(self):
        return self.part.result.loaded

    @property
    def program(self):
        return self.part.result.program


def scene_workplan_path(scene) -> str:
    path = bpy.path.abspath(scene.kezuri.stepnc.filepath)
    if not path:
        raise convert.SceneInputError("no ISO 14649 file: use File > Import > ISO 14649 first")
    if not os.path.isfile(path):
        raise convert.SceneInputError(f"the imported ISO 14649 file is gone: {path}")
    return path


def workplan_job(scene, machine=None, post_name: str = "", read=None) -> Job:
    """A job of one operation: the imported file's workplan in the list's order, without the
    switched-off workingsteps.  ``machine``: the machine profile (None: not checked here);
    ``read``: (text, its LoadedWorkplan) the caller has read, used when the file still holds that
    text (else the plan reads the file)."""
    props, settings = scene.kezuri.stepnc, scene.kezuri.machine
    order = tuple(item.ident for item in props.steps)
    enabled = tuple(item.ident for item in props.steps if item.enabled)
    text = read_text(scene_workplan_path(scene))
    geometry = StepncGeometry(text, read[1] if read is not None and read[0] == text else None)
    setup = Setup(name=scene.name, post=post_name, machine=machine, work_offset=settings.work_offset,
                  rapid_rate=settings.rapid_rate)
    return Job(setup, (JobOperation("stepnc", "stepnc", StepncSettings(order, enabled), geometry),))


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's STEP-NC workplan: ``file = "part.stp"`` (beside the job file), and optionally
    settings ``order`` (instance ids in cutting order) and ``enabled`` (those cut; default all)."""
    from .jobentry import JobFileError

    if entry.objects:
        raise JobFileError(f"{entry.where}: a STEP-NC workplan comes from its file = \"...\", not objects")
    path = entry.table.get("file")
    if not isinstance(path, str) or not path:
        raise JobFileError(f"{entry.where}: no file: give file = \"part.stp\" (an ISO 14649 Part 21 file)")
    typed, path = path, os.path.join(entry.base_dir, path)
    problem = file_problem(path, "an ISO 14649 file")
    if problem:
        raise JobFileError(named(f"{entry.where}: file = {typed!r}", f"{problem} ({path})"))
    unknown = sorted(set(entry.settings) - {"order", "enabled"})
    if unknown:
        raise JobFileError(f"{entry.where}: settings.{unknown[0]} is not a STEP-NC setting; they are order, enabled")
    ids = {}
    for key in ("order", "enabled"):
        value = entry.settings.get(key)
        if value is not None and (not isinstance(value, list)
                                  or not all(isinstance(v, int) and not isinstance(v, bool) for v in value)):
            raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not a list of instance ids")
        ids[key] = tuple(value) if value is not None else None
    settings = StepncSettings(ids["order"], ids["enabled"])
    machine = scene.kezuri.machine
    setup = Setup(name=scene.name, post=post_name, work_offset=machine.work_offset, rapid_rate=machine.rapid_rate)
    frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
    try:                                        # read here, so that an error names the job file's entry too
        text = read_text(path)
        loaded = workplan_from_text(text)
    except InputError as error:
        raise JobFileError(named(f"{entry.where}: file = {typed!r}", str(error))) from error
    except OSError as error:
        raise JobFileError(named(f"{entry.where}: file = {typed!r}", f"{os_reason(error)} ({path})")) from error
    return JobOperation("stepnc", entry.name, settings, StepncGeometry(text, loaded), entry.enabled), setup, frame


def plan_workplan(scene, machine=None, post_name: str = "", progress=None) -> WorkplanJob:
    part = plan_job(workplan_job(scene, machine, post_name), progress=progress).parts[0]
    return WorkplanJob(part, convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0)))


def show_workplan(scene, loaded, program=None) -> list:
    convert.remove_objects(PREFIX)
    frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
    objects = []
    box = block_of(loaded)
    if box is not None:
        (x0, y0, z0), (x1, y1, z1) = box
        vertices, faces = prism(np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]]), z1, z0)
        stock = convert.mesh_object(scene, f"{PREFIX} stock", vertices, faces, frame, (0.85, 0.72, 0.52, 1.0))
        stock.display_type = "WIRE"
        objects.append(stock)
    seen = set()
    for step in loaded.workingsteps:
        feature = step.its_feature
        if feature.id in seen:
            continue
        seen.add(feature.id)
        solid = feature_solid(feature)
        if solid is not None:
            objects.append(convert.mesh_object(scene, f"{PREFIX} {feature.its_id}", *solid, frame,
                                               FEATURE_COLOURS.get(type(feature).__name__, (0.7, 0.7, 0.7, 1.0))))
    if program is not None:
        objects += show_paths(scene, loaded, program)
    return objects


def shown_solids(scene, frame, depsgraph=None) -> dict:
    """The workplan's solids as shown in the scene (not the wire stock), read here on the main
    thread: {object name: (vertices in work mm, triangles, colour)}."""
    from . import preview

    return {o.name: preview.object_solid(o, frame, depsgraph) for o in scene.objects
            if o.name.startswith(PREFIX + " ") and o.type == "MESH" and o.display_type != "WIRE"}


def toolpaths_bytes(job: WorkplanJob, shown: dict) -> bytes:
    """Batch ``stepnc``'s toolpaths picture (``stepnc-toolpaths.png``) as PNG bytes: the program over
    the features' solids ``shown`` (:func:`shown_solids`), in the workplan's order."""
    from . import preview

    names = dict.fromkeys(f"{PREFIX} {step.its_feature.its_id}" for step in job.loaded.workingsteps)
    skipped = list(job.part.skipped)
    caption = ("NOT CUT: " + ", ".join(f"#{s['id']} {s['name']}" for s in skipped)) if skipped else ""
    return preview.toolpath_bytes(job.program.operations, job.part.stock, [shown[n] for n in names if n in shown],
                                  "STEP-NC: FEATURES AND TOOLPATHS", caption=caption)


def show_paths(scene, loaded, program) -> list:
    """The program's toolpaths as curve objects (one per operation and move kind)."""
    frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
    return pathview.show_toolpaths(scene, f"{PREFIX} path", program.operations, stock_box(loaded, program), frame)


def export_nc(scene, post_name: str, path: str, allow: bool | str = False, progress=None, profile=None,
              findings: list | None = None, read=None) -> tuple:
    """Convert the workplan, simulate it (the export gate) and write it: (path, the planned
    :class:`WorkplanJob`, gate's simulation job, gate report).  ``profile``: the machine (default:
    Machine & Stock's for the post); ``read``: as :func:`workplan_job`'s."""
    return export_nc_request(scene, post_name, path, allow, profile, findings, read)(progress)


def export_nc_request(scene, post_name: str, path: str, allow: bool | str = False, profile=None,
                      findings: list | None = None, read=None):
    """Read the scene (the workplan's file, Machine & Stock); ``compute(progress)`` plans, checks
    and writes as :func:`export_nc` says, without touching Blender data."""
    machine = scene.kezuri.machine
    profile = profile or scene_machine(machine, POST_FAMILIES, post_name)
    job = workplan_job(scene, profile, post_name, read)
    frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
    post = machine_post(POST_FAMILIES, post_name, machine.work_offset, machine.orient_spindle, profile)
    if post.needs_texture:
        raise posts.PostError(f"the {post.name} post writes textured engravings only; pick another post")

    def compute(progress=None) -> tuple:
        planning, checking = stages(progress)
        planned = WorkplanJob(plan_job(job, progress=planning).parts[0], frame)
        text = post.to_text(planned.program)
        checked, report = gate.check(simulation(planned), allow, checking, machine=post.machine)
        return write_program(path, text, post, findings), planned, checked, report
    return compute


def extension_for(post_name: str) -> str:
    return posts.extension(POST_FAMILIES, post_name)


def stepnc_request(scene, depsgraph):
    """Read the imported workplan and the list; ``compute(progress)`` converts it in the list's order."""
    job = workplan_job(scene)
    frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
    return lambda progress=None: WorkplanJob(plan_job(job, progress=progress).parts[0], frame)


def simulation(job: WorkplanJob) -> SimulationSetup:
    """The program on the workpiece's block; drills may break through its bottom by their point
    length and 2 mm (the workplan's through-hole rule), onto a spoil board."""
    return SimulationSetup(job.program, job.part.stock, {"fixture_clearance": job.part.result.fixture_clearance},
                           job.frame, "stepnc")


def pockets_part21(scene, depsgraph) -> str:
    """ISO 14649 text for the pockets modelled in the scene (outline objects marked as pockets,
    on the stock plate), roughed and finished with the STEP-NC panel's end mill."""
    settings = scene.kezuri
    check_group(settings.stepnc, "stepnc")
    plate = convert.plate_from_object(settings.stock.plate, depsgraph, scene, settings.stock.origin)
    specs = []
    for obj in sorted((o for o in scene.objects if o.kezuri_pocket.enabled), key=lambda o: o.name):
        loops = convert.outlines_in_work(obj, depsgraph, plate.frame)
        if len(loops) != 1:
            raise convert.SceneInputError(f"pocket {obj.name!r}: the outline must be one closed loop")
        check_group(obj.kezuri_pocket, "pocket", ["depth"], where=f"pocket {obj.name!r}")
        specs.append(stepnc.PocketSpec(obj.name, tuple(map(tuple, loops[0])), obj.kezuri_pocket.depth))
    if not specs:
        raise convert.SceneInputError("no pockets: mark closed outline objects as pockets (with a depth)")
    outline = np.vstack(plate.outline)
    (x0, y0), (x1, y1) = outline.min(axis=0), outline.max(axis=0)
    props = settings.stepnc
    tool = Tool(props.tool_number, "flat", props.tool_diameter, flute_length=props.flute_length, name="end mill")
    return stepnc.pockets_to_part21(((x0, y0, -plate.size[2]), (x1, y1, 0.0)), specs, tool, feed=props.feed,
                                    spindle_rpm=props.spindle_rpm, name=scene.name.upper())


def read_workplan(path: str):
    """(text, workplan) of an ISO 14649 file; an error in it (its syntax, or its data) names the
    file as the user gave it before the line, column or instance the reader names."""
    problem = refusal(path, path, "an ISO 14649 file")
    if problem:
        raise InputError(problem)
    try:
        text = read_text(path)
        return text, workplan_from_text(text)
    except InputError as error:
        raise InputError(named(path, str(error))) from error


class KEZURI_OT_import_stepnc(bpy.types.Operator, ImportHelper):
    """Import an ISO 14649 (STEP-NC) Part 21 file: stock, features and the workplan"""

    bl_idname = "kezuri.import_stepnc"
    bl_label = "Import ISO 14649"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".stp"
    filter_glob: StringProperty(default="*.stp;*.step;*.p21;*.stpnc;*.STP;*.P21;*.STPNC", options={"HIDDEN"})

    def execute(self, context):
        def work():
            loaded = read_workplan(self.filepath)[1]
            fill_workplan_list(context.scene, self.filepath, loaded)
            show_workplan(context.scene, loaded)
            for warning in loaded.warnings:
                self.report({"WARNING"}, translate_message(warning))
            steps, name = len(loaded.workingsteps), os.path.basename(self.filepath)
            self.report({"INFO"}, translate_message(f"{steps} workingsteps from {name}"))
            return {"FINISHED"}
        return run_reported(self, work)


class KEZURI_OT_stepnc_generate(SteppedOperator, bpy.types.Operator):
    """Convert the workplan, in the list's order, and show the toolpaths"""

    bl_idname = "kezuri.stepnc_generate"
    bl_label = "Generate Workplan Toolpaths"
    bl_options = {"REGISTER", "UNDO"}
    progress_label = "stepnc"

    @classmethod
    def poll(cls, context):
        if not len(context.scene.kezuri.stepnc.steps):
            cls.poll_message_set("Import an ISO 14649 file first")
            return False
        return True

    def prepare(self, context):
        return stepnc_request(context.scene, context.evaluated_depsgraph_get())

    def finish(self, context, job):
        program = job.program
        show_workplan(context.scene, job.loaded, program)
        for note in program.notes:
            self.report({"WARNING"}, translate_message(note))
        minutes = program.cycle_time() / 60
        self.report({"INFO"}, translate_message(f"{len(program.operations)} operations, about {minutes:.1f} min"))
        return {"FINISHED"}


class KEZURI_OT_stepnc_export(NCExport, bpy.types.Operator):
    """Write the G-code of the workplan, in the list's order, without the switched-off workingsteps"""

    bl_idname = "kezuri.stepnc_export"
    bl_label = "Export Workplan NC"
    bl_options = {"REGISTER"}

    filename_ext = ".nc"
    filter_glob: StringProperty(default="*.nc;*.ngc", options={"HIDDEN"})
    post: EnumProperty(name="Post", items=post_items(POST_FAMILIES, texture=False), default=post_number("fanuc"))
    post_families = POST_FAMILIES
    file_suffix = "-workplan"

    @classmethod
    def poll(cls, context):
        return KEZURI_OT_stepnc_generate.poll(context)

    def export_request(self, context, path):
        from .simview import result_bytes

        scene = context.scene       # the workplan's solids as shown, for the toolpaths picture (main thread)
        shown = shown_solids(scene, convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0)))
        findings = []
        profile = scene_machine(context.scene.kezuri.machine, POST_FAMILIES, self.post)
        compute = export_nc_request(context.scene, self.post, path, allow=context.scene.kezuri.simulation.acknowledged,
                                    profile=profile, findings=findings)
        label = posts.find(POST_FAMILIES, self.post).label

        def work(progress=None) -> Exported:
            written, planned, simulated, report = compute(progress)
            program = planned.program
            # the sheet as batch stepnc's: its notes are the program's (the workingsteps left out ...), its
            # pictures the toolpaths over the workplan's solids as shown and the simulated stock
            pictures = lambda: [("Toolpaths", toolpaths_bytes(planned, shown)),  # noqa: E731
                                ("Result", result_bytes(simulated, "stepnc"))]
            return Exported(written, None, findings,
                            sheet=ProgramSheet(program, report, profile, label, "stepnc", list(program.notes),
                                               pictures=pictures))
        return work


class KEZURI_OT_export_stepnc(bpy.types.Operator, ExportHelper):
    """Write the pockets modelled in Blender as an ISO 14649 (STEP-NC) Part 21 file"""

    bl_idname = "kezuri.export_stepnc"
    bl_label = "Export ISO 14649"
    bl_options = {"REGISTER"}

    filename_ext = ".stp"
    filter_glob: StringProperty(default="*.stp;*.p21", options={"HIDDEN"})

    def execute(self, context):
        def work():
            text = pockets_part21(context.scene, context.evaluated_depsgraph_get())
            path = write_atomic(self.filepath, text)
            self.report({"INFO"}, translate_message(f"Wrote {path}"))
            return {"FINISHED"}
        return run_reported(self, work)


class KEZURI_OT_workingstep_move(bpy.types.Operator):
    """Move the selected workingstep up or down in the workplan"""

    bl_idname = "kezuri.workingstep_move"
    bl_label = "Move Workingstep"
    bl_options = {"REGISTER", "UNDO"}

    direction: EnumProperty(items=[("UP", "Up", ""), ("DOWN", "Down", "")])

    @classmethod
    def poll(cls, context):
        return len(context.scene.kezuri.stepnc.steps) > 1

    def execute(self, context):
        props = context.scene.kezuri.stepnc
        index = props.active_step
        target = index - 1 if self.direction == "UP" else index + 1
        if not (0 <= index < len(props.steps) and 0 <= target < len(props.steps)):
            return {"CANCELLED"}
        props.steps.move(index, target)
        props.active_step = target
        return {"FINISHED"}


class KEZURI_UL_workingsteps(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_property, index=0, flt_flag=0):
        # feature · operation · tool (the full names and the instance number are in the file)
        row = layout.row(align=True)
        row.prop(item, "enabled", text="")
        row.label(text=f"{item.feature_name} · {iface(item.step)} · {item.tool}", translate=False)


def menu_import(self, context):
    self.layout.operator(KEZURI_OT_import_stepnc.bl_idname, text="ISO 14649 STEP-NC (.stp, .p21)")


def menu_export(self, context):
    self.layout.operator(KEZURI_OT_export_stepnc.bl_idname, text="ISO 14649 STEP-NC (.stp)")


CLASSES = (KEZURI_OT_import_stepnc, KEZURI_OT_stepnc_generate, KEZURI_OT_stepnc_export, KEZURI_OT_export_stepnc,
           KEZURI_OT_workingstep_move, KEZURI_UL_workingsteps)
MENUS = ((bpy.types.TOPBAR_MT_file_import, menu_import), (bpy.types.TOPBAR_MT_file_export, menu_export))


# ----- batch: ``batch.py stepnc`` ----------------------------------------------------------

def batch_arguments(p):
    p.add_argument("--input", help="ISO 14649 Part 21 file (.stp, .p21); default: a built-in two-pocket plate")
    p.add_argument("--post", choices=posts.choices(POST_FAMILIES, texture=False))
    orient_spindle_argument(p)
    machine_arguments(p)
    p.add_argument("--order", help="workingstep instance ids in the order to cut, e.g. 13,14,10 (default: "
                                   "the workplan's order); workingsteps left out are not cut")
    gate.allow_findings_argument(p)


def sample_file(out_dir: str) -> str:
    """A 120 x 80 x 20 mm plate with a rectangular and an L-shaped pocket, as ISO 14649, written
    as ``sample.stp`` into ``out_dir``."""
    pockets = [stepnc.PocketSpec("POCKET1", ((10, 10), (50, 10), (50, 40), (10, 40)), 8.0),
               stepnc.PocketSpec("POCKET2", ((65, 15), (110, 15), (110, 35), (85, 35), (85, 70), (65, 70)), 5.0)]
    text = stepnc.pockets_to_part21(((0, 0, -20), (120, 80, 0)), pockets, Tool(1, "flat", 6.0, flute_length=20.0),
                                    name="KEZURI SAMPLE PLATE")
    return write_atomic(os.path.join(out_dir, "sample.stp"), text)


def apply_order(scene, text: str, path: str) -> None:
    """``--order 13,14,10``: cut these workingsteps, in this order, and no others."""
    try:
        wanted = [int(v.strip().lstrip("#")) for v in text.split(",")]     # an empty item is a typo too
    except ValueError:
        raise convert.SceneInputError(f"--order: instance ids separated by commas, got {text!r}") from None
    twice = sorted({ident for ident in wanted if wanted.count(ident) > 1})
    if twice:   # before: the later mention silently moved it, so 13,14,10,13 cut 14, 10, 13
        raise convert.SceneInputError(f"--order: #{twice[0]} is given more than once in {text!r}; each workingstep "
                                      f"is cut once, in the order given")
    steps = scene.kezuri.stepnc.steps
    known = [item.ident for item in steps]
    for ident in wanted:
        if ident not in known:
            raise convert.SceneInputError(f"--order: #{ident} is not a workingstep of {path} ({known})")
    for target, ident in enumerate(wanted):
        steps.move([item.ident for item in steps].index(ident), target)
    for item in steps:
        item.enabled = item.ident in wanted


def batch(args) -> dict:
    from . import batchio, simview

    scene = batchio.open_blend(None)
    import shutil
    import tempfile

    staging = None
    if args.input:
        path = args.input
    else:   # the sample goes into --out only with the program: nothing is written before the job is checked
        staging = tempfile.mkdtemp(prefix="kezuri-stepnc-")
        path = sample_file(staging)
    from .common import Progress
    post_name = args.post or "fanuc"
    batch_orient_spindle(args, scene, POST_FAMILIES, post_name)
    profile = batch_machine(args, scene, POST_FAMILIES, post_name)
    findings = []
    try:
        problem = refusal(f"--input {path}", path)
        if problem:
            raise InputError(problem)
        text, loaded = read_workplan(path)      # read once: the plan takes it (a big file reads in seconds)
        fill_workplan_list(scene, os.path.abspath(path), loaded)
        if args.order:
            apply_order(scene, args.order, path if staging is None else "the built-in sample")
        nc_path, job, checked, gate_report = export_nc(
            scene, post_name, os.path.join(args.out, f"stepnc{extension_for(post_name)}"), args.allow_findings,
            Progress(None, "check"), profile, findings, (text, loaded))
        if staging is not None:
            path = sample_file(args.out)
            # the scene points at the kept copy where it will be once the run's files move into --out
            final = getattr(args, "final", None)
            scene.kezuri.stepnc.filepath = os.path.abspath(final(path) if final is not None else path)
    finally:
        if staging is not None:
            shutil.rmtree(staging, ignore_errors=True)
    program = job.program
    show_workplan(scene, job.loaded)
    shown = shown_solids(scene, job.frame, bpy.context.evaluated_depsgraph_get())   # before the paths' tubes
    show_paths(scene, job.loaded, program)
    toolpaths_png = write_atomic(os.path.join(args.out, "stepnc-toolpaths.png"), toolpaths_bytes(job, shown))
    simulation_report, png = simview.batch_simulation(scene, simulation(job), args.out, "stepnc", checked)
    steps = {step.id: step for step in job.loaded.workingsteps}
    workingsteps = []
    for op in program.operations:
        entry = describe_step(steps[op.source_id])
        entry.update(tool=op.tool.describe(), moves=len(op))
        workingsteps.append(entry)
    report = {
        "gate": gate_report,
        "workflow": "stepnc",
        "simulation": simulation_report,
        "toolpaths_preview": toolpaths_png,
        "input": os.path.abspath(path),
        "post": post_name,
        "machine": profile.summary(),
        "files": [nc_path],
        "preview": png,
        "workingsteps": workingsteps,
        "skipped_workingsteps": list(job.part.skipped),
        "operations": program.summary(),
        "warnings": list(program.notes),
        "cycle_time_s": round(program.cycle_time(), 1),
    }
    warn(findings, report)
    return report


WORKFLOW = Workflow(
    "STEPNC", "STEP-NC Workplan", "The imported ISO 14649 workplan", classes=CLASSES, menus=MENUS,
    post_families=POST_FAMILIES, request=stepnc_request, simulation=simulation, button="STEP-NC",
    kind="stepnc", job_operation=job_operation,
    commands=(BatchCommand("stepnc", "ISO 14649 (STEP-NC) workplan to G-code (W3)", batch_arguments, batch),))
