"""Suggest Feeds: the selected job-list row's spindle speed, feeds and steps filled from the feeds
calculator for the stock's material (Machine & Stock > Material), its tools (the tool library's
flutes and tool material where it holds the same tool) and the machine the scene's post writes
for, as a job file with a material computes the ones it leaves out (:mod:`.jobfeeds`); the report
shows the chip load each tool then runs at.  The values become the row's own: edit them after."""
from __future__ import annotations

import json

import bpy

from ..toolpath.feeds import materials
from ..toolpath.ir.errors import InputError
from .common import run_reported
from .jobfeeds import KINDS, operation_feeds
from .jobrows import active_row, job_list, read_back, row_entry
from .translations import translate_message


class SuggestFeedsError(InputError):
    """Feeds that cannot be suggested for the row: the message says why."""


def fill(scene, row, keep_typed: bool = True) -> list:
    """The calculator's feeds into the row's settings (``keep_typed``: the ones it has stay, as a
    job file's do): the records (one per tool) of what was filled; the scene has a material."""
    from . import toolstore
    from .preferences import scene_post
    from .workflows import WORKFLOWS

    index = list(job_list(scene).rows).index(row) + 1
    entry = row_entry(row, index)
    families = next(w.post_families for w in WORKFLOWS if w.kind == row.kind)
    added, records = operation_feeds(scene, entry, families, scene_post(scene), toolstore.library_or_none(),
                                     keep_typed)
    if added:
        row.settings = json.dumps({**entry.settings, **added}, sort_keys=True)     # the panel's group follows
    return records


def fill_new(scene, row) -> None:
    """A row added to the list, or loaded from a job file, while the scene has a material: the
    feeds it leaves out from the calculator, so the panel shows what a job file would compute."""
    if scene.kezuri.stock.material != "NONE" and row.kind in KINDS:
        fill(scene, row)


def suggest(scene) -> list:
    """Fill the selected row's settings (every value computed): the records (one per tool)."""
    row = active_row(scene)
    if scene.kezuri.stock.material == "NONE":
        raise SuggestFeedsError("Suggest Feeds needs the stock's Material: pick it in Machine & Stock first")
    read_back(scene)
    records = fill(scene, row, keep_typed=False)
    if not records:
        raise SuggestFeedsError(f"{row_entry(row, 0).where}: no tool to suggest feeds for: its diameter is not a "
                                "positive number")
    return records


def tool_line(record: dict) -> str:
    values = {v["what"]: v["value"] for v in record["values"].values()}
    low, high = record["band_mm"]
    if record.get("chip_load_per") == "revolution":         # a drill: fed per revolution
        return (f"T{record['tool_number']}: {values['rpm']:g} rpm, feed {values['feed']:g} mm/min, feed per "
                f"revolution {record['chip_load_mm']:.4f} mm (band {low:.4f} - {high:.4f} mm)")
    return (f"T{record['tool_number']}: {values['rpm']:g} rpm, feed {values['feed']:g} mm/min, chip load "
            f"{record['chip_load_mm']:.4f} mm per tooth (band {low:.4f} - {high:.4f} mm)")


class KEZURI_OT_job_suggest_feeds(bpy.types.Operator):
    """Fill the selected operation's spindle speed, feeds and steps from the calculator for the stock's material"""

    bl_idname = "kezuri.job_suggest_feeds"
    bl_label = "Suggest Feeds"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        row = active_row(context.scene)
        if row is None:
            cls.poll_message_set("Add an operation to the job list first")
            return False
        if row.kind not in KINDS:
            cls.poll_message_set("Suggest Feeds is for profile, pocket, drilling, chamfer and V-carve operations")
            return False
        return True

    def execute(self, context):
        def run():
            records = suggest(context.scene)
            label = materials.material(context.scene.kezuri.stock.material).label
            self.report({"INFO"}, translate_message(f"Suggested feeds for {active_row(context.scene).name!r} in "
                                                    f"{label}"))
            for record in records:
                self.report({"INFO"}, translate_message(tool_line(record)))
                for flag in record["flags"]:
                    self.report({"WARNING"}, translate_message(flag["message"]))
            return {"FINISHED"}
        return run_reported(self, run)


CLASSES = (KEZURI_OT_job_suggest_feeds,)
