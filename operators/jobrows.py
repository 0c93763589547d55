"""The rows of the CAM tab's job list: one row is one ``[[operations]]`` table of a job file (its
kind, name, switch, objects by slot, settings by property name, and the table's other keys such as
a drilling's ``holes``), plus what the last Generate found for it (tools, time, state).

Only property groups here (registered with :mod:`.properties`); the operators that fill and plan
the rows are :mod:`.joblist`.
"""
from __future__ import annotations

import bpy
from bpy.props import BoolProperty, CollectionProperty, EnumProperty, FloatProperty, IntProperty, \
    PointerProperty, StringProperty


def mark_changed(row, context=None):
    """A cheap marker for the list: a row changed since it was planned shows "stale" until the
    next Generate (which compares the real fingerprints)."""
    if row.state in {"PLANNED", "FINDINGS"}:
        row.state = "STALE"


def selected(job_list, context=None):
    """The list's selection changed: the panel shows the newly selected row's settings."""
    from .joblist import select_row
    select_row(job_list.id_data)


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
    settings: StringProperty(name="Settings", default="{}", update=mark_changed,
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
    show_rapids: BoolProperty(name="Show Rapids", default=False,
                              description="Show the rapid moves in the job's toolpath preview")


CLASSES = (KezuriJobObject, KezuriJobRow, KezuriJobList)
