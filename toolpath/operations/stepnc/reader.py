"""The ISO 14649 reader: a parsed Part 21 file (:mod:`.part21`) into the typed model of
:mod:`.model` (:func:`read_project`), every instance checked as it is read; errors name the
instance (#id), its type and the attribute, and workingsteps that need something unsupported are
left out with a warning naming it (see :mod:`.model` for the two kinds of trouble)."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ...engines import region as rg
from .errors import StepNcError, UnsupportedEntity
from .features import CircularPath, ClosedPocket, ClosedProfile, Feature, GeneralClosedProfile, GeneralPath, LinearPath, LinearProfile, PlanarFace, RectangularClosedProfile, RoundHole, SLOT_ENDS, Slot
from .geometry import BSplineCurve, Block, CURVE_TYPES, Circle, CompositeCurve, CompositeCurveSegment, Helix, Line, PLANE_TYPES, Placement, Plane, Polyline, TrimmedCurve, Vec3
from .model import LENGTH_TYPES, MAX_LENGTH, MAX_NAME, Project, Setup, Workingstep, Workpiece, Workplan
from .process import ApproachRetract, Bidirectional, BottomAndSideMilling, ContourBidirectional, ContourParallel, CuttingTool, DIMENSION_TYPES, DRILLING_TOOL_BODIES, DrillingOperation, DrillingTypeStrategy, FreeformOperation, MILLING_TOOL_BODIES, MachineFunctions, MachiningOperation, MillingStrategy, MillingTechnology, PlaneMilling, PlungeHelix, PlungeRamp, PlungeToolaxis, RapidMovement, TAPERED_BODIES, ToolBody, ToolDimension, Trajectory, Unidirectional
from .coordinates import plain_coordinates
from .part21 import UNKNOWN, UNSET, Enum, Instance, Part21File, Ref, Typed


def _type_name(instance) -> str:
    if isinstance(instance, Instance):
        return instance.type_name
    return "(" + " ".join(instance.type_names) + ")"


class _Reader:
    """Reads instances attribute by attribute; every error names the instance and attribute."""

    def __init__(self, part21: Part21File):
        self.part21 = part21
        self.memo: dict = {}
        self.warnings: list = []

    # ---- attribute access

    def raw(self, inst: Instance, index: int, name: str):
        if index >= len(inst.params):
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} (number {index + 1}) is missing; "
                              f"the instance has {len(inst.params)} attributes")
        return inst.params[index]

    def value(self, inst, index, name, optional=False):
        value = self.raw(inst, index, name)
        if value is UNSET:
            if optional:
                return None
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} is unset ($) but required")
        return value

    def entity(self, inst, index, name, types, optional=False, unsupported=False):
        """The instance an attribute refers to, which must be one of ``types``.  Another type is
        malformed data, or merely unsupported when ``unsupported`` (polymorphic attributes)."""
        value = self.value(inst, index, name, optional)
        if value is None:
            return None
        if not isinstance(value, Ref):
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} must refer to "
                              f"{' or '.join(types)}, found the value {value!r}")
        if value.id not in self.part21.instances:
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} refers to #{value.id}, "
                              "which is not defined")
        target = self.part21.instances[value.id]
        found = _type_name(target)
        if found not in types:
            if unsupported:
                raise UnsupportedEntity(found, target.id, f"as {name} of #{inst.id} {inst.type_name}")
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} must refer to "
                              f"{' or '.join(types)}, found #{target.id} {found}")
        return target

    def entities(self, inst, index, name, types=None) -> list:
        """The instances of a list attribute ($ is an empty list), each one of ``types`` if given."""
        value = self.value(inst, index, name, optional=True) or []
        if not isinstance(value, list) or not all(isinstance(item, Ref) for item in value):
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} must be a list of references, "
                              f"found {value!r}")
        instances = self.part21.instances
        if types is not None and all(ref.id in instances for ref in value):     # the common case at once
            targets = [instances[ref.id] for ref in value]
            if all(type(target) is Instance and target.type_name in types for target in targets):
                return targets
        targets = []
        for ref in value:
            if ref.id not in self.part21.instances:
                raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} refers to #{ref.id}, "
                                  "which is not defined")
            target = self.part21.instances[ref.id]
            if types is not None and _type_name(target) not in types:
                raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} must refer to "
                                  f"{' or '.join(types)}, found #{target.id} {_type_name(target)}")
            targets.append(target)
        return targets

    def number(self, inst, index, name, optional=False, positive=False) -> float | None:
        value = self.value(inst, index, name, optional)
        if isinstance(value, Typed):
            value = value.value
        if value is None:
            return None
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} must be a number, found {value!r}")
        if not math.isfinite(value) or (positive and value <= 0):
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} must be a "
                              f"{'positive' if positive else 'finite'} number, found {value!r}")
        return float(value)

    def length(self, inst, index, name, optional=False, sign=None) -> float | None:
        """A number, or a TOLERANCED_LENGTH_MEASURE / NUMERIC_PARAMETER holding one; at most
        MAX_LENGTH mm, so a mistyped exponent is an error rather than an hours-long toolpath.
        ``sign``: "above 0" (a depth, a diameter) or "0 or more" (an allowance), as ISO 14649 means it."""
        value = self.value(inst, index, name, optional)
        if not isinstance(value, Ref):
            size, holder = self.number(inst, index, name, optional), inst
        else:
            holder = self.entity(inst, index, name, LENGTH_TYPES)
            size = self.number(holder, 0, "theoretical_size") if holder.type_name == "TOLERANCED_LENGTH_MEASURE" \
                else self.number(holder, 1, "its_parameter_value")
        if size is not None and abs(size) > MAX_LENGTH:
            raise StepNcError(f"#{holder.id} {holder.type_name}: {name} {size:g} mm is larger than {MAX_LENGTH:g} mm")
        if size is not None and sign == "above 0" and size <= 0:
            raise StepNcError(f"#{holder.id} {holder.type_name}: {name} {size:g} mm must be above 0")
        if size is not None and sign == "0 or more" and size < 0:
            raise StepNcError(f"#{holder.id} {holder.type_name}: {name} {size:g} mm must be 0 or more")
        return size

    def text(self, inst, index, name) -> str:
        value = self.value(inst, index, name, optional=True)
        if value is None:
            return ""
        if not isinstance(value, str):
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} must be a string, found {value!r}")
        return value

    def enum(self, inst, index, name, optional=False) -> str | None:
        value = self.value(inst, index, name, optional)
        if value is None:
            return None
        if not isinstance(value, Enum):
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} must be an enumeration "
                              f"such as .LEFT., found {value!r}")
        return value.name

    def boolean(self, inst, index, name, optional=False) -> bool | None:
        value = self.value(inst, index, name, optional)
        if value is None or value == UNKNOWN:
            return None
        if not isinstance(value, bool):
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} must be .T. or .F., found {value!r}")
        return value

    def memoised(self, target, convert):
        if target.id not in self.memo:
            self.memo[target.id] = convert(target)
        return self.memo[target.id]

    # ---- geometry

    def point(self, inst, index, name, optional=False) -> Vec3 | None:
        target = self.entity(inst, index, name, ("CARTESIAN_POINT",), optional)
        return None if target is None else self.coordinates(target)

    def direction(self, inst, index, name, optional=False) -> Vec3 | None:
        target = self.entity(inst, index, name, ("DIRECTION",), optional)
        if target is None:
            return None

        def convert(t):
            ratios = np.array(self._coordinates(t, "direction_ratios"))
            size = np.linalg.norm(ratios)
            if size < 1e-12:
                raise StepNcError(f"#{t.id} DIRECTION: direction_ratios are all zero")
            return tuple(float(v) for v in ratios / size)
        return self.memoised(target, convert)

    def _coordinates(self, inst, name) -> Vec3:
        values = self.value(inst, 1, name)
        if (not isinstance(values, list) or not 1 <= len(values) <= 3
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)):
            raise StepNcError(f"#{inst.id} {inst.type_name}: attribute {name} must be 1 to 3 numbers, "
                              f"found {values!r}")
        for value in values:    # 1.0E999 reads as inf; 1.0E300 mm is a mistyped exponent, not a part
            if not math.isfinite(value) or (name == "coordinates" and abs(value) > MAX_LENGTH):
                raise StepNcError(f"#{inst.id} {inst.type_name}: {name} {value:g} is not a coordinate (at most "
                                  f"{MAX_LENGTH:g} mm from the origin)")
        return tuple(float(v) for v in values) + (0.0,) * (3 - len(values))

    def placement(self, inst, index, name, optional=False) -> Placement | None:
        target = self.entity(inst, index, name, ("AXIS2_PLACEMENT_3D",), optional)
        return None if target is None else self.memoised(target, self._placement)

    def _placement(self, inst) -> Placement:
        location = self.point(inst, 1, "location")
        axis = np.array(self.direction(inst, 2, "axis", optional=True) or (0.0, 0.0, 1.0))
        ref = np.array(self.direction(inst, 3, "ref_direction", optional=True) or (1.0, 0.0, 0.0))
        ref = ref - (ref @ axis) * axis
        if np.linalg.norm(ref) < 1e-9:
            raise StepNcError(f"#{inst.id} AXIS2_PLACEMENT_3D: ref_direction is parallel to axis")
        ref /= np.linalg.norm(ref)
        return Placement(inst.id, self.text(inst, 0, "name"), location, tuple(float(v) for v in axis),
                         tuple(float(v) for v in ref))

    def plane(self, inst, index, name) -> Plane:
        target = self.entity(inst, index, name, PLANE_TYPES)

        def convert(t):
            plane = Plane(t.id, self.text(t, 0, "name"), self.placement(t, 1, "position"))
            if not plane.position.is_vertical:
                raise UnsupportedEntity(t.type_name, t.id, "a plane that is not horizontal")
            return plane
        return self.memoised(target, convert)

    def curve(self, inst, index, name):
        target = self.entity(inst, index, name, CURVE_TYPES, unsupported=True)
        return self.memoised(target, self._curve)

    def _curve(self, t):
        if t.type_name == "POLYLINE":
            points = self.entities(t, 1, "points", ("CARTESIAN_POINT",))
            name = self.text(t, 0, "name")
            return Polyline(t.id, name, plain_coordinates(points) or tuple(self.coordinates(p) for p in points))
        if t.type_name == "CIRCLE":
            return self._circle(t)
        if t.type_name == "B_SPLINE_CURVE_WITH_KNOTS":
            return self._bspline(t)
        if t.type_name == "TRIMMED_CURVE":
            basis = self.entity(t, 1, "basis_curve", ("LINE", "CIRCLE", "HELIX"), unsupported=True)
            basis = self.memoised(basis, {"LINE": self._line, "CIRCLE": self._circle,
                                          "HELIX": self._helix}[basis.type_name])
            sense = self.boolean(t, 4, "sense_agreement")
            master = self.enum(t, 5, "master_representation", optional=True) or "UNSPECIFIED"
            return TrimmedCurve(t.id, self.text(t, 0, "name"), basis, self._trim(t, 2, "trim_1", master),
                                self._trim(t, 3, "trim_2", master), sense)
        segments = []
        for segment in self.entities(t, 1, "segments", ("COMPOSITE_CURVE_SEGMENT",)):
            segments.append(CompositeCurveSegment(self.enum(segment, 0, "transition", optional=True) or "",
                                                  self.boolean(segment, 1, "same_sense"),
                                                  self.curve(segment, 2, "parent_curve")))
        return CompositeCurve(t.id, self.text(t, 0, "name"), tuple(segments))

    def coordinates(self, point) -> Vec3:
        """The coordinates of a CARTESIAN_POINT instance."""
        return self.memoised(point, lambda p: self._coordinates(p, "coordinates"))

    def _line(self, t) -> Line:
        vector = self.entity(t, 2, "dir", ("VECTOR",))
        return Line(t.id, self.text(t, 0, "name"), self.point(t, 1, "pnt"),
                    self.direction(vector, 1, "orientation"), self.number(vector, 2, "magnitude"))

    def _bspline(self, t) -> BSplineCurve:
        """B_SPLINE_CURVE_WITH_KNOTS(name, degree, control_points_list, curve_form, closed_curve,
        self_intersect, knot_multiplicities, knots, knot_spec)."""
        degree = self.value(t, 1, "degree")
        points = tuple(self.coordinates(p) for p in self.entities(t, 2, "control_points_list", ("CARTESIAN_POINT",)))
        multiplicities, values = self.value(t, 6, "knot_multiplicities"), self.value(t, 7, "knots")
        if (not isinstance(degree, int) or isinstance(degree, bool) or not 1 <= degree <= 25
                or not isinstance(multiplicities, list) or not isinstance(values, list)
                or len(multiplicities) != len(values)
                or not all(isinstance(m, int) and not isinstance(m, bool) and 1 <= m <= degree + 1
                           for m in multiplicities)
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                           for v in values)):
            raise StepNcError(f"#{t.id} B_SPLINE_CURVE_WITH_KNOTS: degree, knot_multiplicities and knots must be a "
                              "degree of 1 to 25 and two lists of the same length (multiplicities 1 to degree + 1)")
        knots = tuple(float(v) for v, m in zip(values, multiplicities) for _ in range(m))
        if (len(knots) != len(points) + degree + 1 or any(b < a for a, b in zip(knots, knots[1:]))
                or len(points) > 100000 or not knots[len(points)] > knots[degree]):
            raise StepNcError(f"#{t.id} B_SPLINE_CURVE_WITH_KNOTS: {len(points)} control points of degree {degree} "
                              f"need {len(points) + degree + 1} non-decreasing knots, found {len(knots)}")
        polygon = float(np.linalg.norm(np.diff(np.array(points, float), axis=0), axis=1).sum())
        if not polygon <= MAX_LENGTH:
            raise StepNcError(f"#{t.id} B_SPLINE_CURVE_WITH_KNOTS: its control polygon is {polygon:g} mm long, more "
                              f"than {MAX_LENGTH:g} mm")
        return BSplineCurve(t.id, self.text(t, 0, "name"), degree, points, knots)

    def _helix(self, t) -> Helix:
        return Helix(t.id, self.text(t, 0, "name"), self.placement(t, 1, "position"), self.length(t, 2, "radius"),
                     self.number(t, 3, "pitch"))

    def _circle(self, t) -> Circle:
        return Circle(t.id, self.text(t, 0, "name"), self.placement(t, 1, "position"),
                      self.length(t, 2, "radius"))

    def _trim(self, t, index, name, master):
        """A trim select list holds a point, a PARAMETER_VALUE or both; ``master`` picks."""
        items = self.value(t, index, name)
        if not isinstance(items, list):
            raise StepNcError(f"#{t.id} TRIMMED_CURVE: attribute {name} must be a list, found {items!r}")
        points = []
        for ref in (v for v in items if isinstance(v, Ref)):
            target = self.part21.get(ref)
            if _type_name(target) != "CARTESIAN_POINT":
                raise StepNcError(f"#{t.id} TRIMMED_CURVE: attribute {name} must hold a CARTESIAN_POINT or a "
                                  f"PARAMETER_VALUE, found #{target.id} {_type_name(target)}")
            points.append(self.coordinates(target))
        parameters = [float(v.value) for v in items if isinstance(v, Typed) and v.type_name == "PARAMETER_VALUE"]
        if not points and not parameters:
            raise StepNcError(f"#{t.id} TRIMMED_CURVE: attribute {name} has neither a CARTESIAN_POINT nor "
                              f"a PARAMETER_VALUE: {items!r}")
        if parameters and (master == "PARAMETER" or not points):
            return parameters[0]
        return points[0]

    def closed_profile(self, inst, index, name) -> ClosedProfile:
        target = self.entity(inst, index, name, ("RECTANGULAR_CLOSED_PROFILE", "GENERAL_CLOSED_PROFILE"),
                             unsupported=True)

        def convert(t):
            placement = self.placement(t, 0, "placement", optional=True)
            if t.type_name == "RECTANGULAR_CLOSED_PROFILE":
                width, length = self.length(t, 1, "profile_width"), self.length(t, 2, "profile_length")
                for name, size in (("profile_width", width), ("profile_length", length)):
                    if size < 0:    # before: taken as its size without a word
                        raise StepNcError(f"#{t.id} RECTANGULAR_CLOSED_PROFILE: {name} {size:g} mm is negative")
                return RectangularClosedProfile(t.id, placement, width, length)
            return GeneralClosedProfile(t.id, placement, self.curve(t, 1, "closed_profile_shape"))
        return self.memoised(target, convert)

    # ---- features

    def feature(self, inst, index, name) -> Feature:
        target = self.entity(inst, index, name, ("PLANAR_FACE", "CLOSED_POCKET", "ROUND_HOLE", "SLOT"),
                             unsupported=True)
        return self.memoised(target, self._feature)

    def _feature(self, t) -> Feature:
        placement = self.placement(t, 3, "feature_placement")
        if not placement.is_vertical:
            raise UnsupportedEntity(t.type_name, t.id, f"its placement #{placement.id} tilts the tool axis; "
                                    "only features machined along +Z are supported")
        depth = self.plane(t, 4, "depth")
        its_id = self.text(t, 0, "its_id")
        if t.type_name == "PLANAR_FACE":
            if self.value(t, 7, "face_boundary", optional=True) is not None:
                raise UnsupportedEntity(t.type_name, t.id, "a face_boundary")
            self._no_bosses(t, 8)
            path = self.entity(t, 5, "course_of_travel", ("LINEAR_PATH",), unsupported=True)
            profile = self.entity(t, 6, "removal_boundary", ("LINEAR_PROFILE",), unsupported=True)
            course = LinearPath(path.id, self.placement(path, 0, "placement", optional=True),
                                self.length(path, 1, "distance"), self.direction(path, 2, "its_direction"))
            boundary = LinearProfile(profile.id, self.placement(profile, 0, "placement", optional=True),
                                     self.length(profile, 1, "profile_length"))
            face = PlanarFace(t.id, its_id, placement, depth, course, boundary)
            if abs(rg.signed_area(face.corners())) < 1e-9:
                raise StepNcError(f"#{t.id} PLANAR_FACE: the removal boundary #{profile.id} runs along the course "
                                  f"of travel #{path.id}, so the face has no area")
            return face
        if t.type_name == "CLOSED_POCKET":
            self._no_bosses(t, 5)
            slope = self.number(t, 6, "slope", optional=True)
            if slope:
                raise UnsupportedEntity(t.type_name, t.id, f"slanted walls (slope {slope:g} degrees)")
            bottom = self.entity(t, 7, "bottom_condition", ("PLANAR_POCKET_BOTTOM_CONDITION",
                                                             "THROUGH_POCKET_BOTTOM_CONDITION"), unsupported=True)
            pocket = ClosedPocket(t.id, its_id, placement, depth, bottom.type_name,
                                  self.length(t, 8, "planar_radius", optional=True),
                                  self.length(t, 9, "orthogonal_radius", optional=True),
                                  self.closed_profile(t, 10, "feature_boundary"))
            return self._profile_placement(t, pocket)
        if t.type_name == "SLOT":
            return self._slot(t, its_id, placement, depth)
        if self.value(t, 6, "change_in_diameter", optional=True) is not None:
            raise UnsupportedEntity(t.type_name, t.id, "a tapered hole (change_in_diameter)")
        bottom = self.value(t, 7, "bottom_condition")
        bottom_name = _type_name(self.part21.get(bottom)) if isinstance(bottom, Ref) else ""
        return RoundHole(t.id, its_id, placement, depth, self.length(t, 5, "diameter", sign="above 0"), bottom_name)

    def _slot(self, t, its_id, placement, depth) -> Slot:
        """SLOT(its_id, its_workpiece, its_operations, feature_placement, depth, course_of_travel,
        swept_shape, end_conditions)."""
        path = self.entity(t, 5, "course_of_travel", ("LINEAR_PATH", "PARTIAL_CIRCULAR_PATH",
                                                      "COMPLETE_CIRCULAR_PATH", "GENERAL_PATH"), unsupported=True)
        course = self._travel_path(path)
        shape = self.entity(t, 6, "swept_shape", ("SQUARE_U_PROFILE",), unsupported=True)
        if self.value(shape, 0, "placement", optional=True) is not None:
            offset = self.placement(shape, 0, "placement")
            if not np.allclose(offset.location, 0.0) or not np.allclose(offset.ref_direction, (1.0, 0.0, 0.0)):
                raise UnsupportedEntity(shape.type_name, shape.id, "a profile placed off the slot's path")
        width = self.length(shape, 1, "width")
        if width <= 0:
            raise StepNcError(f"#{shape.id} SQUARE_U_PROFILE: width must be positive, found {width:g}")
        radii = [self.length(shape, 2, "first_radius", optional=True),
                 self.length(shape, 4, "second_radius", optional=True)]
        for index, name in ((3, "first_angle"), (5, "second_angle")):
            angle = self.number(shape, index, name, optional=True)
            if angle not in (None, 0.0, 90.0):
                raise UnsupportedEntity(shape.type_name, shape.id, f"slanted walls ({name} {angle:g} degrees)")
        ends = [_type_name(end) for end in self.entities(t, 7, "end_conditions")]
        for end in ends:
            if end not in SLOT_ENDS:
                raise UnsupportedEntity(t.type_name, t.id, f"a {end}")
        ends = (ends + ["RADIUSED_SLOT_END_TYPE"] * 2)[:2]   # not given: closed, as the tool's radius leaves it
        floor = max((r for r in radii if r), default=None)
        return Slot(t.id, its_id, placement, depth, course, width, floor, tuple(ends))

    def _travel_path(self, path):
        """LINEAR_PATH(placement, distance, its_direction), PARTIAL_CIRCULAR_PATH(placement, radius,
        sweep_angle), COMPLETE_CIRCULAR_PATH(placement, radius) or GENERAL_PATH(placement, swept_path)."""
        placement = self.placement(path, 0, "placement", optional=True)
        if placement is not None and not placement.is_vertical:
            raise UnsupportedEntity(path.type_name, path.id, "a path whose placement tilts the tool axis")
        if path.type_name == "LINEAR_PATH":
            course = LinearPath(path.id, placement, self.length(path, 1, "distance"),
                                self.direction(path, 2, "its_direction"))
            if course.distance <= 0:
                raise StepNcError(f"#{path.id} LINEAR_PATH: the slot's distance must be positive, found "
                                  f"{course.distance:g}")
            return course
        if path.type_name == "GENERAL_PATH":
            course = GeneralPath(path.id, placement, self.curve(path, 1, "swept_path"))
            if len(course.local_points()) < 2 or np.ptp(course.local_points()[:, :2], axis=0).max() < 1e-6:
                raise StepNcError(f"#{path.id} GENERAL_PATH: the swept_path has no length")
            if np.ptp(course.local_points()[:, 2]) > 1e-6:
                raise UnsupportedEntity(path.type_name, path.id, "a swept_path that is not level")
            return course
        radius = self.length(path, 1, "radius")
        sweep = 360.0 if path.type_name == "COMPLETE_CIRCULAR_PATH" else self.number(path, 2, "sweep_angle")
        if radius <= 0 or not 0 < abs(sweep) <= 360.0:
            raise StepNcError(f"#{path.id} {path.type_name}: radius must be positive and sweep_angle within "
                              f"0 to 360 degrees, found radius {radius:g} and sweep {sweep:g}")
        return CircularPath(path.id, placement, radius, sweep)

    def _profile_placement(self, t, pocket: ClosedPocket) -> ClosedPocket:
        """ISO 14649-10 places a profile in the feature's coordinates ("in reference to the
        manufacturing_feature; if not given, at its zero point"), so the outline is the feature
        placement composed with the profile's.  Some generators write the feature's absolute
        placement again as the profile's; composed, the pocket lands twice as far from the origin.
        When the composed outline leaves the workpiece's BLOCK and the profile placement read as
        absolute keeps it on the stock (or, with no BLOCK, when the profile repeats the feature's
        location), the absolute reading is taken, with a warning naming the feature.  A pocket off
        the stock in both readings is cut as written, with a warning."""
        profile = pocket.feature_boundary
        own = profile.placement
        if own is None or np.allclose(own.location[:2], 0.0, atol=1e-9):
            return pocket
        frame = pocket.feature_placement
        rotation = frame.matrix()
        relative = Placement(own.id, own.name,
                             tuple(float(v) for v in rotation.T @ (np.array(own.location) - frame.location)),
                             tuple(float(v) for v in rotation.T @ np.array(own.axis)),
                             tuple(float(v) for v in rotation.T @ np.array(own.ref_direction)))
        absolute = replace(pocket, feature_boundary=replace(profile, placement=relative))
        what = f"#{t.id} CLOSED_POCKET '{pocket.its_id}'"
        block = self._feature_block(t)
        holes = self._floor_holes(pocket)
        if holes and (block is None or _beyond(absolute.outline(), block) <= POCKET_OFF_STOCK):
            inside_absolute, inside_composed = (_inside(candidate.outline(), holes) for candidate in (absolute, pocket))
            if inside_absolute and not inside_composed:
                self.warnings.append(
                    f"{what}: the holes {', '.join(f'#{h} at {_xy(c)}' for h, c in holes)} start on its floor "
                    f"(Z {pocket.bottom_z:g}) and lie in it only with its profile's placement #{own.id} read as "
                    f"absolute, not composed with the pocket's #{frame.id}; read so (the generator wrote the "
                    f"pocket's placement twice): the pocket is cut at {_xy(absolute.outline().mean(axis=0))}")
                return absolute
            if inside_composed:
                return pocket
        if block is None:
            if np.allclose(own.location, frame.location, atol=1e-6):
                self.warnings.append(
                    f"{what}: its profile #{profile.id} repeats the pocket's placement #{frame.id} "
                    f"({_xy(frame.location)}); read as one placement (the pocket at {_xy(frame.location)}), not "
                    f"composed (which would put it at {_xy(pocket.outline().mean(axis=0))}); the file gives no "
                    "stock BLOCK to check against")
                return absolute
            return pocket
        composed_off = _beyond(pocket.outline(), block)
        if composed_off <= POCKET_OFF_STOCK:
            return pocket
        absolute_off = _beyond(absolute.outline(), block)
        if absolute_off <= POCKET_OFF_STOCK:
            self.warnings.append(
                f"{what}: composed with its profile's placement #{own.id} the pocket would reach "
                f"{composed_off:.3g} mm beyond the stock BLOCK #{block.id}; the profile's placement is read as "
                f"absolute (the generator wrote the pocket's placement twice): the pocket is cut at "
                f"{_xy(absolute.outline().mean(axis=0))} on the stock")
            return absolute
        self.warnings.append(
            f"{what}: reaches {composed_off:.3g} mm beyond the stock BLOCK #{block.id} (and "
            f"{absolute_off:.3g} mm with its profile's placement read as absolute); cut as written, check the file")
        return pocket

    def _floor_holes(self, pocket: ClosedPocket) -> list:
        """[(id, centre xy)] of the file's ROUND_HOLEs that start on the pocket's floor (drilled from it)."""
        found = []
        for hole in self.part21.by_type("ROUND_HOLE"):
            if not isinstance(hole, Instance):
                continue
            try:
                placement = self.placement(hole, 3, "feature_placement")
            except (StepNcError, UnsupportedEntity):
                continue
            if placement.is_vertical and abs(placement.location[2] - pocket.bottom_z) < 1e-6:
                found.append((hole.id, placement.location[:2]))
        return found

    def _feature_block(self, t):
        """The BLOCK of the feature's workpiece (attribute its_workpiece), or None."""
        try:
            piece = self.entity(t, 1, "its_workpiece", ("WORKPIECE",), optional=True, unsupported=True)
        except (UnsupportedEntity, StepNcError):
            return None
        if piece is None:
            return None
        return self.memoised(piece, self.workpiece).its_bounding_geometry

    def _no_bosses(self, t, index):
        bosses = self.value(t, index, "its_boss", optional=True)
        if bosses:
            raise UnsupportedEntity(t.type_name, t.id, "bosses (islands) in the feature")

    # ---- tools, technology, strategies

    def tool(self, inst, index, name) -> CuttingTool:
        target = self.entity(inst, index, name, ("MILLING_CUTTING_TOOL",), unsupported=True)
        return self.memoised(target, self._tool)

    def _tool(self, t) -> CuttingTool:
        body = self.entity(t, 1, "its_tool_body", MILLING_TOOL_BODIES + DRILLING_TOOL_BODIES, unsupported=True)
        dim = self.entity(body, 0, "dimension", DIMENSION_TYPES)
        dimension = ToolDimension(self.number(dim, 0, "diameter"),
                                  *(self.number(dim, i, n, optional=True) for i, n in enumerate(
                                      ("tool_top_angle", "tool_circumference_angle", "cutting_edge_length",
                                       "edge_radius", "edge_center_vertical", "edge_center_horizontal"), 1)))
        if dimension.diameter <= 0:
            raise StepNcError(f"#{dim.id} {dim.type_name}: diameter must be positive, found {dimension.diameter:g}")
        teeth = self.value(body, 1, "number_of_teeth", optional=True)
        taper = self.number(body, 5, "taper_angle", optional=True) if body.type_name in TAPERED_BODIES else None
        if taper:
            raise UnsupportedEntity(body.type_name, body.id, f"a taper angle of {taper:g} degrees")
        return CuttingTool(t.id, self.text(t, 0, "its_id"),
                           ToolBody(body.id, body.type_name, dimension, teeth if isinstance(teeth, int) else None,
                                    taper),
                           self.number(t, 3, "overall_assembly_length", optional=True))

    def technology(self, inst, index, name) -> MillingTechnology:
        target = self.entity(inst, index, name, ("MILLING_TECHNOLOGY",), unsupported=True)
        return self.memoised(target, lambda t: MillingTechnology(
            t.id, self.number(t, 0, "feedrate", optional=True),
            self.enum(t, 1, "feedrate_reference", optional=True) or "",
            self.number(t, 2, "cutspeed", optional=True), self.number(t, 3, "spindle", optional=True),
            self.number(t, 4, "feedrate_per_tooth", optional=True)))

    def machine_functions(self, inst, index, name) -> MachineFunctions | None:
        target = self.entity(inst, index, name, ("MILLING_MACHINE_FUNCTIONS",), optional=True, unsupported=True)
        if target is None:
            return None
        return self.memoised(target, lambda t: MachineFunctions(t.id, bool(self.boolean(t, 0, "coolant"))))

    def milling_strategy(self, inst, index, name) -> MillingStrategy | None:
        target = self.entity(inst, index, name, ("BIDIRECTIONAL", "BIDIRECTIONAL_MILLING", "UNIDIRECTIONAL",
                                                 "UNIDIRECTIONAL_MILLING", "CONTOUR_PARALLEL", "CONTOUR_BIDIRECTIONAL",
                                                 "BIDIRECTIONAL_CONTOUR"),
                             optional=True, unsupported=True)
        if target is None:
            return None

        def convert(t):
            overlap = self.number(t, 0, "overlap", optional=True)
            if overlap is not None and not 0 < overlap <= 1:     # a ratio of the tool diameter
                raise StepNcError(f"#{t.id} {t.type_name}: overlap {overlap:g} must be above 0 and at most 1 "
                                  "(a ratio of the tool diameter)")
            multiple = self.boolean(t, 1, "allow_multiple_passes", optional=True)
            if t.type_name in ("CONTOUR_BIDIRECTIONAL", "BIDIRECTIONAL_CONTOUR"):
                return ContourBidirectional(overlap, multiple, self.direction(t, 2, "feed_direction", optional=True),
                                            self.enum(t, 3, "stepover_direction", optional=True), None,
                                            self.enum(t, 4, "rotation_direction", optional=True),
                                            self.enum(t, 5, "spiral_cutmode", optional=True),
                                            t.type_name == "CONTOUR_BIDIRECTIONAL")
            if t.type_name.startswith("BIDIRECTIONAL"):
                return Bidirectional(overlap, multiple, self.direction(t, 2, "feed_direction", optional=True),
                                     self.enum(t, 3, "stepover_direction", optional=True),
                                     self.enum(t, 4, "its_stroke_connection_strategy", optional=True))
            if t.type_name.startswith("UNIDIRECTIONAL"):
                return Unidirectional(overlap, multiple, self.direction(t, 2, "feed_direction", optional=True),
                                      self.enum(t, 3, "cutmode", optional=True))
            return ContourParallel(overlap, multiple, self.enum(t, 2, "rotation_direction"),
                                   self.enum(t, 3, "cutmode", optional=True))
        return self.memoised(target, convert)

    def approach_retract(self, inst, index, name) -> ApproachRetract | None:
        target = self.entity(inst, index, name, ("PLUNGE_TOOLAXIS", "PLUNGE_RAMP", "PLUNGE_HELIX"),
                             optional=True, unsupported=True)
        if target is None:
            return None

        def convert(t):
            orientation = self.direction(t, 0, "tool_orientation", optional=True)
            if t.type_name == "PLUNGE_TOOLAXIS":
                return PlungeToolaxis(orientation)
            angle = self.number(t, 1 if t.type_name == "PLUNGE_RAMP" else 2, "angle")
            if not 0 < angle <= 90:
                raise StepNcError(f"#{t.id} {t.type_name}: angle must be above 0 and at most 90 degrees, "
                                  f"found {angle:g}")
            if t.type_name == "PLUNGE_RAMP":
                return PlungeRamp(orientation, angle)
            return PlungeHelix(orientation, self.length(t, 1, "radius"), angle)
        return self.memoised(target, convert)

    def drilling_strategy(self, inst, index, name) -> DrillingTypeStrategy | None:
        target = self.entity(inst, index, name, ("DRILLING_TYPE_STRATEGY",), optional=True, unsupported=True)
        if target is None:
            return None
        names = ("reduced_cut_at_start", "reduced_feed_at_start", "depth_of_start", "reduced_cut_at_end",
                 "reduced_feed_at_end", "depth_of_end")

        def convert(t):
            values = [self.number(t, i, n, optional=True, positive=True) for i, n in enumerate(names)]
            # ISO 14649-11's drilling_type_strategy: the reduced cuts and feeds are positive_ratio_measure
            # (ISO 10303-41: a ratio, 0.5 for half), "reduced" from the programmed value; the standard's
            # prose calls them "a percentage of the programmed value" and files of the 0..100 kind exist
            # (NIST's ex1 before its note 12), so a value above 1 is neither read as percent nor as a
            # faster feed: it is refused by name
            for name, value in zip(names, values):
                if name.startswith("reduced") and value is not None and value > 1:
                    raise StepNcError(f"#{t.id} {t.type_name}: {name} {value:g} is above 1: it is a ratio of the "
                                      f"programmed value (0.5 for half), not a percentage; write {value / 100:g} "
                                      f"for {value:g} %")
            return DrillingTypeStrategy(*values)
        return self.memoised(target, convert)

    # ---- operations

    def operation(self, inst, index, name) -> MachiningOperation:
        target = self.entity(inst, index, name, ("PLANE_ROUGH_MILLING", "PLANE_FINISH_MILLING",
                                                 "BOTTOM_AND_SIDE_ROUGH_MILLING", "BOTTOM_AND_SIDE_FINISH_MILLING",
                                                 "DRILLING", "CENTER_DRILLING", "REAMING", "FREEFORM_OPERATION"),
                             unsupported=True)
        return self.memoised(target, self._operation)

    def _operation(self, t) -> MachiningOperation:
        # machining_operation: its_toolpath, its_tool_direction, its_id, retract_plane, start_point,
        # its_tool, its_technology, its_machine_functions; milling_machining_operation: overcut_length
        common = (t.id, t.type_name, self.text(t, 2, "its_id"), self.length(t, 3, "retract_plane", optional=True),
                  self.tool(t, 5, "its_tool"), self.technology(t, 6, "its_technology"),
                  self.machine_functions(t, 7, "its_machine_functions"))
        if t.type_name == "FREEFORM_OPERATION":
            if self.value(t, 0, "its_toolpath", optional=True) is None:
                strategy = self.value(t, 11, "its_machining_strategy", optional=True)
                raise UnsupportedEntity(t.type_name, t.id, "no explicit toolpaths (its_toolpath); a freeform "
                                        f"strategy{'' if strategy is None else ' ' + repr(strategy)} is not planned")
            return FreeformOperation(*common, self.toolpaths(t, 0, "its_toolpath"))
        if t.type_name in ("DRILLING", "CENTER_DRILLING", "REAMING"):
            drilling = common + (self.length(t, 9, "cutting_depth", optional=True, sign="above 0"),
                                 self.length(t, 10, "previous_diameter", optional=True),
                                 self.number(t, 11, "dwell_time_bottom", optional=True),
                                 self.number(t, 12, "feed_on_retract", optional=True),
                                 self.drilling_strategy(t, 13, "its_machining_strategy"))
            overcut = self.length(t, 8, "overcut_length", optional=True, sign="0 or more")
            if t.type_name == "REAMING":
                return DrillingOperation(*drilling, self.boolean(t, 14, "spindle_stop_at_bottom"),
                                         overcut_length=overcut)
            return DrillingOperation(*drilling, overcut_length=overcut)
        milling = common + (self.approach_retract(t, 9, "approach"), self.approach_retract(t, 10, "retract"),
                            self.milling_strategy(t, 11, "its_machining_strategy"),
                            self.length(t, 12, "axial_cutting_depth", optional=True, sign="above 0"))
        if t.type_name.startswith("PLANE_"):
            return PlaneMilling(*milling, self.length(t, 13, "allowance_bottom", optional=True, sign="0 or more"))
        return BottomAndSideMilling(*milling, self.length(t, 13, "radial_cutting_depth", optional=True, sign="above 0"),
                                    self.length(t, 14, "allowance_side", optional=True, sign="0 or more"),
                                    self.length(t, 15, "allowance_bottom", optional=True, sign="0 or more"))

    def toolpaths(self, inst, index, name) -> tuple:
        """The CUTTER_LOCATION_TRAJECTORYs of a TOOLPATH_LIST."""
        listing = self.entity(inst, index, name, ("TOOLPATH_LIST",))
        found = []
        for t in self.entities(listing, 0, "its_list"):
            if t.type_name != "CUTTER_LOCATION_TRAJECTORY":
                raise UnsupportedEntity(t.type_name, t.id, f"in the toolpath list #{listing.id}")
            axis = self.value(t, 7, "its_toolaxis", optional=True)
            if axis is not None:
                raise UnsupportedEntity(t.type_name, t.id, "a tool axis curve (its_toolaxis): only +Z is machined")
            speed = self.value(t, 2, "its_speed", optional=True)
            if speed is not None and speed != Enum("RAPID"):
                raise UnsupportedEntity(t.type_name, t.id, f"a speed profile {speed!r} (its_speed)")
            technology = None if self.value(t, 3, "its_technology", optional=True) is None \
                else self.technology(t, 3, "its_technology")
            forward = self.boolean(t, 5, "its_direction", optional=True)
            found.append(Trajectory(t.id, speed == Enum("RAPID"), technology, forward is not False,
                                    self.curve(t, 6, "basiccurve")))
        return tuple(found)

    def rapid_movement(self, t) -> RapidMovement:
        return RapidMovement(t.id, self.text(t, 0, "its_id"), self.toolpaths(t, 2, "its_toolpath"))

    # ---- executables

    def step_name(self, t, warn=True, what="workingstep") -> str:
        """A workingstep's (or the project's) its_id, at most MAX_NAME characters and "..." (it is
        written as a comment)."""
        name = self.text(t, 0, "its_id")
        if len(name) <= MAX_NAME:
            return name
        if warn and what == "project":
            self.warnings.append(f"project #{t.id}: its name is {len(name)} characters; the first {MAX_NAME} "
                                 "are used, followed by ...")
        elif warn:
            self.warnings.append(f"workingstep #{t.id}: its name is {len(name)} characters; the first {MAX_NAME} "
                                 "are used, followed by ...")
        return name[:MAX_NAME] + "..."

    def workingstep(self, t) -> Workingstep:
        return Workingstep(t.id, self.step_name(t), self.plane(t, 1, "its_secplane"),
                           self.feature(t, 2, "its_feature"), self.operation(t, 3, "its_operation"))

    def workplan(self, t, seen=()) -> Workplan:
        if t.id in seen:
            raise StepNcError(f"#{t.id} WORKPLAN contains itself (through #{seen[-1]})")
        elements = []
        for element in self.entities(t, 1, "its_elements"):
            if _type_name(element) == "WORKPLAN":
                elements.append(self.workplan(element, seen + (t.id,)))
            elif _type_name(element) == "MACHINING_WORKINGSTEP":
                try:
                    elements.append(self.workingstep(element))
                except UnsupportedEntity as error:
                    self.warnings.append(f"workingstep #{element.id} '{self.step_name(element, warn=False)}' "
                                         f"skipped: {error}")
            elif _type_name(element) == "RAPID_MOVEMENT":
                try:
                    rapid = self.rapid_movement(element)
                except UnsupportedEntity as error:
                    self.warnings.append(f"rapid movement #{element.id} '{self.text(element, 0, 'its_id')}' "
                                         f"skipped: {error}")
                    continue
                if elements and isinstance(elements[-1], Workingstep):
                    elements[-1] = replace(elements[-1], rapids_after=elements[-1].rapids_after + (rapid,))
                else:
                    self.warnings.append(f"rapid movement #{element.id} '{rapid.its_id}' skipped: no workingstep "
                                         "before it in its workplan, so no tool to move")
            else:
                self.warnings.append(f"#{element.id} {_type_name(element)} in workplan #{t.id} skipped: "
                                     "only workingsteps and workplans are supported")
        setup = self.entity(t, 3, "its_setup", ("SETUP",), optional=True)
        if setup is not None:
            try:
                setup = Setup(setup.id, self.text(setup, 0, "its_id"), self.placement(setup, 1, "its_origin", True),
                              self.plane(setup, 2, "its_secplane"))
            except UnsupportedEntity as error:
                self.warnings.append(f"setup #{setup.id} of workplan #{t.id} left out: {error}")
                setup = None
        return Workplan(t.id, self.text(t, 0, "its_id"), tuple(elements), setup)

    def workpiece(self, t) -> Workpiece:
        try:
            block = self.entity(t, 5, "its_bounding_geometry", ("BLOCK",), optional=True, unsupported=True)
        except UnsupportedEntity as error:
            self.warnings.append(f"the bounding geometry of workpiece #{t.id} is left out: {error}")
            block = None
        if block is not None:
            block = Block(block.id, self.text(block, 0, "name"), self.placement(block, 1, "position"),
                          self.length(block, 2, "x"), self.length(block, 3, "y"), self.length(block, 4, "z"))
        clamps = self.entities(t, 6, "clamping_positions", ("CARTESIAN_POINT",))
        return Workpiece(t.id, self.text(t, 0, "its_id"), self.number(t, 2, "global_tolerance", optional=True),
                         block, tuple(self.coordinates(point) for point in clamps))


# A pocket outline may reach this far (mm) beyond the stock BLOCK before its placement is questioned.
POCKET_OFF_STOCK = 1e-3


def _xy(point) -> str:
    return f"X{float(point[0]):g} Y{float(point[1]):g}"


def _inside(outline, holes) -> bool:
    """Whether every hole centre lies inside the outline."""
    region = rg.from_loops([np.asarray(outline, float)[:, :2]])
    return bool(rg.contains_points(region, np.array([c[:2] for _, c in holes], float)).all())


def _beyond(outline, block: Block) -> float:
    """How far (mm) an XY outline reaches outside the block's XY rectangle (0: inside)."""
    (x0, y0, _), (x1, y1, _) = block.box()
    points = np.asarray(outline, float)[:, :2]
    over = np.maximum.reduce([x0 - points[:, 0], points[:, 0] - x1, y0 - points[:, 1], points[:, 1] - y1,
                              np.zeros(len(points))])
    return float(over.max())


def read_project(part21: Part21File) -> tuple:
    """(Project, warnings) from a parsed file.

    Raises StepNcError for malformed data.  Unsupported workingsteps and workplan elements
    are left out of the model, each with a warning naming the entity type and instance.
    """
    projects = part21.by_type("PROJECT")
    if not projects and part21.by_type("MACHINING_PROJECT"):
        from .ap238 import to_arm  # the AP238 integrated form: read as its ISO 14649 rendition
        part21 = to_arm(part21)
        projects = part21.by_type("PROJECT")
    if len(projects) != 1:
        raise StepNcError(f"an ISO 14649 file needs exactly one PROJECT, this one has {len(projects)}")
    reader = _Reader(part21)
    t = projects[0]
    main = reader.entity(t, 1, "main_workplan", ("WORKPLAN",))
    workpieces = tuple(reader.memoised(piece, reader.workpiece)
                       for piece in reader.entities(t, 2, "its_workpieces", ("WORKPIECE",)))
    project = Project(t.id, reader.step_name(t, what="project"), reader.workplan(main), workpieces)
    return project, reader.warnings
