"""The feeds check of a single-workflow batch run (``batch.py engrave``, ``carve``, ``rotary``), as
``batch.py job`` runs it (:func:`.jobfile.feeds_check`): each operation of the written program, its
spindle speed and cutting feed against its tool and the stock's material and the machine
(:func:`..toolpath.feeds.programcheck.check_program`), into report.json's ``feeds`` and, for each
rubbing, overload or beyond-the-machine flag, one warning.  The material is ``--material`` or the
scene's (Machine & Stock > Material); with none, nothing is checked.  The workflows' values (the
gouge-texture paper's for the seeds) are not changed: only warned about.
"""
from __future__ import annotations

from ..toolpath.feeds import materials, programcheck
from ..toolpath.ir.errors import InputError


class MaterialOptionError(InputError):
    """``--material`` names no material of the tables: the message names the option and the value."""


def material_argument(p) -> None:
    p.add_argument("--material", help=f"the stock's material ({', '.join(materials.MATERIALS)}, or none): each "
                                      "operation's spindle speed and feed are checked against it (warnings only); "
                                      "default: the scene's Machine & Stock material")


def material_option(value: str) -> str | None:
    """``--material``'s value as a material key of the tables, None for "none"; anything else is
    refused naming the option and the value as typed."""
    if value.strip().lower() in ("", "none"):
        return None
    try:
        return materials.material(value).key
    except materials.MaterialError as error:
        raise MaterialOptionError(f"--material {value!r}: {error}") from None


def batch_material(args, scene) -> str | None:
    """The material the run is checked against: ``--material`` (set as the scene's too), else the
    scene's; None for none."""
    value = getattr(args, "material", None)
    if value is not None:
        key = material_option(value)
        scene.kezuri.stock.material = key or "NONE"
        return key
    key = scene.kezuri.stock.material
    return None if key == "NONE" else key


def check(args, scene, program, machine, report: dict, findings: list) -> list:
    """Check ``program`` (an IR Program, or its operations) in the run's material on ``machine``:
    report["feeds"] gets the entries, ``findings`` one warning per flag; the entries ([] when no
    material is known)."""
    material = batch_material(args, scene)
    if material is None:
        return []
    entries = checked(program, material, machine, False)
    report["feeds"] = entries
    findings += programcheck.warnings(entries)
    return entries


def checked(program, material: str, machine, library=False) -> list:
    """The feeds check's entries of ``program`` (or its operations) in ``material`` on ``machine``,
    the flutes and tool material from the tool ``library`` where it holds the same tool (False:
    read here)."""
    from .toolstore import tool_makes

    operations = getattr(program, "operations", program)
    tools = {op.tool.number: op.tool for op in operations}.values()
    return programcheck.check_program(operations, material, machine, known=tool_makes(tools, library))


def panel_check(scene):
    """A panel export's feeds check, as :func:`check` is batch's: the scene's material (Machine &
    Stock > Material) and the tool library are read here, on the main thread; returns
    ``check(program, machine, findings) -> entries``, which adds a warning to ``findings`` for each
    flag ([] and nothing checked with no material)."""
    from .toolstore import library_or_none

    key = scene.kezuri.stock.material
    material = None if key == "NONE" else key
    library = library_or_none() if material else None

    def check_program(program, machine, findings: list) -> list:
        if material is None:
            return []
        entries = checked(program, material, machine, library)
        findings += programcheck.warnings(entries)
        return entries
    return check_program
