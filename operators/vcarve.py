"""V-carving in the shell: an operation of job files and of the CAM tab's job list (its settings
as panel properties, :func:`settings_group`, in the sub-panels :data:`PANELS` under the Job panel).

The region is the object in the ``region`` slot (closed curves, a Text in any font, mesh faces;
seen from above, read even-odd so counters are islands) in the plate's work frame, or a text laid
out here: ``text = "Kezuri"`` or ``text = { body = "削り Kezuri", font = "FILE", size = 20,
at = [x, y] }`` (``font``: a font file beside the job file, or one of Blender's bundled fonts by
file name, e.g. "Noto Sans CJK Regular.woff2" for Japanese; default Blender's own font;
``size`` in mm; ``at``: the text's centre in work mm, default the plate's centre).  Settings by
name (:data:`SETTINGS`); the V-bit's angle is ``angle`` (degrees)."""
from __future__ import annotations

import math
import os

import numpy as np

from ..toolpath.engines import region as rg
from ..toolpath.engines.textfile import file_problem, named
from ..toolpath.ir.program import ProgramError
from ..toolpath.job import JobOperation, Setup
from ..toolpath.operations.pocket import pocket as pocket_core
from ..toolpath.operations.vcarve import vcarve as core
from ..toolpath.operations.vcarve.kind import VCarveGeometry, VCarveKind
from . import convert, textcells
from .workflow import Workflow

POST_FAMILIES = ("milling",)
NUMBERS = ("max_depth", "start_depth", "glue_gap", "waste_margin", "tolerance", "rpm", "feed", "entry_feed",
           "clearance_z", "safe_z", "clear_stepover", "clear_step_down", "clear_rpm", "clear_feed")
TOOL = ("tool_number", "angle", "diameter", "flute_length", "clear_tool_number", "clear_diameter",
        "clear_flute_length")
WORDS = ("inlay",)
SETTINGS = NUMBERS + TOOL + WORDS
TEXT_KEYS = ("body", "font", "size", "at")
MAX_TEXT = 2000             # characters of one text
TEXT_SIZES = (0.5, 2000.0)  # mm


def settings_from(entry) -> core.VCarveSettings:
    """The V-carve's settings from a job file's ``settings`` table, each checked by name."""
    from .jobentry import JobFileError

    given = dict(entry.settings)
    for key, value in given.items():
        if key not in SETTINGS:
            raise JobFileError(f"{entry.where}: settings.{key} is not a V-carve setting; they are "
                               f"{', '.join(SETTINGS)}")
        if key in WORDS:
            if not isinstance(value, str):
                raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not a word")
        elif isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise JobFileError(f"{entry.where}: settings.{key} = {value!r} is not a number")
    for key in ("tool_number", "clear_tool_number"):
        if key in given and not isinstance(given[key], int):
            raise JobFileError(f"{entry.where}: settings.{key} = {given[key]!r} is not a whole number")
    default = core.VCarveSettings()
    try:
        tool = core.vbit(given.get("tool_number", default.tool.number),
                         float(given.get("angle", default.tool.shape.tip_angle_deg)),
                         float(given.get("diameter", default.tool.diameter)),
                         float(given.get("flute_length", default.tool.flute_length)))
        clear = pocket_core.end_mill(given.get("clear_tool_number", default.clear_tool.number),
                                     float(given.get("clear_diameter", default.clear_tool.diameter)),
                                     float(given.get("clear_flute_length", default.clear_tool.flute_length)))
    except (ProgramError, core.VCarveError) as error:
        raise JobFileError(f"{entry.where}: the tools: {error}") from None
    values = {key: given[key] for key in WORDS if key in given}
    values.update({key: float(given[key]) for key in NUMBERS if key in given})
    return core.VCarveSettings(tool=tool, clear_tool=clear, **values)


def font_path(font: str, base_dir: str, where: str) -> str:
    """A font file beside the job file, else one of Blender's bundled fonts by its file name."""
    import bpy

    from .jobentry import JobFileError

    given = os.path.join(base_dir, font)
    if os.path.isfile(given):
        return given
    bundled = os.path.join(bpy.utils.system_resource("DATAFILES", path="fonts") or "", os.path.basename(font))
    if os.path.isfile(bundled):
        return bundled
    problem = file_problem(given, "a font file")
    if problem not in (None, "no such file"):          # a folder, a link loop, a path too long ...
        raise JobFileError(named(f"{where}: text.font = {font!r}", problem))
    raise JobFileError(f"{where}: text.font = {font!r}: no such font file (beside the job file, or among "
                       "Blender's fonts)")


def text_spec(text, where: str) -> dict:
    """The ``text`` entry as a table, each key checked."""
    from .jobentry import JobFileError

    spec = {"body": text} if isinstance(text, str) else text
    if not isinstance(spec, dict):
        raise JobFileError(f"{where}: text = {text!r} is neither a string nor a table")
    for key in spec:
        if key not in TEXT_KEYS:
            raise JobFileError(f"{where}: text.{key} is not a text key; they are {', '.join(TEXT_KEYS)}")
    body = spec.get("body")
    if not isinstance(body, str) or not body.strip():
        raise JobFileError(f"{where}: text.body = {body!r}: give the text to carve")
    if len(body) > MAX_TEXT:
        raise JobFileError(f"{where}: text.body has {len(body)} characters, more than {MAX_TEXT}")
    size = spec.get("size", 20.0)
    if isinstance(size, bool) or not isinstance(size, (int, float)) or not TEXT_SIZES[0] <= size <= TEXT_SIZES[1]:
        raise JobFileError(f"{where}: text.size = {size!r} must be a number of mm from {TEXT_SIZES[0]:g} to "
                           f"{TEXT_SIZES[1]:g}")
    at = spec.get("at")
    if at is not None and not (isinstance(at, list) and len(at) == 2 and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in at)):
        raise JobFileError(f"{where}: text.at = {at!r} must be [x, y] in work mm")
    font = spec.get("font")
    if font is not None and not isinstance(font, str):
        raise JobFileError(f"{where}: text.font = {font!r} is not a file name")
    return {"body": body, "size": float(size), "at": at, "font": font}


def text_loops(spec: dict, base_dir: str, where: str) -> list:
    """The text's outlines (mm, centred on the origin), laid out by Blender in its font."""
    return text_outlines(spec, base_dir, where)[0]


def text_outlines(spec: dict, base_dir: str, where: str) -> tuple:
    """(the text's outlines, its characters one by one as (character, index, loops)), mm, centred
    on the origin, laid out by Blender in its font (the characters: [] for a text longer than
    textcells.MAX_CHARACTERS)."""
    import bpy

    from .jobentry import JobFileError

    curve = bpy.data.curves.new("V-carve text", type="FONT")
    try:
        curve.body = spec["body"]
        curve.size = spec["size"]
        curve.align_x = "CENTER"
        curve.align_y = "CENTER"
        if spec["font"]:
            path = font_path(spec["font"], base_dir, where)
            try:
                curve.font = bpy.data.fonts.load(path, check_existing=True)
            except RuntimeError as error:
                raise JobFileError(f"{where}: text.font = {spec['font']!r}: Blender cannot read it ({error})") from None
        local, faces, materials = textcells.character_faces(curve)
    finally:
        bpy.data.curves.remove(curve)
    if not faces:
        raise JobFileError(f"{where}: text {spec['body']!r} has no glyph outlines in its font (is the font missing "
                           "these characters?)")
    points = local[:, :2]
    loops = rg.loops(rg.union_of_faces([points[face] for face in faces], f"text {spec['body']!r}"))
    characters = [] if len(spec["body"]) > textcells.MAX_CHARACTERS else \
        textcells.outlines_by_character(spec["body"], points, faces, materials, f"text {spec['body']!r}")
    return loops, characters


def job_operation(scene, depsgraph, entry, post_name: str):
    """A job file's V-carve: objects ``region`` (and ``plate``: the stock, default the CAM panel's)
    or a ``text``; the settings by name; geometry in work mm in the plate's frame (its top at Z = 0)."""
    from .jobentry import JobFileError
    from .machines import scene_machine

    slots = ("region", "plate")
    for slot in entry.objects:
        if slot not in slots:
            raise JobFileError(f"{entry.where}: objects.{slot}: a V-carve's objects are {', '.join(slots)}")
    has_text = "text" in entry.table
    if has_text == ("region" in entry.objects):
        raise JobFileError(f"{entry.where}: give the region as objects = {{ region = \"<curve, Text or mesh>\" }} "
                           "or as text = \"...\", one of them")
    kezuri = scene.kezuri
    plate = convert.plate_from_object(entry.objects.get("plate", kezuri.stock.plate), depsgraph, scene,
                                      kezuri.stock.origin)
    convert.check_fits(plate, scene)
    settings = settings_from(entry)
    what = f"V-carve {entry.name!r}"
    if has_text:
        spec = text_spec(entry.table["text"], entry.where)
        loops, characters = text_outlines(spec, entry.base_dir, entry.where)
        outline = np.vstack(plate.outline)
        at = np.asarray(spec["at"] if spec["at"] is not None else (outline.min(axis=0) + outline.max(axis=0)) / 2,
                        float)
        loops = [loop + at for loop in loops]
        characters = [(char, index, tuple(loop + at for loop in outlines)) for char, index, outlines in characters]
        letters = f"text {spec['body']!r}"
    else:
        obj = entry.objects["region"]
        loops = convert.outlines_in_work(obj, depsgraph, plate.frame)
        characters = textcells.character_outlines(obj, depsgraph, plate.frame, loops)
        letters = f"object {obj.name!r}"
    what += f" ({letters})"
    try:
        settings.check(what)
        core.carved_region(loops, settings, what)
    except core.VCarveError as error:
        raise JobFileError(f"{entry.where}: the V-carve: {error}") from None
    geometry = VCarveGeometry(tuple(loops), entry.name, 0.0, tuple(plate.outline), float(plate.size[2]),
                              tuple(characters), letters)
    stock = VCarveKind.stock(geometry, None, settings)
    machine = scene_machine(kezuri.machine, POST_FAMILIES, post_name)
    setup = Setup(name=scene.name, post=post_name, machine=machine,
                  work_offset=kezuri.machine.work_offset, rapid_rate=kezuri.machine.rapid_rate, stock=stock)
    return JobOperation("vcarve", entry.name, settings, geometry, entry.enabled), setup, plate.frame


def settings_group() -> type:
    """The V-carve's settings as panel properties (names, units and defaults of VCarveSettings)."""
    from . import kindsettings as ks

    d = core.VCarveSettings()
    return ks.settings_group("KezuriVCarveSettings", {
        "tool_number": ks.whole("Tool Number", d.tool.number, "The V-bit's tool number (T word)"),
        "angle": ks.number("Angle", d.tool.shape.tip_angle_deg, "The V-bit's included angle", "degrees"),
        "diameter": ks.length("Diameter", d.tool.diameter, "The V-bit's diameter"),
        "flute_length": ks.length("Flute Length", d.tool.flute_length, "The V-bit's flute length"),
        "max_depth": ks.length("Max Depth", d.max_depth, "Deepest the V-bit goes; deeper areas cleared flat by "
                                                         "the end mill; 0: no limit"),
        "start_depth": ks.length("Start Depth", d.start_depth, "The tip's depth where the region is 0 wide (an "
                                                               "inlay's plug: how far it goes in)"),
        "tolerance": ks.length("Tolerance", d.tolerance, "How far the path may stray from the medial axis"),
        "clear_tool_number": ks.whole("Mill Tool", d.clear_tool.number, "The end mill's tool number (T word)"),
        "clear_diameter": ks.length("Mill Diameter", d.clear_tool.diameter, "The end mill's diameter"),
        "clear_flute_length": ks.length("Mill Flutes", d.clear_tool.flute_length, "The end mill's flute length"),
        "clear_stepover": ks.length("Stepover", d.clear_stepover, "Between the end mill's rings; 0: its radius"),
        "clear_step_down": ks.length("Step Down", d.clear_step_down, "Deepest cut of one level"),
        "clear_rpm": ks.number("Mill Spindle", d.clear_rpm, "The end mill's spindle speed", "rpm", 0),
        "clear_feed": ks.number("Mill Feed", d.clear_feed, "The end mill's feed", "mm/min", 0),
        "inlay": ks.choice("Inlay", d.inlay, "A plain V-carve, or one half of an inlay", (
            ("none", "None", "A plain V-carve"),
            ("female", "Female", "The inlay's pocket: the design carved in"),
            ("male", "Male", "The inlay's plug: the design mirrored, the waste round it carved away"))),
        "glue_gap": ks.length("Glue Gap", d.glue_gap, "Male: between plug and pocket, square to the walls"),
        "waste_margin": ks.length("Waste Margin", d.waste_margin, "Male: board cleared round the plug; 0: twice "
                                                                  "the widest cut plus 2 mm"),
        "rpm": ks.number("Spindle", d.rpm, "Spindle speed", "rpm", 0),
        "feed": ks.number("Feed", d.feed, "Cutting feed", "mm/min", 0),
        "entry_feed": ks.number("Entry Feed", d.entry_feed, "Feed down into each path", "mm/min", 0),
        "clearance_z": ks.length("Clearance Plane", d.clearance_z, "Height of rapid moves between cuts"),
        "safe_z": ks.length("Safe Z", d.safe_z, "Height where the operation starts and ends"),
    })


PANELS = (("V-Bit", ("tool_number", "angle", "diameter", "flute_length")),
          ("Depth", ("max_depth", "start_depth", "tolerance")),
          ("Clearing", ("clear_tool_number", "clear_diameter", "clear_flute_length", "clear_stepover",
                        "clear_step_down", "clear_rpm", "clear_feed")),
          ("Inlay", ("inlay", "glue_gap", "waste_margin")),
          ("Feeds & Heights", ("rpm", "feed", "entry_feed", "clearance_z", "safe_z")))

WORKFLOW = Workflow("VCARVE", "V-carve", "V-carve closed regions and text with a V-bit; inlays",
                    post_families=POST_FAMILIES, kind="vcarve", job_operation=job_operation,
                    settings_group=settings_group(), settings_panels=PANELS)
