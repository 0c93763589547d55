"""The AP238 integrated form (ISO 10303-238 AIM) read like its ISO 14649 rendition.

``fixtures/iso14649/ex1_ap238.stp`` is our own AP238 rendition of NIST's ``ex1.stp`` (ISO 14649-11
example 1), laid out as ISO 10303-238 Annex J lays out its AIM examples: MACHINING_PROJECT,
MACHINING_WORKPLAN with MACHINING_PROCESS_SEQUENCE_RELATIONSHIPs, MACHINING_WORKINGSTEPs with
ACTION_PROPERTY 'security plane', operations with ACTION_PROPERTYs, features as SHAPE_ASPECT complex
instances with feature components.  Both files must give the same NC, byte for byte; the geometry is
checked against numbers read from the AP238 text with regular expressions.
"""
import os
import random
import re

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.toolpath.ir.program import FEED
from kezuri.toolpath.simulate import blocking, simulate
from kezuri.toolpath.ir.errors import InputError
from kezuri.toolpath.operations.stepnc.errors import StepNcError
from kezuri.toolpath.operations.stepnc.solids import fixture_clearance, stock_box
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program
from test_hostile import time_limit

FIXTURES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fixtures", "iso14649")
ARM = os.path.join(FIXTURES, "ex1.stp")
AIM = os.path.join(FIXTURES, "ex1_ap238.stp")


def aim_text() -> str:
    with open(AIM, encoding="utf-8") as stream:
        return stream.read()


def point(text, name):
    found = re.search(rf"CARTESIAN_POINT\('{re.escape(name)}',\(([-\d.,]+)\)\)", text)
    return np.array([float(v) for v in found.group(1).split(",")])


def length_item(text, name):
    return float(re.search(rf"LENGTH_MEASURE\(([-\d.]+)\),#\d+\)(?:QUALIFIED_REPRESENTATION_ITEM\([^)]*\)\))?"
                           rf"REPRESENTATION_ITEM\('{name}'\)", text).group(1))


@pytest.fixture(scope="module")
def both():
    arm, aim = load_workplan(ARM), load_workplan(AIM)
    return arm, aim, to_program(arm), to_program(aim)


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc", "grbl"])
def test_the_ap238_rendition_gives_the_same_nc_byte_for_byte(both, dialect):
    arm, aim, arm_program, aim_program = both
    assert post.milling_post(dialect).to_text(aim_program) == post.milling_post(dialect).to_text(arm_program)


def test_the_same_workplan_features_and_operations(both):
    arm, aim, _, _ = both
    assert aim.warnings == arm.warnings == ()
    assert [s.id for s in aim.workingsteps] == [s.id for s in arm.workingsteps] == [10, 11, 12, 13, 14]
    for a, b in zip(arm.workingsteps, aim.workingsteps):
        assert (a.its_id, a.its_operation.type_name, a.its_operation.its_id) == \
            (b.its_id, b.its_operation.type_name, b.its_operation.its_id)
        assert a.its_secplane.position.location == b.its_secplane.position.location
        assert a.its_feature.top_z == b.its_feature.top_z and a.its_feature.bottom_z == b.its_feature.bottom_z
        assert a.its_operation.its_technology.feed_mm_min == b.its_operation.its_technology.feed_mm_min
        assert a.its_operation.its_technology.spindle == b.its_operation.its_technology.spindle
        assert a.its_operation.its_tool.its_tool_body.dimension.diameter == \
            b.its_operation.its_tool.its_tool_body.dimension.diameter
        assert a.its_operation.its_machining_strategy == b.its_operation.its_machining_strategy
    assert np.allclose(arm.workingsteps[3].its_feature.outline(), aim.workingsteps[3].its_feature.outline())
    assert np.allclose(arm.workingsteps[0].its_feature.corners(), aim.workingsteps[0].its_feature.corners())


def test_the_geometry_is_where_the_ap238_file_puts_it(both):
    text = aim_text()
    _, _, _, program = both
    # pocket: centre (70, 70), 'length' along its ref_direction (0, 1, 0), 'width' across, 30 deep
    centre = point(text, "POCKET1: LOCATION ")[:2]
    length, width = length_item(text, "length"), length_item(text, "width")
    depth = -point(text, "POCKET1: DEPTH ")[2]
    radius = length_item(text, "effective cutting diameter") / 2          # the first tool body: MILL 18MM
    finish = program.operations[4]
    floor = finish.xyz[(finish.kind == FEED) & np.isclose(finish.xyz[:, 2], -depth)]
    assert floor[:, 0].min() == pytest.approx(centre[0] - width / 2 + radius, abs=1e-6)
    assert floor[:, 0].max() == pytest.approx(centre[0] + width / 2 - radius, abs=1e-6)
    assert floor[:, 1].min() == pytest.approx(centre[1] - length / 2 + radius, abs=1e-6)
    assert floor[:, 1].max() == pytest.approx(centre[1] + length / 2 - radius, abs=1e-6)
    # hole: drilled at its location only
    hole = point(text, "HOLE1: LOCATION ")[:2]
    drill = program.operations[1]
    assert np.allclose(drill.xyz[drill.kind == FEED][:, :2], hole)
    # planar face: its floor is the placement's z plus the depth plane's z
    face = program.operations[0]
    cuts = face.xyz[face.kind == FEED]
    assert cuts[:, 2].min() == pytest.approx(point(text, "PLANAR FACE1:LOCATION ")[2]
                                             + point(text, "PLANAR FACE1:DEPTH ")[2])


def test_the_ap238_program_passes_the_simulation(both):
    _, aim, _, program = both
    result = simulate(program, stock_box(aim, program), cell=1.0, fixture_clearance=fixture_clearance(aim))
    assert blocking(result.findings) == []
    assert result.removed_volume_mm3 > 0


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")
def test_rs274_accepts_the_ap238_program(both):
    _, _, _, program = both
    kinds, points, _ = rs274.motion_endpoints(rs274.run(post.milling_post("linuxcnc").to_text(program)))
    feeds = points[np.array(kinds) == "feed"]
    assert feeds[:, 2].min() == pytest.approx(-38.009, abs=1e-3)     # the drill through the 30 mm hole


def test_an_unsupported_feature_skips_its_workingsteps_with_the_reason():
    text = aim_text().replace("INSTANCED_FEATURE()ROUND_HOLE()SHAPE_ASPECT", "INSTANCED_FEATURE()"
                              "COUNTERBORE_HOLE()SHAPE_ASPECT")
    loaded = load_workplan(text)
    assert [s.id for s in loaded.workingsteps] == [10, 13, 14]
    assert any(w.startswith("workingstep #11 'WS DRILL HOLE1' skipped: COUNTERBORE_HOLE #17 is not supported")
               for w in loaded.warnings)
    unknown = load_workplan(aim_text().replace("('','contour parallel','','');\n#5101",
                                               "('','contour spiral','','');\n#5101"))
    assert any("'WS ROUGH POCKET1' skipped: CONTOUR_SPIRAL #51 is not supported" in w for w in unknown.warnings)


def test_units_of_the_file_are_honoured():
    # the pocket's sizes in metres and the feed in millimetre per minute: the same program
    text = aim_text()
    text = text.replace("LENGTH_MEASURE(80.000),#900)QUALIFIED", "LENGTH_MEASURE(0.080),#908)QUALIFIED")
    text = text.replace("NUMERIC_MEASURE(0.040),#909)", "NUMERIC_MEASURE(2400.),#930)")
    text = text.replace("#923=PRODUCT_DEFINITION_SHAPE", "#930=DERIVED_UNIT((#931,#932));\n"
                        "#931=DERIVED_UNIT_ELEMENT(#900,1.);\n#932=DERIVED_UNIT_ELEMENT(#933,-1.);\n"
                        "#933=(CONVERSION_BASED_UNIT('minute',#934)NAMED_UNIT(#905)TIME_UNIT());\n"
                        "#934=TIME_MEASURE_WITH_UNIT(TIME_MEASURE(60.),#907);\n#923=PRODUCT_DEFINITION_SHAPE")
    loaded = load_workplan(text)
    assert loaded.workingsteps[3].its_feature.feature_boundary.profile_length == pytest.approx(80.0)
    assert loaded.workingsteps[0].its_operation.its_technology.feed_mm_min == pytest.approx(2400.0)


def test_malformed_ap238_files_are_named():
    with pytest.raises(StepNcError, match="exactly one MACHINING_PROJECT, this one has 2"):
        load_workplan(aim_text().replace("#1=MACHINING_PROJECT('EXECUTE EXAMPLE1','',$,(#919));",
                                         "#1=MACHINING_PROJECT('EXECUTE EXAMPLE1','',$,(#919));\n"
                                         "#9=MACHINING_PROJECT('TWO','',$,(#919));"))
    with pytest.raises(StepNcError, match=r"#12 MACHINING_WORKINGSTEP 'WS REAM HOLE1': no 'security plane'"):
        load_workplan(aim_text().replace("#1206=ACTION_PROPERTY('security plane'", "#1206=ACTION_PROPERTY('x'"))
    with pytest.raises(StepNcError, match=r"#18 POCKET 'POCKET1': no boundary"):
        load_workplan(aim_text().replace("'boundary occurrence'", "'edge occurrence'"))


def test_broken_ap238_files_never_give_a_traceback():
    """Instances dropped, attributes cut off, references unset, numbers turned to strings: a named
    error or a program, never another exception (seeded, so the same 150 files every run)."""
    lines = aim_text().splitlines()
    data = [i for i, line in enumerate(lines) if re.match(r"^#\d+=", line)]
    rng = random.Random(19)
    with time_limit(240):
        for _ in range(150):
            broken = list(lines)
            for _ in range(rng.randint(1, 3)):
                i = rng.choice(data)
                head, body = broken[i].split("=", 1)
                kind = rng.randrange(4)
                if kind == 0:
                    broken[i] = ""
                elif kind == 1:
                    broken[i] = re.sub(r",[^,()]*\);$", ");", broken[i])
                elif kind == 2 and re.findall(r"#\d+", body):
                    broken[i] = head + "=" + body.replace(rng.choice(re.findall(r"#\d+", body)), "$", 1)
                else:
                    broken[i] = re.sub(r"\(([-\d.]+)\)", "('x')", broken[i], count=1)
            try:
                to_program(load_workplan("\n".join(broken)))
            except InputError:
                pass
