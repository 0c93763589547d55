"""W6: the exact (manifold) preview of every built-in sample job, beside its height-field preview.

For each sample (the name plate, the rotary block, the STEP-NC plate, the turn-mill bar) the job
is planned from the sample scene as the Simulate operator plans it, then simulated with the
manifold engine at a 0.05 mm tool tolerance: facets lie inside the true tool, so the solid is
within 0.05 mm of the exact cut, always on the side of leaving material.  The notes give the
removed volume against the height field's (0.1 mm cells) as a cross-check.  Issue #7's target:
every sample under 10 s; issue #32's: within 3x the height field's CPU (the notes give
the ratio).  Each job runs once.
"""
from __future__ import annotations

import os
import tempfile
import time

TOLERANCE = 0.05   # mm: the preview's allowed error


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

    rows = []
    for name, (program, stock, extra, _, _) in _sample_jobs():
        moves = sum(len(op) for op in program.operations)
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
                              f"field's {field_cpu:.2f} s: {exact_cpu / max(field_cpu, 1e-9):.0f}x (issue #32: 3x)"})
    return rows
