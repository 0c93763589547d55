"""The router operations (issue 29) on a big sign: a 600 x 300 mm plate with 40 letter-like shapes
(20 rings with their counters, 20 L shapes, each 40 mm tall) pocketed 3 mm deep with a 3 mm end
mill, the plate's outline profiled through with six tabs by a 6 mm end mill, and four mounting
holes drilled: the job planned with an empty cache (CPU seconds; the issue's target is 1 s), after
one warm-up plan of the whole job.  Rows per operation beside the whole job, so what grows is seen."""
from __future__ import annotations

import resource

import numpy as np


def cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def circle(cx, cy, r, n=64):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([cx + r * np.cos(t), cy + r * np.sin(t)])


def letters() -> list:
    loops = []
    for index in range(40):
        column, row = index % 10, index // 10
        x, y = -270 + 60 * column, -105 + 70 * row
        if index % 2:
            loops += [circle(x, y, 20), circle(x, y, 11)[::-1]]           # a ring and its counter
        else:
            loops.append(np.array([[x - 18, y - 20], [x + 18, y - 20], [x + 18, y - 12], [x - 9, y - 12],
                                   [x - 9, y + 20], [x - 18, y + 20]]))   # an L
    return loops


def run() -> list:
    from kezuri.toolpath import job as jobs
    from kezuri.toolpath.ir.program import Tool
    from kezuri.toolpath.operations.drill import drill
    from kezuri.toolpath.operations.drill.kind import DrillGeometry
    from kezuri.toolpath.operations.pocket import pocket
    from kezuri.toolpath.operations.pocket.kind import PocketGeometry
    from kezuri.toolpath.operations.profile import profile
    from kezuri.toolpath.operations.profile.kind import ProfileGeometry
    from kezuri.toolpath.simulate import BoxStock

    plate = np.array([[-300.0, -150.0], [300.0, -150.0], [300.0, 150.0], [-300.0, 150.0]])
    outline = np.array([[-295.0, -145.0], [295.0, -145.0], [295.0, 145.0], [-295.0, 145.0]])
    setup = jobs.Setup(name="sign", stock=BoxStock(-300.0, -150.0, -18.0, 300.0, 150.0, 0.0))
    pocketing = jobs.JobOperation("pocket", "letters", pocket.PocketSettings(
        tool=Tool(5, "flat", 3.0), depth=3.0, step_down=1.5, stepover=1.2, helix_diameter=2.0),
        PocketGeometry(tuple(map(tuple, map(map_tuple, letters()))), "letters", 0.0, (plate,), 18.0))
    profiling = jobs.JobOperation("profile", "cut out", profile.ProfileSettings(
        tool=Tool(6, "flat", 6.0, flute_length=25.0), step_down=6.0, tab_count=6),
        ProfileGeometry((outline,), 18.0))
    drilling = jobs.JobOperation("drill", "holes", drill.DrillSettings(tool=Tool(4, "drill", 5.0, flute_length=40.0),
                                                                          depth=10.0),
                                 DrillGeometry(((-280.0, -130.0), (280.0, -130.0), (280.0, 130.0), (-280.0, 130.0))))
    # warm-up: the first plan in a process imports the planners and loads compiled kernels (about
    # 0.15 s here), which the first row timed (pocketing alone then read 1.03-1.04 s, later 0.90)
    jobs.plan_job(jobs.Job(setup, (pocketing, drilling, profiling)))
    rows = []
    for name, operations in (("pocket 40 letters", (pocketing,)), ("profile with tabs", (profiling,)),
                             ("drill", (drilling,)), ("whole job", (pocketing, drilling, profiling))):
        started = cpu()
        planned = jobs.plan_job(jobs.Job(setup, operations))
        seconds = cpu() - started
        moves = sum(len(op) for part in planned.parts for op in part.operations)
        rows.append({"name": f"router sign 600x300: {name}", "seconds": round(seconds, 3),
                     "target_s": 1.0 if name == "whole job" else None, "notes": f"{moves} moves planned"})
    return rows


def map_tuple(loop):
    return tuple(map(tuple, np.asarray(loop, float)))
