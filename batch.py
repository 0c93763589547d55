"""Kezuri CAM batch entry point.

    python batch.py <command> [options]                      (the bpy wheel from PyPI)
    blender -b [file.blend] --python batch.py -- <command> [options]

Commands (``python batch.py <command> --help`` for the options):
    engrave   gouge-texture name plate (W1)
    rotary    bento-block pockets on a rotating table, C-X-Z (W2)
    stepnc    ISO 14649 (STEP-NC) workplan to G-code (W3)
    turnmill  4.5-axis turn-mill: radial/axial classification and paths, X-Z-C (W4)
    unfold    twisted quad -> flat pattern, turret-punch NC, DXF, SVG (W5)
    elbow     segmented pipe elbow -> flat patterns, DXF, SVG (W5)
    simulate  material removal and safety checks of any NC file we can read (W6)
    demo      every workflow on its built-in sample part, each into a sub-folder of --out

Each command writes its output files, ``report.json`` and a preview PNG into --out.
Exit status: 0 on success, 2 on bad input (the message says what to fix).
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import os
import sys
import time

ROOT = os.path.dirname(os.path.abspath(__file__))


def import_package():
    """Import this folder as the package ``kezuri``, as Blender does (no bpy needed)."""
    if "kezuri" not in sys.modules:
        spec = importlib.util.spec_from_file_location("kezuri", os.path.join(ROOT, "__init__.py"),
                                                      submodule_search_locations=[ROOT])
        package = importlib.util.module_from_spec(spec)
        sys.modules["kezuri"] = package
        spec.loader.exec_module(package)
    return sys.modules["kezuri"]


def load_extension():
    """Import the package and register it with Blender."""
    package = import_package()
    import bpy
    if not hasattr(bpy.types.Scene, "kezuri"):
        package.register()
    return package


def script_arguments(argv: list) -> list:
    """Arguments after ``--`` when run by Blender, else everything after the script name."""
    return argv[argv.index("--") + 1:] if "--" in argv else argv[1:]


def open_blend(path: str | None):
    """The scene to work on: the given .blend's, or a fresh empty one in millimetres."""
    import bpy

    from kezuri.operators import samples
    if path:
        if not os.path.isfile(path):
            raise FileNotFoundError(f"no such .blend file: {path}")
        bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path))
        return bpy.context.scene
    scene = bpy.context.scene
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    return scene


def write_report(out_dir: str, report: dict) -> str:
    from kezuri.post import write_atomic
    return write_atomic(os.path.join(out_dir, "report.json"), json.dumps(report, indent=2, sort_keys=True) + "\n")


def simulation_entry(scene, workflow: str, out_dir: str, stem: str) -> tuple:
    """Simulate the scene's job, render the carved stock to <stem>.png; (report entry, png)."""
    from kezuri.operators import preview
    from kezuri.operators import simulate as shell
    from kezuri.operators.common import Progress

    job = shell.simulate_job(scene, workflow, "heightfield", 0.1, Progress(None, "simulate"))
    carved = shell.show_simulation(scene, job)
    png = preview.render_preview(scene, [carved], [], os.path.join(out_dir, f"{stem}.png"), see_through=False,
                                 color_type="VERTEX")
    return shell.report_of(job.result), png


def rounded(array, digits: int = 6):
    import numpy as np
    return np.round(np.asarray(array, float), digits).tolist()


# ----------------------------------------------------------------------------------------
# W1 engrave

def engrave_arguments(p):
    p.add_argument("--blend", help="a .blend whose scene has the Kezuri plate and letters set")
    p.add_argument("--post", choices=["fanuc", "fanuc-macro", "linuxcnc", "grbl"])
    p.add_argument("--seed", type=int)


def engrave(args) -> dict:
    import bpy

    from kezuri.operators import engrave as shell
    from kezuri.operators import preview, samples
    from kezuri.operators.common import Progress
    from kezuri.operators.preferences import scene_post

    scene = open_blend(args.blend)
    if not args.blend:
        samples.name_plate(scene)
    props = scene.kezuri
    if args.seed is not None:
        props.engrave.seed = args.seed
    post_name = args.post or scene_post(scene)
    started = time.perf_counter()
    job = shell.run_engrave(scene, bpy.context.evaluated_depsgraph_get(), Progress(None, "engrave"))
    seconds = time.perf_counter() - started
    nc_path = os.path.join(args.out, f"engrave{shell.extension_for(post_name)}")
    shell.export_engrave(job, post_name, nc_path, props.machine.work_offset)
    wires = shell.show_engrave(scene, job, show_rapids=False)
    toolpaths_png = preview.render_preview(scene, [props.stock.plate, *shell.letter_objects(props.engrave)], wires,
                                           os.path.join(args.out, "engrave-toolpaths.png"))
    simulation, png = simulation_entry(scene, "ENGRAVE", args.out, "engrave")
    return {
        "simulation": simulation,
        "toolpaths_preview": toolpaths_png,
        "workflow": "engrave",
        "post": post_name,
        "seed": props.engrave.seed,
        "files": [nc_path],
        "preview": png,
        "toolpath_seconds": round(seconds, 3),
        "operations": shell.program_for_post(job, post_name).summary(),
        "cycle_time_s": round(job.baked.cycle_time(), 1),
        "gouge_depths": [round(d, 4) for d in job.depths],
        "warnings": job.result.warnings,
        "skipped": job.result.skipped,
    }


# ----------------------------------------------------------------------------------------
# W2 rotary pockets

def rotary_arguments(p):
    p.add_argument("--blend", help="a .blend with the block as Kezuri stock and pocket outlines marked")
    p.add_argument("--post", choices=["linuxcnc", "fanuc"])


def rotary(args) -> dict:
    import bpy

    from kezuri.operators import preview, samples
    from kezuri.operators import rotary as shell
    from kezuri.operators.common import Progress

    scene = open_blend(args.blend)
    if not args.blend:
        samples.rotary_block(scene)
    post_name = args.post or scene.kezuri.rotary.post
    started = time.perf_counter()
    job = shell.run_rotary(scene, bpy.context.evaluated_depsgraph_get(), Progress(None, "rotary"))
    seconds = time.perf_counter() - started
    nc_path = shell.export_rotary(job, post_name, os.path.join(args.out, f"rotary{shell.extension_for(post_name)}"))
    paths = shell.show_rotary(scene, job)
    toolpaths_png = preview.render_preview(scene, [scene.kezuri.stock.plate], paths,
                                           os.path.join(args.out, "rotary-toolpaths.png"))
    simulation, png = simulation_entry(scene, "ROTARY", args.out, "rotary")
    return {
        "simulation": simulation,
        "toolpaths_preview": toolpaths_png,
        "workflow": "rotary",
        "post": post_name,
        "files": [nc_path],
        "preview": png,
        "toolpath_seconds": round(seconds, 3),
        "cycle_time_s": job.result.cycle_time_s,
        "operations": job.result.program.summary(),
        "pockets": job.result.reports,
    }


# ----------------------------------------------------------------------------------------
# W3 STEP-NC

def stepnc_arguments(p):
    p.add_argument("--input", help="ISO 14649 Part 21 file (.stp, .p21); default: a built-in two-pocket plate")
    p.add_argument("--post", choices=["fanuc", "linuxcnc", "grbl"])
    p.add_argument("--order", help="workingstep instance ids in the order to cut, e.g. 13,14,10 (default: "
                                   "the workplan's order); workingsteps left out are not cut")


def stepnc_sample(out_dir: str) -> str:
    """A 120 x 80 x 20 mm plate with a rectangular and an L-shaped pocket, as ISO 14649."""
    from kezuri.post import write_atomic
    from kezuri.toolpath import stepnc
    from kezuri.toolpath.program import Tool

    pockets = [stepnc.PocketSpec("POCKET1", ((10, 10), (50, 10), (50, 40), (10, 40)), 8.0),
               stepnc.PocketSpec("POCKET2", ((65, 15), (110, 15), (110, 35), (85, 35), (85, 70), (65, 70)), 5.0)]
    text = stepnc.pockets_to_part21(((0, 0, -20), (120, 80, 0)), pockets, Tool(1, "flat", 6.0, flute_length=20.0),
                                    name="KEZURI SAMPLE PLATE")
    return write_atomic(os.path.join(out_dir, "sample.stp"), text)


def stepnc_job(args) -> dict:
    from kezuri.operators import preview
    from kezuri.operators import stepnc as shell
    from kezuri.toolpath import stepnc

    scene = open_blend(None)
    path = args.input or stepnc_sample(args.out)
    if not os.path.isfile(path):
        raise FileNotFoundError(f"no such ISO 14649 file: {path}")
    loaded = stepnc.load_workplan(path)
    shell.fill_workplan_list(scene, os.path.abspath(path), loaded)
    if args.order:
        try:
            wanted = [int(v.strip().lstrip("#")) for v in args.order.split(",") if v.strip()]
        except ValueError:
            raise ValueError(f"--order: instance ids separated by commas, got {args.order!r}") from None
        steps = scene.kezuri.stepnc.steps
        known = [item.ident for item in steps]
        for ident in wanted:
            if ident not in known:
                raise ValueError(f"--order: #{ident} is not a workingstep of {path} ({known})")
        for target, ident in enumerate(wanted):
            steps.move([item.ident for item in steps].index(ident), target)
        for item in steps:
            item.enabled = item.ident in wanted
    post_name = args.post or "fanuc"
    extension = ".ngc" if post_name == "linuxcnc" else ".nc"
    nc_path, program = shell.export_nc(scene, post_name, os.path.join(args.out, f"stepnc{extension}"))
    objects = shell.show_workplan(scene, loaded, program)
    solids = [o for o in objects if o.type == "MESH"]
    paths = [o for o in objects if o.type == "CURVE"]
    toolpaths_png = preview.render_preview(scene, solids, paths, os.path.join(args.out, "stepnc-toolpaths.png"))
    simulation, png = simulation_entry(scene, "STEPNC", args.out, "stepnc")
    steps = {step.id: step for step in loaded.workingsteps}
    order = [item.ident for item in scene.kezuri.stepnc.steps if item.enabled]
    workingsteps = []
    for ident, op in zip(order, program.operations):
        entry = shell.describe_step(steps[ident])
        entry.update(tool=op.tool.describe(), moves=len(op))
        workingsteps.append(entry)
    return {
        "workflow": "stepnc",
        "simulation": simulation,
        "toolpaths_preview": toolpaths_png,
        "input": os.path.abspath(path),
        "post": post_name,
        "files": [nc_path],
        "preview": png,
        "workingsteps": workingsteps,
        "operations": program.summary(),
        "warnings": list(program.notes),
        "cycle_time_s": round(program.cycle_time(), 1),
    }


# ----------------------------------------------------------------------------------------
# W4 turn-mill

def turnmill_arguments(p):
    source = p.add_mutually_exclusive_group()
    source.add_argument("--blend", help="a .blend whose Turn-Mill panel names the part and the stock")
    source.add_argument("--mesh", help="an STL/OBJ/PLY of the part in mm, around the Z axis (stock from its size)")
    p.add_argument("--engine", choices=["BVH", "TRIMESH"], help="ray engine (default: BVH, trimesh for --mesh)")


def turnmill_simulation(scene, job, out_dir: str) -> tuple:
    """Cut the bar with the job's program (radius map + height field), checked against the part;
    render the carved bar to turnmill.png: (report entry, png)."""
    from types import SimpleNamespace

    from kezuri.operators import preview
    from kezuri.operators import simulate as shell
    from kezuri.operators.common import Progress
    from kezuri.toolpath import simulate

    result = simulate.simulate(job.plan.program, job.stock, cell=0.1, progress=Progress(None, "simulate"),
                               design=SimpleNamespace(vertices=job.vertices, faces=job.faces))
    carved = shell.show_simulation(scene, shell.SimulationJob(result, job.frame, "turnmill"))
    png = preview.render_preview(scene, [carved], [], os.path.join(out_dir, "turnmill.png"), see_through=False,
                                 color_type="VERTEX")
    return shell.report_of(result), png


def turnmill_job(args) -> dict:
    import bpy
    import numpy as np

    from kezuri.operators import convert, preview, samples
    from kezuri.operators import turnmill as shell
    from kezuri.toolpath import turnmill as core

    scene = open_blend(args.blend)
    if args.mesh:
        import trimesh
        if not os.path.isfile(args.mesh):
            raise FileNotFoundError(f"no such mesh file: {args.mesh}")
        try:
            loaded = trimesh.load(args.mesh, force="mesh")
        except Exception as error:  # noqa: BLE001 - trimesh raises many kinds for a bad file
            raise core.TurnMillError(f"{args.mesh}: not a readable mesh ({error})") from None
        vertices, faces = np.asarray(loaded.vertices, float), np.asarray(loaded.faces)
        radius = float(np.hypot(vertices[:, 0], vertices[:, 1]).max()) if len(vertices) else 0.0
        stock = core.Stock(radius, float(vertices[:, 2].min()), float(vertices[:, 2].max())) if len(vertices) \
            else core.Stock(1.0, 0.0, 1.0)
        props = scene.kezuri.turnmill
        frame = convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0))
        job = shell.run_on_mesh(vertices, faces, stock, shell.settings_from(props), args.engine or "TRIMESH", frame,
                                name=os.path.basename(args.mesh))
        labels = job.plan.labels
        face_centroids = job.vertices[job.faces].mean(axis=1)
        solids = [convert.mesh_object(scene, "Kezuri Turn-Mill part", job.vertices, job.faces, frame)]
    else:
        if not args.blend:
            samples.turnmill_part(scene)
        if args.engine:
            scene.kezuri.turnmill.engine = args.engine
        job = shell.run_turnmill(scene, bpy.context.evaluated_depsgraph_get())
        part = scene.kezuri.turnmill.part
        labels = shell.polygon_labels(job.plan.labels, job.owner, len(part.data.polygons))
        shell.colour_faces(part, labels)
        face_centroids = np.array([job.frame.to_work([p.center])[0] for p in part.data.polygons]) if \
            part.matrix_world.is_identity else np.array([job.frame.to_work([part.matrix_world @ p.center])[0]
                                                         for p in part.data.polygons])
        solids = [part]
    files = [shell.export_turnmill(job, post, os.path.join(args.out, f"turnmill{shell.extension_for(post)}"))
             for post in ("xzc", "linuxcnc", "cldata")]
    paths = shell.show_turnmill(scene, job)
    toolpaths_png = preview.render_preview(scene, solids, paths, os.path.join(args.out, "turnmill-toolpaths.png"))
    simulation, png = turnmill_simulation(scene, job, args.out)
    return {
        "workflow": "turnmill",
        "files": files,
        "preview": png,
        "toolpaths_preview": toolpaths_png,
        "simulation": simulation,
        "engine": job.engine,
        "rays": job.rays,
        "classification_seconds": round(job.classification_seconds, 3),
        "faces": [{"centroid": rounded(c, 4), "label": shell.REPORT_LABELS[int(k)]}
                  for c, k in zip(face_centroids, labels)],
        "operations": job.plan.program.summary(),
        "cycle_time_s": round(job.plan.program.cycle_time(), 1),
    }


# ----------------------------------------------------------------------------------------
# W5 unfold and elbow

def unfold_arguments(p):
    source = p.add_mutually_exclusive_group()
    source.add_argument("--cdl", help="CADKEY .CDL file with the quad's four LINE records")
    source.add_argument("--corners", help='"x,y,z;x,y,z;x,y,z;x,y,z" in mm (default: the paper\'s test quad)')
    source.add_argument("--blend", help="a .blend whose Kezuri sheet settings hold the corners")
    p.add_argument("--divisions", type=int)
    p.add_argument("--direction", choices=["horizontal", "vertical"])
    p.add_argument("--tool-diameter", type=float)
    p.add_argument("--thickness", type=float)
    p.add_argument("--pitch", type=float)
    p.add_argument("--station", type=int)


def parse_corners(text: str):
    import numpy as np
    try:
        corners = np.array([[float(v) for v in corner.split(",")] for corner in text.split(";")])
    except ValueError:
        raise ValueError(f"--corners: not numbers: {text!r}") from None
    if corners.shape != (4, 3):
        raise ValueError(f'--corners needs four "x,y,z" corners separated by ";", got {text!r}')
    return corners


def unfold(args) -> dict:
    from kezuri.operators import preview
    from kezuri.operators import sheetmetal as shell
    from kezuri.toolpath import unfold as core

    scene = open_blend(args.blend)
    sheet = scene.kezuri.sheet
    for option, name in (("divisions", "divisions"), ("direction", "direction"), ("tool_diameter", "tool_diameter"),
                         ("thickness", "thickness"), ("pitch", "pitch"), ("station", "station")):
        if getattr(args, option) is not None:
            setattr(sheet, name, getattr(args, option))
    if args.cdl:
        if not os.path.isfile(args.cdl):
            raise FileNotFoundError(f"no such CDL file: {args.cdl}")
        with open(args.cdl, encoding="latin-1") as stream:
            corners = core.read_cdl(stream.read())
    elif args.corners:
        corners = parse_corners(args.corners)
    else:
        corners = shell.corners_mm(sheet)
    job = shell.run_unfold(corners, sheet)
    files = shell.unfold_files(job, os.path.join(args.out, "unfold.nc"))
    objects = shell.show_unfold(scene, job)
    png = preview.render_preview(scene, [o for o in objects if o.type == "MESH"], [o for o in objects if o.type != "MESH"],
                                 os.path.join(args.out, "unfold.png"), see_through=False)
    pattern = job.quad.pattern
    return {
        "workflow": "unfold",
        "files": files,
        "preview": png,
        "divisions": job.quad.divisions,
        "direction": job.quad.direction,
        "corners": rounded(job.quad.corners),
        "edge_lengths": rounded(job.quad.edge_lengths, 6),
        "diagonals": rounded(job.quad.diagonals, 6),
        "triangles": [{"3d": rounded(pattern.vertices_3d[t]), "2d": rounded(pattern.vertices_2d[t])}
                      for t in pattern.triangles],
        "outline": rounded(pattern.outline),
        "cut_contour": rounded(job.contour),
        "simulation": shell.punch_report([job.punched], sheet.thickness),
    }


def elbow_arguments(p):
    p.add_argument("--diameter", type=float)
    p.add_argument("--bend-radius", type=float)
    p.add_argument("--angle", type=float)
    p.add_argument("--pieces", type=int)


def elbow(args) -> dict:
    from kezuri.operators import preview
    from kezuri.operators import sheetmetal as shell

    scene = open_blend(None)
    sheet = scene.kezuri.sheet
    for option, name in (("diameter", "elbow_diameter"), ("bend_radius", "elbow_radius"),
                         ("angle", "elbow_angle"), ("pieces", "elbow_pieces")):
        if getattr(args, option) is not None:
            setattr(sheet, name, getattr(args, option))
    result = shell.run_elbow(sheet)
    files = shell.elbow_files(result, os.path.join(args.out, "elbow.dxf"), sheet)
    objects = shell.show_elbow(scene, result)
    solids = [o for o in objects if o.type == "MESH" and len(o.data.polygons)]
    wires = [o for o in objects if o not in solids]
    png = preview.render_preview(scene, solids, wires, os.path.join(args.out, "elbow.png"), see_through=False)
    return {
        "workflow": "elbow",
        "files": files,
        "preview": png,
        "diameter": result.diameter, "bend_radius": result.bend_radius, "angle": result.bend_angle,
        "simulation": shell.punch_report([punched for _, punched in shell.elbow_punching(result, sheet)],
                                         sheet.thickness),
        "pieces": [{"index": piece.index + 1, "angle_deg": round(piece.angle, 6),
                    "outline": rounded(piece.outline),
                    "shortest_mm": round(float(piece.generatrix_lengths.min()), 6),
                    "longest_mm": round(float(piece.generatrix_lengths.max()), 6)} for piece in result.pieces],
    }


# ----------------------------------------------------------------------------------------
# W6 simulate any NC file we can read

def simulate_arguments(p):
    p.add_argument("--nc", required=True, help="G-code in our posts' LinuxCNC/Fanuc dialect")
    p.add_argument("--tool", required=True, help="ball:D, flat:D or bull:D,R (mm)")
    p.add_argument("--stock", required=True, help="box:x0,y0,z0,x1,y1,z1 or cylinder:R,H (axis Z, top at z = 0)")
    p.add_argument("--rotary", choices=["c"], help="C words turn the part about Z")
    p.add_argument("--design", help="the finished part as STL/OBJ/PLY, for the gouge check")
    p.add_argument("--engine", choices=["heightfield", "manifold"], default="heightfield")
    p.add_argument("--cell", type=float, default=0.1, help="height-field cell (mm)")


def parse_stock(text: str):
    from kezuri.toolpath import simulate
    kind, _, sizes = text.partition(":")
    try:
        numbers = [float(v) for v in sizes.split(",")]
    except ValueError:
        raise simulate.SimulationError(f"--stock {text!r}: not numbers") from None
    if kind == "box" and len(numbers) == 6:
        return simulate.BoxStock(*numbers)
    if kind == "cylinder" and len(numbers) == 2:
        return simulate.CylinderStock(*numbers)
    raise simulate.SimulationError(f"--stock {text!r}: give box:x0,y0,z0,x1,y1,z1 or cylinder:R,H")


def simulate_nc(args) -> dict:
    from kezuri.operators import convert, preview
    from kezuri.operators import simulate as shell
    from kezuri.post import write_atomic
    from kezuri.toolpath import ncread, simulate

    if not os.path.isfile(args.nc):
        raise FileNotFoundError(f"no such NC file: {args.nc}")
    with open(args.nc, encoding="latin-1") as stream:
        op, lines = ncread.read_nc(stream.read(), ncread.parse_tool(args.tool), os.path.basename(args.nc))
    if not args.rotary:
        op.rotary = {}
    design = None
    if args.design:
        import trimesh
        if not os.path.isfile(args.design):
            raise FileNotFoundError(f"no such design file: {args.design}")
        design = trimesh.load(args.design, force="mesh")
    result = simulate.simulate([op], parse_stock(args.stock), engine=args.engine, cell=args.cell, design=design)
    report = shell.report_of(result)
    for entry in report["gouges"] + report["rapid_collisions"] + report["other_findings"]:
        entry["line"] = lines[entry["move"]]
    import trimesh
    vertices, faces = result.mesh()
    mesh_path = write_atomic(os.path.join(args.out, "simulated.stl"),
                             trimesh.Trimesh(vertices, faces, process=False).export(file_type="stl"))
    scene = open_blend(None)
    job = shell.SimulationJob(result, convert.WorkFrame(convert.mm_per_unit(scene), (0.0, 0.0, 0.0)), "nc")
    carved = shell.show_simulation(scene, job)
    png = preview.render_preview(scene, [carved], [], os.path.join(args.out, "simulated.png"), see_through=False,
                                 color_type="VERTEX")
    return {"workflow": "simulate", "files": [mesh_path], "preview": png, "nc": os.path.abspath(args.nc),
            "moves": len(op), "simulation": report}


COMMANDS = {
    "engrave": ("gouge-texture name plate (W1)", engrave_arguments, engrave),
    "rotary": ("pockets on a rotating table, C-X-Z (W2)", rotary_arguments, rotary),
    "stepnc": ("ISO 14649 (STEP-NC) workplan to G-code (W3)", stepnc_arguments, stepnc_job),
    "turnmill": ("4.5-axis turn-mill: reach classification, radial/axial paths, X-Z-C (W4)", turnmill_arguments,
                 turnmill_job),
    "unfold": ("twisted quad: flat pattern, turret-punch NC, DXF, SVG (W5)", unfold_arguments, unfold),
    "simulate": ("material removal and safety checks of an NC file (W6)", simulate_arguments, simulate_nc),
    "elbow": ("segmented pipe elbow: flat patterns, DXF, SVG (W5)", elbow_arguments, elbow),
}
DEMO_POSTS = {"engrave": ["--post", "linuxcnc"]}


def demo(args) -> dict:
    """Every workflow on its built-in sample, each into its own sub-folder of --out."""
    results = {}
    for name in [n for n in COMMANDS if n != "simulate"]:
        sub = parser().parse_args([name, *DEMO_POSTS.get(name, []), "--out", os.path.join(args.out, name)])
        os.makedirs(sub.out, exist_ok=True)
        report = COMMANDS[name][2](sub)
        write_report(sub.out, report)
        results[name] = {"files": report["files"], "preview": report.get("preview")}
        print(f"{name}: wrote {', '.join(report['files'])}")
    return {"workflow": "demo", "files": [f for r in results.values() for f in r["files"]], "workflows": results}


def parser() -> argparse.ArgumentParser:
    main = argparse.ArgumentParser(prog="batch.py", description="Kezuri CAM batch runs")
    commands = main.add_subparsers(dest="command", required=True)
    for name, (text, add_arguments, _) in COMMANDS.items():
        p = commands.add_parser(name, help=text)
        add_arguments(p)
        p.add_argument("--out", required=True, help="output folder")
    p = commands.add_parser("demo", help="every workflow on its built-in sample")
    p.add_argument("--out", required=True, help="output folder")
    return main


def main(argv: list) -> int:
    args = parser().parse_args(script_arguments(argv))
    args.out = os.path.abspath(args.out)
    os.makedirs(args.out, exist_ok=True)
    load_extension()
    from kezuri.operators.common import user_errors
    try:
        report = demo(args) if args.command == "demo" else COMMANDS[args.command][2](args)
    except user_errors() as error:
        print(f"kezuri: {error}", file=sys.stderr)
        return 2
    write_report(args.out, report)
    print(f"wrote {os.path.join(args.out, 'report.json')}")
    return 0


if __name__ == "__main__":
    status = main(sys.argv)
    if status:
        sys.exit(status)
