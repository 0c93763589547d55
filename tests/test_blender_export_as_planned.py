"""Export writes what was previewed: after Generate, an Export with nothing changed writes the
planned program without planning again and says so; a changed setting re-plans (and says which
operation), and the program then follows the change (bpy wheel, in-process)."""
import os

import pytest

bpy = pytest.importorskip("bpy")
from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)


def messages(capfd) -> str:
    out, err = capfd.readouterr()
    return out + err


@pytest.fixture
def plate(empty_scene):
    from kezuri.operators import samples
    samples.name_plate(empty_scene)
    empty_scene.kezuri.machine.post = "linuxcnc"        # Generate plans for the post Export writes
    return empty_scene


def test_engrave_export_writes_the_generated_plan_and_replans_a_change(plate, tmp_path, capfd):
    from kezuri.operators import plancache
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    cache = dict(plancache.cache_of(plate))
    assert len(cache) >= 1
    first = tmp_path / "a.ngc"
    assert bpy.ops.kezuri.engrave_export(filepath=str(first), post="linuxcnc") == {"FINISHED"}
    assert "nothing re-planned" in messages(capfd)
    assert set(plancache.cache_of(plate)) >= set(cache)           # the same parts, none added
    plate.kezuri.engrave.seed = plate.kezuri.engrave.seed + 1
    second = tmp_path / "b.ngc"
    assert bpy.ops.kezuri.engrave_export(filepath=str(second), post="linuxcnc") == {"FINISHED"}
    assert "re-planned: engrave" in messages(capfd)
    assert first.read_text() != second.read_text()                 # another seed, other gouge depths
    third = tmp_path / "c.ngc"
    assert bpy.ops.kezuri.engrave_export(filepath=str(third), post="linuxcnc") == {"FINISHED"}
    assert "nothing re-planned" in messages(capfd)
    assert third.read_text() == second.read_text()


def test_a_changed_plate_is_planned_again(plate, tmp_path, capfd):
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    messages(capfd)
    plate.objects["Letters"].location.x += 2.0 / (plate.unit_settings.scale_length * 1000.0)   # 2 mm
    bpy.context.view_layer.update()
    path = tmp_path / "moved.ngc"
    assert bpy.ops.kezuri.engrave_export(filepath=str(path), post="linuxcnc") == {"FINISHED"}
    assert "re-planned: engrave" in messages(capfd)
    assert os.path.getsize(path) > 1000


@pytest.mark.parametrize("sample, generate, export, post", [
    ("rotary_block", "rotary_generate", "rotary_export", "linuxcnc"),
    ("turnmill_part", "turnmill_generate", "turnmill_export", "linuxcnc"),
])
def test_rotary_and_turnmill_exports_write_the_generated_plan(empty_scene, tmp_path, capfd, sample, generate, export,
                                                              post):
    from kezuri.operators import samples
    samples.SCENES[sample](empty_scene)
    assert getattr(bpy.ops.kezuri, generate)() == {"FINISHED"}
    messages(capfd)
    path = tmp_path / "a.nc"
    assert getattr(bpy.ops.kezuri, export)(filepath=str(path), post=post) == {"FINISHED"}
    said = messages(capfd)
    assert "nothing re-planned" in said and "re-planned:" not in said
    assert path.stat().st_size > 1000
