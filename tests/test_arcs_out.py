"""Arcs out in every milling post (post/gcode.py ``arcs_out``, toolpath/ir/arcfit.py).

Checked from the written text, not from the filter's arrays: the arcs are read back by the
independent rules reader (controller_rules.arc_blocks: start, end and centre from the words) and by
LinuxCNC's rs274 (its ARC_FEED calls); each arc is sampled by angle and measured against the planned
polyline by brute force; the controls' radius checks are the rules reader's, written from their
manuals.  The simulated cut of the engraving, the walled carving and the STEP-NC pockets is compared
with and without arcs (removed volume within 0.1 %)."""
import math

import numpy as np
import pytest

import controller_rules
import rs274
from kezuri import post as posts
from kezuri.toolpath import simulate as sim
from kezuri.toolpath.engines import region
from kezuri.toolpath.ir import arcfit
from kezuri.toolpath.ir.program import ARC_CCW, ARC_CW, FEED, RAPID, Operation, Program, Tool
from kezuri.toolpath.operations.carve import carve, carve_samples
from kezuri.toolpath.operations.engrave import engrave
from kezuri.toolpath.operations.stepnc.workplan import PocketSpec, load_workplan, pockets_to_part21, to_program

# post name -> the rules reader's control
POSTS = {"linuxcnc": "linuxcnc", "fanuc": "fanuc-mill", "grbl": "grbl"}
TOL = 0.01                        # mm: the fit's tolerance (what the planners flatten curves with)
PLATE = [np.array([[-100, -50], [100, -50], [100, 50], [-100, 50]], float)]
LETTERS = [("Letters", [np.array([[-60, -20], [-50, -20], [-50, 20], [-60, 20]], float),
                        np.array([[0, -20], [30, -20], [30, 20], [0, 20]], float),
                        np.array([[10, -10], [20, -10], [20, 10], [10, 10]], float)])]
TOOL = Tool(1, "flat", 6.0)


def post_for(name, arcs=True):
    made = posts.create("milling", name)
    return posts.create("milling", name, machine=made.machine.replace(arcs=arcs))


def star_program():
    """Clipper's rounded offset of a 12-point star: lines and round joins, one closed contour."""
    t = np.linspace(0, 2 * math.pi, 12, endpoint=False)
    k = 1 + 0.3 * (np.arange(12) % 2)
    star = np.column_stack([30 * np.cos(t) * k, 30 * np.sin(t) * k])
    loop = max((np.asarray(p) for p in region.offset(region.from_loops([star], "star"), 4.0).to_polygons()), key=len)
    loop = np.vstack([loop, loop[:1]]) + [0.123456, -0.654321]          # off the number grid
    xyz = np.column_stack([loop, np.full(len(loop), -1.0)])
    kinds = np.full(len(xyz), FEED)
    kinds[0] = RAPID
    op = Operation("outline", TOOL, 12000, kinds, xyz, np.where(kinds == RAPID, np.nan, 600.0),
                   start=np.array([loop[0, 0], loop[0, 1], 5.0]), safe_z=5.0, clearance_z=5.0)
    return Program("star", [op]), loop


@pytest.fixture(scope="module")
def engraved():
    result = engrave.plan(PLATE, LETTERS, engrave.EngraveSettings())
    return engrave.bake(result.program)[0]


@pytest.fixture(scope="module")
def stepnc_program():
    pockets = [PocketSpec("POCKET1", ((10, 10), (50, 10), (50, 40), (10, 40)), 8.0),
               PocketSpec("POCKET2", ((65, 15), (110, 15), (110, 35), (85, 35), (85, 70), (65, 70)), 5.0)]
    text = pockets_to_part21(((0, 0, -20), (120, 80, 0)), pockets, Tool(1, "flat", 6.0, flute_length=20.0),
                             name="KEZURI SAMPLE PLATE")
    return to_program(load_workplan(text))


@pytest.fixture(scope="module")
def walled():
    vertices, faces = carve_samples.walled_block()
    return carve.plan(vertices, faces, carve.CarveSettings(rough=False, steep_cleanup=False))


def distance_to_polyline(points, vertices):
    a, b = vertices[:-1], vertices[1:]
    d = b - a
    length2 = np.maximum((d * d).sum(axis=1), 1e-300)
    best = np.full(len(points), np.inf)
    for start in range(0, len(points), 1000):
        p = points[start:start + 1000, None, :]
        t = np.clip(((p - a) * d).sum(axis=2) / length2, 0, 1)
        best[start:start + 1000] = np.linalg.norm(p - (a + t[..., None] * d), axis=2).min(axis=1)
    return best


def arc_samples(start, end, centre, clockwise, count=200):
    """Points along an arc as a control cuts it: by angle from the start, the radius going from the
    start's to the end's."""
    r0, r1 = math.dist(start, centre), math.dist(end, centre)
    a = math.atan2(start[1] - centre[1], start[0] - centre[0])
    b = math.atan2(end[1] - centre[1], end[0] - centre[0])
    sweep = -((a - b) % (2 * math.pi)) if clockwise else (b - a) % (2 * math.pi)
    t = np.linspace(0, 1, count)
    r = r0 + (r1 - r0) * t
    return np.column_stack([centre[0] + r * np.cos(a + sweep * t), centre[1] + r * np.sin(a + sweep * t)])


@pytest.mark.parametrize("name", sorted(POSTS))
def test_the_written_arcs_lie_on_the_polyline_and_pass_the_controls_radius_check(name):
    program, loop = star_program()
    text = post_for(name).to_text(program)
    arcs = controller_rules.arc_blocks(text)
    assert len(arcs) >= 6                                    # the six outer points rounded by the offset
    assert controller_rules.check(text, POSTS[name]) == []
    step = 10.0 ** -post_for(name).decimals
    for number, clockwise, start, end, centre, _, bare in arcs:
        # each arc ends on a vertex of the planned polyline (as written), and every point of it lies
        # within the fit's tolerance of the polyline (the written numbers' rounding on top)
        assert distance_to_polyline(np.array([end]), loop).min() <= step, bare
        assert np.min(np.abs(loop - np.array(end)).max(axis=1)) <= step / 2 + 1e-9, bare
        on_arc = arc_samples(start, end, centre, clockwise)
        assert distance_to_polyline(on_arc, loop).max() <= TOL + 2 * step, bare
        # within the control's arc end check, measured from the words
        assert abs(math.dist(start, centre) - math.dist(end, centre)) <= {"fanuc": 0.001}.get(name, 0.005) + 1e-9


@pytest.mark.parametrize("name", sorted(POSTS))
def test_the_fitted_programs_are_smaller_and_off_means_every_move(name):
    program, loop = star_program()
    with_arcs = post_for(name).to_text(program)
    without = post_for(name, arcs=False).to_text(program)
    assert "G02" not in without and "G03" not in without
    motion = [line for line in without.splitlines() if line.startswith(("G01", "X", "Y"))]
    assert len(motion) == len(loop) - 1                      # every planned feed move one block
    fitted = [line for line in with_arcs.splitlines() if line.startswith(("G01", "G02", "G03", "X", "Y"))]
    assert 2 * len("\n".join(fitted)) < len("\n".join(motion))       # the moves' bytes: a star of straight edges


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed")
def test_rs274_arc_ends_are_the_polylines_points():
    program, loop = star_program()
    fitted = rs274.run(post_for("linuxcnc").to_text(program))
    plain = rs274.run(post_for("linuxcnc", arcs=False).to_text(program))
    kinds, ends, _ = rs274.motion_endpoints(fitted)
    _, plain_ends, _ = rs274.motion_endpoints(plain)
    assert kinds.count("cw") + kinds.count("ccw") >= 6
    # every end point rs274 reaches with arcs is one it reaches without, in the same order
    at = 0
    for point in ends:
        matches = np.flatnonzero(np.abs(plain_ends[at:] - point).max(axis=1) <= 1e-9)
        assert len(matches), point
        at += int(matches[0]) + 1
    assert np.allclose(ends[-1], plain_ends[-1])
    for name, args in fitted:
        if name == "ARC_FEED":
            end = np.array([float(args[0]), float(args[1])])
            assert np.abs(loop - end).max(axis=1).min() <= 0.5e-4 + 1e-9


def test_the_fit_tolerance_is_the_planners_chord_error():
    assert arcfit.DEFAULT_TOLERANCE == region.ARC_TOLERANCE


def test_rotary_operations_texture_requests_and_arc_free_controls_are_left_alone(engraved):
    program, _ = star_program()
    op = program.operations[0]
    turned = op.replace(rotary={"c": np.zeros(len(op))})
    assert arcfit.fit_arcs(turned) is turned
    macro = engrave.plan(PLATE, LETTERS, engrave.EngraveSettings()).program.operations[0]
    assert macro.texture is not None and arcfit.fit_arcs(macro) is macro
    for name in ("linuxcnc-cxz", "fanuc-cxz"):
        cls = posts.find("cxz", name)
        assert cls.family != "milling"


def test_bad_filter_settings_are_refused():
    program, _ = star_program()
    with pytest.raises(arcfit.ArcFitError, match="end tolerance"):
        arcfit.fit_arcs(program.operations[0], end_tolerance=-1.0)
    with pytest.raises(arcfit.ArcFitError, match="least increment"):
        arcfit.fit_arcs(program.operations[0], written=lambda v: v, step=0.0)


def removed(program_or_ops, stock):
    return sim.simulate(program_or_ops, stock, cell=0.1).removed_volume_mm3


@pytest.mark.parametrize("sample", ["engrave", "stepnc", "carve"])
def test_the_simulated_cut_stays_the_same(sample, engraved, stepnc_program, walled):
    """Removed volume with the arcs as the control reads them (centres on the number grid) within
    0.1 % of the planned polylines'; and the arcs are really there."""
    post = post_for("linuxcnc")
    if sample == "engrave":
        program, stock = engraved, sim.BoxStock(-100, -50, -10, 100, 50, 0)
    elif sample == "stepnc":
        program, stock = stepnc_program, sim.BoxStock(0, 0, -20, 120, 80, 0)
    else:
        program = Program("walls", [op for op in walled.program.operations if op.name == "wall pass"])
        x0, y0, z0, x1, y1, z1 = walled.stock
        stock = sim.BoxStock(x0, y0, z0, x1, y1, z1)
    fitted = post.arcs_out(program)
    arcs = sum(int(np.isin(op.kind, (ARC_CW, ARC_CCW)).sum()) for op in fitted.operations)
    before = sum(int(np.isin(op.kind, (ARC_CW, ARC_CCW)).sum()) for op in program.operations)
    assert arcs > before
    plain, arced = removed(program, stock), removed(fitted, stock)
    assert arced == pytest.approx(plain, rel=1e-3)


@pytest.mark.parametrize("control, mismatch, alarms", [
    ("linuxcnc", 0.004, False), ("linuxcnc", 0.006, True), ("grbl", 0.006, True), ("grbl", 0.004, False),
    ("fanuc-mill", 0.0009, False), ("fanuc-mill", 0.002, True)])
def test_the_rules_reader_catches_a_radius_mismatch(control, mismatch, alarms):
    """An arc from (5, 0) about the origin ending at radius 5 + mismatch, and one without I/J."""
    end = 5.0 + mismatch
    text = f"G00 X5. Y0.\nG01 Z-1. F100.\nG03 X0. Y{end:.4f} I-5. J0.\nG03 X5. Y0.\nM30\n"
    found = [v for v in controller_rules.check_arcs(text, control)]
    assert [v[1] for v in found if "differ" in v[2]] == ([3] if alarms else [])
    assert [v[1] for v in found if "without I or J" in v[2]] == [4]


def test_batch_no_arcs_writes_the_straight_moves(tmp_path):
    """``batch.py stepnc --no-arcs``: no G02/G03 (the sample's pocket corners stay polylines) and
    the same moves as rs274 reads the fitted program's, every arc's end among them."""
    import contextlib
    import importlib.util
    import io
    import json
    import os

    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    spec = importlib.util.spec_from_file_location("kezuri_batch_arcs", os.path.join(root, "batch.py"))
    batch = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(batch)
    texts = {}
    for label, extra in (("arcs", ()), ("plain", ("--no-arcs",))):
        out = str(tmp_path / label)
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            assert batch.main(["batch.py", "stepnc", "--post", "linuxcnc", *extra, "--out", out]) == 0
        report = json.loads(open(os.path.join(out, "report.json")).read())
        texts[label] = open(next(f for f in report["files"] if f.endswith(".ngc"))).read()
    assert "G02" not in texts["plain"] and "G03" not in texts["plain"]
    assert texts["arcs"].count("G02") + texts["arcs"].count("G03") >= 4
    if rs274.available():
        kinds, ends, _ = rs274.motion_endpoints(rs274.run(texts["arcs"]))
        _, plain_ends, _ = rs274.motion_endpoints(rs274.run(texts["plain"]))
        for kind, end in zip(kinds, ends):
            if kind in ("cw", "ccw"):
                assert np.abs(plain_ends - end).max(axis=1).min() <= 1e-9
