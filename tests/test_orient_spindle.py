"""Machine & Stock's "Orient Spindle (M19)" (batch: --orient-spindle): the Fanuc posts write M19
between cancelling the length offset and the tool change, for every change; a post without M19
refuses it by name instead of writing a program without it.  The programs are read back by the
independent controller-rules checker (tests/controller_rules.py), not by the post."""
import os
import re

import pytest

bpy = pytest.importorskip("bpy")
import controller_rules as rules  # noqa: E402
from test_hostile_batch import run  # noqa: E402  (batch's entry point in-process, with a time limit)

from kezuri.operators import samples, translations  # noqa: E402


def changes(text: str) -> list:
    """The block before each tool change (M06), in order."""
    lines = text.splitlines()
    return [lines[i - 1] for i, line in enumerate(lines) if re.search(r"\bM0?6\b", line)]


@pytest.mark.parametrize("command, post, family", [("engrave", "fanuc", "fanuc-mill"),
                                                   ("stepnc", "fanuc", "fanuc-mill")])
def test_batch_writes_m19_before_every_tool_change(command, post, family, tmp_path):
    status, message, written = run(command, "--post", post, "--orient-spindle")
    assert status == 0, message[-2000:]
    nc = [path for path in written if path.endswith(".nc")]
    assert len(nc) == 1, written
    text = open(nc[0]).read()
    before = changes(text)
    assert before and all(line == "M19" for line in before), before
    assert text.count("M19") == len(before)
    assert rules.check(text, family) == []
    # and without the option, not one M19
    status, message, written = run(command, "--post", post)
    assert status == 0 and "M19" not in open([p for p in written if p.endswith(".nc")][0]).read()


def test_a_post_without_m19_refuses_the_check_box_in_the_panel(empty_scene, tmp_path):
    scene = empty_scene
    samples.name_plate(scene)
    scene.kezuri.machine.orient_spindle = True
    path = str(tmp_path / "plate.ngc")
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    with pytest.raises(RuntimeError, match=r"Orient Spindle \(M19\): the linuxcnc post does not write M19"):
        bpy.ops.kezuri.engrave_export(filepath=path, post="linuxcnc")
    assert not os.path.exists(path)
    assert bpy.ops.kezuri.engrave_export(filepath=path, post="fanuc") == {"FINISHED"}
    text = open(path).read()
    assert changes(text) and set(changes(text)) == {"M19"}
    japanese = translations.japanese_message("Orient Spindle (M19): the linuxcnc post does not write M19 before a "
                                             "tool change; pick a Fanuc post or switch it off")
    assert japanese is not None and "linuxcnc" in japanese and "M19" in japanese
