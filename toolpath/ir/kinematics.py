"""Machine <-> part coordinates for the rotary-axis machines, and the length and time of a move.

The one home of this conversion.  Pure numpy; imports nothing of the project, so the IR
(:mod:`program`) and the posts can both use it.

Machines
--------
Both machines turn the part about Z by the C axis and move the tool in X and Z only; the IR
holds ``xyz = (X, 0, Z)`` and ``rotary = {"c": degrees}``, C unwrapped (continuous).

One rule maps them to the part: **the part point under the tool is R(C) (X, Y, Z)**, the machine
point turned counter-clockwise (seen from +Z) by C about Z (:func:`machine_to_part`).  So C is the
part angle of the point under the tool, measured from the machine's X direction the tool sits on.

* C-X-Z rotary table (:mod:`rotary`, W2): the tool stays on the negative side, ``X = -R``; C is
  the angle of the part point measured counter-clockwise from the part's -X axis, so ``(-R, 0)``
  has C = 0 (:func:`to_cylindrical`).  Bringing that point under the tool turns the table by -C:
  **+C turns the table clockwise seen from the tool**, i.e. the tool moves counter-clockwise
  relative to the part (ISO 841's +C for the tool).  The C-X-Z posts' header says exactly this.
* X-Z-C turn-mill (:mod:`turnmill`, W4): ``X = +R``, C = atan2(y, x) of the part point, the angle
  brought to the tool on the machine's +X side (:func:`polar`): machine point = Rz(-C) part point.

Length of a move that turns C
-----------------------------
The machine interpolates X, Z and C linearly, so a move traces a spiral piece on the part, not
the chord between its end points.  **The length of a move is the length of that traced curve**
(:func:`traced_lengths`): the distance the tool tip travels over the part.  A full C turn at
radius R is 2 pi R; a move without C motion is its straight length.  This is what
``Operation.move_lengths`` returns for an operation with a C axis, what the C-X-Z posts' G93
inverse-time F words and cycle-time estimates are made of (:func:`inverse_time_feed`,
:func:`cycle_time`), and what the rotary planner's feeds mean.

The X-Z-C turn-mill operation (``xzc.TurnMillOperation``) measures its moves the same way.
(It once used the chord between the part points, :func:`chord_lengths`, still here for its planner,
which splits every move until the traced curve stays within the chordal tolerance of that chord,
:func:`polar_split_counts`.  Moving it to the traced length made its cutting moves a few parts per
million longer, at most 1e-4, and the sample's cycle time 2496 s -> 2500 s, mostly rapids turning
C at the clearance radius.)
"""
from __future__ import annotations

import numpy as np

DEFAULT_MAX_TABLE_RPM = 60.0   # the C table as an axis, for feeds and time estimates
# The shortest time a cutting block is timed at (minutes): 1/9000 min = 6.7 ms.  A control needs a few
# milliseconds to read and plan each block anyway, and the inverse-time F word has a ceiling (Fanuc
# 0i/16/18-M: G93 F 0.001..9999.999, i.e. at least 6 ms per block).  Planners first merge moves
# shorter than this where the path stays within tolerance (``program.merge_short_moves``); a move
# that remains is timed at this floor (so cut slower, honestly, and counted in the cycle time), never
# given an F word the control cannot read.
SHORTEST_BLOCK_MINUTES = 1.0 / 9000.0
ON_AXIS = 1e-9                 # mm: points closer to the axis than this have no angle of their own
_RAPID = 0                     # program.RAPID (program imports this module, not the other way)


def _norms(v: np.ndarray) -> np.ndarray:
    """Lengths of the rows of (n, 2) or (n, 3) vectors (np.linalg.norm is slow on short rows)."""
    return np.sqrt(sum(v[:, k] * v[:, k] for k in range(v.shape[1])))


# ----- points ---------------------------------------------------------------------------------
def machine_to_part(xyz, c_degrees) -> np.ndarray:
    """Machine (X, Y, Z) at C (degrees) -> part points (n, 3): the machine point turned by C.
    (Our machines have no Y; a Y word read from a program turns with X.)"""
    xyz = np.asarray(xyz, dtype=float).reshape(-1, 3)
    angle = np.radians(np.asarray(c_degrees, dtype=float).reshape(-1))
    cos, sin = np.cos(angle), np.sin(angle)
    return np.column_stack([xyz[:, 0] * cos - xyz[:, 1] * sin, xyz[:, 0] * sin + xyz[:, 1] * cos, xyz[:, 2]])


def from_cylindrical(x_word, c_deg) -> np.ndarray:
    """(X word, C degrees) -> part XY (n, 2): the machine point (X, 0) turned back by C."""
    x, c = np.broadcast_arrays(np.asarray(x_word, float).reshape(-1), np.asarray(c_deg, float).reshape(-1))
    return machine_to_part(np.column_stack([x, np.zeros(len(x)), np.zeros(len(x))]), c)[:, :2]


def to_cylindrical(xy) -> tuple[np.ndarray, np.ndarray]:
    """C-X-Z: part XY (n, 2) -> (X word = -R, C in degrees in (-180, 180]).  A point on the axis
    gets C = 0 (use :func:`unwrap_c` along a path)."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    # + 0.0 turns -0.0 into 0.0, so a point on the +X axis gets C = 180, not -180.
    return -_norms(xy), np.degrees(np.arctan2(0.0 - xy[:, 1], 0.0 - xy[:, 0]))


def part_points(op) -> np.ndarray:
    """An operation's end points (tool tip) in part coordinates, (n, 3)."""
    return machine_to_part(op.xyz, op.rotary["c"])


def polar(points) -> tuple[np.ndarray, np.ndarray]:
    """X-Z-C: part points (n, >= 2) -> (R, part angle atan2(y, x) in radians, not unwrapped).  On
    the axis, where the angle is undefined, the previous point's angle is kept."""
    points = np.asarray(points, dtype=float)
    rho = np.hypot(points[:, 0], points[:, 1])
    angle = np.arctan2(points[:, 1], points[:, 0])
    defined = rho > ON_AXIS
    if not defined.all():
        last = np.maximum.accumulate(np.where(defined, np.arange(len(rho)), 0))
        angle = np.where(defined, angle, angle[last])
    return rho, angle


def radial_axes(c_degrees) -> np.ndarray:
    """X-Z-C: the machine's +X direction in part coordinates at each C, (n, 3) unit vectors (the
    axis of a radial turret tool, tip towards holder)."""
    angle = np.radians(np.asarray(c_degrees, dtype=float).reshape(-1))
    return np.column_stack([np.cos(angle), np.sin(angle), np.zeros(len(angle))])


def unwrap_c(c_deg, radius, start_c: float | None = None) -> np.ndarray:
    """Continuous C along a path: each value within 180 degrees of the one before it.

    Points on the axis (radius ~ 0) have no angle of their own and keep the previous C (the
    leading ones take the first C off the axis).  ``start_c`` is where the table already is:
    the path starts within half a turn of it.
    """
    c = np.array(c_deg, float).reshape(-1)
    on_axis = np.asarray(radius, float).reshape(-1) < ON_AXIS
    if on_axis.all():
        return np.full(len(c), 0.0 if start_c is None else float(start_c))
    index = np.where(~on_axis, np.arange(len(c)), 0)
    np.maximum.accumulate(index, out=index)
    first = int(np.flatnonzero(~on_axis)[0])
    c = np.where(np.arange(len(c)) < first, c[first], c[index])
    if start_c is not None:
        c = np.concatenate([[start_c], c])
    c = np.unwrap(c, period=360.0)
    return c[1:] if start_c is not None else c


# ----- moves ----------------------------------------------------------------------------------
def interpolate(x0, c0, z0, x1, c1, z1, t) -> np.ndarray:
    """Part points (n, 3) of the linear X/C/Z machine motion at parameter t (n,)."""
    x = x0 + (x1 - x0) * t
    xy = from_cylindrical(x, c0 + (c1 - c0) * t)
    return np.column_stack([xy, z0 + (z1 - z0) * t])


def speed_and_bend(x0, c0, x1, c1) -> tuple[np.ndarray, np.ndarray]:
    """Bounds on |p'| and |p''| (t in [0, 1]) of the plan point p = R (cos C, sin C) that
    linear X/C moves trace on the part, R = |X|: |p'|^2 = R'^2 + (R C')^2 and |p''|^2 =
    (R C'^2)^2 + (2 R' C')^2 (C in radians), largest at the move's larger R.  A move strays at
    most bend / 8 from its chord."""
    radius = np.maximum(np.abs(x0), np.abs(x1))
    grow, turn = np.abs(x1 - x0), np.radians(np.abs(c1 - c0))
    return np.sqrt(grow ** 2 + (radius * turn) ** 2), turn * np.sqrt((radius * turn) ** 2 + (2 * grow) ** 2)


def polar_split_counts(points: np.ndarray, tolerance: float) -> np.ndarray:
    """X-Z-C: into how many pieces to split each part-space segment between ``points`` (n, >= 2)
    so that linear X-C interpolation bends away from the straight segment by at most
    ``tolerance``.  A sweep of d radians at radius R bends by R (1 - cos(d / 2))."""
    rho = np.hypot(points[:, 0], points[:, 1])
    theta = np.arctan2(points[:, 1], points[:, 0])
    sweep = np.abs((np.diff(theta) + np.pi) % (2 * np.pi) - np.pi)
    reach = np.maximum(rho[:-1], rho[1:])
    limit = 2.0 * np.arccos(np.clip(1.0 - tolerance / np.maximum(reach, 1e-12), -1.0, 1.0))
    return np.maximum(1, np.ceil(sweep / limit - 1e-9)).astype(int)


# 8-point Gauss-Legendre nodes on [0, 1] and weights: the speed along a table move is smooth.
_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(8)
_GAUSS_T, _GAUSS_W = (_GAUSS_X + 1) / 2, _GAUSS_W / 2


def traced_lengths(a: np.ndarray, b: np.ndarray, c0: np.ndarray, c1: np.ndarray) -> np.ndarray:
    """The length convention: length on the part of moves from a to b (machine xyz) while C
    turns c0 -> c1 (degrees), along the curve the linear machine motion traces.

    The part point is p = R(C) m with m the machine point, so |dp/dt|^2 =
    |m'|^2 + C'^2 |m|^2 + 2 C' (m_x m'_y - m_y m'_x) + z'^2, integrated by Gauss-Legendre
    (exact to rounding for a turn at constant radius: 2 pi R per turn).
    """
    d = b - a
    dc = np.radians(c1 - c0)[:, None]
    mx = a[:, 0:1] + d[:, 0:1] * _GAUSS_T[None, :]
    my = a[:, 1:2] + d[:, 1:2] * _GAUSS_T[None, :]
    planar = (d[:, 0:1] ** 2 + d[:, 1:2] ** 2 + dc ** 2 * (mx ** 2 + my ** 2)
              + 2 * dc * (mx * d[:, 1:2] - my * d[:, 0:1]))
    speed = np.sqrt(np.maximum(planar, 0.0) + d[:, 2:3] ** 2)
    return np.einsum("ij,j->i", speed, _GAUSS_W)      # not BLAS: its helper thread spins after each call


def chord_lengths(a: np.ndarray, b: np.ndarray, c0: np.ndarray, c1: np.ndarray) -> np.ndarray:
    """The turn-mill exception (see the module notes): the straight distance on the part between
    the end points of moves from a to b (machine xyz) while C turns c0 -> c1 (degrees)."""
    return np.linalg.norm(machine_to_part(b, c1) - machine_to_part(a, c0), axis=1)


def operation_c_moves(op) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(start points, end points, start C, end C) of every move of an operation with a C axis;
    its first move starts at its first C."""
    c = op.rotary["c"]
    return op.start_points(), op.xyz, np.concatenate([[c[0]], c[:-1]]), c


# ----- C-table timing (the C-X-Z posts' G93 feeds and time estimates) --------------------------
def move_times(op, rapid_rate: float, max_table_rpm: float = DEFAULT_MAX_TABLE_RPM,
               lengths: np.ndarray | None = None) -> np.ndarray:
    """Seconds per move of a C-X-Z operation.  Cutting: path length on the part
    (``op.move_lengths()``, :func:`traced_lengths`) / the move's feed, never less than
    :data:`SHORTEST_BLOCK_MINUTES`, or longer when the table cannot turn that fast; rapids: the
    slowest axis (X/Z at ``rapid_rate``, C at
    ``max_table_rpm``).  ``lengths``: ``op.move_lengths()`` when already at hand."""
    a, b, c0, c1 = operation_c_moves(op)
    table = np.abs(c1 - c0) / (360.0 * max_table_rpm)
    cutting = op.kind != _RAPID
    lengths = op.move_lengths() if lengths is None else lengths
    minutes = np.where(cutting, block_minutes(lengths, np.where(cutting, op.feed, 1.0)),
                       np.sqrt((b[:, 0] - a[:, 0]) ** 2 + (b[:, 2] - a[:, 2]) ** 2) / rapid_rate)
    return np.maximum(minutes, table) * 60.0


def block_minutes(lengths, feed) -> np.ndarray:
    """Minutes of cutting moves of ``lengths`` (mm) at ``feed`` (mm/min), never less than
    :data:`SHORTEST_BLOCK_MINUTES` (the timing floor every G93 F word and time estimate uses)."""
    return np.maximum(np.asarray(lengths, float) / np.asarray(feed, float), SHORTEST_BLOCK_MINUTES)


def inverse_time_feed(op, max_table_rpm: float = DEFAULT_MAX_TABLE_RPM) -> np.ndarray:
    """G93 F words: 1 / minutes for each cutting move (NaN for rapids); at most
    1 / :data:`SHORTEST_BLOCK_MINUTES`."""
    minutes = move_times(op, 1.0, max_table_rpm) / 60.0   # (the rapid rate does not matter here)
    with np.errstate(divide="ignore"):
        return np.where(op.kind != _RAPID, 1.0 / minutes, np.nan)


def cycle_time(op, rapid_rate: float, max_table_rpm: float = DEFAULT_MAX_TABLE_RPM) -> float:
    """Seconds for a C-X-Z operation, the table's speed limit included."""
    return float(move_times(op, rapid_rate, max_table_rpm).sum())
