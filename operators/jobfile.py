"""Job files: ``batch.py job FILE.toml`` plans a whole job (setup + operations) and writes one
program, its report, pictures and the gate's check over the whole job.

A job file (TOML)::

    [setup]
    name = "nameplate"          # the program's name (default: the file's name)
    sample = "name_plate"       # a built-in scene (samples.SCENES), or
    blend = "plate.blend"       # a .blend beside the job file (its scene's objects by name)
    text = "Kezuri"             # the name_plate sample's word
    post = "linuxcnc"           # default: the scene's
    machine = "linuxcnc-manual" # a machine preset (default: the post's own machine)
    arcs = false                # milling posts write every move as planned (default true: G2/G3 fitted)
    material = "hardwood"       # the stock's material: each operation's feeds checked against it
                                # (report.json's ``feeds``; default: the scene's, none = not checked);
                                # a profile's, pocket's, drilling's, chamfer's or V-carve's spindle
                                # speed, feeds and steps left out of its settings are computed
                                # (operators/jobfeeds.py)
    language = "ja"             # the setup sheet's language: en (default) or ja; batch --language wins

    [[operations]]              # in the order they are cut
    kind = "engrave"            # an operation kind (toolpath/operations/<kind>)
    name = "name plate"         # unique in the job
    enabled = true
    objects = { plate = "Plate", letters = "Letters" }   # the kind's object slots
    design = "logo.svg"         # an SVG / DXF beside the job file: its curves made first, one
                                # object per layer ("logo", "logo Cut"), for objects to name
    settings = { seed = 7 }     # the kind's panel settings by property name, checked like the panel's
    tool = 3                    # or tools = { rough = 2, finish = "T3" }: tools from the tool library
                                # (operators/jobtools.py), in place of the kind's tool settings

The CAM tab's job list plans its rows through :func:`job_of` too, and saves them as such a file
(naming the saved .blend), so a file saved from the panel writes the same program in batch.

Every value is checked before any work: an unknown key, kind, object or setting, or a value the
setting's range refuses, is an error naming the file, the operation and the key as typed.
"""
from __future__ import annotations

import os
import time
import tomllib

from ..toolpath.feeds import programcheck
from ..toolpath.engines.textfile import named, os_reason
from ..toolpath.job import Job, Setup, plan_job
from ..toolpath.pictures.setupsheet import LANGUAGES
from .jobentry import JobEntry, JobFileError

SETUP_KEYS = {"name", "sample", "blend", "text", "post", "machine", "work_offset", "allow_findings", "arcs", "stock",
              "work_zero", "material", "language"}
OPERATION_KEYS = {"kind", "name", "enabled", "objects", "settings", "holes", "tabs", "file", "design", "outline", "text", "tool", "tools"}


def read(path: str, text: str | None = None) -> dict:
    """The job file as a dict (``text``: its contents already read, e.g. a template's row); a file
    TOML cannot read is an error naming the file and the line."""
    try:
        if text is not None:
            data = tomllib.loads(text)
        else:
            with open(path, "rb") as stream:
                data = tomllib.loads(stream.read().decode("utf-8-sig"))     # a BOM (Notepad's UTF-8) dropped
    except FileNotFoundError:
        raise JobFileError(f"job file {path}: no such file") from None
    except IsADirectoryError:
        raise JobFileError(f"job file {path}: a folder, not a job file") from None
    except OSError as error:
        raise JobFileError(named(f"job file {path}", os_reason(error))) from None
    except UnicodeDecodeError:
        raise JobFileError(f"job file {path}: not UTF-8 text") from None
    except tomllib.TOMLDecodeError as error:
        raise JobFileError(f"job file {path}: not TOML ({error})") from None
    unknown = sorted(set(data) - {"setup", "operations"})
    if unknown:
        raise JobFileError(f"job file {path}: unknown table {unknown[0]!r}; a job file has [setup] and "
                           "[[operations]]")
    setup = data.get("setup", {})
    if not isinstance(setup, dict):
        raise JobFileError(f"job file {path}: setup must be a table")
    unknown = sorted(set(setup) - SETUP_KEYS)
    if unknown:
        raise JobFileError(f"job file {path}: [setup] has an unknown key {unknown[0]!r}; the keys are "
                           f"{', '.join(sorted(SETUP_KEYS))}")
    if "language" in setup and setup["language"] not in LANGUAGES:
        raise JobFileError(f"job file {path}: [setup] language = {setup['language']!r} is not one of "
                           f"{', '.join(LANGUAGES)}")
    operations = data.get("operations")
    if not isinstance(operations, list) or not operations:
        raise JobFileError(f"job file {path}: no [[operations]]; a job needs at least one")
    for index, table in enumerate(operations, 1):
        if not isinstance(table, dict):
            raise JobFileError(f"job file {path}: operation {index} must be a table")
        unknown = sorted(set(table) - OPERATION_KEYS)
        if unknown:
            raise JobFileError(f"job file {path}: operation {index} has an unknown key {unknown[0]!r}; the keys "
                               f"are {', '.join(sorted(OPERATION_KEYS))}")
        for key in ("kind", "name"):
            if not isinstance(table.get(key), str) or not table[key].strip():
                raise JobFileError(f"job file {path}: operation {index} needs a {key} (text)")
        for key in ("objects", "settings"):
            if not isinstance(table.get(key, {}), dict):
                raise JobFileError(f"job file {path}: operation {index} ({table['name']!r}): {key} must be a table")
        if not isinstance(table.get("enabled", True), bool):
            raise JobFileError(f"job file {path}: operation {index} ({table['name']!r}): enabled must be "
                               "true or false")
    return data


def scene_for(setup: dict, path: str, base_dir: str | None = None):
    """The scene the job's objects come from: the .blend named in [setup] (beside the job file),
    else a built-in sample scene."""
    from . import batchio, samples

    if sum(key in setup for key in ("blend", "sample", "stock")) > 1:
        raise JobFileError(f"job file {path}: [setup] gives more than one of blend, sample and stock; give one")
    if "stock" in setup:
        return stock_scene(setup, path)
    if "blend" in setup:
        blend = os.path.join(base_dir or os.path.dirname(os.path.abspath(path)), str(setup["blend"]))
        return batchio.open_blend(blend, f"job file {path}: [setup] blend = {setup['blend']!r}")
    scene = batchio.open_blend(None)
    sample = setup.get("sample", "name_plate")
    if sample not in samples.SCENES:
        raise JobFileError(f"job file {path}: [setup] sample {sample!r} is not one of "
                           f"{', '.join(sorted(samples.SCENES))}")
    options = {"word": str(setup["text"])} if "text" in setup else {}
    if options and sample != "name_plate":
        raise JobFileError(f"job file {path}: [setup] text is for the name_plate sample")
    samples.SCENES[sample](scene, **options)
    return scene


def stock_scene(setup: dict, path: str):
    """An empty scene with the [setup] ``stock = [x0, y0, z0, x1, y1, z1]`` (mm) as its plate, work
    zero at its top ``work_zero`` ("CORNER": the front-left corner, the default; "CENTER")."""
    import math

    from . import batchio, convert, samples

    box = setup["stock"]
    if not (isinstance(box, list) and len(box) == 6 and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                             and math.isfinite(v) for v in box)):
        raise JobFileError(f"job file {path}: [setup] stock = {box!r} is not [x0, y0, z0, x1, y1, z1] in mm")
    x0, y0, z0, x1, y1, z1 = (float(v) for v in box)
    if not (x0 < x1 and y0 < y1 and z0 < z1):
        raise JobFileError(f"job file {path}: [setup] stock = {box!r}: each lower corner value must lie below the "
                           "upper one")
    zero = setup.get("work_zero", "CORNER")
    if zero not in ("CORNER", "CENTER"):
        raise JobFileError(f"job file {path}: [setup] work_zero = {zero!r} is not CORNER or CENTER")
    import bpy

    scene = batchio.open_blend(None)
    s = 1.0 / convert.mm_per_unit(scene)
    plate = bpy.data.objects.new("Stock", samples.box_mesh("Stock", x0 * s, y0 * s, z0 * s, x1 * s, y1 * s, z1 * s))
    scene.collection.objects.link(plate)
    scene.kezuri.stock.plate = plate
    scene.kezuri.stock.origin = zero
    return scene


def entries(data: dict, scene, path: str, base_dir: str | None = None) -> list:
    import bpy

    from . import jobtools, toolstore

    found, designs, library = [], set(), []

    def library_of():                   # the tool library, read once and only when a tool is named
        if not library:
            library.append(toolstore.load())
        return library[0]

    for index, table in enumerate(data["operations"], 1):
        where = f"job file {os.path.basename(path)}: operation {index} ({table['name']!r})"
        if "design" in table and repr(table["design"]) not in designs:     # a drawing's curves, made once
            from .designfile import job_design
            job_design(scene, table["design"], where, base_dir or os.path.dirname(os.path.abspath(path)))
            designs.add(repr(table["design"]))
        objects = {}
        for slot, name in table.get("objects", {}).items():
            obj = bpy.data.objects.get(name) if isinstance(name, str) else None
            if obj is None or scene not in obj.users_scene:
                raise JobFileError(f"{where}: objects.{slot} = {name!r} is not an object of the scene")
            objects[slot] = obj
        settings = dict(table.get("settings", {}))
        settings.update(jobtools.tool_settings(table, table["kind"], settings, where, library_of))
        found.append(JobEntry(table["name"], table["kind"], table.get("enabled", True), objects,
                              settings, table, where,
                              base_dir or os.path.dirname(os.path.abspath(path))))
    return found


def job_post(families, planned):
    """The job's post, made with what it takes of the setup (work offset, machine: a turn-mill post
    has neither) and with every option the parts ask for (a rotary table's top speed)."""
    import inspect

    from .. import post as posts

    setup = planned.job.setup
    post_class = posts.find(families, setup.post)
    accepted = inspect.signature(post_class.__init__).parameters
    options = {"work_offset": setup.work_offset}
    if setup.machine is not None:
        options["machine"] = setup.machine
    options = {key: value for key, value in options.items() if key in accepted}
    for part in planned.parts:
        options.update(dict(part.post_options))
    return posts.create(families, setup.post, **options)


def same_frame(a, b) -> bool:
    return abs(a.mm_per_unit - b.mm_per_unit) <= 1e-9 * max(1.0, a.mm_per_unit) and all(
        abs(float(x) - float(y)) <= 1e-6 for x, y in zip(a.origin_mm, b.origin_mm))


def describe_frame(frame) -> str:
    return "X {:g} Y {:g} Z {:g} in the scene".format(*(float(v) for v in frame.origin_mm))


def apply_setup(scene, setup_table: dict, path: str) -> None:
    """The [setup] table's machine preset and work offset into the scene's Machine & Stock."""
    if "machine" in setup_table:
        from . import machines
        known = [item.identifier for item in scene.kezuri.machine.bl_rna.properties["preset"].enum_items]
        if setup_table["machine"] not in known:         # Blender's enum raised a TypeError (a traceback)
            raise JobFileError(f"job file {path}: [setup] machine = {setup_table['machine']!r} is not a machine "
                               f"preset; they are {', '.join(known)}")
        scene.kezuri.machine.preset = str(setup_table["machine"])
        machines.fill_machine(scene.kezuri.machine, str(setup_table["machine"]))
    if "arcs" in setup_table:
        if not isinstance(setup_table["arcs"], bool):
            raise JobFileError(f"job file {path}: [setup] arcs must be true or false, got {setup_table['arcs']!r}")
        scene.kezuri.machine.arcs = setup_table["arcs"]
    if "work_offset" in setup_table:
        from .batchio import set_exactly
        set_exactly(scene.kezuri.machine, "work_offset", setup_table["work_offset"], f"job file {path}: work_offset")
    if "material" in setup_table:
        from ..toolpath.feeds import materials
        value = setup_table["material"]
        try:
            scene.kezuri.stock.material = "NONE" if value in ("", "none") else materials.material(value).key
        except materials.MaterialError as error:
            raise JobFileError(f"job file {path}: [setup] material: {error}") from None


def plate_setup(scene, depsgraph, families, post_name: str):
    """The setup of a job whose operations do not give one (drilling, chamfers): the scene's plate
    (Machine & Stock) as the stock, its work zero, the machine for the post: (Setup, WorkFrame)."""
    from ..toolpath.simulate import BoxStock
    from . import convert
    from .limits import check_group
    from .machines import scene_machine

    settings = scene.kezuri
    check_group(settings.machine, "machine")
    plate = convert.plate_from_object(settings.stock.plate, depsgraph, scene, settings.stock.origin)
    convert.check_fits(plate, scene)
    points = [p for loop in plate.outline for p in loop]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    stock = BoxStock(float(min(xs)), float(min(ys)), -float(plate.size[2]), float(max(xs)), float(max(ys)), 0.0)
    machine = scene_machine(settings.machine, families, post_name)
    return Setup(name=scene.name, post=post_name, machine=machine, work_offset=settings.machine.work_offset,
                 rapid_rate=settings.machine.rapid_rate, stock=stock), plate.frame


def job_of(scene, entries: list, name: str, post_name: str, where: str):
    """The job of the entries (read from a job file or the panel's job list), their objects and
    settings read from the scene: (the Job, the work frame, the post families).  One function for
    the file and the panel, so both plan and write the same program."""
    import bpy

    from . import jobfeeds, toolstore
    from .workflows import WORKFLOWS

    adapters = {w.kind: w for w in WORKFLOWS if w.kind and w.job_operation is not None}
    depsgraph = bpy.context.evaluated_depsgraph_get()
    operations, setup, frame, families, feeds = [], None, None, [], []
    material = scene.kezuri.stock.material
    library = toolstore.library_or_none() if material != "NONE" else None
    for entry in entries:
        if entry.kind not in adapters:
            raise JobFileError(f"{entry.where}: kind {entry.kind!r} is not one of {', '.join(sorted(adapters))}")
        workflow = adapters[entry.kind]
        entry, computed = jobfeeds.with_feeds(scene, entry, workflow.post_families, post_name, library)
        feeds += computed           # the settings left out, from the calculator (with a material)
        operation, op_setup, op_frame = workflow.job_operation(scene, depsgraph, entry, post_name)
        operations.append(operation)
        families += [f for f in workflow.post_families if f not in families]
        if setup is None and op_setup is not None:
            setup, frame = op_setup, op_frame
        elif op_frame is not None and frame is not None and not same_frame(op_frame, frame):
            raise JobFileError(f"{entry.where}: its work zero ({describe_frame(op_frame)}) is not the job's "
                               f"({describe_frame(frame)}): the operations of one job share one work zero")
    if setup is None and scene.kezuri.stock.plate is not None and operations:
        setup, frame = plate_setup(scene, depsgraph, families, post_name)
    if setup is None:
        raise JobFileError(f"{where}: no operation gives the stock: begin with one that works on a "
                           "plate or a part (engrave, carve)")
    setup = Setup(name=name, post=post_name, machine=setup.machine, work_offset=setup.work_offset,
                  rapid_rate=setup.rapid_rate, stock=setup.stock, material="" if material == "NONE" else material,
                  feeds=tuple(feeds))
    return Job(setup, tuple(operations)), frame, tuple(families)


def plan_file(path: str, post_name: str | None = None, progress=None, text: str | None = None,
              base_dir: str | None = None):
    """Read the job file (``text``: its contents, already read) and plan it: (the planned job, the
    work frame, the post families, the scene).  ``base_dir``: where the file's relative paths start
    (default: the file's folder)."""
    from .preferences import scene_post

    data = read(path, text)
    setup_table = data.get("setup", {})
    scene = scene_for(setup_table, path, base_dir)
    post_name = post_name or setup_table.get("post") or scene_post(scene)
    apply_setup(scene, setup_table, path)
    name = str(setup_table.get("name") or os.path.splitext(os.path.basename(path))[0])
    job, frame, families = job_of(scene, entries(data, scene, path, base_dir), name, post_name, f"job file {path}")
    return plan_job(job, progress=progress), frame, families, scene


def feeds_check(planned, program, library=False) -> list:
    """The check before export (report.json's ``feeds``): each operation of the program against the
    job's material and machine; [] when the job has no material.  ``library``: the tool library
    already read (see toolstore.tool_makes), else read here."""
    setup = planned.job.setup
    if not setup.material:
        return []
    from .jobfeeds import annotate
    from .toolstore import tool_makes

    entries = programcheck.check_program(program, setup.material, setup.machine,
                                         known=tool_makes(program.tools(), library))
    return annotate(entries, planned, program, setup.feeds)


def write_job(path: str, out: str, post_name: str | None = None, allow_findings: bool = False,
              text: str | None = None, base_dir: str | None = None) -> dict:
    """Plan the job file, check it, write its program, pictures and report data into ``out``."""
    from .. import post as posts
    from . import gate, preview, simview
    from .common import Progress
    from .exporting import warn, write_program
    from .workflow import SimulationSetup

    started = time.perf_counter()
    planned, frame, families, scene = plan_file(path, post_name, Progress(None, "job"), text, base_dir)
    seconds = time.perf_counter() - started
    setup = planned.job.setup
    post_class = posts.find(families, setup.post)
    program = planned.program(macro=post_class.needs_texture)
    cut, stock, limits = planned.simulation()
    simulation = SimulationSetup(cut, stock, limits, frame, setup.name)
    checked, gate_report = gate.check(simulation, allow_findings, Progress(None, "check"), machine=setup.machine)
    post = job_post(families, planned)
    nc_path = os.path.join(out, f"{setup.name}{post_class.extension}")
    findings = []
    write_program(nc_path, post.to_text(program), post, findings)
    feeds = feeds_check(planned, program)
    findings += programcheck.warnings(feeds)
    toolpaths_png = preview.toolpath_png(os.path.join(out, "job-toolpaths.png"), cut.operations, stock, [],
                                         f"JOB {setup.name.upper()}: TOOLPATHS")
    simulation_report, png = simview.batch_simulation(scene, simulation, out, "job", checked)
    report = {
        "workflow": "job",
        "job_file": os.path.abspath(path),
        "gate": gate_report,
        "simulation": simulation_report,
        "post": setup.post,
        "machine": None if setup.machine is None else setup.machine.summary(),
        "files": [nc_path],
        "preview": png,
        "toolpaths_preview": toolpaths_png,
        "toolpath_seconds": round(seconds, 3),
        "job_operations": [{"name": item.operation.name, "kind": item.operation.kind,
                            "operations": [op.name for op in item.part.operations],
                            "warnings": list(item.part.warnings), "plan_seconds": round(item.part.seconds, 3),
                            # characters too fine for a tool (engraving's band, a V-carve's clearing)
                            "too_fine": list(getattr(item.part.result, "too_fine", None) or [])}
                           for item in planned.planned],
        "operations": program.summary(),
        "tools": [tool.describe() for tool in program.tools()],
        "cycle_time_s": round(cut.cycle_time(), 1),
        "warnings": planned.warnings,
        "material": setup.material or None,
        "feeds": feeds,
    }
    language = read(path, text).get("setup", {}).get("language")
    if language is not None:            # the setup sheet's, when the job file gives one (batch.py finished)
        report["setup_sheet_language"] = language
    warn(findings, report)
    return report
