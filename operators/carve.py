"""Carving 3-D surfaces in Blender: the design mesh, Z-level roughing and a ball finishing raster.

The design is a mesh object (a relief, a domed plate, any mesh), taken in world coordinates
converted to millimetres: the work zero is the scene's origin, so model the design with its top
at Z 0 (the stock top) as the samples are.  The stock is the design's box, from its lowest
point up to its highest plus "Stock Above".
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from types import SimpleNamespace

import bpy
import numpy as np
from bpy.props import EnumProperty, StringProperty

from .. import post as posts
from ..toolpath.operations.carve import carve as core
from ..toolpath.operations.carve import carve_samples
from ..toolpath.engines import meshdata, meshfile
from ..toolpath.ir.program import Tool
from ..toolpath.simulate import BoxStock
from ..toolpath.job import Job, JobOperation, Setup, plan_job
from ..toolpath.operations.carve.kind import CarveGeometry
from . import convert
from . import gate
from . import pathview
from .common import SteppedOperator, run_reported
from .exporting import Exported, NCExport, stages, batch_orient_spindle, milling_export_request, machine_post, orient_spindle_argument, warn, write_program
from .machines import batch_machine, machine_arguments, scene_machine
from .limits import check_group
from .plancache import cache_of, keep
from .preferences import scene_post
from .properties import post_items, post_number
from .translations import translate_message
from .workflow import BatchCommand, SimulationSetup, Workflow

POST_FAMILIES = ("milling",)

PREFIX = "Kezuri Carve"


@dataclass
class CarveJob:
    result: core.CarveResult
    vertices: np.ndarray          # the design in work mm
    faces: np.ndarray             # its triangles
    frame: convert.WorkFrame
    seconds: float
    replanned: tuple = ()         # the operations planned by this call (the rest were Generate's)


def settings_from(props) -> core.CarveSettings:
    check_group(props, "carve")
    props = convert.Typed(props)
    return core.CarveSettings(
        rough_tool=Tool(props.rough_tool_number, "flat", props.rough_diameter, name="roughing"),
        finish_tool=Tool(props.finish_tool_number, "ball", props.finish_diameter, name="finishing"),
        rough=props.rough, allowance=props.allowance, step_down=props.step_down,
        rough_stepover=props.rough_stepover, scallop=props.scallop, raster_angle=props.raster_angle,
        max_slope_deg=props.max_slope, steep_cleanup=props.steep_cleanup, wall_pass=props.wall_pass,
        sample_spacing=props.sample_spacing, rough_rpm=props.rough_rpm,
        finish_rpm=props.finish_rpm, rough_feed=props.rough_feed, finish_feed=props.finish_feed,
        plunge_feed=props.plunge_feed, clearance=props.clearance, safe_z=props.safe_z)


def design_mesh(scene, depsgraph) -> tuple:
    """The Carve panel's design as triangles in work mm: (vertices, faces, frame)."""
    obj = scene.kezuri.carve.design
    if obj is not None and convert.is_instancer(obj):
        world, polygons = convert.instanced_mesh_arrays(obj, depsgraph)
    elif obj is None or obj.type != "MESH":
        raise convert.SceneInputError("pick the design (a mesh) in the Carve panel")
    else:
        world, polygons, _ = convert.evaluated_mesh_arrays(obj, depsgraph)
    if not polygons:
        raise convert.SceneInputError(f"design {obj.name!r} has no faces")
    frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
    work = frame.to_work(world)
    if np.isfinite(work).all():
        convert.check_design_fits(obj.name, np.ptp(work, axis=0), scene)
    faces, _ = meshdata.triangulated(polygons)
    return work, faces, frame


def run_on_mesh(vertices, faces, settings: core.CarveSettings, frame, stock_above: float = 0.0, name="carve",
                work_offset="G54", rapid_rate=5000.0, progress=None, cache: dict | None = None) -> CarveJob:
    """Plan (timed) without touching Blender data: a job of one carving operation; ``cache``: the
    scene's plans (:mod:`.plancache`), None to plan afresh."""
    setup = Setup(name=name, work_offset=work_offset, rapid_rate=rapid_rate)
    geometry = CarveGeometry(np.asarray(vertices), np.asarray(faces), float(stock_above))
    planned = plan_job(Job(setup, (JobOperation("carve", "carve", settings, geometry),)), cache, progress=progress)
    if cache is not None:
        keep(cache, planned)
    part = planned.parts[0]
    return CarveJob(part.result.result, part.result.vertices, part.result.faces, frame, part.seconds,
                    tuple(planned.replanned()))


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's carving: object ``design`` (the mesh), the Carve panel's settings by name."""
    from .jobentry import JobFileError, apply_settings

    props = scene.kezuri.carve
    for slot, obj in entry.objects.items():
        if slot != "design":
            raise JobFileError(f"{entry.where}: objects.{slot}: a carving takes objects.design (the mesh)")
        props.design = obj
    apply_settings(props, entry)
    vertices, faces, frame = design_mesh(scene, depsgraph)
    machine = scene.kezuri.machine
    check_group(machine, "machine")
    geometry = CarveGeometry(np.asarray(vertices), np.asarray(faces), float(props.stock_above))
    setup = Setup(name=scene.name, post=post_name, machine=scene_machine(machine, POST_FAMILIES, post_name),
                  work_offset=machine.work_offset, rapid_rate=machine.rapid_rate)
    return JobOperation("carve", entry.name, settings_from(props), geometry, entry.enabled), setup, frame


def carve_request(scene, depsgraph):
    """Read the design and the settings; return ``compute(progress)``, which plans the job
    without touching Blender data (so it can run in steps)."""
    props = scene.kezuri.carve
    vertices, faces, frame = design_mesh(scene, depsgraph)
    settings, name, above = settings_from(props), scene.name, props.stock_above
    machine = scene.kezuri.machine
    check_group(machine, "machine")
    offset, rate = machine.work_offset, machine.rapid_rate
    cache = cache_of(scene)
    return lambda progress=None: run_on_mesh(vertices, faces, settings, frame, above, name, offset, rate, progress,
                                             cache)


def run_carve(scene, depsgraph, progress=None) -> CarveJob:
    return carve_request(scene, depsgraph)(progress)


def show_carve(scene, job: CarveJob) -> list:
    """Replace the previous carving preview with this job's toolpaths."""
    convert.remove_objects(PREFIX)
    return pathview.show_toolpaths(scene, PREFIX, job.result.program.operations, job.result.stock, job.frame,
                                   tube_mm=0.15)


def toolpaths_bytes(job: CarveJob) -> bytes:
    """The toolpaths picture batch ``carve`` draws (``carve-toolpaths.png``), as PNG bytes."""
    from . import preview

    return preview.toolpath_bytes(job.result.program.operations, simulation(job).stock,
                                  [(job.vertices, job.faces, preview.picture_jobs.PART_COLOUR)],
                                  "CARVING: TOOLPATHS OVER THE DESIGN")


def sheet_pictures(job: CarveJob, simulated=None) -> list:
    """The setup sheet's pictures as batch ``carve`` draws them: [(caption, PNG bytes)], the
    toolpaths and, with the gate's ``simulated`` job, the simulated stock."""
    from . import preview

    pictures = [("Toolpaths", toolpaths_bytes(job))]
    if simulated is not None:
        pictures.append(("Result", preview.simulation_bytes(simulated.result, "CARVING: SIMULATED STOCK",
                                                            mesh=simulated.result.mesh(250_000))))
    return pictures


def export_carve(job: CarveJob, post_name: str, path: str, work_offset: str | None = None,
                 allow: bool | str = False, checked: bool = False, orient_spindle: bool = False,
                 machine=None, findings: list | None = None, progress=None, sheet: dict | None = None) -> str:
    """Write the program; the export gate simulates it first unless the caller has (``checked``);
    ``orient_spindle``: M19 before each tool change (Fanuc posts only); ``machine``: the machine
    profile (None: the post's own); ``progress``: the gate's (returning False cancels); ``sheet``:
    filled with what the setup sheet shows (:func:`.exporting.milling_export_request`)."""
    post = machine_post(POST_FAMILIES, post_name, work_offset, orient_spindle, machine)
    text = post.to_text(job.result.program)
    simulated, report = None, None
    if not checked:
        simulated, report = gate.check(simulation(job), allow, progress, machine=post.machine)
    if sheet is not None:
        sheet.update(program=job.result.program, gate=report, machine=post.machine,
                     warnings=list(job.result.warnings), pictures=lambda: sheet_pictures(job, simulated))
    return write_program(path, text, post, findings)


def nc_export_request(scene, depsgraph, post_name: str, target: str):
    """The panel's export: read the scene here; ``work(progress) -> Exported`` plans, checks and
    writes ``target`` without touching Blender data (so it runs in steps, Esc cancelling)."""
    return milling_export_request(scene, post_name, target, POST_FAMILIES, carve_request(scene, depsgraph),
                                  export_carve, "carve")


def extension_for(post_name: str) -> str:
    return posts.extension(POST_FAMILIES, post_name)


def simulation(job: CarveJob) -> SimulationSetup:
    """The program on the design's box, checked against the design mesh."""
    x0, y0, z0, x1, y1, z1 = job.result.stock
    return SimulationSetup(job.result.program, BoxStock(x0, y0, z0, x1, y1, z1),
                           {"design": SimpleNamespace(vertices=job.vertices, faces=job.faces)}, job.frame, "carve")


def add_sample(scene, sample: str = "wave"):
    """The built-in design (``carve_samples.SAMPLES``) as a mesh object, set as the design."""
    vertices, faces = carve_samples.SAMPLES[sample]()
    frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
    mesh = bpy.data.meshes.new(f"Carve sample ({sample})")
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", frame.to_world(vertices).astype(np.float32).ravel())
    mesh.loops.add(3 * len(faces))
    mesh.loops.foreach_set("vertex_index", np.asarray(faces, np.int32).ravel())
    mesh.polygons.add(len(faces))
    mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * len(faces), 3, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(len(faces), 3, np.int32))
    mesh.update()
    obj = bpy.data.objects.new(mesh.name, mesh)
    obj.color = (0.85, 0.72, 0.52, 1.0)
    scene.collection.objects.link(obj)
    scene.kezuri.carve.design = obj
    return obj


def _poll_design(cls, context) -> bool:
    design = context.scene.kezuri.carve.design
    if design is None or design.type != "MESH":
        cls.poll_message_set("Pick the design (a mesh) in the Carve panel")
        return False
    return True


class KEZURI_OT_carve_generate(SteppedOperator, bpy.types.Operator):
    """Plan the Z-level roughing and the ball finishing raster over the design mesh, and show the toolpaths"""

    bl_idname = "kezuri.carve_generate"
    bl_label = "Generate Carving"
    bl_options = {"REGISTER", "UNDO"}
    progress_label = "carve"

    @classmethod
    def poll(cls, context):
        return _poll_design(cls, context)

    def prepare(self, context):
        return carve_request(context.scene, context.evaluated_depsgraph_get())

    def finish(self, context, job):
        show_carve(context.scene, job)
        for warning in job.result.warnings:
            self.report({"WARNING"}, translate_message(warning))
        program = job.result.program
        self.report({"INFO"}, translate_message(
            f"Carving planned: {sum(len(op) for op in program.operations)} moves, stepover "
            f"{job.result.stepover:.3f} mm, about {program.cycle_time() / 60:.1f} min"))
        if job.result.cleanup_stepover is not None:
            self.report({"INFO"}, translate_message(
                f"Steep cleanup: {job.result.steep_area_mm2:.0f} mm2 of faces steeper than "
                f"{context.scene.kezuri.carve.max_slope:g} degrees across the raster, cut again across it at a "
                f"{job.result.cleanup_stepover:.3f} mm stepover"))
        walls = job.result.walls
        if walls is not None and walls.operation is not None:
            self.report({"INFO"}, translate_message(
                f"Wall pass: waterlines {walls.z_step:.3f} mm apart in Z on {job.result.wall_area_mm2:.0f} mm2 of "
                f"walls, {len(walls.levels)} levels, scallop {walls.scallop:.4f} mm on the least steep wall"))
        return {"FINISHED"}


class KEZURI_OT_carve_sample(bpy.types.Operator):
    """Add a built-in design (a wave relief or a domed plate, in mm) and pick it as the design"""

    bl_idname = "kezuri.carve_sample"
    bl_label = "Add Sample Design"
    bl_options = {"REGISTER", "UNDO"}

    sample: EnumProperty(name="Sample", items=[
        ("wave", "Wave Relief", "A 120 x 80 mm plate with a wave on top"),
        ("dome", "Domed Plate", "A 160 x 60 mm domed name plate with a raised ring"),
        ("ridge", "Steep Ridge", "A 100 x 60 mm plate with a ridge along X, its flanks sloping 55 degrees"),
        ("walls", "Walled Block", "An 80 x 60 mm plate with a raised block and a pocket, their walls one 0.5 mm grid "
                                  "cell wide (a height-image relief)"),
        ("block", "Vertical Block", "The same block and pocket with vertical walls")])

    def execute(self, context):
        def work():
            add_sample(context.scene, self.sample)
            return {"FINISHED"}
        return run_reported(self, work)


class KEZURI_OT_carve_export(NCExport, bpy.types.Operator):
    """Write the carving NC program for the chosen controller"""

    bl_idname = "kezuri.carve_export"
    bl_label = "Export Carving NC"
    bl_options = {"REGISTER"}

    filename_ext = ".nc"
    filter_glob: StringProperty(default="*.nc;*.ngc;*.tap", options={"HIDDEN"})
    post: EnumProperty(name="Post", items=post_items(POST_FAMILIES), default=post_number("fanuc"))

    @classmethod
    def poll(cls, context):
        return _poll_design(cls, context)

    file_suffix = "-carve"

    def export_request(self, context, path):
        return nc_export_request(context.scene, context.evaluated_depsgraph_get(), self.post, path)


CLASSES = (KEZURI_OT_carve_generate, KEZURI_OT_carve_sample, KEZURI_OT_carve_export)


# ----- batch: ``batch.py carve`` -------------------------------------------------------------

def batch_arguments(p):
    from . import workflowfeeds
    import argparse

    source = p.add_mutually_exclusive_group()
    source.add_argument("--blend", help="a .blend whose Carve panel names the design mesh")
    source.add_argument("--mesh", help="an STL/OBJ/PLY of the design in mm (work zero: its origin)")
    source.add_argument("--sample", choices=sorted(carve_samples.SAMPLES), help="a built-in design (default: wave)")
    p.add_argument("--post", choices=posts.choices(POST_FAMILIES))
    orient_spindle_argument(p)
    machine_arguments(p)
    from .batchio import number
    from .limits import RANGES
    p.add_argument("--scallop", type=number("--scallop", limit=RANGES["carve"]["scallop"]),
                   help="scallop height in mm the finishing may leave")
    p.add_argument("--angle", type=number("--angle", limit=RANGES["carve"]["raster_angle"]),
                   help="finishing raster angle in degrees")
    p.add_argument("--max-slope", type=number("--max-slope", limit=RANGES["carve"]["max_slope"]),
                   help="the finishing stepover allows for slopes up to this across the raster (degrees)")
    p.add_argument("--steep-cleanup", action=argparse.BooleanOptionalAction, default=None,
                   help="cut the faces steeper than the max slope again across the raster (default: the scene's "
                        "setting, on)")
    p.add_argument("--wall-pass", action=argparse.BooleanOptionalAction, default=None,
                   help="finish the walls no raster finishes (vertical, or steeper than the max slope across both "
                        "rasters) by waterlines (default: the scene's setting, on)")
    workflowfeeds.material_argument(p)
    gate.allow_findings_argument(p)


def read_mesh_file(path: str, option: str = "--mesh") -> tuple:
    """Vertices (mm) and triangles of an STL/OBJ/PLY design (:func:`meshfile.read_mesh`), checked
    as a design; what is wrong with it is said naming ``option`` and the file."""
    vertices, faces = meshfile.read_mesh(path, option)
    try:
        return core.check_mesh(vertices, faces)
    except core.CarveError as error:
        if option == "--surface":
            raise core.CarveError(f"--surface {path}: {error}") from None
        raise core.CarveError(f"--mesh {path}: {error}") from None


def wall_report(result: core.CarveResult, props) -> dict:
    """report.json's ``wall_pass``: what the walls are and what their pass does."""
    from . import batchio

    walls = result.walls
    out = {"on": bool(props.wall_pass), "wall_area_mm2": round(result.wall_area_mm2, 1),
           "raster_slope_deg": round(result.raster_slope_deg, 3)}
    if walls is None or walls.operation is None:
        return out
    summary = result.program.summary()[result.program.operations.index(walls.operation)]
    return {**out, "moves": summary["moves"], "cycle_time_s": summary["cycle_time_s"],
            "feed_length_mm": summary["feed_length_mm"], "z_step_mm": round(walls.z_step, 5),
            "levels": len(walls.levels), "tip_z_range_mm": batchio.rounded([walls.levels[0], walls.levels[-1]], 4),
            "shallowest_wall_deg": round(walls.shallowest_deg, 3), "links_along_wall": walls.links,
            "scallop_closed_form_mm": round(walls.scallop, 5)}


def batch(args) -> dict:
    from . import workflowfeeds
    from . import batchio, preview, simview
    from .common import Progress

    scene = batchio.open_blend(args.blend)
    workflowfeeds.batch_material(args, scene)      # a bad --material refused before planning
    props = scene.kezuri.carve
    if args.scallop is not None:
        batchio.set_exactly(props, "scallop", args.scallop, "--scallop")
    if args.angle is not None:
        batchio.set_exactly(props, "raster_angle", args.angle, "--angle")
    if args.max_slope is not None:
        batchio.set_exactly(props, "max_slope", args.max_slope, "--max-slope")
    if args.steep_cleanup is not None:
        props.steep_cleanup = args.steep_cleanup
    if args.wall_pass is not None:
        props.wall_pass = args.wall_pass
    machine = scene.kezuri.machine
    post_name = args.post or scene_post(scene)
    batch_orient_spindle(args, scene, POST_FAMILIES, post_name)
    profile = batch_machine(args, scene, POST_FAMILIES, post_name)
    if args.mesh:
        vertices, faces = read_mesh_file(args.mesh)
        frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
        job = run_on_mesh(vertices, faces, settings_from(props), frame, props.stock_above,
                          os.path.splitext(os.path.basename(args.mesh))[0], machine.work_offset, machine.rapid_rate,
                          Progress(None, "carve"))
    else:
        if not args.blend:
            add_sample(scene, args.sample or "wave")
        job = run_carve(scene, bpy.context.evaluated_depsgraph_get(), Progress(None, "carve"))
    nc_path = os.path.join(args.out, f"carve{extension_for(post_name)}")
    simulated, gate_report = gate.check(simulation(job), args.allow_findings, Progress(None, "check"), machine=profile)
    findings = []
    export_carve(job, post_name, nc_path, machine.work_offset, checked=True, orient_spindle=machine.orient_spindle,
                 machine=profile, findings=findings)
    design_path = batchio.write_stl(os.path.join(args.out, "design.stl"), job.vertices, job.faces)
    if batchio.shown():
        show_carve(scene, job)
        convert.mesh_object(scene, f"{PREFIX} design", job.vertices, job.faces, job.frame)
    from ..post.output import write_atomic
    toolpaths_png = write_atomic(os.path.join(args.out, "carve-toolpaths.png"), toolpaths_bytes(job))
    mesh = simulated.result.mesh(250_000)
    if batchio.shown():
        simview.show_simulation(scene, simulated, mesh=mesh)
    png = preview.simulation_png(os.path.join(args.out, "carve.png"), simulated.result, "CARVING: SIMULATED STOCK",
                                 mesh=mesh)
    scallop = core.measured_scallop(simulated.result.heightfield, job.vertices, job.faces)
    result = job.result
    cleanup = {"on": bool(props.steep_cleanup), "max_slope_deg": round(props.max_slope, 3),
               "steep_area_mm2": round(result.steep_area_mm2, 1)}
    if result.cleanup_stepover is not None:
        # the same simulation without the cleanup: what the raster alone left
        from ..toolpath import simulate as sim
        setup = simulation(job)
        before = sim.simulate([op for op in setup.program.operations if op.name != "steep cleanup"], setup.stock,
                              cell=gate_report["cell_mm"],
                              **setup.extra)
        cleanup.update({
            "stepover_mm": round(result.cleanup_stepover, 5),
            "slope_across_cleanup_deg": round(result.cleanup_slope_deg, 2),
            "max_scallop_before_mm": round(core.measured_scallop(before.heightfield, job.vertices,
                                                                 job.faces)["max_scallop_mm"], 5),
            "max_scallop_after_mm": round(scallop["max_scallop_mm"], 5)})
    report = {
        "gate": gate_report,
        "workflow": "carve",
        "post": post_name,
        "machine": profile.summary(),
        "files": [nc_path, design_path],
        "preview": png,
        "toolpaths_preview": toolpaths_png,
        "simulation": simview.report_of(simulated.result),
        "scallop": {"asked_mm": round(props.scallop, 6), **{k: (round(v, 5) if isinstance(v, float) else batchio.rounded(v, 3))
                                                  for k, v in scallop.items()}},
        "toolpath_seconds": round(job.seconds, 3),
        "stock": batchio.rounded(result.stock, 4),
        "stepover_mm": round(result.stepover, 5),
        "flat_stepover_mm": round(result.flat_stepover, 5),
        "steepest_slope_deg": round(result.steepest_slope_deg, 2),
        "roughing_levels": batchio.rounded(result.levels, 4),
        "steep_cleanup": cleanup,
        "wall_pass": wall_report(result, props),
        "operations": [{**summary, "tool": op.tool.describe(), "tool_kind": op.tool.kind,
                        "tool_diameter_mm": op.tool.diameter}
                       for op, summary in zip(result.program.operations, result.program.summary())],
        "cycle_time_s": round(result.program.cycle_time(), 1),
        "warnings": result.warnings,
    }
    workflowfeeds.check(args, scene, job.result.program, profile, report, findings)
    warn(findings, report)
    return report


WORKFLOW = Workflow(
    "CARVE", "Carving", "Roughing and finishing of a 3-D surface (relief, domed plate, any mesh)", classes=CLASSES,
    post_families=POST_FAMILIES, request=carve_request, simulation=simulation, kind="carve",
    job_operation=job_operation,
    commands=(BatchCommand("carve", "3-D surface carving of a mesh: Z-level roughing, ball finishing raster",
                           batch_arguments, batch, demo=("--post", "linuxcnc")),))
