"""Steep-region cleanup of relief carving: on a ridge whose 55-degree flanks run along the
finishing raster, the raster alone leaves the closed-form scallop of passes spread over the slope;
the cleanup raster across it brings the scallop within the height asked.  Checked by the
simulation and by an independent measure (the material left along the flank's normal, from the
program's ball centres by ray-sphere intersection), no gouge, and LinuxCNC's rs274."""
import math
from types import SimpleNamespace

import numpy as np
import pytest

import rs274
from test_hostile import time_limit
from kezuri import post as posts
from kezuri.toolpath.operations.carve import carve, carve_samples
from kezuri.toolpath import simulate as sim
from kezuri.toolpath.ir.program import FEED, RAPID

R = 1.5                  # the default finishing ball's radius
SCALLOP = 0.02
THETA = math.radians(55.0)
CREST, FILLET, HEIGHT = 6.0, 4.0, 10.0
# the ridge's joints, by hand: crest arc -> flank at y1, flank -> fillet at y2, fillet -> floor at yf
Y1, Z1 = CREST * math.sin(THETA), -CREST * (1 - math.cos(THETA))
Z2 = -HEIGHT + FILLET * (1 - math.cos(THETA))
Y2 = Y1 + (Z1 - Z2) / math.tan(THETA)
YF = Y2 + FILLET * math.sin(THETA)


def flank_z(y):
    return Z1 - (np.abs(y) - Y1) * math.tan(THETA)


def test_ridge_profile_is_the_one_drawn():
    y = np.linspace(0, 30, 30001)
    z = carve_samples.ridge_profile(y)
    assert z[0] == 0 and z[-1] == -HEIGHT
    on_flank = (y > Y1) & (y < Y2)
    assert z[on_flank] == pytest.approx(flank_z(y[on_flank]), abs=1e-12)
    slope = np.degrees(np.arctan(np.abs(np.diff(z) / np.diff(y))))
    assert slope.max() == pytest.approx(55.0, abs=1e-3)
    # tangent joints: the slope turns no faster than on the 4 mm fillet (d angle = dy / (R cos a))
    assert np.abs(np.diff(slope)).max() <= math.degrees(0.001 / (FILLET * math.cos(THETA))) * 1.01
    assert carve_samples.ridge_profile(-y) == pytest.approx(z)


@pytest.fixture(scope="module")
def ridge():
    v, f = carve_samples.steep_ridge()
    plain = carve.plan(v, f, carve.CarveSettings(max_slope_deg=30.0, scallop=SCALLOP, steep_cleanup=False))
    with time_limit(120):          # the cleanup adds about a third to the plan (12 s here with both)
        cleaned = carve.plan(v, f, carve.CarveSettings(max_slope_deg=30.0, scallop=SCALLOP))
    return v, f, plain, cleaned


def test_the_cleanup_runs_only_where_the_raster_is_too_coarse(ridge):
    v, f, plain, cleaned = ridge
    assert [op.name for op in plain.program.operations] == ["roughing", "finishing"]
    assert plain.warnings and "55 degrees" in plain.warnings[0]
    assert [op.name for op in cleaned.program.operations] == ["roughing", "finishing", "steep cleanup"]
    assert cleaned.warnings == []
    finish, cleanup = cleaned.program.operations[1:]
    assert cleanup.tool == finish.tool and np.array_equal(finish.xyz, plain.program.operations[1].xyz)
    # the steep faces: the grid intervals of the profile whose chord slopes more than 30 degrees
    y = np.linspace(-30, 30, 241)
    chord = np.abs(np.diff(carve_samples.ridge_profile(y))) / 0.25
    assert cleaned.steep_area_mm2 == pytest.approx(100 * 0.25 * np.count_nonzero(chord > math.tan(math.radians(30))),
                                                   rel=1e-9)
    # along X the ridge does not change: the cleanup's stepover is a level surface's, with the
    # convex-bend factor of the finishing rule
    rho = cleaned.convex_radius
    assert cleaned.cleanup_slope_deg < 1e-6
    assert cleaned.cleanup_stepover == pytest.approx(
        carve.MARGIN * 2 * math.sqrt(2 * R * SCALLOP - SCALLOP ** 2) * math.sqrt(rho / (rho + R)), rel=1e-12)
    cutting = cleanup.xyz[cleanup.kind == FEED]
    # no cut beyond the steep band grown by the ball's radius (and the marking grid's cells) on
    # the floor; over the crest, between the two bands, only the links from one flank to the other
    a30 = CREST * 0.5                                     # the crest arc is 30 degrees steep at |y| = r sin 30
    band_hi = YF - FILLET * 0.5 + R + 0.6
    assert np.all(np.abs(cutting[:, 1]) <= band_hi)
    # ...and covers it: lines up the flank at most one stepover apart, over the whole length
    xs, count = np.unique(np.round(cutting[:, 0], 9), return_counts=True)
    xs = xs[count > 20]                                   # the lines (not the links between them)
    assert xs.min() <= -50 + 1e-9 and xs.max() >= 50 - 1e-9
    assert np.diff(xs).max() <= cleaned.cleanup_stepover + 1e-9
    for x in xs[::10]:
        line = cutting[np.abs(cutting[:, 0] - x) < 1e-9, 1]
        for side in (1, -1):
            ys = np.sort(side * line[side * line > 0])
            assert ys.min() <= a30 and ys.max() >= YF - FILLET * 0.5
    # the drop cutter keeps the ball on the flank: the tip of a ball touching the plane of slope
    # theta stands r / cos(theta) - r above the plane under its centre
    contact = np.abs(cutting[:, 1]) - R * math.sin(THETA)
    on_flank = (contact > Y1 + 0.3) & (contact < Y2 - 0.3) & (np.abs(cutting[:, 0]) <= 50 - R)
    assert on_flank.sum() > 1000
    assert cutting[on_flank, 2] == pytest.approx(flank_z(cutting[on_flank, 1]) + R / math.cos(THETA) - R, abs=1e-6)


def test_the_pieces_are_linked_above_the_stock(ridge):
    v, f, plain, cleaned = ridge
    cleanup = cleaned.program.operations[2]
    top = cleaned.stock[5]
    xyz, kind = cleanup.xyz, cleanup.kind
    start = np.vstack([[np.nan] * 3, xyz[:-1]])
    rapid = kind == RAPID
    sideways = rapid & (np.linalg.norm(xyz[:, :2] - start[:, :2], axis=1) > 1e-9)
    assert np.all(xyz[sideways, 2] >= cleanup.clearance_z - 1e-9)
    assert np.all(xyz[rapid, 2] > top)                        # rapids never come down into the stock
    # a piece is entered by a vertical feed plunge from above the stock...
    pieces = np.flatnonzero(rapid[:-1] & (kind[1:] == FEED)) + 1
    assert len(pieces) >= 1
    assert np.allclose(xyz[pieces, :2], xyz[pieces - 1, :2]) and np.all(xyz[pieces - 1, 2] > top)
    # ...or, within 4 ball diameters of the last, reached along the surface: the runs over the two
    # flanks (2.4 mm apart over the crest) and the next line's (one stepover on) are linked, so
    # the whole cleanup is one cut, retracting only where a line leaves the plate (beyond x = +-50)
    cutting = xyz[kind == FEED]
    assert len(pieces) <= 2
    assert np.all(np.abs(cutting[:, 0]) <= 50 + 0.7 * R + 1e-9)
    steps = np.linalg.norm(np.diff(xyz, axis=0)[(kind[1:] == FEED) & (kind[:-1] == FEED)][:, :2], axis=1)
    assert steps.max() <= 4 * 2 * R


def material_along_normal(points, normal, centres, radius):
    """Thickness of material left above each design point along its normal: the distance to the
    first ball (radius, centres) the ray enters; negative if the point is inside a ball (a gouge)."""
    out = np.full(len(points), np.inf)
    for start in range(0, len(points), 200):
        p = points[start:start + 200]
        lo, hi = p.min(axis=0) - radius, p.max(axis=0) + radius
        c = centres[np.all((centres[:, :2] >= lo[:2]) & (centres[:, :2] <= hi[:2]), axis=1)]
        w = c[None, :, :] - p[:, None, :]                       # (points, centres, 3)
        b = w @ normal
        disc = b * b - (np.einsum("pcj,pcj->pc", w, w) - radius * radius)
        entry = np.where(disc >= 0, b - np.sqrt(np.maximum(disc, 0)), np.inf)
        out[start:start + 200] = entry.min(axis=1)
    return out


def ball_centres(operations, step=0.01, window=(-3.0, 3.0)):
    """The ball centres of every feed move, sampled at most ``step`` apart, near x in ``window``."""
    found = []
    for op in operations:
        xyz = op.xyz
        for k in np.flatnonzero(op.kind[1:] == FEED) + 1:
            a, b = xyz[k - 1], xyz[k]
            if max(a[0], b[0]) < window[0] - R or min(a[0], b[0]) > window[1] + R:
                continue
            n = max(1, math.ceil(np.linalg.norm(b - a) / step))
            found.append(a + np.outer(np.linspace(0, 1, n + 1), b - a))
    centres = np.vstack(found)
    return centres + [0.0, 0.0, R]


def test_the_scallop_on_the_flanks_before_and_after(ridge):
    v, f, plain, cleaned = ridge
    # design points on the +y flank's straight part, away from its joints, at x in [-1, 1]
    gx, gy = np.meshgrid(np.arange(-1.0, 1.0001, 0.05), np.arange(Y1 + 0.5, Y2 - 0.5, 0.005), indexing="ij")
    points = np.column_stack([gx.ravel(), gy.ravel(), flank_z(gy.ravel())])
    normal = np.array([0.0, math.sin(THETA), math.cos(THETA)])
    finishing = plain.program.operations[1:]
    before = material_along_normal(points, normal, ball_centres(finishing), R)
    after = material_along_normal(points, normal, ball_centres(cleaned.program.operations[1:]), R)
    # the raster alone: passes d apart across the slope stand d / cos(theta) apart on it
    spread = plain.stepover / math.cos(THETA) / 2
    closed_form = R - math.sqrt(R * R - spread * spread)
    assert before.min() >= -1e-6 and after.min() >= -1e-6   # nothing inside the design
    assert before.max() == pytest.approx(closed_form, rel=0.03) and before.max() > 1.5 * SCALLOP
    assert after.max() <= SCALLOP
    # the material-removal simulation agrees, over the whole design
    design = SimpleNamespace(vertices=v, faces=f)
    sim_before = sim.simulate(plain.program, plain.stock, design=design, cell=0.1)
    sim_after = sim.simulate(cleaned.program, cleaned.stock, design=design, cell=0.1)
    assert [x.message for x in sim_after.findings] == [] and [x.message for x in sim_before.findings] == []
    m_before = carve.measured_scallop(sim_before.heightfield, v, f)
    m_after = carve.measured_scallop(sim_after.heightfield, v, f)
    assert closed_form * 0.8 < m_before["max_scallop_mm"] <= closed_form + 1e-4
    assert m_after["max_scallop_mm"] <= SCALLOP
    assert m_after["deepest_below_design_mm"] < sim.GOUGE_TOLERANCE


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")
def test_linuxcnc_runs_the_cleanup(ridge):
    v, f, plain, cleaned = ridge
    cleanup = cleaned.program.operations[2]
    text = posts.create(("milling",), "linuxcnc").to_text(cleaned.program)
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text))
    found = 0
    for p in cleanup.xyz[::7]:
        while found < len(points) and not np.allclose(points[found], p, atol=6e-4):
            found += 1
        assert found < len(points), f"rs274 never reached {p}"


def test_no_cleanup_where_nothing_is_steep():
    x, y = np.linspace(-20, 20, 41), np.linspace(-10, 10, 21)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    v, f = carve_samples.heightmap_solid(x, y, -5 + 0.2 * gy, -10.0)      # an 11-degree slope
    result = carve.plan(v, f, carve.CarveSettings(max_slope_deg=30.0, rough=False, scallop=0.05))
    assert [op.name for op in result.program.operations] == ["finishing"]
    assert result.cleanup_stepover is None and result.steep_area_mm2 == 0.0


def distance_to_triangle(points, tri):
    """Distance in XY from each point to the (filled) triangle, by hand: 0 inside, else the
    nearest of its three edges."""
    def edge(a, b):
        t = np.clip(((points - a) @ (b - a)) / ((b - a) @ (b - a)), 0, 1)
        return np.linalg.norm(points - (a + t[:, None] * (b - a)), axis=1)
    d = np.minimum.reduce([edge(tri[0], tri[1]), edge(tri[1], tri[2]), edge(tri[2], tri[0])])
    cross = [np.cross(tri[(k + 1) % 3] - tri[k], points - tri[k]) for k in range(3)]
    inside = np.all(np.array(cross) >= 0, axis=0) | np.all(np.array(cross) <= 0, axis=0)
    return np.where(inside, 0.0, d)


@pytest.mark.parametrize("tri", [[[1.0, 1.0], [38.0, 4.0], [12.0, 27.0]], [[5.0, 5.0], [35.0, 5.2], [20.0, 5.1]]])
def test_the_footprint_mask_marks_every_cell_near_a_face(tri):
    tri = np.array(tri)
    cell, grow = 0.5, 1.5
    mask = carve.footprint_mask(tri[None], (0.0, 0.0), (81, 61), cell, grow)
    gx, gy = np.meshgrid(np.arange(81) * cell, np.arange(61) * cell, indexing="ij")
    d = distance_to_triangle(np.column_stack([gx.ravel(), gy.ravel()]), tri).reshape(81, 61)
    assert mask[d <= grow].all()                     # nothing the ball could touch is left out
    assert not mask[d > grow + 3 * cell].any()       # and the marks stay close to it
