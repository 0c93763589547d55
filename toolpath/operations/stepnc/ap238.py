"""The AP238 integrated form (ISO 10303-238 AIM, schema AP238_STEP_NC_MIM or
MODEL_BASED_INTEGRATED_MANUFACTURING_SCHEMA) read as ISO 14649 ARM instances.

An AP238 file says what an ISO 14649 file says with generic STEP resources: executables and
operations are ``action_method`` subtypes (MACHINING_WORKPLAN, MACHINING_WORKINGSTEP,
BOTTOM_AND_SIDE_MILLING_OPERATION ...) tied together by relationship entities
(MACHINING_PROCESS_SEQUENCE_RELATIONSHIP with its sequence_position, MACHINING_OPERATION_RELATIONSHIP,
MACHINING_TECHNOLOGY_RELATIONSHIP, MACHINING_STRATEGY_RELATIONSHIP named 'machining', 'approach' or
'retract' ...); their attributes are ACTION_PROPERTYs named as in clause 5 of the standard ('retract
plane', 'axial cutting depth', 'feedrate', 'security plane' ...) whose representation holds the value;
features are SHAPE_ASPECT complex instances (ROUND_HOLE, POCKET, FLAT_FACE, SLOT) whose placement and
depth plane hang off their PRODUCT_DEFINITION_SHAPE and whose path and profile are feature components
reached through SHAPE_ASPECTs described '... occurrence'; the project, workpieces and setup are
product data (MACHINING_PROJECT, PRODUCT_DEFINITION, MACHINING_SETUP).

:func:`to_arm` walks those paths and writes the ARM instances the ISO 14649 reader
(:func:`reader.read_project`) knows, so both renditions of a part give the same model.  The main
objects keep their AP238 instance numbers (a workingstep #10 stays #10, a feature, operation or
tool keeps its number), so every warning names an instance of the file; helper instances get
numbers above the file's largest.  The geometry (CARTESIAN_POINT, DIRECTION, AXIS2_PLACEMENT_3D,
PLANE, POLYLINE, CIRCLE, TRIMMED_CURVE, COMPOSITE_CURVE) is the same entities in both forms and is
used as it is.  Something the ARM reader does not machine is written as an instance of its own
name (a COUNTERBORE_HOLE, a 'contour spiral' strategy as CONTOUR_SPIRAL), so the workingstep is
skipped with the reason, as in an ISO 14649 file.

Units: lengths follow the representation item's unit (millimetre, metre, inch); feeds are written
in m/s and spindle speeds in rev/s as ISO 14649 has them (a unit per minute is converted).
"""
from __future__ import annotations

import math
from collections import defaultdict

from .model import StepNcError
from .part21 import UNSET, ComplexInstance, Enum, Instance, Part21File, Ref, Typed, iter_refs

AP238_SCHEMAS = ("AP238_STEP_NC_MIM", "MODEL_BASED_INTEGRATED_MANUFACTURING_SCHEMA", "INTEGRATED_CNC_SCHEMA",
                 "AP238_STEP_NC_MIM_LF")

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
HOLE_BOTTOMS = {"through": "THROUGH_BOTTOM_CONDITION", "flat": "FLAT_HOLE_BOTTOM",
                "conical": "CONICAL_HOLE_BOTTOM", "spherical": "SPHERICAL_HOLE_BOTTOM",
                "flat with radius": "FLAT_WITH_RADIUS_HOLE_BOTTOM"}
POCKET_BOTTOMS = {"planar": "PLANAR_POCKET_BOTTOM_CONDITION", "through": "THROUGH_POCKET_BOTTOM_CONDITION"}
SLOT_ENDS = {"open": "OPEN_SLOT_END_TYPE", "radiused": "RADIUSED_SLOT_END_TYPE", "flat": "FLAT_SLOT_END_TYPE",
             "woodruff": "WOODRUFF_SLOT_END_TYPE", "loop": "LOOP_SLOT_END_TYPE"}
WORDS = {"left": "LEFT", "right": "RIGHT", "clockwise": "CW", "counterclockwise": "CCW", "climb": "CLIMB",
         "conventional": "CONVENTIONAL", "tool center point": "TCP", "contact point": "CCP",
         "cutter contact point": "CCP", "straight line": "STRAIGHTLINE", "lift shift plunge": "LIFT_SHIFT_PLUNGE",
         "degouge": "DEGOUGE", "loop back": "LOOP_BACK"}
GEOMETRY = ("AXIS2_PLACEMENT_3D", "CARTESIAN_POINT", "DIRECTION", "PLANE", "POLYLINE", "CIRCLE", "TRIMMED_CURVE",
            "COMPOSITE_CURVE", "LINE", "B_SPLINE_CURVE_WITH_KNOTS")
# length units: SI prefix -> power of ten; conversion-based units known by name -> mm
SI_PREFIX_EXPONENT = {"EXA": 18, "PETA": 15, "TERA": 12, "GIGA": 9, "MEGA": 6, "KILO": 3, "HECTO": 2, "DECA": 1,
                      "DECI": -1, "CENTI": -2, "MILLI": -3, "MICRO": -6, "NANO": -9, "PICO": -12, "FEMTO": -15,
                      "ATTO": -18}     # ISO 10303-41 si_prefix
NAMED_LENGTH_MM = {"inch": 25.4, "foot": 304.8, "millimetre": 1.0, "metre": 1000.0}


def is_ap238(part21: Part21File) -> bool:
    return bool(part21.by_type("MACHINING_PROJECT")) or any(s.upper() in AP238_SCHEMAS for s in part21.schema)


def _params(inst, part: str | None = None) -> list:
    if isinstance(inst, ComplexInstance):
        return inst.params_of(part or inst.type_names[-1])
    return inst.params


def _at(inst, index: int):
    """Attribute ``index`` of an instance (of its last part for a complex one), named when missing."""
    params = _params(inst)
    if index >= len(params):
        raise StepNcError(f"#{inst.id} {_kind(inst)}: attribute number {index + 1} is missing; the instance has "
                          f"{len(params)} attributes")
    return params[index]


def _item_name(inst) -> str:
    if isinstance(inst, ComplexInstance):
        for part in ("REPRESENTATION_ITEM", "SHAPE_ASPECT"):
            if part in inst.type_names:
                value = inst.params_of(part)[0]
                return value if isinstance(value, str) else ""
        return ""
    value = inst.params[0] if inst.params else ""
    return value if isinstance(value, str) else ""


class _Aim:
    """The AP238 instances with the inverse references the mapping paths walk backwards."""

    def __init__(self, part21: Part21File):
        self.part21 = part21
        self.users = defaultdict(list)
        for inst in part21.instances.values():
            for ref in set(iter_refs(inst)):
                self.users[ref.id].append(inst)
        self.out = dict(part21.instances)
        self.next_id = max(part21.instances, default=0) + 1
        self.done: set = set()
        self.current = 0        # the instance being translated (named when the data is malformed)

    # ---- navigation

    def get(self, value, what: str, inst):
        if not isinstance(value, Ref) or value.id not in self.part21.instances:
            raise StepNcError(f"#{inst.id} {_kind(inst)}: {what} must refer to an instance, found {value!r}")
        return self.part21.instances[value.id]

    def referrers(self, inst, type_name: str, index: int) -> list:
        """The simple instances of ``type_name`` whose attribute ``index`` refers to ``inst``."""
        found = []
        for user in self.users.get(inst.id, ()):
            if isinstance(user, Instance) and user.type_name == type_name and len(user.params) > index:
                value = user.params[index]
                if value == Ref(inst.id) or (isinstance(value, list) and Ref(inst.id) in value):
                    found.append(user)
        return sorted(found, key=lambda i: i.id)

    def related(self, inst, relationship: str, name: str | None = None) -> list:
        """The related_method of each ``relationship`` (action_method_relationship) from ``inst``."""
        found = []
        for rel in self.referrers(inst, relationship, 2):
            if name is None or str(_at(rel, 0)).lower() == name:
                found.append(self.get(_at(rel, 3), "related_method", rel))
        return found

    def new(self, type_name: str, params: list) -> Ref:
        ident = self.next_id
        self.next_id += 1
        self.out[ident] = Instance(ident, type_name, params)
        return Ref(ident)

    def put(self, ident: int, type_name: str, params: list) -> Ref:
        self.out[ident] = Instance(ident, type_name, params)
        self.done.add(ident)
        return Ref(ident)

    # ---- properties (action_property / resource_property / property_definition -> representation items)

    def _items(self, owners: list, link: str, index: int) -> dict:
        items = {}
        for owner in owners:
            for holder in self.referrers(owner, link, index):
                rep = self.get(holder.params[-1] if link != "SHAPE_DEFINITION_REPRESENTATION" else _at(holder, 1),
                               "representation", holder)
                rep_name = str(_at(holder, 0)) if link.startswith(("ACTION", "RESOURCE")) else ""
                for ref in _at(rep, 1) if len(_params(rep)) > 1 and isinstance(_at(rep, 1), list) else []:
                    item = self.get(ref, "items", rep)
                    items.setdefault(str(_at(owner, 0)).lower(), []).append((rep_name.lower(), item, rep))
        return items

    def action_properties(self, method) -> dict:
        """{property name: [(representation link name, item, representation)]} of an action_method."""
        return self._items(self.referrers(method, "ACTION_PROPERTY", 2), "ACTION_PROPERTY_REPRESENTATION", 2)

    def resource_properties(self, resource) -> dict:
        return self._items(self.referrers(resource, "RESOURCE_PROPERTY", 2), "RESOURCE_PROPERTY_REPRESENTATION", 2)

    def shape_items(self, definition) -> list:
        """(representation, item) of every representation of a PRODUCT_DEFINITION_SHAPE or
        PROPERTY_DEFINITION of ``definition``."""
        found = []
        for kind in ("PRODUCT_DEFINITION_SHAPE", "PROPERTY_DEFINITION"):
            for pd in self.referrers(definition, kind, 2):
                for link in ("SHAPE_DEFINITION_REPRESENTATION", "PROPERTY_DEFINITION_REPRESENTATION"):
                    for holder in self.referrers(pd, link, 0):
                        rep = self.get(_at(holder, 1), "used_representation", holder)
                        for ref in _at(rep, 1) if isinstance(_at(rep, 1), list) else []:
                            found.append((rep, self.get(ref, "items", rep), pd))
        return found

    # ---- values

    def length(self, item) -> float | None:
        value, unit = _measure(item)
        if value is None:
            return None
        return value * self.length_factor(unit)

    def length_factor(self, unit, seen: tuple = ()) -> float:
        """Millimetres per unit of a length measure's unit: an SI_UNIT of metres with any SI prefix,
        or a CONVERSION_BASED_UNIT by its conversion factor (or, without one, its name: inch,
        foot, millimetre, metre).  A length unit it cannot convert is refused naming the instance:
        before, a yard, a nanometre or a prefix it did not know was read as a millimetre."""
        if not isinstance(unit, Ref) or unit.id not in self.part21.instances:
            return 1.0
        target = self.part21.instances[unit.id]
        if "SI_UNIT" in target.type_names:
            prefix, name = _params(target, "SI_UNIT")[:2]
            name = name.name if isinstance(name, Enum) else str(name)
            if name != "METRE":
                if "LENGTH_UNIT" in target.type_names:
                    raise StepNcError(f"#{target.id} SI_UNIT: a length unit in {name}, not in metres")
                return 1.0
            if not isinstance(prefix, Enum):
                return 1000.0
            if prefix.name not in SI_PREFIX_EXPONENT:
                raise StepNcError(f"#{target.id} SI_UNIT: {prefix.name} is not an SI prefix")
            return 1000.0 * 10.0 ** SI_PREFIX_EXPONENT[prefix.name]
        if "CONVERSION_BASED_UNIT" in target.type_names:
            name, factor = (_params(target, "CONVERSION_BASED_UNIT") + [UNSET, UNSET])[:2]
            if target.id in seen:
                raise StepNcError(f"#{target.id} CONVERSION_BASED_UNIT '{name}': its conversion factor is given in "
                                  f"itself")
            measure = self.part21.instances.get(getattr(factor, "id", None))
            value = _measure(measure) if measure is not None else (None, None)
            if value[0] is not None:
                mm = value[0] * self.length_factor(value[1], seen + (target.id,))
                if not (math.isfinite(mm) and mm > 0):
                    raise StepNcError(f"#{target.id} CONVERSION_BASED_UNIT '{name}': a length unit of {mm:g} mm")
                return mm
            if str(name).lower() in NAMED_LENGTH_MM:
                return NAMED_LENGTH_MM[str(name).lower()]
            raise StepNcError(f"#{target.id} CONVERSION_BASED_UNIT '{name}': no conversion factor, and not a unit "
                              f"Kezuri knows by name ({', '.join(NAMED_LENGTH_MM)})")
        return 1.0

    def per_second(self, unit) -> float:
        """Factor from a DERIVED_UNIT of (length /) time to the same per second; the length part
        to metres (feeds) -- a speed without a length is a rate (spindle)."""
        if not isinstance(unit, Ref) or unit.id not in self.part21.instances:
            return 1.0
        target = self.part21.instances[unit.id]
        if "DERIVED_UNIT" not in target.type_names:
            return 1.0
        factor = 1.0
        for ref in _params(target, "DERIVED_UNIT")[0]:
            element = self.part21.instances.get(getattr(ref, "id", None))
            if element is None or len(_params(element)) < 2:
                continue
            base, exponent = _at(element, 0), float(_at(element, 1))
            base_inst = self.part21.instances.get(getattr(base, "id", None))
            if base_inst is None:
                continue
            if "LENGTH_UNIT" in base_inst.type_names or "CONVERSION_BASED_UNIT" in base_inst.type_names \
                    and "TIME_UNIT" not in base_inst.type_names:
                factor *= (self.length_factor(base) / 1000.0) ** exponent
            elif "TIME_UNIT" in base_inst.type_names and "CONVERSION_BASED_UNIT" in base_inst.type_names:
                seconds = {"minute": 60.0, "hour": 3600.0}.get(str(_params(base_inst, "CONVERSION_BASED_UNIT")[0])
                                                              .lower(), 1.0)
                factor *= seconds ** exponent
        return factor


def _kind(inst) -> str:
    return inst.type_name if isinstance(inst, Instance) else "(" + " ".join(inst.type_names) + ")"


def _measure(item):
    """(value, unit) of a measure_representation_item, simple or complex; value None when unset."""
    if isinstance(item, ComplexInstance):
        if "MEASURE_WITH_UNIT" not in item.type_names:
            return None, None
        value, unit = item.params_of("MEASURE_WITH_UNIT")[:2]
    elif item.type_name in ("MEASURE_REPRESENTATION_ITEM",) and len(item.params) >= 3:
        value, unit = item.params[1], item.params[2]
    elif item.type_name.endswith("MEASURE_WITH_UNIT") and len(item.params) >= 2:
        value, unit = item.params[0], item.params[1]
    else:
        return None, None
    if isinstance(value, Typed):
        value = value.value
    if value is UNSET or value is None:
        return None, unit
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise StepNcError(f"#{item.id} {_kind(item)}: the value must be a number, found {value!r}")
    return float(value), unit


def _text(item) -> str | None:
    if isinstance(item, Instance) and item.type_name == "DESCRIPTIVE_REPRESENTATION_ITEM" and len(item.params) > 1:
        return str(item.params[1]).strip().lower()
    return None


def _enum(words: str | None):
    if words is None:
        return UNSET
    return Enum(WORDS.get(words, words.upper().replace(" ", "_")))


def _placeholder_name(words: str) -> str:
    return str(words).strip().upper().replace(" ", "_") or "UNNAMED"


def to_arm(part21: Part21File) -> Part21File:
    """The ISO 14649 ARM rendition of an AP238 AIM file (see the module's description)."""
    translator = _Translator(part21)
    try:
        return translator.run()
    except (IndexError, KeyError, TypeError, AttributeError, ValueError, ZeroDivisionError) as error:
        if isinstance(error, StepNcError):
            raise
        raise StepNcError(f"the AP238 data does not follow the mapping of ISO 10303-238 near #{translator.current} "
                          f"({type(error).__name__}: {error})") from None


class _Translator(_Aim):

    def run(self) -> Part21File:
        projects = self.part21.by_type("MACHINING_PROJECT")
        self.current = projects[0].id if projects else 0
        if len(projects) != 1:
            raise StepNcError(f"an AP238 file needs exactly one MACHINING_PROJECT, this one has {len(projects)}")
        project = projects[0]
        definition = self._definition_of(project)
        workplan = None
        for association in self.referrers(definition, "PROCESS_PRODUCT_ASSOCIATION", 2):
            process = self.get(_at(association, 3), "process", association)
            if _at(process, 0) == "machining":
                workplan = self.get(_at(process, 2), "chosen_method", process)
        if workplan is None or "MACHINING_WORKPLAN" not in workplan.type_names:
            raise StepNcError(f"#{project.id} MACHINING_PROJECT: no main MACHINING_WORKPLAN (a PRODUCT_DEFINITION_PROCESS "
                              f"'machining' of its PRODUCT_DEFINITION #{definition.id})")
        pieces = [self.get(_at(rel, 4), "related_product_definition", rel)
                  for rel in self.referrers(definition, "MACHINING_PROJECT_WORKPIECE_RELATIONSHIP", 3)]
        main = self.workplan(workplan, ())
        self.put(project.id, "PROJECT", [str(_at(project, 0)), main, [self.workpiece(p) for p in pieces],
                                         UNSET, UNSET, UNSET])
        return Part21File(self.part21.header, self.out, self.part21.data_sections)

    def _definition_of(self, product):
        for formation in self.referrers(product, "PRODUCT_DEFINITION_FORMATION", 2):
            for definition in self.referrers(formation, "PRODUCT_DEFINITION", 2):
                return definition
        raise StepNcError(f"#{product.id} {_kind(product)}: no PRODUCT_DEFINITION_FORMATION and PRODUCT_DEFINITION "
                          "refer to it")

    # ---- product data

    def workpiece(self, definition) -> Ref:
        if definition.id in self.done:
            return Ref(definition.id)
        tolerance, clamps = UNSET, []
        for rep, item, pd in self.shape_items(definition):
            name = str(_at(pd, 0)).lower()
            if name == "global tolerance":
                tolerance = self.length(item)
            elif name == "clamping position" and "CARTESIAN_POINT" in item.type_names:
                clamps.append(Ref(item.id))
        block = UNSET
        for usage in self.referrers(definition, "MAKE_FROM_USAGE_OPTION", 3):
            stock = self.get(_at(usage, 4), "related_product_definition", usage)
            for rep, item, pd in self.shape_items(stock):
                if "BLOCK_SHAPE_REPRESENTATION" in rep.type_names and block is UNSET:
                    block = self.block(rep)
        return self.put(definition.id, "WORKPIECE", [str(_at(definition, 0)), UNSET,
                                                     UNSET if tolerance is None else tolerance, UNSET, UNSET, block,
                                                     clamps])

    def block(self, rep) -> Ref:
        values = {"orientation": UNSET}
        for ref in _at(rep, 1):
            item = self.get(ref, "items", rep)
            name = _item_name(item).lower()
            values[name] = Ref(item.id) if "AXIS2_PLACEMENT_3D" in item.type_names else self.length(item)
        missing = [n for n in ("orientation", "length", "width", "height") if values.get(n) in (None, UNSET)]
        if missing:
            raise StepNcError(f"#{rep.id} BLOCK_SHAPE_REPRESENTATION: no {', '.join(missing)} item")
        return self.put(rep.id, "BLOCK", [_item_name(rep) if isinstance(_at(rep, 0), str) else "",
                                          values["orientation"], values["length"], values["width"], values["height"]])

    # ---- executables

    def workplan(self, workplan, seen: tuple) -> Ref:
        if workplan.id in seen:
            raise StepNcError(f"#{workplan.id} MACHINING_WORKPLAN contains itself (through #{seen[-1]})")
        steps = sorted(self.referrers(workplan, "MACHINING_PROCESS_SEQUENCE_RELATIONSHIP", 2),
                       key=lambda rel: (_position(rel), rel.id))
        elements = []
        for rel in steps:
            element = self.get(_at(rel, 3), "related_method", rel)
            if "MACHINING_WORKPLAN" in element.type_names:
                elements.append(self.workplan(element, seen + (workplan.id,)))
            elif "MACHINING_WORKINGSTEP" in element.type_names:
                elements.append(self.workingstep(element))
            else:
                elements.append(Ref(element.id))     # the ISO 14649 reader names it and leaves it out
        return self.put(workplan.id, "WORKPLAN", [str(_at(workplan, 0)), elements, UNSET,
                                                  self.setup(workplan), UNSET])

    def setup(self, workplan):
        for process in self.referrers(workplan, "PRODUCT_DEFINITION_PROCESS", 2):
            if _at(process, 0) != "setup":
                continue
            for association in self.referrers(process, "PROCESS_PRODUCT_ASSOCIATION", 3):
                definition = self.get(_at(association, 2), "defined_product", association)
                plane, origin = UNSET, UNSET
                for rep, item, pd in self.shape_items(definition):
                    if item.type_names[0] == "PLANE" and str(_at(pd, 0)).lower() == "security plane":
                        plane = Ref(item.id)
                    elif "AXIS2_PLACEMENT_3D" in item.type_names:
                        origin = Ref(item.id)
                if plane is UNSET:
                    return UNSET
                formation = self.get(_at(definition, 2), "formation", definition)
                name = _params(self.get(_at(formation, 2), "of_product", formation))[0]
                return self.new("SETUP", [str(name), origin, plane, []])
        return UNSET

    def workingstep(self, step) -> Ref:
        self.current = step.id
        if step.id in self.done:
            return Ref(step.id)
        properties = self.action_properties(step)
        plane = next((Ref(item.id) for _, item, _ in properties.get("security plane", [])
                      if item.type_names[0] in ("PLANE", "ELEMENTARY_SURFACE")), None)
        if plane is None:
            raise StepNcError(f"#{step.id} MACHINING_WORKINGSTEP '{_at(step, 0)}': no 'security plane' "
                              "ACTION_PROPERTY with a PLANE")
        operations = self.related(step, "MACHINING_OPERATION_RELATIONSHIP")
        if len(operations) != 1:
            raise StepNcError(f"#{step.id} MACHINING_WORKINGSTEP '{_at(step, 0)}': needs one "
                              f"MACHINING_OPERATION_RELATIONSHIP, found {len(operations)}")
        feature = self.feature_of(step)
        return self.put(step.id, "MACHINING_WORKINGSTEP", [str(_at(step, 0)), plane, feature,
                                                           self.operation(operations[0]), UNSET])

    def feature_of(self, step) -> Ref:
        for process in self.related(step, "MACHINING_FEATURE_RELATIONSHIP"):
            for prop in self.referrers(process, "PROPERTY_PROCESS", 2):
                for association in self.referrers(prop, "PROCESS_PROPERTY_ASSOCIATION", 2):
                    return self.feature(self.get(_at(association, 3), "property_or_shape", association))
        raise StepNcError(f"#{step.id} MACHINING_WORKINGSTEP '{_at(step, 0)}': no feature (a "
                          "MACHINING_FEATURE_RELATIONSHIP to a MACHINING_FEATURE_PROCESS with a PROPERTY_PROCESS)")

    # ---- features and their components

    def feature(self, feature) -> Ref:
        self.current = feature.id
        if feature.id in self.done:
            return Ref(feature.id)
        from .ap238_features import feature_to_arm
        return feature_to_arm(self, feature)

    # ---- operations, tools, technology, strategies

    def operation(self, op) -> Ref:
        self.current = op.id
        if op.id in self.done:
            return Ref(op.id)
        from .ap238_process import operation_to_arm
        return operation_to_arm(self, op)


def _position(rel) -> float:
    value = _at(rel, 4) if len(rel.params) > 4 else None
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else 0.0
