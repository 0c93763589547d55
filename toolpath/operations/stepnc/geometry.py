"""ISO 14649 geometry (the ISO 10303-42 resources it uses) as frozen dataclasses: placements, planes,
the workpiece's block, and the curves of outlines, slot paths and explicit toolpaths (polyline, line,
circle, helix, trimmed, composite and B-spline curves), each sampled to points within CHORD_TOLERANCE.
Lengths in mm, angles in degrees.  Part of the typed model (see :mod:`.model`)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Union

import numpy as np

from .errors import StepNcError

# Chord error (mm) when arcs and circles of an outline are turned into polygons.
CHORD_TOLERANCE = 0.001

Vec3 = tuple  # (x, y, z)
# The entity types the reader takes for a plane and for a curve.
PLANE_TYPES = ("PLANE", "ELEMENTARY_SURFACE")
CURVE_TYPES = ("POLYLINE", "TRIMMED_CURVE", "COMPOSITE_CURVE", "CIRCLE", "B_SPLINE_CURVE_WITH_KNOTS")


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


def arc_points(centre, x_axis, y_axis, radius, start_deg, sweep_deg) -> np.ndarray:
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
        return arc_points(centre, x, y, self.radius, 0.0, 360.0)


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
        return arc_points(centre, x, y, basis.radius, t1, sweep)


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
