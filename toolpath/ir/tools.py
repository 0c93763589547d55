"""Tool shapes: one object per tool kind, the one place that knows what each kind looks like.

A :class:`ToolShape` is the tool's end, tip at the origin and axis along +Z: a flat disc of
radius ``flat_radius`` rounded by a ``corner_radius`` (ball, flat, bull nose), or a cone whose
included angle is ``tip_angle_deg`` (drill, V-bit).  It answers what the rest of the core asks
of a tool kind: its profile (:meth:`ToolShape.height_at`, :meth:`ToolShape.radius_at`), whether
it may feed straight down into material, and which construction cuts it in the simulation
(``envelope`` for the height field; ``pointed``, ``spherical`` and ``staircase`` for the swept
solids).  :class:`~.program.Tool` keeps the kind as a string and hands out its shape as
``tool.shape``.
"""
from __future__ import annotations

import math

import numpy as np

from .errors import InputError


class ToolShapeError(InputError):
    """A tool kind no shape is known for."""


class ToolShape:
    """The end of a tool of radius ``radius``; see the module docstring.  Subclasses set the
    class attributes, one subclass per kind."""

    kind = ""
    label = ""                  # what the tool is called in messages
    plunges = False             # centre-cutting: may feed straight down into material
    pointed = False             # a cone (tip_angle_deg), not a rounded disc
    spherical = False           # a ball: every section through the tip's centre is the same circle
    staircase = False           # a level row of places a gap g apart holds the tool shrunk by its
    #                             dip r - sqrt(r^2 - g^2 / 4) (ball and flat: see sweep._level_staircase)
    envelope = ""               # the height field's construction: "sphere", "disc" (disc + torus) or "cone"
    tip_angle_deg = None        # included angle of a pointed tool
    corner_is_radius = False    # a corner radius left at 0 means the whole radius (ball)
    corner_given = False        # the corner radius is a dimension of its own (bull nose R)

    def __init__(self, radius: float, corner_radius: float = 0.0, tip_angle_deg: float | None = None):
        self.radius = radius
        self.given_corner = corner_radius   # as the tool was given it (the swept solids use it)
        if tip_angle_deg:                   # a pointed tool's own angle (a 60 deg V-bit); None: the kind's
            self.tip_angle_deg = float(tip_angle_deg)

    @property
    def corner_radius(self) -> float:
        """The radius rounding the disc's rim in the profile (0: square, or a cone)."""
        return float(self.given_corner)

    @property
    def flat_radius(self) -> float:
        """The radius of the flat disc at the bottom (0 for a ball or a cone)."""
        return 0.0 if self.pointed else float(self.radius) - self.corner_radius

    @property
    def tip_tan(self) -> float:
        """tan of the cone's half angle; 0 for a tool that is not pointed."""
        return math.tan(math.radians(self.tip_angle_deg) / 2) if self.pointed else 0.0

    def profile(self) -> tuple:
        """(tip_tan, corner, flat): a cone whose half angle has tangent tip_tan if tip_tan > 0,
        else a flat disc of radius ``flat`` rounded by a ``corner`` radius (as the compiled
        height-field kernels take it)."""
        return self.tip_tan, self.corner_radius, self.flat_radius

    def height_at(self, d):
        """Height of the tool's underside above its tip at distance d from the axis (d <= R)."""
        tip_tan, corner, flat = self.profile()
        if tip_tan > 0:
            return d / tip_tan
        off = np.maximum(d - flat, 0)
        return corner - np.sqrt(np.maximum(corner * corner - off * off, 0))

    def radius_at(self, h):
        """Radius of the tool at height h above its tip (h >= 0); the full radius above its end."""
        h = np.asarray(h, float)
        tip_tan, corner, flat = self.profile()
        if tip_tan > 0:
            return np.minimum(h * tip_tan, self.radius)
        rise = np.minimum(h, corner)
        return np.where(h >= corner, float(self.radius), flat + np.sqrt(np.maximum(corner * corner
                                                                                  - (corner - rise) ** 2, 0)))

    def describe(self) -> str:
        """The kind in words, with its corner radius where that is a dimension of its own."""
        return f"{self.label} R{self.given_corner:g}" if self.corner_given else self.label


class Ball(ToolShape):
    kind, label = "ball", "ball end mill"
    plunges = spherical = staircase = corner_is_radius = True
    envelope = "sphere"


class Flat(ToolShape):
    kind, label = "flat", "flat end mill"
    plunges = staircase = True
    envelope = "disc"

    @property
    def corner_radius(self) -> float:
        return 0.0


class Bull(ToolShape):
    kind, label = "bull", "bull nose end mill"
    envelope = "disc"
    corner_given = True


class _Cone(ToolShape):
    pointed = True
    envelope = "cone"

    @property
    def corner_radius(self) -> float:
        return 0.0


class Drill(_Cone):
    kind, label = "drill", "drill"
    plunges = True
    tip_angle_deg = 118.0


class VBit(_Cone):
    kind, label = "vbit", "V-bit"
    tip_angle_deg = 90.0


SHAPES = {cls.kind: cls for cls in (Ball, Flat, Bull, Drill, VBit)}
KINDS = tuple(SHAPES)
# included angle of the pointed kinds when a Tool does not give its own (``Tool.tip_angle``)
TIP_ANGLE_DEG = {kind: cls.tip_angle_deg for kind, cls in SHAPES.items() if cls.pointed}


def shape_class(kind: str) -> type:
    """The shape class of a tool kind; an unknown kind is refused."""
    try:
        return SHAPES[kind]
    except (KeyError, TypeError):
        raise ToolShapeError(f"tool kind {kind!r} is not one of {KINDS}") from None


def shape_of(tool) -> ToolShape:
    """The shape of a tool (anything with ``kind``, ``radius`` and ``corner_radius``; a pointed
    tool's ``tip_angle`` where it has one, else its kind's angle)."""
    return shape_class(tool.kind)(tool.radius, tool.corner_radius, getattr(tool, "tip_angle", 0.0) or None)
