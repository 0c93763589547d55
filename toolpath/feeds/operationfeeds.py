"""The feeds an operation of a job takes from the calculator: for each of its tools (a *slot*: a
pocket's main and rest end mills, a drilling's drill and helix end mill, a V-carve's V-bit and
clearing end mill), the spindle speed, feed, plunge feed, step-down and step-over settings the user
left out come from :func:`.calculator.compute` for that tool, the job's material, the operation
kind and the machine profile; the ones typed are kept as typed (the calculator's overrides: a typed
spindle speed gives the computed feed its chip load) and flagged where they leave the band.

Only the kinds without the paper's values are computed (:data:`KINDS`): an engraving, carving or
rotary job keeps the gouge-texture paper's values (and the STEP-NC, turn-mill and punching kinds
their own), as typed or defaulted.  Setting names are the job files' (``settings = { rpm = ... }``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from . import calculator

VALUES = ("rpm", "feed", "plunge_feed", "step_down", "step_over")
STEP_DIGITS = 3         # computed steps kept to 0.001 mm (what a panel field shows)


@dataclass(frozen=True)
class Slot:
    """One tool of an operation kind: the calculator's ``tool_kind`` (when the tool library does
    not say) and ``operation`` kind, and ``settings``: (value in :data:`VALUES`, setting name).
    ``needs``: a setting that must be given and not 0/false for the tool to cut (a pocket's rest
    end mill, a drilling's helix); ``unless``: a setting that, given and not 0, leaves the
    step-down out (a drill's dwell is for holes drilled without pecks)."""

    name: str
    tool_kind: str
    operation: str
    settings: tuple
    needs: str = ""
    unless: str = ""


KINDS = {
    "profile": (Slot("tool", "flat", "profile", (("rpm", "rpm"), ("feed", "feed"), ("plunge_feed", "plunge_feed"),
                                                 ("step_down", "step_down"))),),
    "pocket": (Slot("tool", "flat", "pocket", (("rpm", "rpm"), ("feed", "feed"), ("plunge_feed", "entry_feed"),
                                               ("step_down", "step_down"), ("step_over", "stepover"))),
               Slot("rest", "flat", "pocket", (("rpm", "rest_rpm"), ("feed", "rest_feed"),
                                               ("step_down", "rest_step_down"), ("step_over", "rest_stepover")),
                    needs="rest_diameter")),
    "drill": (Slot("drill", "drill", "drill", (("rpm", "rpm"), ("feed", "feed"), ("step_down", "peck")),
                   unless="dwell"),
              Slot("mill", "flat", "pocket", (("rpm", "mill_rpm"), ("feed", "mill_feed")), needs="helix")),
    "chamfer": (Slot("tool", "vbit", "chamfer", (("rpm", "rpm"), ("feed", "feed"), ("plunge_feed", "plunge_feed"))),),
    "vcarve": (Slot("tool", "vbit", "vcarve", (("rpm", "rpm"), ("feed", "feed"), ("plunge_feed", "entry_feed"))),
               Slot("clear", "flat", "pocket", (("rpm", "clear_rpm"), ("feed", "clear_feed"),
                                                ("step_down", "clear_step_down"), ("step_over", "clear_stepover")))),
}


@dataclass(frozen=True)
class ToolMake:
    """A slot's tool as the operation will cut with it: ``number``, ``kind`` (a calculator tool
    kind), ``diameter`` mm; ``flutes`` and ``material`` (carbide, hss) from the tool library, None
    where it does not hold the tool (the calculator then takes a 2-flute carbide router bit)."""

    number: int
    kind: str
    diameter: float
    flutes: int | None = None
    material: str | None = None


def setting_names(kind: str) -> tuple:
    """Every setting the calculator may fill for an operation of ``kind`` (none for the other kinds)."""
    return tuple(name for slot in KINDS.get(kind, ()) for _, name in slot.settings)


def cuts(slot: Slot, typed: dict) -> bool:
    """Whether the slot's tool cuts with these settings (its ``needs`` given and not 0 / false)."""
    return not slot.needs or bool(typed.get(slot.needs))


def usable(value) -> bool:
    return not isinstance(value, bool) and isinstance(value, (int, float)) and math.isfinite(value) and value > 0


def operation_feeds(kind: str, typed: dict, tools: dict, material, machine=None, keep_typed: bool = True) -> tuple:
    """(the settings to add to ``typed``, one record per slot) of an operation of ``kind`` whose
    typed settings are ``typed``; ``tools``: slot name -> :class:`ToolMake` of the slots that cut.
    ``keep_typed`` False: every value computed (the panel's Suggest Feeds).  A typed value that is
    not a positive number is left for the kind's own check to refuse by name (its slot is not
    computed).  A record: the slot, the tool, each value with its ``source`` ("computed" or
    "typed") and setting name, the chip load the values give, the band, flags, notes, sources."""
    added, records = {}, []
    for slot in KINDS.get(kind, ()):
        tool = tools.get(slot.name)
        if tool is None or not cuts(slot, typed):
            continue
        wanted = dict(slot.settings)
        if slot.unless and typed.get(slot.unless):
            wanted.pop("step_down", None)
        given = {value: typed[name] for value, name in wanted.items() if keep_typed and name in typed}
        if not all(usable(v) for v in given.values()) or not usable(tool.diameter):
            continue
        found = calculator.compute(tool.kind, tool.diameter, material, tool.flutes, slot.operation, machine,
                                   tool.material or "carbide", rpm=given.get("rpm"), feed=given.get("feed"),
                                   plunge_feed=given.get("plunge_feed"))
        computed = {"rpm": found.rpm, "feed": found.feed, "plunge_feed": found.plunge_feed,
                    "step_down": None if found.step_down is None else round(found.step_down, STEP_DIGITS),
                    "step_over": None if found.step_over is None else round(found.step_over, STEP_DIGITS)}
        values = {}
        for value, name in wanted.items():
            if value in given:
                values[name] = {"value": given[value], "source": "typed", "what": value}
            elif computed[value] is not None:
                added[name] = computed[value]
                values[name] = {"value": computed[value], "source": "computed", "what": value}
        records.append({"slot": slot.name, "tool_number": tool.number,
                        "tool": {"kind": found.tool_kind, "diameter_mm": found.diameter, "flutes": found.flutes,
                                 "material": found.tool_material,
                                 "assumed": [name for name, v in (("flutes", tool.flutes),
                                                                  ("tool material", tool.material)) if v is None]},
                        "operation": slot.operation, "material": found.material, "values": values,
                        "chip_load_mm": round(found.chip_load, 4), "chip_load_per": found.per,
                        "band_mm": [round(v, 4) for v in found.band],
                        "flags": [f.as_dict() for f in found.flags], "notes": list(found.notes),
                        "sources": dict(found.sources)})
    return added, records

