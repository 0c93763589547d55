"""The router operations' batch shorthands: ``batch.py profile|pocket|drill|chamfer|vcarve --svg FILE``
(or ``--dxf FILE``; ``batch.py vcarve --text TEXT [--font FILE]`` too), a job of one operation on a
board around the drawing (or the text, laid out by Blender).

Each is a job file written for the user (:mod:`.jobfile`): ``[setup] stock`` is the drawing's
bounding box grown by ``--margin`` and ``--thickness`` deep below Z 0, work zero at its front-left
top corner (``--work-zero CENTER``: the centre); the operation's object is the drawing's layer
(``--layer`` picks one when the file has several with closed outlines); ``--set KEY=VALUE`` sets
one of the kind's settings by its job-file name (the value read as TOML: ``--set depth=3``,
``--set side=\"inside\"`` or ``--set side=inside``); ``--material`` gives the job its material (the
feeds computed where the settings leave them out and checked, as a job file's).  ``report.json``
keeps the job file's text.
"""
from __future__ import annotations

import os
import tomllib

from .jobentry import JobFileError

# the kind's object slot that takes the drawing, and what the command does
KINDS = {
    "profile": ("shape", "cut along (or out) a drawing's outlines, with tabs (SVG, DXF)"),
    "pocket": ("region", "clear a drawing's closed outlines to a depth, islands kept (SVG, DXF)"),
    "drill": ("holes", "drill the circles of a drawing (SVG, DXF)"),
    "chamfer": ("edges", "chamfer a drawing's outlines with a V-bit (SVG, DXF)"),
    "vcarve": ("region", "V-carve a drawing's closed outlines or a text with a V-bit (SVG, DXF, --text)"),
}
TEXT_SIZE = 20.0        # mm: --text-size's default


def text_arguments(p) -> None:
    """``batch.py vcarve``'s text options: ``--text TEXT [--font FILE] [--text-size MM]``."""
    from .batchio import number

    p.add_argument("--text", help="the text to carve (instead of --svg/--dxf); Japanese needs a font that has it")
    p.add_argument("--font", metavar="FILE", help="the text's font: a font file, or one of Blender's bundled "
                   "fonts by name, e.g. \"Noto Sans CJK Regular.woff2\" (default: Blender's own font)")
    p.add_argument("--text-size", type=number("--text-size", 0.5, 2000.0, unit="mm"), default=TEXT_SIZE,
                   help=f"the text's size in mm (default {TEXT_SIZE:g})")


def arguments(p) -> None:
    from . import gate, workflowfeeds
    from .batchio import number
    from .designfile import design_arguments

    design_arguments(p)
    p.add_argument("--thickness", type=number("--thickness", 0.0, 1000.0, lo_open=True, unit="mm"), default=18.0,
                   help="the board's thickness in mm (default 18)")
    p.add_argument("--margin", type=number("--margin", 0.0, 1000.0, unit="mm"), default=10.0,
                   help="board around the drawing in mm (default 10)")
    p.add_argument("--work-zero", choices=("CORNER", "CENTER"), default="CORNER",
                   help="work zero at the board's top front-left corner (default) or its top centre")
    p.add_argument("--post", help="the post (default: the preferences')")
    p.add_argument("--machine", help="a machine preset (default: the post's own machine)")
    workflowfeeds.material_argument(p)
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="one of the operation's settings by its job-file name (repeat for several)")
    gate.allow_findings_argument(p)


def settings(pairs: list) -> dict:
    """``--set`` pairs as a settings table: the value as TOML (a number, true/false, a list, a
    quoted string), else as text."""
    found = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        key = key.strip()
        if not sep or not key or not key.replace("_", "").isalnum():
            raise JobFileError(f"--set {pair!r}: give KEY=VALUE, e.g. --set depth=3")
        try:
            found[key] = tomllib.loads(f"v = {value.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            found[key] = value.strip()
    return found


def job_text(kind: str, args) -> str:
    """The job file the shorthand runs (see the module docstring)."""
    import numpy as np

    from .designfile import design_loops

    if getattr(args, "text", None) is not None:
        return text_job(kind, args)
    if getattr(args, "font", None) is not None:
        raise JobFileError("--font is for --text")
    found = design_loops(args)
    if len(found) > 1:
        names = ", ".join(repr(name) for name, _ in found)
        raise JobFileError(f"--{'svg' if args.svg else 'dxf'}: the drawing has closed outlines on several layers "
                           f"({names}): pick one with --layer")
    name, loops = found[0]
    points = np.vstack(loops)
    (x0, y0), (x1, y1) = points.min(axis=0) - args.margin, points.max(axis=0) + args.margin
    path = os.path.abspath(args.svg or args.dxf)
    design = {"file": path}
    if args.layer:
        design["layer"] = args.layer[0]
    if getattr(args, "scale", None) is not None:
        design["scale"] = float(args.scale)
    operation = {"kind": kind, "name": kind, "design": design, "objects": {KINDS[kind][0]: name},
                 "settings": settings(args.set)}
    return board_job(kind, (x0, y0, x1, y1), args, operation)


def board_job(kind: str, board, args, operation: dict) -> str:
    """The job file of a shorthand: the board ``(x0, y0, x1, y1)`` (mm) as the stock, ``args.thickness``
    thick, the post, machine and material when given, and the one operation."""
    from .workflowfeeds import material_option

    x0, y0, x1, y1 = board
    setup = {"name": kind, "stock": [float(x0), float(y0), -float(args.thickness), float(x1), float(y1), 0.0],
             "work_zero": args.work_zero}
    if args.post:
        setup["post"] = args.post
    if args.machine:
        setup["machine"] = args.machine
    if getattr(args, "material", None) is not None:       # the job's feeds: computed where left out, checked
        setup["material"] = material_option(args.material) or "none"
    return f"[setup]\n{toml_table(setup)}\n[[operations]]\n{toml_table(operation)}"


def text_job(kind: str, args) -> str:
    """The job file of ``batch.py vcarve --text``: the text laid out (as the job will lay it out) to
    size the board round it, the text's centre at the board's middle."""
    import numpy as np

    from . import vcarve

    if args.svg or args.dxf:
        raise JobFileError("give --text or --svg/--dxf, not both")
    text = {"body": args.text, "size": float(args.text_size)}
    if args.font:
        text["font"] = os.path.abspath(args.font) if os.path.isfile(args.font) else args.font
    spec = vcarve.text_spec(text, "--text")
    points = np.vstack(vcarve.text_loops(spec, os.getcwd(), "--text"))
    (x0, y0), (x1, y1) = points.min(axis=0) - args.margin, points.max(axis=0) + args.margin
    # the board in the scene's mm round the text laid out at the origin; the text's origin in work mm
    if args.work_zero == "CENTER":
        text["at"] = [-float(x0 + x1) / 2, -float(y0 + y1) / 2]
    else:
        text["at"] = [-float(x0), -float(y0)]
    operation = {"kind": kind, "name": kind, "text": text, "settings": settings(args.set)}
    return board_job(kind, (x0, y0, x1, y1), args, operation)


def toml_table(table: dict) -> str:
    """A flat TOML table: values as JSON (valid TOML for strings, numbers, booleans and lists), nested
    tables inline."""
    import json

    def value(item):
        if isinstance(item, dict):
            return "{ " + ", ".join(f"{key} = {value(v)}" for key, v in item.items()) + " }"
        if isinstance(item, bool):
            return "true" if item else "false"
        if isinstance(item, list):
            return "[" + ", ".join(value(v) for v in item) + "]"
        return json.dumps(item, ensure_ascii=False)
    return "".join(f"{key} = {value(item)}\n" for key, item in table.items())


def command(kind: str):
    from .workflow import BatchCommand

    def run(args) -> dict:
        from . import jobfile
        text = job_text(kind, args)
        report = jobfile.write_job(f"batch.py {kind}", args.out, args.post, args.allow_findings, text=text,
                                   base_dir=os.getcwd())
        return {**report, "workflow": kind, "job_file_text": text}
    def options(p) -> None:
        arguments(p)
        if kind == "vcarve":
            text_arguments(p)
    return BatchCommand(kind, KINDS[kind][1], options, run, demo=None)


COMMANDS = tuple(command(kind) for kind in KINDS)
