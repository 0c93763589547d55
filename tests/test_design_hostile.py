"""Hostile drawing files: every one is refused with a DesignFileError naming the file and the element
or entity (and its line), quickly: never a traceback, never a hang, never a silent wrong design."""
import os
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from kezuri.toolpath.engines import dxffile, svgfile
from kezuri.toolpath.engines.designshapes import DesignFileError, PointBudget
from kezuri.toolpath.engines.svgpath import PathData, transform_matrix
from test_dxffile import dxf_text, line
from test_hostile import time_limit


def write(tmp_path, text, name):
    path = tmp_path / name
    path.write_bytes(text if isinstance(text, bytes) else text.encode("utf-8"))
    return str(path)


def svg(body, head='width="100mm" height="100mm" viewBox="0 0 100 100"'):
    return f'<svg xmlns="http://www.w3.org/2000/svg" {head}>{body}</svg>'


BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE svg [
 <!ENTITY lol "lol">
 <!ENTITY lol1 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
 <!ENTITY lol2 "&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;">
 <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
 <!ENTITY lol9 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
]>
<svg xmlns="http://www.w3.org/2000/svg"><desc>&lol9;</desc></svg>
"""


def test_billion_laughs_is_refused_quickly(tmp_path):
    started = time.perf_counter()
    with time_limit(5), pytest.raises(DesignFileError, match=r"laughs\.svg: line 4: entity 'lol1'.*refers to others"):
        svgfile.read_svg(write(tmp_path, BILLION_LAUGHS, "laughs.svg"))
    assert time.perf_counter() - started < 1.0


@pytest.mark.parametrize("declaration", ['<!ENTITY xxe SYSTEM "file:///etc/passwd">',
                                         '<!ENTITY % remote SYSTEM "http://example.com/evil.dtd">'])
def test_external_and_parameter_entities_are_refused(tmp_path, declaration):
    text = f'<?xml version="1.0"?>\n<!DOCTYPE svg [\n {declaration}\n]>\n' + svg('<desc>x</desc>')
    with pytest.raises(DesignFileError, match=r"evil\.svg: line 3: entity .*external and parameter entities"):
        svgfile.read_svg(write(tmp_path, text, "evil.svg"))


def test_a_million_point_path_is_refused_naming_the_element(tmp_path):
    d = "M0 0 " + " ".join(f"L{i % 100} {i % 97}" for i in range(1_000_000))
    path = write(tmp_path, svg(f'<path id="scan" d="{d}"/>'), "scan.svg")
    started = time.perf_counter()
    with time_limit(60), pytest.raises(DesignFileError, match=r"scan\.svg: <path id='scan'> \(line 1\): the design "
                                                              r"has more than 500000 points"):
        svgfile.read_svg(path)
    assert time.perf_counter() - started < 30


@pytest.mark.parametrize("cut", [0.3, 0.6, 0.95])
def test_truncated_svg(tmp_path, cut):
    text = svg('<g id="a"><path d="M0 0 L10 0 L10 10 Z"/><circle cx="5" cy="5" r="3"/></g>')
    with pytest.raises(DesignFileError, match=r"cut\.svg: not well-formed XML .*line 1"):
        svgfile.read_svg(write(tmp_path, text[:int(len(text) * cut)], "cut.svg"))


@pytest.mark.parametrize("body, message", [
    ('<circle id="c" cx="nan" cy="0" r="3"/>', r"<circle id='c'> \(line 1\): cx='nan' is not a length"),
    ('<circle id="c" cx="1e999" cy="0" r="3"/>', r"<circle id='c'> \(line 1\): cx='1e999' is not a finite number"),
    ('<path id="p" d="M0 0 L inf 0"/>', r"<path id='p'> \(line 1\): path data: 'i' is not a number at character 8"),
    ('<path id="p" d="M0 0 L 1e400 0"/>', r"<path id='p'> \(line 1\): path data: the number 1e400 is too large"),
    ('<path id="p" d="L 10 10"/>', r"path data must begin with a moveto"),
    ('<path id="p" d="M0 0 A 5 5 0 2 0 10 0"/>', r"an arc flag must be 0 or 1 at character 14"),
    ('<path id="p" d="M0 0 L10"/>', r"path data: a number is missing"),
    ('<rect id="r" width="10" height="10" transform="scale(nan)"/>', r"<rect id='r'>.*holds something not a number"),
    ('<rect id="r" width="10" height="10" transform="rotate(1e999)"/>', r"<rect id='r'>.*a number is too large"),
    ('<rect id="r" width="10" height="10" transform="spin(3)"/>', r"<rect id='r'>.*cannot read it"),
    ('<polygon id="q" points="0,0 10,0 10"/>', r"<polygon id='q'> \(line 1\): points must be pairs of numbers"),
    ('<use id="u" href="#nothing"/>', r"<use id='u'> \(line 1\): href='#nothing' names no element"),
    ('<g id="g"><use id="u" href="#g"/></g>', r"<use id='u'> \(line 1\): href='#g' uses itself"),
    ('<path id="far" d="M0 0 L 1e9 0"/>', r"<path id='far'> \(line 1\): a point lies .* mm from the origin"),
])
def test_bad_svg_values_name_the_element_and_line(tmp_path, body, message):
    with time_limit(10), pytest.raises(DesignFileError, match=r"bad\.svg: .*" + message):
        svgfile.read_svg(write(tmp_path, svg(body), "bad.svg"))


def test_not_svg_and_empty_and_only_text(tmp_path):
    with pytest.raises(DesignFileError, match=r"x\.svg: not an SVG drawing \(the root element is <html>\)"):
        svgfile.read_svg(write(tmp_path, "<html/>", "x.svg"))
    with pytest.raises(DesignFileError, match=r"t\.svg: no lines or curves to cut \(t\.svg: <text> \(line 1\): a text"):
        svgfile.read_svg(write(tmp_path, svg("<text>hi</text>"), "t.svg"))
    with pytest.raises(DesignFileError, match=r"nothing\.svg: no such file"):
        svgfile.read_svg(str(tmp_path / "nothing.svg"))


def test_uses_of_uses_cannot_explode(tmp_path):
    body = '<defs><g id="a0"><path d="M0 0 L1 1"/></g>'
    for level in range(1, 12):
        body += f'<g id="a{level}">' + "".join(f'<use href="#a{level - 1}"/>' for _ in range(10)) + "</g>"
    body += '</defs><use href="#a11"/>'
    with time_limit(30), pytest.raises(DesignFileError, match=r"boom\.svg: .*(more than|points)"):
        svgfile.read_svg(write(tmp_path, svg(body), "boom.svg"))


def test_deep_nesting_is_refused(tmp_path):
    body = "<g>" * 5000 + '<path d="M0 0 L1 1"/>' + "</g>" * 5000
    with time_limit(10), pytest.raises(DesignFileError, match=r"deep\.svg: line 1: elements nested more than 200"):
        svgfile.read_svg(write(tmp_path, svg(body), "deep.svg"))


PATH_ALPHABET = "MmLlHhVvCcSsQqTtAaZz0123456789.-+eE ,"


@settings(max_examples=400, deadline=2000, suppress_health_check=[HealthCheck.too_slow])
@given(st.text(alphabet=PATH_ALPHABET, max_size=120))
def test_any_path_string_reads_or_is_refused_by_name(text):
    with time_limit(5):
        try:
            subpaths = PathData(text, "fuzz.svg: <path>", 0.01, PointBudget("fuzz.svg")).subpaths()
        except DesignFileError as error:
            assert str(error).startswith("fuzz.svg: <path>: ")
            return
    for points, _ in subpaths:
        assert np.all(np.isfinite(points)) or np.any(np.abs(points) > 1e300)


@settings(max_examples=200, deadline=2000)
@given(st.lists(st.tuples(st.sampled_from("MLHVCSQTAZmlhvcsqtaz"),
                          st.lists(st.floats(-1e4, 1e4, allow_nan=False), min_size=7, max_size=7)), max_size=12))
def test_well_formed_paths_give_finite_points(commands):
    from kezuri.toolpath.engines.svgpath import PARAMETERS
    parts = ["M 1 2"]
    for letter, values in commands:
        kinds = PARAMETERS[letter.lower()]
        parts.append(letter + " " + " ".join(("1" if v > 0 else "0") if k == "f" else repr(v)
                                             for k, v in zip(kinds, values)))
    with time_limit(5):
        try:
            subpaths = PathData(" ".join(parts), "w", 0.01, PointBudget("w")).subpaths()
        except DesignFileError as error:
            assert "more than" in str(error)          # a huge arc at 0.01 mm: the point budget
            return
    for points, _ in subpaths:
        assert np.all(np.isfinite(points))


@settings(max_examples=200, deadline=1000)
@given(st.text(alphabet="matrixtranslatescalerotateskewXY()0123456789.-e ,", max_size=60))
def test_any_transform_string_reads_or_is_refused_by_name(text):
    try:
        matrix = transform_matrix(text, "f.svg: <g>")
    except DesignFileError as error:
        assert str(error).startswith("f.svg: <g>: transform")
        return
    assert matrix.shape == (3, 3)


# ----- DXF ---------------------------------------------------------------------------------------------

def good_dxf():
    return dxf_text(line(0, 0, 10, 0), line(10, 0, 10, 10), line(10, 10, 0, 10), line(0, 10, 0, 0),
                    [(0, "CIRCLE"), (8, "CUT"), (10, 5.0), (20, 5.0), (40, 2.0)])


@pytest.mark.parametrize("cut", [0.2, 0.5, 0.8, 0.97])
def test_truncated_dxf(tmp_path, cut):
    text = good_dxf()
    path = write(tmp_path, text[:int(len(text) * cut)], "cut.dxf")
    with time_limit(10), pytest.raises(DesignFileError, match=r"cut\.dxf: .*(cut short|group code)"):
        dxffile.read_dxf(path)


@pytest.mark.parametrize("value, message", [("nan", "is not a finite number"), ("inf", "is not a finite number"),
                                            ("-1e999", "is not a finite number"), ("12,5", "is not a number")])
def test_nan_and_inf_coordinates_name_the_entity_and_line(tmp_path, value, message):
    text = good_dxf().replace(" 10\n5.0\n", f" 10\n{value}\n", 1)
    with pytest.raises(DesignFileError, match=r"bad\.dxf: CIRCLE at line \d+: line \d+: group 10 = .* " + message):
        dxffile.read_dxf(write(tmp_path, text, "bad.dxf"))


def test_an_unknown_entity_is_skipped_and_named(tmp_path):
    text = dxf_text(line(0, 0, 10, 0), [(0, "FOOBAR"), (8, "CUT"), (10, 1.0)])
    design = dxffile.read_dxf(write(tmp_path, text, "odd.dxf"))
    assert any(note.startswith("odd.dxf: skipped 1 FOOBAR (an entity this reader does not know), first at line ")
               for note in design.notes)
    only = dxf_text([(0, "FOOBAR"), (8, "CUT"), (10, 1.0)])
    with pytest.raises(DesignFileError, match=r"only\.dxf: no lines or curves to cut \(.*FOOBAR"):
        dxffile.read_dxf(write(tmp_path, only, "only.dxf"))


@pytest.mark.parametrize("entities, message", [
    ([[(0, "INSERT"), (8, "0"), (2, "NOPE"), (10, 0.0), (20, 0.0)]], r"INSERT at line \d+: block 'NOPE' is not in"),
    ([[(0, "BLOCK"), (2, "LOOP"), (10, 0.0), (20, 0.0), (0, "INSERT"), (8, "0"), (2, "LOOP"), (10, 1.0), (20, 0.0),
       (0, "ENDBLK")], [(0, "INSERT"), (8, "0"), (2, "LOOP"), (10, 0.0), (20, 0.0)]],
     r"block 'LOOP' inserts itself"),
    ([[(0, "CIRCLE"), (8, "0"), (10, 0.0), (20, 0.0), (40, -3.0)]], r"CIRCLE at line \d+: radius -3 must be > 0"),
    ([[(0, "CIRCLE"), (8, "0"), (10, 0.0), (20, 0.0), (40, 3.0), (210, 1.0), (220, 0.0), (230, 0.0)]],
     r"CIRCLE at line \d+: its extrusion \(1, 0, 0\) is not along Z"),
    ([[(0, "SPLINE"), (8, "0"), (71, 3), (40, 0.0), (40, 1.0), (10, 0.0), (20, 0.0), (10, 1.0), (20, 1.0)]],
     r"SPLINE at line \d+: degree 3 with 2 control points"),
    ([[(0, "LINE"), (8, "0"), (10, 0.0), (20, 0.0), (11, 5e9), (21, 0.0)]], r"LINE at line \d+: a point lies"),
    ([[(0, "INSERT"), (8, "0"), (2, "B"), (10, 0.0), (20, 0.0), (70, 100000), (71, 100000)],
      [(0, "BLOCK"), (2, "B"), (10, 0.0), (20, 0.0), (0, "ENDBLK")]], r"100000 columns x 100000 rows"),
])
def test_bad_dxf_entities_are_named(tmp_path, entities, message):
    with time_limit(10), pytest.raises(DesignFileError, match=r"bad\.dxf: .*" + message):
        dxffile.read_dxf(write(tmp_path, dxf_text(*entities, layers=("0",)), "bad.dxf"))


def test_not_a_dxf(tmp_path):
    with pytest.raises(DesignFileError, match=r"x\.dxf: line 1: group code '<svg>' is not a whole number"):
        dxffile.read_dxf(write(tmp_path, "<svg>\n</svg>\n", "x.dxf"))
    with pytest.raises(DesignFileError, match=r"b\.dxf: a binary DXF"):
        dxffile.read_dxf(write(tmp_path, b"AutoCAD Binary DXF\r\n\x1a\x00" + bytes(100), "b.dxf"))
    with pytest.raises(DesignFileError, match=r"e\.dxf: no ENTITIES section"):
        dxffile.read_dxf(write(tmp_path, "  0\nEOF\n", "e.dxf"))
    with pytest.raises(DesignFileError, match=r"u\.dxf: \$INSUNITS = 3: units this reader does not take"):
        dxffile.read_dxf(write(tmp_path, dxf_text(line(0, 0, 1, 1), units=3), "u.dxf"))


@settings(max_examples=150, deadline=3000)
@given(st.data())
def test_dxf_with_random_lines_changed_reads_or_is_refused_by_name(tmp_path_factory, data):
    lines = good_dxf().splitlines()
    for _ in range(data.draw(st.integers(1, 4))):
        index = data.draw(st.integers(0, len(lines) - 1))
        lines[index] = data.draw(st.sampled_from(["", "0", "nan", "-1e400", "LINE", "SECTION", "ENDSEC", "EOF", "999",
                                                  "x", "1e30", "-5", "INSERT", "POLYLINE", "VERTEX"]))
    path = os.path.join(str(tmp_path_factory.mktemp("fuzz")), "f.dxf")
    with open(path, "w") as stream:
        stream.write("\n".join(lines) + "\n")
    with time_limit(10):
        try:
            dxffile.read_dxf(path)
        except DesignFileError as error:
            assert str(error).startswith("f.dxf")


@pytest.mark.parametrize("value", ["-1e400", "1e400", "nan", "x"])
def test_insunits_that_is_no_whole_number_is_named(tmp_path, value):
    """Hypothesis found $INSUNITS = -1e400 (infinity) raising OverflowError instead of a message."""
    text = dxf_text(line(0, 0, 1, 1), units=4).replace("$INSUNITS\n 70\n4\n", f"$INSUNITS\n 70\n{value}\n")
    assert value in text
    with pytest.raises(DesignFileError, match=r"u\.dxf: line \d+: \$INSUNITS = .* is not a whole number"):
        dxffile.read_dxf(write(tmp_path, text, "u.dxf"))
