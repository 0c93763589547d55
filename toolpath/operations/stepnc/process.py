"""ISO 14649-10/-11/-111 process data as frozen dataclasses: the machining operations (plane milling,
bottom and side milling, drilling, freeform with explicit toolpaths, rapid movements) with their cutting
tool, technology, machine functions, strategy and approach/retract.  Units as in the file: lengths in
mm, angles in degrees, feed in m/s and spindle in rev/s (:class:`MillingTechnology` converts to mm/min
and rpm).  Part of the typed model (see :mod:`.model`)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Union

from .geometry import Vec3

# The entity types the reader takes for a tool's dimension and body.
DIMENSION_TYPES = ("MILLING_TOOL_DIMENSION", "TOOL_DIMENSION")
MILLING_TOOL_BODIES = ("ENDMILL", "TAPERED_ENDMILL", "BALL_ENDMILL", "BULLNOSE_ENDMILL", "FACEMILL")
DRILLING_TOOL_BODIES = ("TWIST_DRILL", "TAPERED_DRILL", "CENTER_DRILL", "REAMER", "TAPERED_REAMER")
TAPERED_BODIES = ("TAPERED_ENDMILL", "TAPERED_DRILL", "TAPERED_REAMER")


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
class MachiningAttributes:
    """What every machining_operation of ISO 14649-10 has and the converter uses (``type_name``: which
    operation it is), in the standard's order; the operations below add their own."""

    id: int
    type_name: str
    its_id: str
    retract_plane: float | None
    its_tool: CuttingTool
    its_technology: MillingTechnology
    its_machine_functions: MachineFunctions | None


@dataclass(frozen=True)
class MillingAttributes(MachiningAttributes):
    """What the milling_type_operations (plane, bottom and side) add."""

    approach: ApproachRetract | None
    retract: ApproachRetract | None
    its_machining_strategy: MillingStrategy | None
    axial_cutting_depth: float | None


@dataclass(frozen=True)
class PlaneMilling(MillingAttributes):
    """PLANE_ROUGH_MILLING or PLANE_FINISH_MILLING (``type_name``)."""

    allowance_bottom: float | None

    @property
    def finishing(self) -> bool:
        return self.type_name == "PLANE_FINISH_MILLING"


@dataclass(frozen=True)
class BottomAndSideMilling(MillingAttributes):
    """BOTTOM_AND_SIDE_ROUGH_MILLING or BOTTOM_AND_SIDE_FINISH_MILLING (``type_name``)."""

    radial_cutting_depth: float | None
    allowance_side: float | None
    allowance_bottom: float | None

    @property
    def finishing(self) -> bool:
        return self.type_name == "BOTTOM_AND_SIDE_FINISH_MILLING"


@dataclass(frozen=True)
class DrillingOperation(MachiningAttributes):
    """DRILLING, CENTER_DRILLING or REAMING (``type_name``); ``spindle_stop_at_bottom`` is
    REAMING's own attribute (None for the others)."""

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
class FreeformOperation(MachiningAttributes):
    """FREEFORM_OPERATION with explicit toolpaths (a TOOLPATH_LIST of trajectories), given in the
    coordinates of the workingstep's feature."""

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
