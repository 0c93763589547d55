"""FreeCAD's tool libraries (Path / CAM workbench): a library file ``.fctl`` binding tool numbers to
tool bit files ``.fctb``, as FreeCAD ships them (``Tools/Library/Default.fctl``, ``Tools/Bit/*.fctb``)::

    Default.fctl   {"version": 1, "tools": [{"nr": 1, "path": "5mm_Endmill.fctb"}, ...]}
    5mm_Endmill.fctb
                   {"version": 2, "name": "5mm Endmill", "shape": "endmill.fcstd",
                    "parameter": {"Diameter": "5.0000 mm", "CuttingEdgeHeight": "30.0000 mm", ...},
                    "attribute": {"Flutes": 2, "Material": "HSS"}}

A bit's path is found beside the library, else in the ``Bit`` folder beside the library's folder
(FreeCAD's layout), else as an absolute path.  Shapes: ``endmill`` (flat), ``ballend``,
``bullnose`` (corner radius = Diameter / 2 - FlatRadius), ``v-bit`` (CuttingEdgeAngle: the
included angle), ``drill`` (TipAngle); other shapes (chamfer, probe, tap, slitting saw...) are left
out with a note.  Quantities are text with their unit ("6.0000 mm", "0.25 in", "60.0000 °").
What FreeCAD has no parameter for (stick-out, holder diameter, vendor, product id, the engraver
kind) rides in the attribute ``Kezuri`` (JSON), so a library Kezuri wrote reads back whole.
"""
from __future__ import annotations

import json
import math
import os
import re

from .textfile import read_text_file
from .library import DRILL_POINT_DEG, ToolLibrary, ToolLibraryError, tool_from_fields

SHAPES = {"endmill": "flat", "ballend": "ball", "bullnose": "bull", "v-bit": "vbit", "drill": "drill"}
SHAPE_OF = {"flat": "endmill", "ball": "ballend", "bull": "bullnose", "vbit": "v-bit", "engraver": "v-bit",
            "drill": "drill"}
LENGTH_UNITS = {"mm": 1.0, "in": 25.4, "\"": 25.4, "cm": 10.0}
ANGLE_UNITS = {"°": 1.0, "deg": 1.0}
MATERIALS = {"HSS": "hss", "Carbide": "carbide"}
MATERIAL_OF = {"hss": "HSS", "carbide": "Carbide"}
EXTRA = "Kezuri"
EXTRA_FIELDS = ("kind", "stick_out", "holder_diameter", "vendor", "product_id")
QUANTITY = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S*)\s*\Z")


def quantity(value, units: dict, where: str, key: str) -> float:
    """A FreeCAD quantity ("6.0000 mm") in mm or degrees."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        number, unit = float(value), next(iter(units))
    else:
        match = QUANTITY.match(value) if isinstance(value, str) else None
        if match is None:
            raise ToolLibraryError(f"{where}: parameter {key} = {value!r} is not a quantity (\"6.0 mm\")")
        number, unit = float(match.group(1)), match.group(2) or next(iter(units))
    if unit not in units:
        raise ToolLibraryError(f"{where}: parameter {key} = {value!r}: unit {unit!r} is not one of "
                               f"{', '.join(units)}")
    if not math.isfinite(number):
        raise ToolLibraryError(f"{where}: parameter {key} = {value!r} is not a finite number")
    return number * units[unit]


def load_json(path: str, what: str):
    try:
        return json.loads(read_text_file(path), parse_constant=lambda name: float("nan"))
    except json.JSONDecodeError as error:
        raise ToolLibraryError(f"{path}: not a FreeCAD {what}: not JSON ({error.msg} at line {error.lineno}, "
                               f"column {error.colno})") from None


def bit_path(library_path: str, given: str, where: str) -> str:
    folder = os.path.dirname(os.path.abspath(library_path))
    tried = [given] if os.path.isabs(given) else [os.path.join(folder, given),
                                                   os.path.join(os.path.dirname(folder), "Bit", given)]
    for path in tried:
        if os.path.isfile(path):
            return path
    raise ToolLibraryError(f"{where}: the bit file {given!r} is not there (looked for {' and '.join(tried)})")


def read_bit(path: str, number, where: str):
    """The tool of one bit file, or None (with the reason) for a shape Kezuri does not cut with."""
    bit = load_json(path, "tool bit")
    where = f"{where} (T{number}, {os.path.basename(path)})"
    if not isinstance(bit, dict) or not isinstance(bit.get("parameter", {}), dict) or \
            not isinstance(bit.get("attribute", {}), dict):
        raise ToolLibraryError(f"{where}: not a FreeCAD tool bit (parameter and attribute must be objects)")
    shape = os.path.splitext(os.path.basename(str(bit.get("shape", ""))))[0].lower()
    if shape not in SHAPES:
        return None, f"{where}: a {bit.get('shape')!r} bit is not a tool Kezuri cuts with: left out"
    parameters, attributes = bit.get("parameter", {}), bit.get("attribute", {})
    if "Diameter" not in parameters:
        raise ToolLibraryError(f"{where}: parameter Diameter is missing")
    fields = {"number": number, "kind": SHAPES[shape], "name": bit.get("name", ""),
              "diameter": quantity(parameters["Diameter"], LENGTH_UNITS, where, "Diameter")}
    if "CuttingEdgeHeight" in parameters:
        fields["flute_length"] = quantity(parameters["CuttingEdgeHeight"], LENGTH_UNITS, where, "CuttingEdgeHeight")
    if shape == "bullnose":
        if "FlatRadius" not in parameters:
            raise ToolLibraryError(f"{where}: parameter FlatRadius is missing (a bull nose's flat)")
        flat = quantity(parameters["FlatRadius"], LENGTH_UNITS, where, "FlatRadius")
        fields["corner_radius"] = round(fields["diameter"] / 2 - flat, 9)
    note = None
    if shape == "v-bit":
        if "CuttingEdgeAngle" not in parameters:
            raise ToolLibraryError(f"{where}: parameter CuttingEdgeAngle is missing (a V-bit's included angle)")
        fields["angle"] = quantity(parameters["CuttingEdgeAngle"], ANGLE_UNITS, where, "CuttingEdgeAngle")
        tip = quantity(parameters.get("FlatRadius", 0.0), LENGTH_UNITS, where, "FlatRadius")
        if tip > 0:
            note = (f"{where}: its flat tip (FlatRadius {tip:g} mm) is not kept: Kezuri's V-bit comes to a "
                    "point")
    if shape == "drill":
        fields["angle"] = quantity(parameters["TipAngle"], ANGLE_UNITS, where, "TipAngle") \
            if "TipAngle" in parameters else DRILL_POINT_DEG
    if "Flutes" in attributes:
        fields["flutes"] = attributes["Flutes"]
    if "Material" in attributes:
        if attributes["Material"] not in MATERIALS:
            raise ToolLibraryError(f"{where}: attribute Material = {attributes['Material']!r} is not one of "
                                   f"{', '.join(MATERIALS)}")
        fields["material"] = MATERIALS[attributes["Material"]]
    if EXTRA in attributes:
        try:
            extra = json.loads(attributes[EXTRA])
        except (TypeError, json.JSONDecodeError):
            raise ToolLibraryError(f"{where}: attribute {EXTRA} is not Kezuri's JSON") from None
        unknown = sorted(set(extra) - set(EXTRA_FIELDS)) if isinstance(extra, dict) else ["(not a table)"]
        if unknown:
            raise ToolLibraryError(f"{where}: attribute {EXTRA} has an unknown field {unknown[0]!r}")
        fields.update(extra)
    return tool_from_fields(fields, where), note


def read_path(path: str) -> tuple:
    """(ToolLibrary, notes) from a FreeCAD library file and its bit files."""
    data = load_json(path, "tool library")
    if not isinstance(data, dict) or not isinstance(data.get("tools"), list):
        raise ToolLibraryError(f"{path}: not a FreeCAD tool library: no \"tools\" list")
    tools, wheres, notes = [], [], []
    for index, entry in enumerate(data["tools"], 1):
        where = f"{path}: tool {index}"
        if not isinstance(entry, dict) or not isinstance(entry.get("path"), str) or "nr" not in entry:
            raise ToolLibraryError(f"{where}: needs \"nr\" (the tool number) and \"path\" (its bit file)")
        tool, note = read_bit(bit_path(path, entry["path"], where), entry["nr"], where)
        if note is not None:
            notes.append(note)
        if tool is None:
            continue
        tools.append(tool)
        wheres.append(f"{where} (T{tool.number})")
    return ToolLibrary(tools, wheres), notes


def bit_of(tool) -> dict:
    parameters = {"Diameter": f"{tool.diameter!r} mm", "CuttingEdgeHeight": f"{tool.flute_length!r} mm"}
    if tool.kind == "bull":
        parameters["FlatRadius"] = f"{round(tool.radius - tool.corner_radius, 9)!r} mm"
    if tool.kind in ("vbit", "engraver"):
        parameters["CuttingEdgeAngle"] = f"{tool.angle!r} °"
    if tool.kind == "drill":
        parameters["TipAngle"] = f"{tool.angle!r} °"
    extra = {key: getattr(tool, key) for key in EXTRA_FIELDS
             if key != "kind" and getattr(tool, key) not in (None, "")}
    if tool.kind == "engraver":
        extra["kind"] = "engraver"
    attributes = {"Flutes": tool.flutes, "Material": MATERIAL_OF[tool.material]}
    if extra:
        attributes[EXTRA] = json.dumps(extra, ensure_ascii=False, sort_keys=True)
    return {"version": 2, "name": tool.name, "shape": f"{SHAPE_OF[tool.kind]}.fcstd", "parameter": parameters,
            "attribute": attributes}


def files_of(path: str, library: ToolLibrary) -> list:
    """[(file, text)] of the library at ``path`` (a .fctl) and its bit files: in the ``Bit`` folder
    beside a ``Library`` folder (FreeCAD's layout), else beside the library file."""
    folder = os.path.dirname(os.path.abspath(path))
    bits = os.path.join(os.path.dirname(folder), "Bit") if os.path.basename(folder) == "Library" else folder
    stem = os.path.splitext(os.path.basename(path))[0]
    files, entries = [], []
    for tool in library:
        name = f"{stem}-T{tool.number}.fctb"
        files.append((os.path.join(bits, name), json.dumps(bit_of(tool), indent=2, ensure_ascii=False) + "\n"))
        entries.append({"nr": tool.number, "path": name})
    files.append((path, json.dumps({"tools": entries, "version": 1}, indent=2) + "\n"))
    return files
