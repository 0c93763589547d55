"""W6: material-removal simulation and safety checks.

One call, :func:`simulate`, with two engines behind it:

``"heightfield"`` (Z-map)
    The stock is a grid of columns; each column keeps the lowest Z any tool reached over
    its centre.  The tool axis is Z (3-axis jobs, and C-X-Z jobs where the tool is parallel
    to the table axis).  Per cell the value is the *exact* lower envelope of the tool swept
    along each straight move (closed forms, no sampling along the move):

    * ball: the capsule (the ball centre's segment thickened by R);
    * flat end: the swept disc, lowest at one end of the contact range;
    * bull nose: the flat disc of radius R - r plus the torus: beside level moves exact, elsewhere
      a ring of spheres (spaced so the surface error stays within ``tolerance``);
    * drill / V-bit: the cone's flank beside each move, its rim (a flat disc at the cone's
      top) beside each move that climbs or falls, and the whole cone at the points.

    Speed comes from taking the tool path as one chain.  The envelope of a convex tool over
    one move, g(t) = z(t) + h(|P - C(t)|), is convex in t, so at a cell P the lowest value
    over the whole chain is either an interior minimum of one move (a band of width ~ the
    move's length beside the move: the cylinder part of the capsule, or the leading edge
    of the flat disc) or sits at a vertex where the incoming move still falls and the
    outgoing one rises (for a raster that is a thin sliver).  Each of these regions is cut
    per grid column into exact y-intervals (roots of a quadratic), so a short raster move
    costs ~2R*L/cell^2 cells instead of the ~pi*R^2/cell^2 of stamping the whole tool.

    Two kernels evaluate the regions (``kernel=``): a compiled one (numba, in
    kernel.py), used where numba can be imported, and pure numpy, the fallback.
    They do the same arithmetic in the same order and write the same heights.

``"manifold"``
    Exact solids: the stock minus the swept tool, built in sweep.py (tubes of the tool's
    section along runs of moves, wedges of the tool at corners, hulls of the tool elsewhere),
    unioned in chunks with ``Manifold.batch_boolean``.  Every piece lies within ``tolerance``
    of the true sweep: the tool's corner is an area-equal polygon (no bias in volume), beyond
    the sweep by at most ``sweep.outside`` (under 0.75 x tolerance); other errors leave material.

Rotary C (SPEC W2, C-X-Z): the table turns about Z; a machine position (X, Y, C) is the part
point ``Rot(C) @ (X, Y)`` (X = -R, C = the angle of the part point from the -X axis).
Moves are interpolated in machine coordinates (X, Y, Z and C linear; G2/G3 arcs in machine
XY), cut into chords within :data:`CHORD_TOLERANCE` and converted to part coordinates.

Safety checks (:func:`check`, also part of every :func:`simulate` result): gouges below a
design surface, rapids touching material (moves processed in order against the stock as it
is at that moment), moves outside the machine travel, plunges with tools that cannot
plunge, tools going below a box stock's bottom (into the fixture) and cuts with the spindle
stopped.  :func:`blocking` picks those that stop an export (the export gate).  Every :class:`Finding` names the operation and the move index within it.

Coordinates are millimetres, Z is the tool tip.  Stock: a box, or a cylinder about the Z
axis with its top face at z = 0 (a board on a rotary table).

Layout: stock.py (settings, stocks, findings, the height field), paths.py (moves -> chains of points),
families.py (the height field's regions), heightfield.py (the grid and its evaluation),
kernel.py (the compiled kernels), meshtop.py (a mesh's upper envelope over the grid), checks.py
(design heights and findings), meshes.py (preview meshes, solids <-> arrays), result.py (what a
simulation returns), radiusmap.py (radial turn-mill work), sweep.py, facets.py, floors.py and repeats.py
(the manifold engine's swept solids: pieces, the tool as facets, footprints and shank prisms, runs
that repeat), api.py (:func:`simulate` and :func:`check`).
"""
from __future__ import annotations

from .api import check, check_cell, simulate
from .checks import BLOCKING_KINDS, blocking
from .paths import can_plunge
from .stock import (CHORD_TOLERANCE, ENGINES, GOUGE_TOLERANCE, KERNELS, MAX_CELLS, TOUCH_TOLERANCE, BoxStock, SurfaceStock, CellError, CellTooFine, CylinderStock, Finding, HeightField, SimulationCancelled, SimulationError, as_stock)
from .result import SimulationResult

__all__ = ["simulate", "check", "check_cell", "blocking", "BLOCKING_KINDS", "can_plunge", "as_stock", "BoxStock", "SurfaceStock", "CylinderStock", "Finding", "HeightField",
           "SimulationResult", "SimulationError", "CellError", "CellTooFine", "SimulationCancelled", "ENGINES", "KERNELS", "CHORD_TOLERANCE",
           "TOUCH_TOLERANCE", "GOUGE_TOLERANCE", "MAX_CELLS"]
