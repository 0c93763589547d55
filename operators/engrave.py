"""W1 in Blender: gather the plate and the letters, plan, show the toolpaths, export.

``run_engrave`` is the one job function: the operators, ``batch.py`` and the tests all call
it, so the panel, batch and tests cut the same program.
"""
from __future__ import annotations

import json
import os
import time
from dataclasses import dataclass

import bpy
import numpy as np
from bpy.props import EnumProperty, StringProperty

from .. import post as posts
from ..toolpath.operations.engrave import engrave as core
from ..toolpath.engines import meshdata
from ..toolpath.engines.textfile import file_problem
from ..toolpath.operations.engrave import surface_engrave
from ..toolpath.ir.program import Tool
from ..toolpath.job import Job, JobOperation, Setup, plan_job
from ..toolpath.operations.engrave.kind import EngraveGeometry
from . import convert
from . import textcells
from . import gate
from . import pathview
from .common import SteppedOperator
from .exporting import Exported, NCExport, stages, batch_orient_spindle, milling_export_request, machine_post, orient_spindle_argument, warn, write_program
from .machines import batch_machine, machine_arguments, scene_machine
from .limits import SettingError, check_group
from .plancache import cache_of, keep
from .preferences import scene_post
from .properties import post_items, post_number
from .translations import iface, japanese_message, translate_message
from .workflow import BatchCommand, SimulationSetup, Workflow

POST_FAMILIES = ("milling",)

PREFIX = "Kezuri Engrave"


@dataclass
class EngraveJob:
    result: core.EngraveResult      # planned (roughing untextured, with its texture request)
    baked: object                   # Program with the texture applied (what the baked posts write)
    depths: list                    # gouge target depths of the baked roughing, in order
    plate: convert.Plate
    letter_loops: list              # the letters' outlines, (k, 2) arrays in work mm
    settings: core.EngraveSettings
    surface: object = None          # surface_engrave.SurfaceJob on a curved plate, else None
    replanned: tuple = ()           # the operations planned by this call (the rest were Generate's)


def settings_from(props, machine=None) -> core.EngraveSettings:
    """The core's settings from the Engrave panel; a Safe Z of 0 is the machine profile's clearance
    height (``machine``; the core's own default without one)."""
    safe_z = props.safe_z if props.safe_z > 0 or machine is None else machine.clearance_z
    if props.safe_z <= 0 and machine is not None and safe_z < props.clearance_z:
        raise SettingError(f"Engrave: Safe Z 0 takes the machine's Clearance Height, {safe_z:g} mm, below the "
                           f"Clearance Plane {props.clearance_z:g} mm: give Safe Z, lower the Clearance Plane or "
                           f"raise the machine's Clearance Height")
    props = convert.Typed(props)
    texture = core.GougeTexture(base_depth=props.base_depth, quantum=props.quantum, amplitude=props.amplitude,
                                spacing=props.spacing, motion=props.motion, spacing_jitter=props.spacing_jitter,
                                seed=props.seed)
    return core.EngraveSettings(
        rough_tool=Tool(props.rough_tool_number, "ball", props.rough_diameter, name="roughing ball"),
        finish_tool=Tool(props.finish_tool_number, "flat", props.finish_diameter, name="band finishing"),
        stepover=props.stepover, raster_angle=props.raster_angle, letter_clearance=props.letter_clearance,
        band_width=props.band_width, band_depth=props.band_depth, band_stepover=props.band_stepover,
        band_step_down=props.band_step_down, band_ramp_angle=props.band_ramp_angle,
        burr_depth=props.band_depth, texture=texture, rough_rpm=props.rough_rpm, finish_rpm=props.finish_rpm,
        rough_feed=props.rough_feed, finish_feed=props.finish_feed, plunge_feed=props.plunge_feed,
        clearance_z=props.clearance_z, safe_z=safe_z if safe_z > 0 else core.EngraveSettings.safe_z)


def letter_objects(props) -> list:
    objects = [props.letters] if props.letters is not None else []
    if props.letters_collection is not None:
        objects += [o for o in props.letters_collection.all_objects
                    if (o.type in {"MESH", "CURVE", "FONT"} or convert.is_instancer(o)) and o not in objects]
    return objects


def surface_of(scene, depsgraph, frame):
    """The Engrave panel's plate surface as a surface_engrave.Surface in work mm, or None."""
    obj = scene.kezuri.engrave.surface
    if obj is None:
        return None
    if obj.type != "MESH":
        raise convert.SceneInputError(f"plate surface {obj.name!r} is not a mesh: pick a mesh object whose top "
                                      "is the plate's top")
    world, polygons, _ = convert.evaluated_mesh_arrays(obj, depsgraph)
    if not polygons:
        raise convert.SceneInputError(f"plate surface {obj.name!r} has no faces")
    faces, _ = meshdata.triangulated(polygons)
    return surface_engrave.Surface(frame.to_work(world), faces, obj.name)


def engrave_operation(scene, depsgraph, post_name: str | None = None, name: str = "engrave"):
    """Read the plate, the letters and the settings from the scene: (the job operation, the job's
    setup, the plate).  ``post_name``: the post the program is for (default: the scene's), whose
    machine gives a Safe Z of 0 its height."""
    settings = scene.kezuri
    props = settings.engrave
    check_group(settings.machine, "machine")
    check_group(props, "engrave")
    plate = convert.plate_from_object(settings.stock.plate, depsgraph, scene, settings.stock.origin)
    convert.check_fits(plate, scene)
    objects = [o for o in letter_objects(props) if o != settings.stock.plate]
    if not objects:
        raise convert.SceneInputError("no letters: pick a Text, curve or mesh object as Letters in the Engrave panel")
    letters = [(obj.name, convert.outlines_in_work(obj, depsgraph, plate.frame)) for obj in objects]
    texts = {obj.name: obj.data.body for obj in objects if obj.type == "FONT"}     # to name a glyph left uncut
    outlines = dict(letters)
    characters = tuple((obj.name, character, index, loops) for obj in objects
                       for character, index, loops in textcells.character_outlines(obj, depsgraph, plate.frame,
                                                                                   outlines[obj.name]))
    surface = surface_of(scene, depsgraph, plate.frame)
    post_name = post_name or scene_post(scene)
    machine = scene_machine(settings.machine, POST_FAMILIES, post_name)
    geometry = EngraveGeometry(tuple(plate.outline), float(plate.size[2]),
                               tuple((obj, tuple(loops)) for obj, loops in letters), tuple(texts.items()), surface,
                               characters)
    setup = Setup(name=scene.name, post=post_name, machine=machine, work_offset=settings.machine.work_offset,
                  rapid_rate=settings.machine.rapid_rate)
    return JobOperation("engrave", name, settings_from(props, machine), geometry), setup, plate


def engrave_request(scene, depsgraph, post_name: str | None = None):
    """Read the scene (:func:`engrave_operation`); return ``compute(progress)``, which plans the job
    without touching Blender data (so it can run in steps)."""
    operation, setup, plate = engrave_operation(scene, depsgraph, post_name)
    cache = cache_of(scene)

    def compute(progress=None) -> EngraveJob:
        planned = plan_job(Job(setup, (operation,)), cache, progress=progress)
        keep(cache, planned)
        outcome = planned.parts[0].result
        return EngraveJob(outcome.result, outcome.baked, outcome.depths, plate, operation.geometry.letter_loops,
                          operation.settings, outcome.surface, tuple(planned.replanned()))
    return compute


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's engraving: objects ``plate`` and ``letters`` (and ``surface``), the Engrave panel's
    settings by name."""
    from .jobentry import JobFileError, apply_settings

    slots = {"plate": (scene.kezuri.stock, "plate"), "letters": (scene.kezuri.engrave, "letters"),
             "surface": (scene.kezuri.engrave, "surface")}
    for slot, obj in entry.objects.items():
        if slot not in slots:
            raise JobFileError(f"{entry.where}: objects.{slot}: an engraving's objects are {', '.join(slots)}")
        setattr(*slots[slot], obj)
    apply_settings(scene.kezuri.engrave, entry)
    operation, setup, plate = engrave_operation(scene, depsgraph, post_name, entry.name)
    setup = Setup(name=setup.name, post=setup.post, machine=setup.machine, work_offset=setup.work_offset,
                  rapid_rate=setup.rapid_rate, stock=core.plate_stock(plate.outline, plate.size[2]))
    return JobOperation(operation.kind, operation.name, operation.settings, operation.geometry,
                        entry.enabled), setup, plate.frame


def run_engrave(scene, depsgraph, progress=None, post_name: str | None = None) -> EngraveJob:
    return engrave_request(scene, depsgraph, post_name)(progress)


def show_engrave(scene, job: EngraveJob) -> list:
    """Replace the previous engrave preview with this job's toolpaths (baked: what will be cut)."""
    convert.remove_objects(PREFIX)
    return pathview.show_toolpaths(scene, PREFIX, job.baked.operations, simulation(job).stock, job.plate.frame)


def program_for_post(job: EngraveJob, post_name: str):
    """The macro post writes the untextured path and lets the controller draw the depths."""
    if not posts.find(POST_FAMILIES, post_name).needs_texture:
        return job.baked
    return job.surface.macro if job.surface is not None else job.result.program


def export_engrave(job: EngraveJob, post_name: str, path: str, work_offset: str | None = None,
                   allow: bool | str = False, checked: bool = False, orient_spindle: bool = False,
                   machine=None, findings: list | None = None, progress=None, sheet: dict | None = None) -> str:
    """Write the program for ``post_name``; the export gate simulates it first unless the caller
    has (``checked``); ``allow``: the gate's override (see :func:`gate.check`); ``orient_spindle``:
    M19 before each tool change (Fanuc posts only); ``machine``: the machine profile (None: the
    post's own); ``progress``: the gate's (returning False cancels); ``sheet``: filled with what the
    setup sheet shows (:func:`.exporting.milling_export_request`)."""
    post = machine_post(POST_FAMILIES, post_name, work_offset, orient_spindle, machine)
    program = program_for_post(job, post_name)
    text = post.to_text(program)
    simulated, report = None, None
    if not checked:
        simulated, report = gate.check(simulation(job), allow, progress, machine=post.machine)
    if sheet is not None:
        sheet.update(program=program, gate=report, machine=post.machine, warnings=list(job.result.warnings),
                     pictures=lambda: sheet_pictures(job, simulated))
    return write_program(path, text, post, findings)


def nc_export_request(scene, depsgraph, post_name: str, target: str):
    """The panel's export: read the scene here; ``work(progress) -> Exported`` plans, checks and
    writes ``target`` without touching Blender data (so it runs in steps, Esc cancelling)."""
    return milling_export_request(scene, post_name, target, POST_FAMILIES,
                                  engrave_request(scene, depsgraph, post_name=post_name), export_engrave, "engrave")


def extension_for(post_name: str) -> str:
    return posts.extension(POST_FAMILIES, post_name)


def simulation(job: EngraveJob) -> SimulationSetup:
    """The baked program on the plate; the letters must stand and nothing may go below the
    deepest planned cut."""
    if job.surface is not None:
        surface = job.surface.surface
        extra = surface_engrave.simulation_limits(surface, job.plate.outline, job.letter_loops, job.result.program,
                                                  job.settings.band_depth, -float(job.plate.size[2]))
        return SimulationSetup(job.baked, surface_engrave.plate_stock(surface, job.plate.outline, job.plate.size[2]),
                               extra, job.plate.frame, "engrave")
    extra = core.simulation_limits(job.letter_loops, job.result.program, job.settings.band_depth)
    return SimulationSetup(job.baked, core.plate_stock(job.plate.outline, job.plate.size[2]), extra, job.plate.frame,
                           "engrave")


PANEL_LINES = 6          # characters named in the panel; the rest are counted on one more line


def too_fine_note(too_fine: list) -> str:
    """What the panel keeps of the characters too fine for the tool: [[shown, height], ...]."""
    return json.dumps([[f"'{item['char']}'" if item["char"] else f"#{item['index'] + 1}", item["min_height_mm"]]
                       for item in too_fine], ensure_ascii=False)


def too_fine_lines(props, japanese: bool | None = None) -> list:
    """The Engrave panel's lines for the characters too fine for the band finishing tool, short
    enough for the sidebar (the report has the whole message), in the interface language."""
    try:
        items = json.loads(props.too_fine) if props.too_fine else []
    except ValueError:
        return []
    lines = [f"{shown}: too fine, needs {height:.1f} mm" if height is not None else f"{shown}: too fine at any size"
             for shown, height in items[:PANEL_LINES]]
    if len(items) > PANEL_LINES:
        lines.append(f"and {len(items) - PANEL_LINES} more too fine")
    if japanese is None:
        japanese = iface("Engrave") != "Engrave"
    return [japanese_message(line) or line for line in lines] if japanese else lines


class KEZURI_OT_engrave_generate(SteppedOperator, bpy.types.Operator):
    """Plan the gouge-texture roughing, band finishing and burr contour, and show the toolpaths"""

    bl_idname = "kezuri.engrave_generate"
    bl_label = "Generate Engraving"
    bl_options = {"REGISTER", "UNDO"}
    progress_label = "engrave"

    @classmethod
    def poll(cls, context):
        settings = context.scene.kezuri
        if settings.stock.plate is None:
            cls.poll_message_set("Pick the plate (stock) object first")
            return False
        if settings.engrave.letters is None and settings.engrave.letters_collection is None:
            cls.poll_message_set("Pick the letters (Text, curve or mesh) first")
            return False
        return True

    def prepare(self, context):
        return engrave_request(context.scene, context.evaluated_depsgraph_get())

    def finish(self, context, job):
        show_engrave(context.scene, job)
        context.scene.kezuri.engrave.too_fine = too_fine_note(job.result.too_fine)
        for warning in job.result.warnings:
            self.report({"WARNING"}, translate_message(warning))
        minutes = job.baked.cycle_time() / 60
        self.report({"INFO"},
                    translate_message(f"Engraving planned: {sum(len(op) for op in job.baked.operations)} moves, "
                              f"about {minutes:.1f} min"))
        return {"FINISHED"}


class KEZURI_OT_engrave_export(NCExport, bpy.types.Operator):
    """Write the engraving NC program for the chosen controller"""

    bl_idname = "kezuri.engrave_export"
    bl_label = "Export Engraving NC"
    bl_options = {"REGISTER"}

    filename_ext = ".nc"
    filter_glob: StringProperty(default="*.nc;*.ngc;*.tap", options={"HIDDEN"})
    post: EnumProperty(name="Post", items=post_items(POST_FAMILIES), default=post_number("fanuc"))

    file_suffix = "-engrave"

    @classmethod
    def poll(cls, context):
        return KEZURI_OT_engrave_generate.poll(context)

    def export_request(self, context, path):
        return nc_export_request(context.scene, context.evaluated_depsgraph_get(), self.post, path)


CLASSES = (KEZURI_OT_engrave_generate, KEZURI_OT_engrave_export)


# ----- batch: ``batch.py engrave`` ---------------------------------------------------------

def batch_arguments(p):
    from . import workflowfeeds
    p.add_argument("--blend", help="a .blend whose scene has the Kezuri plate and letters set")
    p.add_argument("--post", choices=posts.choices(POST_FAMILIES))
    orient_spindle_argument(p)
    machine_arguments(p)
    from .batchio import number
    from .limits import RANGES
    p.add_argument("--seed", type=number("--seed", limit=RANGES["engrave"]["seed"]))
    p.add_argument("--band-step-down", type=number("--band-step-down", limit=RANGES["engrave"]["band_step_down"]),
                   help="deepest cut of one level of the band in mm (default 1, the 1 mm flat end mill's diameter)")
    p.add_argument("--band-ramp-angle", type=number("--band-ramp-angle", limit=RANGES["engrave"]["band_ramp_angle"]),
                   help="ramp angle in degrees entering each level of the band (default 3)")
    p.add_argument("--surface", help="the plate's curved top: " + ", ".join(surface_engrave.SURFACES)
                   + " (built in, over the plate) or an STL/OBJ/PLY mesh in work mm (Z 0: the plate's top); "
                   "default: flat")
    workflowfeeds.material_argument(p)
    gate.allow_findings_argument(p)


def add_surface(scene, which: str):
    """Put a plate surface into the scene and pick it in the Engrave panel: a built-in one
    (``surface_engrave.SURFACES``) over the plate's outline, or a mesh file in work mm."""
    settings = scene.kezuri
    plate = convert.plate_from_object(settings.stock.plate, bpy.context.evaluated_depsgraph_get(), scene,
                                      settings.stock.origin)
    if which in surface_engrave.SURFACES:
        points = np.vstack(plate.outline)
        (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
        vertices, faces = surface_engrave.SURFACES[which](x0 - 1, y0 - 1, x1 + 1, y1 + 1, -float(plate.size[2]))
    elif file_problem(which) == "no such file":
        raise convert.SceneInputError(f"--surface {which}: no such file, nor a built-in surface "
                                      f"({', '.join(surface_engrave.SURFACES)})")
    else:
        from .carve import read_mesh_file
        vertices, faces = read_mesh_file(which, "--surface")
    obj = convert.mesh_object(scene, "Plate Surface", vertices, faces, plate.frame)
    settings.engrave.surface = obj
    return obj


def toolpaths_bytes(job: EngraveJob) -> bytes:
    """The toolpaths picture batch ``engrave`` draws (``engrave-toolpaths.png``), as PNG bytes."""
    from . import preview

    setup = simulation(job)
    solids = []
    if job.surface is not None:
        design = setup.extra["design"]
        solids = [(design.vertices, design.faces, preview.picture_jobs.PART_COLOUR)]
    return preview.toolpath_bytes(job.baked.operations, setup.stock, solids, "ENGRAVING: TOOLPATHS",
                                  marks=uncut_marks(job.result))


def sheet_pictures(job: EngraveJob, simulated=None) -> list:
    """The setup sheet's pictures as batch ``engrave`` draws them: [(caption, PNG bytes)], the
    toolpaths and, with the gate's ``simulated`` job, the simulated result."""
    from . import simview

    return simview.sheet_pictures(toolpaths_bytes(job), simulated, "engrave", uncut_marks(job.result))


def uncut_marks(result) -> list:
    """The picture's marks for the regions no tool can enter: (x, y, 0, label) each."""
    marks = []
    for s in result.skipped:
        character = f" '{s['character']}'" if s.get("character") else ""
        marks.append((s["at"][0], s["at"][1], 0.0, f"UNCUT{character} {s['area_mm2']:.2f} MM2"))
    return marks


def batch(args) -> dict:
    from . import workflowfeeds
    from . import batchio, preview, samples, simview
    from .common import Progress

    scene = batchio.open_blend(args.blend)
    if not args.blend:
        samples.name_plate(scene)
    workflowfeeds.batch_material(args, scene)      # a bad --material refused before planning
    props = scene.kezuri
    if args.seed is not None:
        batchio.set_exactly(props.engrave, "seed", args.seed, "--seed")
    for name in ("band_step_down", "band_ramp_angle"):
        if getattr(args, name) is not None:
            batchio.set_exactly(props.engrave, name, getattr(args, name), "--" + name.replace("_", "-"))
    if args.surface:
        add_surface(scene, args.surface)
    post_name = args.post or scene_post(scene)
    batch_orient_spindle(args, scene, POST_FAMILIES, post_name)
    machine = batch_machine(args, scene, POST_FAMILIES, post_name)
    started = time.perf_counter()
    job = run_engrave(scene, bpy.context.evaluated_depsgraph_get(), Progress(None, "engrave"), post_name)
    seconds = time.perf_counter() - started
    nc_path = os.path.join(args.out, f"engrave{extension_for(post_name)}")
    setup = simulation(job)
    checked, gate_report = gate.check(setup, args.allow_findings, Progress(None, "check"), machine=machine)
    findings = []
    export_engrave(job, post_name, nc_path, props.machine.work_offset, checked=True,
                   orient_spindle=props.machine.orient_spindle, machine=machine, findings=findings)
    files = [nc_path]
    solids = []
    if job.surface is not None:
        design = setup.extra["design"]
        files.append(batchio.write_stl(os.path.join(args.out, "design.stl"), design.vertices, design.faces))
        solids = [(design.vertices, design.faces, preview.picture_jobs.PART_COLOUR)]
    if batchio.shown():
        show_engrave(scene, job)
    marks = uncut_marks(job.result)
    toolpaths_png = preview.toolpath_png(os.path.join(args.out, "engrave-toolpaths.png"), job.baked.operations,
                                         setup.stock, solids, "ENGRAVING: TOOLPATHS", marks=marks)
    simulation_report, png = simview.batch_simulation(scene, setup, args.out, "engrave", checked, marks=marks)
    report = {
        "gate": gate_report,
        "simulation": simulation_report,
        "toolpaths_preview": toolpaths_png,
        "workflow": "engrave",
        "post": post_name,
        "machine": machine.summary(),
        "seed": props.engrave.seed,
        "surface": props.engrave.surface.name if props.engrave.surface is not None else "flat",
        "files": files,
        "preview": png,
        "toolpath_seconds": round(seconds, 3),
        "operations": program_for_post(job, post_name).summary(),
        "cycle_time_s": round(job.baked.cycle_time(), 1),
        "gouge_depths": [round(d, 4) for d in job.depths],
        "warnings": job.result.warnings,
        "skipped": job.result.skipped,
        "too_fine": job.result.too_fine,
    }
    workflowfeeds.check(args, scene, program_for_post(job, post_name), machine, report, findings)
    warn(findings, report)
    return report


WORKFLOW = Workflow(
    "ENGRAVE", "Engraving", "The gouge-texture name plate", classes=CLASSES, post_families=POST_FAMILIES,
    request=engrave_request, simulation=simulation, kind="engrave", job_operation=job_operation,
    commands=(BatchCommand("engrave", "gouge-texture name plate (W1)", batch_arguments, batch,
                           demo=("--post", "linuxcnc"),
                           more_demos=(("engrave-dome", ("--surface", "dome", "--post", "fanuc-macro")),)),))
