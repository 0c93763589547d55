"""Milling posts: every LinuxCNC program goes through LinuxCNC's own rs274 interpreter."""
import os
import re

import numpy as np
import pytest

import rs274
from kezuri import post
from kezuri.post import output
from kezuri.post.gcode import PostError, fmt
from kezuri.toolpath.operations.engrave import engrave
from kezuri.toolpath.ir.program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, Program, Tool
from test_engrave import LETTERS, PLATE

needs_rs274 = pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")


def sample_job():
    return engrave.plan(PLATE, LETTERS)


def expected_endpoints(program: Program, decimals=4):
    """Every move of the IR in order, dropping the ones that round to zero length, as the post does."""
    points, kinds = [], []
    for op in program.operations:
        last = np.round(op.start, decimals)
        for kind, xyz in zip(op.kind, op.xyz):
            p = np.round(xyz, decimals)
            if np.array_equal(p, last):
                continue
            points.append(xyz)
            kinds.append({RAPID: "rapid", FEED: "feed", ARC_CW: "cw", ARC_CCW: "ccw"}[int(kind)])
            last = p
    return kinds, np.array(points)


@needs_rs274
def test_linuxcnc_engraving_passes_rs274_and_matches_the_ir():
    baked, depths = engrave.bake(sample_job().program)
    writer = post.milling_post("linuxcnc")
    text = writer.to_text(baked)
    kinds, points, _ = rs274.motion_endpoints(rs274.run(text))
    # the program as the post writes it: the letters' outlines as arcs (tests/test_arcs_out.py
    # checks them against the polylines), every other move as planned
    written = writer.arcs_out(baked)
    assert sum(int(np.isin(op.kind, (ARC_CW, ARC_CCW)).sum()) for op in written.operations) > 100
    want_kinds, want_points = expected_endpoints(written)
    # rs274 also reports the moves the post adds around each operation (safe Z, the start
    # position): the IR's moves must appear in order, each within 1e-3 mm.
    cutting = [i for i, k in enumerate(kinds) if k != "rapid"]
    want_cutting = [i for i, k in enumerate(want_kinds) if k != "rapid"]
    assert len(cutting) == len(want_cutting)
    assert [kinds[i] for i in cutting] == [want_kinds[i] for i in want_cutting]
    assert np.max(np.abs(points[cutting] - want_points[want_cutting])) < 1e-3
    feed_z = points[cutting][:, 2]
    assert feed_z.min() == pytest.approx(-2.8, abs=1e-3)


@needs_rs274
def test_linuxcnc_arcs_and_helices_pass_rs274():
    # A full circle, a half circle counter-clockwise and a helical quarter.
    xyz = [[10, 0, -1], [10, 0, -1], [-10, 0, -1], [0, 10, -2]]
    kind = [FEED, ARC_CW, ARC_CCW, ARC_CW]
    centre = [[np.nan] * 3, [0, 0, -1], [0, 0, -1], [0, 0, -2]]
    op = Operation("arcs", Tool(1, "flat", 3.0), 10000, kind, xyz, [500] * 4, center=centre,
                   start=[10, 0, 5])
    program = Program("arcs", [op])
    calls = rs274.run(post.milling_post("linuxcnc").to_text(program))
    arcs = [(name, [float(v) for v in args]) for name, args in calls if name == "ARC_FEED"]
    assert len(arcs) == 3
    assert arcs[0][1][:5] == pytest.approx([10, 0, 0, 0, -1])     # full circle, clockwise
    assert arcs[1][1][:5] == pytest.approx([-10, 0, 0, 0, 1])
    assert arcs[2][1][5] == pytest.approx(-2)                      # helical end Z
    # The IR's arc length: 2 pi 10 + pi 10 + quarter helix.
    lengths = op.move_lengths()
    assert lengths[1] == pytest.approx(2 * np.pi * 10)
    assert lengths[2] == pytest.approx(np.pi * 10)
    assert lengths[3] == pytest.approx(np.hypot(np.pi * 5, 1))


def test_same_input_same_bytes_and_no_timestamp():
    job = sample_job()
    for name in post.choices("milling"):
        program = job.program if name == "fanuc-macro" else engrave.bake(job.program)[0]
        a = post.milling_post(name).to_text(program)
        b = post.milling_post(name).to_text(program)
        assert a == b
        assert not re.search(r"20\d\d-\d\d-\d\d|\d\d:\d\d:\d\d", a)


def test_header_names_job_tools_and_cycle_time():
    baked, _ = engrave.bake(sample_job().program)
    text = post.milling_post("fanuc").to_text(baked)
    header = text.split("G21")[0]
    assert "T2 6 MM BALL END MILL" in header and "T3 1 MM FLAT END MILL" in header
    minutes = baked.cycle_time() / 60
    match = re.search(r"ESTIMATED CYCLE TIME: (\d+) MIN (\d+) S", header)
    assert match and int(match.group(1)) + int(match.group(2)) / 60 == pytest.approx(minutes, abs=1 / 60)


def test_fanuc_frame_follows_the_paper():
    baked, _ = engrave.bake(engrave.plan(PLATE, LETTERS, engrave.EngraveSettings(safe_z=100.0)).program)
    lines = post.milling_post("fanuc", "G59").to_text(baked).splitlines()
    assert lines[0] == "%" and lines[1].startswith("O0001") and lines[-1] == "%"
    assert "T02 M06" in lines
    start = next(line for line in lines if line.startswith("G00 G90 G59"))
    assert start.endswith("S6000 M03")
    assert lines[lines.index(start) + 1] == "G43 Z100. H02"
    assert lines[-5:-1] == ["G91 G28 Z0.", "G28 X0. Y0.", "G90", "M30"]
    # Every coordinate carries a decimal point (Fanuc reads X106 as 0.106 mm).
    for word in re.findall(r"\b[XYZIJ]-?[\d.]+", "\n".join(lines)):
        assert "." in word, word


def test_grbl_has_no_tool_changer_words():
    baked, _ = engrave.bake(sample_job().program)
    text = post.milling_post("grbl").to_text(baked)
    assert "M06" not in text and "G43" not in text and "G28" not in text
    assert text.count("M00") == 2      # two tool changes after the first tool
    assert "%" not in text


def test_macro_post_writes_o7023_with_the_fixes():
    text = post.milling_post("fanuc-macro").to_text(sample_job().program)
    assert "G66.1 P7023" in text and "G67" in text and "#3001" in text
    assert "GT5" not in text and "IF[#28GE5]" in text
    assert "#24+#25" not in text
    for line in text.splitlines():
        assert line.count("[") == line.count("]"), line
    main, macro = text.split("O7023 (")
    assert main.count("M30") == 1 and macro.strip().endswith("M99\n%".strip())


def test_macro_post_refuses_what_it_cannot_do():
    job = engrave.plan(PLATE, LETTERS, engrave.EngraveSettings(raster_angle=30))
    with pytest.raises(PostError, match="raster angle"):
        post.milling_post("fanuc-macro").to_text(job.program)
    baked, _ = engrave.bake(sample_job().program)
    with pytest.raises(PostError, match="gouge texture"):
        post.milling_post("fanuc-macro").to_text(baked)
    with pytest.raises(PostError, match="unbaked texture"):
        post.milling_post("linuxcnc").to_text(sample_job().program)
    with pytest.raises(PostError, match="unknown post"):
        post.milling_post("heidenhain")


def test_number_format():
    assert fmt(106.0, 3) == "106."
    assert fmt(-2.0, 3) == "-2."
    assert fmt(0.5, 3) == "0.5"
    assert fmt(-0.0001, 3) == "0."
    assert fmt(12.34567, 4) == "12.3457"


def test_atomic_write_leaves_no_partial_file(tmp_path):
    target = tmp_path / "job.nc"
    post.write_atomic(str(target), "G0 X1.\n")
    assert target.read_text() == "G0 X1.\n"
    with pytest.raises(output.OutputError, match="not ASCII"):
        post.write_atomic(str(target), "G0 X2. (\u524a)\n")   # not ASCII: the write fails
    assert target.read_text() == "G0 X1.\n"                   # the old program is intact
    assert sorted(os.listdir(tmp_path)) == ["job.nc"]         # and no temp file is left


def test_written_files_get_ordinary_permissions(tmp_path):
    path = post.write_atomic(str(tmp_path / "job.nc"), "M30\n")
    mask = os.umask(0)
    os.umask(mask)
    assert os.stat(path).st_mode & 0o777 == 0o666 & ~mask
    post.write_atomic(str(tmp_path / "mesh.stl"), b"\x00\x01")
    assert (tmp_path / "mesh.stl").read_bytes() == b"\x00\x01"


# ----- the frames: Z first after the start and every tool load (issue 26) ---------------------------

def frame_lines(text: str) -> list:
    return [line for line in text.splitlines() if line and not line.startswith("(")]


def test_grbl_lifts_z_to_the_clearance_height_before_any_xy_and_never_above_the_reach():
    from kezuri.toolpath.ir import machine
    baked, _ = engrave.bake(sample_job().program)
    text = post.milling_post("grbl").to_text(baked)
    lines = frame_lines(text)
    router = machine.preset("grbl-router")
    assert (router.clearance_z, router.clearance_max) == (20.0, 60.0)
    # the start: the operator zeroed Z on the plate top; the first motion lifts to Z 20, then XY
    assert lines[1] == "G00 G90 G54 Z20."
    assert lines[2].startswith("G00 G90 G54 X-100. Y-49.99 ")
    # every M00 (manual change) is followed by the lift, then the XY move
    pauses = [i for i, line in enumerate(lines) if line == "M00"]
    assert len(pauses) == 2
    for i in pauses:
        assert lines[i - 1] == "G00 G90 G54 Z20." and lines[i - 2] == "M05"
        assert lines[i + 1] == "G00 G90 G54 Z20." and re.match(r"G00 G90 G54 X\S+ Y\S+ S\d+ M03$", lines[i + 2])
    assert lines[-3:] == ["M05", "G00 G90 G54 Z20.", "M30"]
    assert "BEFORE THE START: LOAD T2" in text and "LIFTS TO Z 20. BEFORE XY" in text
    z_words = [float(z) for z in re.findall(r"\bZ(-?[\d.]+)", "\n".join(lines))]
    assert max(z_words) == 20.0 <= router.clearance_max


def test_linuxcnc_lifts_in_machine_coordinates_around_every_manual_change():
    baked, _ = engrave.bake(sample_job().program)
    lines = frame_lines(post.milling_post("linuxcnc").to_text(baked))
    changes = [i for i, line in enumerate(lines) if line.endswith("M06")]
    assert len(changes) == 3
    for i in changes:
        assert lines[i - 3:i] == ["M05", "G49", "G53 G00 Z0."]             # Z up before the change (M6 does not)
        assert lines[i + 1] == "G53 G00 Z0."                               # and again before XY
        assert lines[i + 2].startswith("G00 G90 G54 X")
        assert lines[i + 3].startswith("G43 H")
    assert lines[-5:] == ["M05", "G49", "G53 G00 Z0.", "M30", "%"]


def test_a_changer_that_lifts_on_m6_needs_no_lift_before_it_but_one_after():
    from kezuri.post.linuxcnc import LinuxCNCPost
    from kezuri.toolpath.ir import machine
    baked, _ = engrave.bake(sample_job().program)
    lines = frame_lines(LinuxCNCPost(machine=machine.preset("linuxcnc-atc")).to_text(baked))
    for i in [i for i, line in enumerate(lines) if line.endswith("M06")]:
        assert lines[i - 2:i] == ["M05", "G49"] and lines[i + 1] == "G53 G00 Z0."


def test_clearance_retract_on_linuxcnc_applies_the_offset_then_lifts():
    from kezuri.post.linuxcnc import LinuxCNCPost
    from kezuri.toolpath.ir import machine
    baked, _ = engrave.bake(sample_job().program)
    unhomed = machine.preset("linuxcnc-manual").replace(retract="clearance", clearance_z=25.0)
    text = LinuxCNCPost(machine=unhomed).to_text(baked)
    if rs274.available():
        rs274.run(text)                                  # LinuxCNC's interpreter takes it (raises otherwise)
    lines = frame_lines(text)
    i = lines.index("T2 M06")
    assert lines[i + 1:i + 4] == ["G43 H2", "G00 G90 G54 Z25.", "G00 G90 G54 X-100. Y-49.99 S6000 M03"]
    assert "G53" not in "\n".join(lines)


def test_a_height_above_the_reach_is_refused_naming_both_numbers_and_the_setting():
    from kezuri.toolpath.ir import machine
    job = engrave.plan(PLATE, LETTERS, engrave.EngraveSettings(safe_z=100.0))
    baked, _ = engrave.bake(job.program)
    with pytest.raises(PostError, match=r"safe Z .* 100 mm is above the 60 mm the machine 'Hobby router \(GRBL\)' "
                                        r"reaches above the work zero \(machine setting Z Reach\)"):
        post.milling_post("grbl").to_text(baked)
    with pytest.raises(PostError, match=r"100 mm is above the 80 mm"):
        post.milling_post("linuxcnc").to_text(baked)
    assert "G43 Z100. H02" in post.milling_post("fanuc").to_text(baked)       # 300 mm on the machining centre
    taller = post.create("milling", "grbl", machine=machine.preset("grbl-router").replace(clearance_max=100.0))
    assert "G00 Z100." in taller.to_text(baked)
    with pytest.raises(machine.MachineError, match=r"clearance z = 80.0 is above the 60 mm"):
        machine.preset("grbl-router").replace(clearance_z=80.0)


def test_a_post_refuses_a_retract_or_tool_change_its_control_cannot_write():
    from kezuri.toolpath.ir import machine
    baked, _ = engrave.bake(sample_job().program)
    grbl = post.create("milling", "grbl", machine=machine.preset("grbl-router").replace(retract="reference"))
    with pytest.raises(PostError, match=r"Retract = 'reference' is not a move this control has"):
        grbl.to_text(baked)
    fanuc = post.create("milling", "fanuc", machine=machine.preset("fanuc-vmc").replace(tool_change="manual"))
    with pytest.raises(PostError, match=r"Tool Change = 'manual'"):
        fanuc.to_text(baked)
    slow = post.create("milling", "linuxcnc", machine=machine.preset("linuxcnc-manual").replace(max_spindle_rpm=8000.0))
    with pytest.raises(PostError, match=r"spindle speed S 12000 is above the 8000 rpm"):
        slow.to_text(baked)


def test_every_post_names_its_default_machine():
    for cls in post.posts(("milling", "cxz")):
        profile = post.registry.default_machine(cls)
        assert profile.family == cls.family, cls.name
    assert post.registry.default_machine(post.find("milling", "grbl")).name == "grbl-router"
    assert post.registry.default_machine(post.find("milling", "linuxcnc")).name == "linuxcnc-manual"
    assert post.registry.default_machine(post.find("milling", "fanuc-macro")).name == "fanuc-vmc"
    assert post.registry.default_machine(post.find("cxz", "linuxcnc")).name == "wood-lathe-cxz-linuxcnc"
    assert post.registry.default_machine(post.find("cxz", "fanuc")).name == "wood-lathe-cxz"


@needs_rs274
def test_rs274_moves_only_z_after_every_tool_change():
    """Read back by LinuxCNC's interpreter: after each CHANGE_TOOL the first motion is a traverse
    that keeps X and Y where they were (Z alone: the G53 lift); X/Y move only after it."""
    baked, _ = engrave.bake(sample_job().program)
    calls = rs274.run(post.milling_post("linuxcnc").to_text(baked))
    position, pending, checked = None, False, 0
    for name, args in calls:
        if name == "CHANGE_TOOL":
            pending = True
        elif name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED"):
            xyz = [float(v) for v in args[:3]] if name != "ARC_FEED" else None
            if pending:
                assert name == "STRAIGHT_TRAVERSE" and position is not None
                assert xyz[:2] == position[:2], (position, xyz)
                pending, checked = False, checked + 1
            position = xyz if xyz is not None else position
    assert checked == 3
