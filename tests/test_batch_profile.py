"""The sample job samples/jobs/nameplate-cut-out.toml (engrave + drill + profile with tabs) through
``batch.py job`` in-process: the gate passes, LinuxCNC's rs274 reads the program and finds the cut
through at -20.3 mm and the tabs' tops at -17 mm where the file put them, the controller-rules
reader finds nothing; job files with bad profile settings are refused by name."""
import json
import os
import re

import numpy as np
import pytest

pytest.importorskip("bpy")
import controller_rules  # noqa: E402
import rs274  # noqa: E402
from test_batch_job import JOBS, run  # noqa: E402


@pytest.fixture(scope="module")
def cut_out():
    status, message, out = run("job", os.path.join(JOBS, "nameplate-cut-out.toml"))
    assert status == 0, message[-2000:]
    return out


def test_the_cut_out_job_passes_the_gate_with_its_four_tools(cut_out):
    report = json.loads(open(os.path.join(cut_out, "report.json")).read())
    assert [op["name"] for op in report["job_operations"]] == ["texture and letters", "mounting holes", "cut out"]
    assert report["gate"]["findings"] == [] and not report["gate"]["overridden"]
    assert report["warnings"] == []          # four tabs: the part does not come loose
    text = open(report["files"][0]).read()
    assert re.findall(r"^T(\d+) M0?6", text, re.M) == ["2", "3", "2", "4", "5"]
    assert controller_rules.check(text, "linuxcnc") == []
    cut = [op for op in report["operations"] if op["name"] == "cut out"][0]
    assert cut["min_feed_z_mm"] == pytest.approx(-20.3)


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")
def test_rs274_reads_the_cut_through_and_the_tabs_where_the_file_put_them(cut_out):
    text = open(os.path.join(cut_out, "nameplate-cut-out.ngc")).read()
    start = text.index("T5 M6") if "T5 M6" in text else text.index("T5 M06")
    kinds, points, _ = rs274.motion_endpoints(rs274.run("G21 G90 G17\n" + text[start:], tools=(5,)))
    assert points[:, 2].min() == pytest.approx(-20.3)
    tops = points[np.isclose(points[:, 2], -17.0)]            # 20 mm board, tabs 3 mm high
    for x, y in ((0.0, -45.0), (0.0, 45.0), (-95.0, 0.0), (95.0, 0.0)):
        # the tool centre runs 3 mm (a radius) outside the outline over each tab
        near = np.hypot(tops[:, 0] - x, tops[:, 1] - y)
        assert near.min() < 8.0, (x, y)
    deep = points[points[:, 2] < -17.0 - 1e-6]
    for x, y in ((0.0, -48.0), (0.0, 48.0), (-98.0, 0.0), (98.0, 0.0)):
        assert np.hypot(deep[:, 0] - x, deep[:, 1] - y).min() > 4.0 + 3.0 - 1e-3   # nothing cut under a tab


@pytest.mark.parametrize("table, words", [
    ('objects = { shape = "Outline" }\nsettings = { step_down = 0 }', "step_down must be more than 0"),
    ('objects = { shape = "Outline" }\nsettings = { depth = -3.0 }', "depth must be more than 0"),
    ('objects = { shape = "Outline" }\nsettings = { tab_count = 2, tab_width = 900.0 }', "tab_width"),
    ('objects = { shape = "Outline" }\nsettings = { side = "inside", diameter = 120.0, flute_length = 30.0 }',
     "does not fit inside every contour of object 'Outline'"),
    ('objects = { shape = "Outline" }\nsettings = { speed = 3 }', "settings.speed is not a profile setting"),
    ('objects = { shape = "Outline" }\ntabs = [[0.0]]', r"tabs\[0\] = \[0.0\] is not an \[x, y\] point"),
    ('outline = "Outline"', 'the only outline a profile takes by name is "plate"'),    # no shape: the plate's
])
def test_bad_profile_entries_are_refused_by_name(tmp_path, table, words):
    job = tmp_path / "bad.toml"
    job.write_text('[setup]\nsample = "name_plate_cut_out"\npost = "linuxcnc"\n\n'
                   f'[[operations]]\nkind = "profile"\nname = "cut out"\n{table}\n', encoding="utf-8")
    status, message, out = run("job", str(job))
    assert status != 0
    assert re.search(words, message), message[-800:]
    assert message.startswith("kezuri: ")
    assert "Traceback" not in message
    assert not os.path.exists(os.path.join(out, "bad.ngc"))


def test_the_whole_job_simulated_cuts_no_plunge_of_the_end_mill_and_keeps_the_part(cut_out):
    """The job planned as batch plans it, cut on the height field with the 6 mm end mill (T5) told
    it cannot plunge: no finding; inside the outline (8 mm round corners, 190 x 90 mm) the plate
    keeps its full thickness where nothing but the profile could reach it (within 1 mm of the
    outline), and the kerf beside it is cut through but at the four tabs.  (``cut_out``: batch has
    registered the add-on.)"""
    from kezuri.operators import jobfile
    from kezuri.toolpath import simulate as sim

    planned, _, _, _ = jobfile.plan_file(os.path.join(JOBS, "nameplate-cut-out.toml"))
    program, stock, limits = planned.simulation()
    result = sim.simulate(program, stock, cell=0.2, no_plunge_tools=(5,), **limits)
    assert result.findings == []
    hf = result.heightfield
    gx, gy = np.meshgrid(hf.x(), hf.y(), indexing="ij")
    qx, qy = np.maximum(np.abs(gx) - 87.0, 0.0), np.maximum(np.abs(gy) - 37.0, 0.0)
    inside = (np.abs(gx) <= 87.0) | (np.abs(gy) <= 37.0)
    distance = np.where((np.abs(gx) <= 95.0) & (np.abs(gy) <= 45.0) & inside,
                        np.maximum(np.abs(gx) - 95.0, np.abs(gy) - 45.0), np.hypot(qx, qy) - 8.0)
    material = np.clip(hf.heights, hf.bottom, hf.top)
    edge = (distance < -0.02) & (distance > -1.0)
    assert material[edge].min() > -3.0             # only the engraving's texture (at most 2.8 mm) is there
    kerf = (distance > 0.02) & (distance < 5.9) & (np.abs(gx) < 100.0) & (np.abs(gy) < 50.0)
    through = material[kerf] <= hf.bottom + 1e-6
    assert 0.8 < through.mean() < 1.0              # cut through but at the tabs
