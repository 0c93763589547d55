"""The inlay sample (samples/jobs/inlay-female.toml and inlay-male.toml, one heart from
samples/jobs/inlay-heart.svg, 40 x 34 mm, centred on the work zero): both halves written by
``batch.py job`` through the gate and the controller rules, and their planned depths against the
closed forms the job files and README give (60 deg V-bit, start depth 2 mm, glue gap 0.1 mm,
pocket floor 3 mm, plug 4 mm high)."""
import contextlib
import io
import json
import math
import os

import numpy as np
import pytest

pytest.importorskip("bpy")

import controller_rules  # noqa: E402
from blender_helpers import empty_scene  # noqa: E402,F401  (fixture)
from test_hostile_batch import BATCH  # noqa: E402

JOBS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "samples", "jobs")
TAN = math.tan(math.radians(30.0))


def planned(name):
    from kezuri.operators import jobfile

    job, _, _, _ = jobfile.plan_file(os.path.join(JOBS, f"inlay-{name}.toml"))
    (item,) = job.planned
    return [np.asarray(op.xyz)[np.asarray(op.kind) != 0] for op in item.part.operations], item


def test_the_pocket_has_its_floor_at_3_mm_and_the_v_bit_on_the_outline_offset_by_3_tan_30(empty_scene):
    (clearing, vbit), item = planned("female")
    assert clearing[:, 2].min() == pytest.approx(-3.0, abs=1e-9) and vbit[:, 2].min() == pytest.approx(-3.0, abs=1e-9)
    # the heart's point at the bottom (X0 Y-17): the V-bit comes out to it at the top, Z 0
    tip = np.hypot(vbit[:, 0], vbit[:, 1] + 17.0)
    assert tip.min() < 0.01 and vbit[np.argmin(tip), 2] == pytest.approx(0.0, abs=0.01)
    # the heart's widest (X +-20 at the lobes): the V-bit's path at the floor 3 tan 30 = 1.732 mm in
    floor = vbit[np.abs(vbit[:, 2] + 3.0) < 1e-9]
    assert np.abs(floor[:, 0]).max() == pytest.approx(20.0 - 3.0 * TAN, abs=0.02)
    assert item.part.stock.z1 - item.part.stock.z0 == pytest.approx(18.0)


def test_the_plug_starts_at_2_2_mm_and_its_waste_is_cleared_at_4_mm(empty_scene):
    (clearing, vbit), _ = planned("male")
    shift = 2.0 + 0.1 / math.sin(math.radians(30.0))
    assert shift == pytest.approx(2.2)
    margin = 2 * 4.0 * TAN + 2.0
    assert margin == pytest.approx(6.6188, abs=1e-4)
    assert clearing[:, 2].min() == pytest.approx(-4.0, abs=1e-9) and vbit[:, 2].min() == pytest.approx(-4.0, abs=1e-9)
    for corner in ((-20.0 - margin, -17.0 - margin), (20.0 + margin, 17.0 + margin)):     # the waste box's
        distance = np.hypot(vbit[:, 0] - corner[0], vbit[:, 1] - corner[1])
        assert distance.min() < 0.02 and vbit[np.argmin(distance), 2] == pytest.approx(-shift, abs=1e-3)
    # the heart's notch (X0 Y10, mirrored onto itself): a sharp corner of the waste, which the tip
    # runs out to at its start depth, 2.2 mm
    point = np.hypot(vbit[:, 0], vbit[:, 1] - 10.0)
    assert point.min() < 0.02 and vbit[np.argmin(point), 2] == pytest.approx(-shift, abs=0.01)


@pytest.mark.parametrize("name", ["female", "male"])
def test_both_halves_pass_the_gate_and_the_rules(empty_scene, tmp_path, name):
    out = tmp_path / name
    with contextlib.redirect_stderr(io.StringIO()) as err, contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(["batch.py", "job", os.path.join(JOBS, f"inlay-{name}.toml"), "--out", str(out)])
        except SystemExit as exit_:
            status = exit_.code
    assert status == 0, err.getvalue()[-2000:]
    report = json.loads((out / "report.json").read_text())
    assert report["gate"]["findings"] == []
    assert report["tools"][:2] and [op["kind"] for op in report["job_operations"]] == ["vcarve"]
    assert controller_rules.check(open(report["files"][0]).read(), "linuxcnc") == []
