"""W5 posts: Amada turret-punch NC (G92 / G72 / G69 / G79) and the DXF / SVG flat-pattern export."""
import io
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from kezuri.post import write_atomic
from kezuri.post.amada_punch import AmadaPunchPost
from kezuri.post.gcode import PostError
from kezuri.post.flat_export import ExportError, to_dxf, to_svg
from kezuri.toolpath.ir.program import ProgramError
from kezuri.toolpath.ir.program import PunchOperation, PunchProgram
from kezuri.toolpath.operations.sheetmetal.nibbling import NibblingError, offset_side, segment_lines
from kezuri.toolpath.operations.sheetmetal.unfold import (compensate_outline, signed_area, unfold_elbow, unfold_twisted_quad)

PAPER_CORNERS = np.array([[0, 0, 0], [0, 30, 100], [100, 50, 100], [100, 40, 0]], float)
G72 = re.compile(r"^N(\d{3}) G72 X(-?\d+\.\d\d) Y(-?\d+\.\d\d)$")
G69 = re.compile(r"^G69 I(\d+\.\d\d) J(-?\d+\.\d\d) P(-?\d+\.\d\d) Q(\d+\.\d\d) T(\d{3})$")
G79 = re.compile(r"^G79 I(\d+\.\d\d) J(-?\d+\.\d\d) P(-?\d+\.\d\d) Q(\d+\.\d\d) D(\d+\.\d\d) T(\d{3})$")


def to_text(contour, *, station, pitch, thickness, tool_diameter=0.0, tool_side="outside", origin=(1000.0, 1040.0),
            end_code="G50", punch_diameter=2.0):
    """The seed paper's program of ``contour`` through the IR: one line per segment
    (:func:`segment_lines`), P0 (the contour is the punch centre's path) unless ``tool_diameter`` is
    given: the control then offsets the punch that size to ``tool_side`` (:func:`offset_side`)."""
    compensation = "none" if tool_diameter == 0 else offset_side(contour, tool_side)
    op = PunchOperation("contour", station, tool_diameter or punch_diameter, pitch, thickness, segment_lines(contour),
                        compensation)
    return AmadaPunchPost(end_code).to_text(PunchProgram("part", [op], origin))


def paper_contour(tool_diameter=2.0):
    """The seed's twisted quad, developed horizontally and compensated for the tool."""
    outline = unfold_twisted_quad(PAPER_CORNERS, 5, "horizontal").pattern.outline
    return compensate_outline(outline + [20.0, 20.0], tool_diameter)   # moved onto the sheet


def parse(text, line_word=G69):
    lines = text.splitlines()
    starts, moves = [], []
    for a, b in zip(lines[1:-1:2], lines[2:-1:2]):
        m72, mline = G72.match(a), line_word.match(b)
        assert m72 and mline, (a, b)
        starts.append((int(m72.group(1)), float(m72.group(2)), float(m72.group(3))))
        moves.append(mline.groups())
    return lines, starts, moves


# ---------------------------------------------------------------- Amada NC


def test_program_layout_and_closure():
    contour = paper_contour()
    text = to_text(contour, station=302, pitch=2.0, thickness=1.6)
    lines, starts, moves = parse(text)
    assert lines[0] == "N000 G92 X1000.00 Y1040.00"
    assert lines[-1] == "G50"
    assert len(lines) == 2 + 2 * len(contour)
    assert len(starts) == len(moves) == len(contour)            # one G72/G69 pair per segment
    assert [s[0] for s in starts] == list(range(1, len(contour) + 1))
    assert all(m[2] == "0.00" and m[3] == "2.00" and m[4] == "302" for m in moves)  # P0: compensated
    # re-integrate I/J from each G72 point: every segment ends where the next begins, the last at the first
    xy = np.array([(s[1], s[2]) for s in starts])
    ends = xy + np.array([[float(m[0]) * math.cos(math.radians(float(m[1]))),
                           float(m[0]) * math.sin(math.radians(float(m[1])))] for m in moves])
    gap = np.linalg.norm(ends - np.roll(xy, -1, axis=0), axis=1)
    tol = 0.011 + np.array([float(m[0]) for m in moves]) * math.radians(0.005)
    assert np.all(gap <= tol), gap
    np.testing.assert_allclose(xy, contour, atol=0.005)


def test_angle_quadrants_and_table2_format():
    square = [(10, 10), (60, 10), (60, 60), (10, 60)]
    _, _, moves = parse(to_text(square, station=5, pitch=1.5, thickness=1.0))
    assert [m[1] for m in moves] == ["0.00", "90.00", "180.00", "-90.00"]
    assert all(m[0] == "50.00" and m[4] == "005" for m in moves)
    # the first line of Table 2: N001 G72 X .93 Y 147.66 / G69 I 20.29 J -5.32 P 0 Q2.00 T 302
    a = np.array([0.93, 147.66])
    b = a + 20.29 * np.array([math.cos(math.radians(-5.32)), math.sin(math.radians(-5.32))])
    text = to_text([a, b, (b[0], 300.0)], station=302, pitch=2.0, thickness=1.0)
    assert text.splitlines()[1:3] == ["N001 G72 X0.93 Y147.66", "G69 I20.29 J-5.32 P0.00 Q2.00 T302"]


def test_tool_offset_sign():
    ccw = [(0, 0), (100, 0), (100, 50), (0, 50)]
    def p_words(contour, **kw):
        return {m[2] for m in parse(to_text(contour, station=302, pitch=2.0, thickness=1.0, **kw))[2]}
    assert p_words(ccw, tool_diameter=10.0) == {"-10.00"}                 # outside a CCW loop = right
    assert p_words(ccw[::-1], tool_diameter=10.0) == {"10.00"}            # outside a CW loop = left
    assert p_words(ccw, tool_diameter=10.0, tool_side="inside") == {"10.00"}
    assert p_words(ccw, tool_diameter=10.0, tool_side="left") == {"10.00"}
    assert p_words(ccw, tool_diameter=10.0, tool_side="right") == {"-10.00"}
    assert p_words(ccw) == {"0.00"}
    with pytest.raises(NibblingError, match="tool side"):
        to_text(ccw, station=302, pitch=2.0, thickness=1.0, tool_diameter=5.0, tool_side="up")


def test_thick_sheet_uses_punching_line():
    contour = paper_contour()
    with pytest.raises(PostError, match="pitch Q 3 must be at least the thickness 4.5 mm"):
        to_text(contour, station=302, pitch=3.0, thickness=4.5)
    text = to_text(contour, station=302, pitch=5.0, thickness=4.5, origin=(1250, 1000), end_code="M30")
    lines, starts, moves = parse(text, G79)
    assert lines[0] == "N000 G92 X1250.00 Y1000.00" and lines[-1] == "M30"
    assert "G69" not in text
    assert len(moves) == len(contour) and all(m[4] == "4.50" and m[3] == "5.00" for m in moves)
    # 3.2 mm itself still nibbles with G69 (G79 only when thicker)
    assert "G69" in to_text(contour, station=302, pitch=2.0, thickness=3.2)


def test_elbow_pattern_to_nc():
    piece = unfold_elbow(90.0, 150.0, 100.0, 4, divisions=36).pieces[1]
    path = compensate_outline(piece.outline + [50.0, 100.0], 3.0)
    text = to_text(path, station=101, pitch=1.0, thickness=1.2)
    assert text.count("G72") == text.count("G69") == len(path)


def test_bad_input_is_rejected():
    square = [(0, 0), (10, 0), (10, 10), (0, 10)]
    ok = dict(station=302, pitch=2.0, thickness=1.0)
    for station in (0, 1000, 3.0, True):
        with pytest.raises(ProgramError, match="station"):
            to_text(square, **{**ok, "station": station})
    with pytest.raises(ProgramError, match="pitch"):
        to_text(square, **{**ok, "pitch": 0.0})
    with pytest.raises(ProgramError, match="thickness"):
        to_text(square, **{**ok, "thickness": float("nan")})
    with pytest.raises(PostError, match="output resolution"):
        to_text([(0, 0), (10, 0), (10, 10), (10.004, 10)], **ok)
    with pytest.raises(NibblingError, match="3 distinct points"):
        to_text([(0, 0), (10, 0), (0, 0)], **ok)
    with pytest.raises(PostError, match="end code"):
        to_text(square, **ok, end_code="M02")


def test_write_atomic(tmp_path):
    target = tmp_path / "PART.NC"
    target.write_text("old")
    text = to_text([(0, 0), (10, 0), (10, 10)], station=302, pitch=2.0, thickness=1.0)
    write_atomic(target, text)
    assert target.read_text() == text
    assert [p.name for p in tmp_path.iterdir()] == ["PART.NC"]


def test_the_punch_ir_refuses_what_no_punch_can_do():
    line = [[[0.0, 0.0], [10.0, 0.0]]]
    ok = dict(name="op", station=302, punch_diameter=10.0, pitch=2.0, thickness=1.0, lines=line)
    for change, words in ((dict(punch_diameter=0.0), "punch diameter must be a finite number > 0"),
                          (dict(pitch="x"), "nibbling pitch Q must be a number, got 'x'"),
                          (dict(thickness=math.inf), "sheet thickness must be a finite number > 0"),
                          (dict(lines=[[[0.0, 0.0], [math.nan, 0.0]]]), "non-finite"),
                          (dict(lines=np.zeros((0, 2, 2))), r"pairs of \(x, y\), got shape \(0, 2, 2\)"),
                          (dict(compensation="outside"), "compensation must be one of")):
        with pytest.raises(ProgramError, match=words):
            PunchOperation(**{**ok, **change})
    op = PunchOperation(**ok)
    line[0][1][0] = 99.0                                  # the caller's array changed after: not the operation's
    assert op.lengths().tolist() == [10.0] and op.angles().tolist() == [0.0]
    with pytest.raises(ProgramError, match="G92 origin must be finite"):
        PunchProgram("p", [op], (math.inf, 0.0))
    with pytest.raises(ProgramError, match="one or more PunchOperations"):
        PunchProgram("p", [])
    with pytest.raises(PostError, match="writes a PunchProgram"):
        AmadaPunchPost().to_text("N001 G72 X0 Y0")
    with pytest.raises(PostError, match="end code"):
        AmadaPunchPost(end_code="M02")


def test_two_stations_in_one_program_are_numbered_on():
    """Two operations: the second's lines go on numbering after the first's, each with its own
    station, pitch and offset word; the notes are comments after G92."""
    first = PunchOperation("outline", 302, 10.0, 2.0, 1.6, [[[10.0, 20.0], [60.0, 20.0]]])
    second = PunchOperation("slot", 101, 4.0, 1.5, 1.6, [[[30.0, 40.0], [30.0, 30.0]], [[30.0, 30.0], [20.0, 30.0]]],
                            compensation="left")
    text = AmadaPunchPost().to_text(PunchProgram("p", [first, second], (1250.0, 1000.0), notes=["part (a)"]))
    assert text == ("N000 G92 X1250.00 Y1000.00\n(PART [A])\n"
                    "N001 G72 X10.00 Y20.00\nG69 I50.00 J0.00 P0.00 Q2.00 T302\n"
                    "N002 G72 X30.00 Y40.00\nG69 I10.00 J-90.00 P4.00 Q1.50 T101\n"
                    "N003 G72 X30.00 Y30.00\nG69 I10.00 J180.00 P4.00 Q1.50 T101\nG50\n")


# ---------------------------------------------------------------- DXF / SVG


def dxf_pairs(text):
    lines = text.splitlines()
    assert len(lines) % 2 == 0
    return [(int(lines[i]), lines[i + 1].strip()) for i in range(0, len(lines), 2)]


def dxf_entities(pairs):
    """Entities of the ENTITIES section as (type, {code: [values]})."""
    start = pairs.index((2, "ENTITIES"))
    end = pairs.index((0, "ENDSEC"), start)
    entities = []
    for code, value in pairs[start + 1:end]:
        if code == 0:
            entities.append((value, {}))
        else:
            entities[-1][1].setdefault(code, []).append(value)
    return entities


@pytest.fixture
def flat_job():
    quad = unfold_twisted_quad(PAPER_CORNERS, 5, "horizontal")
    outline = quad.pattern.outline
    return outline, compensate_outline(outline, 4.0), quad.pattern.bend_lines()


def test_dxf_is_wellformed_r12(flat_job):
    outline, cut, bends = flat_job
    text = to_dxf([outline], [cut], bends)
    pairs = dxf_pairs(text)
    assert pairs[-1] == (0, "EOF")
    assert (9, "$ACADVER") in pairs and pairs[pairs.index((9, "$ACADVER")) + 1] == (1, "AC1009")
    sections = [pairs[i + 1][1] for i, p in enumerate(pairs) if p == (0, "SECTION")]
    assert sections == ["HEADER", "TABLES", "ENTITIES"]
    assert pairs.count((0, "SECTION")) == pairs.count((0, "ENDSEC"))
    # each LAYER table entry: name -> its line type (group 6)
    layers = {}
    for i, p in enumerate(pairs):
        if p == (0, "LAYER"):
            entry = dict(pairs[i + 1:i + 6])
            layers[entry[2]] = entry[6]
    assert layers["CUT"] == "CONTINUOUS" and layers["PUNCH_PATH"] == "CONTINUOUS"
    assert layers["BEND"] == "DASHED"
    assert "PATTERN" not in layers
    # the DASHED line type is defined R12-style: 73 = number of dashes, 40 = their total length, 49 each
    i = pairs.index((2, "DASHED"))
    ltype = pairs[i:pairs.index((0, "ENDTAB"), i)]
    dashes = [float(v) for c, v in ltype if c == 49]
    assert (73, str(len(dashes))) in ltype and len(dashes) >= 2
    assert any(d > 0 for d in dashes) and any(d < 0 for d in dashes)     # dashes and gaps
    assert float(dict(ltype)[40]) == pytest.approx(sum(abs(d) for d in dashes))

    entities = dxf_entities(pairs)
    kinds = [e[0] for e in entities]
    assert len(bends) == 2 * 5 - 1                      # inner edges of 10 triangles in a strip
    assert kinds.count("POLYLINE") == 2 and kinds.count("SEQEND") == 2
    assert kinds.count("LINE") == len(bends)
    assert kinds.count("VERTEX") == len(outline) + len(cut)
    polylines = [i for i, k in enumerate(kinds) if k == "POLYLINE"]
    for i, (layer, contour) in zip(polylines, (("CUT", outline), ("PUNCH_PATH", cut))):
        assert entities[i][1][8] == [layer] and entities[i][1][70] == ["1"]      # closed
        verts = entities[i + 1:i + 1 + len(contour)]
        assert all(v[0] == "VERTEX" and v[1][8] == [layer] for v in verts)
        xy = np.array([[float(v[1][10][0]), float(v[1][20][0])] for v in verts])
        np.testing.assert_allclose(xy, contour, atol=1e-6)
        assert entities[i + 1 + len(contour)][0] == "SEQEND"
    for kind, codes in entities:
        if kind == "LINE":
            assert codes[8] == ["BEND"] and codes[6] == ["DASHED"] and set(codes) >= {10, 20, 11, 21}


def paper_quad_area_3d(divisions=5):
    """Area of the paper's twisted quad as the surface that is unfolded, computed here from the
    corners alone: L1 (P1 -> P2) and L3 (P4 -> P3) divided into N equal parts, each strip quad
    a_i a_i+1 b_i+1 b_i split by the diagonal b_i - a_i+1 (the horizontal YR strips), and the
    3-D triangle areas summed.  Unfolding a triangle is an isometry, so the flat pattern has
    exactly this area."""
    p1, p2, p3, p4 = PAPER_CORNERS
    t = np.arange(divisions + 1)[:, None] / divisions
    a, b = p1 + (p2 - p1) * t, p4 + (p3 - p4) * t
    area = 0.0
    for i in range(divisions):
        for u, v, w in ((a[i], a[i + 1], b[i]), (a[i + 1], b[i + 1], b[i])):
            area += 0.5 * np.linalg.norm(np.cross(v - u, w - u))
    return area


def shoelace(points):
    x, y = np.asarray(points, float).T
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def test_dxf_reads_back_with_ezdxf(flat_job):
    ezdxf = pytest.importorskip("ezdxf")     # pinned in requirements.txt: this runs in the suite
    outline, cut, bends = flat_job
    doc = ezdxf.read(io.StringIO(to_dxf([outline], [cut], bends)))
    auditor = doc.audit()
    assert not auditor.has_errors, [str(e.message) for e in auditor.errors]
    assert doc.linetypes.has_entry("DASHED")
    dashed = doc.linetypes.get("DASHED")
    assert len(dashed.pattern_tags.tags) > 0 and not dashed.pattern_tags.is_complex_type()
    assert doc.layers.get("BEND").dxf.linetype == "DASHED"
    assert doc.layers.get("CUT").dxf.linetype == "CONTINUOUS"
    msp = doc.modelspace()
    assert {e.dxf.layer for e in msp} == {"CUT", "BEND", "PUNCH_PATH"}
    assert len(msp.query('POLYLINE[layer=="CUT"]')) == 1
    assert len(msp.query('POLYLINE[layer=="PUNCH_PATH"]')) == 1
    bend_lines = msp.query('LINE[layer=="BEND"]')
    assert len(bend_lines) == len(bends) == 9 and len(msp.query("LINE")) == len(bends)
    assert all(line.dxf.linetype == "DASHED" for line in bend_lines)
    punch = msp.query('POLYLINE[layer=="PUNCH_PATH"]')[0]
    assert punch.is_closed
    np.testing.assert_allclose([tuple(p)[:2] for p in punch.points()], cut, atol=1e-6)
    # The CUT outline is the developed part: its area is the 3-D surface's (from the corners alone).
    part = msp.query('POLYLINE[layer=="CUT"]')[0]
    assert part.is_closed
    expected = paper_quad_area_3d(5)
    assert expected > 9000                                    # about 100 x 100 mm, twisted
    assert shoelace([tuple(p)[:2] for p in part.points()]) == pytest.approx(expected, rel=1e-6)
    # every bend line joins two outline vertices (a fold runs from edge to edge of the sheet)
    ends = np.array([tuple(p)[:2] for p in part.points()])
    for line in bend_lines:
        for end in (line.dxf.start, line.dxf.end):
            assert np.min(np.linalg.norm(ends - [end[0], end[1]], axis=1)) < 1e-6


def test_svg_is_wellformed(flat_job):
    outline, cut, bends = flat_job
    elbow = unfold_elbow(90.0, 150.0, 100.0, 3, divisions=24)
    pattern = [outline] + [p.outline + [0.0, 200.0 + 150.0 * p.index] for p in elbow.pieces]
    text = to_svg(pattern, [cut], bends, margin=2.0)
    root = ET.fromstring(text)
    ns = {"s": "http://www.w3.org/2000/svg"}
    assert root.get("width").endswith("mm") and root.get("height").endswith("mm")
    vb = [float(v) for v in root.get("viewBox").split()]
    assert vb[2] == pytest.approx(float(root.get("width")[:-2]))
    groups = {g.get("id"): g for g in root.findall("s:g", ns)}
    assert set(groups) == {"CUT", "BEND", "PUNCH_PATH"}
    assert all(g.get("class") == name for name, g in groups.items())
    assert len(groups["CUT"].findall("s:path", ns)) == len(pattern)   # one path per contour
    assert len(groups["PUNCH_PATH"].findall("s:path", ns)) == 1
    assert len(groups["BEND"].findall("s:line", ns)) == len(bends)
    assert not groups["BEND"].findall("s:path", ns) and not groups["CUT"].findall("s:line", ns)
    dash = [float(v) for v in groups["BEND"].get("stroke-dasharray").split()]
    assert len(dash) >= 2 and min(dash) > 0                       # the bend lines are dashed
    assert groups["CUT"].get("stroke-dasharray") is None and groups["PUNCH_PATH"].get("stroke-dasharray") is None
    d = groups["PUNCH_PATH"].find("s:path", ns).get("d")
    assert d.startswith("M ") and d.endswith(" Z")
    nums = np.array([float(v) for v in re.findall(r"-?\d+\.\d+", d)]).reshape(-1, 2)
    np.testing.assert_allclose(nums * [1, -1], cut, atol=1e-6)       # SVG y points down
    d = groups["CUT"].find("s:path", ns).get("d")
    nums = np.array([float(v) for v in re.findall(r"-?\d+\.\d+", d)]).reshape(-1, 2)
    assert shoelace(nums) == pytest.approx(paper_quad_area_3d(5), rel=1e-6)
    # everything inside the viewBox
    allpts = np.vstack(pattern + [cut]) * [1, -1]
    assert np.all(allpts[:, 0] >= vb[0]) and np.all(allpts[:, 0] <= vb[0] + vb[2])
    assert np.all(allpts[:, 1] >= vb[1]) and np.all(allpts[:, 1] <= vb[1] + vb[3])


def test_exports_reject_bad_input():
    with pytest.raises(ExportError, match="nothing to export"):
        to_dxf([])
    with pytest.raises(ExportError, match="non-finite"):
        to_svg([np.array([[0, 0], [1, np.nan], [1, 1]])])
    with pytest.raises(ExportError, match="bend lines"):
        to_dxf([np.array([[0, 0], [1, 0], [1, 1]])], bend_lines=np.zeros((2, 3)))
    # a single (k, 2) array is one contour
    assert to_svg(np.array([[0, 0], [10, 0], [10, 10]])).count("<path") == 1
    assert signed_area(np.array([[0, 0], [10, 0], [10, 10]])) > 0


def test_a_contour_beyond_the_controls_reach_is_refused():
    """04P words address 9999.99 mm: a corner or a line beyond that is refused naming the corner."""
    square = np.array([[0.0, 0.0], [9000.0, 0.0], [9000.0, 9000.0], [0.0, 9000.0]])
    assert to_text(square, station=302, pitch=50.0, thickness=1.0).count("G69") == 4
    wide = np.array([[5000.0, 0.0], [10500.0, 0.0], [10500.0, 5000.0], [5000.0, 5000.0]])
    with pytest.raises(PostError, match=r"corner 2 of the contour, G72 X10500\.00 Y0\.00 .* is beyond the 9999\.99 mm"):
        to_text(wide, station=302, pitch=50.0, thickness=1.0)
    with pytest.raises(PostError, match=r"corner 1 .* \(the line from it 10000\.00 mm long\), is beyond"):
        to_text(square + [[0, 0], [1000, 0], [1000, 0], [0, 0]], station=302, pitch=50.0, thickness=1.0)
    with pytest.raises(PostError, match=r"G92 X12000\.00: beyond the 9999\.99 mm"):
        to_text(square, station=302, pitch=50.0, thickness=1.0, origin=(12000.0, 0.0))
