"""Text too fine for the tool (toolpath/engines/finetext.py): closed forms on slots and squares.

A slot of width w between two bars (the waste a raised letter leaves between two strokes) is
missed by a round tool of diameter D exactly when w < D; scaled by s its width is s w, so the
smallest height at which it is reached is height x D / w.  The expected numbers below come from
that arithmetic, not from the module.
"""
import math

import numpy as np
import pytest

from kezuri.toolpath.engines import finetext as ft
from kezuri.toolpath.engines import region as rg


def box(x0, y0, x1, y1):
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], float)


def two_bars(gap: float, height: float = 10.0, bar: float = 2.0):
    """Two bars ``bar`` wide and ``height`` tall, ``gap`` apart, as one character 'H'-like; the
    waste to cut: the band 4 mm around them (the slot between them included)."""
    left, right = box(0, 0, bar, height), box(bar + gap, 0, 2 * bar + gap, height)
    letters = rg.from_loops([left, right])
    waste = rg.offset(letters, 4.0) - letters
    return ft.Character("H", 0, (left, right)), waste


@pytest.mark.parametrize("gap", [0.3, 0.5, 0.8, 0.95])
def test_a_slot_narrower_than_the_tool_is_named_with_its_width(gap):
    character, waste = two_bars(gap)
    found = ft.check([character], waste, 1.0)
    assert len(found) == 1
    f = found[0]
    assert (f.char, f.index) == ("H", 0)
    # the whole slot (gap x 10 mm) is missed, less what the tool's arc reaches at its two mouths
    assert f.missed_mm2 == pytest.approx(gap * 10.0, rel=0.12)
    assert f.narrowest_mm == pytest.approx(gap, rel=0.01)
    assert f.height_mm == pytest.approx(10.0)
    # 10 mm x 1 mm / gap, rounded up to 0.1 mm
    expected = math.ceil(10.0 * 1.0 / gap / 0.1 - 1e-6) / 10
    assert expected - 1e-9 <= f.min_height_mm <= expected + 0.2 + 1e-9


@pytest.mark.parametrize("gap", [1.05, 1.5, 3.0])
def test_a_slot_the_tool_enters_is_not_named(gap):
    character, waste = two_bars(gap)
    assert ft.check([character], waste, 1.0) == []


def test_the_smallest_height_scales_linearly_with_the_tool_and_the_gap():
    character, waste = two_bars(0.5)
    one = ft.check([character], waste, 1.0)[0]
    half = ft.check([character], waste, 0.8)[0]
    assert one.min_height_mm == pytest.approx(20.0, abs=0.2)          # 10 x 1 / 0.5
    assert half.min_height_mm == pytest.approx(16.0, abs=0.2)         # 10 x 0.8 / 0.5
    given = ft.check([ft.Character("H", 0, character.loops, height=5.0)], waste, 1.0)[0]
    assert given.min_height_mm == pytest.approx(10.0, abs=0.2)        # the caller's height: 5 x 1 / 0.5


def test_at_the_named_height_the_character_passes():
    character, waste = two_bars(0.4)
    f = ft.check([character], waste, 1.0)[0]
    s = f.min_height_mm / f.height_mm
    scaled = ft.Character("H", 0, tuple(loop * s for loop in character.loops))
    big = rg.from_loops([loop * s for loop in character.loops])
    assert ft.check([scaled], rg.offset(big, 4.0) - big, 1.0) == []


def test_sharp_corners_are_not_gaps():
    """An L-shaped letter: the waste has a 90 degree convex corner in its elbow, which no round
    tool reaches at any size: that is a corner, not a gap, and nothing is named."""
    letter = np.array([[0, 0], [6, 0], [6, 2], [2, 2], [2, 8], [0, 8]], float)
    region = rg.from_loops([letter])
    waste = rg.offset(region, 4.0) - region
    # the elbow's cap is there to be missed: r^2 (1 - pi/4) = 0.054 mm^2 for the 1 mm tool
    reached = rg.offset(rg.offset(waste, -0.5), 0.5)
    assert rg.area(waste - reached) > 0.05
    assert ft.check([ft.Character("L", 0, (letter,))], waste, 1.0) == []


def test_a_counter_smaller_than_the_tool_is_a_gap():
    """An 'o' 4 mm across with a round counter 0.6 mm across: missed whole by the 1 mm tool."""
    angles = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    outer = np.column_stack([2 * np.cos(angles), 2 * np.sin(angles)])
    inner = np.column_stack([0.3 * np.cos(angles), 0.3 * np.sin(angles)])[::-1]
    letter = rg.from_loops([outer, inner])
    waste = rg.offset(letter, 4.0) - letter
    f = ft.check([ft.Character("o", 3, (outer, inner))], waste, 1.0)
    assert len(f) == 1 and f[0].index == 3
    assert f[0].missed_mm2 == pytest.approx(math.pi * 0.09, rel=0.05)
    assert f[0].narrowest_mm == pytest.approx(0.6, rel=0.02)
    assert f[0].min_height_mm == pytest.approx(4.0 / 0.6, abs=0.15)


def test_each_gap_is_named_by_the_character_it_lies_in():
    first, _ = two_bars(2.0)                                   # wide: the tool enters
    second_loops = tuple(loop + [20.0, 0.0] for loop in two_bars(0.5)[0].loops)
    second = ft.Character("I", 1, second_loops)
    letters = rg.from_loops(list(first.loops) + list(second_loops))
    waste = rg.offset(letters, 4.0) - letters
    found = ft.check([first, second], waste, 1.0)
    assert [(f.char, f.index) for f in found] == [("I", 1)]
    assert 20 < found[0].at[0] < 26


def test_bad_tool_is_refused():
    character, waste = two_bars(0.5)
    for bad in (0, -1, float("nan"), "1"):
        with pytest.raises(ft.FineTextError, match="tool diameter"):
            ft.check([character], waste, bad)


def test_a_slot_closed_at_one_end_is_a_gap():
    """A 'U' whose inside is 0.6 mm wide and 8 mm deep: the walls and the floor of the slot are one
    run of wall turning half a turn, so it is a gap, with its width and height as for a slot."""
    u = np.array([[0, 0], [4.6, 0], [4.6, 10], [2.6, 10], [2.6, 2], [2.0, 2], [2.0, 10], [0, 10]], float)
    region = rg.from_loops([u])
    waste = rg.offset(region, 4.0) - region
    found = ft.check([ft.Character("U", 0, (u,))], waste, 1.0)
    assert len(found) == 1
    assert found[0].narrowest_mm == pytest.approx(0.6, rel=0.01)
    assert found[0].missed_mm2 == pytest.approx(0.6 * 8, rel=0.1)
    assert math.ceil(10 / 0.6 * 10 - 1e-6) / 10 - 1e-9 <= found[0].min_height_mm <= math.ceil(10 / 0.6 * 10) / 10 + 0.2


def test_a_wedge_between_strokes_is_a_corner():
    """A 'V' whose inside is a 40 degree wedge: the tool reaches in until it touches both sides,
    and what is left at the tip is left at any size: not named."""
    half = math.tan(math.radians(20)) * 8
    v = np.array([[0, 0], [6, 0], [6, 8], [3 + half, 8], [3, 0.5], [3 - half, 8], [0, 8]], float)
    region = rg.from_loops([v])
    waste = rg.offset(region, 4.0) - region
    assert ft.check([ft.Character("V", 0, (v,))], waste, 1.0) == []


@pytest.mark.parametrize("gap, named", [(0.08, False), (0.15, True)])
def test_a_hairline_narrower_than_1_percent_of_the_height_is_not_a_gap(gap, named):
    """Two contours of a font 0.08 mm apart in a 10 mm character (0.8 % of its height) touch by
    design; at 0.15 mm (1.5 %) the slot is named, with its width."""
    character, waste = two_bars(gap)
    found = ft.check([character], waste, 1.0)
    assert bool(found) == named
    if named:
        assert found[0].narrowest_mm == pytest.approx(gap, rel=0.02)


@pytest.mark.parametrize("width, named", [(0.6, True), (1.2, False)])
def test_letters_cut_in_are_checked_on_their_strokes(width, named):
    """A pocket or a V-carve's flat clearing cuts the strokes themselves: an 'I' of one stroke
    ``width`` wide and 10 mm tall is named for the 1 mm tool iff the stroke is narrower."""
    stroke = box(0, 0, width, 10)
    found = ft.check([ft.Character("I", 0, (stroke,))], [stroke], 1.0)
    assert bool(found) == named
    if named:
        assert found[0].missed_mm2 == pytest.approx(width * 10, rel=0.01)
        assert found[0].narrowest_mm == pytest.approx(width, rel=0.01)
        assert found[0].min_height_mm == pytest.approx(math.ceil(10 / width * 10) / 10, abs=0.11)


def test_the_same_character_drawn_larger_asks_for_the_same_height():
    """The smallest height is a property of the character's shape and the tool, not of the size it
    is drawn at now: the 0.4 mm slot of a 10 mm character asks for 25 mm drawn at 10 or at 16 mm."""
    character, _ = two_bars(0.4)
    asked = []
    for k in (1.0, 1.6):
        loops = tuple(loop * k for loop in character.loops)
        letters = rg.from_loops(list(loops))
        asked.append(ft.check([ft.Character("H", 0, loops)], rg.offset(letters, 4.0) - letters, 1.0)[0].min_height_mm)
    assert asked[0] == pytest.approx(25.0, abs=0.2)
    assert asked[1] == pytest.approx(asked[0], abs=0.2)
