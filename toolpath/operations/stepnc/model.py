"""ISO 14649-10/-11 (STEP-NC, milling) entities as a small typed model.

:func:`.reader.read_project` turns a parsed Part 21 file (:mod:`.part21`) into these frozen dataclasses:
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
from dataclasses import dataclass
from typing import Union

import numpy as np

from ...engines import region as rg
from ...ir.errors import MAX_REACH_MM, InputError

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


# --------------------------------------------------------------------------- the vocabulary the reader accepts


PLANE_TYPES = ("PLANE", "ELEMENTARY_SURFACE")
CURVE_TYPES = ("POLYLINE", "TRIMMED_CURVE", "COMPOSITE_CURVE", "CIRCLE", "B_SPLINE_CURVE_WITH_KNOTS")
MAX_NAME = 200    # characters of a workingstep name written (as a comment); a longer one is cut, with a note
MAX_LENGTH = MAX_REACH_MM    # mm: 100 m, larger than any machine (errors.MAX_REACH_MM)
DIMENSION_TYPES = ("MILLING_TOOL_DIMENSION", "TOOL_DIMENSION")
MILLING_TOOL_BODIES = ("ENDMILL", "TAPERED_ENDMILL", "BALL_ENDMILL", "BULLNOSE_ENDMILL", "FACEMILL")
DRILLING_TOOL_BODIES = ("TWIST_DRILL", "TAPERED_DRILL", "CENTER_DRILL", "REAMER", "TAPERED_REAMER")
TAPERED_BODIES = ("TAPERED_ENDMILL", "TAPERED_DRILL", "TAPERED_REAMER")
LENGTH_TYPES = ("TOLERANCED_LENGTH_MEASURE", "NUMERIC_PARAMETER")
