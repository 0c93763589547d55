"""The scene read as Blender shows it (issue 27, "Scenes read wrongly"): a plate or letters tilted
by an unapplied rotation are refused by name, a turn about Z is honoured, letters shown through a
collection instance are cut like the plain object, and a plate larger than the machine (a unit
scale mistake) is refused before any planning.  bpy wheel, in-process."""
import math
import time

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

from kezuri.operators import convert, samples  # noqa: E402
from kezuri.operators import engrave as shell  # noqa: E402


@pytest.fixture
def scene(empty_scene):
    samples.name_plate(empty_scene)
    yield empty_scene
    for name in ("Letter source", "Shown letters", "Nothing"):      # what instance_letters made
        collection = bpy.data.collections.get(name)
        if collection is not None:
            for obj in list(collection.objects):
                bpy.data.objects.remove(obj)
            bpy.data.collections.remove(collection)


def depsgraph():
    graph = bpy.context.evaluated_depsgraph_get()
    graph.update()
    return graph


def cutting_moves(scene) -> np.ndarray:
    """Every point of every baked operation below the plate top (what the tools cut), in order."""
    job = shell.run_engrave(scene, depsgraph())
    xyz = np.concatenate([op.xyz for op in job.baked.operations])
    return xyz[xyz[:, 2] < 0]


@pytest.mark.parametrize("axis, index", [("X", 0), ("Y", 1)])
def test_a_plate_tilted_about_x_or_y_is_refused_naming_it_and_the_tilt(scene, axis, index):
    plate = bpy.data.objects["Plate"]
    plate.rotation_euler[index] = math.radians(10.0)
    with pytest.raises(convert.SceneInputError) as error:
        shell.engrave_operation(scene, depsgraph())
    assert str(error.value) == (f"plate 'Plate' is tilted 10 deg about {axis}: apply or clear its rotation "
                                "(Ctrl-A)")


def test_a_tilt_below_the_threshold_and_a_flip_upside_down_are_level(scene):
    plate = bpy.data.objects["Plate"]
    plate.rotation_euler[0] = math.radians(0.0005)          # 0.0005 deg: 0.0017 mm over the 200 mm plate
    shell.engrave_operation(scene, depsgraph())
    assert convert.tilt_of(np.diag([1.0, 1.0, -1.0]))[0] == 0.0      # a mirror in Z keeps the top level
    assert convert.tilt_of(np.array([[1, 0, 0], [0, -1, 0], [0, 0, -1.0]]))[0] == pytest.approx(0.0, abs=1e-9)


def test_a_plate_turned_about_z_is_read_turned_as_today(scene):
    plate = bpy.data.objects["Plate"]
    plate.rotation_euler[2] = math.radians(30.0)
    operation, _, read = shell.engrave_operation(scene, depsgraph())
    # the 200 x 100 mm top turned 30 deg: its corners at (+-100, +-50) turned, about the centre
    corners = np.array([[100, 50], [-100, 50], [-100, -50], [100, -50]], float)
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    turned = corners @ np.array([[c, s], [-s, c]])
    outline = np.concatenate(read.outline)
    for corner in turned:
        assert np.min(np.linalg.norm(outline - corner, axis=1)) < 1e-3
    assert read.size[0] == pytest.approx(2 * (100 * c + 50 * s), abs=1e-3)


def test_letters_tilted_out_of_the_plate_top_are_refused_by_name(scene):
    bpy.data.objects["Letters"].rotation_euler[1] = math.radians(4.0)
    with pytest.raises(convert.SceneInputError) as error:
        shell.engrave_operation(scene, depsgraph())
    assert str(error.value) == ("object 'Letters' is tilted 4 deg about Y out of the plate's top: apply or clear "
                                "its rotation (Ctrl-A)")


def instance_letters(scene, where=(0.0, 0.0, 0.0)):
    """Move the Letters object into a collection the scene does not hold, and show that collection
    through an Empty at ``where`` (Add > Collection Instance); the Engrave panel takes the Empty's
    collection as its letters."""
    letters = bpy.data.objects["Letters"]
    scene.collection.objects.unlink(letters)
    source = bpy.data.collections.new("Letter source")
    source.objects.link(letters)
    empty = bpy.data.objects.new("Sign text", None)
    empty.instance_type = "COLLECTION"
    empty.instance_collection = source
    empty.location = where
    shown = bpy.data.collections.new("Shown letters")
    scene.collection.children.link(shown)
    shown.objects.link(empty)
    scene.kezuri.engrave.letters = None
    scene.kezuri.engrave.letters_collection = shown
    return empty


def test_letters_shown_through_a_collection_instance_are_cut_like_the_plain_object(scene):
    plain = cutting_moves(scene)
    instance_letters(scene)
    instanced = cutting_moves(scene)
    assert len(plain) > 1000
    assert instanced.shape == plain.shape
    assert np.abs(instanced - plain).max() < 1e-6


def test_a_collection_instance_moved_moves_its_letters(scene):
    reference = shell.engrave_operation(scene, depsgraph())[0].geometry.letter_loops
    instance_letters(scene, where=(10.0, -5.0, 0.0))           # 10 mm right, 5 mm to the front
    moved = shell.engrave_operation(scene, depsgraph())[0].geometry.letter_loops
    plain = np.concatenate(reference)
    shifted = np.concatenate(moved)
    assert shifted.shape == plain.shape
    assert np.abs(shifted - (plain + [10.0, -5.0])).max() < 1e-4


def test_a_collection_instance_showing_no_letters_is_refused_by_name(scene):
    empty = instance_letters(scene)
    empty.instance_collection = bpy.data.collections.new("Nothing")
    with pytest.raises(convert.SceneInputError, match="collection instance 'Sign text' shows no Text, curve or mesh"):
        shell.engrave_operation(scene, depsgraph())


def test_a_plate_modelled_in_mm_in_a_metre_scene_is_refused_within_a_second(scene):
    scene.unit_settings.scale_length = 1.0          # Blender's default: one unit is a metre, the plate 200 m wide
    start = time.monotonic()
    with pytest.raises(convert.SceneInputError) as error:
        shell.engrave_request(scene, depsgraph())
    assert time.monotonic() - start < 1.0
    message = str(error.value)
    assert message.startswith("plate 'Plate' is 200000 x 100000 x 20000 mm at the scene's unit scale of 1 m per unit")
    assert "Scene > Units" in message


def test_a_plate_larger_than_the_machine_but_not_than_any_machine_is_left_to_the_gate(scene):
    """A small engraving on a big board fits the machine: the board is not refused for its size;
    the export gate measures what the program spans (tests/test_batch.py: exit 3, naming the axis)."""
    scene.kezuri.machine.preset = "grbl-router"
    from kezuri.operators import machines
    machines.fill_machine(scene.kezuri.machine, "grbl-router")
    scene.kezuri.machine.travel_x = 150.0
    operation, setup, plate = shell.engrave_operation(scene, depsgraph(), "grbl")
    assert plate.size[0] == pytest.approx(200.0) and setup.machine.travel[0] == pytest.approx(150.0)



@pytest.fixture
def carve_scene(empty_scene):
    assert bpy.ops.kezuri.carve_sample(sample="wave") == {"FINISHED"}
    yield empty_scene
    for name in ("Design source", "Shown design"):
        collection = bpy.data.collections.get(name)
        if collection is not None:
            for obj in list(collection.objects):
                bpy.data.objects.remove(obj)
            bpy.data.collections.remove(collection)


def test_a_design_mesh_shown_through_a_collection_instance_is_read_where_it_is_shown(carve_scene):
    from kezuri.operators import carve
    plain, plain_faces, _ = carve.design_mesh(carve_scene, depsgraph())
    design = carve_scene.kezuri.carve.design
    for collection in list(design.users_collection):
        collection.objects.unlink(design)
    source = bpy.data.collections.new("Design source")
    source.objects.link(design)
    empty = bpy.data.objects.new("Design shown", None)
    empty.instance_type = "COLLECTION"
    empty.instance_collection = source
    empty.location = (0.0, 0.0, -3.0 / 1000 / carve_scene.unit_settings.scale_length)      # 3 mm lower
    shown = bpy.data.collections.new("Shown design")
    carve_scene.collection.children.link(shown)
    shown.objects.link(empty)
    carve_scene.kezuri.carve.design = empty
    vertices, faces, _ = carve.design_mesh(carve_scene, depsgraph())
    assert np.array_equal(faces, plain_faces)
    assert np.abs(vertices - (plain - [0.0, 0.0, 3.0])).max() < 1e-4


def test_a_design_far_larger_than_any_machine_is_refused_before_planning(carve_scene):
    from kezuri.operators import carve
    carve_scene.unit_settings.scale_length = 1.0          # the 120 mm wave read as 120 m
    start = time.monotonic()
    with pytest.raises(convert.SceneInputError) as error:
        carve.carve_request(carve_scene, depsgraph())
    assert time.monotonic() - start < 1.0
    assert str(error.value).startswith(f"design {carve_scene.kezuri.carve.design.name!r} is 120000 x 80000 x ")
    assert "at the scene's unit scale of 1 m per unit, larger than the 1270 mm X travel" in str(error.value)
