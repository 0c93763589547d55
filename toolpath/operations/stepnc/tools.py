"""The tools of a workplan: which T number each MILLING_CUTTING_TOOL gets, and its IR tool.

T numbers come from the file's tool identifiers where they are numbers: a tool whose its_id is
``2``, ``T2``, ``T02``, ``T2 5 mm drill``, ``TOOL 2`` or ``Tool #2`` is T2, whatever order the
workingsteps use it in, so an operator who loads the tools by the file's names loads the right
ones.  Identifiers that are not numbers (``MILL 18MM``: a size is not a tool number) and numbers
that clash (two different tools claiming one number; the first in the workplan keeps it) or that
no control takes (0, more than MAX_TOOL_NUMBER) get the lowest numbers the file leaves free, in
order of first use, and a note says which got which.  Generators often write a new tool instance
for every operation: instances with the same identifier, body and dimensions are one tool.
Split from workplan.py.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from ...ir.program import Tool
from .process import CuttingTool, DRILLING_TOOL_BODIES

# What a tool body is called in the NC comments (Tool.describe); bodies not listed use the IR kind's name.
BODY_LABELS = {"TWIST_DRILL": "twist drill", "TAPERED_DRILL": "drill", "CENTER_DRILL": "centre drill",
               "REAMER": "reamer", "TAPERED_REAMER": "reamer", "TAP": "tap", "COUNTERSINK": "countersink",
               "COUNTERBORE": "counterbore", "FACEMILL": "face mill"}
# The largest T number taken from a file: 4 digits, what a Fanuc T word holds (B-62764EN, "Tool function").
MAX_TOOL_NUMBER = 9999
# "2", "T2", "T02", "T2 5 mm drill", "TOOL 2", "Tool #2", "T-2": the number must end the identifier or be
# followed by a separator (not a letter, digit or decimal point: "T10MM" and "T2.5" are not tool numbers).
NUMBERED = re.compile(r"^\s*(?:T(?:OOL)?[\s#_\-]*)?(\d+)(?=$|[^0-9A-Za-z.])", re.IGNORECASE)
BARE_NUMBER = re.compile(r"^\s*\d+\s*$")


def number_in(identifier: str) -> int | None:
    """The tool number an identifier states (``T2 5 mm drill`` -> 2), or None.  A leading number
    counts only when it is the whole identifier (``6 mm end mill`` names a size, not T6)."""
    text = str(identifier or "")
    match = NUMBERED.match(text)
    if match is None:
        return None
    if not re.match(r"^\s*T", text, re.IGNORECASE) and not BARE_NUMBER.match(text):
        return None
    return int(match.group(1))


@dataclass(frozen=True)
class ToolNumbering:
    """{MILLING_CUTTING_TOOL instance id: T number}, the notes on how they were given, and per
    T number the file's tool (instance id and identifier) for the NC header."""

    numbers: dict
    notes: tuple
    named: dict          # T number -> (instance id, its_id)


def _key(tool: CuttingTool) -> tuple:
    body = tool.its_tool_body
    return (tool.its_id, body.type_name, body.dimension, body.number_of_teeth, body.taper_angle,
            tool.overall_assembly_length)


def tool_numbering(workingsteps) -> ToolNumbering:
    """T numbers for the tools of ``workingsteps`` (in the workplan's own order, so reordering
    never renumbers): the file's where its identifiers are numbers, else the lowest free ones."""
    distinct, first_instance = [], {}
    for step in workingsteps:
        tool = step.its_operation.its_tool
        key = _key(tool)
        if key not in first_instance:
            first_instance[key] = tool
            distinct.append(key)
    given, notes, unnumbered = {}, [], []
    for key in distinct:
        tool = first_instance[key]
        number = number_in(tool.its_id)
        what = f"#{tool.id} MILLING_CUTTING_TOOL '{tool.its_id}'"
        if number is None:
            unnumbered.append(key)
        elif not 1 <= number <= MAX_TOOL_NUMBER:
            notes.append(f"{what} names T{number}, not a tool number every control takes (1..{MAX_TOOL_NUMBER})")
            unnumbered.append(key)
        elif number in given:
            other = first_instance[given[number]]
            notes.append(f"{what} and #{other.id} '{other.its_id}' both claim T{number} but are different tools "
                         f"(identifier, body or dimensions): #{other.id} keeps T{number}")
            unnumbered.append(key)
        else:
            given[number] = key
    numbers_of = {key: number for number, key in given.items()}
    free = (n for n in range(1, 10 ** 9) if n not in given)
    assigned = []
    for key in unnumbered:
        numbers_of[key] = next(free)
        tool = first_instance[key]
        assigned.append(f"T{numbers_of[key]} '{tool.its_id}'")
    if assigned:
        notes.append("tools without a usable number in their identifier, numbered in order of first use: "
                     + ", ".join(assigned))
    numbers = {}
    for step in workingsteps:
        tool = step.its_operation.its_tool
        numbers[tool.id] = numbers_of[_key(tool)]
    named = {numbers_of[key]: (first_instance[key].id, first_instance[key].its_id) for key in distinct}
    return ToolNumbering(numbers, tuple(notes), named)


def tool_numbers(workingsteps) -> dict:
    """{MILLING_CUTTING_TOOL instance id: T number} (see :func:`tool_numbering`)."""
    return tool_numbering(workingsteps).numbers


def tool_for(tool: CuttingTool, number: int) -> Tool:
    """The IR tool of an ISO 14649 cutting tool; its name says the file's identifier and instance."""
    body = tool.its_tool_body
    dimension = body.dimension
    corner = dimension.edge_radius or 0.0
    if body.type_name == "BALL_ENDMILL":
        kind, corner = "ball", dimension.diameter / 2
    elif body.type_name in DRILLING_TOOL_BODIES:
        kind = "drill"
    else:
        kind = "bull" if corner > 0 else "flat"
    extra = {"flute_length": dimension.cutting_edge_length} if dimension.cutting_edge_length else {}
    return Tool(number, kind, dimension.diameter, min(corner, dimension.diameter / 2), name=tool.its_id,
                label=BODY_LABELS.get(body.type_name, ""), **extra)
