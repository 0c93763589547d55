"""Carving surfaces: stepover and levels from closed forms, the samples simulated against
their design (no gouge, the scallop asked for), the programs through LinuxCNC's rs274."""
import math
from types import SimpleNamespace

import numpy as np
import pytest

import rs274
from kezuri import post as posts
from kezuri.toolpath.operations.carve import carve, carve_samples
from kezuri.toolpath import simulate as sim
from kezuri.toolpath.ir.program import FEED, Tool


def test_ball_stepover_is_the_chord_of_the_scallop():
    # a ball of radius r leaves h between passes s apart: (s/2)^2 + (r - h)^2 = r^2
    for r, h in ((1.5, 0.02), (3.0, 0.01), (0.5, 0.1)):
        s = carve.ball_stepover(r, h)
        assert (s / 2) ** 2 + (r - h) ** 2 == pytest.approx(r * r, rel=1e-12)


@pytest.mark.parametrize("angle", [0.0, 30.0, 90.0, 135.0])
def test_raster_lines_cover_the_rectangle(angle):
    bounds = (-10.0, -5.0, 20.0, 15.0)
    lines = carve.raster_lines(bounds, angle, 0.7)
    a = math.radians(angle)
    v = np.array([-math.sin(a), math.cos(a)])
    offsets = np.array([line[0] @ v for line in lines])
    corners = np.array([[-10, -5], [20, -5], [20, 15], [-10, 15]]) @ v
    assert offsets[0] == pytest.approx(corners.min()) and offsets[-1] == pytest.approx(corners.max())
    assert np.diff(offsets).max() <= 0.7 + 1e-12
    for line in lines:
        assert line[1] @ v == pytest.approx(line[0] @ v)
        for p in line:     # ends on the rectangle's boundary
            assert min(abs(p[0] + 10), abs(p[0] - 20), abs(p[1] + 5), abs(p[1] - 15)) < 1e-9


def box_design(height=-7.0):
    x, y = np.linspace(-20, 20, 5), np.linspace(-10, 10, 3)
    return carve_samples.heightmap_solid(x, y, np.full((5, 3), height), -15.0)


def test_a_level_design_closed_forms():
    v, f = box_design(-7.0)
    settings = carve.CarveSettings(allowance=0.5, step_down=3.0, scallop=0.02)
    result = carve.plan(v, f, settings, stock_top=0.0)
    # the flat end mill stops 0.5 above the plane: levels -3, -6, then -6.5
    assert result.levels == pytest.approx([-3.0, -6.0, -6.5])
    rough, finish = result.program.operations
    assert rough.xyz[rough.kind == FEED, 2].min() == pytest.approx(-6.5, abs=1e-12)
    assert result.stepover == pytest.approx(carve.MARGIN * 2 * math.sqrt(2 * 1.5 * 0.02 - 0.02 ** 2))
    assert result.steepest_slope_deg == 0 and result.convex_radius == math.inf
    cutting = finish.xyz[finish.kind == FEED]
    # the ball's tip runs on the plane; beyond the edge (up to 0.7 r) its side still touches the edge
    inside = (np.abs(cutting[:, 0]) <= 20) & (np.abs(cutting[:, 1]) <= 10)
    assert cutting[inside, 2] == pytest.approx(-7.0, abs=1e-9)
    out = np.maximum(np.abs(cutting[:, 0]) - 20, 0), np.maximum(np.abs(cutting[:, 1]) - 10, 0)
    d = np.hypot(*out)
    assert cutting[~inside, 2] == pytest.approx(-7.0 - 1.5 + np.sqrt(1.5 ** 2 - d[~inside] ** 2), abs=1e-6)
    assert d.max() == pytest.approx(0.7 * 1.5 * math.sqrt(2), abs=1e-9)


@pytest.mark.parametrize("sample,angle", [("wave", 0.0), ("dome", 30.0)])
def test_samples_simulate_without_gouges_and_within_the_scallop(sample, angle):
    v, f = carve_samples.SAMPLES[sample]()
    settings = carve.CarveSettings(raster_angle=angle, scallop=0.02)
    result = carve.plan(v, f, settings)
    assert [op.tool.kind for op in result.program.operations] == ["flat", "ball"]
    done = sim.simulate(result.program, result.stock, design=SimpleNamespace(vertices=v, faces=f), cell=0.1)
    assert [x.message for x in done.findings] == []
    measured = carve.measured_scallop(done.heightfield, v, f)
    assert measured["max_scallop_mm"] <= settings.scallop
    assert measured["max_scallop_mm"] > 0.5 * settings.scallop       # the stepover is not wastefully small
    assert measured["deepest_below_design_mm"] < sim.GOUGE_TOLERANCE
    # the roughing alone leaves at least the allowance (less the check's tolerance) everywhere
    rough = sim.simulate(result.program.operations[:1], result.stock, cell=0.25)
    left = carve.measured_scallop(rough.heightfield, v, f)
    assert left["max_vertical_excess_mm"] >= settings.allowance
    assert left["deepest_below_design_mm"] == 0.0
    assert rough.heightfield.heights.min() >= v[:, 2].min() - 1e-6


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")
def test_linuxcnc_runs_the_carving_program():
    v, f = carve_samples.wave_relief(cell=2.0)
    result = carve.plan(v, f, carve.CarveSettings(scallop=0.05, step_down=4.0))
    text = posts.create(("milling",), "linuxcnc").to_text(result.program)
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text))
    expected = np.vstack([op.xyz for op in result.program.operations])
    # every move of the program, in order, ends where rs274 says it does (tool changes may add moves)
    assert len(points) >= len(expected)
    found = 0
    for p in expected:
        while found < len(points) and not np.allclose(points[found], p, atol=6e-4):
            found += 1
        assert found < len(points), f"rs274 never reached {p}"


def test_bad_settings_are_named():
    v, f = box_design()
    with pytest.raises(carve.CarveError, match="scallop"):
        carve.plan(v, f, carve.CarveSettings(scallop=2.0))
    with pytest.raises(carve.CarveError, match="ball"):
        carve.plan(v, f, carve.CarveSettings(finish_tool=Tool(2, "flat", 3.0)))
    with pytest.raises(carve.CarveError, match="roughing needs"):
        carve.plan(v, f, carve.CarveSettings(rough_tool=Tool(1, "vbit", 6.0)))
    with pytest.raises(carve.CarveError, match="stock top"):
        carve.plan(v, f, stock_top=-10.0)
    with pytest.raises(carve.CarveError, match="step down"):
        carve.plan(v, f, carve.CarveSettings(step_down=0.0))
    with pytest.raises(carve.CarveError, match="flat in X or Y"):
        carve.plan(np.array([[0, 0, 0], [1, 0, 0], [2, 0, 1.0]]), [[0, 1, 2]])


def test_collinear_points_go_every_other_so_no_two_neighbours_leave():
    """Points on one straight line: the inner ones are candidates, and of each run of
    neighbouring candidates the first, third, ... leave; a point off the line breaks the run."""
    line = np.column_stack([np.arange(7.0), np.zeros(7), np.zeros(7)])
    assert carve._drop_collinear(line, 1e-6)[:, 0].tolist() == [0, 2, 4, 6]
    bent = line.copy()
    bent[3, 2] = 1.0                     # a bump: 2, 3 and 4 stay candidates no more (3 is above its chord)
    kept = carve._drop_collinear(bent, 1e-6)[:, 0].tolist()
    assert kept == [0, 2, 3, 4, 6]


def test_the_design_envelope_keeps_nothing_between_calls():
    """The export gate and the measured scallop ask for the design's envelope over the same grid:
    each call computes it afresh (no module memo), so an answer its caller changed changes nothing;
    and on one tilted triangle it is the triangle's plane at the cell centres inside it."""
    from kezuri.toolpath.simulate.heightfield import stock_grid
    from kezuri.toolpath.simulate.meshtop import mesh_top

    v, f = carve_samples.wave_relief(4.0)
    hf = stock_grid(sim.BoxStock(-60, -40, -15, 60, 40, -1), 0.5)
    first = mesh_top(hf, v, f)
    kept = first.copy()
    first[:] = 0.0
    again = mesh_top(hf, v.copy(), f.copy())
    assert np.array_equal(again, kept)
    ramp = mesh_top(stock_grid(sim.BoxStock(0, 0, -15, 10, 10, 12), 1.0), np.array([(0.0, 0, 0), (10, 0, 10), (0, 10, 0)]),
                    np.array([(0, 1, 2)]))
    centres = np.arange(10) + 0.5
    inside = centres[:, None] + centres[None, :] < 10 - 1e-6
    assert np.allclose(ramp[inside], np.broadcast_to(centres[:, None], ramp.shape)[inside])     # z = x
    assert np.all(np.isneginf(ramp[~inside]))
    assert np.isfinite(again).sum() > 0.8 * again.size and again.max() <= v[:, 2].max()     # edge centres: -inf
