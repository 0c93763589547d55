"""W2 in Blender: pockets on a rotating table (CNC wood lathe), C-X-Z.

The block is the stock object (its top centre is on the rotation axis); each pocket is an
object whose Kezuri pocket settings are on (Object properties > Kezuri Pocket, or the Rotary
Pockets panel): its outline (a closed curve or mesh), depth, wall angle and bottom.
``run_rotary`` is the job function shared by the operators, batch.py and the tests.
"""
from __future__ import annotations

import dataclasses

import os
import time
from dataclasses import dataclass

import bpy
from bpy.props import EnumProperty, StringProperty

from .. import post as posts
from ..toolpath.operations.rotary import rotary as core
from ..toolpath.ir.program import Tool
from ..toolpath.job import Job, JobOperation, Setup, plan_job
from ..toolpath.operations.rotary.kind import RotaryGeometry
from . import convert
from . import gate
from . import pathview
from .common import SteppedOperator
from .exporting import Exported, NCExport, ProgramSheet, stages, warn, write_program
from .machines import batch_machine, machine_arguments, scene_machine
from .limits import check_group
from .plancache import cache_of, keep
from .properties import post_items, post_number
from .translations import translate_message
from .workflow import BatchCommand, SimulationSetup, Workflow

PREFIX = "Kezuri Rotary"
POST_FAMILIES = ("cxz",)


@dataclass
class RotaryJob:
    result: core.RotaryResult
    settings: core.RotarySettings
    frame: convert.WorkFrame
    block: core.Block
    stock: object               # the job's part's stock: the block, its top centre on the axis
    replanned: tuple = ()       # the operations planned by this call (the rest were Generate's)


def settings_from(props) -> core.RotarySettings:
    check_group(props, "rotary")
    props = convert.Typed(props)
    return core.RotarySettings(
        tool=Tool(props.tool_number, "ball", props.tool_diameter, flute_length=props.flute_length,
                  name="pencil bit"),
        spindle_rpm=props.spindle_rpm, cutting_speed=props.cutting_speed, plunge_speed=props.plunge_speed,
        spacing=props.spacing, stepover=props.stepover, step_down=props.step_down, allowance=props.allowance,
        wall_stepover=props.wall_stepover, max_table_rpm=props.max_table_rpm)


def pocket_objects(scene) -> list:
    return sorted((o for o in scene.objects if o.kezuri_pocket.enabled), key=lambda o: o.name)


def rotary_operation(scene, depsgraph, name: str = "rotary"):
    """Read the block, the pockets and the settings: (the job operation, the job's setup, the
    block's frame, the block)."""
    settings = scene.kezuri
    check_group(settings.machine, "machine")
    check_group(settings.rotary, "rotary")
    plate = convert.plate_from_object(settings.stock.plate, depsgraph, scene, "CENTER")
    size_x, size_y, thickness = plate.size
    block = core.Block(size_x, size_y, thickness)
    pockets = []
    for obj in pocket_objects(scene):
        loops = convert.outlines_in_work(obj, depsgraph, plate.frame)
        if len(loops) != 1:
            raise convert.SceneInputError(f"pocket {obj.name!r}: the outline must be one closed loop, "
                                          f"found {len(loops)}")
        props = obj.kezuri_pocket
        check_group(props, "pocket", where=f"pocket {obj.name!r}")
        pockets.append(core.Pocket(obj.name, loops[0], props.depth, props.wall_angle, props.bottom,
                                   props.sphere_radius if props.bottom == "sphere" else None))
    if not pockets:
        raise convert.SceneInputError("no pockets: mark outline objects as pockets in the Rotary Pockets panel")
    rotary_settings = settings_from(settings.rotary)
    setup = Setup(name=scene.name, post=settings.rotary.post, work_offset=settings.machine.work_offset,
                  rapid_rate=settings.machine.rapid_rate)
    operation = JobOperation("rotary", name, rotary_settings, RotaryGeometry(block, tuple(pockets)))
    return operation, setup, plate.frame, block


def rotary_request(scene, depsgraph):
    """Read the scene (:func:`rotary_operation`); return ``compute(progress)``, which plans
    without touching Blender data (so it can run in steps)."""
    operation, setup, frame, block = rotary_operation(scene, depsgraph)
    job = Job(setup, (operation,))
    cache = cache_of(scene)

    def compute(progress=None) -> RotaryJob:
        planned = plan_job(job, cache, progress=progress)
        keep(cache, planned)
        part = planned.parts[0]
        return RotaryJob(part.result, operation.settings, frame, block, part.stock, tuple(planned.replanned()))
    return compute


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's rotary pockets: object ``block`` (the board; the pockets are the scene's objects
    marked as pockets), the Rotary Pockets panel's settings by name."""
    from .jobentry import JobFileError, apply_settings

    for slot, obj in entry.objects.items():
        if slot != "block":
            raise JobFileError(f"{entry.where}: objects.{slot}: rotary pockets take objects.block (the board)")
        scene.kezuri.stock.plate = obj
    apply_settings(scene.kezuri.rotary, entry)
    operation, setup, frame, _ = rotary_operation(scene, depsgraph, entry.name)
    return dataclasses.replace(operation, enabled=entry.enabled), setup, frame


def run_rotary(scene, depsgraph, progress=None) -> RotaryJob:
    return rotary_request(scene, depsgraph)(progress)


def show_rotary(scene, job: RotaryJob) -> list:
    """Replace the previous preview with each pocket's toolpaths, back in the part frame."""
    convert.remove_objects(PREFIX)
    pockets = job.result.pockets
    return pathview.show_toolpaths(scene, PREFIX, [p.operation for p in pockets], simulation(job).stock, job.frame,
                                   names=[p.pocket.name for p in pockets])


def extension_for(post_name: str) -> str:
    return posts.extension(POST_FAMILIES, post_name)


def toolpaths_bytes(job: RotaryJob) -> bytes:
    """The toolpaths picture batch ``rotary`` draws (``rotary-toolpaths.png``), as PNG bytes."""
    from . import preview

    return preview.toolpath_bytes(job.result.program.operations, simulation(job).stock, [],
                                  "ROTARY TABLE C-X-Z: TOOLPATHS (PART FRAME)")


def sheet_pictures(job: RotaryJob, simulated=None) -> list:
    """The setup sheet's pictures as batch ``rotary`` draws them: [(caption, PNG bytes)], the
    toolpaths and, with the gate's ``simulated`` job, the simulated stock."""
    from . import simview

    return simview.sheet_pictures(toolpaths_bytes(job), simulated, "rotary")


def export_rotary(job: RotaryJob, post_name: str, path: str, allow: bool | str = False, checked: bool = False,
                  machine=None, findings: list | None = None, progress=None, sheet: dict | None = None) -> str:
    """Write the program; the export gate simulates it first unless the caller has (``checked``);
    ``machine``: the machine profile (None: the post's own); ``progress``: the gate's; ``sheet``:
    filled with the gate's ``gate`` report and the ``machine`` (the setup sheet's)."""
    post = posts.create(POST_FAMILIES, post_name, work_offset=job.result.program.work_offset,
                        max_table_rpm=job.settings.max_table_rpm, **({} if machine is None else {"machine": machine}))
    text = post.to_text(job.result.program)
    simulated, report = None, None
    if not checked:
        simulated, report = gate.check(simulation(job), allow, progress, machine=post.machine)
    if sheet is not None:
        sheet.update(gate=report, machine=post.machine, pictures=lambda: sheet_pictures(job, simulated))
    return write_program(path, text, post, findings)


def nc_export_request(scene, depsgraph, post_name: str, target: str):
    """The panel's export: read the scene here; ``work(progress) -> Exported`` plans, checks and
    writes ``target`` without touching Blender data (so it runs in steps, Esc cancelling)."""
    from .workflowfeeds import panel_check

    compute = rotary_request(scene, depsgraph)
    allow = scene.kezuri.simulation.acknowledged
    profile = scene_machine(scene.kezuri.machine, POST_FAMILIES, post_name)
    feeds_check, label = panel_check(scene), posts.find(POST_FAMILIES, post_name).label

    def work(progress=None) -> Exported:
        planning, checking = stages(progress)
        job, findings, sheet = compute(planning), [], {}
        written = export_rotary(job, post_name, target, allow=allow, machine=profile, findings=findings,
                                progress=checking, sheet=sheet)
        feeds = feeds_check(job.result.program, sheet["machine"], findings)
        return Exported(written, job.replanned, findings,
                        sheet=ProgramSheet(job.result.program, sheet["gate"], sheet["machine"], label, "rotary",
                                           [], feeds, sheet["pictures"]))
    return work


def simulation(job: RotaryJob) -> SimulationSetup:
    """The C-X-Z program on the block (its top centre on the table's axis)."""
    return SimulationSetup(job.result.program, job.stock, {}, job.frame, "rotary")


class KEZURI_OT_rotary_generate(SteppedOperator, bpy.types.Operator):
    """Plan the roughing, wall finishing and bottom spirals of every pocket, in C-X-Z"""

    bl_idname = "kezuri.rotary_generate"
    bl_label = "Generate Rotary Pockets"
    bl_options = {"REGISTER", "UNDO"}
    progress_label = "rotary"

    @classmethod
    def poll(cls, context):
        if context.scene.kezuri.stock.plate is None:
            cls.poll_message_set("Pick the block (stock) object first")
            return False
        return True

    def prepare(self, context):
        return rotary_request(context.scene, context.evaluated_depsgraph_get())

    def finish(self, context, job):
        show_rotary(context.scene, job)
        minutes, seconds = divmod(int(round(job.result.cycle_time_s)), 60)
        self.report({"INFO"}, translate_message(f"{len(job.result.pockets)} pockets planned; estimated cycle time "
                              f"{minutes} min {seconds:02d} s"))
        return {"FINISHED"}


class KEZURI_OT_rotary_export(NCExport, bpy.types.Operator):
    """Write the C-X-Z program for the wood lathe"""

    bl_idname = "kezuri.rotary_export"
    bl_label = "Export Rotary NC"
    bl_options = {"REGISTER"}

    filename_ext = ".ngc"
    filter_glob: StringProperty(default="*.ngc;*.nc", options={"HIDDEN"})
    post: EnumProperty(name="Post", items=post_items(POST_FAMILIES), default=post_number("linuxcnc"))
    post_families = POST_FAMILIES
    file_suffix = "-rotary"

    @classmethod
    def poll(cls, context):
        return KEZURI_OT_rotary_generate.poll(context)

    def preferred_post(self, context):
        return context.scene.kezuri.rotary.post          # the Rotary Pockets panel's post

    def export_request(self, context, path):
        return nc_export_request(context.scene, context.evaluated_depsgraph_get(), self.post, path)


class KEZURI_OT_mark_pocket(bpy.types.Operator):
    """Mark the selected outline objects as rotary pockets (or unmark them)"""

    bl_idname = "kezuri.mark_pocket"
    bl_label = "Mark as Pocket"
    bl_options = {"REGISTER", "UNDO"}

    enable: bpy.props.BoolProperty(name="Pocket", default=True)

    @classmethod
    def poll(cls, context):
        if not any(o.type in {"MESH", "CURVE"} for o in context.selected_objects):
            cls.poll_message_set("Select closed curves or meshes that outline the pockets")
            return False
        return True

    def execute(self, context):
        count = 0
        for obj in context.selected_objects:
            if obj.type in {"MESH", "CURVE"} and obj != context.scene.kezuri.stock.plate:
                obj.kezuri_pocket.enabled = self.enable
                count += 1
        self.report({"INFO"},
                    translate_message(f"{count} object(s) {'marked as' if self.enable else 'no longer'} pockets"))
        return {"FINISHED"}


CLASSES = (KEZURI_OT_rotary_generate, KEZURI_OT_rotary_export, KEZURI_OT_mark_pocket)


# ----- batch: ``batch.py rotary`` ----------------------------------------------------------

def batch_arguments(p):
    from . import workflowfeeds
    p.add_argument("--blend", help="a .blend with the block as Kezuri stock and pocket outlines marked")
    p.add_argument("--post", choices=posts.choices(POST_FAMILIES))
    machine_arguments(p)
    workflowfeeds.material_argument(p)
    gate.allow_findings_argument(p)


def batch(args) -> dict:
    from . import workflowfeeds
    from . import batchio, preview, samples, simview
    from .common import Progress

    scene = batchio.open_blend(args.blend)
    if not args.blend:
        samples.rotary_block(scene)
    workflowfeeds.batch_material(args, scene)      # a bad --material refused before planning
    post_name = args.post or scene.kezuri.rotary.post
    machine = batch_machine(args, scene, POST_FAMILIES, post_name)
    started = time.perf_counter()
    job = run_rotary(scene, bpy.context.evaluated_depsgraph_get(), Progress(None, "rotary"))
    seconds = time.perf_counter() - started
    checked, gate_report = gate.check(simulation(job), args.allow_findings, Progress(None, "check"), machine=machine)
    findings = []
    nc_path = export_rotary(job, post_name, os.path.join(args.out, f"rotary{extension_for(post_name)}"), checked=True,
                            machine=machine, findings=findings)
    if batchio.shown():
        show_rotary(scene, job)
    from ..post.output import write_atomic
    toolpaths_png = write_atomic(os.path.join(args.out, "rotary-toolpaths.png"), toolpaths_bytes(job))
    simulation_report, png = simview.batch_simulation(scene, simulation(job), args.out, "rotary", checked)
    report = {
        "gate": gate_report,
        "simulation": simulation_report,
        "toolpaths_preview": toolpaths_png,
        "workflow": "rotary",
        "post": post_name,
        "machine": machine.summary(),
        "files": [nc_path],
        "preview": png,
        "toolpath_seconds": round(seconds, 3),
        "cycle_time_s": job.result.cycle_time_s,
        "operations": job.result.program.summary(),
        "pockets": job.result.reports,
    }
    workflowfeeds.check(args, scene, job.result.program, machine, report, findings)
    warn(findings, report)
    return report


WORKFLOW = Workflow(
    "ROTARY", "Rotary Pockets", "The pockets on the rotating table", classes=CLASSES, post_families=POST_FAMILIES,
    request=rotary_request, simulation=simulation, button="Rotary", kind="rotary", job_operation=job_operation,
    commands=(BatchCommand("rotary", "pockets on a rotating table, C-X-Z (W2)", batch_arguments, batch),))
