"""The job-only kinds' settings checks (toolpath/operations/fields.py): every bound and choice is refused
with the kind's own error class, in the words the kinds have always used (the Japanese templates in
operators/translations.py match them), one case per kind of rule, the expected text written out here."""
import pytest

from kezuri.toolpath.operations.chamfer.chamfer import ChamferError, ChamferSettings
from kezuri.toolpath.operations.drill.drill import DrillError, DrillSettings
from kezuri.toolpath.operations.fields import FINITE, NUMBER, Field, Fields
from kezuri.toolpath.operations.pocket.pocket import PocketError, PocketSettings
from kezuri.toolpath.operations.profile.profile import ProfileError, ProfileSettings
from kezuri.toolpath.operations.vcarve.vcarve import VCarveError, VCarveSettings

CASES = [
    (ProfileSettings, (10.0,), ProfileError, dict(side="middle"),
     "profile: side must be one of outside, inside, on, got 'middle'"),
    (ProfileSettings, (10.0,), ProfileError, dict(feed=float("nan")), "profile: feed must be a number, got nan"),
    (ProfileSettings, (10.0,), ProfileError, dict(feed=True), "profile: feed must be a number, got True"),
    (ProfileSettings, (10.0,), ProfileError, dict(clearance_z="20"), "profile: clearance_z must be a number, got '20'"),
    (ProfileSettings, (10.0,), ProfileError, dict(feed=0), "profile: feed must be more than 0, got 0"),
    (ProfileSettings, (10.0,), ProfileError, dict(allowance=-0.5), "profile: allowance must be 0 or more, got -0.5"),
    (ProfileSettings, (10.0,), ProfileError, dict(ramp_angle=50.0),
     "profile: ramp_angle must be more than 0 and at most 45 degrees, got 50.0"),
    (PocketSettings, (), PocketError, dict(strategy="spiral"),
     "pocket: strategy must be one of offset, zigzag, got 'spiral'"),
    (PocketSettings, (), PocketError, dict(angle=float("inf")), "pocket: angle must be a number, got inf"),
    (PocketSettings, (), PocketError, dict(rest_feed=-1), "pocket: rest_feed must be more than 0, got -1"),
    (PocketSettings, (), PocketError, dict(ramp_angle=0.2), "pocket: ramp_angle must be from 0.5 to 45 degrees, got 0.2"),
    (PocketSettings, (), PocketError, dict(stepover=0.005), "pocket: stepover must be at least 0.01 mm, got 0.005"),
    (PocketSettings, ("slot",), PocketError, dict(helix_diameter=0.05),
     "slot: helix_diameter must be 0 (no helix) or from 0.1 to 100000 mm, got 0.05"),
    (PocketSettings, (), PocketError, dict(helix_diameter=-1.0), "pocket: helix_diameter must be 0 or more, got -1.0"),
    (VCarveSettings, (), VCarveError, dict(clear_stepover=-1.0),
     "V-carve: clear_stepover must be 0 (the end mill's radius) or more, got -1.0"),
    (VCarveSettings, (), VCarveError, dict(tolerance=0.5), "V-carve: tolerance must be from 0.001 to 0.1 mm, got 0.5"),
    (VCarveSettings, (), VCarveError, dict(inlay="both"), "V-carve: inlay must be one of none, female, male, got 'both'"),
    (ChamferSettings, (), ChamferError, dict(tip_gap=float("nan")), "chamfer: tip_gap must be 0 or more, got nan"),
    (ChamferSettings, (), ChamferError, dict(plunge_feed=0.0), "chamfer: plunge_feed must be a positive number, got 0.0"),
    (ChamferSettings, (), ChamferError, dict(rpm="fast"), "chamfer: rpm must be a positive number, got 'fast'"),
    (DrillSettings, (), DrillError, dict(depth=-2.0), "drilling: depth must be a positive number, got -2.0"),
    (DrillSettings, (), DrillError, dict(peck_gap=float("-inf")), "drilling: peck_gap must be 0 or more, got -inf"),
    (DrillSettings, (), DrillError, dict(retract="g99"), "drilling: retract must be one of initial, r, got 'g99'"),
    (DrillSettings, (), DrillError, dict(helix=True, helix_pitch=0.0),
     "helix milling: helix_pitch must be a positive number, got 0.0"),
    (DrillSettings, (), DrillError, dict(helix=False, helix_pitch=0.0), None),
    (DrillSettings, (), DrillError, dict(spot=True, spot_depth=float("nan")),
     "spot drilling: spot_depth must be a positive number, got nan"),
]


@pytest.mark.parametrize("settings_type, args, error, values, message", CASES)
def test_each_rule_reads_as_it_always_has(settings_type, args, error, values, message):
    settings = settings_type(**values)
    if message is None:
        settings.check(*args)
        return
    with pytest.raises(error) as caught:
        settings.check(*args)
    assert str(caught.value) == message


def test_the_defaults_pass():
    ProfileSettings().check(10.0)
    for settings_type in (PocketSettings, VCarveSettings, ChamferSettings, DrillSettings):
        settings_type().check()


class Plain:
    low = 0.0
    top = 2.5
    mode = "a"


@pytest.mark.parametrize("field, value, words", [
    (Field("low", low=0.0, above=True), 0.0, "x: low must be more than 0, got 0.0"),
    (Field("low", low=1.0, above=True), 1.0, "x: low must be more than 1, got 1.0"),
    (Field("top", high=2.0, low=0.0, above=True, unit="mm"), 2.5, "x: top must be more than 0 and at most 2 mm, got 2.5"),
    (Field("top", low=3.0, unit="s"), 2.5, "x: top must be at least 3 s, got 2.5"),
    (Field("top", low=3.0, high=4.0, zero="off"), 2.5, "x: top must be 0 (off) or from 3 to 4, got 2.5"),
    (Field("mode", choices=("b", "c")), "a", "x: mode must be one of b, c, got 'a'"),
])
def test_the_words_of_each_bound(field, value, words):
    settings = Plain()
    setattr(settings, field.name, value)
    with pytest.raises(ValueError) as caught:
        Fields(NUMBER, (field,)).check(settings, "x", ValueError)
    assert str(caught.value) == words


def test_zero_is_taken_where_it_has_a_meaning_and_the_bounds_are_inclusive():
    Fields(NUMBER, (Field("low", low=3.0, high=4.0, zero="off"), Field("top", low=2.5, high=2.5))).check(
        Plain(), "x", ValueError)


def test_numbers_are_all_typed_before_the_first_bound():
    class Two:
        first = -1.0
        second = "2"
    with pytest.raises(ValueError, match="^x: second must be a number, got '2'$"):
        Fields(NUMBER, (Field("first", low=0.0), Field("second"))).check(Two(), "x", ValueError)
    with pytest.raises(ValueError, match="^x: first must be 0 or more, got -1.0$"):
        Fields(FINITE, (Field("first", low=0.0), Field("second"))).check(Two(), "x", ValueError)


def test_an_unbounded_finite_field_asks_for_a_number():
    class One:
        only = float("nan")
    with pytest.raises(ValueError, match="^x: only must be a number, got nan$"):
        Fields(FINITE, (Field("only"),)).check(One(), "x", ValueError)
