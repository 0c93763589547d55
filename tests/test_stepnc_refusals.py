"""A refusal names the real reason of every workingstep (the entity not supported), never "switched off",
for the entities added for issue 19: the AP238 form, explicit toolpaths, curved slots, the new strategies;
and every warning and note those files give has a Japanese template."""
import os
import re
import subprocess
import sys

import pytest

from kezuri.toolpath.operations.stepnc import nothing_to_machine
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program
from test_stepnc_ap238 import AIM, aim_text
from test_stepnc_contour_bidirectional import TEXT as STRATEGIES
from test_stepnc_floor_clue import pocket_file
from test_stepnc_freeform import freeform_file
from test_stepnc_slot_paths import slot_file

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def every_feature_unsupported() -> str:
    return (aim_text().replace("FLAT_FACE()", "BOSS()").replace("ROUND_HOLE()", "COUNTERBORE_HOLE()")
            .replace("POCKET()", "STEP()"))


def test_the_batch_refusal_lists_every_workingstep_s_entity(tmp_path):
    source = tmp_path / "none.stp"
    source.write_text(every_feature_unsupported(), encoding="utf-8")
    out = tmp_path / "out"
    done = subprocess.run([sys.executable, os.path.join(ROOT, "batch.py"), "stepnc", "--input", str(source),
                           "--out", str(out)], capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert done.returncode == 2, done.stderr[-2000:]
    assert "Traceback" not in done.stderr and "switched off" not in done.stderr
    for step, entity in ((10, "BOSS #16"), (11, "COUNTERBORE_HOLE #17"), (12, "COUNTERBORE_HOLE #17"),
                         (13, "STEP #18"), (14, "STEP #18")):
        assert f"workingstep #{step} " in done.stderr and f"{entity} is not supported" in done.stderr
    assert not out.exists() or not any(out.iterdir())


def test_explicit_toolpaths_refused_name_their_entities():
    loaded = load_workplan(freeform_file(pocket_list="#501", hole_speed="#26"))
    assert loaded.workingsteps == ()
    reason = nothing_to_machine(loaded.warnings)
    assert "workingstep #60 'WS PLUNGE HOLE1' skipped: CUTTER_LOCATION_TRAJECTORY #312 is not supported" in reason
    assert "workingstep #61 'WS MILL POCKET1' skipped: CUTTER_CONTACT_TRAJECTORY #502 is not supported" in reason
    assert "switched off" not in reason


def test_the_new_warnings_and_notes_have_japanese_templates():
    pytest.importorskip("bpy")
    from kezuri.operators import translations

    texts = [every_feature_unsupported(), freeform_file(pocket_list="#501", hole_speed="#26"),
             freeform_file(before="#66,"), slot_file(path3_placement="#44"), pocket_file(),
             aim_text().replace("('','contour parallel','','');\n#5101", "('','contour spiral','','');\n#5101")]
    messages = []
    for text in texts:
        loaded = load_workplan(text)
        messages += list(loaded.warnings)
        if loaded.workingsteps:
            messages += list(to_program(loaded).notes)
        else:
            messages.append(nothing_to_machine(loaded.warnings))
    contour = open(os.path.join(ROOT, "tests", "fixtures", "iso14649", "ex1.stp"), encoding="latin-1").read()
    contour = contour.replace("#42= BIDIRECTIONAL_MILLING(0.05, .T., #43, .LEFT., $);",
                              "#42= CONTOUR_BIDIRECTIONAL(0.05, .T., #43, .LEFT., $, $);")
    messages += list(to_program(load_workplan(contour)).notes)
    messages += list(to_program(load_workplan(STRATEGIES)).notes)
    assert len(messages) >= 12 and os.path.exists(AIM)
    for message in messages:
        japanese = translations.japanese_message(message)
        assert japanese is not None and re.search(r"[\u3040-\u30ff\u4e00-\u9fff]", japanese), message
