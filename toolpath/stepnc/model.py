"""ISO 14649-10/-11 (STEP-NC, milling) entities as a small typed model.

:func:`read_project` turns a parsed Part 21 file (:mod:`.part21`) into frozen dataclasses:
PROJECT -> WORKPLAN -> MACHINING_WORKINGSTEP (security plane, feature, operation) with the
features, operations, strategies, tools and technology a 2.5-D job needs.  Each class keeps
the attributes it uses, named and ordered as in the standard; ``id`` is the instance number.

Spellings found in the wild are all accepted: BIDIRECTIONAL / BIDIRECTIONAL_MILLING,
UNIDIRECTIONAL / UNIDIRECTIONAL_MILLING, TOOL_DIMENSION / MILLING_TOOL_DIMENSION,
ELEMENTARY_SURFACE / PLANE (NIST's toolkit rewrote the ISO examples with the second names).

Two kinds of trouble are kept apart:

* :class:`StepNcError` (a ValueError): the file is malformed, e.g. a placement attribute that
  refers to a CARTESIAN_POINT, or a missing attribute.  The message names the instance (#id),
  its type and the attribute.
* :class:`UnsupportedEntity`: the file is fine but uses something this converter does not
  machine (a SLOT, a B-spline outline, a tilted feature).  The reader skips the workingstep
  that needs it and records a warning; the rest of the workplan still converts.

Units: lengths in mm, angles in degrees, feed in m/s and spindle in rev/s as in the file
(:class:`MillingTechnology` converts to mm/min and rpm).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Union

import numpy as np

from .. import region as rg
from ..errors import InputError
from .part21 import UNKNOWN, UNSET, Enum, Instance, Part21File, Ref, Typed

# Chord error (mm) when arcs and circles of an outline are turned into polygons.
CHORD_TOLERANCE = 0.001

Vec3 = tuple  # (x, y, z)


class StepNcError(InputError):
    """Malformed ISO 14649 data; the message names the instance and the attribute."""


class UnsupportedEntity(Exception):
    """Valid data that this converter cannot machine (the workingstep is skipped)."""

    def __init__(self, type_name: str, instance_id: int, detail: str = ""):
        self.type_name = type_name
        self.instance_id = instance_id
        self.detail = detail
        text = f"{type_name} #{instance_id} is not supported"
        super().__init__(text + (f" ({detail})" if detail else ""))


# --------------------------------------------------------------------------- geometry


@dataclass(frozen=True)
class Placement:
    """AXIS2_PLACEMENT_3D: a right-handed frame; ``ref_direction`` is made orthogonal to ``axis``."""

    id: int
    name: str
    location: Vec3
    axis: Vec3 = (0.0, 0.0, 1.0)
    ref_direction: Vec3 = (1.0, 0.0, 0.0)

    def matrix(self) -> np.ndarray:
        """3x3 with columns x, y, z of the frame in its parent's coordinates."""
        z = np.array(self.axis, float)
        x = np.array(self.ref_direction, float)
        return np.column_stack([x, np.cross(z, x), z])

    def to_parent(self, points) -> np.ndarray:
        """(n, 2) or (n, 3) local points -> (n, 3) parent points."""
        pts = np.asarray(points, float).reshape(len(points), -1)
        if pts.shape[1] == 2:
            pts = np.column_stack([pts, np.zeros(len(pts))])
        return pts @ self.matrix().T + np.array(self.location, float)

    def direction_to_parent(self, vector) -> np.ndarray:
        return self.matrix() @ np.array(vector, float)

    @property
    def is_vertical(self) -> bool:
        """True when the local z axis is the machine's +Z (what a 3-axis mill can do)."""
        return abs(self.axis[2] - 1.0) < 1e-9


IDENTITY = Placement(0, "", (0.0, 0.0, 0.0))


@dataclass(frozen=True)
class Plane:
    """PLANE or ELEMENTARY_SURFACE (security plane, depth plane)."""

    id: int
    name: str
    position: Placement


@dataclass(frozen=True)
class Block:
    """BLOCK (ISO 10303-42): a box of size x, y, z from the corner at ``position``."""

    id: int
    name: str
    position: Placement
    x: float
    y: float
    z: float

    def box(self) -> tuple:
        """((xmin, ymin, zmin), (xmax, ymax, zmax)) in the parent coordinates."""
        corners = np.array([[i * self.x, j * self.y, k * self.z] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
        world = self.position.to_parent(corners)
        return tuple(world.min(axis=0)), tuple(world.max(axis=0))


# --------------------------------------------------------------------------- curves


def _arc_points(centre, x_axis, y_axis, radius, start_deg, sweep_deg) -> np.ndarray:
    """Points of an arc in the plane of (x_axis, y_axis), chord error <= CHORD_TOLERANCE."""
    if radius <= CHORD_TOLERANCE:
        count = 8
    else:
        step = 2 * math.acos(1 - CHORD_TOLERANCE / radius)
        count = max(1, math.ceil(abs(math.radians(sweep_deg)) / step))
    angles = np.radians(start_deg + sweep_deg * np.linspace(0, 1, count + 1))
    return (np.asarray(centre)[None, :] + radius * np.cos(angles)[:, None] * np.asarray(x_axis)[None, :]
            + radius * np.sin(angles)[:, None] * np.asarray(y_axis)[None, :])


@dataclass(frozen=True)
class Polyline:
    id: int
    name: str
    points: tuple  # ((x, y, z), ...)

    def sample(self) -> np.ndarray:
        return np.array(self.points, float)


@dataclass(frozen=True)
class Line:
    """LINE(pnt, dir): the point at parameter t is pnt + t * magnitude * orientation."""

    id: int
    name: str
    pnt: Vec3
    orientation: Vec3
    magnitude: float

    def at(self, t: float) -> np.ndarray:
        return np.array(self.pnt) + t * self.magnitude * np.array(self.orientation)

    def parameter(self, point) -> float:
        offset = np.asarray(point, float) - np.array(self.pnt)
        return float(offset @ np.array(self.orientation)) / self.magnitude


@dataclass(frozen=True)
class Circle:
    """CIRCLE in the xy plane of ``position``; the parameter is the angle in degrees."""

    id: int
    name: str
    position: Placement
    radius: float

    def frame(self):
        m = self.position.matrix()
        return np.array(self.position.location, float), m[:, 0], m[:, 1]

    def parameter(self, point) -> float:
        centre, x, y = self.frame()
        offset = np.asarray(point, float) - centre
        return math.degrees(math.atan2(offset @ y, offset @ x))

    def sample(self) -> np.ndarray:
        centre, x, y = self.frame()
        return _arc_points(centre, x, y, self.radius, 0.0, 360.0)


@dataclass(frozen=True)
class Helix:
    """HELIX(name, position, radius, pitch) as NIST's ISO 14649 toolkit writes it (ex1E): turns about
    the z axis of ``position``, rising ``pitch`` per counter-clockwise turn.  Only trimmed by points."""

    id: int
    name: str
    position: Placement
    radius: float
    pitch: float

    def frame(self):
        m = self.position.matrix()
        return np.array(self.position.location, float), m[:, 0], m[:, 1]


@dataclass(frozen=True)
class TrimmedCurve:
    """TRIMMED_CURVE of a LINE or CIRCLE.  A trim is a point (x, y, z) or a parameter."""

    id: int
    name: str
    basis_curve: Union[Line, Circle, Helix]
    trim_1: Union[Vec3, float]
    trim_2: Union[Vec3, float]
    sense_agreement: bool

    def _parameter(self, trim) -> float:
        return self.basis_curve.parameter(trim) if isinstance(trim, tuple) else float(trim)

    def sample(self) -> np.ndarray:
        t1, t2 = self._parameter(self.trim_1), self._parameter(self.trim_2)
        basis = self.basis_curve
        if isinstance(basis, Line):
            return np.array([basis.at(t1), basis.at(t2)])
        # sense agreement: from trim 1 the way the parameter grows (counter-clockwise), else back
        sweep = (t2 - t1) % 360.0 if self.sense_agreement else -((t1 - t2) % 360.0)
        if abs(sweep) < 1e-9:
            sweep = 360.0 if self.sense_agreement else -360.0
        centre, x, y = basis.frame()
        return _arc_points(centre, x, y, basis.radius, t1, sweep)


@dataclass(frozen=True)
class CompositeCurveSegment:
    transition: str
    same_sense: bool
    parent_curve: object  # Polyline | TrimmedCurve | Circle

    def sample(self) -> np.ndarray:
        points = self.parent_curve.sample()
        return points if self.same_sense else points[::-1]


@dataclass(frozen=True)
class CompositeCurve:
    id: int
    name: str
    segments: tuple  # of CompositeCurveSegment

    def sample(self) -> np.ndarray:
        pieces = []
        for index, segment in enumerate(self.segments):
            points = segment.sample()
            if pieces:
                gap = np.linalg.norm(points[0] - pieces[-1][-1])
                if gap > 1e-3:
                    raise StepNcError(f"#{self.id} COMPOSITE_CURVE: segment {index + 1} starts {gap:.4g} mm "
                                      "away from the end of the previous one")
                points = points[1:]
            pieces.append(points)
        return np.vstack(pieces)


# A B-spline curve is sampled at most this far (mm) apart along its control polygon: chord error within
# 0.001 mm where the curve bends no tighter than a 5 mm radius.
BSPLINE_STEP = 0.2


@dataclass(frozen=True)
class BSplineCurve:
    """B_SPLINE_CURVE_WITH_KNOTS (non-rational): ``knots`` expanded by their multiplicities."""

    id: int
    name: str
    degree: int
    control_points: tuple
    knots: tuple

    def at(self, u: float) -> np.ndarray:
        """The point at parameter u (de Boor)."""
        p, knots, points = self.degree, np.array(self.knots), np.array(self.control_points, float)
        k = int(np.clip(np.searchsorted(knots, u, side="right") - 1, p, len(points) - 1))
        d = [points[j + k - p].copy() for j in range(p + 1)]
        for r in range(1, p + 1):
            for j in range(p, r - 1, -1):
                left, right = knots[j + k - p], knots[j + 1 + k - r]
                alpha = 0.0 if right == left else (u - left) / (right - left)
                d[j] = (1 - alpha) * d[j - 1] + alpha * d[j]
        return d[p]

    def sample(self) -> np.ndarray:
        knots, points = np.array(self.knots), np.array(self.control_points, float)
        start, end = knots[self.degree], knots[len(points)]
        spans = [(a, b) for a, b in zip(knots[self.degree:len(points)], knots[self.degree + 1:len(points) + 1])
                 if b > a]
        length = float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())
        per_span = max(16, math.ceil(length / BSPLINE_STEP / max(1, len(spans))))
        params = [start] + [a + (b - a) * i / per_span for a, b in spans for i in range(1, per_span + 1)]
        params[-1] = end
        return np.array([self.at(u) for u in params])


Curve = Union[Polyline, Circle, TrimmedCurve, CompositeCurve, BSplineCurve]


# --------------------------------------------------------------------------- profiles and features


@dataclass(frozen=True)
class RectangularClosedProfile:
    """Centred on its placement; ``profile_length`` along the placement's x axis."""

    id: int
    placement: Placement | None
    profile_width: float
    profile_length: float

    def outline(self) -> np.ndarray:
        """The closed outline as (k, 3) points in the feature's coordinates (last != first)."""
        half_x, half_y = self.profile_length / 2, self.profile_width / 2
        corners = [(-half_x, -half_y), (half_x, -half_y), (half_x, half_y), (-half_x, half_y)]
        return (self.placement or IDENTITY).to_parent(corners)


@dataclass(frozen=True)
class GeneralClosedProfile:
    id: int
    placement: Placement | None
    closed_profile_shape: Curve

    def outline(self) -> np.ndarray:
        points = self.closed_profile_shape.sample()
        if np.linalg.norm(points[0] - points[-1]) > 1e-3:
            raise StepNcError(f"#{self.id} GENERAL_CLOSED_PROFILE: the outline #{self.closed_profile_shape.id} "
                              "is not closed (its last point is not its first)")
        return (self.placement or IDENTITY).to_parent(points[:-1])


ClosedProfile = Union[RectangularClosedProfile, GeneralClosedProfile]


@dataclass(frozen=True)
class LinearPath:
    """Course of travel of a planar face: ``distance`` along ``its_direction``."""

    id: int
    placement: Placement | None
    distance: float
    its_direction: Vec3

    def local_points(self) -> np.ndarray:
        """The path's start and end in the feature's coordinates."""
        origin = (self.placement or IDENTITY).to_parent([(0.0, 0.0)])[0]
        travel = (self.placement or IDENTITY).direction_to_parent(self.its_direction)
        return np.array([origin, origin + travel / np.linalg.norm(travel) * self.distance])


@dataclass(frozen=True)
class CircularPath:
    """PARTIAL_CIRCULAR_PATH(placement, radius, sweep_angle) or COMPLETE_CIRCULAR_PATH(placement, radius):
    an arc of ``radius`` about the placement's origin, from the point on its x axis, ``sweep_angle``
    degrees counter-clockwise about its z axis (negative: clockwise); 360 for the complete circle."""

    id: int
    placement: Placement | None
    radius: float
    sweep_angle: float

    def local_points(self) -> np.ndarray:
        frame = self.placement or IDENTITY
        m = frame.matrix()
        return _arc_points(np.array(frame.location, float), m[:, 0], m[:, 1], self.radius, 0.0, self.sweep_angle)


@dataclass(frozen=True)
class GeneralPath:
    """GENERAL_PATH(placement, swept_path): the slot's centre line is the curve, in the placement."""

    id: int
    placement: Placement | None
    swept_path: object

    def local_points(self) -> np.ndarray:
        return (self.placement or IDENTITY).to_parent(self.swept_path.sample())


@dataclass(frozen=True)
class LinearProfile:
    """Removal boundary of a planar face: a straight profile of ``profile_length`` along x."""

    id: int
    placement: Placement | None
    profile_length: float


class _Feature:
    """Shared by the features: the top is the feature placement, the bottom its depth plane
    (given in the feature's own coordinates)."""

    @property
    def top_z(self) -> float:
        return float(self.feature_placement.location[2])

    @property
    def bottom_z(self) -> float:
        return float(self.feature_placement.to_parent([self.depth.position.location])[0, 2])

    def to_world_xy(self, points) -> np.ndarray:
        return self.feature_placement.to_parent(points)[:, :2]


@dataclass(frozen=True)
class PlanarFace(_Feature):
    id: int
    its_id: str
    feature_placement: Placement
    depth: Plane
    course_of_travel: LinearPath
    removal_boundary: LinearProfile

    def corners(self) -> np.ndarray:
        """The face as a (4, 2) world XY parallelogram: the removal boundary swept along the
        course of travel (both from their placements, in the feature's coordinates)."""
        path, profile = self.course_of_travel, self.removal_boundary
        origin = (path.placement or IDENTITY).to_parent([(0.0, 0.0)])[0]
        travel = (path.placement or IDENTITY).direction_to_parent(path.its_direction) * path.distance
        across = (profile.placement or IDENTITY).direction_to_parent((1.0, 0.0, 0.0)) * profile.profile_length
        local = np.array([origin, origin + travel, origin + travel + across, origin + across])
        return self.to_world_xy(local)


@dataclass(frozen=True)
class ClosedPocket(_Feature):
    id: int
    its_id: str
    feature_placement: Placement
    depth: Plane
    bottom_condition: str
    planar_radius: float | None
    orthogonal_radius: float | None
    feature_boundary: ClosedProfile

    def outline(self) -> np.ndarray:
        """The pocket outline in world XY, (k, 2), without the corner rounding."""
        return self.to_world_xy(self.feature_boundary.outline())


@dataclass(frozen=True)
class RoundHole(_Feature):
    id: int
    its_id: str
    feature_placement: Placement
    depth: Plane
    diameter: float
    bottom_condition: str

    @property
    def centre(self) -> tuple:
        return tuple(float(v) for v in self.feature_placement.location[:2])


SLOT_ENDS = ("OPEN_SLOT_END_TYPE", "RADIUSED_SLOT_END_TYPE", "FLAT_SLOT_END_TYPE")


@dataclass(frozen=True)
class Slot(_Feature):
    """SLOT along a LINEAR_PATH with a SQUARE_U_PROFILE of ``width``.  ``ends``: the end types at the
    path's start and end (OPEN: the slot runs out of the part, so the region the tools clear goes
    one width beyond it; RADIUSED: a half circle of half the width; FLAT: square).  It answers what
    the pocket strategies ask of a CLOSED_POCKET (outline, radii)."""

    id: int
    its_id: str
    feature_placement: Placement
    depth: Plane
    course_of_travel: Union[LinearPath, CircularPath, GeneralPath]
    width: float
    planar_radius: float | None
    ends: tuple
    orthogonal_radius = None
    bottom_condition = "PLANAR_POCKET_BOTTOM_CONDITION"

    def centreline(self) -> np.ndarray:
        """The slot's centre line in world XY, (k, 2): a straight line, an arc or a curve."""
        return self.to_world_xy(self.course_of_travel.local_points())

    @property
    def closed(self) -> bool:
        """A slot round a complete circle (or along a closed curve) has no ends."""
        line = self.centreline()
        return len(line) > 2 and bool(np.linalg.norm(line[0] - line[-1]) < 1e-6)

    def axis(self) -> tuple:
        """(start, end) of the slot's centre line in world XY."""
        line = self.centreline()
        return line[0], line[-1]

    @property
    def course(self) -> tuple:
        """The slot's direction at its start in the feature's coordinates (the default raster direction)."""
        local = self.course_of_travel.local_points()
        step = next((p - local[0] for p in local[1:] if np.linalg.norm(p - local[0]) > 1e-9), np.array([1.0, 0, 0]))
        return tuple(step / np.linalg.norm(step))

    def region(self):
        """The region the slot removes in world XY (a CrossSection): the centre line swept by the
        width, with round joins; radiused ends round, flat ends square, open ends one width beyond."""
        if isinstance(self.course_of_travel, LinearPath):
            return rg.from_loops([self.outline()], f"slot #{self.id} '{self.its_id}'")
        line = self.centreline()
        half = self.width / 2
        if not self.closed:
            line = line.copy()
            for index, inward, kind in ((0, 1, self.ends[0]), (-1, -2, self.ends[1])):
                if kind == "OPEN_SLOT_END_TYPE":
                    tangent = line[index] - line[inward]
                    line[index] = line[index] + tangent / np.linalg.norm(tangent) * self.width
        polygons = []
        for a, b in zip(line[:-1], line[1:]):
            along = b - a
            if np.linalg.norm(along) < 1e-12:
                continue
            side = np.array([-along[1], along[0]]) / np.linalg.norm(along) * half
            polygons.append(np.array([a - side, b - side, b + side, a + side]))
        joints = line[1:-1] if not self.closed else line[:-1]
        disks = list(joints)
        for point, kind in ((line[0], self.ends[0]), (line[-1], self.ends[1])):
            if kind == "RADIUSED_SLOT_END_TYPE" and not self.closed:
                disks.append(point)
        count = rg.circle_segments(half)
        ring = np.column_stack([np.cos(np.linspace(0, 2 * math.pi, count, endpoint=False)),
                                np.sin(np.linspace(0, 2 * math.pi, count, endpoint=False))]) * half
        polygons += [ring + point for point in disks]
        return rg.union_of_faces([p if rg.signed_area(p) > 0 else p[::-1] for p in polygons],
                                 f"slot #{self.id} '{self.its_id}'")

    def outline(self) -> np.ndarray:
        """The region the slot removes in world XY (k, 2), counter-clockwise; open ends reach one
        width beyond the part.  A curved slot: the outer loop of :meth:`region`."""
        if not isinstance(self.course_of_travel, LinearPath):
            return max(rg.loops(self.region()), key=lambda loop: abs(rg.signed_area(loop)))
        start, end = self.axis()
        along = (end - start) / np.linalg.norm(end - start)
        side = np.array([-along[1], along[0]]) * self.width / 2
        points = []
        for point, kind, outward in ((end, self.ends[1], along), (start, self.ends[0], -along)):
            if kind == "OPEN_SLOT_END_TYPE":
                point = point + outward * self.width
            if kind == "RADIUSED_SLOT_END_TYPE":
                base = math.degrees(math.atan2(outward[1], outward[0]))
                arc = _arc_points(np.append(point, 0.0), np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]),
                                  self.width / 2, base - 90.0, 180.0)
                points += list(arc[:, :2])
            else:
                turn = side if outward @ along > 0 else -side
                points += [point - turn, point + turn]
        return np.array(points)


Feature = Union[PlanarFace, ClosedPocket, RoundHole, Slot]


# --------------------------------------------------------------------------- tools and technology


@dataclass(frozen=True)
class ToolDimension:
    """MILLING_TOOL_DIMENSION (or TOOL_DIMENSION)."""

    diameter: float
    tool_top_angle: float | None = None
    tool_circumference_angle: float | None = None
    cutting_edge_length: float | None = None
    edge_radius: float | None = None
    edge_center_vertical: float | None = None
    edge_center_horizontal: float | None = None


@dataclass(frozen=True)
class ToolBody:
    """ENDMILL, BALL_ENDMILL, TWIST_DRILL, ... (``type_name`` says which)."""

    id: int
    type_name: str
    dimension: ToolDimension
    number_of_teeth: int | None
    taper_angle: float | None = None


@dataclass(frozen=True)
class CuttingTool:
    """MILLING_CUTTING_TOOL."""

    id: int
    its_id: str
    its_tool_body: ToolBody
    overall_assembly_length: float | None


@dataclass(frozen=True)
class MillingTechnology:
    id: int
    feedrate: float | None          # m/s
    feedrate_reference: str
    cutspeed: float | None          # m/s
    spindle: float | None           # rev/s, negative = clockwise
    feedrate_per_tooth: float | None  # mm

    @property
    def feed_mm_min(self) -> float | None:
        return None if self.feedrate is None else self.feedrate * 60000.0

    @property
    def spindle_rpm(self) -> float | None:
        return None if self.spindle is None else abs(self.spindle) * 60.0

    @property
    def spindle_clockwise(self) -> bool:
        return self.spindle is None or self.spindle <= 0


@dataclass(frozen=True)
class MachineFunctions:
    """MILLING_MACHINE_FUNCTIONS (only coolant is used)."""

    id: int
    coolant: bool


# --------------------------------------------------------------------------- strategies


@dataclass(frozen=True)
class Bidirectional:
    """BIDIRECTIONAL (BIDIRECTIONAL_MILLING): zigzag strokes.  ``overlap`` is a ratio of the tool
    diameter; ``stepover_direction`` LEFT or RIGHT of ``feed_direction``."""

    overlap: float | None
    allow_multiple_passes: bool | None
    feed_direction: Vec3 | None
    stepover_direction: str | None
    stroke_connection_strategy: str | None


@dataclass(frozen=True)
class Unidirectional:
    overlap: float | None
    allow_multiple_passes: bool | None
    feed_direction: Vec3 | None
    cutmode: str | None


@dataclass(frozen=True)
class ContourParallel:
    """Rings parallel to the outline; ``rotation_direction`` CW or CCW."""

    overlap: float | None
    allow_multiple_passes: bool | None
    rotation_direction: str
    cutmode: str | None


@dataclass(frozen=True)
class ContourBidirectional(Bidirectional):
    """CONTOUR_BIDIRECTIONAL (``contour_first``) or BIDIRECTIONAL_CONTOUR: zigzag strokes along
    ``feed_direction`` stepping to ``stepover_direction``, and one contour pass along the boundary,
    before the strokes or after them, turning ``rotation_direction`` (CW / CCW) or, when that is not
    given, climb or conventional as ``spiral_cutmode`` says."""

    rotation_direction: str | None = None
    spiral_cutmode: str | None = None
    contour_first: bool = True


MillingStrategy = Union[Bidirectional, Unidirectional, ContourParallel, ContourBidirectional]


@dataclass(frozen=True)
class DrillingTypeStrategy:
    """Reduced cut (spindle) and feed, as ratios, over the first and last depths of a hole."""

    reduced_cut_at_start: float | None
    reduced_feed_at_start: float | None
    depth_of_start: float | None
    reduced_cut_at_end: float | None
    reduced_feed_at_end: float | None
    depth_of_end: float | None


@dataclass(frozen=True)
class PlungeToolaxis:
    tool_orientation: Vec3 | None


@dataclass(frozen=True)
class PlungeRamp:
    tool_orientation: Vec3 | None
    angle: float  # degrees from the horizontal


@dataclass(frozen=True)
class PlungeHelix:
    tool_orientation: Vec3 | None
    radius: float
    angle: float  # degrees from the horizontal


ApproachRetract = Union[PlungeToolaxis, PlungeRamp, PlungeHelix]


# --------------------------------------------------------------------------- operations


@dataclass(frozen=True)
class PlaneMilling:
    """PLANE_ROUGH_MILLING or PLANE_FINISH_MILLING (``type_name``)."""

    id: int
    type_name: str
    its_id: str
    retract_plane: float | None
    its_tool: CuttingTool
    its_technology: MillingTechnology
    its_machine_functions: MachineFunctions | None
    approach: ApproachRetract | None
    retract: ApproachRetract | None
    its_machining_strategy: MillingStrategy | None
    axial_cutting_depth: float | None
    allowance_bottom: float | None

    @property
    def finishing(self) -> bool:
        return self.type_name == "PLANE_FINISH_MILLING"


@dataclass(frozen=True)
class BottomAndSideMilling:
    """BOTTOM_AND_SIDE_ROUGH_MILLING or BOTTOM_AND_SIDE_FINISH_MILLING (``type_name``)."""

    id: int
    type_name: str
    its_id: str
    retract_plane: float | None
    its_tool: CuttingTool
    its_technology: MillingTechnology
    its_machine_functions: MachineFunctions | None
    approach: ApproachRetract | None
    retract: ApproachRetract | None
    its_machining_strategy: MillingStrategy | None
    axial_cutting_depth: float | None
    radial_cutting_depth: float | None
    allowance_side: float | None
    allowance_bottom: float | None

    @property
    def finishing(self) -> bool:
        return self.type_name == "BOTTOM_AND_SIDE_FINISH_MILLING"


@dataclass(frozen=True)
class DrillingOperation:
    """DRILLING, CENTER_DRILLING or REAMING (``type_name``); ``spindle_stop_at_bottom`` is
    REAMING's own attribute (None for the others)."""

    id: int
    type_name: str
    its_id: str
    retract_plane: float | None
    its_tool: CuttingTool
    its_technology: MillingTechnology
    its_machine_functions: MachineFunctions | None
    cutting_depth: float | None
    previous_diameter: float | None
    dwell_time_bottom: float | None
    feed_on_retract: float | None
    its_machining_strategy: DrillingTypeStrategy | None
    spindle_stop_at_bottom: bool | None = None
    overcut_length: float | None = None    # how far a through hole is drilled past its bottom


@dataclass(frozen=True)
class Trajectory:
    """CUTTER_LOCATION_TRAJECTORY(its_priority, its_type, its_speed, its_technology, its_machine_functions,
    its_direction, basiccurve, its_toolaxis, surface_normal): the tool centre point along ``basiccurve``
    (reversed when its_direction is .F.), at rapid when its_speed is .RAPID., else at its technology's
    feed (the operation's when it has none)."""

    id: int
    rapid: bool
    its_technology: MillingTechnology | None
    forward: bool
    basiccurve: object


@dataclass(frozen=True)
class FreeformOperation:
    """FREEFORM_OPERATION with explicit toolpaths (a TOOLPATH_LIST of trajectories), given in the
    coordinates of the workingstep's feature."""

    id: int
    type_name: str
    its_id: str
    retract_plane: float | None
    its_tool: CuttingTool
    its_technology: MillingTechnology
    its_machine_functions: MachineFunctions | None
    its_toolpath: tuple
    finishing = False
    its_machining_strategy = None
    allowance_bottom = None
    allowance_side = None


@dataclass(frozen=True)
class RapidMovement:
    """RAPID_MOVEMENT(its_id, its_secplane, its_toolpath, its_tool_direction): rapids along its
    trajectories, in the workpiece's coordinates, with the tool of the workingstep before it."""

    id: int
    its_id: str
    its_toolpath: tuple


MachiningOperation = Union[PlaneMilling, BottomAndSideMilling, DrillingOperation, FreeformOperation]


# --------------------------------------------------------------------------- executables and project


@dataclass(frozen=True)
class Workingstep:
    """MACHINING_WORKINGSTEP."""

    id: int
    its_id: str
    its_secplane: Plane
    its_feature: Feature
    its_operation: MachiningOperation
    rapids_after: tuple = ()     # RAPID_MOVEMENTs that follow it in the workplan


@dataclass(frozen=True)
class Setup:
    id: int
    its_id: str
    its_origin: Placement | None
    its_secplane: Plane


@dataclass(frozen=True)
class Workplan:
    """WORKPLAN.  ``its_elements`` holds the workingsteps and nested workplans this converter
    supports, in order; skipped elements are reported as warnings by :func:`read_project`."""

    id: int
    its_id: str
    its_elements: tuple
    its_setup: Setup | None

    def workingsteps(self) -> list:
        """The workingsteps in execution order, nested workplans flattened."""
        steps = []
        for element in self.its_elements:
            steps += element.workingsteps() if isinstance(element, Workplan) else [element]
        return steps


@dataclass(frozen=True)
class Workpiece:
    id: int
    its_id: str
    global_tolerance: float | None
    its_bounding_geometry: Block | None
    clamping_positions: tuple


@dataclass(frozen=True)
class Project:
    id: int
    its_id: str
    main_workplan: Workplan
    its_workpieces: tuple


# --------------------------------------------------------------------------- reader


PLANE_TYPES = ("PLANE", "ELEMENTARY_SURFACE")
MAX_LENGTH = 1.0e5   # mm: 100 m, larger than any machine
DIMENSION_TYPES = ("MILLING_TOOL_DIMENSION", "TOOL_DIMENSION")
MILLING_TOOL_BODIES = ("ENDMILL", "TAPERED_ENDMILL", "BALL_ENDMILL", "BULLNOSE_ENDMILL", "FACEMILL")
DRILLING_TOOL_BODIES = ("TWIST_DRILL", "TAPERED_DRILL", "CENTER_DRILL", "REAMER", "TAPERED_REAMER")
TAPERED_BODIES = ("TAPERED_ENDMILL", "TAPERED_DRILL", "TAPERED_REAMER")
LENGTH_TYPES = ("TOLERANCED_LENGTH_MEASURE", "NUMERIC_PARAMETER")


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

    def length(self, inst, index, name, optional=False) -> float | None:
        """A number, or a TOLERANCED_LENGTH_MEASURE / NUMERIC_PARAMETER holding one; at most
        MAX_LENGTH mm, so a mistyped exponent is an error rather than an hours-long toolpath."""
        value = self.value(inst, index, name, optional)
        if not isinstance(value, Ref):
            size, holder = self.number(inst, index, name, optional), inst
        else:
            holder = self.entity(inst, index, name, LENGTH_TYPES)
            size = self.number(holder, 0, "theoretical_size") if holder.type_name == "TOLERANCED_LENGTH_MEASURE" \
                else self.number(holder, 1, "its_parameter_value")
        if size is not None and abs(size) > MAX_LENGTH:
            raise StepNcError(f"#{holder.id} {holder.type_name}: {name} {size:g} mm is larger than {MAX_LENGTH:g} mm")
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
        target = self.entity(inst, index, name, ("POLYLINE", "TRIMMED_CURVE", "COMPOSITE_CURVE", "CIRCLE",
                                                 "B_SPLINE_CURVE_WITH_KNOTS"), unsupported=True)
        return self.memoised(target, self._curve)

    def _curve(self, t):
        if t.type_name == "POLYLINE":
            points = self.entities(t, 1, "points", ("CARTESIAN_POINT",))
            return Polyline(t.id, self.text(t, 0, "name"), tuple(self.coordinates(p) for p in points))
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
                return RectangularClosedProfile(t.id, placement, self.length(t, 1, "profile_width"),
                                                self.length(t, 2, "profile_length"))
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
        return RoundHole(t.id, its_id, placement, depth, self.length(t, 5, "diameter"), bottom_name)

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
        return self.memoised(target, lambda t: DrillingTypeStrategy(*(
            self.number(t, i, n, optional=True, positive=True) for i, n in enumerate(
                ("reduced_cut_at_start", "reduced_feed_at_start", "depth_of_start", "reduced_cut_at_end",
                 "reduced_feed_at_end", "depth_of_end")))))

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
            drilling = common + (self.length(t, 9, "cutting_depth", optional=True),
                                 self.length(t, 10, "previous_diameter", optional=True),
                                 self.number(t, 11, "dwell_time_bottom", optional=True),
                                 self.number(t, 12, "feed_on_retract", optional=True),
                                 self.drilling_strategy(t, 13, "its_machining_strategy"))
            overcut = self.length(t, 8, "overcut_length", optional=True)
            if t.type_name == "REAMING":
                return DrillingOperation(*drilling, self.boolean(t, 14, "spindle_stop_at_bottom"),
                                         overcut_length=overcut)
            return DrillingOperation(*drilling, overcut_length=overcut)
        milling = common + (self.approach_retract(t, 9, "approach"), self.approach_retract(t, 10, "retract"),
                            self.milling_strategy(t, 11, "its_machining_strategy"),
                            self.length(t, 12, "axial_cutting_depth", optional=True))
        if t.type_name.startswith("PLANE_"):
            return PlaneMilling(*milling, self.length(t, 13, "allowance_bottom", optional=True))
        return BottomAndSideMilling(*milling, self.length(t, 13, "radial_cutting_depth", optional=True),
                                    self.length(t, 14, "allowance_side", optional=True),
                                    self.length(t, 15, "allowance_bottom", optional=True))

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

    def workingstep(self, t) -> Workingstep:
        return Workingstep(t.id, self.text(t, 0, "its_id"), self.plane(t, 1, "its_secplane"),
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
                    self.warnings.append(f"workingstep #{element.id} '{self.text(element, 0, 'its_id')}' "
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
        from .ap238 import to_arm    # the AP238 integrated form: read as its ISO 14649 rendition
        part21 = to_arm(part21)
        projects = part21.by_type("PROJECT")
    if len(projects) != 1:
        raise StepNcError(f"an ISO 14649 file needs exactly one PROJECT, this one has {len(projects)}")
    reader = _Reader(part21)
    t = projects[0]
    main = reader.entity(t, 1, "main_workplan", ("WORKPLAN",))
    workpieces = tuple(reader.memoised(piece, reader.workpiece)
                       for piece in reader.entities(t, 2, "its_workpieces", ("WORKPIECE",)))
    project = Project(t.id, reader.text(t, 0, "its_id"), reader.workplan(main), workpieces)
    return project, reader.warnings
