"""How the work grows: CPU seconds and peak memory of each workflow as its input grows, with the
fitted exponent of each (least squares of log CPU on log size).

    nice .venv/bin/python bench/run.py --only scaling          (or: python bench/bench_scaling.py)

Every point runs in a child process of its own (``--child KIND SIZE``), so its peak RSS
(``resource.getrusage``) is its own; CPU is the child's ``time.process_time`` over the measured
work only (imports, sample building and program writing are not counted), except the
``simulate --nc`` batch row, which is the whole command as a user runs it.

Rows:
- engrave: the sample name plate scaled to a 200 .. 1200 mm wide plate (letters in proportion),
  plan + bake + the export gate's simulation at 0.1 mm (core); exponent on the plate's area.
- carve: the wave relief scaled in X and Y (area x1 .. x4), and at finer scallops (stepover);
- turn-mill: the sample part with every face split into 4, 16, 64 (faces);
- simulate: a finishing raster of 1e4 .. 1e6 moves written by the LinuxCNC post, read back
  (read_nc) and cut on a 0.1 mm height field; beside it the reader following every line one at a
  time (``bulk=False``, the reader as it was); and ``batch.py simulate --nc`` of the 1e6 program;
- Part 21: pocket plates written by our STEP-NC writer, parsed (the existing reader).

"Before" columns: the reader's old path runs in the same run; the engraving's old design fill
(one float64 grid of the whole plate and full-grid gouge temporaries) is no longer in the code, so
its numbers are the ones measured on this machine at the start of the change (2026-11-27, load
about 1; same script), kept in :data:`ENGRAVE_BEFORE`.

"refused up front at": where each workflow refuses before doing the work, found by the child
``--child limits`` with the workflows' own up-front checks (the work estimates of
toolpath/workload.py that plan_job asks, the height field's cell count, the NC file's lines, the
elbow's piece count) called by bisection on cheap inputs, never by doing the work: the size just
over the limit and the message a user sees there are recorded in each row (``refusal``).
- punch: bench_punch's 400 mm elbow in 8 .. 60 pieces, every piece's program simulated.
"""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
OUT = os.path.join(HERE, "scaling.json")

ENGRAVE_WIDTHS = (200, 400, 800, 1200)
# plate width (mm): (CPU s, peak RSS MB) of plan + bake + gate before the change, measured at its
# start with the same child (the 1200 mm plate with the cell limit lifted to allow 0.1 mm)
ENGRAVE_BEFORE = {200: (0.52, 448), 400: (1.13, 703), 800: (3.34, 1589), 1200: (7.71, 3048)}
# batch.py engrave of that sign before the change (CPU s user + sys, peak RSS MB; /usr/bin/time, the
# base commit ae77f3d, same session): the gate fell back to 0.2 mm cells
ENGRAVE_SIGN_BEFORE = (3.9, 1056)
CARVE_AREAS = (1.0, 2.0, 4.0)
CARVE_SCALLOPS = (0.08, 0.02, 0.005)
TURNMILL_SPLITS = (0, 1, 2, 3)
SIMULATE_MOVES = (10_000, 100_000, 1_000_000)
PART21_POCKETS = (400, 1600, 6400, 12800)
SIMULATE_STOCK = (0.0, 0.0, -20.0, 200.0, 100.0, 0.0)
PUNCH_PIECES = (8, 15, 30, 60)      # the workflow takes 2 .. 60 pieces (operators/limits.py)


# ----- the children ---------------------------------------------------------------------------------

def _measure(work) -> dict:
    import resource

    start = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    started = time.process_time()
    extra = work() or {}
    cpu = time.process_time() - started
    return {"cpu_s": cpu, "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
            "start_rss_mb": start, **extra}


def _engrave(width: float) -> dict:
    import numpy as np

    from bench_engrave import sample_inputs
    from kezuri.toolpath import simulate as sim
    from kezuri.toolpath.operations.engrave import engrave

    sample_plate, sample_letters = sample_inputs()
    s = width / 200.0
    plate = [np.asarray(loop) * s for loop in sample_plate]
    letters = [(name, [np.asarray(loop) * s for loop in loops]) for name, loops in sample_letters]

    def cut(plate, letters, cell):
        result = engrave.plan(plate, letters)
        baked, _ = engrave.bake(result.program)
        extra = engrave.simulation_limits([loop for _, loops in letters for loop in loops], result.program,
                                          engrave.EngraveSettings().band_depth)
        simulated = sim.simulate(baked, engrave.plate_stock(plate, 10.0), cell=cell, **extra)
        hf = simulated.heightfield
        return {"moves": sum(len(op) for op in baked.operations), "cells": int(hf.shape[0] * hf.shape[1]),
                "findings": len(simulated.findings)}

    # warm-up, as the other children do: the first call loads the compiled kernels (the 200 mm plate:
    # 0.37 s CPU cold, 0.10 s warm, 2026-11-28); the points measured it until then, ENGRAVE_BEFORE's too
    cut(sample_plate, sample_letters, 0.5)
    return _measure(lambda: cut(plate, letters, 0.1))


def _carve(area: float, scallop: float) -> dict:
    from kezuri.toolpath.operations.carve import carve, carve_samples

    vertices, faces = carve_samples.wave_relief()
    vertices = vertices.copy()
    vertices[:, :2] *= math.sqrt(area)
    settings = carve.CarveSettings(scallop=scallop)
    carve.plan(*carve_samples.wave_relief())      # kernels compiled and loaded

    def work():
        result = carve.plan(vertices, faces, settings)
        return {"stepover_mm": result.stepover, "moves": sum(len(op) for op in result.program.operations)}
    return _measure(work)


def _turnmill(splits: int) -> dict:
    import trimesh

    from kezuri.toolpath.operations.turnmill import turnmill

    vertices, faces, stock = turnmill.sample_part()
    for _ in range(splits):
        vertices, faces = trimesh.remesh.subdivide(vertices, faces)
    turnmill.plan(*turnmill.sample_part())          # kernels loaded, trimesh's first ray scene built

    def work():
        result = turnmill.plan(vertices, faces, stock)
        return {"faces": len(faces), "moves": sum(len(op) for op in result.program.operations)}
    return _measure(work)


def _punch(pieces: int) -> dict:
    """bench_punch's elbow of a 400 mm pipe in ``pieces`` pieces, every piece's program punched."""
    from bench_punch import elbow_programs
    from kezuri.toolpath.operations.sheetmetal import punch

    programs = elbow_programs(pieces=pieces)
    punch.simulate_punching(*programs[0][:1], punch_diameter=10.0)     # loaded

    def work():
        hits = 0
        for text, outline, joints in programs:
            hits += punch.simulate_punching(text, punch_diameter=10.0, pattern=outline, joints=joints).hits
        return {"pieces": pieces, "hits": hits}
    return _measure(work)


def raster_text(moves: int) -> str:
    from bench_simulate import raster
    from kezuri.post import registry
    from kezuri.toolpath.ir.program import Program

    return registry.create(["milling"], "linuxcnc").to_text(Program("raster", [raster(moves)]))


def _simulate(path: str, bulk: bool) -> dict:
    from kezuri.toolpath import simulate as sim
    from kezuri.toolpath.simulate import ncread

    with open(path) as stream:
        text = stream.read()
    tool = ncread.parse_tool("ball:6")
    sim.simulate(ncread.read_nc(text[:50_000].rsplit("\n", 1)[0], tool).runs[0][0], SIMULATE_STOCK, cell=0.5)

    def work():
        read = ncread.read_nc(text, tool, "raster", bulk=bulk)
        started = time.process_time()
        sim.simulate([run for run, _ in read.runs], SIMULATE_STOCK, cell=0.1)
        return {"moves": len(read.operation), "simulate_s": time.process_time() - started,
                "megabytes": len(text) / 1e6}
    return _measure(work)


def _batch_simulate(path: str) -> dict:
    import batch

    def work():
        status = batch.main(["batch.py", "simulate", "--nc", path, "--tool", "ball:6", "--stock",
                             "box:" + ",".join(f"{v:g}" for v in SIMULATE_STOCK), "--out", path + ".out"])
        return {"status": status}
    return _measure(work)


def _part21(path: str) -> dict:
    from kezuri.toolpath.operations import stepnc

    with open(path) as stream:
        text = stream.read()

    def work():
        stepnc.parse_part21(text)
        return {"megabytes": len(text.encode()) / 1e6}
    return _measure(work)


def _batch_engrave(blend: str) -> dict:
    import batch

    def work():
        out = blend + ".out"
        status = batch.main(["batch.py", "engrave", "--blend", blend, "--post", "linuxcnc", "--out", out,
                             "--travel", "1400", "800", "150"])      # the preset's 600 x 400 mm would not hold it
        with open(os.path.join(out, "report.json")) as stream:
            return {"status": status, "gate_cell_mm": json.load(stream)["gate"]["cell_mm"]}
    return _measure(work)


def _sign_blend(path: str) -> dict:
    """The sample name plate at 6 mm per unit: a 1200 x 600 mm sign (as tests/test_hostile_batch.py)."""
    import batch
    batch.load_extension()
    import bpy

    from kezuri.operators import batchio, samples
    scene = batchio.open_blend(None)
    samples.name_plate(scene)
    scene.unit_settings.scale_length = 0.006
    bpy.ops.wm.save_as_mainfile(filepath=path)
    return {"path": path}


# ----- where each row is refused up front ---------------------------------------------------------

def first_over(refusal, low: float, high: float, whole: bool = False, rounds: int = 60) -> float:
    """The smallest size in (low, high] that ``refusal(size)`` refuses (it returns the message, or
    None), by bisection: refusals grow with the size, ``low`` passes and ``high`` is refused."""
    assert refusal(low) is None and refusal(high) is not None, (low, high)
    for _ in range(rounds):
        if (high - low <= 1) if whole else (high - low <= 1e-4 * high):
            break
        middle = (low + high) // 2 if whole else (low + high) / 2
        if refusal(middle) is None:
            low = middle
        else:
            high = middle
    return high


def refused_by(call):
    """The message of the InputError ``call()`` raises (the real refusal), or None when it passes."""
    from kezuri.toolpath.ir.errors import InputError
    try:
        call()
    except InputError as error:
        return str(error)
    return None


def _limits() -> dict:
    """For each series: the size at which the workflow refuses before doing the work, found with the
    workflows' own up-front checks (estimates and grid counts: never the work itself), and the
    message a user sees there."""
    import numpy as np

    from bench_engrave import sample_inputs
    from kezuri.toolpath import workload
    from kezuri.toolpath.job import Setup, kind_of
    from kezuri.toolpath.operations.carve import carve, carve_samples
    from kezuri.toolpath.operations.carve.kind import CarveGeometry
    from kezuri.toolpath.operations.engrave import engrave
    from kezuri.toolpath.operations.sheetmetal import unfold
    from kezuri.toolpath.operations.turnmill import turnmill
    from kezuri.toolpath.simulate import MAX_CELLS
    from kezuri.toolpath.simulate.heightfield import stock_grid

    out = {}
    # engrave: the gate's 0.1 mm grid (past MAX_CELLS the gate goes to 0.2 .. 1.6 mm) and the gouges
    plate, letters = sample_inputs()
    x0, y0 = np.vstack(plate).min(axis=0)
    x1, y1 = np.vstack(plate).max(axis=0)
    sample_width = x1 - x0

    def cells(width, cell):
        s = width / sample_width
        return math.ceil((x1 - x0) * s / cell - 1e-9) * math.ceil((y1 - y0) * s / cell - 1e-9)

    def grid_refusal(cell):
        def refusal(width):
            if cells(width, cell) <= MAX_CELLS:        # the grid would be made: not called
                return None
            stock = engrave.plate_stock([np.asarray(loop) * (width / sample_width) for loop in plate], 10.0)
            return refused_by(lambda: stock_grid(stock, cell))
        return refusal

    def gouges(width):
        s = width / sample_width
        area, _, _ = workload.outline_measures([np.asarray(loop) * s for loop in plate])
        _, perimeter, _ = workload.outline_measures([np.asarray(loop) * s for _, loops in letters for loop in loops])
        return refused_by(lambda: workload.engrave("sign", area, perimeter, engrave.EngraveSettings()))
    fine = first_over(grid_refusal(0.1), 200, 4000, whole=True)
    coarsest = first_over(grid_refusal(1.6), 200, 100_000, whole=True)
    planned = first_over(gouges, 200, 100_000, whole=True)
    out["engrave"] = {"gate_0.1_mm_width": fine, "gate_0.1_mm_message": grid_refusal(0.1)(fine),
                      "gate_1.6_mm_width": coarsest, "gouges_width": planned, "gouges_message": gouges(planned)}
    # carve: the finishing raster's tool positions, over the area and over 1 / scallop
    vertices, faces = carve_samples.wave_relief()

    def carve_refusal(area, scallop, spacing=carve.CarveSettings().sample_spacing):
        v = vertices.copy()
        v[:, :2] *= math.sqrt(area)
        settings = carve.CarveSettings(scallop=scallop, sample_spacing=spacing)
        return refused_by(lambda: kind_of("carve").workload(Setup(name="relief"), settings, CarveGeometry(v, faces, 0.0)))
    area = first_over(lambda a: carve_refusal(a, 0.02), 1.0, 1e4)
    # the finest scallop the settings take (operators/limits.py: scallop from 0.0001 mm) is not refused at
    # the default sample spacing: the limit is met when the spacing is fine as well
    finest = 0.0001
    size = tuple(vertices.max(axis=0) - vertices.min(axis=0))
    positions = workload.carve("relief", size, 0.0, carve.CarveSettings(scallop=finest))[0].amount
    inverse = first_over(lambda q: carve_refusal(1.0, finest, 1.0 / q), 1.0 / 0.25, 1.0 / 0.01)
    out["carve"] = {"area_x": area, "area_message": carve_refusal(area, 0.02), "finest_scallop_mm": finest,
                    "finest_scallop_positions": positions, "spacing_mm": 1.0 / inverse,
                    "spacing_message": carve_refusal(1.0, finest, 1.0 / inverse)}
    # turn-mill: classification samples; a face split in 4 (the bench's subdivision) has a quarter of its area
    v, f, _ = turnmill.sample_part()
    t = v[f]
    areas = np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1) / 2.0

    def faces_refusal(times):
        return refused_by(lambda: workload.turnmill("part", np.repeat(areas / times, int(times)),
                                                    turnmill.TurnMillSettings()))
    times = first_over(faces_refusal, 1, 4096, whole=True)
    out["turnmill"] = {"faces": int(times) * len(f), "faces_x": int(times), "message": faces_refusal(times)}
    # simulate --nc: the lines of the program; the height field's cells
    out["simulate"] = {"lines": workload.LIMITS["nc lines"].most + 1,
                       "message": refused_by(lambda: workload.nc_program(
                           "raster.ngc", int(workload.LIMITS["nc lines"].most) + 1)),
                       "max_cells": MAX_CELLS}
    # Part 21: the STEP-NC workflow's file size
    most = int(workload.LIMITS["stepnc bytes"].most)
    out["part21"] = {"bytes": most + 1, "message": refused_by(lambda: workload.stepnc("pockets.stp", most + 1))}
    # punching: pieces of an elbow (one program each; a program's hits are limited, not the pieces' sum):
    # the workflow's range (panel and batch --pieces, as argparse says it), the core's own limit behind it
    import argparse

    from kezuri.operators.batchio import number
    from kezuri.operators.limits import RANGES
    allowed = RANGES["sheet"]["elbow_pieces"]
    try:
        number("--pieces", limit=allowed)(str(int(allowed.hi) + 1))
        taken = None
    except argparse.ArgumentTypeError as error:
        taken = f"argument --pieces: {error}"
    core = unfold.MAX_DIVISIONS + 1
    out["punch"] = {"pieces": int(allowed.hi) + 1, "message": taken, "core_pieces": core,
                    "core_message": refused_by(lambda: unfold.unfold_elbow(90.0, 3000.0, 400.0, core))}
    return out


def _write(kind: str, size: int, path: str) -> dict:
    """The input files, written by a child of their own (their writing's memory is not the reader's)."""
    if kind == "sign":
        return _sign_blend(path)
    if kind == "nc":
        text = raster_text(size)
    else:
        from bench_stepnc import large_file
        text = large_file(size)
    with open(path, "w") as stream:
        stream.write(text)
    return {"path": path}


def child(argv: list) -> dict:
    sys.path.insert(0, ROOT)
    sys.path.insert(0, HERE)
    kind, *values = argv
    if kind == "batch":
        return _batch_simulate(values[0])
    if kind == "batch-engrave":
        return _batch_engrave(values[0])
    if kind == "write" and values[0] == "sign":
        return _write("sign", 0, values[2])
    if kind == "limits":
        import batch
        batch.load_extension()
        return _limits()
    from batch import import_package
    import_package()
    if kind == "engrave":
        return _engrave(float(values[0]))
    if kind == "carve":
        return _carve(float(values[0]), float(values[1]))
    if kind == "turnmill":
        return _turnmill(int(values[0]))
    if kind == "simulate":
        return _simulate(values[0], values[1] == "bulk")
    if kind == "part21":
        return _part21(values[0])
    if kind == "punch":
        return _punch(int(values[0]))
    if kind == "write":
        return _write(values[0], int(values[1]), values[2])
    raise SystemExit(f"unknown child {kind}")


# ----- the parent -----------------------------------------------------------------------------------

def run_child(*args) -> dict:
    done = subprocess.run([sys.executable, os.path.abspath(__file__), "--child", *map(str, args)],
                          capture_output=True, text=True, cwd=ROOT)
    lines = [line for line in done.stdout.splitlines() if line.startswith("{")]
    if done.returncode or not lines:
        raise RuntimeError(f"bench child {args} failed:\n{done.stderr[-3000:]}")
    return json.loads(lines[-1])


def exponent(sizes, seconds) -> float:
    """The slope of log(seconds) on log(size), least squares."""
    import numpy as np

    x, y = np.log(np.asarray(sizes, float)), np.log(np.asarray(seconds, float))
    return float(np.polyfit(x, y, 1)[0])


def series(name, unit, sizes, points, size_of, before=None, note="", refused=("—", None)):
    """One table row per point, and the fitted exponents (CPU and peak RSS above the start);
    ``refused``: (where the workflow refuses up front, the message it gives there)."""
    cpu = [p["cpu_s"] for p in points]
    fitted = exponent([size_of(s) for s in sizes], cpu)
    memory = exponent([size_of(s) for s in sizes], [max(p["peak_rss_mb"] - p["start_rss_mb"], 1.0) for p in points])
    rows = []
    for size, point in zip(sizes, points):
        row = {"name": f"scaling: {name}, {unit(size)}", "seconds": point["cpu_s"], "target_s": None,
               "cpu_s": round(point["cpu_s"], 3), "peak_rss_mb": round(point["peak_rss_mb"]),
               "exponent": round(fitted, 2), "memory_exponent": round(memory, 2), "refused_up_front_at": refused[0],
               "refusal": refused[1], "point": point}
        if before is not None:
            row["before_cpu_s"], row["before_peak_rss_mb"] = before(size)
        row["notes"] = (f"peak {point['peak_rss_mb']:.0f} MB; CPU ~ size^{fitted:.2f} over the series"
                        + (f"; before: {row['before_cpu_s']:.2f} s, {row['before_peak_rss_mb']:.0f} MB"
                           if before is not None and row["before_cpu_s"] is not None else "") + note)
        rows.append(row)
    return rows


def refusals(limits: dict) -> dict:
    """(short text for the README's column, the message) of each series, from :func:`_limits`."""
    e, c, t = limits["engrave"], limits["carve"], limits["turnmill"]
    cells = limits["simulate"]["max_cells"] / 1e6
    engrave = (f"gate at 0.1 mm up to a {e['gate_0.1_mm_width']:,} mm wide plate ({cells:.0f} M cells), then on 0.2 .. "
               f"1.6 mm cells (report: gate cell_mm); planning refused past {e['gouges_width'] / 1000:.1f} m wide "
               f"(2e6 gouges), exit 2", e["gouges_message"])
    simulate = (f"1e7 lines (new), exit 2; the stock past {cells:.0f} M cells at --cell, exit 2",
                limits["simulate"]["message"])
    return {
        "engrave": engrave,
        "carve area": (f"area x{c['area_x']:.0f} (2e7 tool positions), exit 2", c["area_message"]),
        "carve scallop": (f"not by the scallop: at {c['finest_scallop_mm']:g} mm (the finest taken) "
                          f"{c['finest_scallop_positions'] / 1e6:.1f} M positions; with sample spacing under "
                          f"{c['spacing_mm']:.4f} mm as well, exit 2", c["spacing_message"]),
        "turnmill": (f"{t['faces']:,} faces (x{t['faces_x']}: 5e6 samples, 4 a face at least), exit 2", t["message"]),
        "simulate": simulate,
        "part21": (f"{limits['part21']['bytes'] / 1e6:.0f} MB, exit 2", limits["part21"]["message"]),
        "punch": (f"{limits['punch']['pieces']} pieces (the panel's and batch's range; the core's: "
                  f"{limits['punch']['core_pieces'] - 1:,}), exit 2; 20,000 hits a program", limits["punch"]["message"]),
    }


def run() -> list:
    import shutil
    import tempfile

    load = os.getloadavg()[0]
    refused = refusals(run_child("limits"))
    rows = []
    engrave = [run_child("engrave", w) for w in ENGRAVE_WIDTHS]
    rows += series("engrave plan + bake + gate at 0.1 mm", lambda w: f"{w} x {w // 2} mm plate", ENGRAVE_WIDTHS,
                   engrave, lambda w: w * w / 2, before=lambda w: ENGRAVE_BEFORE.get(w, (None, None)),
                   note="; exponent on the plate's area", refused=refused["engrave"])
    folder = tempfile.mkdtemp(prefix="kezuri-scaling-")
    try:
        sign = run_child("batch-engrave", run_child("write", "sign", 0, os.path.join(folder, "sign.blend"))["path"])
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    rows.append({"name": "scaling: batch.py engrave, the sample as a 1200 x 600 mm sign (whole command)",
                 "seconds": sign["cpu_s"], "target_s": None, "cpu_s": round(sign["cpu_s"], 3),
                 "peak_rss_mb": round(sign["peak_rss_mb"]), "exponent": None,
                 "refused_up_front_at": refused["engrave"][0], "refusal": refused["engrave"][1], "point": sign, "before_cpu_s": ENGRAVE_SIGN_BEFORE[0], "before_peak_rss_mb": ENGRAVE_SIGN_BEFORE[1],
                 "notes": f"gate cell {sign['gate_cell_mm']:g} mm (target: 0.1 mm within 2 GB); peak "
                          f"{sign['peak_rss_mb']:.0f} MB; before: {ENGRAVE_SIGN_BEFORE[0]} s, "
                          f"{ENGRAVE_SIGN_BEFORE[1]} MB with the gate at 0.2 mm (the 0.1 mm grid was over the "
                          "cell limit)"})
    carve_area = [run_child("carve", a, 0.02) for a in CARVE_AREAS]
    rows += series("carve wave relief, scallop 0.02 mm", lambda a: f"area x{a:g}", CARVE_AREAS, carve_area,
                   lambda a: a, note="; exponent on the area", refused=refused["carve area"])
    carve_step = [run_child("carve", 1.0, s) for s in CARVE_SCALLOPS]
    rows += series("carve wave relief, 120 x 80 mm", lambda s: f"scallop {s:g} mm", CARVE_SCALLOPS, carve_step,
                   lambda s: 1.0 / [p for p, v in zip(carve_step, CARVE_SCALLOPS) if v == s][0]["stepover_mm"],
                   note="; exponent on 1 / stepover", refused=refused["carve scallop"])
    turn = [run_child("turnmill", k) for k in TURNMILL_SPLITS]
    rows += series("turn-mill sample part plan", lambda k: f"faces x{4 ** k}", TURNMILL_SPLITS, turn,
                   lambda k: 4 ** k, note="; exponent on the face count", refused=refused["turnmill"])
    folder = tempfile.mkdtemp(prefix="kezuri-scaling-")
    try:
        programs = [run_child("write", "nc", m, os.path.join(folder, f"raster-{m}.ngc"))["path"] for m in SIMULATE_MOVES]
        bulk = [run_child("simulate", path, "bulk") for path in programs]
        old = [run_child("simulate", path, "lines") for path in programs]
        whole = run_child("batch", programs[-1])
        files = [run_child("write", "p21", p, os.path.join(folder, f"pockets-{p}.stp"))["path"] for p in PART21_POCKETS]
        part21 = [run_child("part21", path) for path in files]
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    before = {m: (p["cpu_s"], p["peak_rss_mb"]) for m, p in zip(SIMULATE_MOVES, old)}
    rows += series("simulate NC: read + cut at 0.1 mm", lambda m: f"{m:.0e} moves", SIMULATE_MOVES, bulk,
                   lambda m: m, before=lambda m: before[m],
                   note="; before = the reader following every line one at a time, same run",
                   refused=refused["simulate"])
    rows.append({"name": f"scaling: batch.py simulate --nc, {SIMULATE_MOVES[-1]:.0e} moves (whole command)",
                 "seconds": whole["cpu_s"], "target_s": 10.0, "cpu_s": round(whole["cpu_s"], 3),
                 "peak_rss_mb": round(whole["peak_rss_mb"]), "exponent": None,
                 "refused_up_front_at": refused["simulate"][0], "refusal": refused["simulate"][1], "point": whole, "before_cpu_s": 13.7, "before_peak_rss_mb": 954,
                 "notes": f"CPU s incl. Blender start-up, reading, cutting, STL and picture; peak "
                          f"{whole['peak_rss_mb']:.0f} MB; before (at the start of the change): 13.7 s, 954 MB"})
    size = {p: q["megabytes"] for p, q in zip(PART21_POCKETS, part21)}
    rows += series("Part 21 parse (pocket plates)", lambda p: f"{size[p]:.1f} MB", PART21_POCKETS, part21,
                   lambda p: size[p], note="; exponent on the file size", refused=refused["part21"])
    punched = [run_child("punch", n) for n in PUNCH_PIECES]
    rows += series("punch: 400 mm pipe elbow, every piece's program simulated", lambda n: f"{n} pieces", PUNCH_PIECES,
                   punched, lambda n: n, note="; exponent on the pieces", refused=refused["punch"])
    for row in rows:
        row["load"] = round(load, 2)
    with open(OUT, "w") as stream:
        json.dump({"load_at_start": load, "cpus": os.cpu_count(), "rows": rows}, stream, indent=2)
    return rows


def table(rows) -> str:
    """The README's table (markdown)."""
    lines = ["| work | CPU s | peak RSS MB | CPU exponent | before: CPU s, MB | refused up front at |",
             "|---|---:|---:|---:|---|---|"]
    for r in rows:
        before = (f"{r['before_cpu_s']:.2f}, {r['before_peak_rss_mb']:.0f}"
                  if r.get("before_cpu_s") is not None else "")
        fitted = "" if r.get("exponent") is None else f"{r['exponent']:.2f}"
        lines.append(f"| {r['name'][len('scaling: '):]} | {r['cpu_s']:.2f} | {r['peak_rss_mb']} | {fitted} | {before} "
                     f"| {r['refused_up_front_at']} |")
    return "\n".join(lines)


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--child":
        print(json.dumps(child(sys.argv[2:])))
    else:
        print(table(run()))
        print(f"wrote {OUT}")
