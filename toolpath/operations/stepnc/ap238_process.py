"""AP238 operations, tools, technology, machine functions and strategies -> ISO 14649 ARM
instances (see :mod:`.ap238`).  Property names are those of ISO 10303-238 clause 5."""
from __future__ import annotations

from .ap238_aim import attribute, enum_of, kind_of, measure_of, name_of, placeholder_name, text_of
from .errors import StepNcError
from .part21 import UNSET, Ref



# AP238 operation (entity, description) -> ISO 14649 operation
OPERATIONS = {
    ("PLANE_MILLING_OPERATION", "roughing"): "PLANE_ROUGH_MILLING",
    ("PLANE_MILLING_OPERATION", "finishing"): "PLANE_FINISH_MILLING",
    ("BOTTOM_AND_SIDE_MILLING_OPERATION", "roughing"): "BOTTOM_AND_SIDE_ROUGH_MILLING",
    ("BOTTOM_AND_SIDE_MILLING_OPERATION", "finishing"): "BOTTOM_AND_SIDE_FINISH_MILLING",
    ("DRILLING_OPERATION", "drilling"): "DRILLING",
    ("DRILLING_OPERATION", "center drilling"): "CENTER_DRILLING",
    ("BORING_OPERATION", "reaming"): "REAMING",
}
MILLING = ("PLANE_ROUGH_MILLING", "PLANE_FINISH_MILLING", "BOTTOM_AND_SIDE_ROUGH_MILLING",
           "BOTTOM_AND_SIDE_FINISH_MILLING")
# MACHINING_TOOL_BODY_REPRESENTATION name -> ISO 14649 tool body
TOOL_BODIES = {"endmill": "ENDMILL", "tapered endmill": "TAPERED_ENDMILL", "ball endmill": "BALL_ENDMILL",
               "bullnose endmill": "BULLNOSE_ENDMILL", "facemill": "FACEMILL", "drill": "TWIST_DRILL",
               "twist drill": "TWIST_DRILL", "tapered drill": "TAPERED_DRILL", "center drill": "CENTER_DRILL",
               "reamer": "REAMER", "tapered reamer": "TAPERED_REAMER"}
STRATEGIES = {"bidirectional": "BIDIRECTIONAL", "unidirectional": "UNIDIRECTIONAL",
              "contour parallel": "CONTOUR_PARALLEL", "contour bidirectional": "CONTOUR_BIDIRECTIONAL",
              "bidirectional contour": "BIDIRECTIONAL_CONTOUR"}
APPROACHES = {"plunge toolaxis": "PLUNGE_TOOLAXIS", "plunge ramp": "PLUNGE_RAMP", "plunge helix": "PLUNGE_HELIX"}

def _value(aim, properties: dict, name: str, kind: str = "length", item_name: str | None = None):
    """The value of property ``name`` (the first item, or the one named ``item_name`` either as the
    item or as the link to its representation); UNSET when absent or unset."""
    for link, item, _ in properties.get(name, []):
        if item_name is not None and item_name not in (name_of(item).lower(), link):
            continue
        if kind == "text":
            text = text_of(item)
            if text is not None:
                return text
            continue
        if kind == "ref":
            return Ref(item.id)
        value, unit = measure_of(item)
        if value is None:
            return UNSET
        if kind == "length":
            return value * aim.length_factor(unit)
        if kind == "rate":
            return value * aim.per_second(unit)
        return value
    return UNSET if kind != "text" else None


def operation_to_arm(aim, op) -> Ref:
    kind = op.type_names[0] if len(op.type_names) == 1 else next(
        (t for t in op.type_names if t.endswith("_OPERATION")), op.type_names[0])
    description = str(attribute(op, 1)).strip().lower()
    arm = OPERATIONS.get((kind, description))
    if arm is None:
        # an operation the ISO 14649 reader does not machine: named after its kind and description
        name = kind if kind not in ("DRILLING_OPERATION", "BORING_OPERATION", "MILLING_TYPE_OPERATION") \
            else placeholder_name(description or kind)
        return aim.put(op.id, name, [])
    properties = aim.action_properties(op)
    tools = [t for t in aim.part21.by_type("MACHINING_TOOL")
             if isinstance(attribute(t, 2), list) and Ref(op.id) in attribute(t, 2)]
    if len(tools) != 1:
        raise StepNcError(f"#{op.id} {kind_of(op)} '{attribute(op, 0)}': needs one MACHINING_TOOL whose usage lists it, "
                          f"found {len(tools)}")
    technology = aim.related(op, "MACHINING_TECHNOLOGY_RELATIONSHIP")
    if not technology:
        raise StepNcError(f"#{op.id} {kind_of(op)} '{attribute(op, 0)}': no MACHINING_TECHNOLOGY_RELATIONSHIP")
    functions = aim.related(op, "MACHINING_FUNCTIONS_RELATIONSHIP")
    common = [UNSET, UNSET, str(attribute(op, 0)), _value(aim, properties, "retract plane"), UNSET,
              tool(aim, tools[0]), milling_technology(aim, technology[0]),
              machine_functions(aim, functions[0]) if functions else UNSET,
              _value(aim, properties, "overcut length")]
    strategies = {}
    for rel in aim.referrers(op, "MACHINING_STRATEGY_RELATIONSHIP", 2):
        strategies[str(attribute(rel, 0)).lower()] = aim.get(attribute(rel, 3), "related_method", rel)
    if arm in MILLING:
        params = common + [approach(aim, strategies.get("approach")), approach(aim, strategies.get("retract")),
                           strategy(aim, strategies.get("machining")),
                           _value(aim, properties, "axial cutting depth")]
        if arm.startswith("PLANE_"):
            params += [_value(aim, properties, "allowance bottom")]
        else:
            params += [_value(aim, properties, "radial cutting depth"), _value(aim, properties, "allowance side"),
                       _value(aim, properties, "allowance bottom")]
        return aim.put(op.id, arm, params)
    params = common + [_value(aim, properties, "cutting depth"), _value(aim, properties, "previous diameter"),
                       _value(aim, properties, "dwell time bottom", "number"),
                       _value(aim, properties, "feedrate on retract", "number"),
                       drilling_strategy(aim, strategies.get("machining"))]
    if arm == "REAMING":
        stop = _value(aim, properties, "spindle stop at bottom", "text")
        params += [stop in ("spindle stop", "spindle stop at bottom", "true", "stop"), UNSET, UNSET]
    return aim.put(op.id, arm, params)


def tool(aim, machining_tool) -> Ref:
    if machining_tool.id in aim.done:
        return Ref(machining_tool.id)
    bodies = [(link, item, rep) for link, item, rep in aim.resource_properties(machining_tool).get("tool body", [])]
    if not bodies:
        raise StepNcError(f"#{machining_tool.id} MACHINING_TOOL '{attribute(machining_tool, 0)}': no 'tool body' "
                          "RESOURCE_PROPERTY with a MACHINING_TOOL_BODY_REPRESENTATION")
    rep = bodies[0][2]
    items = {name_of(item).lower(): item for _, item, _ in bodies}
    body_name = str(attribute(rep, 0)).strip().lower() or str(attribute(machining_tool, 1)).strip().lower()

    def length(name):
        value, unit = measure_of(items[name]) if name in items else (None, None)
        return UNSET if value is None else value * aim.length_factor(unit)

    def number(name):
        value = measure_of(items[name])[0] if name in items else None
        return UNSET if value is None else value

    diameter = length("effective cutting diameter")
    if diameter is UNSET:
        raise StepNcError(f"#{rep.id} MACHINING_TOOL_BODY_REPRESENTATION '{body_name}': no 'effective cutting "
                          "diameter' item")
    point = number("point angle")
    top = UNSET if point is UNSET else (180.0 - point) / 2.0     # ISO 14649's tool_top_angle (ex1: 31 = (180 - 118) / 2)
    edge = length("edge radius")
    if edge is UNSET:
        edge = length("corner radius")
    dimension = aim.new("MILLING_TOOL_DIMENSION", [diameter, top, UNSET, length("maximum depth of cut"), edge,
                                                  UNSET, UNSET])
    teeth = number("number of effective teeth")
    body_type = TOOL_BODIES.get(body_name, placeholder_name(body_name))
    body = aim.put(rep.id, body_type, [dimension, UNSET if teeth is UNSET else int(round(teeth)), UNSET, UNSET,
                                       UNSET, number("taper angle")])
    return aim.put(machining_tool.id, "MILLING_CUTTING_TOOL", [str(attribute(machining_tool, 0)), body, [],
                                                                length("overall assembly length"), UNSET, UNSET])


def milling_technology(aim, technology) -> Ref:
    if technology.id in aim.done:
        return Ref(technology.id)
    p = aim.action_properties(technology)
    reference = _value(aim, p, "feedrate reference", "text")
    return aim.put(technology.id, "MILLING_TECHNOLOGY", [
        _value(aim, p, "feedrate", "rate", "feed speed"), enum_of(reference),
        _value(aim, p, "spindle", "rate", "surface speed"), _value(aim, p, "spindle", "rate", "rotational speed"),
        _value(aim, p, "feedrate", "length", "feed per tooth"), UNSET, UNSET, UNSET, UNSET])


def machine_functions(aim, functions) -> Ref:
    if functions.id in aim.done:
        return Ref(functions.id)
    coolant = _value(aim, aim.action_properties(functions), "coolant", "text")
    return aim.put(functions.id, "MILLING_MACHINE_FUNCTIONS", [coolant == "coolant on", UNSET, UNSET, False, UNSET,
                                                               [], False, UNSET, UNSET, []])


def strategy(aim, method):
    if method is None:
        return UNSET
    if method.id in aim.done:
        return Ref(method.id)
    description = str(attribute(method, 1)).strip().lower()
    arm = STRATEGIES.get(description)
    if arm is None:
        return aim.put(method.id, placeholder_name(description), [])
    p = aim.action_properties(method)
    overlap = _value(aim, p, "overlap ratio", "number")
    passes = _value(aim, p, "multiple passes", "text")
    multiple = UNSET if passes is None else passes == "multiple passes allowed"
    feed = _value(aim, p, "feed direction", "ref")
    if arm == "BIDIRECTIONAL":
        params = [overlap, multiple, feed, enum_of(_value(aim, p, "stepover direction", "text")),
                  enum_of(_value(aim, p, "stroke connection strategy", "text"))]
    elif arm == "UNIDIRECTIONAL":
        params = [overlap, multiple, feed, enum_of(_value(aim, p, "cutmode", "text"))]
    elif arm == "CONTOUR_PARALLEL":
        params = [overlap, multiple, enum_of(_value(aim, p, "rotation direction", "text")),
                  enum_of(_value(aim, p, "cutmode", "text"))]
    else:    # CONTOUR_BIDIRECTIONAL / BIDIRECTIONAL_CONTOUR(overlap, multiple, feed_direction, stepover_direction, rotation_direction, spiral_cutmode)
        params = [overlap, multiple, feed, enum_of(_value(aim, p, "stepover direction", "text")),
                  enum_of(_value(aim, p, "rotation direction", "text")),
                  enum_of(_value(aim, p, "spiral cutmode", "text"))]
    return aim.put(method.id, arm, params)


def approach(aim, method):
    if method is None:
        return UNSET
    if method.id in aim.done:
        return Ref(method.id)
    description = str(attribute(method, 1)).strip().lower()
    arm = APPROACHES.get(description)
    if arm is None:
        return aim.put(method.id, placeholder_name(description), [])
    p = aim.action_properties(method)
    orientation = _value(aim, p, "tool orientation", "ref")
    if arm == "PLUNGE_TOOLAXIS":
        return aim.put(method.id, arm, [orientation])
    angle = _value(aim, p, "plunge angle", "number")
    if arm == "PLUNGE_RAMP":
        return aim.put(method.id, arm, [orientation, angle])
    return aim.put(method.id, arm, [orientation, _value(aim, p, "plunge radius"), angle])


def drilling_strategy(aim, method):
    if method is None:
        return UNSET
    if method.id in aim.done:
        return Ref(method.id)
    if "DRILLING_TYPE_STRATEGY" not in method.type_names:
        return aim.put(method.id, kind_of(method), [])
    p = aim.action_properties(method)
    return aim.put(method.id, "DRILLING_TYPE_STRATEGY", [
        _value(aim, p, "reduced cut at start", "number"), _value(aim, p, "reduced feedrate at start", "number"),
        _value(aim, p, "depth of start"), _value(aim, p, "reduced cut at end", "number"),
        _value(aim, p, "reduced feedrate at end", "number"), _value(aim, p, "depth of end")])


__all__ = ["operation_to_arm", "tool", "milling_technology", "machine_functions", "strategy", "approach",
           "drilling_strategy"]
