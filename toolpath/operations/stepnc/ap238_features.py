"""AP238 machining features -> ISO 14649 ARM features (see :mod:`.ap238`).

A feature is a complex instance with a SHAPE_ASPECT part (name = its_id, of_shape = the workpiece's
PRODUCT_DEFINITION_SHAPE) and a part naming its kind: ROUND_HOLE, POCKET, FLAT_FACE (a planar face),
SLOT.  Its PRODUCT_DEFINITION_SHAPE carries a SHAPE_REPRESENTATION_WITH_PARAMETERS with the placement
(item 'orientation') and the pocket's fillet radii, and a SHAPE_REPRESENTATION 'maximum feature limit'
with the depth PLANE.  Paths and profiles are feature components (PATH_FEATURE_COMPONENT 'linear',
LINEAR_PROFILE, CIRCULAR_CLOSED_PROFILE, RECTANGULAR_CLOSED_PROFILE, CLOSED_PATH_PROFILE, SQUARE_U_PROFILE,
HOLE_BOTTOM, POCKET_BOTTOM, SLOT_END) tied to the feature by a SHAPE_ASPECT described '<role>
occurrence' and a SHAPE_DEFINING_RELATIONSHIP or FEATURE_COMPONENT_RELATIONSHIP.  A component's own
'orientation' item that is the feature's placement itself is no placement of its own (the profile
sits at the feature's zero point), so it is never composed twice.
"""
from __future__ import annotations

from .ap238_aim import attribute, kind_of, measure_of, name_of, placeholder_name
from .errors import StepNcError
from .geometry import CURVE_TYPES
from .part21 import UNSET, Ref

HOLE_BOTTOMS = {"through": "THROUGH_BOTTOM_CONDITION", "flat": "FLAT_HOLE_BOTTOM",
                "conical": "CONICAL_HOLE_BOTTOM", "spherical": "SPHERICAL_HOLE_BOTTOM",
                "flat with radius": "FLAT_WITH_RADIUS_HOLE_BOTTOM"}
POCKET_BOTTOMS = {"planar": "PLANAR_POCKET_BOTTOM_CONDITION", "through": "THROUGH_POCKET_BOTTOM_CONDITION"}
SLOT_ENDS = {"open": "OPEN_SLOT_END_TYPE", "radiused": "RADIUSED_SLOT_END_TYPE", "flat": "FLAT_SLOT_END_TYPE",
             "woodruff": "WOODRUFF_SLOT_END_TYPE", "loop": "LOOP_SLOT_END_TYPE"}
KINDS = ("ROUND_HOLE", "POCKET", "FLAT_FACE", "PLANAR_FACE", "SLOT")


def feature_to_arm(aim, feature) -> Ref:
    kind = next((t for t in feature.type_names if t in KINDS), None)
    if kind is None or "SHAPE_ASPECT" not in feature.type_names:
        own = [t for t in feature.type_names if t not in ("CHARACTERIZED_OBJECT", "FEATURE_DEFINITION",
                                                           "INSTANCED_FEATURE", "SHAPE_ASPECT")]
        return aim.put(feature.id, own[0] if own else kind_of(feature), [])
    aspect = feature.params_of("SHAPE_ASPECT")
    its_id = str(aspect[0])
    workpiece = _workpiece(aim, feature, aspect)
    shapes = aim.referrers(feature, "PRODUCT_DEFINITION_SHAPE", 2)
    if not shapes:
        raise StepNcError(f"#{feature.id} {kind} '{its_id}': no PRODUCT_DEFINITION_SHAPE refers to it")
    placement, depth, measures = None, None, {}
    for rep, item, _ in aim.shape_items(feature):
        name = name_of(item).lower()
        if "AXIS2_PLACEMENT_3D" in item.type_names and name in ("orientation", "") and placement is None:
            placement = item
        elif item.type_names[0] in ("PLANE", "ELEMENTARY_SURFACE") and \
                str(attribute(rep, 0)).lower() == "maximum feature limit":
            depth = item
        elif "MEASURE_WITH_UNIT" in item.type_names or item.type_names[0] == "MEASURE_REPRESENTATION_ITEM":
            measures[name] = aim.length(item)
    if placement is None:
        raise StepNcError(f"#{feature.id} {kind} '{its_id}': no placement (an AXIS2_PLACEMENT_3D 'orientation' in "
                          "the SHAPE_REPRESENTATION_WITH_PARAMETERS of its PRODUCT_DEFINITION_SHAPE)")
    if depth is None:
        raise StepNcError(f"#{feature.id} {kind} '{its_id}': no depth (a PLANE in its SHAPE_REPRESENTATION "
                          "'maximum feature limit')")
    parts = _components(aim, shapes)
    head = [its_id, workpiece, [], Ref(placement.id), Ref(depth.id)]
    if kind == "ROUND_HOLE":
        diameter = _component_length(aim, parts, "diameter", feature, its_id, ("diameter",))
        bottom = _bottom(aim, parts, HOLE_BOTTOMS)
        return aim.put(feature.id, "ROUND_HOLE", head + [diameter, UNSET, bottom])
    if kind in ("FLAT_FACE", "PLANAR_FACE"):
        path = _linear_path(aim, _required(parts, "course of travel", feature, its_id), placement)
        profile = _required(parts, "removal boundary", feature, its_id)
        if profile.type_names[0] != "LINEAR_PROFILE":
            boundary = aim.put(profile.id, placeholder_name(profile.type_names[0]), [])
        else:
            length = _first_length(aim, profile)
            boundary = aim.put(profile.id, "LINEAR_PROFILE", [_own_placement(aim, profile, placement), length])
        return aim.put(feature.id, "PLANAR_FACE", head + [path, boundary, UNSET, []])
    if kind == "SLOT":
        path = _linear_path(aim, _required(parts, "course of travel", feature, its_id), placement)
        shape = _required(parts, "swept shape", feature, its_id)
        if shape.type_names[0] != "SQUARE_U_PROFILE":
            swept = aim.put(shape.id, placeholder_name(shape.type_names[0]), [])
        else:
            values = _lengths(aim, shape)
            swept = aim.put(shape.id, "SQUARE_U_PROFILE", [UNSET, values.get("width", UNSET),
                                                           values.get("first radius", UNSET), UNSET,
                                                           values.get("second radius", UNSET), UNSET])
        ends = [aim.put(end.id, SLOT_ENDS.get(str(attribute(end, 1)).lower(), placeholder_name(f"{attribute(end, 1)} slot end")),
                        []) for end in _slot_ends(aim, shapes)]
        return aim.put(feature.id, "SLOT", head + [path, swept, ends])
    # POCKET: closed when its boundary is a closed profile
    boundary = _required(parts, "boundary", feature, its_id)
    bottom = _bottom(aim, parts, POCKET_BOTTOMS) if parts.get("bottom condition") else UNSET
    if bottom is UNSET:
        raise StepNcError(f"#{feature.id} POCKET '{its_id}': no bottom condition (a POCKET_BOTTOM through a "
                          "'bottom condition occurrence')")
    return aim.put(feature.id, "CLOSED_POCKET", head + [
        [], UNSET, bottom, measures.get("fillet radius", UNSET), measures.get("orthogonal fillet radius", UNSET),
        _closed_profile(aim, boundary, placement)])


def _workpiece(aim, feature, aspect):
    shape = aim.part21.instances.get(getattr(aspect[2], "id", None))
    if shape is not None and "PRODUCT_DEFINITION_SHAPE" in shape.type_names:
        definition = aim.part21.instances.get(getattr(attribute(shape, 2), "id", None))
        if definition is not None and "PRODUCT_DEFINITION" in definition.type_names:
            return aim.workpiece(definition)
    return UNSET


def _components(aim, shapes) -> dict:
    """{role: [component]} from the SHAPE_ASPECTs '<role> occurrence' of the feature's shape."""
    found = {}
    for shape in shapes:
        for occurrence in aim.referrers(shape, "SHAPE_ASPECT", 2):
            role = str(attribute(occurrence, 1)).lower()
            role = role[:-len(" occurrence")] if role.endswith(" occurrence") else role
            for link in ("SHAPE_DEFINING_RELATIONSHIP", "FEATURE_COMPONENT_RELATIONSHIP"):
                for rel in aim.referrers(occurrence, link, 3):
                    found.setdefault(role, []).append(aim.get(attribute(rel, 2), "relating_shape_aspect", rel))
    return found


def _slot_ends(aim, shapes) -> list:
    """The SLOT_ENDs of a slot, the 'course of travel start' one first."""
    found = []
    for shape in shapes:
        for occurrence in aim.referrers(shape, "SHAPE_ASPECT", 2):
            if str(attribute(occurrence, 1)).lower() != "end condition occurrence":
                continue
            for rel in aim.referrers(occurrence, "FEATURE_COMPONENT_RELATIONSHIP", 3):
                order = {"course of travel start": 0, "course of travel end": 1}.get(str(attribute(rel, 0)).lower(), 2)
                found.append((order, rel.id, aim.get(attribute(rel, 2), "relating_shape_aspect", rel)))
    return [end for _, _, end in sorted(found, key=lambda item: item[:2])]


def _required(parts, role, feature, its_id):
    if not parts.get(role):
        kind = next((t for t in feature.type_names if t in KINDS), kind_of(feature))
        raise StepNcError(f"#{feature.id} {kind} '{its_id}': no {role} (a feature component through a "
                          f"SHAPE_ASPECT '{role} occurrence')")
    return parts[role][0]


def _lengths(aim, component) -> dict:
    return {name_of(item).lower(): aim.length(item) for rep, item, _ in aim.shape_items(component)
            if "MEASURE_WITH_UNIT" in item.type_names or item.type_names[0] == "MEASURE_REPRESENTATION_ITEM"}


def _first_length(aim, component):
    values = [v for v in _lengths(aim, component).values() if v is not None]
    if not values:
        raise StepNcError(f"#{component.id} {kind_of(component)}: no length item in its representation")
    return values[0]


def _component_length(aim, parts, role, feature, its_id, names):
    component = _required(parts, role, feature, its_id)
    values = _lengths(aim, component)
    for name in names:
        if values.get(name) is not None:
            return values[name]
    raise StepNcError(f"#{component.id} {kind_of(component)}: no '{names[0]}' item in its representation")


def _own_placement(aim, component, feature_placement):
    """The component's own 'orientation' placement, or UNSET when it has none or it is the feature's."""
    for rep, item, _ in aim.shape_items(component):
        if "AXIS2_PLACEMENT_3D" in item.type_names and item.id != feature_placement.id:
            return Ref(item.id)
    return UNSET


def _linear_path(aim, path, feature_placement) -> Ref:
    """A PATH_FEATURE_COMPONENT: 'linear' (a 'distance' and a DIRECTION), 'partial circular' ('radius',
    'sweep angle'), 'complete circular' ('radius') or 'complex' (a curve in a PATH_SHAPE_REPRESENTATION
    'sweep path'), each placed by its own 'orientation' if it has one."""
    kind = str(attribute(path, 1)).lower()
    own = _own_placement(aim, path, feature_placement)
    if kind in ("partial circular", "complete circular"):
        values = _lengths(aim, path)
        if values.get("radius") is None:
            raise StepNcError(f"#{path.id} PATH_FEATURE_COMPONENT: a circular path needs a 'radius'")
        if kind == "complete circular":
            return aim.put(path.id, "COMPLETE_CIRCULAR_PATH", [own, values["radius"]])
        sweep = next((_angle(aim, item) for _, item, _ in aim.shape_items(path)
                      if name_of(item).lower() == "sweep angle"), None)
        if sweep is None:
            raise StepNcError(f"#{path.id} PATH_FEATURE_COMPONENT: a partial circular path needs a 'sweep angle'")
        return aim.put(path.id, "PARTIAL_CIRCULAR_PATH", [own, values["radius"], sweep])
    if kind == "complex":
        curves = _curves(aim, path)
        if not curves:
            raise StepNcError(f"#{path.id} PATH_FEATURE_COMPONENT: a complex path needs a curve ('sweep path')")
        return aim.put(path.id, "GENERAL_PATH", [own, Ref(curves[0].id)])
    if kind != "linear":
        return aim.put(path.id, placeholder_name(f"{attribute(path, 1)} path"), [])
    direction = next((Ref(item.id) for rep, item, _ in aim.shape_items(path) if "DIRECTION" in item.type_names), None)
    values = _lengths(aim, path)
    if direction is None or values.get("distance") is None:
        raise StepNcError(f"#{path.id} PATH_FEATURE_COMPONENT: a linear path needs a DIRECTION and a 'distance'")
    return aim.put(path.id, "LINEAR_PATH", [own, values["distance"], direction])


def _curves(aim, owner) -> list:
    """The curves the reader knows (:data:`.geometry.CURVE_TYPES`) among the items of ``owner``'s
    shape representations."""
    return [item for _, item, _ in aim.shape_items(owner) if item.type_names[0] in CURVE_TYPES]


def _angle(aim, item) -> float | None:
    """Degrees of a plane angle measure (its unit degrees or radians)."""
    value, unit = measure_of(item)
    if value is None:
        return None
    target = aim.part21.instances.get(getattr(unit, "id", None))
    if target is not None and "SI_UNIT" in target.type_names:
        return value * 180.0 / 3.141592653589793
    return value


def _bottom(aim, parts, names) -> Ref:
    bottom = parts.get("bottom condition", [None])[0]
    if bottom is None:
        return UNSET
    words = str(attribute(bottom, 1)).lower()
    return aim.put(bottom.id, names.get(words, placeholder_name(f"{words} {bottom.type_names[0]}")), [])


def _closed_profile(aim, profile, feature_placement) -> Ref:
    kind = profile.type_names[0]
    own = _own_placement(aim, profile, feature_placement)
    if kind == "RECTANGULAR_CLOSED_PROFILE":
        values = _lengths(aim, profile)
        if values.get("width") is None or values.get("length") is None:
            raise StepNcError(f"#{profile.id} RECTANGULAR_CLOSED_PROFILE: needs 'width' and 'length' items")
        return aim.put(profile.id, "RECTANGULAR_CLOSED_PROFILE", [own, values["width"], values["length"]])
    if kind == "CLOSED_PATH_PROFILE":
        curves = _curves(aim, profile)
        if not curves:
            raise StepNcError(f"#{profile.id} CLOSED_PATH_PROFILE: no curve in its PATH_SHAPE_REPRESENTATION")
        return aim.put(profile.id, "GENERAL_CLOSED_PROFILE", [own, Ref(curves[0].id)])
    return aim.put(profile.id, placeholder_name(kind), [])
