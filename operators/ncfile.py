"""W6 for any NC file: ``batch.py simulate --nc FILE``: read G-code in our posts' LinuxCNC/Fanuc
dialect, cut a stock with it, check it against a design mesh, write the carved stock as STL."""
from __future__ import annotations

import os
from types import SimpleNamespace

from ..toolpath import simulate as core
from ..toolpath.engines import meshfile
from ..toolpath.engines.textfile import read_text, refusal
from .workflow import BatchCommand, Workflow


def batch_arguments(p):
    p.add_argument("--nc", required=True, help="G-code in our posts' LinuxCNC/Fanuc dialect")
    p.add_argument("--tool", required=True, help="ball:D, flat:D or bull:D,R (mm)")
    p.add_argument("--stock", required=True, help="box:x0,y0,z0,x1,y1,z1 or cylinder:R,H (axis Z, top at z = 0)")
    p.add_argument("--rotary", choices=["c"], help="C words turn the part about Z")
    p.add_argument("--design", help="the finished part as STL/OBJ/PLY, for the gouge check")
    p.add_argument("--engine", choices=list(core.ENGINES), default="heightfield")
    from .batchio import number
    from .limits import RANGES
    p.add_argument("--cell", type=number("--cell", limit=RANGES["simulation"]["cell"]), default=0.1,
                   help="height-field cell (mm)")


def parse_stock(text: str):
    kind, _, sizes = text.partition(":")
    try:
        numbers = [float(v) for v in sizes.split(",")]
    except ValueError:
        raise core.SimulationError(f"--stock {text!r}: not numbers") from None
    if kind == "box" and len(numbers) == 6:
        return core.BoxStock(*numbers)
    if kind == "cylinder" and len(numbers) == 2:
        return core.CylinderStock(*numbers)
    raise core.SimulationError(f"--stock {text!r}: give box:x0,y0,z0,x1,y1,z1 or cylinder:R,H")


def load_design(path: str, option: str = "--design"):
    """The design mesh (vertices, faces in mm) of an STL/OBJ/PLY file (:func:`meshfile.read_mesh`: a
    file that is no mesh, or random bytes that load as one without faces, is refused naming it)."""
    vertices, faces = meshfile.read_mesh(path, option)
    return SimpleNamespace(vertices=vertices, faces=faces)


def batch(args) -> dict:
    import trimesh

    from ..post import write_atomic
    from ..toolpath.simulate import ncread
    from . import batchio, convert, preview, simview
    from .common import Progress

    problem = refusal(f"--nc {args.nc}", args.nc, "an NC file")
    if problem:
        raise core.SimulationError(problem)
    tool = ncread.parse_tool(args.tool)
    from .limits import DIAMETER, LIBRARY
    # the one table of ranges: before, flat:1e6 (a 1 km end mill) and flat:1e-9 were simulated
    for label, value, limit in (("diameter", tool.diameter, DIAMETER),
                                ("corner radius", tool.corner_radius if tool.kind == "bull" else 0.0,
                                 LIBRARY["corner_radius"])):
        if not limit.allows(value):
            raise core.SimulationError(f"--tool {args.tool!r}: {label} {value:g} mm is outside the allowed range "
                                       f"{limit.text(label)}")
    stock = parse_stock(args.stock)
    core.check_cell(stock, args.cell)       # before reading: a 1e7-line file took its whole read to be refused
    text = read_text(args.nc)
    from ..toolpath import workload
    workload.nc_program(args.nc, workload.nc_lines(text))    # before reading: 1e7 lines is about 4 GB and 40 s
    progress = Progress(None, "simulate")      # on stderr; a long run can be stopped (Ctrl-C) between its steps
    try:
        read = ncread.read_nc(text, tool, os.path.basename(args.nc), progress=lambda f: progress(0.3 * f, "reading"))
    except ncread.NCReadError as error:     # which file the line is of
        raise ncread.NCReadError(f"--nc {args.nc}: {error}") from None
    op, lines = read
    if not args.rotary:
        import numpy as np
        c = op.rotary.get("c")
        turns = np.flatnonzero(np.abs(c - c[0]) > 1e-9) if c is not None else []
        if len(turns):      # before: the C words were dropped without a word, the part never turned
            raise core.SimulationError(f"--nc {args.nc}: line {lines[turns[0]]} turns the C axis; give --rotary c "
                                       f"to simulate the part turning with it")
        op.rotary = {}
        runs = [(run.replace(rotary={}), run_lines) for run, run_lines in read.runs]
    else:
        runs = read.runs
    design = None
    if args.design:
        design = load_design(args.design)
    # one operation per spindle state (the reader's runs): a cut with the spindle stopped is named by its line
    result = core.simulate([run for run, _ in runs], stock, engine=args.engine, cell=args.cell, design=design,
                           design_name=os.path.basename(args.design or ""),
                           progress=lambda f: progress(0.3 + 0.7 * f, "cutting"))
    report = simview.report_of(result)
    report["nc_ignored"] = read.ignored          # what the reader read and set aside, per code
    report["warnings"] = list(result.warnings)   # what the simulation repaired in its input
    for entry in report["gouges"] + report["rapid_collisions"] + report["other_findings"]:
        entry["line"] = runs[entry["operation"]][1][entry["move"]]
    vertices, faces = result.mesh()
    mesh_path = write_atomic(os.path.join(args.out, "simulated.stl"),
                             trimesh.Trimesh(vertices, faces, process=False).export(file_type="stl"))
    scene = batchio.open_blend(None)
    job = simview.SimulationJob(result, convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0)), "nc")
    simview.show_simulation(scene, job, mesh=(vertices, faces))
    png = preview.simulation_png(os.path.join(args.out, "simulated.png"), result,
                                 f"NC FILE: {os.path.basename(args.nc)} SIMULATED", mesh=(vertices, faces))
    return {"workflow": "simulate", "files": [mesh_path], "preview": png, "nc": os.path.abspath(args.nc),
            "moves": len(op), "simulation": report}


WORKFLOW = Workflow(
    "NCFILE", "NC File", "Material removal and safety checks of an NC file",
    commands=(BatchCommand("simulate", "material removal and safety checks of an NC file (W6)", batch_arguments,
                           batch, demo=None),))
