"""The toolpath intermediate representation (IR).

A :class:`Program` is a list of :class:`Operation`.  An operation holds one tool, its
spindle and feeds, its clearance heights and its moves, kept as numpy arrays because a
texture job has 10^5 moves.  Every coordinate is in millimetres in the work coordinate
system; Z is the tool tip (the point a G43 tool-length offset refers to).

Posts (``post/``) read this and alone decide which controller words to write.  It is all a post
takes from the core, with :mod:`.kinematics` and :mod:`.errors` (``tests/test_layering.py`` holds
them to it), and every name a post takes is defined here: the Program and its Operations with
their :class:`MoveKind`, the X-Z-C turn-mill's :class:`TurnMillOperation`, the gouge-texture
request (:class:`GougeTexture`, an Operation's ``texture``), the turret punch's
:class:`PunchProgram`, the machine a post assumes (:func:`default_machine`) and the arc filter
(:func:`fit_program`).
"""
from __future__ import annotations

import dataclasses
import enum
import math
from dataclasses import dataclass, field

import numpy as np

from . import kinematics, tools
from .errors import InputError, ProgramError
from .moves import ARC_CCW, ARC_CW, FEED, RAPID, arc_sweep
from .cycles import DrillCycle
from .machine import DEFAULT_FOR_FAMILY, preset
from .tools import KINDS as TOOL_KINDS, TIP_ANGLE_DEG  # noqa: F401 (re-exported)


# ----- the gouge texture request: an Operation's ``texture`` (the engrave workflow plans it untextured;
# ``engrave.bake`` applies it, the controller-macro post writes a macro that draws it on the control)

class EngraveError(InputError):
    """Input the engrave workflow cannot use; the message names what is wrong."""


GOUGE_MOTIONS = ("ramp", "scoop")


@dataclass(frozen=True)
class GougeTexture:
    """Random chisel-mark depths applied along the raster (paper defaults)."""

    base_depth: float = -2.0
    quantum: float = 0.2
    amplitude: float = 0.8
    spacing: float = 20.0
    motion: str = "ramp"          # "ramp": straight lines between depths; "scoop": dive, then push up
    scoop_dive: float = 0.25      # scoop: fraction of a gouge spent diving
    spacing_jitter: float = 0.0   # 0..0.5: each gouge length varies by +/- this fraction (baked only)
    raster_angle: float = 0.0     # degrees from +X; gouges are spaced along the raster
    seed: int = 0

    def __post_init__(self):
        for name in ("base_depth", "quantum", "amplitude", "spacing", "scoop_dive", "spacing_jitter", "raster_angle"):
            if not math.isfinite(getattr(self, name)):
                raise EngraveError(f"texture {name} must be a finite number")
        if self.quantum <= 0 or self.amplitude < 0 or self.spacing <= 0:
            raise EngraveError("texture quantum and gouge spacing must be > 0, amplitude >= 0")
        if self.motion not in GOUGE_MOTIONS:
            raise EngraveError(f"gouge motion must be one of {GOUGE_MOTIONS}, got {self.motion!r}")
        if not 0 < self.scoop_dive < 1:
            raise EngraveError("scoop dive fraction must be between 0 and 1")
        if not 0 <= self.spacing_jitter <= 0.5:
            raise EngraveError("spacing jitter must be between 0 and 0.5")
        if self.base_depth + self.amplitude > 0:
            raise EngraveError("the shallowest gouge (base depth + amplitude) would lie above the plate top")

    def level(self, k):
        """Depth offset (mm, >= 0) for level k in 0..4."""
        return self.quantum * np.round(np.asarray(k) * self.amplitude / (4 * self.quantum) + 1e-9)

    def depth(self, digit):
        """Target Z for a digit 0..9 (vectorised)."""
        d = np.asarray(digit)
        if np.any((d < 0) | (d > 9)):
            raise EngraveError("gouge digits must be 0..9")
        shallow = d <= 4
        k = np.where(shallow, d, d - 5)
        return np.where(shallow, self.base_depth + self.level(k), self.base_depth - self.level(k))

    @property
    def shallowest(self) -> float:
        return self.base_depth + float(self.level(4))

    @property
    def deepest(self) -> float:
        return self.base_depth - float(self.level(4))


class MoveKind(enum.IntEnum):
    RAPID = RAPID
    FEED = FEED
    ARC_CW = ARC_CW
    ARC_CCW = ARC_CCW


@dataclass(frozen=True)
class Tool:
    """A cutter.  ``kind`` is one of TOOL_KINDS (its shape: :attr:`shape`); lengths in mm."""

    number: int
    kind: str
    diameter: float
    corner_radius: float = 0.0
    flute_length: float = 20.0
    name: str = ""
    label: str = ""    # what the tool is called in comments when the kind's name is wrong (e.g. "reamer")
    tip_angle: float = 0.0  # a pointed tool's included angle in degrees (0: its kind's, 90 for a V-bit)

    def __post_init__(self):
        try:
            shape = tools.shape_class(self.kind)
        except tools.ToolShapeError as error:
            raise ProgramError(str(error)) from None
        if not (np.isfinite(self.diameter) and self.diameter > 0):
            raise ProgramError(f"tool diameter must be a positive number, got {self.diameter}")
        if not (isinstance(self.number, int) and 0 <= self.number <= 999):
            raise ProgramError(f"tool number must be an integer 0..999, got {self.number!r}")
        if shape.corner_is_radius and self.corner_radius == 0.0:
            object.__setattr__(self, "corner_radius", self.diameter / 2)
        if not 0 <= self.corner_radius <= self.diameter / 2 + 1e-9:
            raise ProgramError(f"corner radius {self.corner_radius:g} does not fit a {self.diameter:g} mm tool")
        if self.tip_angle:
            if not shape.pointed:
                raise ProgramError(f"a tip angle ({self.tip_angle!r} deg) is for a pointed tool, not a {shape.label}")
            if not (isinstance(self.tip_angle, (int, float)) and 1.0 <= self.tip_angle <= 179.0):
                raise ProgramError(f"tip angle must be from 1 to 179 degrees, got {self.tip_angle!r}")

    @property
    def radius(self) -> float:
        return self.diameter / 2

    @property
    def shape(self) -> tools.ToolShape:
        """The tool's end: its profile, whether it plunges, how the simulation cuts it."""
        return tools.shape_of(self)

    def describe(self) -> str:
        kind = self.label or self.shape.describe()
        if self.tip_angle and not self.label:
            kind = f"{self.tip_angle:g} deg {kind}"
        text = f"T{self.number} {self.diameter:g} mm {kind}"
        return text + (f" ({self.name})" if self.name else "")


@dataclass
class Operation:
    """One tool's worth of cutting.

    Moves are parallel arrays of length n:
      kind    int8      RAPID, FEED, ARC_CW, ARC_CCW
      xyz     (n, 3)    end point
      center  (n, 3)    arc centre (NaN for straight moves); arcs lie in the XY plane
      feed    (n,)      mm/min for cutting moves, NaN for rapids
      rotary  {axis: (n,)}  end positions of rotary axes in degrees, e.g. {"c": ...}
    Rotary axis "c" is a table turning the part about Z: with the table at C, the tool at
    machine (x, y) touches the part point R(C) (x, y) (R = rotation by C, counter-clockwise).
    The axes move linearly in machine coordinates, so a move traces a curve on the part, and
    lengths and times are measured along that curve (:mod:`kinematics` has the conversion and
    the length convention).
    ``start`` is where the tool is before the first move (normally above the clearance plane).
    ``texture`` carries a request a post may honour itself: a :class:`GougeTexture` that a
    controller macro applies at run time; the moves are then the untextured path.
    ``texture_marks`` (n, 2), with a texture on a curved plate (:mod:`surface_engrave`): per move,
    1 where a new gouge depth is drawn as the move starts (else 0), and how far along the gouge's
    ramp the move ends (0..1; NaN: the move is cut as programmed); the macro adds the depth to Z.
    ``links`` (n,) bool, or None when the planner did not say: True on a feed move the planner made
    to go from one cut to the next at depth (a link inside a pocket), not to cut.  Posts write a
    link as any feed move; pictures draw it as a link.
    ``cycle``: a :class:`~.cycles.DrillCycle` when the moves are a drilling cycle's, expanded (a
    post whose control has canned cycles may write the cycle instead of the moves); None otherwise.
    """

    name: str
    tool: Tool
    spindle_rpm: float
    kind: np.ndarray
    xyz: np.ndarray
    feed: np.ndarray
    center: np.ndarray | None = None
    rotary: dict = field(default_factory=dict)
    spindle_cw: bool = True
    clearance_z: float = 20.0
    safe_z: float = 50.0           # where the operation starts and ends; within every preset machine's reach
    start: np.ndarray | None = None
    texture: GougeTexture | None = None
    texture_marks: np.ndarray | None = None
    coolant: bool = False
    comment: str = ""
    source_id: int | None = None   # what the operation was made from (a STEP-NC workingstep's instance id)
    links: np.ndarray | None = None
    cycle: DrillCycle | None = None

    def __post_init__(self):
        self.kind = np.ascontiguousarray(self.kind, dtype=np.int8)
        self.xyz = np.ascontiguousarray(self.xyz, dtype=float).reshape(-1, 3)
        self.feed = np.ascontiguousarray(self.feed, dtype=float)
        n = len(self.kind)
        if self.center is None:
            self.center = np.full((n, 3), np.nan)
        self.center = np.ascontiguousarray(self.center, dtype=float).reshape(-1, 3)
        self.rotary = {k: np.ascontiguousarray(v, dtype=float) for k, v in self.rotary.items()}
        if self.start is None:
            first = self.xyz[0] if n else np.zeros(3)
            self.start = np.array([first[0], first[1], self.safe_z])
        self.start = np.asarray(self.start, dtype=float)
        if self.links is not None:
            self.links = np.ascontiguousarray(self.links, dtype=bool).reshape(-1)
        self.validate()

    def validate(self):
        n = len(self.kind)
        if self.xyz.shape != (n, 3) or self.feed.shape != (n,) or self.center.shape != (n, 3):
            raise ProgramError(f"operation {self.name!r}: move arrays have different lengths")
        for axis, values in self.rotary.items():
            if values.shape != (n,):
                raise ProgramError(f"operation {self.name!r}: rotary axis {axis} has {values.shape} values for {n} moves")
            if not np.all(np.isfinite(values)):
                raise ProgramError(f"operation {self.name!r}: rotary axis {axis} has a non-finite value")
        if n and not np.all(np.isin(self.kind, (RAPID, FEED, ARC_CW, ARC_CCW))):
            raise ProgramError(f"operation {self.name!r}: unknown move kind")
        if not np.all(np.isfinite(self.xyz)):
            bad = int(np.flatnonzero(~np.isfinite(self.xyz).all(axis=1))[0])
            raise ProgramError(f"operation {self.name!r}: move {bad} has a non-finite coordinate")
        cutting = self.kind != RAPID
        if np.any(cutting & ~(self.feed > 0)):
            bad = int(np.flatnonzero(cutting & ~(self.feed > 0))[0])
            raise ProgramError(f"operation {self.name!r}: cutting move {bad} has no positive feed")
        arcs = (self.kind == ARC_CW) | (self.kind == ARC_CCW)
        if np.any(arcs & ~np.isfinite(self.center[:, :2]).all(axis=1)):
            raise ProgramError(f"operation {self.name!r}: an arc has no centre")
        if not (np.isfinite(self.spindle_rpm) and self.spindle_rpm >= 0):
            raise ProgramError(f"operation {self.name!r}: spindle speed must be >= 0")
        if self.texture_marks is not None:
            marks = np.asarray(self.texture_marks, float)
            if marks.shape != (n, 2) or self.texture is None:
                raise ProgramError(f"operation {self.name!r}: texture marks need a texture and one (flag, fraction) "
                                   "pair per move")
        if self.links is not None and (self.links.shape != (n,) or np.any(self.links & (self.kind == RAPID))):
            raise ProgramError(f"operation {self.name!r}: links must mark feed moves, one flag per move")
        if self.cycle is not None:
            if not isinstance(self.cycle, DrillCycle):
                raise ProgramError(f"operation {self.name!r}: cycle must be a DrillCycle or None, "
                                   f"got {type(self.cycle).__name__}")
            self.cycle.validate()
            if np.any((self.kind == ARC_CW) | (self.kind == ARC_CCW)) or self.rotary:
                raise ProgramError(f"operation {self.name!r}: a drilling cycle's moves are straight, without rotary axes")
            self.cycle.check_moves(self.xyz, self.kind, FEED)
        if self.texture is not None and not isinstance(self.texture, GougeTexture):
            raise ProgramError(f"operation {self.name!r}: texture must be a GougeTexture or None, "
                               f"got {type(self.texture).__name__}")

    def __len__(self):
        return len(self.kind)

    def replace(self, **changes) -> "Operation":
        return dataclasses.replace(self, **changes)

    # ----- derived quantities -------------------------------------------------------
    def start_points(self) -> np.ndarray:
        """The point each move starts from, (n, 3)."""
        if not len(self):
            return np.empty((0, 3))
        return np.vstack([self.start[None, :], self.xyz[:-1]])

    def move_lengths(self) -> np.ndarray:
        """Path length of every move on the part in mm (arcs along the arc, helical included;
        with a C table along the curve the linear machine motion traces on the part)."""
        a = self.start_points()
        b = self.xyz
        if "c" in self.rotary and len(self):
            # Integrated along the curve (the costly case, asked for by every post, the cycle time
            # and the pictures): kept with copies of the moves it came from, used while they match.
            inputs = (self.start, self.xyz, self.rotary["c"])
            memo = self.__dict__.get("_traced_memo")
            if memo is not None and all(np.array_equal(x, y) for x, y in zip(memo[0], inputs)):
                return memo[1].copy()
            lengths = kinematics.traced_lengths(*kinematics.operation_c_moves(self))
            self.__dict__["_traced_memo"] = (tuple(np.array(x, copy=True) for x in inputs), lengths.copy())
            return lengths
        length = np.linalg.norm(b - a, axis=1)
        arcs = np.flatnonzero((self.kind == ARC_CW) | (self.kind == ARC_CCW))
        if len(arcs):
            c = self.center[arcs, :2]
            r = np.linalg.norm(a[arcs, :2] - c, axis=1)
            sweep = arc_sweep(a[arcs, :2], b[arcs, :2], c, self.kind[arcs] == ARC_CW)
            planar = np.abs(sweep) * r
            length[arcs] = np.hypot(planar, b[arcs, 2] - a[arcs, 2])
        return length

    def feed_length(self) -> float:
        return float(self.move_lengths()[self.kind != RAPID].sum())

    def rapid_length(self) -> float:
        return float(self.move_lengths()[self.kind == RAPID].sum())

    def cycle_time(self, rapid_rate: float) -> float:
        """Estimated seconds: cutting at the programmed feed, rapids at ``rapid_rate`` mm/min."""
        lengths = self.move_lengths()
        cutting = self.kind != RAPID
        seconds = float(np.sum(lengths[cutting] / self.feed[cutting]) * 60.0)
        seconds += float(lengths[~cutting].sum() / rapid_rate * 60.0)
        return seconds

    def feed_z_range(self) -> tuple[float, float]:
        cutting = self.kind != RAPID
        if not cutting.any():
            return (float("nan"), float("nan"))
        z = self.xyz[cutting, 2]
        return (float(z.min()), float(z.max()))

    def feeds(self) -> tuple:
        """(cutting feed, plunge feed) in mm/min, None where the operation has no such move: the
        cutting feed is the one the longest share of the cutting length runs at; the plunge feed
        the one of the longest share of the straight feed moves going only down Z (X, Y and the
        rotary axes still)."""
        cutting = self.kind != RAPID
        if not cutting.any():
            return None, None
        lengths = self.move_lengths()
        a, b = self.start_points(), self.xyz
        still = np.all(np.abs(b[:, :2] - a[:, :2]) <= 1e-9, axis=1) & (b[:, 2] < a[:, 2])
        for values in self.rotary.values():
            before = np.concatenate([values[:1], values[:-1]])
            still &= np.abs(values - before) <= 1e-9
        plunges = (self.kind == FEED) & still
        return _weighted_mode(self.feed[cutting & ~plunges], lengths[cutting & ~plunges]), \
            _weighted_mode(self.feed[plunges], lengths[plunges])

    def summary(self, rapid_rate: float) -> dict:
        zmin, zmax = self.feed_z_range()
        feed, plunge = self.feeds()
        tool = self.tool
        return {"name": self.name, "tool": tool.describe(), "tool_number": tool.number,
                "tool_kind": tool.kind, "tool_diameter_mm": float(tool.diameter),
                "tool_corner_radius_mm": float(tool.corner_radius), "tool_flute_length_mm": float(tool.flute_length),
                "spindle_rpm": float(self.spindle_rpm),
                "feed_mm_min": feed, "plunge_feed_mm_min": plunge,
                "moves": len(self), "feed_length_mm": round(self.feed_length(), 3),
                "cycle_time_s": round(self.cycle_time(rapid_rate), 1),
                "min_feed_z_mm": round(zmin, 4), "max_feed_z_mm": round(zmax, 4)}


def _weighted_mode(values: np.ndarray, weights: np.ndarray) -> float | None:
    """The value carrying the largest total weight (the first of equals); None for no values."""
    if not len(values):
        return None
    unique, index = np.unique(values, return_inverse=True)
    return float(unique[int(np.argmax(np.bincount(index.ravel(), weights=weights)))])


def walked(op: "Operation", arc_step: float = np.radians(6.0)) -> tuple:
    """(kind (m,), points (m + 1, 3)): the operation's path with every arc walked in pieces of at
    most ``arc_step`` radians (helical arcs climbing evenly), each piece keeping its arc's kind;
    straight moves as they are.  The start is the first point.  For drawing a path that has arcs
    (a viewport polyline would otherwise join an arc's ends with a chord)."""
    a, b = op.start_points(), op.xyz
    arcs = np.flatnonzero((op.kind == ARC_CW) | (op.kind == ARC_CCW))
    if not len(arcs) or op.rotary:
        return op.kind.copy(), np.vstack([op.start[None, :], op.xyz])
    centre = op.center[arcs, :2]
    sweep = arc_sweep(a[arcs, :2], b[arcs, :2], centre, op.kind[arcs] == ARC_CW)
    count = np.ones(len(op), np.int64)
    count[arcs] = np.maximum(np.ceil(np.abs(sweep) / arc_step).astype(np.int64), 1)
    owner = np.repeat(np.arange(len(op)), count)
    piece = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count) + 1
    points = b[owner].copy()
    on_arc = np.isin(owner, arcs)
    index = np.searchsorted(arcs, owner[on_arc])
    t = piece[on_arc] / count[owner[on_arc]]
    start = a[arcs][index]
    angle = np.arctan2(start[:, 1] - centre[index, 1], start[:, 0] - centre[index, 0]) + sweep[index] * t
    radius = np.hypot(start[:, 0] - centre[index, 0], start[:, 1] - centre[index, 1])
    points[on_arc] = np.column_stack([centre[index, 0] + radius * np.cos(angle),
                                      centre[index, 1] + radius * np.sin(angle),
                                      start[:, 2] + (b[arcs][index, 2] - start[:, 2]) * t])
    last = np.cumsum(count) - 1
    points[last] = b                   # each move ends exactly where it says
    return op.kind[owner], np.vstack([op.start[None, :], points])


@dataclass
class Program:
    """What a post turns into one NC file."""

    name: str
    operations: list
    units: str = "mm"
    work_offset: str = "G54"
    rapid_rate: float = 5000.0  # mm/min, for cycle-time estimates
    notes: list = field(default_factory=list)  # warnings worth writing into the header

    def cycle_time(self) -> float:
        return sum(op.cycle_time(self.rapid_rate) for op in self.operations)

    def tools(self) -> list:
        seen = {}
        for op in self.operations:
            seen.setdefault(op.tool.number, op.tool)
        return list(seen.values())

    def summary(self) -> list:
        return [op.summary(self.rapid_rate) for op in self.operations]


class PathBuilder:
    """Collects moves for one operation, then freezes them into arrays.

    ``retract_to_clearance`` and ``plunge`` keep the approach/retract logic in one place so
    every workflow moves between cuts the same way: up to the clearance plane, rapid
    across, rapid down to just above the work, feed in.
    """

    def __init__(self, clearance_z: float, feed: float, plunge_feed: float, approach_gap: float = 2.0,
                 surface_z: float = 0.0):
        self.clearance_z = clearance_z
        self.feed = feed
        self.plunge_feed = plunge_feed
        self.approach_z = surface_z + approach_gap
        self._blocks: list = []         # frozen (kind, xyz, feed, center) arrays, in order
        self._kind: list = []           # single moves since the last block
        self._xyz: list = []
        self._feed: list = []
        self._center: list = []
        self._count = 0                 # moves so far, in blocks and singles
        self._links: list = []          # indices of the feed moves :meth:`line` marked as links
        self.position = None

    def _add(self, kind, xyz, feed, center=(np.nan, np.nan, np.nan)):
        self._kind.append(kind)
        self._xyz.append(tuple(float(v) for v in xyz))
        self._feed.append(feed)
        self._center.append(center)
        self._count += 1
        self.position = self._xyz[-1]

    def rapid(self, x, y, z):
        self._add(RAPID, (x, y, z), np.nan)

    def line(self, x, y, z, feed=None, link: bool = False):
        """A feed move; ``link``: it goes from one cut to the next (:attr:`Operation.links`)."""
        if link:
            self._links.append(self._count)
        self._add(FEED, (x, y, z), self.feed if feed is None else feed)

    def polyline(self, points: np.ndarray, feed=None):
        """Feed moves through every point (k, 3), appended in one go (kept as arrays)."""
        points = np.array(points, dtype=float).reshape(-1, 3)      # a copy: the caller's may change
        if not len(points):
            return
        count = len(points)
        self._freeze()
        self._blocks.append((np.full(count, FEED, np.int8), points,
                             np.full(count, self.feed if feed is None else feed, dtype=float),
                             np.full((count, 3), np.nan)))
        self._count += count
        self.position = tuple(points[-1].tolist())

    def _freeze(self):
        """The single moves so far as one block of arrays."""
        if self._kind:
            n = len(self._kind)
            self._blocks.append((np.array(self._kind, dtype=np.int8), np.array(self._xyz, dtype=float).reshape(n, 3),
                                 np.array(self._feed, dtype=float), np.array(self._center, dtype=float).reshape(n, 3)))
            self._kind, self._xyz, self._feed, self._center = [], [], [], []

    def arc(self, x, y, z, cx, cy, clockwise: bool, feed=None):
        self._add(ARC_CW if clockwise else ARC_CCW, (x, y, z), self.feed if feed is None else feed,
                  (cx, cy, z))

    def retract(self):
        if self.position is not None and self.position[2] < self.clearance_z:
            self.rapid(self.position[0], self.position[1], self.clearance_z)

    def plunge(self, x, y, z):
        """Go from anywhere to (x, y, z): retract, rapid over, rapid to the approach gap, feed down."""
        if self.position is not None and np.allclose(self.position, (x, y, z)):
            return
        self.retract()
        self.rapid(x, y, self.clearance_z)
        if self.approach_z < self.clearance_z and z < self.approach_z:
            self.rapid(x, y, self.approach_z)
        self.line(x, y, z, self.plunge_feed)

    def arrays(self):
        self._freeze()
        if not self._blocks:
            return dict(kind=np.zeros(0, np.int8), xyz=np.zeros((0, 3)), feed=np.zeros(0), center=np.zeros((0, 3)))
        kind, xyz, feed, center = (np.concatenate(column) for column in zip(*self._blocks))
        self._blocks = [(kind, xyz, feed, center)]
        return dict(kind=kind.copy(), xyz=xyz.copy(), feed=feed.copy(), center=center.copy())

    def links(self) -> np.ndarray:
        """(n,) bool: the moves :meth:`line` marked as links."""
        marks = np.zeros(self._count, bool)
        marks[self._links] = True
        return marks


def merge_short_moves(op: Operation, tolerance: float, min_minutes: float = kinematics.SHORTEST_BLOCK_MINUTES,
                      resolution: float = 0.001, accept=None, accept_above: float = 0.0) -> Operation:
    """``op`` with its too-short straight cutting moves merged into their neighbours.

    A cutting move is too short when it is shorter than ``resolution`` (the least increment a
    control reads: it would be written as no motion, or as one digit of motion timed over the true
    0.0001 mm) or takes less than ``min_minutes`` at its feed (a block the control cannot time: its
    inverse-time F would pass the word's ceiling, :data:`kinematics.SHORTEST_BLOCK_MINUTES`).  Its end
    point is dropped, so the move and the next straight cutting move become one, when the dropped
    point stays within ``tolerance`` of the merged move (measured on the part: C is turned back with
    :func:`kinematics.machine_to_part`, and for a C move the merged move's bend counts too); the last
    move before a rapid merges with the one before it instead.  A merged move takes the lower feed of
    the two.  A short move that cannot be merged within tolerance stays; the timing floor
    (:func:`kinematics.block_minutes`) then times it, so it is cut slower, never written with an F
    word the control cannot read.  Rapids and arcs are never touched.  The planners of the rotary
    machines (:mod:`rotary`, :mod:`turnmill`) apply this to every operation they make.
    ``accept(a, c_a, b, c_b)``: optional, a further condition on merged moves whose dropped point
    lies more than ``accept_above`` off them, such as the tool staying clear of the part: for m
    moves from machine points a (m, 3) at C c_a (m,) to b at c_b (C 0 without a C axis), (m,) bool.
    It is asked once, for every merge as first proposed (move k's end dropped into k + 1, or k - 1's
    into k); a merge proposed only after others were made is not made where ``accept`` is asked.
    """
    n = len(op)
    if n < 2:
        return op
    has_c = "c" in op.rotary
    c_all = np.concatenate([[op.rotary["c"][0]], op.rotary["c"]]) if has_c else np.zeros(n + 1)
    machine = np.vstack([op.start[None, :], op.xyz])          # point k = end of move k - 1; point 0 = start
    part = kinematics.machine_to_part(machine, c_all) if has_c else machine
    kind = np.concatenate([[RAPID], op.kind])                 # kind of the move ending at each point
    feed = np.concatenate([[np.nan], op.feed])
    lengths = np.concatenate([[0.0], op.move_lengths()])
    short = (kind == FEED) & ((lengths < resolution) | (lengths / np.where(kind == FEED, feed, 1.0) < min_minutes))
    keep = np.ones(n + 1, bool)
    previous = np.arange(n + 1) - 1                           # the kept point before each point

    def deviation(a, p, b) -> float:
        """Distance of part point p from the part segment a-b, plus the bend of the merged C move."""
        ab, ap = part[b] - part[a], part[p] - part[a]
        t = float(np.clip(np.dot(ap, ab) / max(float(np.dot(ab, ab)), 1e-30), 0.0, 1.0))
        off = float(np.linalg.norm(ap - t * ab))
        if has_c:
            _, bend = kinematics.speed_and_bend(machine[a, 0:1], c_all[a:a + 1], machine[b, 0:1], c_all[b:b + 1])
            off += float(bend[0]) / 8.0
        return off

    accepted = {}
    if accept is not None:
        first = [(k - 1, k, k + 1) if k < n and kind[k + 1] == FEED else (k - 2, k - 1, k)
                 for k in np.flatnonzero(short).tolist() if k >= 2 or (k == 1 and k < n and kind[k + 1] == FEED)]
        if first:
            triples = np.array(first)
            answers = accept(machine[triples[:, 0]], c_all[triples[:, 0]], machine[triples[:, 2]], c_all[triples[:, 2]])
            accepted = dict(zip(first, np.asarray(answers, bool).tolist()))

    def accepts(a, drop, b) -> bool:
        return accepted.get((a, drop, b), False)

    for k in np.flatnonzero(short).tolist():
        if not keep[k]:
            continue
        a = previous[k]
        if a < 0:
            continue
        move_length = float(np.linalg.norm(part[k] - part[a]))
        if move_length >= resolution and move_length / feed[k] >= min_minutes:
            continue                                          # no longer short once an earlier point went
        if k < n and kind[k + 1] == FEED:                     # drop k: a -> k -> k+1 becomes a -> k+1
            drop, after = k, k + 1
        elif kind[a] == FEED and previous[a] >= 0:            # drop a: prev(a) -> a -> k becomes prev(a) -> k
            drop, after = a, k
        else:
            continue
        off = deviation(previous[drop], drop, after)
        if off > tolerance or (accept is not None and off > accept_above and not accepts(previous[drop], drop, after)):
            continue
        keep[drop] = False
        previous[after] = previous[drop]
        feed[after] = min(feed[after], feed[drop])
    if keep.all():
        return op
    moves = keep[1:]
    changes = dict(kind=op.kind[moves], xyz=op.xyz[moves], feed=feed[1:][moves], center=op.center[moves])
    if op.rotary:
        changes["rotary"] = {axis: values[moves] for axis, values in op.rotary.items()}
    return op.replace(**changes)


# The X-Z-C machine family's operation (was xzc.py): The X-Z-C machine family's operation: a turn-mill centre turning the part on C, its turret's
TOOL_DIRECTIONS = ("radial", "axial")   # the turret tools of an X-Z-C turn-mill centre


@dataclass
class TurnMillOperation(Operation):
    """An X-Z-C operation: ``xyz`` = (X, 0, Z) of the tool tip, X the radius from the axis,
    ``rotary = {"c": degrees}``.  ``direction`` is the turret tool: "radial" (along machine X,
    pointing at the axis) or "axial" (along Z, pointing down).  Lengths and cycle times are
    measured in part coordinates, where the tool actually cuts, along the curve the tool tip traces
    (:func:`kinematics.traced_lengths`, the one convention of every C move)."""

    direction: str = "radial"

    def validate(self):
        super().validate()
        if self.direction not in TOOL_DIRECTIONS:
            raise ProgramError(f"operation {self.name!r}: direction must be one of {TOOL_DIRECTIONS}")
        if set(self.rotary) != {"c"}:
            raise ProgramError(f"operation {self.name!r}: an X-Z-C operation moves exactly the C axis")
        if np.any(self.xyz[:, 1] != 0):
            raise ProgramError(f"operation {self.name!r}: the machine has no Y axis (Y must be 0)")

    def part_start(self) -> np.ndarray:
        """Where the tool tip is before the first move, in part coordinates (3,)."""
        return kinematics.machine_to_part(self.start, self.rotary["c"][:1])[0]

    def part_points(self) -> np.ndarray:
        """Tool-tip positions in part coordinates."""
        return kinematics.part_points(self)

    def tool_axes(self) -> np.ndarray:
        """Unit tool-axis vectors (tip towards holder) in part coordinates."""
        if self.direction == "axial":
            return np.tile([0.0, 0.0, 1.0], (len(self), 1))
        return kinematics.radial_axes(self.rotary["c"])

    def ball_centres(self) -> np.ndarray:
        return self.part_points() + self.tool.radius * self.tool_axes()

    def cycle_time(self, rapid_rate: float) -> float:
        """Estimated seconds: cutting blocks timed as the post's G93 F words time them
        (:func:`kinematics.block_minutes`), rapids at ``rapid_rate`` mm/min."""
        lengths = self.move_lengths()
        cutting = self.kind != RAPID
        minutes = kinematics.block_minutes(lengths[cutting], self.feed[cutting]).sum()
        return float(minutes * 60.0 + lengths[~cutting].sum() / rapid_rate * 60.0)


def default_machine(family: str, name: str = ""):
    """The machine profile a program of ``family`` assumes when the user picks only the post:
    the preset ``name`` (a post's own), else the family's default; None for a family without
    machines (CL data)."""
    name = name or DEFAULT_FOR_FAMILY.get(family)
    return preset(name) if name else None


def fit_program(program: Program, **settings) -> Program:
    """Arcs out, the filter every milling post runs before writing: :func:`.arcfit.fit_program`
    (``tolerance``, ``end_tolerance``, ``written``, ``step``), imported at the first call, as it
    brings numba, which the IR and the posts do not load before a program is written."""
    from . import arcfit

    return arcfit.fit_program(program, **settings)


# ----- the turret-punch family's program: lines of hits a round punch makes in a sheet (see PunchProgram)

COMPENSATIONS = ("none", "left", "right")


def _number(value, what: str) -> float:
    """``value`` as a finite number > 0, or a :class:`ProgramError` naming ``what``."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ProgramError(f"{what} must be a number, got {value!r}") from None
    if not math.isfinite(number) or number <= 0:
        raise ProgramError(f"{what} must be a finite number > 0, got {value!r}")
    return number


@dataclass
class PunchOperation:
    """One turret station's hits: ``lines`` (k, 2, 2), the first and the last hit of each line, in
    the order they are punched.  ``punch_diameter`` the round punch's size, ``pitch`` the largest
    spacing between hits (the G69 Q word), ``thickness`` the sheet's, all in mm."""

    name: str
    station: int
    punch_diameter: float
    pitch: float
    thickness: float
    lines: np.ndarray
    compensation: str = "none"

    def __post_init__(self):
        try:
            self.lines = np.array(self.lines, dtype=float)       # a copy: the caller's may change
        except (TypeError, ValueError):
            raise ProgramError(f"operation {self.name!r}: lines must be (first hit, last hit) pairs of (x, y)") from None
        self.validate()

    def validate(self):
        station_ok = isinstance(self.station, (int, np.integer)) and not isinstance(self.station, bool)
        if not station_ok or not 1 <= self.station <= 999:
            raise ProgramError(f"turret station must be an integer 1..999, got {self.station!r}")
        self.punch_diameter = _number(self.punch_diameter, "punch diameter")
        self.pitch = _number(self.pitch, "nibbling pitch Q")
        self.thickness = _number(self.thickness, "sheet thickness")
        if self.lines.ndim != 3 or self.lines.shape[1:] != (2, 2) or len(self.lines) == 0:
            raise ProgramError(f"lines must be (first hit, last hit) pairs of (x, y), got shape {self.lines.shape}")
        if not np.all(np.isfinite(self.lines)):
            raise ProgramError("a line has a non-finite coordinate (NaN or infinity)")
        if self.compensation not in COMPENSATIONS:
            raise ProgramError(f"operation {self.name!r}: compensation must be one of {COMPENSATIONS}, "
                               f"got {self.compensation!r}")

    def __len__(self):
        return len(self.lines)

    def lengths(self) -> np.ndarray:
        """Each line's length, first hit to last (mm)."""
        delta = self.lines[:, 1] - self.lines[:, 0]
        return np.hypot(delta[:, 0], delta[:, 1])

    def angles(self) -> np.ndarray:
        """Each line's direction in degrees from +X, counter-clockwise positive (-180..180)."""
        delta = self.lines[:, 1] - self.lines[:, 0]
        return np.degrees(np.arctan2(delta[:, 1], delta[:, 0]))


@dataclass
class PunchProgram:
    """What a punch post turns into one NC file: ``operations`` (:class:`PunchOperation`) in order,
    ``origin`` the sheet origin the program sets (machine X, Y in mm: the Amada G92), ``notes`` lines
    the post writes as comments at the start (where the part sits on the sheet, the clamps, the joints)."""

    name: str
    operations: list
    origin: tuple = (1000.0, 1040.0)
    notes: list = field(default_factory=list)

    def __post_init__(self):
        self.validate()

    def validate(self):
        if not self.operations or not all(isinstance(op, PunchOperation) for op in self.operations):
            raise ProgramError(f"punch program {self.name!r}: its operations must be one or more PunchOperations")
        try:
            x, y = (float(v) for v in self.origin)
        except (TypeError, ValueError):
            raise ProgramError(f"G92 origin must be two numbers (x, y), got {self.origin!r}") from None
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ProgramError("G92 origin must be finite")
        self.origin = (x, y)
        for op in self.operations:
            op.validate()

    def line_count(self) -> int:
        return sum(len(op) for op in self.operations)
