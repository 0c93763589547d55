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


def suggest(scene) -> list:
    """Fill the selected row's settings: the records (one per tool) of what was filled."""
    from . import toolstore
    from .joblist import adapters
    from .preferences import scene_post

    row = active_row(scene)
    if scene.kezuri.stock.material == "NONE":
        raise SuggestFeedsError("Suggest Feeds needs the stock's Material: pick it in Machine & Stock first")
    read_back(scene)
    index = list(job_list(scene).rows).index(row) + 1
    entry = row_entry(row, index)
    added, records = operation_feeds(scene, entry, adapters()[row.kind].post_families, scene_post(scene),
                                     toolstore.library_or_none(), keep_typed=False)
    if not records:
        raise SuggestFeedsError(f"{entry.where}: no tool to suggest feeds for: its diameter is not a positive number")
    row.settings = json.dumps({**entry.settings, **added}, sort_keys=True)     # the panel's group follows
    return records


def tool_line(record: dict) -> str:
    values = {v["what"]: v["value"] for v in record["values"].values()}
    low, high = record["band_mm"]
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
