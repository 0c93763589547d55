"""W5 posts: Amada turret-punch NC (G92 / G72 / G69 / G79) and the DXF / SVG flat-pattern export."""
import io
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from kezuri.post import write_atomic
from kezuri.post.amada_punch import to_text
from kezuri.post.gcode import PostError
from kezuri.post.flat_export import ExportError, to_dxf, to_svg
from kezuri.toolpath.unfold import compensate_outline, signed_area, unfold_elbow, unfold_twisted_quad

PAPER_CORNERS = np.array([[0, 0, 0], [0, 30, 100], [100, 50, 100], [100, 40, 0]], float)
G72 = re.compile(r"^N(\d{3}) G72 X(-?\d+\.\d\d) Y(-?\d+\.\d\d)$")
G69 = re.compile(r"^G69 I(\d+\.\d\d) J(-?\d+\.\d\d) P(-?\d+\.\d\d) Q(\d+\.\d\d) T(\d{3})$")
G79 = re.compile(r"^G79 I(\d+\.\d\d) J(-?\d+\.\d\d) P(-?\d+\.\d\d) Q(\d+\.\d\d) D(\d+\.\d\d) T(\d{3})$")


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
    with pytest.raises(PostError, match="tool side"):
        to_text(ccw, station=302, pitch=2.0, thickness=1.0, tool_diameter=5.0, tool_side="up")


def test_thick_sheet_uses_punching_line():
    contour = paper_contour()
    with pytest.raises(PostError, match="pitch Q 3.0 must be at least the thickness 4.5"):
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
        with pytest.raises(PostError, match="station"):
            to_text(square, **{**ok, "station": station})
    with pytest.raises(PostError, match="pitch"):
        to_text(square, **{**ok, "pitch": 0.0})
    with pytest.raises(PostError, match="thickness"):
        to_text(square, **{**ok, "thickness": float("nan")})
    with pytest.raises(PostError, match="output resolution"):
        to_text([(0, 0), (10, 0), (10, 10), (10.004, 10)], **ok)
    with pytest.raises(PostError, match="3 distinct points"):
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
    layers = [pairs[i + 1][1] for i, p in enumerate(pairs) if p == (0, "LAYER")]
    assert {"PATTERN", "CUT"} <= set(layers)

    entities = dxf_entities(pairs)
    kinds = [e[0] for e in entities]
    assert len(bends) == 2 * 5 - 1                      # inner edges of 10 triangles in a strip
    assert kinds.count("POLYLINE") == 2 and kinds.count("SEQEND") == 2
    assert kinds.count("LINE") == len(bends)
    assert kinds.count("VERTEX") == len(outline) + len(cut)
    polylines = [i for i, k in enumerate(kinds) if k == "POLYLINE"]
    for i, (layer, contour) in zip(polylines, (("PATTERN", outline), ("CUT", cut))):
        assert entities[i][1][8] == [layer] and entities[i][1][70] == ["1"]      # closed
        verts = entities[i + 1:i + 1 + len(contour)]
        assert all(v[0] == "VERTEX" and v[1][8] == [layer] for v in verts)
        xy = np.array([[float(v[1][10][0]), float(v[1][20][0])] for v in verts])
        np.testing.assert_allclose(xy, contour, atol=1e-6)
        assert entities[i + 1 + len(contour)][0] == "SEQEND"
    for kind, codes in entities:
        if kind == "LINE":
            assert codes[8] == ["PATTERN"] and set(codes) >= {10, 20, 11, 21}


def test_dxf_reads_back_with_ezdxf(flat_job):
    ezdxf = pytest.importorskip("ezdxf")
    outline, cut, bends = flat_job
    doc = ezdxf.read(io.StringIO(to_dxf([outline], [cut], bends)))
    msp = doc.modelspace()
    assert len(msp.query('POLYLINE[layer=="PATTERN"]')) == 1
    assert len(msp.query('POLYLINE[layer=="CUT"]')) == 1
    assert len(msp.query('LINE[layer=="PATTERN"]')) == len(bends)
    poly = msp.query('POLYLINE[layer=="CUT"]')[0]
    assert poly.is_closed
    np.testing.assert_allclose([tuple(p)[:2] for p in poly.points()], cut, atol=1e-6)


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
    assert len(groups["PATTERN"].findall("s:path", ns)) == len(pattern)   # one path per contour
    assert len(groups["CUT"].findall("s:path", ns)) == 1
    assert len(groups["PATTERN"].findall("s:line", ns)) == len(bends)
    d = groups["CUT"].find("s:path", ns).get("d")
    assert d.startswith("M ") and d.endswith(" Z")
    nums = np.array([float(v) for v in re.findall(r"-?\d+\.\d+", d)]).reshape(-1, 2)
    np.testing.assert_allclose(nums * [1, -1], cut, atol=1e-6)       # SVG y points down
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
