"""The AP238 integrated form (ISO 10303-238 AIM) as instances to walk: the inverse references the
mapping paths follow backwards, the properties hung on an action_method or a resource, lengths in
their units, and the readers of attribute values that every part of the translation (ap238.py,
ap238_features.py, ap238_process.py) uses."""
from __future__ import annotations

import math
from collections import defaultdict

from .errors import StepNcError
from .part21 import UNSET, ComplexInstance, Enum, Instance, Part21File, Ref, Typed, iter_refs

WORDS = {"left": "LEFT", "right": "RIGHT", "clockwise": "CW", "counterclockwise": "CCW", "climb": "CLIMB",
         "conventional": "CONVENTIONAL", "tool center point": "TCP", "contact point": "CCP",
         "cutter contact point": "CCP", "straight line": "STRAIGHTLINE", "lift shift plunge": "LIFT_SHIFT_PLUNGE",
         "degouge": "DEGOUGE", "loop back": "LOOP_BACK"}
# length units: SI prefix -> power of ten; conversion-based units known by name -> mm
SI_PREFIX_EXPONENT = {"EXA": 18, "PETA": 15, "TERA": 12, "GIGA": 9, "MEGA": 6, "KILO": 3, "HECTO": 2, "DECA": 1,
                      "DECI": -1, "CENTI": -2, "MILLI": -3, "MICRO": -6, "NANO": -9, "PICO": -12, "FEMTO": -15,
                      "ATTO": -18}     # ISO 10303-41 si_prefix
NAMED_LENGTH_MM = {"inch": 25.4, "foot": 304.8, "millimetre": 1.0, "metre": 1000.0}


def attributes(inst, part: str | None = None) -> list:
    if isinstance(inst, ComplexInstance):
        return inst.params_of(part or inst.type_names[-1])
    return inst.params


def attribute(inst, index: int):
    """Attribute ``index`` of an instance (of its last part for a complex one), named when missing."""
    params = attributes(inst)
    if index >= len(params):
        raise StepNcError(f"#{inst.id} {kind_of(inst)}: attribute number {index + 1} is missing; the instance has "
                          f"{len(params)} attributes")
    return params[index]


def name_of(inst) -> str:
    if isinstance(inst, ComplexInstance):
        for part in ("REPRESENTATION_ITEM", "SHAPE_ASPECT"):
            if part in inst.type_names:
                value = inst.params_of(part)[0]
                return value if isinstance(value, str) else ""
        return ""
    value = inst.params[0] if inst.params else ""
    return value if isinstance(value, str) else ""


class Aim:
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
            raise StepNcError(f"#{inst.id} {kind_of(inst)}: {what} must refer to an instance, found {value!r}")
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
            if name is None or str(attribute(rel, 0)).lower() == name:
                found.append(self.get(attribute(rel, 3), "related_method", rel))
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
                rep = self.get(holder.params[-1] if link != "SHAPE_DEFINITION_REPRESENTATION" else attribute(holder, 1),
                               "representation", holder)
                rep_name = str(attribute(holder, 0)) if link.startswith(("ACTION", "RESOURCE")) else ""
                for ref in attribute(rep, 1) if len(attributes(rep)) > 1 and isinstance(attribute(rep, 1), list) else []:
                    item = self.get(ref, "items", rep)
                    items.setdefault(str(attribute(owner, 0)).lower(), []).append((rep_name.lower(), item, rep))
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
                        rep = self.get(attribute(holder, 1), "used_representation", holder)
                        for ref in attribute(rep, 1) if isinstance(attribute(rep, 1), list) else []:
                            found.append((rep, self.get(ref, "items", rep), pd))
        return found

    # ---- values

    def length(self, item) -> float | None:
        value, unit = measure_of(item)
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
            prefix, name = attributes(target, "SI_UNIT")[:2]
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
            name, factor = (attributes(target, "CONVERSION_BASED_UNIT") + [UNSET, UNSET])[:2]
            if target.id in seen:
                raise StepNcError(f"#{target.id} CONVERSION_BASED_UNIT '{name}': its conversion factor is given in "
                                  f"itself")
            measure = self.part21.instances.get(getattr(factor, "id", None))
            value = measure_of(measure) if measure is not None else (None, None)
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
        for ref in attributes(target, "DERIVED_UNIT")[0]:
            element = self.part21.instances.get(getattr(ref, "id", None))
            if element is None or len(attributes(element)) < 2:
                continue
            base, exponent = attribute(element, 0), float(attribute(element, 1))
            base_inst = self.part21.instances.get(getattr(base, "id", None))
            if base_inst is None:
                continue
            if "LENGTH_UNIT" in base_inst.type_names or "CONVERSION_BASED_UNIT" in base_inst.type_names \
                    and "TIME_UNIT" not in base_inst.type_names:
                factor *= (self.length_factor(base) / 1000.0) ** exponent
            elif "TIME_UNIT" in base_inst.type_names and "CONVERSION_BASED_UNIT" in base_inst.type_names:
                seconds = {"minute": 60.0, "hour": 3600.0}.get(str(attributes(base_inst, "CONVERSION_BASED_UNIT")[0])
                                                              .lower(), 1.0)
                factor *= seconds ** exponent
        return factor


def kind_of(inst) -> str:
    return inst.type_name if isinstance(inst, Instance) else "(" + " ".join(inst.type_names) + ")"


def measure_of(item):
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
        raise StepNcError(f"#{item.id} {kind_of(item)}: the value must be a number, found {value!r}")
    return float(value), unit


def text_of(item) -> str | None:
    if isinstance(item, Instance) and item.type_name == "DESCRIPTIVE_REPRESENTATION_ITEM" and len(item.params) > 1:
        return str(item.params[1]).strip().lower()
    return None


def enum_of(words: str | None):
    if words is None:
        return UNSET
    return Enum(WORDS.get(words, words.upper().replace(" ", "_")))


def placeholder_name(words: str) -> str:
    return str(words).strip().upper().replace(" ", "_") or "UNNAMED"
