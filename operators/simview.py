"""The simulation in the scene: run a workflow's :class:`SimulationSetup`, show the carved stock,
list the findings, and the ``simulation`` entry of a batch report.

Needs no workflow table: the Simulate operator (:mod:`.simulate`) and every workflow's batch
command call it with the workflow they have.
"""
from __future__ import annotations

from dataclasses import dataclass

import bpy
import numpy as np

from ..toolpath.pictures import picture_jobs
from ..toolpath import simulate as core
from . import convert
from .common import CoreCall
from .translations import translate_message

PREFIX = "Kezuri Simulated"
COLOUR_ATTRIBUTES = {"DEPTH": "Kezuri depth", "OPERATION": "Kezuri operation"}
OPERATION_COLOURS = np.array([(0.95, 0.45, 0.10, 1.0), (0.10, 0.60, 1.00, 1.0), (0.20, 0.80, 0.30, 1.0),
                              (0.90, 0.80, 0.10, 1.0), (0.75, 0.30, 0.95, 1.0), (0.90, 0.20, 0.30, 1.0)])


@dataclass
class SimulationJob:
    result: core.SimulationResult
    frame: convert.WorkFrame
    name: str


def _scaled(progress, start: float, end: float):
    if progress is None:
        return None
    return lambda fraction, text="": progress(start + (end - start) * fraction, text)


def simulation_request(workflow, scene, engine: str = "heightfield", cell: float = 0.1):
    """Read ``workflow``'s job from the scene; return what cuts its stock without touching
    Blender data: a ``compute(progress)`` that plans and simulates (run in steps), or for the
    manifold engine, whose booleans hold Python's GIL, the job planned now and its simulation
    as a :class:`CoreCall` (run in a separate process from the UI)."""
    if workflow.simulation is None:
        raise convert.SceneInputError(f"no simulation for {workflow.label!r}")
    plan = workflow.request(scene, bpy.context.evaluated_depsgraph_get())
    if engine == "manifold":
        setup = workflow.simulation(plan(None))
        return CoreCall("toolpath.simulate", "simulate",
                        dict(program_or_operations=setup.program, stock=setup.stock, engine=engine, cell=cell,
                             **setup.extra),
                        then=lambda result: SimulationJob(result, setup.frame, setup.name))

    def compute(progress=None) -> SimulationJob:
        return run_setup(workflow.simulation(plan(_scaled(progress, 0.0, 0.2))), engine, cell,
                         _scaled(progress, 0.2, 1.0))
    return compute


def run_setup(setup, engine: str = "heightfield", cell: float = 0.1, progress=None) -> SimulationJob:
    """Cut ``setup``'s stock with its program."""
    result = core.simulate(setup.program, setup.stock, engine=engine, cell=cell, progress=progress, **setup.extra)
    return SimulationJob(result, setup.frame, setup.name)


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


def show_simulation(scene, job: SimulationJob, max_cells: int = 250_000, mesh=None):
    """The simulated stock as a mesh in the Kezuri collection (replaces the last one), with two
    colour attributes: by depth, and by the operation whose surface shows there.  ``mesh``: the
    stock's (vertices, faces) if already built (else ``job.result.mesh(max_cells)``)."""
    convert.remove_objects(PREFIX)
    vertices, faces = job.result.mesh(max_cells) if mesh is None else mesh
    obj = convert.mesh_object(scene, f"{PREFIX} stock ({job.name})", vertices, faces, job.frame,
                              color=(0.85, 0.72, 0.52, 1.0))
    vertices = np.asarray(vertices, float)
    # over the job's own depth range (0 .. its deepest cut), not the stock's thickness
    depth, deepest = picture_jobs.surface_depth(job.result, vertices)
    by_depth = np.column_stack([picture_jobs.depth_colours(depth, deepest) / 255.0, np.ones(len(depth))])
    light = np.array([0.92, 0.80, 0.60, 1.0])
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


def gate_key(finding) -> str:
    """A finding as the export gate's override names it (see :func:`gate.finding_key`)."""
    return f"{finding.kind} {finding.operation}:{finding.move}"


def store_findings(scene, job: SimulationJob):
    """List the findings in the panel; a new list clears any earlier override of the export gate."""
    props = scene.kezuri.simulation
    props.allow_findings = False
    items = props.findings
    items.clear()
    blocking = set(map(id, core.blocking(job.result.findings)))
    for f in job.result.findings:
        item = items.add()
        item.kind, item.message = f.kind, translate_message(f.message)
        item.blocking, item.signature = id(f) in blocking, gate_key(f)
        item.operation, item.move = f.operation, f.move
        if f.xy is not None:
            item.location = job.frame.to_world([(float(f.xy[0]), float(f.xy[1]), f.z or 0.0)])[0]


def batch_simulation(scene, setup, out_dir: str, stem: str, job: SimulationJob | None = None, marks=()) -> tuple:
    """Batch: cut ``setup``'s stock (height field, 0.1 mm) unless ``job`` has done it already (the
    export gate's), render the carved stock to ``<stem>.png`` (``marks``: places left uncut, drawn
    on it): (report entry, png path)."""
    import os

    from ..post.output import write_atomic
    from .batchio import shown
    from .common import Progress

    if job is None:
        job = run_setup(setup, "heightfield", 0.1, Progress(None, "simulate"))
    if shown():      # the scene's object is the closed solid; the picture needs only its look
        mesh = job.result.mesh(250_000)
        show_simulation(scene, job, mesh=mesh)
    else:
        mesh = None
    png = write_atomic(os.path.join(out_dir, f"{stem}.png"), result_bytes(job, stem, marks, mesh))
    return report_of(job.result), png


def sheet_pictures(toolpaths: bytes, simulated, stem: str, marks=()) -> list:
    """A setup sheet's pictures as batch draws them: [(caption, PNG bytes)], the ``toolpaths``
    picture and, with the gate's ``simulated`` job, the simulated stock (:func:`result_bytes`)."""
    pictures = [("Toolpaths", toolpaths)]
    if simulated is not None:
        pictures.append(("Result", result_bytes(simulated, stem, marks)))
    return pictures


def result_bytes(job: SimulationJob, stem: str, marks=(), mesh=None) -> bytes:
    """The simulated stock's picture :func:`batch_simulation` draws (``<stem>.png``), as PNG bytes
    (``mesh``: the stock's look if already built; None: its top surface, built here)."""
    from . import preview

    mesh = job.result.surface(250_000) if mesh is None else mesh
    return preview.simulation_bytes(job.result, f"{stem.upper()}: SIMULATED STOCK",
                                    preview.SIDE_VIEW_DEG if stem == "turnmill" else 35.0, mesh, marks)
