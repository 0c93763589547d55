"""The tool library: the cutters a shop owns, each once, by its number.

A :class:`LibraryTool` is one cutter as the craftsperson describes it (lengths in mm):

    number           the T number the programs call it by (1..999)
    kind             flat, ball, bull, vbit, drill or engraver (:data:`KINDS`)
    diameter         cutting diameter
    corner_radius    bull nose: the corner radius (<= diameter / 2); ball: diameter / 2; others 0
    angle            vbit and engraver: included angle (1..179 degrees); drill: point angle
                     (default 118); None for the others
    flutes           number of flutes (1..20)
    flute_length     length of cut
    stick_out        how far the tool stands out of the holder (None: not measured)
    holder_diameter  the holder's (collet nut's) diameter (None: not known)
    material         "carbide" or "hss"
    vendor, product_id, name   words

A :class:`ToolLibrary` holds them sorted by number, two tools never under one number.  Every
check raises :class:`ToolLibraryError` naming the tool and the field; the readers of the file
formats (:mod:`.formats`) put the file and the line or entry in front.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from ..ir.errors import InputError
from ..ir.program import ProgramError, Tool
from ..ir.tools import TIP_ANGLE_DEG
from ..feeds import calculator

KINDS = ("flat", "ball", "bull", "vbit", "drill", "engraver")
KIND_LABELS = {"flat": "flat end mill", "ball": "ball end mill", "bull": "bull nose end mill",
               "vbit": "V-bit", "drill": "drill", "engraver": "engraver"}
MATERIALS = ("carbide", "hss")
ANGLED = ("vbit", "engraver", "drill")
DRILL_POINT_DEG = 118.0          # the common twist-drill point angle, used when a drill gives none
MAX_NUMBER = 999                 # what the posts write (ir.program.Tool)
MAX_FLUTES = calculator.MAX_FLUTES     # one bound with the feeds calculator (see there why 20)
FIELDS = ("number", "kind", "diameter", "corner_radius", "angle", "flutes", "flute_length", "stick_out",
          "holder_diameter", "material", "vendor", "product_id", "name")
LENGTHS = ("diameter", "corner_radius", "flute_length", "stick_out", "holder_diameter")


class ToolLibraryError(InputError):
    """A tool or a library that cannot be used as given: the message names the tool and the field."""


def is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


@dataclass(frozen=True)
class LibraryTool:
    number: int
    kind: str
    diameter: float
    corner_radius: float = 0.0
    angle: float | None = None
    flutes: int = 2
    flute_length: float = 20.0
    stick_out: float | None = None
    holder_diameter: float | None = None
    material: str = "carbide"
    vendor: str = ""
    product_id: str = ""
    name: str = ""

    def __post_init__(self):
        number = self.number
        if isinstance(number, bool) or not isinstance(number, int) or not 1 <= number <= MAX_NUMBER:
            raise ToolLibraryError(f"tool number {number!r} is not a whole number 1..{MAX_NUMBER}")
        where = f"T{number}"
        if self.kind not in KINDS:
            raise ToolLibraryError(f"{where}: kind {self.kind!r} is not one of {', '.join(KINDS)}")
        for key in LENGTHS:
            value = getattr(self, key)
            if value is None and key in ("stick_out", "holder_diameter"):
                continue
            if not is_number(value) or not math.isfinite(value):
                raise ToolLibraryError(f"{where}: {key} {value!r} is not a number (mm)")
            if value < 0 or (value == 0 and key != "corner_radius"):
                raise ToolLibraryError(f"{where}: {key} {value!r} must be positive (mm)")
            object.__setattr__(self, key, float(value))
        radius = self.diameter / 2
        if self.kind == "ball":
            if self.corner_radius == 0.0:
                object.__setattr__(self, "corner_radius", radius)
            elif abs(self.corner_radius - radius) > 1e-9:
                raise ToolLibraryError(f"{where}: a ball end mill's corner radius is its radius {radius:g} mm, "
                                       f"not {self.corner_radius:g}")
        elif self.kind == "bull":
            if not 0 < self.corner_radius <= radius + 1e-9:
                raise ToolLibraryError(f"{where}: corner_radius {self.corner_radius:g} mm must be above 0 and at most "
                                       f"the radius {radius:g} mm")
        elif self.corner_radius != 0.0:
            raise ToolLibraryError(f"{where}: a {KIND_LABELS[self.kind]} has no corner radius (got "
                                   f"{self.corner_radius:g} mm)")
        self.check_angle(where)
        if isinstance(self.flutes, bool) or not isinstance(self.flutes, int) or not 1 <= self.flutes <= MAX_FLUTES:
            raise ToolLibraryError(f"{where}: flutes {self.flutes!r} is not a whole number 1..{MAX_FLUTES}")
        if self.material not in MATERIALS:
            raise ToolLibraryError(f"{where}: material {self.material!r} is not one of {', '.join(MATERIALS)}")
        for key in ("vendor", "product_id", "name"):
            if not isinstance(getattr(self, key), str):
                raise ToolLibraryError(f"{where}: {key} {getattr(self, key)!r} is not text")

    def check_angle(self, where: str) -> None:
        angle = self.angle
        if self.kind not in ANGLED:
            if angle is not None:
                raise ToolLibraryError(f"{where}: a {KIND_LABELS[self.kind]} has no tip angle (got {angle!r})")
            return
        if angle is None:
            if self.kind != "drill":
                raise ToolLibraryError(f"{where}: a {KIND_LABELS[self.kind]} needs its included angle (degrees)")
            angle = DRILL_POINT_DEG
        if not is_number(angle) or not math.isfinite(angle) or not 1 <= angle <= 179:
            raise ToolLibraryError(f"{where}: angle {angle!r} is not an included angle 1..179 degrees")
        object.__setattr__(self, "angle", float(angle))

    @property
    def radius(self) -> float:
        return self.diameter / 2

    def label(self) -> str:
        """The kind in words, with its angle or corner radius."""
        label = KIND_LABELS[self.kind]
        if self.kind in ("vbit", "engraver"):
            return f"{self.angle:g}° {label}"
        if self.kind == "bull":
            return f"{label} R{self.corner_radius:g}"
        return label

    def describe(self) -> str:
        text = f"T{self.number} {self.diameter:g} mm {self.label()}"
        return text + (f" ({self.name})" if self.name else "")

    def to_ir_tool(self) -> Tool:
        """The program's tool (:class:`~..ir.program.Tool`): an engraver is cut as the V-bit it is."""
        kind = "vbit" if self.kind == "engraver" else self.kind
        label = "engraver" if self.kind == "engraver" else ""
        try:
            return Tool(self.number, kind, self.diameter, corner_radius=self.corner_radius,
                        flute_length=self.flute_length, name=self.name, label=label,
                        tip_angle=self.tip_angle_for(kind))
        except ProgramError as error:
            raise ToolLibraryError(f"T{self.number}: not a tool a program can use: {error}") from None

    def tip_angle_for(self, kind: str) -> float:
        """The program tool's ``tip_angle``: this tool's angle where it is pointed and differs from
        its kind's (0: the kind's own, so a 90 deg V-bit or a 118 deg drill is the tool it always was)."""
        if kind not in TIP_ANGLE_DEG or self.angle is None or abs(self.angle - TIP_ANGLE_DEG[kind]) <= 1e-9:
            return 0.0
        return float(self.angle)

    def as_dict(self) -> dict:
        return {key: getattr(self, key) for key in FIELDS}

    def replace(self, **changes) -> "LibraryTool":
        return dataclasses.replace(self, **changes)


def tool_from_fields(fields: dict, where: str) -> LibraryTool:
    """A tool from a dict of its fields by name; an unknown or missing field is an error naming
    ``where`` and the field (a ball's corner radius and a drill's angle may be left out)."""
    unknown = sorted(set(fields) - set(FIELDS))
    if unknown:
        raise ToolLibraryError(f"{where}: unknown field {unknown[0]!r}; the fields are {', '.join(FIELDS)}")
    for key in ("number", "kind", "diameter"):
        if key not in fields:
            raise ToolLibraryError(f"{where}: the field {key!r} is missing")
    try:
        return LibraryTool(**fields)
    except ToolLibraryError as error:
        message, named = str(error), f"T{fields['number']}"
        if named in where:                   # "file: line 2 (T2): diameter ...", not "(T2): T2: ..."
            message = message.removeprefix(f"{named}: ")
        raise ToolLibraryError(f"{where}: refused: {message}") from None


class ToolLibrary:
    """Tools by number, sorted; immutable (every change gives a new library)."""

    def __init__(self, tools=(), wheres=None):
        wheres = list(wheres) if wheres is not None else [f"T{t.number}" for t in tools]
        seen = {}
        for tool, where in zip(tools, wheres):
            if not isinstance(tool, LibraryTool):
                raise ToolLibraryError(f"{where}: not a tool")
            if tool.number in seen:
                first, first_where = seen[tool.number]
                raise ToolLibraryError(f"tool number T{tool.number} is given twice: {first_where} "
                                       f"({first.describe()}) and {where} ({tool.describe()})")
            seen[tool.number] = (tool, where)
        self.tools = tuple(sorted((t for t, _ in seen.values()), key=lambda t: t.number))

    def __len__(self):
        return len(self.tools)

    def __iter__(self):
        return iter(self.tools)

    def __eq__(self, other):
        return isinstance(other, ToolLibrary) and self.tools == other.tools

    def numbers(self) -> tuple:
        return tuple(t.number for t in self.tools)

    def find(self, number: int) -> LibraryTool | None:
        for tool in self.tools:
            if tool.number == number:
                return tool
        return None

    def get(self, number) -> LibraryTool:
        """The tool numbered ``number`` (an int, or text such as "T3" or "3")."""
        wanted = tool_number(number)
        tool = self.find(wanted)
        if tool is None:
            have = ", ".join(f"T{n}" for n in self.numbers()) or "none"
            raise ToolLibraryError(f"no tool T{wanted} in the tool library (it has {have})")
        return tool

    def with_tool(self, tool: LibraryTool, replace: bool = False) -> "ToolLibrary":
        old = self.find(tool.number)
        if old is not None and not replace:
            raise ToolLibraryError(f"T{tool.number} is already in the library ({old.describe()}); "
                                   f"refused: {tool.describe()}")
        return ToolLibrary([t for t in self.tools if t.number != tool.number] + [tool])

    def without(self, number: int) -> "ToolLibrary":
        self.get(number)
        return ToolLibrary([t for t in self.tools if t.number != number])

    def merged(self, incoming: "ToolLibrary", replace: bool = False, source: str = "the file") -> tuple:
        """(the library with ``incoming``'s tools added, numbers added, numbers replaced).  A number
        already here is refused, naming both tools, unless ``replace``; then nothing is merged."""
        clashes = [(self.find(t.number), t) for t in incoming if self.find(t.number) is not None]
        changed = [(old, new) for old, new in clashes if old != new]
        if changed and not replace:
            lines = "; ".join(f"T{new.number}: {source} has {new.describe()}, the library has {old.describe()}"
                              for old, new in changed)
            raise ToolLibraryError(f"{len(changed)} tool number(s) already in the library: {lines}; nothing "
                                   "was imported (replace them to overwrite)")
        numbers = {t.number for t in incoming}
        merged = ToolLibrary([t for t in self.tools if t.number not in numbers] + list(incoming))
        added = tuple(t.number for t in incoming if self.find(t.number) is None)
        replaced = tuple(new.number for _, new in changed)
        return merged, added, replaced


def tool_number(value) -> int:
    """A tool number as a job file or the user gives it: 3, "3" or "T3"."""
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    if isinstance(value, str):
        text = value.strip()
        digits = text[1:] if text[:1] in ("T", "t") else text
        if digits.isdigit():
            return int(digits)
    raise ToolLibraryError(f"tool {value!r} is not a tool number (3 or \"T3\")")
