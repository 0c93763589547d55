"""The rows of the CAM tab's job list: one row is one ``[[operations]]`` table of a job file (its
kind, name, switch, objects by slot, settings by property name, and the table's other keys such as
a drilling's ``holes``), plus what the last Generate found for it (tools, time, state).

The property groups (registered with :mod:`.properties`), the row as a job file's entry, and the
selected row's settings shown in (and read back from) its kind's panel group; the operators that
fill and plan the rows are :mod:`.joblist`.
"""
from __future__ import annotations

import json

import bpy
from bpy.props import BoolProperty, CollectionProperty, EnumProperty, FloatProperty, IntProperty, \
    PointerProperty, StringProperty

from ..toolpath.feeds.operationfeeds import setting_names
from ..toolpath.ir.errors import InputError
from .jobentry import JobEntry, JobFileError, apply_settings, settings_of


def mark_changed(row, context=None):
    """A cheap marker for the list: a row changed since it was planned shows "stale" until the
    next Generate (which compares the real fingerprints)."""
    if row.state in {"PLANNED", "FINDINGS"}:
        row.state = "STALE"


def settings_changed(row, context=None):
    """A row's settings text changed: stale, and if its kind's panel group shows this row, the group
    takes the new settings (else the next read-back would put the panel's old ones over them); a
    text that does not read is left for Generate to refuse by name."""
    mark_changed(row)
    scene = row.id_data
    group = group_of(scene, row.kind)
    if group is None or job_list(scene).shown != row.uid:
        return
    try:
        if json.loads(row.settings or "{}") != shown_settings(group, row.kind):
            show_row(scene, row)
    except (ValueError, InputError) as error:
        print(f"Kezuri: {error}")
        job_list(scene).shown = -1          # the panel no longer shows the row: its text stays as typed


def selected(listed, context=None):
    """The list's selection changed: the panel shows the newly selected row's settings."""
    select_row(listed.id_data)


class KezuriJobObject(bpy.types.PropertyGroup):
    """One object of an operation, by the slot its kind reads it from (an engraving's "plate")."""

    slot: StringProperty(name="Slot", description="Which of the operation's objects this is")
    object: PointerProperty(name="Object", type=bpy.types.Object,
                            description="The scene object the operation reads for this slot")


class KezuriJobRow(bpy.types.PropertyGroup):
    """One operation of the job (``name`` is the operation's name, unique in the job)."""

    kind: StringProperty(name="Kind", description="The operation's kind (engrave, drill ...)")
    uid: IntProperty(name="Row", options={"HIDDEN"})
    enabled: BoolProperty(name="Enabled", default=True, update=mark_changed,
                          description="Plan and cut this operation (switched off: left out of the program)")
    objects: CollectionProperty(type=KezuriJobObject)
    settings: StringProperty(name="Settings", default="{}", update=settings_changed,
                             description="The operation's settings by property name (JSON), as a job file keeps them")
    extra: StringProperty(name="More", default="{}", update=mark_changed,
                          description="The operation's other keys (JSON), e.g. a drilling's holes in work mm")
    state: EnumProperty(name="State", default="NEW", items=[
        ("NEW", "Not Planned", "Not planned yet: Generate plans it"),
        ("PLANNED", "Planned", "Planned: its toolpaths are what Export writes"),
        ("STALE", "Stale", "Changed since it was planned: Generate or Export plans it again"),
        ("FINDINGS", "Findings", "Planned, with warnings or simulation findings"),
        ("FAILED", "Failed", "Planning it failed: see the report")])
    tools: StringProperty(name="Tools", description="The tool numbers the operation uses")
    minutes: FloatProperty(name="Time", description="Estimated cutting time (min)", precision=1)
    findings: IntProperty(name="Findings", description="Warnings of its plan and findings of the last simulation")
    fingerprint: StringProperty(name="Fingerprint", options={"HIDDEN"})
    snapshot: StringProperty(name="Snapshot", options={"HIDDEN"})


class KezuriJobList(bpy.types.PropertyGroup):
    """The job list of a scene (``scene.kezuri.job_list``)."""

    rows: CollectionProperty(type=KezuriJobRow)
    active: IntProperty(name="Operation", default=0, min=0,
                        update=selected)
    shown: IntProperty(name="Shown Row", default=-1, options={"HIDDEN"})
    next_uid: IntProperty(name="Next Row", default=1, options={"HIDDEN"})


# ----- the selected row and its kind's panel ---------------------------------------------------------

def group_of(scene, kind: str):
    """The kind's panel group (``scene.kezuri.<kind>``), None for a kind without one (drill)."""
    group = getattr(scene.kezuri, kind, None)
    return group if isinstance(group, bpy.types.PropertyGroup) else None


def job_list(scene):
    return scene.kezuri.job_list


def active_row(scene):
    rows = job_list(scene).rows
    index = job_list(scene).active
    return rows[index] if 0 <= index < len(rows) else None


def row_by_uid(scene, uid: int):
    return next((row for row in job_list(scene).rows if row.uid == uid), None)


# ----- the selected row and its kind's panel ---------------------------------------------------------

def read_back(scene) -> None:
    """The panel group's settings back into the row shown in it (editing the panel edits the row)."""
    row = row_by_uid(scene, job_list(scene).shown)
    group = None if row is None else group_of(scene, row.kind)
    if group is not None:
        settings = json.dumps(shown_settings(group, row.kind), sort_keys=True)
        if settings != row.settings:
            row.settings = settings


def shown_settings(group, kind: str) -> dict:
    """The panel group's settings as the row keeps them: those that differ from the kind's
    defaults, and the spindle speed, feeds and steps the feeds calculator would fill whatever their
    value (what the panel shows is what runs: a job file with a material computes the ones it
    leaves out, :mod:`.jobfeeds`)."""
    return settings_of(group, keep=setting_names(kind))


def show_row(scene, row) -> None:
    """The row's settings into its kind's panel group (checked as a job file's are)."""
    group = group_of(scene, row.kind)
    if group is not None:
        apply_settings(group, row_entry(row, 0))
    job_list(scene).shown = row.uid


def select_row(scene) -> None:
    """The list's selection changed: keep what the panel holds, then show the new row's settings."""
    read_back(scene)
    row = active_row(scene)
    if row is None:
        job_list(scene).shown = -1
        return
    try:
        show_row(scene, row)
    except InputError as error:     # a row edited by hand into a bad value: say so, keep the panel
        print(f"Kezuri: {error}")
        job_list(scene).shown = -1



# ----- rows as job-file entries -----------------------------------------------------------------------

def parsed(row, field: str, where: str) -> dict:
    try:
        value = json.loads(getattr(row, field) or "{}")
    except json.JSONDecodeError as error:
        raise JobFileError(f"{where}: {field} is not JSON ({error})") from None
    if not isinstance(value, dict):
        raise JobFileError(f"{where}: {field} must be a table of names and values")
    return value


def row_entry(row, index: int) -> JobEntry:
    """The row as a job file's entry (``index``: its place in the list, from 1, for messages)."""
    where = f"job list: operation {index} ({row.name!r})" if index else f"job list: {row.name!r}"
    objects = {item.slot: item.object for item in row.objects}     # an empty slot clears the scene's
    extra = parsed(row, "extra", where)
    table = {"kind": row.kind, "name": row.name, "enabled": row.enabled, **extra}
    return JobEntry(row.name, row.kind, row.enabled, objects, parsed(row, "settings", where), table, where)


def snapshot(scene, row) -> str:
    """What the list compares to say "stale" cheaply: the row as it would be saved."""
    settings = row.settings
    if job_list(scene).shown == row.uid and group_of(scene, row.kind) is not None:
        settings = json.dumps(shown_settings(group_of(scene, row.kind), row.kind), sort_keys=True)
    objects = sorted((item.slot, item.object.name if item.object else "") for item in row.objects)
    return json.dumps([row.kind, row.name, row.enabled, objects, settings, row.extra])


def changed(scene, row) -> bool:
    return row.state in {"PLANNED", "FINDINGS"} and bool(row.snapshot) and row.snapshot != snapshot(scene, row)


def shown_state(scene, row) -> str:
    """The row's state for the list: a planned row whose inputs changed since it was planned, or
    after a row that changed (it starts from that row's stock), reads "stale"."""
    if row.state not in {"PLANNED", "FINDINGS"}:
        return row.state
    for earlier in job_list(scene).rows:
        if earlier == row:
            break
        if changed(scene, earlier):       # switched on or off, or edited: the stock after it differs
            return "STALE"
    return "STALE" if changed(scene, row) else row.state



CLASSES = (KezuriJobObject, KezuriJobRow, KezuriJobList)
