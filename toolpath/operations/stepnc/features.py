"""ISO 14649-10 manufacturing features as frozen dataclasses: the planar face, closed pocket, round hole
and slot, with the profiles (rectangular, general closed, linear) and paths (linear, circular, general)
that shape them.  Each answers what the strategies ask in world XY: outline, corners, centre, region.
Part of the typed model (see :mod:`.model`)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Union

import numpy as np

from ...engines import region as rg
from .errors import StepNcError
from .geometry import IDENTITY, Curve, Placement, Plane, Vec3, arc_points


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
        return arc_points(np.array(frame.location, float), m[:, 0], m[:, 1], self.radius, 0.0, self.sweep_angle)


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
                arc = arc_points(np.append(point, 0.0), np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]),
                                  self.width / 2, base - 90.0, 180.0)
                points += list(arc[:, :2])
            else:
                turn = side if outward @ along > 0 else -side
                points += [point - turn, point + turn]
        return np.array(points)


Feature = Union[PlanarFace, ClosedPocket, RoundHole, Slot]
