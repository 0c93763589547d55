"""Kezuri CAM batch entry point.

    python batch.py <command> [options]                      (the bpy wheel from PyPI)
    blender -b [file.blend] --python batch.py -- <command> [options]

Commands:
    engrave [--blend FILE] [--post fanuc|fanuc-macro|linuxcnc|grbl] [--seed N] --out DIR
    demo --out DIR        every workflow on its built-in sample part

Each command writes its NC file(s), ``report.json`` and a preview PNG into DIR.
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


def load_extension():
    """Import this folder as the package ``kezuri`` (as Blender does) and register it."""
    if "kezuri" not in sys.modules:
        spec = importlib.util.spec_from_file_location("kezuri", os.path.join(ROOT, "__init__.py"),
                                                      submodule_search_locations=[ROOT])
        package = importlib.util.module_from_spec(spec)
        sys.modules["kezuri"] = package
        spec.loader.exec_module(package)
    package = sys.modules["kezuri"]
    import bpy
    if not hasattr(bpy.types.Scene, "kezuri"):
        package.register()
    return package


def script_arguments(argv: list) -> list:
    """Arguments after ``--`` when run by Blender, else everything after the script name."""
    return argv[argv.index("--") + 1:] if "--" in argv else argv[1:]


def open_blend(path: str | None):
    import bpy
    if path:
        if not os.path.isfile(path):
            raise FileNotFoundError(f"no such .blend file: {path}")
        bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path))
    return bpy.context.scene


def write_report(out_dir: str, report: dict) -> str:
    from kezuri.post import write_atomic
    return write_atomic(os.path.join(out_dir, "report.json"), json.dumps(report, indent=2, sort_keys=True) + "\n")


def engrave(args) -> dict:
    import bpy
    from kezuri.operators import engrave as shell
    from kezuri.operators import preview, samples
    from kezuri.operators.common import Progress

    scene = open_blend(args.blend)
    if not args.blend:
        samples.clear_scene(scene)
        samples.set_millimetres(scene)
        samples.name_plate(scene)
    props = scene.kezuri
    if args.seed is not None:
        props.engrave.seed = args.seed
    post_name = args.post or props.machine.post
    started = time.perf_counter()
    job = shell.run_engrave(scene, bpy.context.evaluated_depsgraph_get(), Progress(None, "engrave"))
    seconds = time.perf_counter() - started
    nc_path = os.path.join(args.out, f"engrave{shell.extension_for(post_name)}")
    shell.export_engrave(job, post_name, nc_path, props.machine.work_offset)
    wires = shell.show_engrave(scene, job, show_rapids=False)
    png = preview.render_preview(scene, [props.stock.plate, *shell.letter_objects(props.engrave)], wires,
                                 os.path.join(args.out, "engrave.png"))
    written_program = shell.program_for_post(job, post_name)
    return {
        "workflow": "engrave",
        "post": post_name,
        "seed": props.engrave.seed,
        "files": [nc_path],
        "preview": png,
        "toolpath_seconds": round(seconds, 3),
        "operations": written_program.summary(),
        "cycle_time_s": round(job.baked.cycle_time(), 1),
        "gouge_depths": [round(d, 4) for d in job.depths],
        "warnings": job.result.warnings,
        "skipped": job.result.skipped,
    }


COMMANDS = {"engrave": engrave}


def demo(args) -> dict:
    """Every workflow on its built-in sample, each into its own sub-folder of --out."""
    results = {}
    for name in COMMANDS:
        sub = argparse.Namespace(**{**DEFAULTS[name], "out": os.path.join(args.out, name)})
        os.makedirs(sub.out, exist_ok=True)
        report = COMMANDS[name](sub)
        write_report(sub.out, report)
        results[name] = {"files": report["files"], "preview": report.get("preview")}
        print(f"{name}: wrote {', '.join(report['files'])}")
    return {"workflow": "demo", "files": [f for r in results.values() for f in r["files"]], "workflows": results}


DEFAULTS = {"engrave": {"blend": None, "post": "linuxcnc", "seed": None}}


def parser() -> argparse.ArgumentParser:
    main = argparse.ArgumentParser(prog="batch.py", description="Kezuri CAM batch runs")
    commands = main.add_subparsers(dest="command", required=True)
    p = commands.add_parser("engrave", help="gouge-texture name plate (W1)")
    p.add_argument("--blend", help="a .blend whose scene has the Kezuri plate and letters set")
    p.add_argument("--post", choices=["fanuc", "fanuc-macro", "linuxcnc", "grbl"])
    p.add_argument("--seed", type=int)
    p.add_argument("--out", required=True)
    p = commands.add_parser("demo", help="every workflow on its built-in sample")
    p.add_argument("--out", required=True)
    return main


def main(argv: list) -> int:
    args = parser().parse_args(script_arguments(argv))
    args.out = os.path.abspath(args.out)
    os.makedirs(args.out, exist_ok=True)
    load_extension()
    from kezuri.operators.common import user_errors
    try:
        report = demo(args) if args.command == "demo" else COMMANDS[args.command](args)
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
