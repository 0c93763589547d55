"""The steep-region cleanup in Blender and batch: the panel's setting, Generate on the ridge
sample, and ``batch.py carve --sample ridge`` reporting the scallop before and after it."""
import json
import math

import pytest

bpy = pytest.importorskip("bpy")

import rs274  # noqa: E402
from kezuri.operators import carve as shell  # noqa: E402
from kezuri.operators import panels  # noqa: E402
from blender_helpers import draw_panel, run_batch  # noqa: E402


def test_the_setting_is_on_the_panel_and_reaches_the_core(empty_scene):
    assert bpy.ops.kezuri.carve_sample(sample="ridge") == {"FINISHED"}
    props = empty_scene.kezuri.carve
    assert props.steep_cleanup is True          # on by default: the scallop asked for holds everywhere
    assert "steep_cleanup" in draw_panel(panels.KEZURI_PT_carve_settings, bpy.context).props
    props.steep_cleanup = False
    assert shell.settings_from(props).steep_cleanup is False
    props.steep_cleanup, props.max_slope, props.scallop, props.rough = True, 30.0, 0.05, False
    assert bpy.ops.kezuri.carve_generate() == {"FINISHED"}
    assert "Kezuri Carve steep cleanup" in {o.name for o in bpy.data.collections["Kezuri"].objects}


def test_batch_reports_the_scallop_before_and_after(tmp_path):
    done = run_batch("carve", "--sample", "ridge", "--max-slope", "30", "--scallop", "0.04", "--post", "linuxcnc",
                     "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((tmp_path / "report.json").read_text())
    assert [(op["name"], op["tool_kind"]) for op in report["operations"]] == [
        ("roughing", "flat"), ("finishing", "ball"), ("steep cleanup", "ball")]
    assert report["simulation"]["gouges"] == [] and report["simulation"]["rapid_collisions"] == []
    steep = report["steep_cleanup"]
    # the raster alone: passes d apart across a 55-degree slope stand d / cos 55 apart on it; where
    # that slope bends convexly (the crest, radius 6 mm) the scallop grows to s^2 (1/r + 1/rho) / 8
    r, d = 1.5, report["stepover_mm"]
    s = d / math.cos(math.radians(55))
    assert 0.04 < steep["max_scallop_before_mm"] <= s * s * (1 / r + 1 / 6.0) / 8
    assert steep["max_scallop_after_mm"] <= 0.04
    assert steep["max_scallop_after_mm"] == report["scallop"]["max_scallop_mm"]
    assert steep["on"] is True and steep["max_slope_deg"] == 30 and steep["steep_area_mm2"] > 1000
    if rs274.available():
        rs274.run((tmp_path / "carve.ngc").read_text())
    off = run_batch("carve", "--sample", "ridge", "--max-slope", "30", "--scallop", "0.04", "--no-steep-cleanup",
                    "--out", str(tmp_path / "off"))
    assert off.returncode == 0, off.stderr[-3000:]
    report = json.loads((tmp_path / "off" / "report.json").read_text())
    assert [op["name"] for op in report["operations"]] == ["roughing", "finishing"]
    assert report["scallop"]["max_scallop_mm"] == pytest.approx(steep["max_scallop_before_mm"], abs=1e-5)
    assert report["warnings"] and "55 degrees" in report["warnings"][0]


def test_a_bad_max_slope_is_refused_by_name(tmp_path):
    bad = run_batch("carve", "--sample", "ridge", "--max-slope", "95", "--out", str(tmp_path))
    assert bad.returncode == 2 and "max-slope" in bad.stderr and "89" in bad.stderr
    assert not any(tmp_path.iterdir())
