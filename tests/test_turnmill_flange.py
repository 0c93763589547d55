"""The radial tool next to an overhanging flange: a spool built by hand (two flanges of radius 20
on a core of radius 9, each ring a regular 64-gon), planned by the core, and every radial move
followed as the machine does it (X, Z and C interpolated linearly) and measured in closed form
against the flanges' rim edges.

The planner may leave the ball short of the surface by the chordal tolerance (the scallop between
centres a stepover apart), never more.  Before the fix, a roughing pass rounding the rim at
z -5.18 (just under the inner flange face) had its centres 0.75 mm apart, and the straight moves
between them cut the polygon's corners by 0.03 mm: the export gate refused the program."""
import math

import numpy as np
import pytest

from kezuri.toolpath.operations.turnmill import turnmill as tm
from kezuri.toolpath.ir.program import FEED

from test_hostile import time_limit

R, TOL, SIDES = 3.0, 0.01, 64
PROFILE = [(20.0, -40.0), (20.0, -35.0), (9.0, -35.0), (9.0, -5.0), (20.0, -5.0), (20.0, 0.0)]
RIMS = [(20.0, -40.0), (20.0, -35.0), (20.0, -5.0), (20.0, 0.0)]      # the flanges' convex edges


def ring(radius, z):
    angle = 2 * math.pi * np.arange(SIDES) / SIDES
    return np.column_stack([radius * np.cos(angle), radius * np.sin(angle), np.full(SIDES, z)])


def spool():
    """Vertices: the bottom centre, one 64-gon per profile corner, the top centre; faces: fans at
    the ends and two triangles per facet between neighbouring rings, wound outward."""
    vertices = np.vstack([[(0.0, 0.0, -40.0)]] + [ring(*corner) for corner in PROFILE] + [[(0.0, 0.0, 0.0)]])
    top = len(vertices) - 1
    j = np.arange(SIDES)
    k = (j + 1) % SIDES
    faces = [np.column_stack([np.zeros(SIDES, int), 1 + k, 1 + j])]                 # bottom, facing -Z
    for i in range(len(PROFILE) - 1):
        lower, upper = 1 + i * SIDES, 1 + (i + 1) * SIDES
        faces += [np.column_stack([lower + j, lower + k, upper + k]), np.column_stack([lower + j, upper + k, upper + j])]
    last = 1 + (len(PROFILE) - 1) * SIDES
    faces.append(np.column_stack([last + j, last + k, np.full(SIDES, top)]))          # top, facing +Z
    faces = np.vstack(faces)
    tri = vertices[faces]
    volume = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6
    # the closed-form volume of the spool of 64-gons: area of a 64-gon is 32 r^2 sin(2 pi / 64)
    area = lambda r: SIDES / 2 * r * r * math.sin(2 * math.pi / SIDES)      # noqa: E731
    assert volume == pytest.approx(10 * area(20) + 30 * area(9), rel=1e-12)    # outward, closed
    return vertices, faces


def rim_distance(points):
    """Distance from each point to the nearest edge of the four rim polygons: point to segment,
    t = clip((p - a).(b - a) / |b - a|^2, 0, 1)."""
    best = np.full(len(points), np.inf)
    for radius, z in RIMS:
        a = ring(radius, z)
        b = np.roll(a, -1, axis=0)
        ab = b - a
        p = points[:, None, :]
        t = np.clip(np.einsum("nkj,kj->nk", p - a, ab) / np.einsum("kj,kj->k", ab, ab), 0, 1)
        d = np.linalg.norm(p - (a + t[..., None] * ab), axis=2).min(axis=1)
        best = np.minimum(best, d)
    return best


def machine_path(op, step=0.02):
    """Ball centres along every move of a radial operation as the control interpolates it:
    X, Z and C linear from the previous position, sampled every ``step`` mm of tip travel and at
    most 0.05 degrees of C apart; the centre is r beyond the tip along the machine's +X."""
    xyz, c = np.vstack([op.start, op.xyz]), np.r_[op.rotary["c"][0], op.rotary["c"]]
    centres = []
    for i in range(1, len(xyz)):
        arc = np.linalg.norm(xyz[i] - xyz[i - 1]) + math.radians(abs(c[i] - c[i - 1])) * (xyz[i, 0] + R)
        n = max(2, math.ceil(arc / step) + 1)
        s = np.linspace(0.0, 1.0, n)
        x = xyz[i - 1, 0] + s * (xyz[i, 0] - xyz[i - 1, 0]) + R
        z = xyz[i - 1, 2] + s * (xyz[i, 2] - xyz[i - 1, 2])
        angle = np.radians(c[i - 1] + s * (c[i] - c[i - 1]))
        centres.append(np.column_stack([x * np.cos(angle), x * np.sin(angle), z]))
    return np.vstack(centres)


@pytest.fixture(scope="module")
def plan():
    vertices, faces = spool()
    with time_limit(300):
        return tm.plan(vertices, faces, tm.Stock(20.0, -40.0, 0.0))


def test_the_spool_is_planned_with_radial_roughing_under_the_flange(plan):
    names = [op.name for op in plan.program.operations]
    assert "radial roughing" in names and "radial finishing" in names
    rough = next(op for op in plan.program.operations if op.name == "radial roughing")
    # roughing reaches in between the flanges, under the inner face (z -5) and above z -35
    feeds = rough.xyz[rough.kind == FEED]
    assert np.any((feeds[:, 2] < -5) & (feeds[:, 2] > -5 - R) & (feeds[:, 0] < 20 - R))


@pytest.mark.parametrize("name", ["radial roughing", "radial finishing"])
def test_no_radial_move_brings_the_ball_nearer_the_rims_than_the_tolerance(plan, name):
    op = next(op for op in plan.program.operations if op.name == name)
    centres = machine_path(op)
    # only centres within reach of a rim can touch it: |(rho, z) - (20, z_rim)| >= the 3-D distance
    # to the polygon's edges minus its sag (20 (1 - cos(pi / 64)) = 0.024 mm)
    rho = np.hypot(centres[:, 0], centres[:, 1])
    near = np.zeros(len(centres), bool)
    for radius, z in RIMS:
        near |= np.hypot(rho - radius, centres[:, 2] - z) < R + 0.1
    assert near.sum() > 1000
    distance = np.concatenate([rim_distance(chunk) for chunk in np.array_split(centres[near], 1 + near.sum() // 20000)])
    assert distance.min() >= R - TOL, (name, float(R - distance.min()))
