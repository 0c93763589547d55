"""The tool-centre paths that clear a region, and the moves that cut them level by level.

A *centre region* is where the tool centre may go (the pocket shrunk by the tool's radius and the
wall allowance).  :func:`offset_rings` clears it by rings from the inside out (each ring keeps the
orientation the region gives its loop: counter-clockwise round the outer wall, clockwise round an
island, so a clockwise spindle climbs along both); :func:`zigzag_chains` by the raster of
:func:`..engines.region.zigzag` plus one ring along the boundary.  :class:`Cutter` cuts such paths
at a list of levels, entering each path on a helix inside the region where one fits, else on a
ramp along the path (:func:`..engines.ramp.ramped_passes`); where neither fits the error names
the place.  Every move is straight (arcs are fitted later, for every post alike).
"""
from __future__ import annotations

import math

import numpy as np

from ...engines import ramp
from ...engines import region as rg
from ...ir.errors import InputError
from ...ir.program import PathBuilder
from ..stepnc.motion import split_outside

MAX_RINGS = 5000            # more rings than this is a mistyped stepover, not a pocket
LINK_TOLERANCE = 0.01       # mm: a link at depth may graze the centre region's edge by this much
HELIX_TOLERANCE = 0.005     # mm: chord error of the helix polyline
ENTRY_GAP = 1.0             # mm above the level already cut where an entry starts feeding


class ClearingError(InputError):
    """A region the tool cannot enter or clear; the message names the place."""


def offset_rings(centres, stepover: float) -> list:
    """Closed rings (each (k, 2), last == first) at 0, s, 2s, ... inside ``centres``, innermost
    first, each started near where the one before ended."""
    distances = []
    while rg.area(rg.offset(centres, -len(distances) * stepover)) >= rg.MIN_AREA:
        distances.append(len(distances) * stepover)
        if len(distances) > MAX_RINGS:
            raise ClearingError(f"more than {MAX_RINGS} rings at a {stepover:g} mm stepover")
    rings, here = [], np.asarray(rg.centroid(centres), float)
    for distance in distances[::-1]:
        inner = rg.offset(centres, -distance) if distance else centres    # the outermost ring exact
        loops = [np.vstack([loop, loop[:1]]) for loop in rg.loops(inner)]
        for loop, index in rg.order_loops_nearest(loops, here):
            rings.append(rg.rotate_closed(loop, index))
            here = rings[-1][-1]
    return rings


def zigzag_chains(centres, stepover: float, angle: float) -> list:
    """Raster chains at ``angle`` degrees (cut where a step between rows would leave the region),
    then the ring along the region's boundary."""
    chains = split_outside(rg.zigzag(centres, stepover, angle), centres)
    here = chains[-1][-1] if chains else rg.centroid(centres)
    loops = [np.vstack([loop, loop[:1]]) for loop in rg.loops(centres)]
    for loop, index in rg.order_loops_nearest(loops, here):
        chains.append(rg.rotate_closed(loop, index))
    return chains


def path_length(points) -> float:
    return float(np.hypot(*np.diff(np.asarray(points, float)[:, :2], axis=0).T).sum())


class Cutter:
    """The moves of one operation.  ``centres``: the centre region (links at depth and helices
    stay in it); ``helix_radius``: of the helix entry (0: ramp only); ``ramp_angle``: degrees, of
    the helix and of the ramp; ``what``: words naming the pocket and tool in errors."""

    def __init__(self, centres, clearance_z: float, feed: float, entry_feed: float, helix_radius: float,
                 ramp_angle: float, min_ramp: float, what: str, diameter: float, helix_diameter: float):
        self.path = PathBuilder(clearance_z, feed, entry_feed)
        self.clearance_z = clearance_z
        self.entry_feed = entry_feed
        self.grown = rg.offset(centres, LINK_TOLERANCE)
        loops = rg.loops(self.grown)
        self.edges = np.vstack([np.hstack([loop, np.roll(loop, -1, axis=0)]) for loop in loops]) if loops else \
            np.empty((0, 4))
        self.helix_radius = helix_radius
        room = rg.offset(centres, -helix_radius) if helix_radius > 0 else None
        self.helix_room = room if room is not None and room.area() >= rg.MIN_AREA else None
        self.ramp_angle = ramp_angle
        self.min_ramp = min_ramp
        self.what = what
        self.diameter = diameter            # the tool's and the helix's, for the messages
        self.helix_diameter = helix_diameter
        self.refusal = None                 # why the first path no entry fits was left uncut
        self.notes: list = []

    def inside(self, points) -> bool:
        return bool(rg.contains_points(self.grown, np.asarray(points, float)).all())

    def link_fits(self, a, b) -> bool:
        """Whether the straight move a -> b stays in the (grown) centre region: both ends inside and
        no edge of its boundary crossed on the way."""
        a, b = np.asarray(a, float), np.asarray(b, float)
        if not self.inside(np.array([a, b])):
            return False
        e0, f = self.edges[:, :2], self.edges[:, 2:] - self.edges[:, :2]
        d = b - a
        denom = d[0] * f[:, 1] - d[1] * f[:, 0]
        rel = e0 - a
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (rel[:, 0] * f[:, 1] - rel[:, 1] * f[:, 0]) / denom
            u = (rel[:, 0] * d[1] - rel[:, 1] * d[0]) / denom
        return not bool(((np.abs(denom) > 1e-15) & (t >= 0) & (t <= 1) & (u >= 0) & (u <= 1)).any())

    def cut(self, chains: list, levels: list, cleared: float):
        """Every chain at each level in turn (the material above ``cleared`` is gone where the
        chains reach), linking at depth where the link stays in the region."""
        for z in levels:
            for chain in chains:
                chain = np.asarray(chain, float)
                here = self.path.position
                if here is not None and abs(here[2] - z) < 1e-9 and self.link_fits(here[:2], chain[0]):
                    self.path.line(chain[0][0], chain[0][1], z, link=True)
                    self.path.polyline(np.column_stack([chain[1:], np.full(len(chain) - 1, z)]))
                else:
                    self.enter(chain, cleared, z)
            cleared = z

    def enter(self, chain: np.ndarray, cleared: float, z: float):
        """Retract, rapid over the chain's start, rapid down to ENTRY_GAP above the cut level and
        enter: a helix where it fits, else a ramp along the chain."""
        x, y = chain[0]
        top = min(cleared + ENTRY_GAP, self.clearance_z)
        moves = self.helix(chain[0], top, z)
        if moves is not None:
            moves = np.vstack([moves, np.column_stack([chain[1:], np.full(len(chain) - 1, z)])])
        else:
            length = path_length(chain)
            d, h = self.diameter, self.helix_diameter
            if length < self.min_ramp:
                if self.refusal is None:
                    self.refusal = self.refused(x, y, length)
                self.note(f"{self.what}: the {d:g} mm end mill cannot enter at X{x:.3f} Y{y:.3f} (a {length:.2f} mm "
                          "path): left uncut there")
                return
            if self.helix_radius > 0:
                self.note(f"{self.what}: the {d:g} mm end mill's {h:g} mm helix does not fit at X{x:.3f} Y{y:.3f}; "
                          "ramped along the path")
            moves = ramp.ramped_passes(chain, [z], self.ramp_angle, top)[1:]
        self.path.retract()
        self.path.rapid(x, y, self.clearance_z)
        self.path.rapid(x, y, top)
        self.path.polyline(moves)

    def refused(self, x: float, y: float, length: float) -> str:
        """Why the path at (x, y) cannot be entered (the plan is refused when no path can be)."""
        d, h = self.diameter, self.helix_diameter
        if self.helix_radius > 0:
            return (f"{self.what}: the {d:g} mm end mill's {h:g} mm helix does not fit in the region at X{x:.3f} "
                    f"Y{y:.3f}, nor a ramp along the path there ({length:.2f} mm long, less than {self.min_ramp:g} mm)")
        return (f"{self.what}: the {d:g} mm end mill's ramp does not fit in the region at X{x:.3f} Y{y:.3f}: the "
                f"path there is {length:.2f} mm long, less than {self.min_ramp:g} mm")

    def note(self, text: str):
        if text not in self.notes:
            self.notes.append(text)

    def walls(self, walls, levels: list, top: float):
        """A ring along every loop of ``walls`` (a centre region's boundary), each cut at every
        level in turn, ramped down along itself from ``top``."""
        here = self.path.position[:2] if self.path.position is not None else rg.centroid(walls)
        loops = [np.vstack([loop, loop[:1]]) for loop in rg.loops(walls)]
        for loop, index in rg.order_loops_nearest(loops, here):
            ring = rg.rotate_closed(loop, index)
            self.path.retract()
            self.path.rapid(ring[0][0], ring[0][1], self.clearance_z)
            self.path.rapid(ring[0][0], ring[0][1], min(top + ENTRY_GAP, self.clearance_z))
            self.path.line(ring[0][0], ring[0][1], top, self.entry_feed)
            self.path.polyline(ramp.ramped_passes(ring, levels, self.ramp_angle, top)[1:])

    def helix(self, start, top: float, z: float):
        """Points (k, 3) down a counter-clockwise helix through ``start`` from ``top`` to ``z`` at the
        ramp angle, then once round at ``z`` back to ``start``; None where no such circle fits (its
        disc inside the region: its centre in the region shrunk by the helix's radius)."""
        radius = self.helix_radius
        if radius <= 0 or self.helix_room is None:
            return None
        angles = np.radians(np.arange(0, 360, 15))
        directions = np.column_stack([np.cos(angles), np.sin(angles)])
        centres = np.asarray(start, float) + radius * directions
        fits = np.flatnonzero(rg.contains_points(self.helix_room, centres))
        if not len(fits):
            return None
        centre, direction = centres[fits[0]], directions[fits[0]]
        segments = rg.circle_segments(radius, HELIX_TOLERANCE)
        pitch = 2 * math.pi * radius * math.tan(math.radians(self.ramp_angle))
        sweep = 2 * math.pi * (top - z) / pitch
        count = max(1, math.ceil(sweep / (2 * math.pi) * segments))
        first = math.atan2(-direction[1], -direction[0])
        turns = first + np.linspace(0, sweep, count + 1)[1:]
        rest = 2 * math.pi + (-sweep) % (2 * math.pi)       # once round at z, on to the start
        laps = max(1, math.ceil(rest / (2 * math.pi) * segments))
        lap = first + sweep + np.linspace(0, rest, laps + 1)[1:]
        heights = np.concatenate([top - (top - z) * np.arange(1, count + 1) / count, np.full(laps, z)])
        angles = np.concatenate([turns, lap])
        points = np.column_stack([centre[0] + radius * np.cos(angles), centre[1] + radius * np.sin(angles), heights])
        points[-1, :2] = start
        return points

    def cut_nothing(self) -> bool:
        return self.path.position is None

    def finish(self, safe_z: float):
        self.path.retract()
        x, y, _ = self.path.position
        self.path.rapid(x, y, safe_z)
        return self.path.arrays()
