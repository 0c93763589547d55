"""The CAM tab's job list: the scene's operations in one list, planned as one job, one program.

A row is one ``[[operations]]`` table of a job file (:mod:`.jobrows`), so the list plans through
the job files' own function (:func:`.jobfile.job_of`) and a file saved from it reproduces the
same program in batch.  The selected row's settings live in its kind's panel group while it is
selected (``scene.kezuri.engrave`` for an engraving: the kind's own settings panels edit them)
and are read back into the row before any plan, save or selection change.

Plans are kept per scene (fingerprint -> part, :func:`toolpath.job.plan_job`'s cache; shell
state, not the core's), so Generate and Export re-plan only the operations whose inputs changed
and those after them, and Export writes what Generate previewed when nothing changed.
"""
from __future__ import annotations

import json
import math
import os

import bpy
from bpy.props import BoolProperty, EnumProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from ..toolpath.ir.errors import InputError
from ..toolpath.job import fingerprint, plan_job
from . import convert, pathview, simview
from .common import SteppedOperator, run_reported
from .exporting import Exported, NCExport, ProgramSheet, stages, machine_post, write_program
from .jobentry import JobFileError
from .plancache import cache_of, keep, replanned_message
from .jobrows import (active_row, job_list, read_back, row_by_uid, row_entry, select_row, show_row,
                      shown_state, snapshot)
from .preferences import scene_post
from .properties import post_items, post_number
from .suggestfeeds import fill_new
from .translations import translate_message

PREFIX = "Kezuri Job"
# an operation's objects when a row is added: slot -> (group of scene.kezuri, its property; None: empty)
DEFAULT_SLOTS = {"engrave": (("plate", "stock", "plate"), ("letters", "engrave", "letters"),
                             ("surface", "engrave", "surface")),
                 "profile": (("shape", None, None),),      # no shape: the plate's outline
                 "pocket": (("region", "engrave", "letters"), ("plate", "stock", "plate")),
                 "drill": (("holes", None, None),), "chamfer": (("edges", None, None), ("holes", None, None)),
                 "vcarve": (("region", "engrave", "letters"), ("plate", "stock", "plate"))}
DEFAULT_EXTRA = {"profile": {"tabs": []}}
DEFAULT_SETTINGS = {"profile": {"tab_count": 4}}     # a new cut-out holds its part (a job file says so itself)
ROW_KEYS = ("kind", "name", "enabled", "objects", "settings")      # a job file's keys a row keeps apart


def adapters() -> dict:
    """The workflows a job can hold: {kind: workflow} of those with ``kind`` and ``job_operation``."""
    from .workflows import WORKFLOWS
    return {w.kind: w for w in WORKFLOWS if w.kind and w.job_operation is not None}


def kind_items(self=None, context=None) -> list:
    return _KIND_ITEMS


_KIND_ITEMS = [(w.kind, w.label, w.description) for w in adapters().values()]


# ----- rows as job-file entries -----------------------------------------------------------------------

def rows_upto(scene, upto: int | None = None) -> list:
    rows = list(job_list(scene).rows)
    return rows if upto is None else rows[:upto + 1]


def build(scene, post_name: str | None = None, upto: int | None = None):
    """The job of the list (or of its rows up to ``upto``), read from the scene through the job
    files' own function: (the Job, the work frame, the post families)."""
    from .jobfile import job_of

    read_back(scene)
    rows = rows_upto(scene, upto)
    if not rows:
        raise JobFileError("the job list is empty: add an operation first")
    entries = [row_entry(row, index) for index, row in enumerate(rows, 1)]
    try:
        return job_of(scene, entries, scene.name, post_name or scene_post(scene), "job list")
    finally:
        shown = row_by_uid(scene, job_list(scene).shown)     # the groups now hold the last rows': put back
        if shown is not None:
            show_row(scene, shown)


def stale_names(scene, job) -> list:
    """Names of the switched-on operations whose fingerprint differs from the one planned."""
    before, stale = "", []
    for operation in job.operations:
        if not operation.enabled:
            continue
        key = fingerprint(job.setup, operation, before)
        row = next((r for r in job_list(scene).rows if r.name == operation.name), None)
        if row is None or row.fingerprint != key:
            stale.append(operation.name)
        before = key
    return stale


def record(scene, planned, findings_by_row: dict | None = None) -> None:
    """Each row's state, tools and time from the planned job."""
    by_name = {item.operation.name: item for item in planned.planned}
    rate = planned.job.setup.rapid_rate
    for row in job_list(scene).rows:
        item = by_name.get(row.name)
        if item is None:
            if not row.enabled:
                row.state, row.tools, row.minutes, row.findings = "NEW", "", 0.0, 0
            continue
        numbers = list(dict.fromkeys(op.tool.number for op in item.part.operations))
        row.tools = " ".join(f"T{n}" for n in numbers)
        row.minutes = sum(op.cycle_time(rate) for op in item.part.operations) / 60.0
        row.findings = len(item.part.warnings) + (findings_by_row or {}).get(row.name, 0)
        row.fingerprint = item.fingerprint
        row.snapshot = snapshot(scene, row)
        row.state = "FINDINGS" if row.findings else "PLANNED"


def show_toolpaths(scene, planned, frame) -> list:
    """Each part's toolpaths in the scene, coloured by move kind as the pictures are (the scene's
    Show Rapids switch hides the rapids), named "<row>: <operation>"."""
    convert.remove_objects(PREFIX)
    operations = [op for item in planned.planned for op in item.part.operations]
    names = [f"{item.operation.name}: {op.name}" for item in planned.planned for op in item.part.operations]
    return pathview.show_toolpaths(scene, PREFIX, operations, planned.stock, frame, names=names)


def feeds_findings(planned) -> tuple:
    """The feeds check of the planned job (Machine & Stock's material): (warnings, {row name: how
    many}); nothing when the material is None."""
    from ..toolpath.feeds import programcheck
    from .jobfile import feeds_check

    if not planned.job.setup.material:
        return [], {}
    entries = feeds_check(planned, planned.program())
    owners, counts = operation_rows(planned), {}
    for index, entry in enumerate(entries):
        if entry.get("flags") and index < len(owners):
            counts[owners[index]] = counts.get(owners[index], 0) + len(entry["flags"])
    return programcheck.warnings(entries), counts


def operation_rows(planned) -> list:
    """The operation's name of each of the program's operations, in order."""
    return [item.operation.name for item in planned.planned for _ in item.part.operations]


# ----- the program --------------------------------------------------------------------------------------

def export_job(scene, path: str, post_name: str, allow=False, findings: list | None = None, progress=None):
    """Plan what is stale (the rest from the scene's kept plans), check the whole job through the
    export gate and write one program with its setup sheet beside it, in the interface language,
    both or neither (as the Export button): (the written path, the names re-planned)."""
    from .exporting import program_and_sheet
    from .translations import interface_language

    work = program_and_sheet(lambda staged: export_job_request(scene, staged, post_name, allow), path,
                             interface_language())
    exported = work(progress)
    exported.then(scene)
    if findings is not None:
        findings += exported.findings
    return exported.path, exported.replanned


def export_job_request(scene, path: str, post_name: str, allow=False):
    """Read the job list (main thread); ``compute(progress) -> Exported`` plans, checks and writes
    without touching Blender data; its ``then`` records the rows' states in the scene."""
    from .. import post as posts
    from . import gate
    from .preview import toolpath_bytes
    from .simview import result_bytes
    from .workflow import SimulationSetup

    job, frame, families = build(scene, post_name)
    cache = cache_of(scene)
    setup = job.setup
    from ..toolpath.feeds import programcheck
    from .jobfile import feeds_check
    from .toolstore import library_or_none

    library = library_or_none() if setup.material else None     # read here: compute may run off the main thread
    post = machine_post(families, setup.post, setup.work_offset, scene.kezuri.machine.orient_spindle, setup.machine)
    macro = posts.find(families, setup.post).needs_texture
    post_label = posts.find(families, setup.post).label

    def compute(progress=None):
        planning, checking = stages(progress)
        planned = plan_job(job, cache, planning)
        keep(cache, planned)
        cut, stock, limits = planned.simulation()
        simulated, checked = gate.check(SimulationSetup(cut, stock, limits, frame, setup.name), allow, checking,
                                        machine=setup.machine)
        findings = []
        program = planned.program(macro=macro)
        written = write_program(path, post.to_text(program), post, findings)
        feeds = feeds_check(planned, program, library)
        findings += programcheck.warnings(feeds)   # the feeds: warnings only
        # the setup sheet beside the program (NCExport writes both): as batch job's
        sheet = ProgramSheet(program, checked, setup.machine, post_label, "job", list(planned.warnings), feeds,
                             lambda: [("Toolpaths", toolpath_bytes(cut.operations, stock, [],
                                                                   f"JOB {setup.name.upper()}: TOOLPATHS")),
                                      ("Result", result_bytes(simulated, "job"))])
        return Exported(written, planned.replanned(), findings, lambda scene: record(scene, planned), sheet)
    return compute


# ----- job files ----------------------------------------------------------------------------------------

def toml_value(value) -> str:
    """A value as TOML writes it (text, whole number, number, true/false, list, inline table)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise JobFileError(f"the value {value} cannot be written to a job file")
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)      # a JSON string is a TOML basic string
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{toml_key(k)} = {toml_value(v)}" for k, v in value.items()) + " }" if value else "{}"
    raise JobFileError(f"the value {value!r} cannot be written to a job file")


def toml_key(key: str) -> str:
    bare = key and all(c.isascii() and (c.isalnum() or c in "_-") for c in key)
    return key if bare else json.dumps(key, ensure_ascii=False)


def job_file_text(scene, path: str) -> str:
    """The list as a job file: [setup] names the saved .blend (relative to the file) and the post;
    one [[operations]] table per row."""
    if not bpy.data.filepath:
        raise JobFileError("save the .blend first: a job file names the .blend its objects come from")
    read_back(scene)
    rows = job_list(scene).rows
    if not len(rows):
        raise JobFileError("the job list is empty: add an operation first")
    blend = os.path.relpath(bpy.data.filepath, os.path.dirname(os.path.abspath(path)))
    machine = scene.kezuri.machine
    lines = ["# Saved from Kezuri's job list: the objects come from the .blend, the settings are the panel's",
             "[setup]", f"name = {toml_value(scene.name)}", f"blend = {toml_value(blend)}",
             f"post = {toml_value(scene_post(scene))}", f"work_offset = {toml_value(machine.work_offset)}"]
    if scene.kezuri.stock.material != "NONE":
        lines.append(f"material = {toml_value(scene.kezuri.stock.material)}")
    for index, row in enumerate(rows, 1):
        entry = row_entry(row, index)
        lines += ["", "[[operations]]", f"kind = {toml_value(row.kind)}", f"name = {toml_value(row.name)}",
                  f"enabled = {toml_value(row.enabled)}"]
        objects = {slot: obj.name for slot, obj in entry.objects.items() if obj is not None}
        if objects:
            lines.append(f"objects = {toml_value(objects)}")
        lines.append(f"settings = {toml_value(entry.settings)}")
        for key, value in entry.table.items():
            if key not in ROW_KEYS:
                lines.append(f"{toml_key(key)} = {toml_value(value)}")
    return "\n".join(lines) + "\n"


def load_job_file(scene, path: str) -> int:
    """The job file's operations into the list (replacing it), objects found by name in this scene;
    its machine preset and work offset into Machine & Stock.  Returns the number of rows."""
    from . import jobfile

    data = jobfile.read(path)
    for index, table in enumerate(data["operations"], 1):
        if table["kind"] not in adapters():
            raise JobFileError(f"job file {os.path.basename(path)}: operation {index} ({table['name']!r}): kind "
                               f"{table['kind']!r} is not one of {', '.join(sorted(adapters()))}")
    found = jobfile.entries(data, scene, path)     # every object checked before the list changes
    jobfile.apply_setup(scene, data.get("setup", {}), path)
    listed = job_list(scene)
    listed.shown = -1
    listed.rows.clear()
    for entry in found:
        row = new_row(scene, entry.kind, entry.name, slots=False)
        row.enabled = entry.enabled
        for slot, obj in entry.objects.items():
            item = row.objects.add()
            item.slot, item.object = slot, obj
        row.settings = json.dumps(entry.settings, sort_keys=True)
        row.extra = json.dumps({k: v for k, v in entry.table.items() if k not in ROW_KEYS})
        fill_new(scene, row)        # with a material: what the file leaves out, as batch computes it
    listed.active = 0
    return len(found)


# ----- rows -----------------------------------------------------------------------------------------------

def unique_name(scene, wanted: str) -> str:
    names = {row.name for row in job_list(scene).rows}
    name, number = wanted, 2
    while name in names:
        name, number = f"{wanted} {number}", number + 1
    return name


def new_row(scene, kind: str, name: str | None = None, slots: bool = True):
    listed = job_list(scene)
    row = listed.rows.add()
    row.uid = listed.next_uid
    listed.next_uid += 1
    row.kind = kind
    row.name = unique_name(scene, name or kind)
    if slots:
        for slot, group, prop in DEFAULT_SLOTS.get(kind, ()):
            item = row.objects.add()
            item.slot, item.object = slot, getattr(getattr(scene.kezuri, group), prop) if group else None
        row.extra = json.dumps(DEFAULT_EXTRA.get(kind, {}))
        row.settings = json.dumps(DEFAULT_SETTINGS.get(kind, {}))
    return row


class JobListOperator:
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        if active_row(context.scene) is None:
            cls.poll_message_set("Add an operation to the job list first")
            return False
        return True

    def execute(self, context):
        return run_reported(self, lambda: self.run(context))


class KEZURI_OT_job_add(bpy.types.Operator):
    """Add an operation to the end of the job"""

    bl_idname = "kezuri.job_add"
    bl_label = "Add Operation"
    bl_options = {"REGISTER", "UNDO"}

    kind: EnumProperty(name="Kind", items=kind_items)

    def execute(self, context):
        def run():
            read_back(context.scene)
            label = next((label for key, label, _ in _KIND_ITEMS if key == self.kind), self.kind)
            row = new_row(context.scene, self.kind, label.lower())
            job_list(context.scene).active = len(job_list(context.scene).rows) - 1
            fill_new(context.scene, row)        # with a material: the calculator's feeds (Suggest Feeds)
            self.report({"INFO"}, translate_message(f"Added {row.name!r}"))
            return {"FINISHED"}
        return run_reported(self, run)


class KEZURI_OT_job_duplicate(JobListOperator, bpy.types.Operator):
    """Add a copy of the selected operation after it"""

    bl_idname = "kezuri.job_duplicate"
    bl_label = "Duplicate Operation"

    def run(self, context):
        scene = context.scene
        read_back(scene)
        listed, source = job_list(scene), active_row(scene)
        row = new_row(scene, source.kind, source.name, slots=False)
        for item in source.objects:
            copy = row.objects.add()
            copy.slot, copy.object = item.slot, item.object
        row.enabled, row.settings, row.extra = source.enabled, source.settings, source.extra
        listed.rows.move(len(listed.rows) - 1, listed.active + 1)
        listed.active += 1
        return {"FINISHED"}


class KEZURI_OT_job_remove(JobListOperator, bpy.types.Operator):
    """Remove the selected operation from the job"""

    bl_idname = "kezuri.job_remove"
    bl_label = "Remove Operation"

    def run(self, context):
        listed = job_list(context.scene)
        if listed.shown == active_row(context.scene).uid:
            listed.shown = -1
        listed.rows.remove(listed.active)
        listed.active = min(listed.active, max(0, len(listed.rows) - 1))
        select_row(context.scene)
        return {"FINISHED"}


class KEZURI_OT_job_move(JobListOperator, bpy.types.Operator):
    """Move the selected operation up or down the job (the order it is cut in)"""

    bl_idname = "kezuri.job_move"
    bl_label = "Move Operation"

    direction: EnumProperty(name="Direction", items=[("UP", "Up", "Cut it earlier"), ("DOWN", "Down", "Cut it later")])

    def run(self, context):
        listed = job_list(context.scene)
        target = listed.active + (-1 if self.direction == "UP" else 1)
        if not 0 <= target < len(listed.rows):
            return {"CANCELLED"}
        listed.rows.move(listed.active, target)
        listed.active = target
        return {"FINISHED"}


class KEZURI_OT_job_generate(SteppedOperator, bpy.types.Operator):
    """Plan the job's operations that changed (and those after them) and show every toolpath"""

    bl_idname = "kezuri.job_generate"
    bl_label = "Generate Job"
    bl_options = {"REGISTER", "UNDO"}
    progress_label = "job"

    @classmethod
    def poll(cls, context):
        return JobListOperator.poll.__func__(cls, context)

    def prepare(self, context):
        try:
            job, frame, _ = build(context.scene)
        except InputError as error:
            mark_failed(context.scene, error)
            raise
        cache = cache_of(context.scene)
        return lambda progress=None: (plan_job(job, cache, progress), frame)

    def finish(self, context, result):
        planned, frame = result
        scene = context.scene
        keep(cache_of(scene), planned)
        feeds, counts = feeds_findings(planned)
        record(scene, planned, counts)
        show_toolpaths(scene, planned, frame)
        for warning in planned.warnings + feeds:
            self.report({"WARNING"}, translate_message(warning))
        minutes = sum(row.minutes for row in job_list(scene).rows if row.enabled)
        self.report({"INFO"}, translate_message(replanned_message(planned.replanned())))
        self.report({"INFO"}, translate_message(f"Job planned: about {minutes:.1f} min"))
        return {"FINISHED"}


class KEZURI_OT_job_simulate(SteppedOperator, bpy.types.Operator):
    """Cut the stock with the whole job, or with the operations up to the selected one, and check it"""

    bl_idname = "kezuri.job_simulate"
    bl_label = "Simulate Job"
    bl_options = {"REGISTER", "UNDO"}
    progress_label = "simulate"

    upto: BoolProperty(name="Up to Selected", default=False,
                       description="Cut only the operations up to the selected one (the stock as it is then)")

    @classmethod
    def poll(cls, context):
        return JobListOperator.poll.__func__(cls, context)

    def prepare(self, context):
        from .limits import check_group
        from .workflow import SimulationSetup

        scene = context.scene
        props = scene.kezuri.simulation
        check_group(props, "simulation")
        job, frame, _ = build(scene, upto=job_list(scene).active if self.upto else None)
        cache = cache_of(scene)

        def compute(progress=None):
            planned = plan_job(job, cache, None)
            cut, stock, limits = planned.simulation()
            setup = SimulationSetup(cut, stock, limits, frame, job.setup.name)
            return planned, simview.run_setup(setup, props.engine, props.cell, progress)
        return compute

    def finish(self, context, result):
        planned, job = result
        scene = context.scene
        simview.show_simulation(scene, job)
        simview.store_findings(scene, job)
        owners = operation_rows(planned)
        counts: dict = {}
        for finding in job.result.findings:
            if 0 <= finding.operation < len(owners):
                counts[owners[finding.operation]] = counts.get(owners[finding.operation], 0) + 1
        record(scene, planned, counts)
        for finding in job.result.findings[:10]:
            self.report({"WARNING"}, translate_message(finding.message))
        self.report({"INFO"}, translate_message(f"Removed {job.result.removed_volume_mm3 / 1000:.1f} cm^3 in "
                                                f"{job.result.seconds:.1f} s; {len(job.result.findings)} finding(s)"))
        return {"FINISHED"}


class KEZURI_OT_job_export(NCExport, bpy.types.Operator):
    """Write the job as one NC program: what Generate planned, re-planning only what changed"""

    bl_idname = "kezuri.job_export"
    bl_label = "Export Job NC"
    bl_options = {"REGISTER", "UNDO"}       # it records the rows' states

    filename_ext = ".nc"
    filter_glob: StringProperty(default="*.nc;*.ngc;*.tap", options={"HIDDEN"})
    post: EnumProperty(name="Post", items=post_items(("milling",)), default=post_number("fanuc"))

    file_suffix = "-job"

    @classmethod
    def poll(cls, context):
        return JobListOperator.poll.__func__(cls, context)

    def export_request(self, context, path):
        return export_job_request(context.scene, path, self.post,
                                  allow=context.scene.kezuri.simulation.acknowledged)


class KEZURI_OT_job_save(bpy.types.Operator, ExportHelper):
    """Save the job list as a job file (TOML) for batch.py job"""

    bl_idname = "kezuri.job_save"
    bl_label = "Save Job File"
    bl_options = {"REGISTER", "UNDO"}       # it reads the panel's settings back into the selected row

    filename_ext = ".toml"
    filter_glob: StringProperty(default="*.toml", options={"HIDDEN"})

    @classmethod
    def poll(cls, context):
        return JobListOperator.poll.__func__(cls, context)

    def execute(self, context):
        from ..post.output import write_atomic

        def run():
            text = job_file_text(context.scene, self.filepath)
            write_atomic(self.filepath, text)
            if bpy.data.is_dirty:
                self.report({"WARNING"}, translate_message("The .blend has unsaved changes: batch reads the saved "
                                                           ".blend, save it too"))
            self.report({"INFO"}, translate_message(f"Wrote {self.filepath}"))
            return {"FINISHED"}
        return run_reported(self, run)


class KEZURI_OT_job_load(bpy.types.Operator, ImportHelper):
    """Load a job file's operations into the job list (its objects by name from this scene)"""

    bl_idname = "kezuri.job_load"
    bl_label = "Load Job File"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".toml"
    filter_glob: StringProperty(default="*.toml", options={"HIDDEN"})

    def execute(self, context):
        def run():
            count = load_job_file(context.scene, self.filepath)
            self.report({"INFO"}, translate_message(f"Loaded {count} operation(s)"))
            return {"FINISHED"}
        return run_reported(self, run)


STATE_ICONS = {"NEW": "DOT", "PLANNED": "CHECKMARK", "STALE": "TIME", "FINDINGS": "ERROR", "FAILED": "CANCEL"}


def mark_failed(scene, error) -> None:
    """The rows the error names (as "job list: operation 2 ('holes')") are marked as failed."""
    for index, row in enumerate(job_list(scene).rows, 1):
        if f"job list: operation {index} ({row.name!r})" in str(error):
            row.state = "FAILED"


class KEZURI_UL_job(bpy.types.UIList):
    # one operation per row: switch, name, tools, time, state (the counts of warnings and findings)

    def draw_item(self, context, layout, data, item, icon, active_data, active_propname, index=0, flt_flag=0):
        row = layout.row(align=True)
        row.active = item.enabled
        row.prop(item, "enabled", text="")
        row.prop(item, "name", text="", emboss=False)
        state = shown_state(context.scene, item) if item.enabled else "NEW"
        if state != "NEW" and item.tools:
            row.label(text=item.tools, translate=False)
            row.label(text=f"{item.minutes:.1f}'", translate=False)
        row.label(text=str(item.findings) if state == "FINDINGS" else "", icon=STATE_ICONS[state], translate=False)


class KEZURI_MT_job_add(bpy.types.Menu):
    bl_idname = "KEZURI_MT_job_add"
    bl_label = "Add Operation"

    def draw(self, context):
        for key, label, _ in _KIND_ITEMS:
            self.layout.operator("kezuri.job_add", text=label).kind = key


CLASSES = (KEZURI_OT_job_add, KEZURI_OT_job_duplicate, KEZURI_OT_job_remove, KEZURI_OT_job_move,
           KEZURI_OT_job_generate, KEZURI_OT_job_simulate, KEZURI_OT_job_export, KEZURI_OT_job_save,
           KEZURI_OT_job_load, KEZURI_UL_job, KEZURI_MT_job_add)
