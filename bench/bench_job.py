"""Jobs (issue 28): changing one operation's setting re-plans that operation and those after it
(the cache keeps the rest), on every sample, and a batch of personalised plates from a CSV.

Rows (CPU seconds of the re-plan after one setting changed; the first plan beside it):
  job replan <sample>: the sample's job planned once with a cache, then one setting of its LAST
    operation changed and the job planned again (target < 1 s).
  job plates per plate: ``batch.py job samples/jobs/nameplates.toml --each <100 rows>`` in one process,
    CPU per plate (target <= 2 s): planning, the gate over the job, the program, pictures, sheet.
"""
from __future__ import annotations

import csv
import dataclasses
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
PLATES = 100


def cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def samples():
    from kezuri.toolpath import job as jobs
    from kezuri.toolpath.ir import machine
    from kezuri.toolpath.ir.program import Tool
    from kezuri.toolpath.operations.carve import carve, carve_samples
    from kezuri.toolpath.operations.carve.kind import CarveGeometry
    from kezuri.toolpath.operations.drill import drill
    from kezuri.toolpath.operations.drill.kind import DrillGeometry
    from kezuri.toolpath.operations.engrave import engrave
    from kezuri.toolpath.operations.engrave.kind import EngraveGeometry
    from kezuri.toolpath.operations.rotary import rotary
    from kezuri.toolpath.operations.rotary.kind import RotaryGeometry
    from kezuri.toolpath.operations.stepnc.kind import StepncGeometry, StepncSettings
    from kezuri.toolpath.operations.turnmill import turnmill as tm
    from kezuri.toolpath.operations.turnmill.kind import TurnMillGeometry

    def square(cx, cy, hx, hy):
        return np.array([[cx - hx, cy - hy], [cx + hx, cy - hy], [cx + hx, cy + hy], [cx - hx, cy + hy]])

    plate = EngraveGeometry((square(0, 0, 100, 50),), 20.0,
                            (("Letters", (square(-40, 0, 15, 20), square(0, 0, 15, 20), square(40, 0, 15, 20))),))
    holes = DrillGeometry(((-90.0, -40.0), (90.0, -40.0), (90.0, 40.0), (-90.0, 40.0)))
    drilling = drill.DrillSettings(tool=Tool(4, "drill", 5.0, flute_length=40.0), depth=12.0)
    block, pockets = rotary.sample_job()
    vertices, faces = carve_samples.wave_relief()
    ex1 = open(os.path.join(ROOT, "tests", "fixtures", "iso14649", "ex1.stp"), encoding="utf-8").read()
    op = jobs.JobOperation
    return {
        "engrave + drill": (jobs.Setup(name="plate"),
                            [op("engrave", "plate", engrave.EngraveSettings(), plate), op("drill", "holes", drilling, holes)],
                            lambda s: dataclasses.replace(s, depth=10.0)),
        "engrave": (jobs.Setup(name="plate"), [op("engrave", "plate", engrave.EngraveSettings(), plate)],
                    lambda s: dataclasses.replace(s, band_width=2.5)),
        "carve": (jobs.Setup(name="relief"), [op("carve", "relief", carve.CarveSettings(), CarveGeometry(vertices, faces))],
                  lambda s: dataclasses.replace(s, finish_feed=s.finish_feed + 100)),
        "rotary": (jobs.Setup(name="bento", machine=machine.preset("wood-lathe-cxz")),
                   [op("rotary", "pockets", rotary.RotarySettings(), RotaryGeometry(block, tuple(pockets)))],
                   lambda s: dataclasses.replace(s, stepover=s.stepover * 0.9)),
        "stepnc": (jobs.Setup(name="ex1"), [op("stepnc", "workplan", StepncSettings(), StepncGeometry(ex1))],
                   lambda s: StepncSettings(order=(10, 11, 12, 14, 13))),
        "turnmill": (jobs.Setup(name="bar", machine=machine.preset("fanuc-0it-turnmill")),
                     [op("turnmill", "bar", tm.TurnMillSettings(), TurnMillGeometry(*tm.sample_part()))],
                     lambda s: dataclasses.replace(s, feed=s.feed + 50)),
    }


def replan_rows() -> list:
    from kezuri.toolpath import job as jobs

    rows = []
    for name, (setup, operations, change) in samples().items():
        cache = {}
        started = cpu()
        jobs.plan_job(jobs.Job(setup, tuple(operations)), cache)
        first = cpu() - started
        last = operations[-1]
        changed = operations[:-1] + [dataclasses.replace(last, settings=change(last.settings))]
        started = cpu()
        planned = jobs.plan_job(jobs.Job(setup, tuple(changed)), cache)
        seconds = cpu() - started
        rows.append({"name": f"job replan {name}", "seconds": round(seconds, 3), "target_s": 1.0,
                     "notes": f"re-planned {planned.replanned()} of {len(operations)}; first plan {first:.2f} s CPU"})
    return rows


def plates_row() -> dict:
    folder = tempfile.mkdtemp(prefix="kezuri-bench-plates-")
    rows = os.path.join(folder, "rows.csv")
    names = ["Tanaka", "Sato", "Suzuki", "Ito", "Kato", "Mori", "Abe", "Ono", "Sakai", "Endo"]
    with open(rows, "w", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        writer.writerow(["name", "seed"])
        for index in range(PLATES):
            writer.writerow([names[index % len(names)], index])
    command = [sys.executable, os.path.join(ROOT, "batch.py"), "job", os.path.join(ROOT, "samples", "jobs", "nameplates.toml"),
               "--each", rows, "--out", os.path.join(folder, "out")]
    started = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True)
    wall = time.perf_counter() - started
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    per_plate = (usage.ru_utime + usage.ru_stime) / PLATES
    return {"name": "job plates per plate", "seconds": round(per_plate, 3), "target_s": 2.0,
            "notes": f"{PLATES} plates from a CSV, one process, exit {done.returncode}, {wall:.0f} s wall"}


def run() -> list:
    return replan_rows() + [plates_row()]
