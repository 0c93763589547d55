"""The turn-mill programs' frames, read back as text by the independent rules reader
(``controller_rules.check_turret_frames``): from the program start and after every turret index
the tool reaches its start point clear of the bar, every home return starts clear of it, and the
program ends clear of it; and the reader catches each of these when it is broken."""
import re

import numpy as np
import pytest

import controller_rules as rules
from kezuri.post import turnmill_xzc
from kezuri.toolpath.operations.turnmill import turnmill as tm
from test_turnmill_unmachined import hex_bar_with_hole


@pytest.fixture(scope="module")
def programs():
    """(name, control, text, stock) of the sample's and the hex bar's programs on both posts."""
    out = []
    for name, (v, f, stock) in (("sample", tm.sample_part()), ("hex bar", hex_bar_with_hole())):
        program = tm.plan(v, f, stock, name=name).program
        out.append((f"{name} xzc", "turnmill-xzc", turnmill_xzc.TurnMillXZCPost().to_text(program), stock))
        out.append((f"{name} linuxcnc", "turnmill-linuxcnc", turnmill_xzc.TurnMillLinuxCNCPost().to_text(program),
                    stock))
    return out


def test_every_frame_stays_clear_of_the_bar(programs):
    for name, control, text, stock in programs:
        assert rules.check(text, control) == [], name
        assert rules.check_turret_frames(text, control, stock.radius, stock.z_max) == [], name


def test_each_index_is_followed_by_a_rapid_to_a_start_point_outside_the_bar(programs):
    """Read independently of the rule: the first move after each T word is G00 with X beyond the
    bar's diameter and Z above its end face (the corner the post starts every operation from)."""
    for name, control, text, stock in programs:
        if control != "turnmill-xzc":
            continue
        lines = text.splitlines()
        indexes = [i for i, line in enumerate(lines) if re.match(r"^T\d{4}$", line)]
        assert len(indexes) == len({op for op in re.findall(r"^T(\d{4})$", text, re.M)}) >= 1, name
        for i in indexes:
            assert lines[i - 1] == "G28 U0. W0.", name
            first = next(line for line in lines[i + 1:] if re.search(r"\b[XZ]-?[0-9.]", line))
            words = dict(re.findall(r"([GXZC])(-?[0-9.]+)", first))
            assert words["G"] == "00", (name, first)
            assert float(words["X"]) / 2 > stock.radius and float(words["Z"]) > stock.z_max, (name, first)
        assert lines[-3:] == ["G28 U0. W0.", "M30", "%"], name


FRAME = ("%\nO0001\nG21 G18\nG28 U0. W0.\nT0101\nM133 P4000\n{approach}\nG93\nG01 X80. Z-10. F10.\n"
         "G00 X{retract} Z-10.\nG98\nM135\n{end}\nM30\n%\n")


@pytest.mark.parametrize("approach, retract, end, expected", [
    ("G00 X89. Z2. C0.\nZ-10.", "89.", "G28 U0. W0.", None),          # clear corner, then down outside the bar
    ("G00 X70. Z-10. C0.", "89.", "G28 U0. W0.", "rapid into"),        # straight to a point inside the bar
    ("G00 X89. Z2. C0.\nZ-10.\nX70.", "89.", "G28 U0. W0.", "rapid into"),   # rapid in before the first cut
    ("G00 X89. Z2. C0.\nZ-10.", "80.", "G28 U0. W0.", "home return from"),   # home without retracting
    ("G00 X89. Z2. C0.\nZ-10.", "80.", "", "program ends with the tool"),    # ends inside the bar
])
def test_the_rule_catches_each_break(approach, retract, end, expected):
    text = FRAME.format(approach=approach, retract=retract, end=end).replace("\n\n", "\n")
    found = rules.check_turret_frames(text, "turnmill-xzc", 42.5, 0.0)
    if expected is None:
        assert found == []
    else:
        assert found and all(expected in message for _, _, message in found), found


def test_linuxcnc_x_is_a_radius():
    text = "G21\nT1 M06 G43 H1\nS4000 M03\nG00 X44.5 Z2. C0.\nZ-10.\nG93\nG01 X40. F10.\nG94\nG00 X44.5\nM05\nM30\n"
    assert rules.check_turret_frames(text, "turnmill-linuxcnc", 42.5, 0.0) == []
    inside = text.replace("G00 X44.5 Z2. C0.", "G00 X30. Z-5. C0.")
    assert rules.check_turret_frames(inside, "turnmill-linuxcnc", 42.5, 0.0)
    assert np.isclose(42.5, 85.0 / 2)
