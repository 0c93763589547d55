"""The feeds a job's operation takes from the calculator (:mod:`..toolpath.feeds.operationfeeds`)
when the job has a material: its tools as the operation will cut with them (number and diameter
from its settings, else the kind's defaults; flutes and tool material from the tool library where
it holds the same tool: number, kind and diameter, else a 2-flute carbide router bit), the
machine profile the job is written for, and the settings the user left out filled in.  Also the
report's side: each ``feeds`` entry of report.json gets its values with their source."""
from __future__ import annotations

import dataclasses

from ..toolpath.feeds import operationfeeds as of
from ..toolpath.feeds.calculator import FeedsError
from ..toolpath.feeds.materials import MaterialError
from ..toolpath.operations.chamfer.chamfer import ChamferSettings
from ..toolpath.operations.drill.drill import DrillSettings
from ..toolpath.operations.pocket.pocket import PocketSettings
from ..toolpath.operations.profile.profile import ProfileSettings
from ..toolpath.operations.vcarve.vcarve import VCarveSettings
from .jobtools import SLOTS

KINDS = tuple(of.KINDS)
# (kind, slot) -> the kind's default tool there (its number and diameter when the settings do not give them)
DEFAULT_TOOLS = {("profile", "tool"): lambda: ProfileSettings().tool, ("pocket", "tool"): lambda: PocketSettings().tool,
                 ("drill", "drill"): lambda: DrillSettings().tool, ("drill", "mill"): lambda: DrillSettings().mill,
                 ("chamfer", "tool"): lambda: ChamferSettings().tool, ("vcarve", "tool"): lambda: VCarveSettings().tool,
                 ("vcarve", "clear"): lambda: VCarveSettings().clear_tool}
IR_KINDS = {"flat": "flat", "drill": "drill", "vbit": "vbit"}


def whole(value) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def slot_tool(kind: str, slot, settings: dict, library):
    """The slot's :class:`of.ToolMake` from the operation's settings (None where a number or
    diameter is not a number: the kind's own check refuses it by name)."""
    number_key, diameter_key = SLOTS[kind][slot.name][:2]
    if (kind, slot.name) in DEFAULT_TOOLS:
        default = DEFAULT_TOOLS[(kind, slot.name)]()
        number, diameter = settings.get(number_key, default.number), settings.get(diameter_key, default.diameter)
    else:       # a pocket's rest end mill: its diameter given, its number the next (0: the next)
        main = settings.get("tool_number", PocketSettings().tool.number)
        number = settings.get(number_key) or (main + 1 if whole(main) else None)
        diameter = settings.get(diameter_key)
    if not whole(number) or not of.usable(diameter):
        return None
    entry = library.find(number) if library is not None else None
    if (entry is not None and entry.to_ir_tool().kind == IR_KINDS[slot.tool_kind]
            and abs(entry.diameter - float(diameter)) <= 1e-6):
        return of.ToolMake(number, entry.kind, float(diameter), entry.flutes, entry.material)
    return of.ToolMake(number, slot.tool_kind, float(diameter))


def operation_feeds(scene, entry, families, post_name: str, library, keep_typed: bool = True) -> tuple:
    """(the settings to add, the records) of a job entry of a computed kind in the scene's
    material (Machine & Stock), on the machine the post writes for."""
    from .jobentry import JobFileError
    from .machines import scene_machine

    tools = {}
    for slot in of.KINDS[entry.kind]:
        tool = slot_tool(entry.kind, slot, entry.settings, library)
        if tool is not None:
            tools[slot.name] = tool
    machine = scene_machine(scene.kezuri.machine, families, post_name)
    try:
        added, records = of.operation_feeds(entry.kind, entry.settings, tools, scene.kezuri.stock.material, machine,
                                            keep_typed)
    except (FeedsError, MaterialError) as error:
        raise JobFileError(f"{entry.where}: feeds: {error}") from None
    for record in records:
        record["job_operation"] = entry.name
    return added, records


def with_feeds(scene, entry, families, post_name: str, library) -> tuple:
    """(the entry with the computed settings added, the records); the entry as it is (and no
    records) when the scene has no material or the kind keeps its own values."""
    if scene.kezuri.stock.material == "NONE" or entry.kind not in of.KINDS:
        return entry, []
    added, records = operation_feeds(scene, entry, families, post_name, library)
    return dataclasses.replace(entry, settings={**entry.settings, **added}), records


def annotate(entries: list, planned, program, records) -> list:
    """Each report.json ``feeds`` entry (one per program operation, in order) with ``values``:
    its slot's spindle speed, feeds and steps by setting name, each with its ``source``
    ("computed" or "typed"), and ``values_chip_load_mm``: the chip load they give."""
    owners = {}
    for item in planned.planned:
        for op in (*item.part.operations, *(item.part.macro_operations or ())):
            owners[id(op)] = item.operation.name
    by_tool = {(r["job_operation"], r["tool_number"]): r for r in records}
    for entry, op in zip(entries, program.operations):
        record = by_tool.get((owners.get(id(op)), op.tool.number))
        if record is not None:
            entry["values"] = {name: {"value": v["value"], "source": v["source"]} for name, v in record["values"].items()}
            entry["values_chip_load_mm"] = record["chip_load_mm"]
    return entries
