"""``batch.py profile|pocket|drill|chamfer --svg FILE`` (or ``--dxf``): a router operation on a
drawing in one command, run in-process as a user runs it. The drawings are written here in the
conventions of Inkscape (an SVG in mm with a viewBox) and of a laser shop's R12 DXF; the programs
are read back by rs274 and the rules reader, the pocket's removed volume checked against its
closed form."""
import json
import math
import os

import numpy as np
import pytest

pytest.importorskip("bpy")
import controller_rules  # noqa: E402
import rs274  # noqa: E402
from test_batch_job import run  # noqa: E402

SVG = """<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" width="120mm" height="80mm" viewBox="0 0 120 80">
  <rect x="10" y="10" width="100" height="60" rx="5" fill="none" stroke="#000"/>
  <circle cx="30" cy="40" r="6" fill="none" stroke="#000"/>
  <circle cx="90" cy="40" r="6" fill="none" stroke="#000"/>
</svg>
"""
# a 100 x 60 rounded rectangle (r 5) with two 12 mm holes: its area, the pocket's floor
AREA = 100 * 60 - (4 - math.pi) * 25 - 2 * math.pi * 36


def dxf_r12(entities: list) -> str:
    body = "".join(entities)
    return f"0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n{body}0\nENDSEC\n0\nEOF\n"


def circle(x, y, r, layer="HOLES"):
    return f"0\nCIRCLE\n8\n{layer}\n10\n{x}\n20\n{y}\n30\n0.0\n40\n{r}\n"


@pytest.fixture
def drawing(tmp_path):
    path = tmp_path / "plate.svg"
    path.write_text(SVG, encoding="utf-8")
    return str(path)


@pytest.mark.parametrize("kind, options", [("profile", ("--set", "lead=none")), ("pocket", ()), ("drill", ()),
                                           ("chamfer", ())])
def test_each_shorthand_writes_a_clean_program(drawing, kind, options):
    status, message, out = run(kind, "--svg", drawing, "--post", "linuxcnc", *options)
    assert status == 0, message[-2000:]
    report = json.loads(open(os.path.join(out, "report.json")).read())
    assert report["workflow"] == kind and report["gate"]["findings"] == []
    text = open(report["files"][0]).read()
    assert controller_rules.check(text, "linuxcnc") == []
    if rs274.available():
        kinds, points, _ = rs274.motion_endpoints(rs274.run(text, tools=(4, 5, 6, 7)))
        assert len(points) > 3 and points[:, 2].min() < 0
    assert "[setup]\nname = \"" + kind in report["job_file_text"]


def test_the_pocket_clears_the_drawing_to_its_closed_form_volume(drawing):
    status, message, out = run("pocket", "--svg", drawing, "--post", "linuxcnc", "--set", "depth=4")
    assert status == 0, message[-2000:]
    removed = json.loads(open(os.path.join(out, "report.json")).read())["simulation"]["removed_volume_mm3"]
    assert removed == pytest.approx(AREA * 4, rel=0.002)       # 0.1 mm cells along 340 mm of wall


def test_the_drill_finds_the_circles_of_a_laser_shops_dxf(tmp_path):
    path = tmp_path / "holes.dxf"
    path.write_text(dxf_r12([circle(20, 20, 2.5), circle(80, 20, 2.5), circle(50, 60, 2.5)]), encoding="utf-8")
    status, message, out = run("drill", "--dxf", str(path), "--post", "linuxcnc", "--set", "depth=6")
    assert status == 0, message[-2000:]
    text = open(os.path.join(out, "drill.ngc")).read()
    # work zero at the board's front-left corner, 10 mm round the drawing: the holes at +10 - 17.5
    assert rs274.available()
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text, tools=(4,)))
    bottoms = {(round(x, 3), round(y, 3)) for x, y, z in points if abs(z + 6.0) < 1e-6}
    assert bottoms == {(12.5, 12.5), (72.5, 12.5), (42.5, 52.5)}


def test_bad_shorthands_are_refused_by_name(drawing, tmp_path):
    two = tmp_path / "two.dxf"
    two.write_text(dxf_r12([circle(20, 20, 2.5, "A"), circle(80, 20, 2.5, "B")]), encoding="utf-8")
    for argv, words in ((("pocket", "--svg", str(tmp_path / "none.svg")), "none.svg"),
                        (("drill", "--dxf", str(two)), "pick one with --layer"),
                        (("pocket", "--svg", drawing, "--set", "depht=3"), "depht"),
                        (("pocket", "--svg", drawing, "--set", "nonsense"), "give KEY=VALUE"),
                        (("profile", "--svg", drawing, "--thickness", "0"), "--thickness"),
                        (("pocket",), "no design: give --svg FILE or --dxf FILE")):
        status, message, out = run(*argv)
        assert status == 2, (argv, message[-1500:])
        assert words in message and "Traceback" not in message, message[-1500:]
        assert not os.path.exists(out)
    status, message, out = run("drill", "--dxf", str(two), "--layer", "B", "--post", "linuxcnc")
    assert status == 0, message[-1500:]
