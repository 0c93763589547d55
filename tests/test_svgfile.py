"""SVG drawings read into loops in mm (toolpath/engines/svgfile.py), checked against closed forms.

The files are written here in the conventions Inkscape 1.x and Illustrator write (an Inkscape
file: width/height in mm with a viewBox in mm, layers as <g inkscape:groupmode="layer">, arcs
as sodipodi:type="arc" paths; an Illustrator file: width/height in pt or px, the old
<!ENTITY ns_svg ...> declarations, top-level groups id="Layer_1")."""
import math

import numpy as np
import pytest

from kezuri.toolpath.engines import svgfile
from kezuri.toolpath.engines.region import ARC_TOLERANCE

TOL = ARC_TOLERANCE

INKSCAPE = """<?xml version="1.0" encoding="UTF-8" standalone="no"?>
<!-- Created with Inkscape (http://www.inkscape.org/) -->
<svg width="100mm" height="50mm" viewBox="0 0 100 50" version="1.1" id="svg5"
   inkscape:version="1.2.2 (b0a8486541, 2022-12-01)" sodipodi:docname="sign.svg"
   xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
   xmlns:sodipodi="http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd"
   xmlns="http://www.w3.org/2000/svg" xmlns:svg="http://www.w3.org/2000/svg">
  <sodipodi:namedview id="namedview7" pagecolor="#ffffff" inkscape:document-units="mm"/>
  <defs id="defs2">
    <path id="star" d="M 0,0 H 4 V 3 H 0 Z"/>
  </defs>
  <g inkscape:label="Cut" inkscape:groupmode="layer" id="layer1">
    <circle style="fill:none;stroke:#000000;stroke-width:0.264583" id="hole" cx="50" cy="15" r="10"/>
    <rect id="frame" width="30" height="20" x="2" y="25" rx="5"/>
    <path sodipodi:type="arc" sodipodi:cx="80" sodipodi:cy="25" sodipodi:rx="5" sodipodi:ry="5"
       sodipodi:start="0" sodipodi:end="3.1415927" sodipodi:open="true" sodipodi:arc-type="arc"
       id="half" d="M 85,25 A 5,5 0 0 1 80,30 5,5 0 0 1 75,25"/>
  </g>
  <g inkscape:groupmode="layer" id="layer2" inkscape:label="Guides" style="display:none">
    <rect id="guide" width="100" height="50" x="0" y="0"/>
  </g>
  <g inkscape:groupmode="layer" id="layer3" inkscape:label="Pocket" transform="translate(60,10)">
    <g id="turned" transform="rotate(30) scale(2,1)">
      <rect id="box" width="10" height="5" x="0" y="0"/>
    </g>
    <use xlink:href="#star" x="20" y="30" id="use1" xmlns:xlink="http://www.w3.org/1999/xlink"/>
    <text x="0" y="0" id="label">CUT</text>
  </g>
</svg>
"""


def write(tmp_path, text, name="design.svg"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def svg(body, head='width="100mm" height="100mm" viewBox="0 0 100 100"'):
    return f'<svg xmlns="http://www.w3.org/2000/svg" {head}>{body}</svg>'


def area(points):
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def perimeter(points, closed=True):
    pts = np.vstack([points, points[:1]]) if closed else points
    return float(np.hypot(*np.diff(pts, axis=0).T).sum())


def shape(design, source_part):
    found = [s for s in design.shapes if source_part in s.source]
    assert len(found) == 1, [s.source for s in design.shapes]
    return found[0]


@pytest.fixture
def inkscape(tmp_path):
    return svgfile.read_svg(write(tmp_path, INKSCAPE, "sign.svg"))


def test_inkscape_layers_hidden_layer_skipped_and_text_noted(inkscape):
    assert inkscape.layers() == ["Cut", "Pocket"]
    assert not any("guide" in s.source for s in inkscape.shapes)
    assert any("<text id='label'>" in note and "line" in note for note in inkscape.notes)


def test_circle_of_radius_10_area_and_vertices_within_the_tolerance(inkscape):
    hole = shape(inkscape, "id='hole'")
    assert hole.closed and hole.layer == "Cut"
    # Y up: cy = 15 below the top of a 50 mm page is 35 mm above its bottom
    assert hole.circle == pytest.approx((50.0, 35.0, 10.0))
    radii = np.hypot(hole.points[:, 0] - 50, hole.points[:, 1] - 35)
    assert np.allclose(radii, 10.0, atol=1e-9)
    exact = math.pi * 100                                    # 314.159
    assert exact - 2 * math.pi * 10 * TOL <= abs(area(hole.points)) <= exact
    # chords: the sagitta of each is within the tolerance
    chord = np.hypot(*np.diff(np.vstack([hole.points, hole.points[:1]]), axis=0).T)
    assert np.all(10 - np.sqrt(100 - (chord / 2) ** 2) <= TOL + 1e-12)


def test_rounded_rect_area_closed_form(inkscape):
    frame = shape(inkscape, "id='frame'")
    exact = 30 * 20 - (4 - math.pi) * 5 ** 2              # corners of r = 5 cut off
    assert exact - 2 * math.pi * 5 * TOL <= abs(area(frame.points)) <= exact + 1e-9
    assert frame.points[:, 0].min() == pytest.approx(2) and frame.points[:, 0].max() == pytest.approx(32)
    assert frame.points[:, 1].min() == pytest.approx(50 - 45) and frame.points[:, 1].max() == pytest.approx(50 - 25)


def test_inkscape_open_arc_is_a_half_circle_on_the_screen_bottom_half(inkscape):
    half = shape(inkscape, "id='half'")
    assert not half.closed
    assert perimeter(half.points, closed=False) == pytest.approx(5 * math.pi, abs=5 * math.pi * 1e-3)
    radii = np.hypot(half.points[:, 0] - 80, half.points[:, 1] - 25)
    assert np.allclose(radii, 5, atol=1e-9)
    # SVG's y = 30 (screen: below the centre) is y = 20 in the design (Y up)
    assert half.points[:, 1].min() == pytest.approx(20, abs=1e-6) and half.points[:, 1].max() == pytest.approx(25)


def test_transformed_group_rotated_30_and_scaled(inkscape):
    box = shape(inkscape, "id='box'")
    assert abs(area(box.points)) == pytest.approx(10 * 2 * 5)
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    # corner (10, 0) of the rect: scale -> (20, 0), rotate 30 -> (20c, 20s), translate -> +(60, 10); Y flipped
    corner = (60 + 20 * c, 50 - (10 + 20 * s))
    assert np.min(np.hypot(box.points[:, 0] - corner[0], box.points[:, 1] - corner[1])) < 1e-9
    assert box.layer == "Pocket"


def test_use_of_a_defs_path_shifted_by_its_x_and_y(inkscape):
    used = shape(inkscape, "id='star'")
    assert abs(area(used.points)) == pytest.approx(12)
    assert used.points[:, 0].min() == pytest.approx(80) and used.points[:, 1].max() == pytest.approx(50 - 40)


def test_units_a_100_mm_page_with_viewbox_0_0_1000_500(tmp_path):
    text = svg('<rect x="0" y="0" width="1000" height="500"/><path d="M 0 0 L 100 0 L 0 100 Z"/>',
               'width="100mm" height="50mm" viewBox="0 0 1000 500"')
    design = svgfile.read_svg(write(tmp_path, text))
    page, corner = design.shapes
    assert page.points.min(axis=0) == pytest.approx([0, 0]) and page.points.max(axis=0) == pytest.approx([100, 50])
    assert abs(area(page.points)) == pytest.approx(5000)
    # the triangle in the SVG's top-left corner is at the design's top-left (Y up)
    assert sorted(map(tuple, np.round(corner.points, 9))) == [(0.0, 40.0), (0.0, 50.0), (10.0, 50.0)]


@pytest.mark.parametrize("head, side_mm", [
    ('width="72pt" height="72pt" viewBox="0 0 72 72"', 25.4),             # Illustrator in points
    ('width="96px" height="96px" viewBox="0 0 96 96"', 25.4),             # Illustrator in px: 96 px = 1 in
    ('width="96" height="96"', 25.4),                                     # bare numbers are px
    ('viewBox="0 0 96 96"', 25.4),                                        # no size: user units are px
    ('width="2in" height="2in" viewBox="0 0 96 96"', 50.8),
    ('width="10cm" height="10cm" viewBox="0 0 96 96"', 100.0),
])
def test_page_units(tmp_path, head, side_mm):
    design = svgfile.read_svg(write(tmp_path, svg('<rect width="96" height="96"/>' if "72pt" not in head
                                                  else '<rect width="72" height="72"/>', head)))
    (square,) = design.shapes
    assert square.points.max(axis=0) - square.points.min(axis=0) == pytest.approx([side_mm, side_mm])


ILLUSTRATOR = """<?xml version="1.0" encoding="utf-8"?>
<!-- Generator: Adobe Illustrator 16.0.0, SVG Export Plug-In . SVG Version: 6.00 Build 0)  -->
<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" "http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd" [
	<!ENTITY ns_extend "http://ns.adobe.com/Extensibility/1.0/">
	<!ENTITY ns_ai "http://ns.adobe.com/AdobeIllustrator/10.0/">
	<!ENTITY ns_graphs "http://ns.adobe.com/Graphs/1.0/">
]>
<svg version="1.1" id="Layer_1" xmlns:x="&ns_extend;" xmlns:i="&ns_ai;" xmlns:graph="&ns_graphs;"
	 xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" x="0px" y="0px" width="144pt"
	 height="72pt" viewBox="0 0 144 72" enable-background="new 0 0 144 72" xml:space="preserve">
<g id="Layer_1_1_">
	<polygon fill="none" stroke="#000000" points="10,10 70,10 70,40 10,40 	"/>
	<ellipse fill="none" stroke="#000000" cx="110" cy="36" rx="20" ry="10"/>
	<polyline fill="none" stroke="#000000" points="10,60 130,60"/>
	<line fill="none" stroke="#000000" x1="130" y1="60" x2="130" y2="70"/>
</g>
<g id="Cut" data-name="Cut">
	<path fill="none" stroke="#000000" d="M20.5,50.5c0,5.5-4.5,10-10,10s-10-4.5-10-10s4.5-10,10-10S20.5,45,20.5,50.5z"/>
</g>
</svg>
"""


def test_illustrator_file_with_entities_points_and_its_layers(tmp_path):
    design = svgfile.read_svg(write(tmp_path, ILLUSTRATOR))
    pt = 25.4 / 72
    box = shape(design, "<polygon>")
    assert abs(area(box.points)) == pytest.approx(60 * 30 * pt * pt)
    ellipse = shape(design, "<ellipse>")
    exact = math.pi * 20 * 10 * pt * pt
    assert exact * (1 - 2e-3) <= abs(area(ellipse.points)) <= exact
    assert design.layers() == ["", "Cut"]
    # four cubic quarters of r = 10 pt with controls 5.5 pt out (c, s, s, S): the area of those cubics,
    # sampled finely here, within the flattening tolerance along the outline
    round_one = shape(design, "<path>")
    t = np.linspace(0, 1, 20001)[:, None]
    quarters = [[(20.5, 50.5), (20.5, 56), (16, 60.5), (10.5, 60.5)], [(10.5, 60.5), (5, 60.5), (0.5, 56), (0.5, 50.5)],
                [(0.5, 50.5), (0.5, 45), (5, 40.5), (10.5, 40.5)], [(10.5, 40.5), (16, 40.5), (20.5, 45), (20.5, 50.5)]]
    fine = np.vstack([(1 - t) ** 3 * np.array(a) + 3 * (1 - t) ** 2 * t * np.array(b) + 3 * (1 - t) * t ** 2 * np.array(c)
                      + t ** 3 * np.array(d) for a, b, c, d in quarters]) * pt
    assert abs(area(round_one.points)) == pytest.approx(abs(area(fine)), abs=perimeter(fine) * TOL)
    assert abs(area(fine)) == pytest.approx(math.pi * 100 * pt * pt, rel=5e-3)     # nearly a circle
    assert round_one.layer == "Cut"
    # the polyline and the line join into one open piece
    (opened,) = [s for s in design.shapes if not s.closed]
    assert perimeter(opened.points, closed=False) == pytest.approx(130 * pt)


def segment_area(r, chord):
    theta = 2 * math.asin(chord / 2 / r)
    return r * r / 2 * (theta - math.sin(theta))


@pytest.mark.parametrize("large, sweep", [(0, 0), (0, 1), (1, 0), (1, 1)])
def test_arc_flags_large_and_sweep(tmp_path, large, sweep):
    """An arc of r = 10 from (40, 50) to (50, 50), closed by its chord: the small segment or the large
    one, on the side the sweep flag says (sweep 1: clockwise on the screen, Y down)."""
    design = svgfile.read_svg(write(tmp_path, svg(f'<path d="M 40 50 A 10 10 0 {large} {sweep} 50 50 Z"/>')))
    (seg,) = design.shapes
    small = segment_area(10, 10)
    exact = math.pi * 100 - small if large else small
    assert abs(area(seg.points)) == pytest.approx(exact, abs=2 * math.pi * 10 * TOL)
    # from left to right, clockwise on the screen goes over the top (the small arc and the large one
    # alike: the flag picks the centre): above the chord with Y up, the chord the lowest line
    above = sweep == 1
    ys = seg.points[:, 1] - 50
    assert (ys.max() > 1 and ys.min() > -1e-9) if above else (ys.min() < -1 and ys.max() < 1e-9)
    assert (ys.max() - ys.min() if above else -ys.min()) == pytest.approx(
        10 + 10 * math.cos(math.pi / 6) if large else 10 - 10 * math.cos(math.pi / 6), abs=TOL)


def test_path_number_syntax_and_implicit_repeats(tmp_path):
    design = svgfile.read_svg(write(tmp_path, svg(
        '<path d="M0,0 10,0 10,10 0,10z"/>'               # pairs after M are linetos
        '<path d="m20-0 1e1.0 0 10-10-0z"/>'              # 1e1 then .0; - starts a number
        '<path d="M40 0h10v10h-10Z m 20 0 l5 0 0 5 -5 0 z"/>'
        '<path d="M70,0 l-.5.5"/>')))                     # -.5 and .5
    first, second, third, fourth, line = design.shapes
    for square in (first, second, third):
        assert abs(area(square.points)) == pytest.approx(100)
    assert second.points.min(axis=0) == pytest.approx([20, 90]) and second.points.max(axis=0) == pytest.approx([30, 100])
    assert fourth.points.min(axis=0) == pytest.approx([60, 95])       # relative m after z: from the subpath's start
    assert abs(area(fourth.points)) == pytest.approx(25)
    assert line.points == pytest.approx(np.array([[70, 100], [69.5, 99.5]]))


def polyline_distance(points, q):
    a, b = points[:-1], points[1:]
    ab = b - a
    t = np.clip(((q - a) * ab).sum(1) / np.maximum((ab * ab).sum(1), 1e-300), 0, 1)
    return float(np.hypot(*(a + t[:, None] * ab - q).T).min())


def test_smooth_curves_reflect_the_previous_control_point(tmp_path):
    design = svgfile.read_svg(write(tmp_path, svg('<path d="M0 50 C 0 40 10 40 10 50 S 20 60 20 50"/>'
                                                  '<path d="M30 50 Q 35 40 40 50 T 50 50"/>')))
    cubic, quad = design.shapes
    # the S segment: controls (10, 60) (reflected), (20, 60); its middle (P0 + 3 P1 + 3 P2 + P3) / 8
    mid = np.array([(10 + 30 + 60 + 20) / 8, (50 + 180 + 180 + 50) / 8])
    assert polyline_distance(cubic.points, (mid[0], 100 - mid[1])) <= TOL
    # the T segment: control (45, 60), its middle (P0 + 2 P1 + P2) / 4
    mid = np.array([(40 + 90 + 50) / 4, (50 + 120 + 50) / 4])
    assert polyline_distance(quad.points, (mid[0], 100 - mid[1])) <= TOL


def test_compact_arc_flags_touch_the_next_number(tmp_path):
    compact = svgfile.read_svg(write(tmp_path, svg('<path d="M10 50a10 10 0 1020 0z"/>')))
    spaced = svgfile.read_svg(write(tmp_path, svg('<path d="M10 50 a 10 10 0 1 0 20 0 z"/>'), "b.svg"))
    assert compact.shapes[0].points == pytest.approx(spaced.shapes[0].points)
    assert abs(area(compact.shapes[0].points)) == pytest.approx(math.pi * 50, abs=0.5)


def test_transforms_matrix_skew_and_rotate_about_a_point(tmp_path):
    design = svgfile.read_svg(write(tmp_path, svg(
        '<rect width="10" height="10" transform="matrix(1 0 0 1 5 5)"/>'
        '<rect width="10" height="10" transform="skewX(45)"/>'
        '<rect x="40" y="40" width="10" height="10" transform="rotate(90, 45 45)"/>'
        '<g transform="translate(50 0)"><g transform="scale(.5)"><rect width="10" height="10"/></g></g>')))
    shifted, skewed, turned, nested = design.shapes
    assert shifted.points.min(axis=0) == pytest.approx([5, 85])
    assert abs(area(skewed.points)) == pytest.approx(100) and skewed.points[:, 0].max() == pytest.approx(20)
    assert turned.points.min(axis=0) == pytest.approx([40, 50]) and turned.points.max(axis=0) == pytest.approx([50, 60])
    assert nested.points.min(axis=0) == pytest.approx([50, 95]) and abs(area(nested.points)) == pytest.approx(25)


def test_lines_drawn_separately_join_into_a_loop(tmp_path):
    design = svgfile.read_svg(write(tmp_path, svg(
        '<line x1="0" y1="0" x2="10" y2="0"/><line x1="10" y1="10" x2="10" y2="0"/>'
        '<line x1="10" y1="10" x2="0" y2="10"/><path d="M0 10.004 V 0"/>')))
    (loop,) = design.shapes
    assert loop.closed and abs(area(loop.points)) == pytest.approx(100, abs=0.1)
