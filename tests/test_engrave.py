"""W1 core: the gouge texture rule, the three operations, and what they must never do."""
import math

import numpy as np
import pytest

from kezuri.toolpath.operations.engrave import engrave
from kezuri.toolpath.engines import region
from kezuri.toolpath.ir.program import FEED, RAPID, Operation, Tool

PLATE = [np.array([[-100, -50], [100, -50], [100, 50], [-100, 50]], float)]
# Two block letters: an "I" bar and an "O" (a square ring with a counter).
LETTER_I = np.array([[-60, -20], [-50, -20], [-50, 20], [-60, 20]], float)
LETTER_O_OUT = np.array([[0, -20], [30, -20], [30, 20], [0, 20]], float)
LETTER_O_IN = np.array([[10, -10], [20, -10], [20, 10], [10, 10]], float)
LETTERS = [("Letters", [LETTER_I, LETTER_O_OUT, LETTER_O_IN])]


def glyph_region():
    return region.from_loops([LETTER_I, LETTER_O_OUT, LETTER_O_IN])


def distance_to_region_boundary(points, loops):
    """Distance from each point to the nearest boundary segment of the loops (brute force)."""
    best = np.full(len(points), np.inf)
    for loop in loops:
        a = loop
        b = np.roll(loop, -1, axis=0)
        for p0, p1 in zip(a, b):
            d = p1 - p0
            t = np.clip(((points - p0) @ d) / (d @ d), 0, 1)
            best = np.minimum(best, np.linalg.norm(points - (p0 + t[:, None] * d), axis=1))
    return best


# ----- the depth rule ------------------------------------------------------------------

def test_depth_rule_matches_the_paper_table():
    texture = engrave.GougeTexture()
    # The paper's table: digits 0..4 -> -2.0, -1.8, -1.6, -1.4, -1.2; 5..9 -> -2.0 .. -2.8.
    expected = [-2.0, -1.8, -1.6, -1.4, -1.2, -2.0, -2.2, -2.4, -2.6, -2.8]
    assert np.allclose(texture.depth(np.arange(10)), expected)


def test_digit_five_gives_base_depth_not_minus_one():
    # The paper's macro tested #28 GT 5 and sent 5 to the shallow branch: -2 + 1.0 = -1.0.
    assert engrave.GougeTexture().depth(5) == pytest.approx(-2.0)


def test_depth_rule_scales_with_amplitude():
    texture = engrave.GougeTexture(base_depth=-3.0, quantum=0.1, amplitude=0.4)
    assert np.allclose(texture.depth([0, 4, 9]), [-3.0, -2.6, -3.4])


@pytest.mark.parametrize("bad", [dict(quantum=0), dict(spacing=-1), dict(amplitude=float("nan")),
                                 dict(motion="wiggle"), dict(base_depth=-0.5)])
def test_bad_texture_settings_are_refused(bad):
    with pytest.raises(engrave.EngraveError):
        engrave.GougeTexture(**bad)


# ----- the texture applied to moves ------------------------------------------------------

def straight_row(length=100.0, z=-2.0):
    """Plunge at X0, one long row along +X, a stepover in Y, a row back."""
    xyz = [[0, 0, 2], [0, 0, z], [length, 0, z], [length, 3, z], [0, 3, z], [0, 3, 20]]
    kind = [RAPID, FEED, FEED, FEED, FEED, RAPID]
    feed = [np.nan, 300, 1000, 1000, 1000, np.nan]
    return Operation("row", Tool(2, "ball", 6.0), 6000, kind, xyz, feed, start=[0, 0, 20])


def test_long_rows_are_cut_in_twenty_mm_gouges_with_drawn_depths():
    op = straight_row(100.0)
    digits = iter([0, 9, 5, 4, 1, 2, 3, 6, 7, 8])
    textured, depths = engrave.apply_texture(op, engrave.GougeTexture(), digits)
    cut = textured.xyz[textured.kind == FEED]
    # Row 1: X 20, 40, 60, 80, 100 at the depths of digits 0, 9, 5, 4, 1.
    row1 = cut[1:6]
    assert np.allclose(row1[:, 0], [20, 40, 60, 80, 100])
    assert np.allclose(row1[:, 2], [-2.0, -2.8, -2.0, -1.2, -1.8])
    # The stepover (no X travel) stays at the last depth.
    assert np.allclose(cut[6], [100, 3, -1.8])
    # Row 2 back along -X: X 80 .. 0 at digits 2, 3, 6, 7, 8.
    assert np.allclose(cut[7:12, 0], [80, 60, 40, 20, 0])
    assert np.allclose(cut[7:12, 2], [-1.6, -1.4, -2.2, -2.4, -2.6])
    assert depths == pytest.approx([-2.0, -2.8, -2.0, -1.2, -1.8, -1.6, -1.4, -2.2, -2.4, -2.6])


def test_untextured_move_kinds_pass_through():
    op = straight_row(15.0)  # rows shorter than the gouge spacing
    textured, depths = engrave.apply_texture(op, engrave.GougeTexture(), iter([9] * 10))
    assert depths == []
    assert np.allclose(textured.xyz, op.xyz)
    assert np.array_equal(textured.kind, op.kind)


def test_remainder_of_a_row_stays_at_the_last_depth():
    op = straight_row(50.0)
    textured, depths = engrave.apply_texture(op, engrave.GougeTexture(), iter([9, 4, 0, 0]))
    cut = textured.xyz[textured.kind == FEED]
    assert np.allclose(cut[1:4], [[20, 0, -2.8], [40, 0, -1.2], [50, 0, -1.2]])


def test_consecutive_gouges_differ_by_at_most_one_point_six():
    op = straight_row(2000.0)
    textured, depths = engrave.apply_texture(op, engrave.GougeTexture(), engrave.digits_from_seed(7))
    assert len(depths) == 200
    assert np.max(np.abs(np.diff(depths))) <= 1.6 + 1e-9
    assert np.all(np.abs(np.round(np.array(depths) / 0.2) * 0.2 - depths) < 1e-9)
    assert min(depths) >= -2.8 - 1e-9 and max(depths) <= -1.2 + 1e-9


def test_scoop_dives_then_pushes_up():
    op = straight_row(40.0)
    texture = engrave.GougeTexture(motion="scoop", scoop_dive=0.25)
    textured, depths = engrave.apply_texture(op, texture, iter([9, 9, 0, 0]))
    cut = textured.xyz[textured.kind == FEED][1:5]
    # Each 20 mm gouge: reach the drawn depth after 5 mm, rise to the shallowest level at its end.
    assert np.allclose(cut, [[5, 0, -2.8], [20, 0, -2.0], [25, 0, -2.8], [40, 0, -2.0]])


def test_spacing_jitter_varies_gouge_lengths_within_bounds():
    op = straight_row(1000.0)
    texture = engrave.GougeTexture(spacing_jitter=0.3)
    textured, _ = engrave.apply_texture(op, texture, engrave.digits_from_seed(1), np.random.default_rng(3))
    xs = textured.xyz[textured.kind == FEED][1:, 0]
    first_row = xs[: np.argmax(xs) + 1]
    steps = np.diff(np.concatenate([[0.0], first_row]))[:-1]
    assert steps.min() >= 14 - 1e-9 and steps.max() <= 26 + 1e-9
    assert steps.std() > 1.0


# ----- the planned job -----------------------------------------------------------------

def planned(**changes):
    settings = engrave.EngraveSettings(**changes)
    return engrave.plan(PLATE, LETTERS, settings)


def test_three_operations_with_the_papers_tools():
    result = planned()
    names = [op.name for op in result.program.operations]
    assert names == ["roughing (gouge texture)", "band finishing", "burr contour"]
    rough, band, burr = result.program.operations
    assert (rough.tool.kind, rough.tool.diameter) == ("ball", 6.0)
    assert (band.tool.kind, band.tool.diameter) == ("flat", 1.0)
    assert burr.tool == rough.tool
    assert rough.texture is not None and band.texture is None


def test_no_tool_ever_cuts_inside_a_letter():
    result = planned()
    baked, _ = engrave.bake(result.program)
    glyphs = glyph_region()
    loops = [LETTER_I, LETTER_O_OUT, LETTER_O_IN]
    for op in baked.operations:
        cutting = op.xyz[op.kind != RAPID]
        below_top = cutting[cutting[:, 2] < 0]
        inside = region.contains_points(glyphs, below_top[:, :2])
        assert not inside.any(), op.name
        # The tool's radius at the top face must not reach into a letter either.
        reach = op.tool.radius if op.tool.kind == "flat" else \
            np.sqrt(np.maximum(0, op.tool.radius ** 2 - (op.tool.radius + below_top[:, 2]) ** 2))
        clearance = distance_to_region_boundary(below_top[:, :2], loops)
        assert np.all(clearance >= reach - 1e-6), op.name


def test_roughing_depths_follow_the_rule_and_band_is_flat():
    result = planned()
    baked, depths = engrave.bake(result.program)
    rough, band, burr = baked.operations
    assert len(depths) > 100
    grid = np.round((np.array(depths) + 2.0) / 0.2)
    assert np.allclose(np.array(depths), -2.0 + 0.2 * grid)
    assert min(depths) >= -2.8 - 1e-9 and max(depths) <= -1.2 + 1e-9
    assert set(np.round(depths, 6)) == set(np.round(np.arange(-2.8, -1.19, 0.2), 6))
    # Every cutting move below the top is at a drawn depth, the base depth or a plunge; the band
    # is cut at two 1 mm levels, each entered on a ramp (tests/test_band_ramp.py checks the ramps)
    band_z = band.xyz[(band.kind == FEED) & (band.xyz[:, 2] < 0), 2]
    assert band_z.min() == pytest.approx(-2.0) and np.isclose(band_z, -1.0).any()
    assert np.isclose(band_z, -2.0).sum() + np.isclose(band_z, -1.0).sum() > 0.5 * len(band_z)
    assert np.allclose(burr.xyz[(burr.kind == FEED) & (burr.xyz[:, 2] < 0), 2], -2.0)


def test_roughing_covers_the_plate_outside_the_band():
    result = planned()
    rough = result.program.operations[0]
    rows = rough.xyz[rough.kind == FEED]
    ys = np.unique(np.round(rows[:, 1], 6))
    # Zigzag at no more than the 3 mm stepover over the full 100 mm height.
    assert np.max(np.diff(ys)) <= 3.0 + 1e-9
    assert ys.min() < -49.9 and ys.max() > 49.9
    # Every roughing point keeps the 4 mm clearance from the letters (offset arcs are chords
    # within the region layer's arc tolerance).
    below = rows[rows[:, 2] < 0]
    clearance = distance_to_region_boundary(below[:, :2], [LETTER_I, LETTER_O_OUT, LETTER_O_IN])
    assert clearance.min() >= 4.0 - region.ARC_TOLERANCE - 1e-6


def test_band_rings_reach_from_the_letter_wall_to_the_band_edge():
    result = planned()
    band = result.program.operations[1]
    pts = band.xyz[(band.kind == FEED) & (band.xyz[:, 2] < 0)]
    d = distance_to_region_boundary(pts[:, :2], [LETTER_I, LETTER_O_OUT, LETTER_O_IN])
    assert d.min() == pytest.approx(0.5, abs=0.02)      # the 1 mm tool touches the letter walls
    assert d.max() == pytest.approx(3.5, abs=0.02)      # and reaches the band's outer edge
    levels = np.unique(np.round(d[d < 3.4] / 0.5))
    assert len(levels) >= 6                               # 0.5 mm stepover rings


def test_burr_contour_follows_the_band_border():
    burr = planned().program.operations[2]
    pts = burr.xyz[(burr.kind == FEED) & (burr.xyz[:, 2] < 0)]
    d = distance_to_region_boundary(pts[:, :2], [LETTER_I, LETTER_O_OUT, LETTER_O_IN])
    assert np.allclose(d, 4.0, atol=0.02)


def test_same_seed_same_program_other_seed_other_program():
    program = planned().program
    a, depths_a = engrave.bake(program)
    b, depths_b = engrave.bake(program)
    other = [op.replace(texture=op.texture and engrave.GougeTexture(seed=1)) for op in program.operations]
    c, depths_c = engrave.bake(program.__class__(program.name, other))
    assert depths_a == depths_b and np.array_equal(a.operations[0].xyz, b.operations[0].xyz)
    assert depths_a != depths_c


def test_raster_angle_turns_rows_and_gouges():
    result = planned(raster_angle=90.0)
    baked, depths = engrave.bake(result.program)
    rough = baked.operations[0]
    moves = (rough.xyz - rough.start_points())[rough.kind == FEED][:, :2]
    long_moves = moves[np.linalg.norm(moves, axis=1) > 10]
    assert np.all(np.abs(long_moves[:, 0]) < 1e-6)  # rows now run along Y
    assert len(depths) > 50


def test_tool_too_big_for_a_counter_is_reported_as_skipped():
    tiny_counter = [("Letters", [LETTER_O_OUT, np.array([[14.6, -5], [15.4, -5], [15.4, 5], [14.6, 5]])])]
    result = engrave.plan(PLATE, tiny_counter)
    skipped = [s for s in result.skipped if s["operation"] == "band finishing"]
    assert len(skipped) == 1
    assert skipped[0]["area_mm2"] == pytest.approx(0.8 * 10, rel=0.01)
    assert skipped[0]["at"] == pytest.approx([15.0, 0.0], abs=0.01)
    assert any("too big" in w for w in result.warnings)
    # named by the letters object it lies in; the character is not known without the object's text
    assert (skipped[0]["letters"], skipped[0]["character"]) == ("Letters", None)
    assert "band finishing: the tool is too big to enter a gap of 8.00 mm^2 in letters 'Letters' near X15.0 Y0.0; it " \
           "is left uncut" in result.warnings


def test_a_region_left_uncut_is_named_by_its_character_when_the_text_tells_it():
    tiny = np.array([[14.6, -5], [15.4, -5], [15.4, 5], [14.6, 5]])
    letters = [("Word", [LETTER_I, LETTER_O_OUT, tiny])]
    result = engrave.plan(PLATE, letters, texts={"Word": "I O"})       # two glyphs, two characters (not spaces)
    band = [s for s in result.skipped if s["operation"] == "band finishing"]
    assert [(s["letters"], s["character"]) for s in band] == [("Word", "O")]
    assert "band finishing: the tool is too big to enter a gap of 8.00 mm^2 in 'O' of letters 'Word' near X15.0 Y0.0; " \
           "it is left uncut" in result.warnings
    # a text that does not match the glyphs (three characters, two glyphs): the object only
    result = engrave.plan(PLATE, letters, texts={"Word": "IOX"})
    assert [s["character"] for s in result.skipped if s["operation"] == "band finishing"] == [None]


def test_glyphs_of_an_i_and_a_lower_case_letter():
    from kezuri.toolpath.operations.engrave import glyphs
    stem, dot = np.array([[0, 0], [2, 0], [2, 10], [0, 10]], float), np.array([[0, 12], [2, 12], [2, 14], [0, 14]])
    ring_out = np.array([[5, 0], [12, 0], [12, 8], [5, 8]], float)
    ring_in = np.array([[7, 2], [10, 2], [10, 6], [7, 6]], float)
    loops = [stem, dot, ring_out, ring_in]
    assert glyphs.character_at(loops, "io", (8.5, 4.0)) == "o"              # in the o's counter
    assert glyphs.character_at(loops, "io", (1.0, 13.0)) == "i"             # the dot is the i's
    assert glyphs.character_at(loops, "i\no", (8.5, 4.0)) is None          # two lines: not told
    assert glyphs.describe("o") == "'o' (U+006F)" and glyphs.describe("O") == "'O'"
    assert glyphs.describe("\u6f22") == "'\u6f22' (U+6F22)"
    assert glyphs.owner([("A", [stem]), ("B", [ring_out, ring_in])], (8.5, 4.0)) == "B"
    assert glyphs.owner([("A", [stem]), ("B", [ring_out, ring_in])], (3.0, 5.0)) == "A"   # nearest


@pytest.mark.parametrize("plate, letters, match", [
    ([], LETTERS, "plate: no closed outline"),
    (PLATE, [], "no letters"),
    (PLATE, [("Word", [np.array([[0, 0], [10, 0]])])], "fewer than 3"),
    (PLATE, [("Word", [np.array([[90, 0], [120, 0], [120, 10], [90, 10]])])], "outside the plate"),
    (PLATE, [("Word", [np.array([[0, 0], [np.nan, 0], [10, 10]])])], "non-finite"),
])
def test_bad_geometry_is_refused_with_a_clear_message(plate, letters, match):
    with pytest.raises(ValueError, match=match):
        engrave.plan(plate, letters)


@pytest.mark.parametrize("changes, match", [
    (dict(stepover=0.0), "stepover"),
    (dict(stepover=8.0), "wider than"),
    (dict(letter_clearance=2.0), "cut into the letters"),
    (dict(finish_tool=Tool(3, "flat", 6.0)), "the 6 mm finishing tool is wider than the 4 mm band"),
    (dict(rough_feed=float("nan")), "finite"),
])
def test_bad_settings_are_refused(changes, match):
    with pytest.raises(engrave.EngraveError, match=match):
        planned(**changes)


def test_cycle_time_matches_feed_lengths():
    baked, _ = engrave.bake(planned().program)
    for op in baked.operations:
        cutting = op.kind != RAPID
        lengths = op.move_lengths()
        expected = np.sum(lengths[cutting] / op.feed[cutting]) * 60 + lengths[~cutting].sum() / 5000 * 60
        assert op.cycle_time(5000) == pytest.approx(expected)
        assert op.feed_length() == pytest.approx(lengths[cutting].sum())
    assert math.isclose(baked.cycle_time(), sum(op.cycle_time(5000) for op in baked.operations))


# ---------------------------------------------------------------- depth against the plate


def test_a_cut_through_the_plate_is_refused_naming_the_setting_and_the_thickness():
    deep = engrave.EngraveSettings(texture=engrave.GougeTexture(base_depth=-30.0))
    # deepest gouge: -30 - 0.8 = -30.8, below the bottom (Z -20) of a 20 mm plate
    with pytest.raises(engrave.EngraveError, match=r"base depth -30 mm - amplitude 0\.8 mm cuts to Z -30\.8, "
                                                   r"through the 20 mm plate \(its bottom is Z -20\)"):
        engrave.plan(PLATE, LETTERS, deep, plate_thickness=20.0)
    # the paper's depths (deepest -2.8) on a 2.5 mm plate: through; on a 3 mm plate: fine
    with pytest.raises(engrave.EngraveError, match=r"cuts to Z -2\.8, through the 2\.5 mm plate"):
        engrave.plan(PLATE, LETTERS, plate_thickness=2.5)
    result = engrave.plan(PLATE, LETTERS, plate_thickness=3.0)
    _, depths = engrave.bake(result.program)
    assert min(depths) >= -2.8 - 1e-9
    # reaching the bottom exactly is through too; the band depth is checked as well
    with pytest.raises(engrave.EngraveError, match=r"cuts to Z -2\.8, through the 2\.8 mm plate"):
        engrave.plan(PLATE, LETTERS, plate_thickness=2.8)
    band = engrave.EngraveSettings(band_depth=-12.0, burr_depth=-2.0)
    with pytest.raises(engrave.EngraveError, match=r"band depth -12 mm cuts to Z -12, through the 10 mm plate"):
        engrave.plan(PLATE, LETTERS, band, plate_thickness=10.0)
    for bad in (0.0, -5.0, float("nan")):
        with pytest.raises(engrave.EngraveError, match="plate thickness must be a positive number"):
            engrave.plan(PLATE, LETTERS, plate_thickness=bad)
