"""What every workflow's batch command shares: the scene to work on, and rounding for reports."""
from __future__ import annotations

import os

from ..toolpath.engines.textfile import file_problem, named
from .convert import SceneInputError


def open_blend(path: str | None, shown: str | None = None):
    """The scene to work on: the given .blend's, or a fresh empty one in millimetres.  An error
    names the file as ``shown`` (default ``--blend path``; a job file: its ``blend =``)."""
    import bpy

    from . import samples
    if path:
        shown = shown or f"--blend {path}"
        problem = file_problem(path, "a .blend file")
        if problem == "no such file":
            raise SceneInputError(f"{shown}: no such .blend file")
        if problem:
            raise SceneInputError(named(shown, problem))
        try:
            bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path))
        except RuntimeError as error:
            reason = str(error).strip().removeprefix("Error:").strip()
            raise SceneInputError(f"{shown}: not a .blend file Blender can open ({reason})") from None
        return bpy.context.scene
    scene = bpy.context.scene
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    return scene


def shown() -> bool:
    """Whether batch's results are put in the scene as objects: only when Blender has a window to
    show them (``blender file.blend --python batch.py -- ...``).  In background mode the scene is
    thrown away at exit and the pictures are drawn from the arrays, so those objects would be
    time spent for nobody."""
    import bpy
    return not bpy.app.background


def rounded(array, digits: int = 6):
    import numpy as np
    return np.round(np.asarray(array, float), digits).tolist()


# ----- batch arguments, checked against their meaning -------------------------------------------

def number(option: str, lo=None, hi=None, *, integer: bool = False, lo_open: bool = False, unit: str = "",
           limit=None):
    """An argparse ``type`` that takes a finite number within [lo, hi] (``lo_open``: lo excluded),
    or the range ``limit`` of ``limits.RANGES`` (so batch and the panel share one table),
    and refuses anything else naming the option, the value given and the range: never a value the
    scene would silently clamp to another job."""
    import argparse
    import math

    if limit is not None:
        lo, hi, lo_open, integer, unit = limit.lo, limit.hi, limit.lo_open, limit.integer, limit.unit
    kind = "an integer" if integer else "a number"
    low = "" if lo is None else (f"{lo:g} <" if lo_open else f"{lo:g} <=")
    high = "" if hi is None else f"<= {hi:g}"
    allowed = " ".join(part for part in (low, option.lstrip("-"), high) if part) + (f" {unit}" if unit else "")

    def parse(text: str):
        try:
            value = int(text) if integer else float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not {kind} (allowed: {allowed})") from None
        if not math.isfinite(value) or (lo is not None and (value <= lo if lo_open else value < lo)) or \
                (hi is not None and value > hi):
            raise argparse.ArgumentTypeError(f"{text} is outside the allowed range {allowed}")
        return value
    parse.__name__ = option
    return parse


def set_exactly(group, name: str, value, option: str) -> None:
    """Set a scene setting from a batch argument and make sure it took the value as given (Blender
    clamps to a property's limits without a word)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise SceneInputError(f"{option}: {value!r} is not a value")
    setattr(group, name, value)
    held = getattr(group, name)
    if isinstance(value, float) or isinstance(held, float):
        same = abs(float(held) - float(value)) <= 1e-6 * max(1.0, abs(float(value)))
    else:
        same = held == value
    if not same:
        raise SceneInputError(f"{option} {value}: the setting would hold {held} instead; give a value the "
                              f"setting allows")


def write_stl(path: str, vertices, faces) -> str:
    """A binary STL of (vertices mm, faces) written through temp + rename (the mesh a job was
    machined against, ``design.stl``, for other tools to check the cut)."""
    import trimesh

    from ..post.output import write_atomic

    data = trimesh.exchange.stl.export_stl(trimesh.Trimesh(vertices, faces, process=False))
    return write_atomic(path, data)


# ----- the setup sheet -------------------------------------------------------------------------------

SHEET_NAME = "setup-sheet.html"
SHEET_PICTURES = (("toolpaths_preview", "Toolpaths"), ("preview", "Result"))


def program_extensions() -> set:
    """The file extensions a post writes programs with (the post registry's)."""
    from ..post import registry
    return {cls.extension.lower() for cls in registry.posts()}


def post_label(report: dict) -> str:
    """The label of the report's post (the registry's, within the machine's family where known);
    of each, where the run wrote several ("xzc, cldata": the turn-mill's)."""
    from ..post import registry
    choice = report.get("post")
    if not isinstance(choice, str):
        return ""
    machine = report.get("machine")
    family = machine.get("family") if isinstance(machine, dict) else None

    def label(name: str) -> str:
        for families in ((family,) if family else (), None):
            try:
                return registry.find(families, name).label
            except registry.UnknownPostError:
                continue
        return name
    return ", ".join(label(name.strip()) for name in choice.split(","))


def machine_label(machine):
    """The report's machine: its summary (a dict), or a preset's name turned into its label."""
    from ..toolpath.ir import machine as machines
    if isinstance(machine, str):
        try:
            return machines.preset(machine).label
        except machines.MachineError:
            return machine
    return machine


def write_program_sheet(nc_path: str, program, report: dict, machine, post: str, language: str = "en", *,
                        job_name: str | None = None, stick_out: dict | None = None, pictures=()) -> str:
    """A panel's export: the setup sheet of ``program`` (an IR Program, written to ``nc_path``)
    beside it as ``<program>-setup-sheet.html``, from the gate's ``report`` entries (``gate``,
    ``feeds``, ``warnings``), in ``language``, titled ``job_name`` (None: the program's name),
    with the tools' ``stick_out`` ({tool number: mm}) and ``pictures`` ([(caption, PNG bytes)]); its path."""
    from ..post.output import write_atomic
    from ..toolpath.pictures import setupsheet

    with open(nc_path, "rb") as stream:
        programs = [setupsheet.program_file(os.path.basename(nc_path), stream.read())]
    sheet = setupsheet.sheet_from(program, report, machine, post, list(pictures), programs=programs, job_name=job_name,
                                  stick_out=stick_out)
    translate = None
    if language == "ja":
        from .translations import sheet_text as translate
    path = os.path.splitext(nc_path)[0] + "-" + SHEET_NAME
    return write_atomic(path, setupsheet.setup_sheet(sheet, language, translate).encode("utf-8"))


def sheet_language(args, report: dict) -> str:
    """The setup sheet's language: ``--language``, else the job file's [setup] language, else English."""
    return getattr(args, "language", None) or report.get("setup_sheet_language") or "en"


def write_setup_sheet(out_dir: str, report: dict, language: str = "en") -> dict:
    """Write ``setup-sheet.html`` into ``out_dir`` (the staging folder) from a batch run's
    ``report`` and the files it lists (programs, pictures), in ``language`` (en, ja); returns the
    report with its ``setup_sheet`` entry.  Every batch command's report goes through here once (batch.py)."""
    from ..post.output import write_atomic

    path = write_atomic(os.path.join(out_dir, SHEET_NAME), report_sheet(report, language).encode("utf-8"))
    return {**report, "setup_sheet": path}


def report_sheet(report: dict, language: str = "en", programs=None, pictures=None) -> str:
    """The setup sheet's HTML of a batch run's ``report``, in ``language``: its programs the files
    the report lists (``programs``: :func:`setupsheet.program_file` entries given instead, as a
    panel's export has them before it writes them), its pictures the PNGs the report names
    (``pictures``: [(caption, PNG bytes)] given instead, drawn in memory)."""
    from ..toolpath.pictures import setupsheet

    def read(path) -> bytes | None:
        if not isinstance(path, str) or not os.path.isfile(path):
            return None
        with open(path, "rb") as stream:
            return stream.read()

    if programs is None:
        extensions = program_extensions()
        listed = [path for path in report.get("files") or ()
                  if os.path.splitext(str(path))[1].lower() in extensions]
        if isinstance(report.get("nc"), str):          # the simulate command: the program it read
            listed.append(report["nc"])
        programs = [setupsheet.program_file(os.path.basename(path), data) for path in listed
                    if (data := read(path)) is not None]
    if pictures is None:
        pictures = [(caption, data) for key, caption in SHEET_PICTURES
                    if (data := read(report.get(key))) is not None and data.startswith(setupsheet.PNG_SIGNATURE)]
    workflow, program = report.get("workflow"), (report.get("gate") or {}).get("program")
    if program is None and isinstance(report.get("nc"), str):
        program = os.path.basename(report["nc"])
    name = f"{workflow}: {program}" if workflow and program else None
    from .toolstore import stick_outs
    sheet = setupsheet.sheet_from(None, report, machine_label(report.get("machine")), post_label(report) or None,
                                  pictures, programs=programs, job_name=name,
                                  stick_out=stick_outs(report["operations"]) if report.get("operations") else {})
    translate = None
    if language == "ja":
        from .translations import sheet_text as translate
    return setupsheet.setup_sheet(sheet, language, translate)
