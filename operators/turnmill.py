"""W4 in Blender: turn-mill reach classification (face colours) and radial/axial paths, X-Z-C NC.

The part is a mesh around the Z axis (= the C axis) of the work frame; the stock a round bar
given in the Turn-Mill panel.  Inside Blender the rays are cast with mathutils' BVHTree; the
core's trimesh engine is the other choice (and the one batch runs use without Blender).
"""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass

import bpy
import numpy as np
from bpy.props import EnumProperty, StringProperty
from mathutils import Vector
from mathutils.bvhtree import BVHTree

from .. import post as posts
from ..post import write_atomic
from ..post.capacity import program_findings, program_kb, short_blocks
from ..toolpath.ir import machine
from ..toolpath.engines import meshdata, meshfile
from ..toolpath.operations.turnmill import turnmill as core
from ..toolpath.ir.errors import MAX_REACH_MM
from ..toolpath.job import Job, JobOperation, Setup, plan_job
from ..toolpath.operations.turnmill import kind as turnmill_kind
from . import convert
from . import gate
from . import pathview
from .common import SteppedOperator
from .exporting import Exported, NCExport, ProgramSheet, stages, report_findings
from .limits import check_group
from .plancache import cache_of, keep
from .properties import post_items, post_number
from .translations import translate_message
from .workflow import BatchCommand, SimulationSetup, Workflow

POST_FAMILIES = ("xzc", "cldata")

PREFIX = "Kezuri Turn-Mill"
ATTRIBUTE = "Kezuri reach"
LABEL_COLOURS = {core.NEITHER: (0.45, 0.45, 0.45, 1.0), core.RADIAL: (0.15, 0.45, 1.0, 1.0),
                 core.AXIAL: (0.2, 0.85, 0.3, 1.0), core.BOTH: (0.75, 0.3, 0.95, 1.0)}
REPORT_LABELS = {core.NEITHER: "none", core.RADIAL: "radial", core.AXIAL: "axial", core.BOTH: "both"}
SKIPPED_COLOUR = (250, 150, 20)       # the toolpath picture's faces no tool reaches (RGB 0-255)
REPORT_FACES = 20000                   # report.json lists each face's class up to this many faces


class BVHRayEngine:
    """The core's RayEngine on Blender's BVHTree: does any ray hit the mesh?"""

    backend = "bvhtree"

    def __init__(self, vertices, faces):
        self.tree = BVHTree.FromPolygons([tuple(v) for v in np.asarray(vertices, float)],
                                         [tuple(int(i) for i in f) for f in np.asarray(faces)], epsilon=0.0)

    def intersects_any(self, origins, directions) -> np.ndarray:
        cast = self.tree.ray_cast
        return np.array([cast(Vector(o), Vector(d))[0] is not None
                         for o, d in zip(np.asarray(origins, float), np.asarray(directions, float))], dtype=bool)


def engine_for(name: str, vertices, faces):
    return BVHRayEngine(vertices, faces) if name == "BVH" else core.TrimeshRayEngine(vertices, faces)


@dataclass
class TurnMillJob:
    plan: core.TurnMillPlan
    vertices: np.ndarray       # work mm
    faces: np.ndarray          # triangles
    owner: np.ndarray          # triangle -> polygon of the Blender mesh (or itself)
    frame: convert.WorkFrame
    rays: int
    classification_seconds: float
    engine: str
    stock: core.Stock
    profile: machine.MachineProfile = machine.PRESETS[machine.DEFAULT_FOR_FAMILY["xzc"]]
    replanned: tuple = ()      # the operations planned by this call (the rest were Generate's)


def machine_profile(name: str | None = None, given_as: str = "--machine") -> machine.MachineProfile:
    """The turn-mill's machine profile: the preset ``name`` (default: the 0i-T turn-mill), refused
    by name when it is not a turn-mill (X-Z-C) machine."""
    profile = machine.preset(name or machine.DEFAULT_FOR_FAMILY["xzc"])
    if profile.family != "xzc":
        raise machine.MachineError(f"{given_as} {name}: {profile.label} is not a turn-mill; the turn-mill presets are "
                                   f"{', '.join(p.name for p in machine.presets('xzc'))}")
    return profile


def settings_from(props, profile: machine.MachineProfile | None = None) -> core.TurnMillSettings:
    """The panel's settings; the machine's block time (``profile.block_ms``) sets the shortest move."""
    check_group(props, "turnmill")
    props = convert.Typed(props)
    profile = machine_profile() if profile is None else profile
    return core.TurnMillSettings(tool_diameter=props.tool_diameter, tolerance=props.tolerance, feed=props.feed,
                                 spindle_rpm=props.spindle_rpm, sample_spacing=props.sample_spacing,
                                 block_ms=profile.block_ms)


def run_on_mesh(vertices, faces, stock: core.Stock, settings: core.TurnMillSettings, engine_name: str,
                frame: convert.WorkFrame, owner=None, selected=None, name="turn-mill", progress=None,
                profile: machine.MachineProfile | None = None, cache: dict | None = None) -> TurnMillJob:
    """Classify (timed), then plan: a job of one turn-mill operation.  ``selected``: a face mask;
    unselected faces still block rays but get no paths (nor are they reported as not machined).
    Touches no Blender data (the BVH engine is mathutils only)."""
    profile = machine_profile() if profile is None else profile
    setup = Setup(name=name, machine=profile)
    geometry = turnmill_kind.TurnMillGeometry(vertices, faces, stock, selected,
                                              BVHRayEngine if engine_name == "BVH" else core.TrimeshRayEngine)
    planned = plan_job(Job(setup, (JobOperation("turnmill", "turn-mill", settings, geometry),)), cache,
                       progress=progress)
    if cache is not None:
        keep(cache, planned)
    outcome = planned.parts[0].result
    owner = np.arange(len(outcome.faces)) if owner is None else owner
    return TurnMillJob(outcome.plan, outcome.vertices, outcome.faces, owner, frame, outcome.rays,
                       outcome.classification_seconds, engine_name, stock, profile, tuple(planned.replanned()))


def part_mesh(scene, depsgraph) -> tuple:
    """The Turn-Mill panel's part as triangles in work mm: (object, vertices, faces, owner, frame)."""
    obj = scene.kezuri.turnmill.part
    if obj is None or obj.type != "MESH":
        raise convert.SceneInputError("pick the part (a mesh around the Z axis) in the Turn-Mill panel")
    world, polygons, _ = convert.evaluated_mesh_arrays(obj, depsgraph)
    if not polygons:
        raise convert.SceneInputError(f"part {obj.name!r} has no faces")
    frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
    vertices = frame.to_work(world)
    faces, owner = meshdata.triangulated(polygons)
    return obj, vertices, faces, owner, frame


def turnmill_request(scene, depsgraph, profile: machine.MachineProfile | None = None):
    """Read the part and the settings; return ``compute(progress)``, which classifies and plans
    without touching Blender data (so it can run in steps)."""
    props = scene.kezuri.turnmill
    check_group(props, "turnmill")
    obj, vertices, faces, owner, frame = part_mesh(scene, depsgraph)
    selected = None
    if props.selected_only:
        selected_polygons = np.zeros(len(obj.data.polygons), bool)
        obj.data.polygons.foreach_get("select", selected_polygons)
        if not selected_polygons.any():
            raise convert.SceneInputError(f"part {obj.name!r}: no faces are selected (select them in Edit Mode, "
                                          "or switch off Selected Faces Only)")
        selected = selected_polygons[owner]
    stock = core.Stock(props.stock_radius, props.stock_z_min, props.stock_z_max)
    profile = machine_profile() if profile is None else profile
    settings, engine, name = settings_from(props, profile), props.engine, scene.name
    cache = cache_of(scene)
    return lambda progress=None: run_on_mesh(vertices, faces, stock, settings, engine, frame, owner, selected,
                                             name=name, progress=progress, profile=profile, cache=cache)


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's turn-mill operation: object ``part`` (the mesh around the Z axis), the Turn-Mill
    panel's settings by name (the bar: stock_radius, stock_z_min, stock_z_max)."""
    from .jobentry import JobFileError, apply_settings

    props = scene.kezuri.turnmill
    for slot, obj in entry.objects.items():
        if slot != "part":
            raise JobFileError(f"{entry.where}: objects.{slot}: a turn-mill operation takes objects.part")
        props.part = obj
    apply_settings(props, entry, skip=("selected_only",))
    obj, vertices, faces, owner, frame = part_mesh(scene, depsgraph)
    profile = machine_profile()
    geometry = turnmill_kind.TurnMillGeometry(vertices, faces, core.Stock(props.stock_radius, props.stock_z_min,
                                                                          props.stock_z_max), None,
                                              BVHRayEngine if props.engine == "BVH" else core.TrimeshRayEngine)
    operation = JobOperation("turnmill", entry.name, settings_from(props, profile), geometry, entry.enabled)
    return operation, Setup(name=scene.name, machine=profile), frame


def run_turnmill(scene, depsgraph, progress=None, profile: machine.MachineProfile | None = None) -> TurnMillJob:
    return turnmill_request(scene, depsgraph, profile)(progress)


def polygon_labels(triangle_labels: np.ndarray, owner: np.ndarray, polygon_count: int) -> np.ndarray:
    """Per Blender polygon: the directions that reach all of its triangles (the labels are bit
    sets: radial 1, axial 2, both 3)."""
    return meshdata.polygon_bits(triangle_labels, owner, polygon_count, core.BOTH)


def colour_faces(obj, labels: np.ndarray):
    """Face colours in a colour attribute (Solid shading > Attribute shows it).  Colour
    attributes live on points or face corners: every corner of a face gets the face's colour."""
    mesh = obj.data
    attribute = mesh.color_attributes.get(ATTRIBUTE)
    if attribute is None:
        attribute = mesh.color_attributes.new(ATTRIBUTE, "FLOAT_COLOR", "CORNER")
    totals = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_total", totals)
    colours = np.array([LABEL_COLOURS[int(k)] for k in labels], dtype=np.float32)
    attribute.data.foreach_set("color", np.repeat(colours, totals, axis=0).ravel())
    mesh.color_attributes.active_color = attribute
    mesh.update()


def show_turnmill(scene, job: TurnMillJob) -> list:
    convert.remove_objects(PREFIX)
    return pathview.show_toolpaths(scene, PREFIX, job.plan.program.operations, job.stock, job.frame)


def machine_findings(job: TurnMillJob, post, text: str) -> list:
    """What the machine cannot take of a posted program (size past its memory, blocks shorter
    than its block time: :func:`post.capacity.program_findings`).  Only the program the profile's
    control stores is measured: the one with a program number (the LinuxCNC variant is streamed
    from disk, the CL data goes to another post-processor)."""
    if not getattr(post, "program_number", None):
        return []
    return program_findings(text, job.profile, f"the {post.name} program")


def unmachined_warnings(job: TurnMillJob) -> list:
    """One line for each feature no tool reaches (as in the NC header)."""
    return turnmill_kind.unmachined_warnings(job.plan)


def toolpaths_bytes(job: TurnMillJob) -> bytes:
    """The toolpaths picture batch ``turnmill`` draws (``turnmill-toolpaths.png``), as PNG bytes."""
    from . import preview

    return preview.toolpath_bytes(job.plan.program.operations, job.stock,
                                  [(job.vertices, job.faces, preview.picture_jobs.PART_COLOUR)],
                                  "TURN-MILL X-Z-C: TOOLPATHS ON THE PART", tilt_deg=preview.SIDE_VIEW_DEG,
                                  highlights=skipped_highlight(job))


def sheet_pictures(job: TurnMillJob, simulated=None) -> list:
    """The setup sheet's pictures as batch ``turnmill`` draws them: [(caption, PNG bytes)], the
    toolpaths and, with the gate's ``simulated`` job, the simulated stock."""
    from . import simview

    return simview.sheet_pictures(toolpaths_bytes(job), simulated, "turnmill")


def export_turnmill(job: TurnMillJob, post_name: str, path: str, allow: bool | str = False,
                    checked: bool = False, progress=None, sheet: dict | None = None) -> tuple:
    """Write the program; the export gate simulates it first unless the caller has (``checked``;
    ``progress``: the gate's).  Returns the path and the machine's findings on the program
    (:func:`machine_findings`); ``sheet``: filled with the gate's ``gate`` report (the setup sheet's)."""
    post = posts.create(POST_FAMILIES, post_name)
    text = post.to_text(job.plan.program)
    simulated, report = None, None
    if not checked:
        simulated, report = gate.check(simulation(job), allow, progress)
    if sheet is not None:
        sheet.update(gate=report, pictures=lambda: sheet_pictures(job, simulated))
    return write_atomic(path, text), machine_findings(job, post, text)


def nc_export_request(scene, depsgraph, post_name: str, target: str):
    """The panel's export: read the scene here; ``work(progress) -> Exported`` classifies, plans,
    checks and writes ``target`` without touching Blender data (so it runs in steps, Esc cancelling)."""
    compute = turnmill_request(scene, depsgraph)
    allow = scene.kezuri.simulation.acknowledged

    label = posts.find(POST_FAMILIES, post_name).label

    def work(progress=None) -> Exported:
        planning, checking = stages(progress)
        job, sheet = compute(planning), {}
        written, findings = export_turnmill(job, post_name, target, allow=allow, progress=checking, sheet=sheet)
        # the sheet's notes as batch's report has them: the unmachined features, then the machine's findings
        return Exported(written, job.replanned, unmachined_warnings(job) + findings,
                        sheet=ProgramSheet(job.plan.program, sheet["gate"], job.profile, label, "turnmill",
                                           pictures=sheet["pictures"]))
    return work


def extension_for(post_name: str) -> str:
    return posts.extension(POST_FAMILIES, post_name)


def simulation(job: TurnMillJob) -> SimulationSetup:
    """The X-Z-C program on the round bar, checked against the part."""
    from types import SimpleNamespace

    return SimulationSetup(job.plan.program, job.stock, {"design": SimpleNamespace(vertices=job.vertices,
                                                                                   faces=job.faces)},
                           job.frame, "turnmill")


def _poll_part(cls, context) -> bool:
    part = context.scene.kezuri.turnmill.part
    if part is None or part.type != "MESH":
        cls.poll_message_set("Pick the part (a mesh) in the Turn-Mill panel")
        return False
    return True


class KEZURI_OT_turnmill_classify(SteppedOperator, bpy.types.Operator):
    """Cast rays from every face: colour it by the tool directions that reach it (blue radial,
    green axial, purple both, grey neither)"""

    bl_idname = "kezuri.turnmill_classify"
    bl_label = "Classify Faces"
    bl_options = {"REGISTER", "UNDO"}
    progress_label = "classify"

    @classmethod
    def poll(cls, context):
        return _poll_part(cls, context)

    def prepare(self, context):
        props = context.scene.kezuri.turnmill
        check_group(props, "turnmill", ["sample_spacing"])
        _, vertices, faces, owner, _ = part_mesh(context.scene, context.evaluated_depsgraph_get())
        vertices, faces = core.check_mesh(vertices, faces)
        engine_name, spacing = props.engine, props.sample_spacing

        def compute(progress=None):
            engine = engine_for(engine_name, vertices, faces)
            return core.classify_faces(vertices, faces, engine, spacing, progress), owner
        return compute

    def finish(self, context, result):
        labels, owner = result
        obj = context.scene.kezuri.turnmill.part
        per_polygon = polygon_labels(labels, owner, len(obj.data.polygons))
        colour_faces(obj, per_polygon)
        if context.space_data is not None and context.space_data.type == "VIEW_3D":
            context.space_data.shading.color_type = "VERTEX"
        counts = {REPORT_LABELS[k]: int(np.count_nonzero(per_polygon == k)) for k in REPORT_LABELS}
        self.report({"INFO"}, translate_message("Faces: " + ", ".join(f"{v} {k}" for k, v in counts.items())))
        return {"FINISHED"}


class KEZURI_OT_turnmill_generate(SteppedOperator, bpy.types.Operator):
    """Classify the faces, then plan radial and axial roughing and finishing paths"""

    bl_idname = "kezuri.turnmill_generate"
    bl_label = "Generate Turn-Mill Paths"
    bl_options = {"REGISTER", "UNDO"}
    progress_label = "turn-mill"

    @classmethod
    def poll(cls, context):
        return _poll_part(cls, context)

    def prepare(self, context):
        return turnmill_request(context.scene, context.evaluated_depsgraph_get())

    def finish(self, context, job):
        obj = context.scene.kezuri.turnmill.part
        colour_faces(obj, polygon_labels(job.plan.labels, job.owner, len(obj.data.polygons)))
        show_turnmill(context.scene, job)
        report_findings(self, unmachined_warnings(job))
        ops = job.plan.program.operations
        self.report({"INFO"},
                    translate_message(f"{len(ops)} operations, about {job.plan.program.cycle_time() / 60:.1f} min"))
        return {"FINISHED"}


class KEZURI_OT_turnmill_export(NCExport, bpy.types.Operator):
    """Write the X-Z-C program (or its CL data) for the turn-mill centre"""

    bl_idname = "kezuri.turnmill_export"
    bl_label = "Export Turn-Mill NC"
    bl_options = {"REGISTER"}

    filename_ext = ".nc"
    filter_glob: StringProperty(default="*.nc;*.ngc;*.cls", options={"HIDDEN"})
    post: EnumProperty(name="Post", items=post_items(POST_FAMILIES), default=post_number("xzc"))
    post_families = POST_FAMILIES
    file_suffix = "-turnmill"

    @classmethod
    def poll(cls, context):
        return _poll_part(cls, context)

    def preferred_post(self, context):
        return None                                       # the turn-mill has no post setting: X-Z-C

    def export_request(self, context, path):
        return nc_export_request(context.scene, context.evaluated_depsgraph_get(), self.post, path)


CLASSES = (KEZURI_OT_turnmill_classify, KEZURI_OT_turnmill_generate, KEZURI_OT_turnmill_export)


# ----- batch: ``batch.py turnmill`` --------------------------------------------------------

def batch_arguments(p):
    source = p.add_mutually_exclusive_group()
    source.add_argument("--blend", help="a .blend whose Turn-Mill panel names the part and the stock")
    source.add_argument("--mesh", help="an STL/OBJ/PLY of the part in mm, around the Z axis (stock from its size)")
    p.add_argument("--engine", choices=["BVH", "TRIMESH"], help="ray engine (default: BVH, trimesh for --mesh)")
    p.add_argument("--machine", choices=[profile.name for profile in machine.presets("xzc")],
                   help="machine profile: program memory and block time (default: fanuc-0it-turnmill)")
    p.add_argument("--post", choices=posts.choices(POST_FAMILIES), action="append",
                   help="write the program for this post (repeat for more; default: every turn-mill post)")
    gate.allow_findings_argument(p)


def read_mesh_file(path: str) -> tuple:
    """Vertices (mm) and triangles of an STL/OBJ/PLY part (:func:`meshfile.read_mesh`), checked as
    the turn-mill planner needs it, and the round bar around it."""
    vertices, faces = meshfile.read_mesh(path, "--mesh")
    try:
        vertices, faces = core.check_mesh(vertices, faces)     # closed, consistently wound: named before the stock
        core.check_on_axis(vertices)
        radius = float(np.hypot(vertices[:, 0], vertices[:, 1]).max())
        stock = core.Stock(radius, float(vertices[:, 2].min()), float(vertices[:, 2].max()))
    except (core.TurnMillError, meshdata.MeshInputError) as error:
        raise type(error)(f"--mesh {path}: {error}") from None
    return vertices, faces, stock


def batch(args) -> dict:
    from . import batchio, preview, samples, simview

    scene = batchio.open_blend(args.blend)
    profile = machine_profile(getattr(args, "machine", None))
    if args.mesh:
        vertices, faces, stock = read_mesh_file(args.mesh)
        frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
        job = run_on_mesh(vertices, faces, stock, settings_from(scene.kezuri.turnmill, profile),
                          args.engine or "TRIMESH", frame, name=os.path.basename(args.mesh), profile=profile)
        labels = job.plan.labels
        face_centroids = job.vertices[job.faces].mean(axis=1)
    else:
        if not args.blend:
            samples.turnmill_part(scene)
        if args.engine:
            scene.kezuri.turnmill.engine = args.engine
        job = run_turnmill(scene, bpy.context.evaluated_depsgraph_get(), profile=profile)
        part = scene.kezuri.turnmill.part
        labels = polygon_labels(job.plan.labels, job.owner, len(part.data.polygons))
        if batchio.shown():
            colour_faces(part, labels)
        centres = np.empty(len(part.data.polygons) * 3)
        part.data.polygons.foreach_get("center", centres)
        matrix = np.array(part.matrix_world)
        face_centroids = job.frame.to_work(convert.placed(centres, matrix))
    from .common import Progress
    checked, gate_report = gate.check(simulation(job), args.allow_findings, Progress(None, "check"))
    names = args.post or posts.choices(POST_FAMILIES)
    made = {name: posts.create(POST_FAMILIES, name) for name in dict.fromkeys(names)}
    texts = {name: post.to_text(job.plan.program) for name, post in made.items()}
    files = [write_atomic(os.path.join(args.out, f"turnmill{extension_for(name)}"), text)
             for name, text in texts.items()]
    warnings = unmachined_warnings(job) + [finding for name, post in made.items()
                                           for finding in machine_findings(job, post, texts[name])]
    for warning in warnings:
        print(f"kezuri: warning: {warning}", file=sys.stderr)
    if batchio.shown():
        show_turnmill(scene, job)
    toolpaths_png = write_atomic(os.path.join(args.out, "turnmill-toolpaths.png"), toolpaths_bytes(job))
    simulation_report, png = simview.batch_simulation(scene, simulation(job), args.out, "turnmill", checked)
    return {
        "gate": gate_report,
        "workflow": "turnmill",
        "files": files,
        "preview": png,
        "toolpaths_preview": toolpaths_png,
        "simulation": simulation_report,
        "engine": job.engine,
        "rays": job.rays,
        "classification_seconds": round(job.classification_seconds, 3),
        "face_counts": {label: int(np.count_nonzero(np.asarray(labels) == k)) for k, label in REPORT_LABELS.items()},
        # each face with its class, up to REPORT_FACES (a 790k-face bar made a 90 MB report.json)
        "faces": ([{"centroid": batchio.rounded(c, 4), "label": REPORT_LABELS[int(k)]}
                   for c, k in zip(face_centroids, labels)] if len(labels) <= REPORT_FACES else
                  f"{len(labels):,} faces: more than {REPORT_FACES:,} are counted (face_counts), not listed"),
        "operations": job.plan.program.summary(),
        "cycle_time_s": round(job.plan.program.cycle_time(), 1),
        "machine": job.profile.name,
        "post": ", ".join(texts),               # every program written (the setup sheet's Post)
        "not_machined": {"faces": int(sum(len(f.faces) for f in job.plan.skipped)),
                         "area_mm2": round(float(sum(f.area for f in job.plan.skipped)), 3),
                         "features": [feature.as_dict() for feature in job.plan.skipped]},
        "programs": {name: {"size_kb": round(program_kb(text), 1), "memory_kb": job.profile.memory_kb,
                            "short_blocks": (len(short_blocks(text, job.profile.block_ms))
                                             if job.profile.block_ms is not None else None),
                            "block_ms": job.profile.block_ms}
                     for name, text in texts.items() if getattr(made[name], "program_number", None)},
        "warnings": warnings,
    }


def skipped_highlight(job: TurnMillJob) -> list:
    """The toolpath picture's highlight of the faces no tool reaches, in their own colour."""
    ids = job.plan.skipped_faces()
    if not len(ids):
        return []
    return [(job.vertices, job.faces[ids], SKIPPED_COLOUR, f"NOT MACHINED ({len(ids)} FACES)")]


WORKFLOW = Workflow(
    "TURNMILL", "Turn-Mill", "The turn-mill part's radial and axial operations", classes=CLASSES,
    post_families=POST_FAMILIES, request=turnmill_request, simulation=simulation, kind="turnmill",
    job_operation=job_operation,
    commands=(BatchCommand("turnmill", "4.5-axis turn-mill: reach classification, radial/axial paths, X-Z-C (W4)",
                           batch_arguments, batch),))
