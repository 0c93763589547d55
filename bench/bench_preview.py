"""W6: the exact (manifold) preview of every built-in sample job, beside its height-field preview.

For each sample (the name plate, the rotary block, the STEP-NC plate, the turn-mill bar) the job
is planned from the sample scene as the Simulate operator plans it, then simulated with the
manifold engine at a 0.05 mm tool tolerance: facets lie inside the true tool, so the solid is
within 0.05 mm of the exact cut, always on the side of leaving material.  The notes give the
removed volume against the height field's (0.1 mm cells) as a cross-check.  Issue #7's target:
every sample under 10 s; issue #32's: within 3x the height field's CPU (the notes give
the ratio).  Each job runs once.  A last row runs a program of 1e5 moves (ramped circles, see
:func:`ramped_circles`) the same way.  Every exact preview runs twice in child processes, side by
side in the same run: with this code and with the code of commit BASE (before issue #32's level-run
prisms; checked out by ``git archive`` into a temporary folder), each after an untimed height-field
run that loads the compiled kernels.
"""
from __future__ import annotations

import json
import os
import pickle
import subprocess
import sys
import tarfile
import tempfile
import time

TOLERANCE = 0.05   # mm: the preview's allowed error
BASE = "495f8bd"   # the exact preview before issue #32's prisms and left-out repeated moves
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_CHILD = """
import json, os, pickle, sys, time
sys.path.insert(0, sys.argv[1])
from batch import import_package
import_package()
from kezuri.toolpath import simulate as sim
class Unpickler(pickle.Unpickler):
    # the IR's classes as this tree names them (commit BASE kept TurnMillOperation in ir/xzc.py)
    def find_class(self, module, name):
        try:
            return super().find_class(module, name)
        except AttributeError:
            return super().find_class(module.rsplit(".", 1)[0] + ".xzc", name)
program, stock, extra, cell = Unpickler(open(sys.argv[2], "rb")).load()
sim.simulate(program, stock, cell=cell, **extra)                  # loads the compiled kernels
cpu = time.process_time()
exact = sim.simulate(program, stock, engine="manifold", cell=cell, tolerance=float(sys.argv[3]), **extra)
print(json.dumps({"cpu": time.process_time() - cpu, "removed": exact.removed_volume_mm3}))
"""


def base_tree() -> str:
    """A temporary folder holding the code of commit BASE."""
    folder = tempfile.mkdtemp(prefix="kezuri-base-")
    archive = subprocess.run(["git", "-C", ROOT, "archive", "--format=tar", BASE], check=True,
                             capture_output=True).stdout
    with tarfile.open(fileobj=__import__("io").BytesIO(archive)) as tar:
        tar.extractall(folder, filter="data")
    return folder


def exact_in_child(root: str, program, stock, extra: dict, cell: float) -> dict:
    """CPU seconds and removed volume of the exact preview with the code in ``root``, in a child process."""
    with tempfile.NamedTemporaryFile(suffix=".pickle", delete=False) as stream:
        pickle.dump((program, stock, extra, cell), stream)
    try:
        out = subprocess.run([sys.executable, "-c", _CHILD, root, stream.name, str(TOLERANCE)], check=True,
                             capture_output=True, text=True).stdout
    finally:
        os.unlink(stream.name)
    return json.loads(out.strip().splitlines()[-1])


def side_by_side(base: str, program, stock, extra: dict, cell: float, field_cpu: float) -> str:
    """The note comparing this code's exact preview with BASE's, both in child processes, and
    (an added figure; issue #32's target is against the 0.1 mm field) with a height field of
    0.05 mm cells, about as fine as the preview's 0.05 mm tolerance."""
    from kezuri.toolpath import simulate as sim

    now, before = (exact_in_child(root, program, stock, extra, cell) for root in (ROOT, base))
    cpu = time.process_time()
    fine = sim.simulate(program, stock, cell=0.05, **extra)
    fine_cpu = time.process_time() - cpu
    return (f"side by side in child processes: CPU {now['cpu']:.2f} s ({now['cpu'] / max(field_cpu, 1e-9):.0f}x), "
            f"removed {now['removed']:.1f} mm^3; commit {BASE}: {before['cpu']:.2f} s "
            f"({before['cpu'] / max(field_cpu, 1e-9):.0f}x), {before['removed']:.1f} mm^3; "
            f"{before['cpu'] / max(now['cpu'], 1e-9):.2f}x faster; a 0.05 mm height field: {fine_cpu:.2f} s, "
            f"removed {fine.removed_volume_mm3:.1f} mm^3, exact/that {now['cpu'] / max(fine_cpu, 1e-9):.1f}x")


def floor(exact, field_cpu: float) -> str:
    """The least any boolean preview could cost: the finished cut (stock minus the exact result)
    handed over as one clean mesh, made a Manifold and subtracted from the stock once, with
    nothing to union.  Building the cut's pieces, and unioning them, comes on top."""
    from manifold3d import Manifold

    from kezuri.toolpath.simulate.stock import stock_solid

    stock = stock_solid(exact.stock, TOLERANCE)
    mesh = (stock - exact.solid).to_mesh()
    cpu = time.process_time()
    result = stock - Manifold(mesh)
    result.num_tri()
    spent = time.process_time() - cpu
    return (f"floor (the finished cut as one mesh, {len(mesh.tri_verts)} triangles, made a solid and "
            f"subtracted once): {spent:.3f} s, {spent / max(field_cpu, 1e-9):.1f}x the height field")


def _sample_jobs():
    import bpy

    import kezuri
    from kezuri.operators import samples, stepnc, workflows
    from kezuri.toolpath.operations import stepnc as stepnc_core

    if not hasattr(bpy.types.Scene, "kezuri"):
        kezuri.register()
    scene = bpy.context.scene
    makers = {"ENGRAVE": samples.name_plate, "ROTARY": samples.rotary_block, "TURNMILL": samples.turnmill_part}
    for workflow in ("ENGRAVE", "ROTARY", "STEPNC", "TURNMILL"):
        samples.clear_scene(scene)
        samples.set_millimetres(scene)
        if workflow == "STEPNC":
            path = stepnc.sample_file(tempfile.mkdtemp())
            stepnc.fill_workplan_list(scene, os.path.abspath(path), stepnc_core.load_workplan(path))
        else:
            makers[workflow](scene)
        flow = workflows.workflow_of(workflow)
        setup = flow.simulation(flow.request(scene, bpy.context.evaluated_depsgraph_get())(None))
        yield workflow.lower(), (setup.program, setup.stock, setup.extra, setup.frame, setup.name)


def run():
    from kezuri.toolpath import simulate as sim

    import shutil

    rows = []
    base = base_tree()
    try:
        rows = _rows(base)
    finally:
        shutil.rmtree(base, ignore_errors=True)
    return rows


def _rows(base: str) -> list:
    from kezuri.toolpath import simulate as sim

    rows = []
    for name, (program, stock, extra, _, _) in _sample_jobs():
        moves = sum(len(op) for op in program.operations)
        sim.simulate(program, stock, cell=0.5, **extra)      # loads the compiled kernels, untimed
        cpu = time.process_time()
        field = sim.simulate(program, stock, cell=0.1, **extra)
        field_cpu = time.process_time() - cpu
        started, cpu = time.perf_counter(), time.process_time()
        exact = sim.simulate(program, stock, engine="manifold", cell=0.5, tolerance=TOLERANCE, **extra)
        seconds, exact_cpu = time.perf_counter() - started, time.process_time() - cpu
        difference = exact.removed_volume_mm3 / field.removed_volume_mm3 - 1
        rows.append({"name": f"preview: manifold, {name} sample ({moves} moves)", "seconds": seconds,
                     "target_s": 10.0,
                     "notes": f"tolerance {TOLERANCE} mm; removed {exact.removed_volume_mm3:.0f} mm^3, "
                              f"{difference:+.2%} against the height field at 0.1 mm ({field.seconds:.2f} s); "
                              f"{len(exact.findings)} findings; CPU {exact_cpu:.2f} s against the height "
                              f"field's {field_cpu:.2f} s: {exact_cpu / max(field_cpu, 1e-9):.0f}x (issue #32: 3x); "
                              + floor(exact, field_cpu) + "; "
                              + side_by_side(base, program, stock, extra, 0.5, field_cpu)})
    rows.append(big_row(base))
    return rows


def ramped_circles(grid: int = 10, layers: int = 3, moves: int = 140):
    """A 1e5-move engraving program (grid x grid circles of 2 mm radius, a flat 1 mm end mill,
    ``layers`` passes 0.5 mm apart, each entered by a 3 degree ramp along the circle, moves
    of 1/``moves`` of a turn), and its plate."""
    import math

    import numpy as np

    from kezuri.toolpath.ir.program import FEED, RAPID, Operation, Tool

    tool = Tool(1, "flat", 1.0)
    step = 2 * math.pi / moves
    ramp = int(math.ceil(0.5 / math.tan(math.radians(3.0)) / (2.0 * step)))   # moves down 0.5 mm
    points, kinds = [np.array([[-4.0, -4.0, 5.0]])], [np.array([RAPID])]
    for cx in np.arange(grid) * 6.0:
        for cy in np.arange(grid) * 6.0:
            points.append([[cx + 2.0, cy, 0.0]])
            kinds.append([RAPID])
            for layer in range(layers):
                # down the ramp from the circle's start, once round at depth from the ramp's end,
                # and back along the circle to the start (as a CAM enters every layer at one place)
                index = np.concatenate([np.arange(1, ramp + moves + 1), np.arange(ramp + moves - 1, moves - 1, -1)])
                z = -0.5 * layer - np.minimum(index, ramp) * (0.5 / ramp)
                z[ramp + moves:] = -0.5 * (layer + 1)
                angle = (index % moves) * step
                points.append(np.column_stack([cx + 2 * np.cos(angle), cy + 2 * np.sin(angle), z]))
                kinds.append(np.full(len(index), FEED))
            points.append([[cx + 2.0, cy, 5.0]])
            kinds.append([RAPID])
    points, kinds = np.vstack(points), np.concatenate(kinds)
    operation = Operation("ramped circles", tool, 18000, kinds, points, np.full(len(kinds), 600.0),
                          start=np.array([-4.0, -4.0, 5.0]))
    return [operation], (-6.0, -6.0, -10.0, grid * 6.0, grid * 6.0, 0.0)


def big_row(base: str | None = None):
    """The 1e5-move row: height field and exact preview, and (``base``: a folder with the code of
    commit BASE) the two exact previews side by side in child processes."""
    import math

    from kezuri.toolpath import simulate as sim

    program, plate = ramped_circles()
    moves = sum(len(op) for op in program)
    sim.simulate(program, plate, cell=0.5)                   # loads the compiled kernels, untimed
    cpu = time.process_time()
    field = sim.simulate(program, plate, cell=0.1)
    field_cpu = time.process_time() - cpu
    started, cpu = time.perf_counter(), time.process_time()
    exact = sim.simulate(program, plate, engine="manifold", tolerance=TOLERANCE)
    seconds, exact_cpu = time.perf_counter() - started, time.process_time() - cpu
    notes_floor = floor(exact, field_cpu)
    closed = 100 * math.pi * (2.5 ** 2 - 1.5 ** 2) * 1.5       # 100 grooves 1 mm wide round r = 2 mm, 1.5 deep
    notes = (f"removed {exact.removed_volume_mm3:.0f} mm^3 ({exact.removed_volume_mm3 / closed - 1:+.2%} against the "
             f"closed form, {field.removed_volume_mm3 / closed - 1:+.2%} for the height field); CPU {exact_cpu:.1f} s "
             f"against the height field's {field_cpu:.2f} s: "
             f"{exact_cpu / max(field_cpu, 1e-9):.0f}x (issue #32: 3x); {notes_floor}")
    if base is not None:
        notes += "; " + side_by_side(base, program, plate, {}, 0.1, field_cpu)
    return {"name": f"preview: manifold, {moves} moves (ramped circles)", "seconds": seconds, "target_s": None,
            "notes": notes}
