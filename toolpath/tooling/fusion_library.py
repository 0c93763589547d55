"""Fusion 360's tool library (the JSON its Tool Library dialog exports: ``{"data": [tool, ...]}``).

Each tool is an object with ``type`` ("flat end mill", "ball end mill", "bull nose end mill",
"chamfer mill", "drill", "spot drill", ...), ``unit`` ("millimeters" or "inches"), ``BMC`` (body
material: "carbide", "hss"), ``description``, ``vendor``, ``product-id``, ``post-process.number``
(the T number) and ``geometry``, whose keys are the ISO 13399 property symbols:

    DC   cutting diameter           NOF  number of flutes       LCF  length of cut (flutes)
    LB   body length below holder   OAL  overall length         RE   corner radius
    SIG  drill point angle          TA   taper angle: from the axis, half the included angle

An entry of a type Kezuri does not cut with (a tap, a thread mill, a probe, a face mill...) is left
out, and a note names it; everything else Fusion keeps (guid, presets, holder shape) is not read.
A wrong unit, a missing number or diameter, a NaN is an error naming the file, the entry and the key.
The export writes what the library knows in the same keys (OAL = LB, the length Kezuri knows) and
the kind in ``post-process.comment`` where Fusion has no type for it (an engraver).
"""
from __future__ import annotations

import json
import math
import uuid

from .library import DRILL_POINT_DEG, ToolLibrary, ToolLibraryError, is_number, tool_from_fields

TYPES = {"flat end mill": "flat", "ball end mill": "ball", "bull nose end mill": "bull", "chamfer mill": "vbit",
         "drill": "drill", "spot drill": "drill"}
TYPE_OF = {"flat": "flat end mill", "ball": "ball end mill", "bull": "bull nose end mill", "vbit": "chamfer mill",
           "engraver": "chamfer mill", "drill": "drill"}
UNITS = {"millimeters": 1.0, "inches": 25.4}
MATERIALS = {"carbide": "carbide", "hss": "hss"}
KIND_MARK = "kezuri kind="
NAMESPACE = uuid.UUID("6b657a75-7269-4361-8d00-746f6f6c7321")     # Kezuri's own namespace for tool guids


def number_at(mapping: dict, key: str, where: str, required: bool = True):
    value = mapping.get(key)
    if value is None:
        if required:
            raise ToolLibraryError(f"{where}: {key} is missing")
        return None
    if not is_number(value) or not math.isfinite(value):
        raise ToolLibraryError(f"{where}: {key} = {value!r} is not a number")
    return value


def text_at(entry: dict, key: str, where: str) -> str:
    value = entry.get(key, "")
    if not isinstance(value, str):
        raise ToolLibraryError(f"{where}: {key} = {value!r} is not text")
    return value


def read_entry(entry: dict, where: str) -> dict | None:
    """The library fields of one Fusion tool, or None for a type Kezuri does not cut with."""
    post = entry.get("post-process", {})
    geometry = entry.get("geometry")
    if not isinstance(post, dict) or not isinstance(geometry, dict):
        raise ToolLibraryError(f"{where}: post-process and geometry must be objects")
    number = post.get("number")
    if isinstance(number, float) and number.is_integer():
        number = int(number)
    if number is None:
        raise ToolLibraryError(f"{where}: post-process.number (the tool number) is missing")
    where = f"{where} (T{number})"
    kind_type = entry.get("type")
    comment = post.get("comment", "")
    if kind_type not in TYPES:
        return None
    kind = TYPES[kind_type]
    if isinstance(comment, str) and comment.startswith(KIND_MARK):
        kind = comment[len(KIND_MARK):].split()[0] if comment[len(KIND_MARK):].split() else kind
    unit = entry.get("unit")
    if unit not in UNITS:
        raise ToolLibraryError(f"{where}: unit = {unit!r} is not one of {', '.join(UNITS)}")
    scale = UNITS[unit]
    fields = {"number": number, "kind": kind,
              "diameter": number_at(geometry, "DC", f"{where}: geometry") * scale}
    flutes = number_at(geometry, "NOF", f"{where}: geometry", required=False)
    if flutes is not None:
        if flutes != int(flutes):
            raise ToolLibraryError(f"{where}: geometry NOF = {flutes!r} is not a whole number of flutes")
        fields["flutes"] = int(flutes)
    for key, name in (("LCF", "flute_length"), ("LB", "stick_out")):
        value = number_at(geometry, key, f"{where}: geometry", required=False)
        if value is not None:
            fields[name] = value * scale
    corner = number_at(geometry, "RE", f"{where}: geometry", required=False)
    if corner is not None and kind in ("ball", "bull"):
        fields["corner_radius"] = corner * scale
    if kind in ("vbit", "engraver"):
        taper = number_at(geometry, "TA", f"{where}: geometry")
        fields["angle"] = 2.0 * taper
    elif kind == "drill":
        point = number_at(geometry, "SIG", f"{where}: geometry", required=False)
        fields["angle"] = DRILL_POINT_DEG if point is None else point
    holder = entry.get("holder")
    if isinstance(holder, dict) and isinstance(holder.get("segments"), list) and holder["segments"]:
        first = holder["segments"][0]
        if isinstance(first, dict):
            value = number_at(first, "lower-diameter", f"{where}: holder segment 1", required=False)
            if value is not None:
                fields["holder_diameter"] = value * scale
    material = entry.get("BMC")
    if material is not None:
        if material not in MATERIALS:
            raise ToolLibraryError(f"{where}: BMC = {material!r} is not one of {', '.join(MATERIALS)}")
        fields["material"] = MATERIALS[material]
    fields["name"] = text_at(entry, "description", where)
    fields["vendor"] = text_at(entry, "vendor", where)
    fields["product_id"] = text_at(entry, "product-id", where)
    return tool_from_fields(fields, where)


def read_text(text: str, path: str) -> tuple:
    """(ToolLibrary, notes) from a Fusion 360 tool library's JSON text."""
    try:
        data = json.loads(text, parse_constant=lambda name: float("nan"))
    except json.JSONDecodeError as error:
        raise ToolLibraryError(f"{path}: not a Fusion 360 tool library: not JSON ({error.msg} at line "
                               f"{error.lineno}, column {error.colno})") from None
    if not isinstance(data, dict) or not isinstance(data.get("data"), list):
        raise ToolLibraryError(f"{path}: not a Fusion 360 tool library: no \"data\" list of tools")
    tools, wheres, notes = [], [], []
    for index, entry in enumerate(data["data"], 1):
        where = f"{path}: entry {index}"
        if not isinstance(entry, dict):
            raise ToolLibraryError(f"{where}: not an object")
        tool = read_entry(entry, where)
        if tool is None:
            notes.append(f"{where}: a {entry.get('type')!r} is not a tool Kezuri cuts with: left out")
            continue
        tools.append(tool)
        wheres.append(f"{where} (T{tool.number})")
    return ToolLibrary(tools, wheres), notes


def write_entry(tool) -> dict:
    geometry = {"DC": tool.diameter, "NOF": tool.flutes, "LCF": tool.flute_length}
    if tool.stick_out is not None:
        geometry["LB"] = tool.stick_out
    geometry["OAL"] = tool.stick_out if tool.stick_out is not None else tool.flute_length
    if tool.kind in ("ball", "bull"):
        geometry["RE"] = tool.corner_radius
    if tool.kind in ("vbit", "engraver"):
        geometry["TA"] = tool.angle / 2
    if tool.kind == "drill":
        geometry["SIG"] = tool.angle
    post = {"number": tool.number, "diameter-offset": tool.number, "length-offset": tool.number, "turret": 0,
            "live": True, "break-control": False, "manual-tool-change": False,
            "comment": f"{KIND_MARK}{tool.kind}" if tool.kind == "engraver" else ""}
    entry = {"guid": str(uuid.uuid5(NAMESPACE, f"T{tool.number} {tool.kind} {tool.diameter!r} {tool.name}")),
             "type": TYPE_OF[tool.kind], "unit": "millimeters", "BMC": tool.material, "GRADE": "Mill Generic",
             "description": tool.name, "vendor": tool.vendor, "product-id": tool.product_id,
             "geometry": geometry, "post-process": post}
    if tool.holder_diameter is not None:
        entry["holder"] = {"type": "holder", "unit": "millimeters", "description": "", "segments": [
            {"height": 0.0, "lower-diameter": tool.holder_diameter, "upper-diameter": tool.holder_diameter}]}
    return entry


def write_text(library: ToolLibrary) -> str:
    return json.dumps({"data": [write_entry(tool) for tool in library]}, indent=2,
                      ensure_ascii=False) + "\n"
