"""W6 in Blender: the carved stock before any NC is written, and the safety findings.

``simulate_job`` runs the material-removal simulation for the job of one workflow (engrave,
rotary pockets, STEP-NC) on its stock, with that workflow's design limits; the Simulate
operator shows the result as a mesh coloured by depth and lists the findings in the panel.
"""
from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace

import bpy
import numpy as np
from bpy.props import EnumProperty, IntProperty

from ..toolpath import region
from ..toolpath import simulate as core
from . import convert
from .common import CoreCall, SteppedOperator
from .translations import translate_message

PREFIX = "Kezuri Simulated"
COLOUR_ATTRIBUTES = {"DEPTH": "Kezuri depth", "OPERATION": "Kezuri operation"}
OPERATION_COLOURS = np.array([(0.95, 0.45, 0.10, 1.0), (0.10, 0.60, 1.00, 1.0), (0.20, 0.80, 0.30, 1.0),
                              (0.90, 0.80, 0.10, 1.0), (0.75, 0.30, 0.95, 1.0), (0.90, 0.20, 0.30, 1.0)])
WORKFLOW_ITEMS = [("ENGRAVE", "Engraving", "The gouge-texture name plate"),
                  ("ROTARY", "Rotary Pockets", "The pockets on the rotating table"),
                  ("STEPNC", "STEP-NC Workplan", "The imported ISO 14649 workplan"),
                  ("TURNMILL", "Turn-Mill", "The turn-mill part's radial and axial operations")]
# Offsets are polygons within region.ARC_TOLERANCE of the true curve: a keep region is checked
# this much inside its outline, so chord sag is not reported as a gouge.
KEEP_MARGIN = 2 * region.ARC_TOLERANCE


@dataclass
class SimulationJob:
    result: core.SimulationResult
    frame: convert.WorkFrame
    name: str


def box_stock_of(outline_loops, thickness: float) -> core.BoxStock:
    points = np.vstack(outline_loops)
    (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
    return core.BoxStock(float(x0), float(y0), -float(thickness), float(x1), float(y1), 0.0)


def _scaled(progress, start: float, end: float):
    if progress is None:
        return None
    return lambda fraction, text="": progress(start + (end - start) * fraction, text)


def _simulation_setup(scene, workflow: str):
    """Read the workflow's job from the scene: ``(plan(progress), setup(planned))``, neither
    touching Blender data; setup gives (program, stock, extra simulate arguments, frame, name)."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    if workflow == "ENGRAVE":
        from . import engrave
        props = scene.kezuri.engrave
        plate_frame = convert.plate_from_object(scene.kezuri.stock.plate, depsgraph, scene,
                                                scene.kezuri.stock.origin).frame
        letters = [loop for obj in engrave.letter_objects(props)
                   for loop in convert.outlines_in_work(obj, depsgraph, plate_frame)]
        band_depth = props.band_depth

        def setup(job):
            keep = region.offset(region.from_loops(letters, "letters"), -KEEP_MARGIN)
            texture = job.result.program.operations[0].texture
            floor = min(texture.deepest, band_depth) if texture is not None else band_depth
            extra = {"design": floor - KEEP_MARGIN, "keep_regions": [[np.asarray(loop) for loop in keep.to_polygons()]]}
            return job.baked, box_stock_of(job.plate.outline, job.plate.size[2]), extra, job.plate.frame, "engrave"
        return engrave.engrave_request(scene, depsgraph), setup
    if workflow == "ROTARY":
        from . import rotary

        def setup(job):
            b = job.block
            stock = core.BoxStock(-b.size_x / 2, -b.size_y / 2, -b.thickness, b.size_x / 2, b.size_y / 2, 0.0)
            return job.result.program, stock, {}, job.frame, "rotary"
        return rotary.rotary_request(scene, depsgraph), setup
    if workflow == "STEPNC":
        from . import stepnc
        loaded = stepnc.load_scene_workplan(scene)
        program = stepnc.scene_program(scene, loaded)
        stock = stepnc.stock_box(loaded, program)
        frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
        return (lambda progress=None: program), (lambda planned: (planned, stock, {}, frame, "stepnc"))
    if workflow == "TURNMILL":
        from . import turnmill

        def setup(job):
            design = SimpleNamespace(vertices=job.vertices, faces=job.faces)
            return job.plan.program, job.stock, {"design": design}, job.frame, "turnmill"
        return turnmill.turnmill_request(scene, depsgraph), setup
    raise convert.SceneInputError(f"no simulation for {workflow!r}")


def simulation_request(scene, workflow: str, engine: str = "heightfield", cell: float = 0.1):
    """Read the workflow's job from the scene; return what cuts its stock without touching
    Blender data: a ``compute(progress)`` that plans and simulates (run in steps), or for the
    manifold engine, whose booleans hold Python's GIL, the job planned now and its simulation
    as a :class:`CoreCall` (run in a separate process from the UI)."""
    plan, setup = _simulation_setup(scene, workflow)
    if engine == "manifold":
        program, stock, extra, frame, name = setup(plan(None))
        return CoreCall("toolpath.simulate", "simulate",
                        dict(program_or_operations=program, stock=stock, engine=engine, cell=cell, **extra),
                        then=lambda result: SimulationJob(result, frame, name))

    def compute(progress=None) -> SimulationJob:
        program, stock, extra, frame, name = setup(plan(_scaled(progress, 0.0, 0.2)))
        result = core.simulate(program, stock, engine=engine, cell=cell, progress=_scaled(progress, 0.2, 1.0),
                               **extra)
        return SimulationJob(result, frame, name)
    return compute


def simulate_job(scene, workflow: str, engine: str = "heightfield", cell: float = 0.1, progress=None) -> SimulationJob:
    """Plan the workflow's job from the scene and cut its stock with it."""
    return simulation_request(scene, workflow, engine, cell)(progress)


def report_of(result: core.SimulationResult) -> dict:
    """The ``simulation`` entry of a batch report."""
    gouges = result.findings_of("gouge")
    rapids = result.findings_of("rapid_in_material")
    finding = lambda f: {"operation": f.operation, "move": f.move, "message": f.message,  # noqa: E731
                         "xy": None if f.xy is None else [round(float(v), 3) for v in f.xy],
                         "depth_mm": None if f.depth_mm is None else round(float(f.depth_mm), 4)}
    return {
        "engine": result.engine,
        "kernel": result.kernel,
        "cell_mm": result.cell,
        "tolerance_mm": result.tolerance,
        "seconds": round(result.seconds, 3),
        "removed_volume_mm3": round(result.removed_volume_mm3, 1),
        "gouges": [finding(f) for f in gouges],
        "max_gouge_mm": round(max((f.depth_mm or 0.0 for f in gouges), default=0.0), 4),
        "gouge_volume_mm3": None if result.gouge_volume_mm3 is None else round(result.gouge_volume_mm3, 1),
        "rapid_collisions": [finding(f) for f in rapids],
        "other_findings": [finding(f) for f in result.findings if f.kind not in ("gouge", "rapid_in_material")],
    }


def show_simulation(scene, job: SimulationJob, max_cells: int = 250_000):
    """The simulated stock as a mesh in the Kezuri collection (replaces the last one), with two
    colour attributes: by depth, and by the operation whose surface shows there."""
    convert.remove_objects(PREFIX)
    vertices, faces = job.result.mesh(max_cells)
    obj = convert.mesh_object(scene, f"{PREFIX} stock ({job.name})", vertices, faces, job.frame,
                              color=(0.85, 0.72, 0.52, 1.0))
    vertices = np.asarray(vertices, float)
    depth = job.result.depth_at(vertices)
    shade = np.clip(depth / max(float(depth.max()), 1e-9), 0, 1)[:, None]
    light, dark = np.array([0.92, 0.80, 0.60, 1.0]), np.array([0.35, 0.20, 0.08, 1.0])
    by_depth = light * (1 - shade) + dark * shade
    by_operation = np.tile(light, (len(vertices), 1))
    operation = job.result.operation_at(vertices)
    cut = (operation >= 0) & (depth > 1e-6)
    by_operation[cut] = OPERATION_COLOURS[operation[cut] % len(OPERATION_COLOURS)]
    for key, colours in (("OPERATION", by_operation), ("DEPTH", by_depth)):
        attribute = obj.data.color_attributes.new(COLOUR_ATTRIBUTES[key], "FLOAT_COLOR", "POINT")
        attribute.data.foreach_set("color", colours.astype(np.float32).ravel())
    obj.data.color_attributes.active_color = obj.data.color_attributes[
        COLOUR_ATTRIBUTES[scene.kezuri.simulation.colour_by]]
    return obj


def store_findings(scene, job: SimulationJob):
    items = scene.kezuri.simulation.findings
    items.clear()
    for f in job.result.findings:
        item = items.add()
        item.kind, item.message = f.kind, translate_message(f.message)
        item.operation, item.move = f.operation, f.move
        if f.xy is not None:
            item.location = job.frame.to_world([(float(f.xy[0]), float(f.xy[1]), f.z or 0.0)])[0]


class KEZURI_OT_simulate(SteppedOperator, bpy.types.Operator):
    """Cut the stock with the job's toolpaths and check for gouges, rapids through material and moves outside the machine"""  # noqa: E501

    bl_idname = "kezuri.simulate"
    bl_label = "Simulate"
    bl_options = {"REGISTER", "UNDO"}
    progress_label = "simulate"

    workflow: EnumProperty(name="Job", items=WORKFLOW_ITEMS, default="ENGRAVE")

    def prepare(self, context):
        props = context.scene.kezuri.simulation
        return simulation_request(context.scene, self.workflow, props.engine, props.cell)

    def finish(self, context, job):
        show_simulation(context.scene, job)
        store_findings(context.scene, job)
        for finding in job.result.findings[:10]:
            self.report({"WARNING"}, translate_message(finding.message))
        self.report({"INFO"}, translate_message(f"Removed {job.result.removed_volume_mm3 / 1000:.1f} cm^3 in "
                              f"{job.result.seconds:.1f} s; {len(job.result.findings)} finding(s)"))
        return {"FINISHED"}


class KEZURI_OT_frame_finding(bpy.types.Operator):
    """Put the 3D cursor on a finding and centre the view on it"""

    bl_idname = "kezuri.frame_finding"
    bl_label = "Show Finding"
    bl_options = {"REGISTER"}

    index: IntProperty(default=0, min=0)

    def execute(self, context):
        items = context.scene.kezuri.simulation.findings
        if self.index >= len(items):
            return {"CANCELLED"}
        context.scene.cursor.location = items[self.index].location
        if context.area is not None and context.area.type == "VIEW_3D":
            bpy.ops.view3d.view_center_cursor()
        return {"FINISHED"}


CLASSES = (KEZURI_OT_simulate, KEZURI_OT_frame_finding)
