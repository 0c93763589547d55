"""The nibbling lines round a cut contour: collinear pieces merged, no hit twice, micro-joints left.

A turret punch nibbles a straight line with a G69 (G79) block: hits evenly spaced from its first
to its last point, both included, as few as keep them at most the pitch Q apart
(:func:`.punch.line_steps`).  Written one line per contour segment, as the seed paper does, a
corner's hit is punched twice (the end of one line and the start of the next) and the collinear
pieces of one straight edge (an elbow's square end, 48 segments of one straight line) become
separate lines with a double hit at every joint.  Here:

* **Collinear pieces are merged** (:func:`corners`): a point that lies within ``COLLINEAR_TOL``
  of the straight line between the corners either side of it is no corner.
* **No hit twice**: each corner's hit belongs to one of its two lines; the other line stops one
  hit spacing short of it (its own spacing, so no gap grows past the pitch).  A line shorter
  than the pitch has only its two ends: it keeps both, and its neighbours give theirs up.
* **Micro-joints**: ``joints`` webs of ``joint_width`` left uncut on the outer contour so the
  part stays in the sheet until it is shaken out (PTC Creo NC Sheetmetal's "SHAKEAWAY_DIST":
  the material left at a micro-joint point, the tool path trimmed by half of it either side).
  The joints go one at a time to the line with the longest share (its length over its joints
  + 1), spread evenly along it (one at its middle, two at its quarters), each at least a punch
  diameter and a half from the corners; the hits either side of it are ``joint_width`` + the punch
  diameter apart, centre to centre, so their discs leave a web ``joint_width`` wide.

Everything is in the contour's coordinates (the tool-centre path, mm).  :meth:`Nibbling.operation`
gives the lines as the IR's :class:`~...ir.program.PunchOperation`, which a punch post writes.

:func:`segment_lines` is the seed paper's layout instead: one line per contour segment, every
corner punched twice; with :func:`offset_side` the control may offset the punch off the contour.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...ir.errors import InputError
from ...ir.program import PunchOperation
from .punch import line_steps

COLLINEAR_TOL = 0.005      # mm: half the 0.01 mm the NC words resolve
MIN_LINE = 0.01            # mm: a shorter line cannot be written (two decimals)
MAX_JOINTS = 8
# A web a punch leaves standing at a micro-joint: 0.2..0.5 mm on thin sheet is the common shop
# range; 0.4 mm is used as the default (issue 26 asks for 0.3..0.5 mm).
DEFAULT_JOINT_WIDTH = 0.4
DEFAULT_JOINTS = 2
TOOL_SIDES = ("left", "right", "outside", "inside")


class NibblingError(InputError):
    """A contour or setting the nibbling lines cannot be made from; the message names which."""


@dataclass(frozen=True)
class Nibbling:
    """``lines`` (k, 2, 2): the first and the last hit of each line, in order round the contour;
    ``joints`` (j, 2, 2): the two hits either side of each micro-joint; ``corners`` the contour's
    corners after merging; ``merged`` how many contour points were on a straight line between
    their neighbours; ``pitch`` and ``punch_diameter`` what the lines were spaced for."""

    lines: np.ndarray
    joints: np.ndarray
    joint_width: float
    corners: np.ndarray
    merged: int
    pitch: float
    punch_diameter: float

    def moved(self, offset) -> "Nibbling":
        d = np.asarray(offset, float)
        return Nibbling(self.lines + d, self.joints + d, self.joint_width, self.corners + d, self.merged,
                        self.pitch, self.punch_diameter)

    def operation(self, station: int, thickness: float, name: str = "nibbling") -> PunchOperation:
        """The lines as the IR's punch operation: turret ``station``, on a sheet ``thickness`` mm."""
        return PunchOperation(name, station, self.punch_diameter, self.pitch, thickness, self.lines)

    def describe(self) -> list:
        """One line for the NC header and the report: the micro-joints left."""
        if len(self.joints):
            return [f"micro-joints: {len(self.joints)} of {self.joint_width:g} mm"]
        return ["micro-joints: none, the part falls free at the last hits"]


def contour_points(contour) -> np.ndarray:
    """Clean (k, 2) points of a closed contour: repeated points and the repeated closing point removed."""
    pts = np.asarray(contour, float)
    if pts.ndim != 2 or pts.shape[1] != 2 or not np.all(np.isfinite(pts)):
        raise NibblingError("a contour must be finite (x, y) points")
    keep = [0]
    for i in range(1, len(pts)):
        if np.hypot(*(pts[i] - pts[keep[-1]])) > 1e-9:
            keep.append(i)
    pts = pts[keep]
    if len(pts) > 1 and np.hypot(*(pts[0] - pts[-1])) <= 1e-9:
        pts = pts[:-1]
    if len(pts) < 3:
        raise NibblingError("a closed contour needs at least 3 distinct points")
    return pts


def _on_chord(pts: np.ndarray, a: np.ndarray, b: np.ndarray, tol: float) -> bool:
    """Every point of ``pts`` within ``tol`` of the segment a-b and in order along it."""
    ab = b - a
    length = math.hypot(*ab)
    if length <= 1e-12:
        return False
    u = ab / length
    rel = pts - a
    along = rel @ u
    across = np.abs(rel[:, 0] * u[1] - rel[:, 1] * u[0])
    return bool(np.all(across <= tol) and np.all(np.diff(np.r_[0.0, along, length]) > 0))


def corners(contour, tol: float = COLLINEAR_TOL) -> np.ndarray:
    """The corners of the closed ``contour``: points within ``tol`` of the straight line between
    the corners either side (and between them along it) are dropped."""
    pts = contour_points(contour)
    k = len(pts)
    # start at the sharpest turn: certainly a corner
    d_in = pts - np.roll(pts, 1, axis=0)
    d_out = np.roll(pts, -1, axis=0) - pts
    turn = np.abs(np.arctan2(d_in[:, 0] * d_out[:, 1] - d_in[:, 1] * d_out[:, 0], (d_in * d_out).sum(axis=1)))
    start = int(np.argmax(turn))
    ring = np.roll(pts, -start, axis=0)
    ring = np.vstack([ring, ring[:1]])
    kept = [0]
    i = 0
    while i < k:
        j = i + 1
        while j + 1 <= k and _on_chord(ring[i + 1:j + 1], ring[i], ring[j + 1], tol):
            j += 1
        kept.append(j)
        i = j
    kept = kept[:-1]                       # the last is the first again
    out = ring[kept]
    if len(out) < 3:
        raise NibblingError("the contour has fewer than 3 corners once collinear points are merged")
    return out


def _joint_counts(pts: np.ndarray, count: int, width: float, d: float) -> np.ndarray:
    """How many joints each line takes: one at a time to the line with the longest share
    (length / (joints + 1)), so a long edge takes two before a short one takes any."""
    lengths = np.hypot(*(np.roll(pts, -1, axis=0) - pts).T)
    counts = np.zeros(len(pts), dtype=int)
    for _ in range(count):
        counts[int(np.argmax(lengths / (counts + 1)))] += 1
    need = counts * (width + 3 * d)
    short = np.flatnonzero(lengths < need)
    if len(short):
        i = int(short[0])
        raise NibblingError(f"micro-joints: {count} joint(s) do not fit: line {i + 1} of the cut contour, among the "
                            f"longest, is {lengths[i]:.2f} mm, and {counts[i]} joint(s) on it need {need[i]:.2f} mm "
                            f"(each the {width:g} mm web, a punch diameter of {d:g} mm either side and to the "
                            f"corners); give fewer joints")
    return counts


def _assign(chain: list, pitch: float, closed: bool) -> list:
    """(first hit, last hit) of each line of ``chain`` [(start, end), ...] whose consecutive lines
    share a corner (and the last the first, when ``closed``), each shared hit punched once."""
    lengths = [math.hypot(*(b - a)) for a, b in chain]
    steps = [int(line_steps(m, pitch)) for m in lengths]
    m = len(chain)
    drop_start, drop_end = [False] * m, [False] * m
    order = list(range(m))
    if closed:
        s = int(np.argmax(steps))
        order = [(s + 1 + i) % m for i in range(m)]     # the longest last: it drops its end
    dropped = False              # the current line's start hit is the previous line's (it kept its end)
    for position, k in enumerate(order):
        last = position == m - 1
        n = steps[k]
        drop_start[k] = dropped
        if last:
            drop_end[k] = closed         # open: a joint's gap, nobody shares it; closed: as assumed at the start
        else:
            drop_end[k] = n - 1 >= dropped + 1
        if n - 1 < drop_start[k] + drop_end[k]:
            before = (k - 1) % m
            shorter = min(lengths[k], lengths[before])
            raise NibblingError(
                f"lines {before + 1} and {k + 1} of the cut contour ({lengths[before]:.2f} and {lengths[k]:.2f} mm) "
                f"meet at a corner and are no longer than the nibbling pitch {pitch:g} mm: their shared corner "
                f"would be punched twice; give a pitch below {shorter:.2f} mm or fewer divisions")
        dropped = not drop_end[k]
    out = []
    for k, (a, b) in enumerate(chain):
        u = (b - a) / lengths[k]
        spacing = lengths[k] / steps[k]
        out.append((a + u * spacing * drop_start[k], b - u * spacing * drop_end[k]))
    return out


def nibble(contour, pitch: float, punch_diameter: float, joints: int = DEFAULT_JOINTS,
           joint_width: float = DEFAULT_JOINT_WIDTH, tol: float = COLLINEAR_TOL) -> Nibbling:
    """The nibbling lines round the closed tool-centre ``contour`` (see the module notes)."""
    for name, value in (("nibbling pitch", pitch), ("punch diameter", punch_diameter)):
        if not (isinstance(value, (int, float, np.floating)) and math.isfinite(value) and value > 0):
            raise NibblingError(f"{name} must be a number > 0, got {value!r}")
    if isinstance(joints, bool) or not isinstance(joints, (int, np.integer)) or not 0 <= joints <= MAX_JOINTS:
        raise NibblingError(f"micro-joints: the count must be a whole number 0..{MAX_JOINTS}, got {joints!r}")
    if not (isinstance(joint_width, (int, float, np.floating)) and math.isfinite(joint_width) and joint_width > 0):
        raise NibblingError(f"micro-joint width must be a number > 0 (mm), got {joint_width!r}")
    raw = contour_points(contour)
    pts = corners(raw, tol)
    k = len(pts)
    ends = np.roll(pts, -1, axis=0)
    lengths = np.hypot(*(ends - pts).T)
    short = np.flatnonzero(lengths < MIN_LINE)
    if len(short):
        raise NibblingError(f"segment {int(short[0]) + 1} of the cut contour is {lengths[short[0]]:.4f} mm long, "
                            f"shorter than the {MIN_LINE} mm the NC words resolve")
    if joints == 0:
        lines = _assign([(pts[i], ends[i]) for i in range(k)], pitch, closed=True)
        return Nibbling(np.array(lines), np.zeros((0, 2, 2)), float(joint_width), pts, len(raw) - k, float(pitch),
                        float(punch_diameter))
    counts = _joint_counts(pts, joints, joint_width, punch_diameter)
    half = joint_width / 2 + punch_diameter / 2
    pieces, gaps = [], []                  # pieces in order round the contour; a gap after some
    for i in range(k):
        a, b = pts[i], ends[i]
        u = (b - a) / math.hypot(*(b - a))
        start = a
        for c in range(counts[i]):        # the joints at (c + 1/2) / count of the line
            mid = a + (b - a) * (c + 0.5) / counts[i]
            pieces.append((start, mid - u * half))
            gaps.append(len(pieces) - 1)   # the gap follows this piece
            start = mid + u * half
        pieces.append((start, b))
    lines, joint_hits = [None] * len(pieces), []
    n = len(pieces)
    for j, gap in enumerate(gaps):
        first = (gap + 1) % n
        last = gaps[(j + 1) % len(gaps)]
        idx = [(first + t) % n for t in range(((last - first) % n) + 1)]
        for index, hits in zip(idx, _assign([pieces[t] for t in idx], pitch, closed=False)):
            lines[index] = hits
    for gap in gaps:
        joint_hits.append((pieces[gap][1], pieces[(gap + 1) % n][0]))
    return Nibbling(np.array(lines), np.array(joint_hits), float(joint_width), pts, len(raw) - k, float(pitch),
                    float(punch_diameter))


def segment_lines(contour) -> np.ndarray:
    """(k, 2, 2): one line per segment of the closed ``contour``, corner to corner, the last closing
    the loop: the seed paper's program, where every corner is punched twice (:func:`nibble` shares
    the corners' hits and merges collinear pieces)."""
    pts = contour_points(contour)
    return np.stack([pts, np.roll(pts, -1, axis=0)], axis=1)


def offset_side(contour, tool_side: str) -> str:
    """Which side of travel ("left" or "right") the control offsets the punch to, for the closed
    part ``contour`` and ``tool_side``: "left" / "right" of travel, or "outside" / "inside" of it."""
    if tool_side not in TOOL_SIDES:
        raise NibblingError(f"tool side must be one of {TOOL_SIDES}, got {tool_side!r}")
    if tool_side in ("left", "right"):
        return tool_side
    x, y = contour_points(contour).T
    ccw = float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)) > 0
    return "left" if (tool_side == "outside") != ccw else "right"      # travelling CCW the outside is on the right
