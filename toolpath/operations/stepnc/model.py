"""ISO 14649-10/-11 (STEP-NC, milling) entities as a small typed model, and its top: the project.

:func:`.reader.read_project` turns a parsed Part 21 file (:mod:`.part21`) into these frozen dataclasses:
PROJECT -> WORKPLAN -> MACHINING_WORKINGSTEP (security plane, feature, operation) with the
features, operations, strategies, tools and technology a 2.5-D job needs.  Each class keeps
the attributes it uses, named and ordered as in the standard; ``id`` is the instance number.
The model is held by theme:

* this module: PROJECT, WORKPIECE, WORKPLAN, SETUP, MACHINING_WORKINGSTEP and the limits the reader
  holds every entity to;
* :mod:`.geometry`: placements, planes, the block and the curves;
* :mod:`.features`: the features with their profiles and paths;
* :mod:`.process`: the operations with their tools, technology, strategies and toolpaths;
* :mod:`.errors`: the two kinds of trouble below.

Spellings found in the wild are all accepted: BIDIRECTIONAL / BIDIRECTIONAL_MILLING,
UNIDIRECTIONAL / UNIDIRECTIONAL_MILLING, TOOL_DIMENSION / MILLING_TOOL_DIMENSION,
ELEMENTARY_SURFACE / PLANE (NIST's toolkit rewrote the ISO examples with the second names).

Two kinds of trouble are kept apart (:mod:`.errors`):

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

from dataclasses import dataclass

from ...ir.errors import MAX_REACH_MM
from .features import Feature
from .geometry import Block, Placement, Plane
from .process import MachiningOperation

# The limits and measure types the reader holds every entity to:
MAX_NAME = 200    # characters of a workingstep name written (as a comment); a longer one is cut, with a note
MAX_LENGTH = MAX_REACH_MM    # mm: 100 m, larger than any machine (errors.MAX_REACH_MM)
LENGTH_TYPES = ("TOLERANCED_LENGTH_MEASURE", "NUMERIC_PARAMETER")


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
