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

from .ap238_aim import Aim, attribute, attributes, kind_of, name_of
from .ap238_features import feature_to_arm
from .ap238_process import operation_to_arm
from .errors import StepNcError
from .part21 import UNSET, Part21File, Ref

AP238_SCHEMAS = ("AP238_STEP_NC_MIM", "MODEL_BASED_INTEGRATED_MANUFACTURING_SCHEMA", "INTEGRATED_CNC_SCHEMA",
                 "AP238_STEP_NC_MIM_LF")

GEOMETRY = ("AXIS2_PLACEMENT_3D", "CARTESIAN_POINT", "DIRECTION", "PLANE", "POLYLINE", "CIRCLE", "TRIMMED_CURVE",
            "COMPOSITE_CURVE", "LINE", "B_SPLINE_CURVE_WITH_KNOTS")


def is_ap238(part21: Part21File) -> bool:
    return bool(part21.by_type("MACHINING_PROJECT")) or any(s.upper() in AP238_SCHEMAS for s in part21.schema)


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


class _Translator(Aim):

    def run(self) -> Part21File:
        projects = self.part21.by_type("MACHINING_PROJECT")
        self.current = projects[0].id if projects else 0
        if len(projects) != 1:
            raise StepNcError(f"an AP238 file needs exactly one MACHINING_PROJECT, this one has {len(projects)}")
        project = projects[0]
        definition = self._definition_of(project)
        workplan = None
        for association in self.referrers(definition, "PROCESS_PRODUCT_ASSOCIATION", 2):
            process = self.get(attribute(association, 3), "process", association)
            if attribute(process, 0) == "machining":
                workplan = self.get(attribute(process, 2), "chosen_method", process)
        if workplan is None or "MACHINING_WORKPLAN" not in workplan.type_names:
            raise StepNcError(f"#{project.id} MACHINING_PROJECT: no main MACHINING_WORKPLAN (a PRODUCT_DEFINITION_PROCESS "
                              f"'machining' of its PRODUCT_DEFINITION #{definition.id})")
        pieces = [self.get(attribute(rel, 4), "related_product_definition", rel)
                  for rel in self.referrers(definition, "MACHINING_PROJECT_WORKPIECE_RELATIONSHIP", 3)]
        main = self.workplan(workplan, ())
        self.put(project.id, "PROJECT", [str(attribute(project, 0)), main, [self.workpiece(p) for p in pieces],
                                         UNSET, UNSET, UNSET])
        return Part21File(self.part21.header, self.out, self.part21.data_sections)

    def _definition_of(self, product):
        for formation in self.referrers(product, "PRODUCT_DEFINITION_FORMATION", 2):
            for definition in self.referrers(formation, "PRODUCT_DEFINITION", 2):
                return definition
        raise StepNcError(f"#{product.id} {kind_of(product)}: no PRODUCT_DEFINITION_FORMATION and PRODUCT_DEFINITION "
                          "refer to it")

    # ---- product data

    def workpiece(self, definition) -> Ref:
        if definition.id in self.done:
            return Ref(definition.id)
        tolerance, clamps = UNSET, []
        for rep, item, pd in self.shape_items(definition):
            name = str(attribute(pd, 0)).lower()
            if name == "global tolerance":
                tolerance = self.length(item)
            elif name == "clamping position" and "CARTESIAN_POINT" in item.type_names:
                clamps.append(Ref(item.id))
        block = UNSET
        for usage in self.referrers(definition, "MAKE_FROM_USAGE_OPTION", 3):
            stock = self.get(attribute(usage, 4), "related_product_definition", usage)
            for rep, item, pd in self.shape_items(stock):
                if "BLOCK_SHAPE_REPRESENTATION" in rep.type_names and block is UNSET:
                    block = self.block(rep)
        return self.put(definition.id, "WORKPIECE", [str(attribute(definition, 0)), UNSET,
                                                     UNSET if tolerance is None else tolerance, UNSET, UNSET, block,
                                                     clamps])

    def block(self, rep) -> Ref:
        values = {"orientation": UNSET}
        for ref in attribute(rep, 1):
            item = self.get(ref, "items", rep)
            name = name_of(item).lower()
            values[name] = Ref(item.id) if "AXIS2_PLACEMENT_3D" in item.type_names else self.length(item)
        missing = [n for n in ("orientation", "length", "width", "height") if values.get(n) in (None, UNSET)]
        if missing:
            raise StepNcError(f"#{rep.id} BLOCK_SHAPE_REPRESENTATION: no {', '.join(missing)} item")
        return self.put(rep.id, "BLOCK", [name_of(rep) if isinstance(attribute(rep, 0), str) else "",
                                          values["orientation"], values["length"], values["width"], values["height"]])

    # ---- executables

    def workplan(self, workplan, seen: tuple) -> Ref:
        if workplan.id in seen:
            raise StepNcError(f"#{workplan.id} MACHINING_WORKPLAN contains itself (through #{seen[-1]})")
        steps = sorted(self.referrers(workplan, "MACHINING_PROCESS_SEQUENCE_RELATIONSHIP", 2),
                       key=lambda rel: (_position(rel), rel.id))
        elements = []
        for rel in steps:
            element = self.get(attribute(rel, 3), "related_method", rel)
            if "MACHINING_WORKPLAN" in element.type_names:
                elements.append(self.workplan(element, seen + (workplan.id,)))
            elif "MACHINING_WORKINGSTEP" in element.type_names:
                elements.append(self.workingstep(element))
            else:
                elements.append(Ref(element.id))     # the ISO 14649 reader names it and leaves it out
        return self.put(workplan.id, "WORKPLAN", [str(attribute(workplan, 0)), elements, UNSET,
                                                  self.setup(workplan), UNSET])

    def setup(self, workplan):
        for process in self.referrers(workplan, "PRODUCT_DEFINITION_PROCESS", 2):
            if attribute(process, 0) != "setup":
                continue
            for association in self.referrers(process, "PROCESS_PRODUCT_ASSOCIATION", 3):
                definition = self.get(attribute(association, 2), "defined_product", association)
                plane, origin = UNSET, UNSET
                for rep, item, pd in self.shape_items(definition):
                    if item.type_names[0] == "PLANE" and str(attribute(pd, 0)).lower() == "security plane":
                        plane = Ref(item.id)
                    elif "AXIS2_PLACEMENT_3D" in item.type_names:
                        origin = Ref(item.id)
                if plane is UNSET:
                    return UNSET
                formation = self.get(attribute(definition, 2), "formation", definition)
                name = attributes(self.get(attribute(formation, 2), "of_product", formation))[0]
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
            raise StepNcError(f"#{step.id} MACHINING_WORKINGSTEP '{attribute(step, 0)}': no 'security plane' "
                              "ACTION_PROPERTY with a PLANE")
        operations = self.related(step, "MACHINING_OPERATION_RELATIONSHIP")
        if len(operations) != 1:
            raise StepNcError(f"#{step.id} MACHINING_WORKINGSTEP '{attribute(step, 0)}': needs one "
                              f"MACHINING_OPERATION_RELATIONSHIP, found {len(operations)}")
        feature = self.feature_of(step)
        return self.put(step.id, "MACHINING_WORKINGSTEP", [str(attribute(step, 0)), plane, feature,
                                                           self.operation(operations[0]), UNSET])

    def feature_of(self, step) -> Ref:
        for process in self.related(step, "MACHINING_FEATURE_RELATIONSHIP"):
            for prop in self.referrers(process, "PROPERTY_PROCESS", 2):
                for association in self.referrers(prop, "PROCESS_PROPERTY_ASSOCIATION", 2):
                    return self.feature(self.get(attribute(association, 3), "property_or_shape", association))
        raise StepNcError(f"#{step.id} MACHINING_WORKINGSTEP '{attribute(step, 0)}': no feature (a "
                          "MACHINING_FEATURE_RELATIONSHIP to a MACHINING_FEATURE_PROCESS with a PROPERTY_PROCESS)")

    # ---- features and their components

    def feature(self, feature) -> Ref:
        self.current = feature.id
        if feature.id in self.done:
            return Ref(feature.id)
        return feature_to_arm(self, feature)

    # ---- operations, tools, technology, strategies

    def operation(self, op) -> Ref:
        self.current = op.id
        if op.id in self.done:
            return Ref(op.id)
        return operation_to_arm(self, op)


def _position(rel) -> float:
    value = attribute(rel, 4) if len(rel.params) > 4 else None
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else 0.0
