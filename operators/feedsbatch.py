"""``batch.py feeds --tool KIND:DIAMETER[:FLUTES] --material NAME [--operation KIND] [--machine PRESET]
[--tool-material carbide|hss] [--rpm N] [--feed N]``: the calculator's values and their sources, printed
as JSON (nothing is written; bad input exits 2 naming the option and the value as typed)."""
from __future__ import annotations

from ..toolpath.feeds import calculator, materials
from ..toolpath.ir import machine as machines
from ..toolpath.ir.errors import InputError

NAME = "feeds"
HELP = "feeds and speeds of a tool in a material for an operation, printed as JSON (nothing written)"


class FeedsOptionError(InputError):
    """A ``batch.py feeds`` option the calculator cannot take: the message names it and its value."""


def arguments(p) -> None:
    p.add_argument("--tool", required=True, metavar="KIND:DIAMETER[:FLUTES]",
                   help=f"the tool: kind ({', '.join(calculator.TOOL_KINDS)}), diameter in mm, flutes (default "
                        f"{calculator.DEFAULT_FLUTES}), e.g. flat:6:2")
    p.add_argument("--material", required=True, help=f"the stock: {', '.join(materials.MATERIALS)}")
    p.add_argument("--operation", default="profile", help=f"the operation kind: {', '.join(calculator.OPERATIONS)} "
                                                          "(default profile)")
    p.add_argument("--machine", help="a machine preset: its fastest spindle and feed cap the values "
                                     f"({', '.join(machines.PRESETS)}); default: none")
    p.add_argument("--tool-material", default="carbide", help="carbide (default) or hss")
    p.add_argument("--rpm", type=str, help="the spindle speed you mean to run (checked, not changed)")
    p.add_argument("--feed", type=str, help="the feed you mean to run, mm/min (checked, not changed)")


def tool_spec(text: str) -> tuple:
    """(kind, diameter, flutes or None) of ``--tool KIND:DIAMETER[:FLUTES]``."""
    parts = str(text).split(":")
    if len(parts) not in (2, 3):
        raise FeedsOptionError(f"batch.py feeds --tool {text!r}: give KIND:DIAMETER or KIND:DIAMETER:FLUTES, e.g. flat:6:2")
    try:
        kind = calculator.tool_kind(parts[0])
        diameter = calculator.positive(_number(parts[1], "diameter"), "tool diameter")
        flutes = None
        if len(parts) == 3:
            try:
                flutes = int(parts[2])
            except ValueError:
                raise calculator.FeedsError(f"flutes = {parts[2]!r}: must be a whole number 1..{calculator.MAX_FLUTES}") from None
            calculator.flute_count(flutes)
    except InputError as error:
        raise FeedsOptionError(f"batch.py feeds --tool {text!r}: {error}") from None
    return kind, diameter, flutes


def _number(text, what: str) -> float:
    try:
        return float(text)
    except (TypeError, ValueError):
        raise calculator.FeedsError(f"{what} = {text!r}: must be a number") from None


def _option(option: str, value, read):
    try:
        return read(value)
    except InputError as error:
        raise FeedsOptionError(f"batch.py feeds {option} {value!r}: {error}") from None


def run(args) -> dict:
    kind, diameter, flutes = tool_spec(args.tool)
    material = _option("--material", args.material, materials.material)
    operation = _option("--operation", args.operation, calculator.operation_kind)
    tool_material = _option("--tool-material", args.tool_material, materials.tool_material)
    machine = None if args.machine is None else _option("--machine", args.machine, machines.preset)
    rpm = None if args.rpm is None else _option("--rpm", args.rpm,
                                                lambda v: calculator.positive(_number(v, "rpm"), "rpm"))
    feed = None if args.feed is None else _option("--feed", args.feed,
                                                  lambda v: calculator.positive(_number(v, "feed"), "feed"))
    result = calculator.compute(kind, diameter, material, flutes, operation, machine, tool_material, rpm=rpm, feed=feed)
    return {"feeds": result.as_dict(), "machine": None if machine is None else
            {"name": machine.name, "max_spindle_rpm": machine.max_spindle_rpm,
             "min_spindle_rpm": machine.min_spindle_rpm, "max_feed_mm_min": machine.max_feed}}
