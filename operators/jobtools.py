"""Tools named in a job file, resolved through the tool library.

An ``[[operations]]`` table may name its tool from the library instead of typing its fields::

    tool = 3                                   # or "T3": the kind's first tool (:data:`SLOTS`)
    tools = { rough = 2, finish = "T3" }       # a kind with several tools, by slot

Each named tool gives the operation its number, diameter and (where the kind has one) flute
length, as the kind's settings would; an unknown number, a tool of the wrong kind for the slot, a
pointed tool whose angle the operation does not cut with, or a setting typed beside the tool that
names the same field are errors naming the file, the operation and the key.
"""
from __future__ import annotations

from ..toolpath.ir.tools import TIP_ANGLE_DEG
from ..toolpath.tooling.library import KIND_LABELS, ToolLibraryError, tool_number

# kind -> slot -> (number setting, diameter setting, flute length setting or None, the kinds it takes,
# the tip angle: True where the kind is planned for its shape's angle only, the name of the setting
# that takes the library tool's angle, or False where the angle does not shape the cut); the first
# slot is the one ``tool = N`` fills
SLOTS = {
    "engrave": {"rough": ("rough_tool_number", "rough_diameter", None, ("ball",), False),
                "finish": ("finish_tool_number", "finish_diameter", None, ("flat",), False)},
    "carve": {"rough": ("rough_tool_number", "rough_diameter", None, ("flat",), False),
              "finish": ("finish_tool_number", "finish_diameter", None, ("ball",), False)},
    "rotary": {"tool": ("tool_number", "tool_diameter", "flute_length", ("ball",), False)},
    "profile": {"tool": ("tool_number", "diameter", "flute_length", ("flat",), False)},
    "pocket": {"tool": ("tool_number", "diameter", "flute_length", ("flat",), False),
               "rest": ("rest_tool_number", "rest_diameter", "rest_flute_length", ("flat",), False)},
    "drill": {"drill": ("tool_number", "diameter", "flute_length", ("drill",), True),
              "mill": ("mill_tool_number", "mill_diameter", "mill_flute_length", ("flat",), False),
              "spot": ("spot_tool_number", "spot_diameter", None, ("drill",), False)},
    "chamfer": {"tool": ("tool_number", "diameter", "flute_length", ("vbit", "engraver"), True)},
    "vcarve": {"tool": ("tool_number", "diameter", "flute_length", ("vbit", "engraver"), "angle"),
               "clear": ("clear_tool_number", "clear_diameter", "clear_flute_length", ("flat",), False)},
}
KEYS = ("tool", "tools")


def named_tools(table: dict, kind: str, where: str) -> dict:
    """slot -> the tool as typed, from the table's ``tool`` / ``tools``."""
    from .jobentry import JobFileError

    if "tool" not in table and "tools" not in table:
        return {}
    slots = SLOTS.get(kind)
    if slots is None:
        raise JobFileError(f"{where}: a {kind} operation does not take its tools from the library; the kinds "
                           f"that do are {', '.join(SLOTS)}")
    if "tool" in table and "tools" in table:
        raise JobFileError(f"{where}: give tool or tools, not both")
    if "tool" in table:
        return {next(iter(slots)): table["tool"]}
    given = table["tools"]
    if not isinstance(given, dict) or not given:
        raise JobFileError(f"{where}: tools must be a table of slot = tool number, e.g. "
                           f"tools = {{ {next(iter(slots))} = 3 }}")
    unknown = sorted(set(given) - set(slots))
    if unknown:
        raise JobFileError(f"{where}: tools.{unknown[0]} is not a tool of a {kind}; its tools are "
                           f"{', '.join(slots)}")
    return dict(given)


def tool_settings(table: dict, kind: str, settings: dict, where: str, library_of) -> dict:
    """The settings the named tools give, to add to the operation's typed ones; ``library_of()``
    gives the tool library (read only when a tool is named)."""
    from .jobentry import JobFileError

    named = named_tools(table, kind, where)
    found = {}
    for slot, typed in named.items():
        key = "tool" if "tool" in table else f"tools.{slot}"
        number_key, diameter_key, flute_key, kinds, angled = SLOTS[kind][slot]
        try:
            tool = library_of().get(tool_number(typed))
        except ToolLibraryError as error:
            raise JobFileError(f"{where}: {key} = {typed!r} cannot be used: {error}") from None
        if tool.kind not in kinds:
            raise JobFileError(f"{where}: {key} = {typed!r} is {tool.describe()}; the {kind}'s {slot} tool must "
                               f"be a {' or '.join(KIND_LABELS[k] for k in kinds)}")
        ir_kind = "vbit" if tool.kind == "engraver" else tool.kind
        if angled is True and abs(tool.angle - TIP_ANGLE_DEG[ir_kind]) > 1e-9:
            raise JobFileError(f"{where}: {key} = {typed!r} is {tool.describe()} with a {tool.angle:g}° point; the "
                               f"{kind} is planned for a {TIP_ANGLE_DEG[ir_kind]:g}° one (a program's tool does not "
                               "carry its angle yet)")
        values = {number_key: tool.number, diameter_key: tool.diameter}
        if flute_key is not None:
            values[flute_key] = tool.flute_length
        if isinstance(angled, str):
            values[angled] = tool.angle
        typed_too = sorted(set(values) & set(settings))
        if typed_too:
            raise JobFileError(f"{where}: settings.{typed_too[0]} and {key} = {typed!r} both give the {slot} tool; "
                               "give one")
        found.update(values)
    return found
