"""The tool path as the simulation sees it: each operation's moves as one chain of points in
part coordinates (arcs and rotary moves cut into chords), and the moves that are checked
against the material before they cut."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..ir import kinematics
from ..ir.program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, Program, Tool, arc_sweep
from .stock import CHORD_TOLERANCE, SimulationError

def can_plunge(tool: Tool, no_plunge_tools=()) -> bool:
    """Whether the tool may feed straight down into material (centre-cutting).

    Drills, ball and flat end mills can (see :attr:`.tools.ToolShape.plunges`), unless their tool
    number is in ``no_plunge_tools`` (e.g. a flat end mill that is not centre-cutting)."""
    return tool.shape.plunges and tool.number not in set(no_plunge_tools)


def operations_of(program_or_operations) -> list:
    if isinstance(program_or_operations, Program):
        ops = list(program_or_operations.operations)
    elif isinstance(program_or_operations, Operation):
        ops = [program_or_operations]
    else:
        try:
            ops = list(program_or_operations)
        except TypeError:
            raise SimulationError("simulate needs a Program, an Operation or a list of Operations")
    for op in ops:
        if not isinstance(op, Operation):
            raise SimulationError(f"not an Operation: {op!r}")
        op.validate()
        if not np.all(np.isfinite(op.start)):
            raise SimulationError(f"operation {op.name!r}: start point has a non-finite coordinate")
        unknown = set(op.rotary) - {"c"}
        if unknown:
            raise SimulationError(f"operation {op.name!r}: rotary axes {sorted(unknown)} are not simulated "
                             "(only C, a table turning about Z)")
    if not any(len(op) for op in ops):
        raise SimulationError("nothing to simulate: the program has no moves")
    return ops


# ----- the path as the simulation sees it ---------------------------------------------------

@dataclass
class Chain:
    """One operation's tool tip path in part coordinates: points[s] -> points[s + 1] is
    segment s, cut by move ``move[s]``; ``checked`` segments are tested against the material
    before they are applied (rapids, plunges of tools that cannot plunge)."""

    op_index: int
    tool: Tool
    points: np.ndarray
    move: np.ndarray
    rapid: np.ndarray
    checked: np.ndarray
    radial: bool = False       # a turn-mill radial tool: its axis points from the C axis to the tip


def machine_samples(op: Operation):
    """Points along every move in machine coordinates: (xyz (k, 3), c (k,), move (k,)), ending
    at each move's end point.

    Each move is cut into chords within CHORD_TOLERANCE of the true path: G2/G3 arcs in XY,
    and moves that turn C (a straight machine move is an arc on the part)."""
    n = len(op)
    a = op.start_points()
    b = op.xyz
    has_c = "c" in op.rotary
    c_end = op.rotary["c"] if has_c else np.zeros(n)
    c_start = np.concatenate([[c_end[0]], c_end[:-1]]) if n else c_end
    arcs = (op.kind == ARC_CW) | (op.kind == ARC_CCW)
    sweep = np.zeros(n)
    radius_a = np.zeros(n)
    radius_b = np.zeros(n)
    pieces = np.ones(n, dtype=np.int64)
    if arcs.any():
        centre = op.center[arcs, :2]
        sweep[arcs] = arc_sweep(a[arcs, :2], b[arcs, :2], centre, op.kind[arcs] == ARC_CW)
        radius_a[arcs] = np.linalg.norm(a[arcs, :2] - centre, axis=1)
        radius_b[arcs] = np.linalg.norm(b[arcs, :2] - centre, axis=1)
        pieces[arcs] = _chords(np.abs(sweep[arcs]), np.maximum(radius_a[arcs], radius_b[arcs]))
    if has_c:
        reach = np.maximum(np.hypot(a[:, 0], a[:, 1]), np.hypot(b[:, 0], b[:, 1]))
        pieces = np.maximum(pieces, _chords(np.radians(np.abs(c_end - c_start)), reach))
    move = np.repeat(np.arange(n), pieces)
    t = (np.arange(len(move)) - np.repeat(np.cumsum(pieces) - pieces, pieces) + 1) / pieces[move]
    xyz = a[move] + t[:, None] * (b - a)[move]
    on_arc = arcs[move]
    if on_arc.any():
        m = move[on_arc]
        centre = op.center[m, :2]
        start_angle = np.arctan2(a[m, 1] - centre[:, 1], a[m, 0] - centre[:, 0])
        angle = start_angle + t[on_arc] * sweep[m]
        r = radius_a[m] + t[on_arc] * (radius_b[m] - radius_a[m])
        xyz[on_arc, 0] = centre[:, 0] + r * np.cos(angle)
        xyz[on_arc, 1] = centre[:, 1] + r * np.sin(angle)
    c = c_start[move] + t * (c_end - c_start)[move]
    return xyz, c, move


def _chords(angle: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """Chords needed to follow an arc of ``angle`` radians at ``radius`` within CHORD_TOLERANCE."""
    ratio = np.clip(1.0 - CHORD_TOLERANCE / np.maximum(radius, 1e-12), -1.0, 1.0)
    step = 2.0 * np.arccos(ratio)
    return np.maximum(1, np.ceil(angle / np.maximum(step, 1e-9) - 1e-9)).astype(np.int64)


def chains_of(ops: list, no_plunge_tools) -> list:
    chains = []
    for index, op in enumerate(ops):
        if not len(op):
            continue
        xyz, c, move = machine_samples(op)
        start_c = op.rotary["c"][0] if "c" in op.rotary else 0.0
        machine = np.vstack([op.start[None, :], xyz])
        c_all = np.concatenate([[start_c], c])
        points = kinematics.machine_to_part(machine, c_all)
        # Drop repeated points: every segment then has a length.
        keep = np.ones(len(points), bool)
        keep[1:] = np.any(np.abs(np.diff(points, axis=0)) > 1e-9, axis=1)
        seg_move = move[keep[1:]]
        points = points[keep]
        if len(points) < 2:
            continue
        rapid = op.kind[seg_move] == RAPID
        checked = rapid.copy()
        if not can_plunge(op.tool, no_plunge_tools):
            # A plunge: a feed move along -Z alone (no X, Y or C travel) in machine coordinates.
            a = op.start_points()
            straight_down = ((op.kind == FEED) & (np.abs(op.xyz[:, 0] - a[:, 0]) < 1e-9)
                             & (np.abs(op.xyz[:, 1] - a[:, 1]) < 1e-9) & (op.xyz[:, 2] < a[:, 2]))
            if "c" in op.rotary:
                c_end = op.rotary["c"]
                straight_down &= np.abs(c_end - np.concatenate([[c_end[0]], c_end[:-1]])) < 1e-9
            checked |= straight_down[seg_move]
        chains.append(Chain(index, op.tool, points, seg_move, rapid, checked,
                             getattr(op, "direction", None) == "radial"))
    return chains


def without_short_moves(points: np.ndarray, length: float) -> np.ndarray:
    """The polyline with every move shorter than ``length`` merged into the next: a point within
    ``length`` of the last point kept is left out (the last point stays, in place of the one kept
    before it if need be).  Numerical noise of a few 1e-7 mm between two arcs no longer splits a
    level run in two; the path moves by less than ``length``."""
    short = np.flatnonzero(np.linalg.norm(np.diff(points, axis=0), axis=1) < length)
    if not len(short):
        return points
    keep = np.ones(len(points), bool)
    for k in short + 1:
        last = k - 1
        while not keep[last]:
            last -= 1
        if np.linalg.norm(points[k] - points[last]) < length:
            if k < len(points) - 1 or last == 0:
                keep[k] = False
            else:
                keep[last] = False        # the path still ends where it ends
    return points[keep] if keep.sum() >= 2 else points[[0, -1]]
