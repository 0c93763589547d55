"""DXF drawings read into loops in mm (toolpath/engines/dxffile.py), checked against closed forms.

R12 files are written here by hand as laser shops' CAD writes them (group code lines right-aligned,
a HEADER with $INSUNITS, a LAYER table, ENTITIES); R2000 files with ezdxf (a test dependency only:
the reader is our own), whose own B-spline evaluation is the independent reference for SPLINE."""
import math

import numpy as np
import pytest

from kezuri.toolpath.engines import dxffile
from kezuri.toolpath.engines.designshapes import DesignFileError
from kezuri.toolpath.engines.region import ARC_TOLERANCE

ezdxf = pytest.importorskip("ezdxf")
TOL = ARC_TOLERANCE


def area(points):
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def perimeter(points, closed=True):
    pts = np.vstack([points, points[:1]]) if closed else points
    return float(np.hypot(*np.diff(pts, axis=0).T).sum())


def dxf_text(*entities, units=4, layers=("0", "CUT")):
    """An R12-style ASCII DXF: codes right-aligned in three columns, as AutoCAD writes them."""
    pairs = [(0, "SECTION"), (2, "HEADER"), (9, "$ACADVER"), (1, "AC1009")]
    if units is not None:
        pairs += [(9, "$INSUNITS"), (70, units)]
    pairs += [(0, "ENDSEC"), (0, "SECTION"), (2, "TABLES"), (0, "TABLE"), (2, "LAYER"), (70, len(layers))]
    for name in layers:
        off = name.startswith("OFF")
        pairs += [(0, "LAYER"), (2, name), (70, 0), (62, -7 if off else 7), (6, "CONTINUOUS")]
    pairs += [(0, "ENDTAB"), (0, "ENDSEC")]
    blocks = [e for e in entities if e and e[0] == (0, "BLOCK")]
    if blocks:
        pairs += [(0, "SECTION"), (2, "BLOCKS")]
        for block in blocks:
            pairs += block
        pairs += [(0, "ENDSEC")]
    pairs += [(0, "SECTION"), (2, "ENTITIES")]
    for entity in entities:
        if entity and entity[0] != (0, "BLOCK"):
            pairs += entity
    pairs += [(0, "ENDSEC"), (0, "EOF")]
    return "".join(f"{code:>3}\n{value}\n" for code, value in pairs)


def line(x0, y0, x1, y1, layer="CUT"):
    return [(0, "LINE"), (8, layer), (10, x0), (20, y0), (30, 0.0), (11, x1), (21, y1), (31, 0.0)]


def write(tmp_path, text, name="part.dxf"):
    path = tmp_path / name
    path.write_text(text, encoding="latin-1")
    return str(path)


def test_r12_lines_in_any_order_and_direction_join_into_one_loop(tmp_path):
    text = dxf_text(line(0, 0, 40, 0), line(40, 25, 0, 25), line(40, 0, 40, 25), line(0, 0, 0, 25.000001))
    design = dxffile.read_dxf(write(tmp_path, text))
    (loop,) = design.shapes
    assert loop.closed and loop.layer == "CUT"
    assert abs(area(loop.points)) == pytest.approx(1000) and perimeter(loop.points) == pytest.approx(130, abs=1e-5)
    assert "LINE at line" in loop.source and "and 3 more" in loop.source
    assert design.notes == ()


@pytest.mark.parametrize("units, mm", [(1, 25.4), (4, 1.0), (5, 10.0), (6, 1000.0)])
def test_insunits_to_mm(tmp_path, units, mm):
    text = dxf_text(line(0, 0, 1, 0), line(1, 0, 1, 1), line(1, 1, 0, 1), line(0, 1, 0, 0), units=units)
    (loop,) = dxffile.read_dxf(write(tmp_path, text)).shapes
    assert abs(area(loop.points)) == pytest.approx(mm * mm)


def test_a_file_without_units_is_mm_with_a_note_or_the_scale_given(tmp_path):
    text = dxf_text(line(0, 0, 1, 0), line(1, 0, 1, 1), line(1, 1, 0, 1), line(0, 1, 0, 0), units=None)
    path = write(tmp_path, text)
    design = dxffile.read_dxf(path)
    assert abs(area(design.shapes[0].points)) == pytest.approx(1.0)
    assert any("no units" in note for note in design.notes)
    assert abs(area(dxffile.read_dxf(path, scale=25.4).shapes[0].points)) == pytest.approx(645.16)
    with pytest.raises(DesignFileError, match=r"mm\.dxf: the file says its units \(mm\)"):
        dxffile.read_dxf(write(tmp_path, dxf_text(line(0, 0, 1, 0), units=4), "mm.dxf"), scale=2.0)


def test_circle_r10_area_within_the_tolerance_and_recognised(tmp_path):
    text = dxf_text([(0, "CIRCLE"), (8, "HOLES"), (10, 30.0), (20, 40.0), (30, 0.0), (40, 10.0)], layers=("HOLES",))
    (hole,) = dxffile.read_dxf(write(tmp_path, text)).shapes
    assert hole.circle == pytest.approx((30, 40, 10))
    assert math.pi * 100 - 2 * math.pi * 10 * TOL <= area(hole.points) <= math.pi * 100      # counter-clockwise
    assert np.allclose(np.hypot(hole.points[:, 0] - 30, hole.points[:, 1] - 40), 10, atol=1e-9)


def test_arc_and_mirrored_extrusion(tmp_path):
    arc = [(0, "ARC"), (8, "CUT"), (10, 10.0), (20, 0.0), (40, 5.0), (50, 0.0), (51, 90.0)]
    mirrored = [(0, "CIRCLE"), (8, "CUT"), (10, 10.0), (20, 0.0), (40, 2.0), (210, 0.0), (220, 0.0), (230, -1.0)]
    design = dxffile.read_dxf(write(tmp_path, dxf_text(arc, mirrored)))
    quarter = next(s for s in design.shapes if not s.closed)
    assert quarter.points[0] == pytest.approx([15, 0]) and quarter.points[-1] == pytest.approx([10, 5])
    # chords are shorter than their arcs by about tol / (3 r) of it
    assert 5 * math.pi / 2 * (1 - TOL / 5) <= perimeter(quarter.points, closed=False) <= 5 * math.pi / 2
    circle = next(s for s in design.shapes if s.closed)
    assert circle.circle == pytest.approx((-10, 0, 2))       # X mirrored by the (0, 0, -1) extrusion


def test_lwpolyline_with_bulges_a_slot(tmp_path):
    """A slot 20 long, 10 wide: two straight sides and two half circles (bulge 1 = a half turn,
    counter-clockwise): area 20 x 10 + pi 5^2, perimeter 40 + 2 pi 5."""
    doc = ezdxf.new("R2000")
    doc.header["$INSUNITS"] = 4
    doc.modelspace().add_lwpolyline([(0, 0, 0, 0, 0), (20, 0, 0, 0, 1), (20, 10, 0, 0, 0), (0, 10, 0, 0, 1)],
                                    format="xyseb", close=True, dxfattribs={"layer": "CUT"})
    doc.saveas(tmp_path / "slot.dxf")
    (slot,) = dxffile.read_dxf(str(tmp_path / "slot.dxf")).shapes
    exact_area, exact_perimeter = 200 + math.pi * 25, 40 + 10 * math.pi
    assert exact_area - exact_perimeter * TOL <= area(slot.points) <= exact_area
    assert exact_perimeter - 10 * math.pi * TOL / 5 <= perimeter(slot.points) <= exact_perimeter
    assert slot.points[:, 0].max() == pytest.approx(25, abs=TOL) and slot.points[:, 0].min() == pytest.approx(-5, abs=TOL)


@pytest.mark.parametrize("bulge", [0.25, -0.25, 2.0, -2.0])
def test_a_bulge_arc_against_its_closed_form(tmp_path, bulge):
    """From (0, 0) to (10, 0) with bulge b the arc turns 4 atan b; the chord closes it: the
    segment's area r^2 / 2 (theta - sin theta) with r = c / (2 sin(theta / 2))."""
    text = dxf_text([(0, "LWPOLYLINE"), (8, "CUT"), (90, 2), (70, 1), (10, 0.0), (20, 0.0), (42, bulge),
                     (10, 10.0), (20, 0.0)])
    (piece,) = dxffile.read_dxf(write(tmp_path, text)).shapes
    theta = 4 * math.atan(abs(bulge))
    r = 10 / (2 * math.sin(theta / 2))
    exact = r * r / 2 * (theta - math.sin(theta))
    assert abs(area(piece.points)) == pytest.approx(exact, abs=2 * math.pi * r * TOL)
    assert np.sign(area(piece.points)) == np.sign(bulge)       # the arc out, the chord back: its turning sense
    assert (piece.points[:, 1].min() < -1) == (bulge > 0)          # counter-clockwise from (0,0) to (10,0): below


def test_r12_polyline_with_vertices(tmp_path):
    polyline = [(0, "POLYLINE"), (8, "CUT"), (66, 1), (70, 1), (0, "VERTEX"), (8, "CUT"), (10, 0.0), (20, 0.0),
                (0, "VERTEX"), (8, "CUT"), (10, 30.0), (20, 0.0), (0, "VERTEX"), (8, "CUT"), (10, 30.0), (20, 20.0),
                (0, "SEQEND"), (8, "CUT")]
    (triangle,) = dxffile.read_dxf(write(tmp_path, dxf_text(polyline))).shapes
    assert triangle.closed and area(triangle.points) == pytest.approx(300)


def test_insert_of_a_block_rotated_30_and_scaled_2(tmp_path):
    """A 5 x 5 square block (base point (1, 1)) inserted at (100, 50), rotated 30 deg, scaled 2: a
    10 x 10 square with its base corner on the insertion point, sides along 30 and 120 deg."""
    block = [(0, "BLOCK"), (8, "0"), (2, "SQ"), (70, 0), (10, 1.0), (20, 1.0), (3, "SQ")] + \
        line(1, 1, 6, 1, "0") + line(6, 1, 6, 6, "0") + line(6, 6, 1, 6, "0") + line(1, 6, 1, 1, "0") + \
        [(0, "ENDBLK"), (8, "0")]
    insert = [(0, "INSERT"), (8, "PARTS"), (2, "SQ"), (10, 100.0), (20, 50.0), (41, 2.0), (42, 2.0), (50, 30.0)]
    design = dxffile.read_dxf(write(tmp_path, dxf_text(block, insert, layers=("0", "PARTS"))))
    (square,) = design.shapes
    assert square.layer == "PARTS"                               # layer 0 in a block: the insert's
    assert abs(area(square.points)) == pytest.approx(100)
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    expected = {(100, 50), (100 + 10 * c, 50 + 10 * s), (100 + 10 * c - 10 * s, 50 + 10 * s + 10 * c),
                (100 - 10 * s, 50 + 10 * c)}
    found = {tuple(np.round(p, 6)) for p in square.points}
    assert found == {tuple(np.round(p, 6)) for p in expected}
    assert "of block 'SQ' inserted at line" in square.source


def test_ezdxf_insert_minsert_and_nested_blocks(tmp_path):
    doc = ezdxf.new("R2000")
    doc.header["$INSUNITS"] = 4
    hole = doc.blocks.new("HOLE")
    hole.add_circle((0, 0), 3)
    plate = doc.blocks.new("PLATE")
    plate.add_blockref("HOLE", (10, 0))
    plate.add_blockref("HOLE", (20, 0))
    doc.modelspace().add_blockref("PLATE", (0, 0), dxfattribs={"column_count": 3, "column_spacing": 50,
                                                               "row_count": 2, "row_spacing": 40})
    doc.saveas(tmp_path / "grid.dxf")
    design = dxffile.read_dxf(str(tmp_path / "grid.dxf"))
    centres = sorted((round(s.circle[0], 6), round(s.circle[1], 6)) for s in design.shapes)
    assert centres == sorted((10.0 + dx + 50 * c, 40.0 * r) for c in range(3) for r in range(2) for dx in (0, 10))
    assert all(s.circle[2] == pytest.approx(3) for s in design.shapes)


def test_spline_against_ezdxf_evaluation_and_a_parabola(tmp_path):
    doc = ezdxf.new("R2000")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    wavy = msp.add_spline(dxfattribs={"layer": "CUT"})
    wavy.dxf.degree = 3
    wavy.control_points = [(0, 0), (10, 30), (30, -20), (50, 25), (70, 0), (90, 10)]
    wavy.knots = [0, 0, 0, 0, 1, 2, 3, 3, 3, 3]
    parabola = msp.add_spline(dxfattribs={"layer": "PARABOLA"})
    parabola.dxf.degree = 2
    parabola.control_points = [(0, 0), (5, 10), (10, 0)]
    parabola.knots = [0, 0, 0, 1, 1, 1]
    doc.saveas(tmp_path / "spline.dxf")
    design = dxffile.read_dxf(str(tmp_path / "spline.dxf"))
    ours = design.open_paths("CUT")[0]
    reference = np.array([(p.x, p.y) for p in wavy.construction_tool().points(np.linspace(0, 3, 601))])
    a, b = ours[:-1], ours[1:]

    def distance(q):
        ab = b - a
        t = np.clip(((q - a) * ab).sum(1) / (ab * ab).sum(1), 0, 1)
        return np.hypot(*(a + t[:, None] * ab - q).T).min()
    assert max(distance(q) for q in reference) <= TOL
    assert ours[0] == pytest.approx([0, 0]) and ours[-1] == pytest.approx([90, 10])
    # a clamped quadratic with controls (0,0) (5,10) (10,0): x = 10 t, y = 20 t (1 - t), a parabola
    curve = design.open_paths("PARABOLA")[0]
    assert np.allclose(curve[:, 1], 2 * curve[:, 0] * (1 - curve[:, 0] / 10), atol=1e-9)


def test_spline_through_fit_points_only_passes_through_them(tmp_path):
    fit = [(0, 0), (10, 5), (20, 0), (30, 5)]
    groups = [(0, "SPLINE"), (8, "CUT"), (70, 8), (71, 3), (72, 0), (73, 0), (74, 4)]
    for x, y in fit:
        groups += [(11, float(x)), (21, float(y)), (31, 0.0)]
    (curve,) = dxffile.read_dxf(write(tmp_path, dxf_text(groups))).shapes
    for point in fit:
        assert np.hypot(*(curve.points - point).T).min() < 1e-9


def test_ellipse_area(tmp_path):
    doc = ezdxf.new("R2000")
    doc.header["$INSUNITS"] = 4
    doc.modelspace().add_ellipse((50, 20), major_axis=(0, 30), ratio=0.5)
    doc.saveas(tmp_path / "ellipse.dxf")
    (ellipse,) = dxffile.read_dxf(str(tmp_path / "ellipse.dxf")).shapes
    exact = math.pi * 30 * 15
    assert exact * (1 - 1e-3) <= abs(area(ellipse.points)) <= exact
    assert ellipse.points[:, 1].max() == pytest.approx(50) and ellipse.points[:, 0].max() == pytest.approx(65, abs=TOL)


def test_layers_off_layers_skipped_and_texts_noted(tmp_path):
    text = dxf_text(line(0, 0, 10, 0, "OFF_NOTES") + [], [(0, "TEXT"), (8, "CUT"), (10, 0.0), (20, 0.0), (40, 3.0),
                                                         (1, "PART 7")],
                    [(0, "CIRCLE"), (8, "CUT"), (10, 0.0), (20, 0.0), (40, 4.0)], layers=("CUT", "OFF_NOTES"))
    design = dxffile.read_dxf(write(tmp_path, text))
    assert [s.layer for s in design.shapes] == ["CUT"]
    assert any("TEXT" in note and "line" in note for note in design.notes)
    assert any("OFF_NOTES" in note for note in design.notes)


def test_r2000_file_from_ezdxf_with_every_kind(tmp_path):
    doc = ezdxf.new("R2000")
    doc.header["$INSUNITS"] = 1                              # inches
    msp = doc.modelspace()
    msp.add_circle((1, 1), 0.5, dxfattribs={"layer": "HOLES"})
    msp.add_lwpolyline([(0, 0), (4, 0), (4, 2), (0, 2)], close=True, dxfattribs={"layer": "OUTLINE"})
    doc.saveas(tmp_path / "inch.dxf")
    design = dxffile.read_dxf(str(tmp_path / "inch.dxf"))
    assert design.layers() == ["HOLES", "OUTLINE"]
    assert design.shapes[0].circle == pytest.approx((25.4, 25.4, 12.7))
    assert abs(area(design.loops("OUTLINE")[0])) == pytest.approx(8 * 25.4 ** 2)


def test_periodic_closed_and_rational_splines_against_ezdxf(tmp_path):
    doc = ezdxf.new("R2000")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    periodic = msp.add_spline(dxfattribs={"layer": "LOOP"})      # a closed cubic: 4 points wrapped round
    periodic.dxf.degree = 3
    periodic.control_points = [(0, 0), (20, 0), (20, 20), (0, 20), (0, 0), (20, 0), (20, 20)]
    periodic.knots = list(range(11))
    periodic.closed = True
    rational = msp.add_rational_spline([(0, 0), (10, 10), (20, 0)], [1, 0.7071, 1], degree=2,
                                       dxfattribs={"layer": "ARC"})
    doc.saveas(tmp_path / "splines.dxf")
    design = dxffile.read_dxf(str(tmp_path / "splines.dxf"))
    (loop,) = design.loops("LOOP")
    (arc,) = design.open_paths("ARC")
    for ours, entity in ((np.vstack([loop, loop[:1]]), periodic), (arc, rational)):
        tool = entity.construction_tool()
        reference = np.array([(p.x, p.y) for p in tool.approximate(400)])
        a, b = ours[:-1], ours[1:]
        ab = b - a
        for q in reference:
            t = np.clip(((q - a) * ab).sum(1) / (ab * ab).sum(1), 0, 1)
            assert np.hypot(*(a + t[:, None] * ab - q).T).min() <= TOL
    # the closed cubic B-spline of that square's corners runs through (16.667, 3.333) ... (3.333, 16.667)
    assert np.hypot(loop[:, 0] - 50 / 3, loop[:, 1] - 10 / 3).min() < 1e-6


def test_r2000_lwpolyline_written_by_hand_with_handles_and_subclass_markers(tmp_path):
    """As AutoCAD 2000+ writes it: handle (5), owner (330), subclass markers (100), constant width
    (43), elevation (38), per-vertex widths (40/41) between the coordinates and the bulge."""
    groups = [(0, "LWPOLYLINE"), (5, "2F"), (330, "1F"), (100, "AcDbEntity"), (8, "CUT"), (100, "AcDbPolyline"),
              (90, 4), (70, 1), (43, 0.0), (38, 0.0),
              (10, 0.0), (20, 0.0), (40, 0.0), (41, 0.0),
              (10, 30.0), (20, 0.0), (40, 0.0), (41, 0.0), (42, 0.41421356237),     # tan(22.5 deg): a quarter turn
              (10, 40.0), (20, 10.0),
              (10, 0.0), (20, 10.0)]
    (part,) = dxffile.read_dxf(write(tmp_path, dxf_text(groups))).shapes
    # the 30 x 10 rectangle, the triangle (30,0)-(40,10)-(30,10), and beyond its chord the segment of a
    # quarter turn of r = 10 about (30, 10): 300 + 50 + r^2 / 2 (pi / 2 - sin(pi / 2))
    segment = 100 / 2 * (math.pi / 2 - 1)
    exact = 300 + 50 + segment
    assert exact - 2 * math.pi * 10 * TOL <= area(part.points) <= exact


def test_paper_space_entities_are_left_out(tmp_path):
    frame = [(0, "LWPOLYLINE"), (67, 1), (8, "CUT"), (90, 4), (70, 1), (10, 0.0), (20, 0.0), (10, 420.0), (20, 0.0),
             (10, 420.0), (20, 297.0), (10, 0.0), (20, 297.0)]
    part = [(0, "CIRCLE"), (8, "CUT"), (10, 0.0), (20, 0.0), (40, 4.0)]
    design = dxffile.read_dxf(write(tmp_path, dxf_text(frame, part)))
    assert [s.circle for s in design.shapes] == [pytest.approx((0, 0, 4))]
    assert any("1 LWPOLYLINE in paper space" in note for note in design.notes)
