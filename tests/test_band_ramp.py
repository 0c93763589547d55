"""Band finishing in step-downs of at most 1 x D with ramp entry, checked on the posted text.

The 1 mm flat end mill used to take the band's 2.0 mm in one pass (2 x D) after a straight
plunge.  Now every ring is cut at levels at most ``band_step_down`` apart (default 1.0 mm = 1 x
D), each entered on a ramp along the ring at ``band_ramp_angle`` (default 3 degrees).  What is
checked here is the LinuxCNC program read by LinuxCNC's own interpreter (``rs274``, its
canonical calls), the flat tool's moves between its CHANGE_TOOL and the next:
* no Z-only feed of the flat tool ends below the plate's top (Z 0);
* the level passes lie at the expected depths, no step between them deeper than D;
* every ramp descends at the angle set, in closed form: a ramp down h mm is h / tan(angle) mm
  long in XY, and each move of it drops tan(angle) x its XY length;
* the simulated cut is the one-pass band's (only the order of cutting changed).
"""
import math

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.toolpath.operations.engrave import engrave
from kezuri.toolpath.engines import ramp
from kezuri.toolpath import simulate
from test_engrave import LETTERS, PLATE

pytestmark = pytest.mark.skipif(not rs274.available(), reason="LinuxCNC's rs274 is not installed")

FLAT = 3            # the band finishing tool's number (EngraveSettings default)
# Removed volume of the test plate's program with the one-pass band (main at 0bdb292, before this
# change), simulated on the plate stock at 0.1 mm cells: the whole program and the band alone.
BEFORE_MM3 = {"program": 36693.57, "band": 2472.40}


def flat_tool_moves(settings) -> np.ndarray:
    """(kind, x0, y0, z0, x1, y1, z1) per STRAIGHT_FEED/TRAVERSE of tool FLAT, from rs274."""
    baked, _ = engrave.bake(engrave.plan(PLATE, LETTERS, settings).program)
    # every move as planned (Arcs off): the closed forms below are the straight moves' (the level
    # passes' arcs are checked in tests/test_arcs_out.py; the ramps change Z and stay lines)
    default = post.milling_post("linuxcnc").machine
    calls = rs274.run(post.milling_post("linuxcnc", machine=default.replace(arcs=False)).to_text(baked))
    tool, here, rows = None, None, []
    for name, args in calls:
        if name == "CHANGE_TOOL":
            tool = int(args[0])
        elif name in ("STRAIGHT_FEED", "STRAIGHT_TRAVERSE"):
            end = [float(a) for a in args[:3]]
            if tool == FLAT and here is not None:
                rows.append([name == "STRAIGHT_FEED", *here, *end])
            here = end
        elif name == "ARC_FEED":
            raise AssertionError("the band is cut in straight moves")
    return np.array(rows)


@pytest.fixture(scope="module")
def default_moves():
    return flat_tool_moves(engrave.EngraveSettings())


def check_band(moves, depths, angle):
    feed = moves[moves[:, 0] == 1]
    start, end = feed[:, 1:4], feed[:, 4:7]
    dxy = np.hypot(*(end[:, :2] - start[:, :2]).T)
    dz = end[:, 2] - start[:, 2]
    # no Z-only feed ends below the plate's top (rs274 prints 4 decimals; the post writes 3)
    z_only = dxy < 1e-3
    assert z_only.any() and end[z_only, 2].min() >= -1e-9
    # the level passes: horizontal feeds below the top lie at the expected depths only
    level = (np.abs(dz) < 1e-9) & (end[:, 2] < -1e-9)
    assert sorted(set(np.round(end[level, 2], 3))) == sorted(round(d, 3) for d in depths)
    steps = -np.diff([0.0] + sorted(depths, reverse=True))
    assert steps.max() <= 1.0 + 1e-9                                   # <= 1 x D of the 1 mm tool
    # every descending feed with XY travel is on a ramp of the angle set (and nothing climbs)
    slope = math.tan(math.radians(angle))
    down = dz < -1e-9
    assert not np.any(dz[~z_only] > 1e-9)
    ramped = down & ~z_only
    assert np.all(np.abs(-dz[ramped] - slope * dxy[ramped]) <= 2e-3)
    # closed form per ramp: consecutive descending moves from one level to the next
    ramps, current = [], None
    for is_ramp, drop, length in zip(ramped, -dz, dxy):
        if is_ramp:
            current = [0.0, 0.0] if current is None else current
            current[0] += drop
            current[1] += length
        elif current is not None:
            ramps.append(current)
            current = None
    ramps = np.array(ramps)
    step = abs(depths[0])
    assert np.allclose(ramps[:, 0], step, atol=2e-3)                    # each ramp descends one level
    assert np.allclose(ramps[:, 1], step / slope, rtol=2e-4, atol=2e-3)  # h / tan(angle) long
    return ramps


def test_default_band_two_levels_of_1mm_entered_on_3_degree_ramps(default_moves):
    ramps = check_band(default_moves, [-1.0, -2.0], 3.0)
    assert np.allclose(ramps[:, 1], 1.0 / math.tan(math.radians(3.0)), rtol=2e-4)   # 19.081 mm each
    assert len(ramps) % 2 == 0                                              # two per ring


def test_step_down_and_angle_are_followed():
    settings = engrave.EngraveSettings(band_step_down=0.5, band_ramp_angle=5.0)
    check_band(flat_tool_moves(settings), [-0.5, -1.0, -1.5, -2.0], 5.0)


def test_the_simulated_cut_is_the_one_pass_bands():
    result = engrave.plan(PLATE, LETTERS)
    baked, _ = engrave.bake(result.program)
    stock = engrave.plate_stock(PLATE, 10.0)
    limits = engrave.simulation_limits([loop for _, loops in LETTERS for loop in loops], result.program, -2.0)
    whole = simulate.simulate(baked.operations, stock, cell=0.1, **limits)
    band = simulate.simulate(baked.operations[1:2], stock, cell=0.1, **limits)
    assert whole.findings == [] and band.findings == []
    assert whole.removed_volume_mm3 == pytest.approx(BEFORE_MM3["program"], rel=1e-3)
    assert band.removed_volume_mm3 == pytest.approx(BEFORE_MM3["band"], rel=1e-3)


@pytest.mark.parametrize("changes, match", [
    (dict(band_step_down=1.5), r"band step down 1.5 mm is more than the 1 mm finishing tool's diameter"),
    (dict(band_step_down=0.0), "band step down must be greater than zero"),
    (dict(band_ramp_angle=0.0), "band ramp angle must be more than 0 and at most 45 degrees, got 0"),
    (dict(band_ramp_angle=60.0), "band ramp angle must be more than 0 and at most 45 degrees, got 60"),
    (dict(band_ramp_angle=float("nan")), "band ramp angle must be a finite number"),
])
def test_bad_band_settings_are_refused(changes, match):
    with pytest.raises(engrave.EngraveError, match=match):
        engrave.plan(PLATE, LETTERS, engrave.EngraveSettings(**changes))


# ----- the ramp module on shapes worked by hand ---------------------------------------------------

def test_levels_are_equal_steps_of_at_most_the_step():
    assert ramp.levels(-2.0, 1.0) == [-1.0, -2.0]
    assert ramp.levels(-2.0, 0.8) == pytest.approx([-2 / 3, -4 / 3, -2.0])
    assert ramp.levels(-0.3, 1.0) == [-0.3]


def test_a_ramp_longer_than_the_ring_winds_down_round_it():
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]], float)     # perimeter 4 mm
    angle = math.degrees(math.atan(0.1))                                     # 0.1 mm down per mm
    moves = ramp.ramped_passes(square, [-1.0], angle)
    corners = [[1, 0], [1, 1], [0, 1], [0, 0]]
    # entry at (0, 0, 0); the ramp: 10 mm = 2 laps + 2 mm, passing a corner every mm, 0.1 down
    # per mm; then one lap at -1 from where it ended, (1, 1), back to (1, 1)
    ramp_points = [[*corners[(k - 1) % 4], -0.1 * k] for k in range(1, 11)]
    lap = [[*corners[(k - 1) % 4], -1.0] for k in range(11, 15)]
    assert np.allclose(moves, [[0, 0, 0]] + ramp_points + lap)


def test_an_open_path_ramps_out_and_back_and_ends_in_the_direction_given():
    line = np.array([[0, 0], [10, 0]], float)
    angle = math.degrees(math.atan(0.5))                                    # 0.5 mm down per mm
    # two levels: the first is entered at the far end and runs back, so the last runs as given;
    # each ramp (1 mm down = 2 mm) goes 1 mm out and 1 mm back
    assert np.allclose(ramp.ramped_passes(line, [-1.0, -2.0], angle),
                       [[10, 0, 0], [9, 0, -0.5], [10, 0, -1], [0, 0, -1],
                        [1, 0, -1.5], [0, 0, -2], [10, 0, -2]])
    assert np.allclose(ramp.ramped_passes(line, [-1.0], angle), [[0, 0, 0], [1, 0, -0.5], [0, 0, -1], [10, 0, -1]])


def test_bad_ramps_are_refused():
    with pytest.raises(ramp.RampError, match="step down must be a number > 0 mm"):
        ramp.levels(-2.0, 0.0)
    with pytest.raises(ramp.RampError, match="ramp angle must be more than 0"):
        ramp.ramped_passes(np.array([[0, 0], [1, 0]], float), [-1.0], 90.0)
