"""The post registry and the workflow table: one place for each thing.

A post class defined here, in the test, must show up everywhere a user picks a post (the
panel's enums, the preferences, batch's --post choices, export file names) without an edit to
any other file; and every list of posts in the shell must be the registry's."""
import importlib.util
import os

import pytest

from kezuri import post
from kezuri.post import registry
from kezuri.post.linuxcnc import LinuxCNCPost

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture
def throwaway_post():
    class ThrowawayPost(LinuxCNCPost):
        name = "throwaway-mill"
        choice = "throwaway"
        label = "Throwaway Mill"
        label_ja = "使い捨てフライス"
        description = "A post that exists only in this test"
        family = "milling"
        extension = ".tap"
        order = 99
    yield ThrowawayPost
    registry.unregister(ThrowawayPost)


def load_batch():
    spec = importlib.util.spec_from_file_location("kezuri_batch_for_test", os.path.join(ROOT, "batch.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_every_post_file_declares_itself():
    families = {cls.name: cls.family for cls in post.posts()}
    assert families == {"fanuc": "milling", "fanuc-macro": "milling", "linuxcnc": "milling", "grbl": "milling",
                        "linuxcnc-cxz": "cxz", "fanuc-cxz": "cxz", "turnmill-xzc": "xzc",
                        "turnmill-linuxcnc": "xzc", "cldata": "cldata", "amada-04p": "punch"}
    for cls in post.posts():
        assert cls.label and cls.description and cls.extension.startswith(".")
        assert cls.label_ja and cls.description_ja, f"{cls.name}: Japanese label and description"
    assert post.choices("milling") == ["fanuc", "fanuc-macro", "linuxcnc", "grbl"]
    assert post.choices("milling", texture=False) == ["fanuc", "linuxcnc", "grbl"]
    assert post.choices("cxz") == ["linuxcnc", "fanuc"]
    assert post.choices(("xzc", "cldata")) == ["xzc", "linuxcnc", "cldata"]
    # The CL data file is .cls everywhere (the shell once called it .cl).
    assert post.extension(("xzc", "cldata"), "cldata") == ".cls"


def test_a_post_class_is_all_it_takes(throwaway_post):
    assert post.choices("milling")[-1] == "throwaway"
    assert post.find("milling", "throwaway") is throwaway_post
    assert post.find("milling", "throwaway-mill") is throwaway_post
    assert isinstance(post.milling_post("throwaway", "G55"), throwaway_post)
    assert "throwaway" not in post.choices("cxz")
    batch = load_batch()
    args = batch.parser().parse_args(["engrave", "--post", "throwaway", "--out", "x"])
    assert args.post == "throwaway"
    args = batch.parser().parse_args(["stepnc", "--post", "throwaway", "--out", "x"])
    assert args.post == "throwaway"
    with pytest.raises(SystemExit):
        batch.parser().parse_args(["rotary", "--post", "throwaway", "--out", "x"])


def test_registering_twice_or_without_a_family_is_refused():
    with pytest.raises(TypeError, match="already registered"):
        type("Again", (LinuxCNCPost,), {"name": "linuxcnc2", "choice": "linuxcnc", "label": "Again",
                                        "family": "milling"})
    with pytest.raises(TypeError, match="a known family"):
        type("Lost", (LinuxCNCPost,), {"name": "lost", "label": "Lost", "family": "laser"})
    with pytest.raises(post.PostError, match="unknown post 'heidenhain'; choose one of fanuc, fanuc-macro"):
        post.milling_post("heidenhain")


def test_enum_numbers_are_stable_and_distinct():
    numbers = [registry.enum_number(registry.key_of(cls)) for cls in post.posts("milling")]
    assert len(set(numbers)) == len(numbers) and 0 not in numbers
    assert registry.enum_number("fanuc") == registry.enum_number("fanuc")


bpy = pytest.importorskip("bpy")


def test_the_panel_enums_and_file_names_follow_the_registry(empty_scene, throwaway_post):
    from kezuri.operators import engrave, preferences, stepnc, turnmill
    machine = empty_scene.kezuri.machine
    machine.post = "throwaway"                       # refused by Blender if the enum did not list it
    assert machine.post == "throwaway"
    assert preferences.scene_post(empty_scene) == "throwaway"
    assert engrave.extension_for("throwaway") == ".tap"
    assert stepnc.extension_for("throwaway") == ".tap"
    assert turnmill.extension_for("cldata") == ".cls"
    with pytest.raises(TypeError):
        empty_scene.kezuri.rotary.post = "throwaway"
    empty_scene.kezuri.rotary.post = "fanuc"
    assert empty_scene.kezuri.rotary.post == "fanuc"
    machine.post = "DEFAULT"
    assert preferences.scene_post(empty_scene) == "fanuc"
    labels = {item.identifier: item.name for item in machine.bl_rna.properties["post"].enum_items}
    if labels:     # Blender lists a dynamic enum's items here only in some versions
        assert labels["throwaway"] == "Throwaway Mill"


def test_post_labels_are_translated():
    from kezuri.operators import translations
    ja = translations.TRANSLATIONS["ja_JP"]
    for cls in post.posts():
        assert ja[("*", cls.label)] == cls.label_ja
        assert ja[("*", cls.description)] == cls.description_ja


def test_the_workflow_table_drives_batch_and_simulate():
    from kezuri.operators import simulate, workflows
    batch = load_batch()
    names = list(batch.commands())
    assert names == ["engrave", "rotary", "stepnc", "turnmill", "unfold", "elbow", "carve", "simulate", "job",
                     "profile", "pocket", "drill", "chamfer", "vcarve"]
    assert [w.key for w in workflows.simulated()] == ["ENGRAVE", "ROTARY", "STEPNC", "TURNMILL", "CARVE"]
    assert [item[0] for item in simulate._ITEMS] == ["ENGRAVE", "ROTARY", "STEPNC", "TURNMILL", "CARVE"]
    for workflow in workflows.WORKFLOWS:
        for family in workflow.post_families:
            assert family in post.FAMILIES
