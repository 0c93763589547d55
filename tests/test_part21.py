"""Tests for the ISO 10303-21 reader and writer (toolpath/operations/stepnc/part21.py, part21_writer.py)."""
import os
import random
import time

import numpy as np
import pytest

from kezuri.toolpath.operations.stepnc.part21 import (DERIVED, UNKNOWN, UNSET, ComplexInstance, Entity, Enum, Instance, Part21Error, Part21File, Ref, Typed, iter_refs, parse_part21, read_part21)
from kezuri.toolpath.operations.stepnc.part21_writer import (Part21Writer, format_real, format_string, make_header, write_part21)

FIXTURES = os.environ.get("KEZURI_FIXTURES", os.path.join(os.path.dirname(__file__), "fixtures"))
EX1 = os.path.join(FIXTURES, "iso14649", "ex1.stp")

HEADER = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION((''),'2;1');
FILE_NAME('','',(''),(''),'','','');
FILE_SCHEMA(('TEST_SCHEMA'));
ENDSEC;
DATA;
"""  # the DATA lines of wrap() start on line 8
FOOTER = """ENDSEC;
END-ISO-10303-21;
"""


def wrap(data: str) -> str:
    return HEADER + data + "\n" + FOOTER


def parse_data(data: str) -> Part21File:
    return parse_part21(wrap(data))


@pytest.fixture(scope="module")
def ex1() -> Part21File:
    return read_part21(EX1)


# --------------------------------------------------------------------------- fixture facts


def test_ex1_header(ex1):
    assert [e.type_name for e in ex1.header] == ["FILE_DESCRIPTION", "FILE_NAME", "FILE_SCHEMA"]
    assert ex1.header_entity("FILE_DESCRIPTION").params == [
        ["ISO 14649-11 EXAMPLE 1", "SIMPLE PROGRAM WITH A PLANAR_FACE, A POCKET, AND A ROUND_HOLE"],
        "1",
    ]
    file_name = ex1.header_entity("file_name").params
    assert file_name[0] == "EXAMPLE1.STP"
    assert file_name[2] == ["YONG TAK HYUN", "JOCHEN WOLF"]
    assert file_name[4] == "$"  # a string containing a dollar sign, not UNSET
    assert ex1.schema == ["MACHINING_SCHEMA", "MILLING_SCHEMA"]
    assert ex1.data_sections == [[]]


def test_ex1_instance_count_and_ids(ex1):
    assert len(ex1.instances) == 105
    assert min(ex1.instances) == 1 and max(ex1.instances) == 127
    # #35, #36 and #59 exist only inside comments
    for missing in (3, 5, 15, 35, 36, 59):
        assert missing not in ex1.instances


def test_ex1_workplan(ex1):
    wp = ex1.get(2)
    assert isinstance(wp, Instance)
    assert wp.type_name == "WORKPLAN"
    assert wp.params[0] == "MAIN WORKPLAN"
    assert wp.params[1] == [Ref(10), Ref(11), Ref(12), Ref(13), Ref(14)]
    assert wp.params[2] is UNSET and wp.params[3] == Ref(8)
    steps = ex1.resolve(wp.params[1])
    assert [s.type_name for s in steps] == ["MACHINING_WORKINGSTEP"] * 5
    assert [s.params[0] for s in steps] == [
        "WS FINISH PLANAR FACE1", "WS DRILL HOLE1", "WS REAM HOLE1",
        "WS ROUGH POCKET1", "WS FINISH POCKET1"]
    assert [s.id for s in ex1.by_type("MACHINING_WORKINGSTEP")] == [10, 11, 12, 13, 14]
    assert ex1.by_type("machining_workingstep") == steps
    assert ex1.by_type("NO_SUCH_ENTITY") == []


def test_ex1_values(ex1):
    dim = ex1.get(Ref(30))
    assert dim.type_name == "MILLING_TOOL_DIMENSION"
    assert dim.params == [18.0, UNSET, UNSET, 29.0, 0.0, UNSET, UNSET]
    assert isinstance(dim.params[0], float)

    bidi = ex1.get(42)
    assert bidi.type_name == "BIDIRECTIONAL_MILLING"
    assert bidi.params == [0.05, True, Ref(43), Enum("LEFT"), UNSET]
    assert bidi.line == 105

    endmill = ex1.get(29)  # TAPERED_ENDMILL(#30,4,.RIGHT.,.F.,$,$)
    assert endmill.params == [Ref(30), 4, Enum("RIGHT"), False, UNSET, UNSET]
    assert isinstance(endmill.params[1], int) and not isinstance(endmill.params[1], bool)
    assert ex1.resolve(endmill.params[0]) is dim

    assert ex1.get(40).params[3] == -12.0  # clockwise spindle
    assert ex1.get(43).params == ["STRATEGY PLANAR FACE1: 1.DIRECTION", [0.0, 1.0, 0.0]]
    assert ex1.get(9).params[4] == []  # WORKPIECE_SETUP(...,())
    assert ex1.get(26).type_name == "THROUGH_BOTTOM_CONDITION" and ex1.get(26).params == []
    assert ex1.get(96).params[0] == " AXIS "  # blanks inside strings are kept
    assert ex1.get(1).line == 58


def test_ex1_unset_params_and_commented_versions(ex1):
    pocket = ex1.get(18)
    assert pocket.type_name == "CLOSED_POCKET"
    # the live line, not the commented-out one that has #35 in position 8
    assert pocket.params == ["POCKET1", Ref(4), [Ref(22), Ref(23)], Ref(84), Ref(65), [], UNSET,
                             Ref(27), UNSET, Ref(37), Ref(28)]
    assert pocket.params[6] is UNSET and pocket.params[8] is UNSET
    assert ex1.get(30).params[0] == 18.0  # not the commented 20.000
    assert ex1.get(117).params[1] == [0.0, 1.0, 0.0]


def test_ex1_every_reference_resolves(ex1):
    count = 0
    for inst in ex1.instances.values():
        for ref in iter_refs(inst):
            assert ex1.get(ref).id == ref.id
            count += 1
    assert count == 128  # 233 '#n' on the live DATA lines, less the 105 instance names
    assert ex1.resolve(5.0) == 5.0 and ex1.resolve("x") == "x"
    with pytest.raises(KeyError, match="#999"):
        ex1.get(999)


def test_ex1_round_trip(ex1):
    text = write_part21(ex1)
    again = parse_part21(text)
    assert again.instances == ex1.instances
    assert again.header == ex1.header
    assert write_part21(again) == text  # stable
    assert "#30=MILLING_TOOL_DIMENSION(18.,$,$,29.,0.,$,$);" in text
    assert "#42=BIDIRECTIONAL_MILLING(0.05,.T.,#43,.LEFT.,$);" in text
    assert "#40=MILLING_TECHNOLOGY(0.04,.TCP.,$,-12.,$,.F.,.F.,.F.,$);" in text
    lines = text.splitlines()
    assert lines[:3] == ["ISO-10303-21;", "HEADER;",
                         "FILE_DESCRIPTION(('ISO 14649-11 EXAMPLE 1','SIMPLE PROGRAM WITH A "
                         "PLANAR_FACE, A POCKET, AND A ROUND_HOLE'),'1');"]
    assert lines[-2:] == ["ENDSEC;", "END-ISO-10303-21;"]
    ids = [int(line[1:line.index("=")]) for line in lines if line.startswith("#")]
    assert ids == sorted(ex1.instances)


# --------------------------------------------------------------------------- lexical details


def test_numbers():
    f = parse_data("#1=A(1,-2,+3,1.,1.E-3,-0.5,0.5,12.500,1.5e2,-12.,0.);")
    values = f.get(1).params
    assert values == [1, -2, 3, 1.0, 0.001, -0.5, 0.5, 12.5, 150.0, -12.0, 0.0]
    assert [type(v) for v in values] == [int] * 3 + [float] * 8


def test_enums_logicals_unset_derived():
    f = parse_data("#1=A(.T.,.F.,.U.,.RIGHT.,.t.,.left.,$,*,.CW_1.);")
    assert f.get(1).params == [True, False, UNKNOWN, Enum("RIGHT"), True, Enum("LEFT"), UNSET,
                               DERIVED, Enum("CW_1")]
    assert UNKNOWN == Enum("U")


def test_nested_lists_and_typed_parameters():
    f = parse_data("#1=A(((1,2),(3,())),LENGTH_MEASURE(5.),"
                   "(POSITIVE_LENGTH_MEASURE(2.E-3),TEXT('x')),B((#1)));")
    assert f.get(1).params == [
        [[1, 2], [3, []]],
        Typed("LENGTH_MEASURE", 5.0),
        [Typed("POSITIVE_LENGTH_MEASURE", 0.002), Typed("TEXT", "x")],
        Typed("B", [Ref(1)]),
    ]
    assert list(iter_refs(f.get(1))) == [Ref(1)]


def test_comments_everywhere():
    f = parse_part21(
        "/* before */ISO-10303-21;/**/\nHEADER; /* a\nmulti-line\ncomment */\n"
        "FILE_DESCRIPTION(/*x*/(''),'2;1');FILE_NAME('','',(''),(''),'','','');\n"
        "FILE_SCHEMA(('S'));ENDSEC;DATA;\n"
        "#1 /*a*/ = /*b*/ A /*c*/ ( /*d*/ 1 /*e*/ , '/* not a comment */' ) /*f*/ ;\n"
        "/* #2=B(); commented out */\n"
        "ENDSEC;END-ISO-10303-21;\n/* trailing comment */\n")
    assert list(f.instances) == [1]
    assert f.get(1).params == [1, "/* not a comment */"]


def test_lower_case_keywords_are_upper_cased():
    f = parse_part21(wrap("#1=cartesian_point('p',(0.,0.,0.));\n#2=(b_part() a_Part(1));"))
    assert f.get(1).type_name == "CARTESIAN_POINT"
    assert f.get(2).type_names == ("B_PART", "A_PART")


@pytest.mark.parametrize("encoded, decoded", [
    ("'it''s'", "it's"),
    ("''''", "'"),
    ("''", ""),
    ("'a\\\\b'", "a\\b"),
    ("'\\X\\E9t\\X\\E9'", "\u00e9t\u00e9"),
    ("'\\X2\\03B103B2\\X0\\ x'", "\u03b1\u03b2 x"),
    ("'\\X2\\D83DDE00\\X0\\'", "\U0001F600"),  # a surrogate pair written by UTF-16 writers
    ("'\\X4\\0001F6000001F601\\X0\\'", "\U0001F600\U0001F601"),
    ("'\\S\\a'", "\u00e1"),  # 0x61 + 0x80 in ISO 8859-1
    ("'\\PE\\\\S\\a'", "\u0441"),  # the same code in ISO 8859-5 (Cyrillic)
    ("'\\S\\'''", "\u00a7"),  # \S\ then the doubled quote: 0x27 + 0x80
    ("'ab\ncd'", "abcd"),  # line breaks are not part of the value
    ("'\\N\\one\\F\\'", "one"),  # print control directives
    ("'C:\\temp\\x.stp'", "C:\\temp\\x.stp"),  # lone backslashes are kept
    ("'#1=A($);'", "#1=A($);"),
])
def test_string_escapes(encoded, decoded):
    f = parse_data(f"#1=A({encoded});")
    assert f.get(1).params == [decoded]


def test_format_string():
    assert format_string("plain text #1 $ (a,b);") == "'plain text #1 $ (a,b);'"
    assert format_string("it's") == "'it''s'"
    assert format_string("a\\b") == "'a\\\\b'"
    assert format_string("\u00e9\u03b1\u03b2\U0001F600\n") == \
        "'\\X\\E9\\X2\\03B103B2\\X0\\\\X4\\0001F600\\X0\\\\X\\0A'"


def test_strings_round_trip():
    rng = random.Random(21)
    alphabet = "ab '\\\"$#()*,;./\n\t\u00e9\u00ff\u0100\u03b1\uffff\U0001F600\U0010FFFF"
    strings = ["".join(rng.choice(alphabet) for _ in range(rng.randrange(0, 12)))
               for _ in range(300)]
    w = Part21Writer()
    for s in strings:
        w.add("S", s)
    f = parse_part21(w.text())
    assert [inst.params[0] for inst in f.instances.values()] == strings


# --------------------------------------------------------------------------- complex instances


COMPLEX = """#1=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#2))
   REPRESENTATION_CONTEXT('ID','3D'));
#2= ( LENGTH_UNIT ( ) NAMED_UNIT ( * ) SI_UNIT ( .MILLI. , .METRE. ) ) ;
#3=MEASURE_REPRESENTATION_ITEM('d',LENGTH_MEASURE(5.),#2);"""


def test_complex_instances():
    f = parse_data(COMPLEX)
    ctx, unit = f.get(1), f.get(2)
    assert isinstance(ctx, ComplexInstance) and isinstance(unit, ComplexInstance)
    assert ctx.type_names == ("GEOMETRIC_REPRESENTATION_CONTEXT", "GLOBAL_UNIT_ASSIGNED_CONTEXT",
                              "REPRESENTATION_CONTEXT")
    assert ctx.params_of("GLOBAL_UNIT_ASSIGNED_CONTEXT") == [[Ref(2)]]
    assert ctx.line == 8 and unit.line == 10
    assert unit.parts == [("LENGTH_UNIT", []), ("NAMED_UNIT", [DERIVED]),
                          ("SI_UNIT", [Enum("MILLI"), Enum("METRE")])]
    assert f.by_type("SI_UNIT") == [unit]
    assert f.get(3).params[1] == Typed("LENGTH_MEASURE", 5.0)
    with pytest.raises(KeyError):
        unit.params_of("CONVERSION_BASED_UNIT")
    again = parse_part21(write_part21(f))
    assert again.instances == f.instances
    assert "#2=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));" in write_part21(f)


def test_multiple_data_sections():
    text = HEADER.replace("DATA;\n", "DATA(('first'),('S1'));\n#1=A(#2);\nENDSEC;\n"
                          "DATA;\n#2=B(#1);\n") + FOOTER
    f = parse_part21(text)
    assert f.data_sections == [[["first"], ["S1"]], []]
    assert f.get(1).params == [Ref(2)] and f.get(2).params == [Ref(1)]


# --------------------------------------------------------------------------- errors


def error_of(text: str) -> Part21Error:
    with pytest.raises(Part21Error) as info:
        parse_part21(text)
    return info.value


def test_error_message_format():
    err = error_of(wrap("#1=A(1 2);"))
    assert (err.line, err.column, err.instance_id) == (8, 8, 1)
    assert str(err) == "line 8, column 8 (#1): expected ',' or ')', found '2'"
    assert isinstance(err, ValueError)


def test_dangling_reference_names_the_instance():
    err = error_of(wrap("#1=A(#2);\n#2=B();\n#3=B(#1,\n  (#2,#99));"))
    assert (err.line, err.column, err.instance_id) == (11, 7, 3)
    assert str(err) == "line 11, column 7 (#3): reference to undefined instance #99"


def test_duplicate_instance():
    err = error_of(wrap("#1=A();\n#2=A();\n#1=B();"))
    assert (err.line, err.column, err.instance_id) == (10, 1, 1)
    assert "duplicate instance #1 (first defined on line 8)" in str(err)


@pytest.mark.parametrize("data, line, column, instance, message", [
    ("#1=A('abc);", 8, 6, 1, "unterminated string"),
    ("#1=A(1);\n#2=B(1, /* never closed", 9, 9, 2, "unterminated comment"),
    ("#1=A(1);\n%", 9, 1, None, "unexpected character '%'"),
    ("#1=A(1);\n#2=B(1,@3);", 9, 8, 2, "edition 3"),
    ('#1=A("0FF");', 8, 6, 1, "binary values"),
    ("#1=A(.5);", 8, 6, 1, "0.5"),
    ("#1=A(-);", 8, 6, 1, "unexpected character '-'"),
    ("#1=A(1,);", 8, 8, 1, "expected a parameter value, found ')'"),
    ("#1=A(1)", 9, 1, 1, "expected ';', found 'ENDSEC'"),
    ("#1 A(1);", 8, 4, 1, "expected '=', found 'A'"),
    ("#1=(A(1) 2);", 8, 10, 1, "expected ')' or another entity name"),
    ("#1=A(LENGTH_MEASURE(1.,2.));", 8, 6, 1, "exactly one value"),
    ("#1=A(LENGTH_MEASURE);", 8, 20, 1, "expected '(' after LENGTH_MEASURE"),
    ("#1=A('\\X2\\00E9');", 8, 7, 1, "\\X2\\"),
    ("#1=A('ok\\X\\G1');", 8, 9, 1, "\\X\\ must be followed by two hex digits"),
    ("#1=A(1);\nFOO;", 9, 1, None, "expected an instance '#n=' or 'ENDSEC;', found 'FOO'"),
])
def test_syntax_errors(data, line, column, instance, message):
    err = error_of(wrap(data))
    assert (err.line, err.column, err.instance_id) == (line, column, instance), str(err)
    assert message in str(err)
    assert str(err).startswith(f"line {line}, column {column}")


def test_missing_endsec():
    err = error_of(HEADER + "#1=A();\nEND-ISO-10303-21;\n")
    assert (err.line, err.column) == (9, 1)
    assert "missing 'ENDSEC;'" in str(err)
    err = error_of(HEADER.replace("ENDSEC;\n", "") + "#1=A();\n" + FOOTER)
    assert (err.line, err.column) == (6, 1)
    assert "missing 'ENDSEC;' of the header" in str(err)


@pytest.mark.parametrize("text, line, column, message", [
    ("", 1, 1, "expected 'ISO-10303-21;' at the start of the file, found end of file"),
    ("HEADER;", 1, 1, "expected 'ISO-10303-21;'"),
    ("\n\n  /* unterminated", 3, 3, "unterminated comment"),
    (HEADER + "#1=A();\nENDSEC;\n", 10, 1, "expected 'END-ISO-10303-21;'"),
    (wrap("#1=A();") + "#2=B();\n", 11, 1, "nothing after 'END-ISO-10303-21;'"),
    (HEADER.replace("DATA;", "ANCHOR;\nENDSEC;\nDATA;") + FOOTER, 7, 1, "ANCHOR sections"),
    ("ISO-10303-21;\nHEADER;\nFILE_NAME('a' 'b');", 3, 15, "expected ',' or ')'"),
])
def test_structure_errors(text, line, column, message):
    err = error_of(text)
    assert (err.line, err.column) == (line, column), str(err)
    assert message in str(err)


# --------------------------------------------------------------------------- writer


@pytest.mark.parametrize("value, text", [
    (5.0, "5."), (0.05, "0.05"), (-12.0, "-12."), (0.0, "0."), (-0.0, "-0."), (100.0, "100."),
    (1e-7, "1.E-07"), (1.5e20, "1.5E+20"), (123456.789, "123456.789"), (0.1 + 0.2, "0.30000000000000004"),
    (np.float64(2.5), "2.5"),
])
def test_format_real(value, text):
    assert format_real(value) == text
    assert parse_data(f"#1=A({text});").get(1).params == [float(value)]


def test_format_real_round_trips_exactly():
    rng = random.Random(7)
    for _ in range(2000):
        x = rng.uniform(-1e3, 1e3) * 10.0 ** rng.randrange(-30, 30)
        text = format_real(x)
        assert "." in text and float(text) == x
    for bad in (float("nan"), float("inf"), -float("inf")):
        with pytest.raises(ValueError):
            format_real(bad)


def test_builder_produces_a_file_that_parses_back():
    w = Part21Writer()
    project = w.reserve()  # top-down numbering, as in ISO 14649 examples
    point = w.add("CARTESIAN_POINT", "ORIGIN", (0.0, 1.5, -2.0))
    axis = w.add("DIRECTION", "AXIS", [0.0, 0.0, 1.0])
    place = w.add("AXIS2_PLACEMENT_3D", "SETUP", point, axis, UNSET)
    tool = w.add("MILLING_TOOL_DIMENSION", np.float64(6.0), UNSET, UNSET, 25.0, np.int64(0), UNSET, UNSET)
    strat = w.add("BIDIRECTIONAL_MILLING", 0.5, True, axis, Enum("LEFT"), UNSET)
    unit = w.add_complex([("LENGTH_UNIT", []), ("NAMED_UNIT", [DERIVED]),
                          ("SI_UNIT", [Enum("MILLI"), Enum("METRE")])])
    w.define(project, "PROJECT", "IT'S A TEST \u00e9", place, [tool, strat, unit],
             Typed("LENGTH_MEASURE", 5.0), UNKNOWN, False)
    assert (project, point, unit) == (Ref(1), Ref(2), Ref(7))

    text = w.text(description=("builder test",), name="t.stp", schema=("MACHINING_SCHEMA",))
    assert text == w.text(description=("builder test",), name="t.stp", schema=("MACHINING_SCHEMA",))
    assert text.startswith("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('builder test'),'2;1');\n"
                           "FILE_NAME('t.stp','',(''),(''),'Kezuri CAM part21','Kezuri CAM','');\n"
                           "FILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n"
                           "#1=PROJECT('IT''S A TEST \\X\\E9',#4,(#5,#6,#7),LENGTH_MEASURE(5.),.U.,.F.);\n"
                           "#2=CARTESIAN_POINT('ORIGIN',(0.,1.5,-2.));\n")
    assert "#5=MILLING_TOOL_DIMENSION(6.,$,$,25.,0,$,$);" in text
    assert text.endswith("ENDSEC;\nEND-ISO-10303-21;\n")

    f = parse_part21(text)
    assert f.instances == w.instances  # tuples and numpy scalars were normalized
    assert f.schema == ["MACHINING_SCHEMA"]
    assert f.get(2).params == ["ORIGIN", [0.0, 1.5, -2.0]]
    assert write_part21(f) == text
    assert f == w.file(description=("builder test",), name="t.stp", schema=("MACHINING_SCHEMA",))


def test_builder_output_is_deterministic():
    def build():
        w = Part21Writer()
        p = w.add("CARTESIAN_POINT", "P", [1.0, 2.0, 3.0])
        w.add("PLACEMENT", p)
        return w.text()
    assert build() == build()
    assert "'',(''),(''),'Kezuri CAM part21'" in build()  # empty time stamp by default


def test_builder_rejects_bad_input():
    w = Part21Writer()
    with pytest.raises(ValueError, match="type name"):
        w.add("lower_case")
    with pytest.raises(ValueError, match="type name"):
        w.add("TWO WORDS")
    with pytest.raises(TypeError, match="UNSET"):
        w.add("A", None)
    with pytest.raises(TypeError):
        w.add("A", {"a": 1})
    with pytest.raises(ValueError):
        w.add("A", float("nan"))
    with pytest.raises(ValueError, match="enumeration"):
        w.add("A", Enum("NOT VALID"))
    with pytest.raises(ValueError):
        w.add("A", Ref(0))
    with pytest.raises(ValueError):
        w.add_complex([])
    assert w.instances == {}
    r = w.reserve()
    with pytest.raises(ValueError, match="#1"):
        w.text()
    w.define(r, "A")
    with pytest.raises(ValueError, match="not reserved"):
        w.define(r, "B")
    assert "#1=A();" in w.text()


def test_write_part21_checks_references_and_ids():
    with pytest.raises(ValueError, match="#1 refers to #7"):
        write_part21([Instance(1, "A", [Ref(7)])])
    with pytest.raises(ValueError, match="duplicate"):
        write_part21([Instance(1, "A", []), Instance(1, "B", [])])
    with pytest.raises(ValueError, match="bad instance id"):
        write_part21([Instance(0, "A", [])])


def test_write_part21_fills_missing_header_entities_in_order():
    f = Part21File(header=[Entity("FILE_SCHEMA", [["S"]]), Entity("FILE_POPULATION", ["S", "x", []])],
                   instances={2: Instance(2, "B", []), 1: Instance(1, "A", [Ref(2)])})
    text = write_part21(f)
    lines = text.splitlines()
    assert [line[:line.index("(")] for line in lines[2:6]] == [
        "FILE_DESCRIPTION", "FILE_NAME", "FILE_SCHEMA", "FILE_POPULATION"]
    assert lines[4] == "FILE_SCHEMA(('S'));"
    assert lines[6:10] == ["ENDSEC;", "DATA;", "#1=A(#2);", "#2=B();"]
    # an explicit header replaces the file's own; a mapping or list of instances works too
    own = make_header(description=("d",), schema=("X",), time_stamp="2024-01-01T00:00:00")
    text2 = write_part21(f.instances, header=own)
    assert "FILE_SCHEMA(('X'));" in text2 and "'2024-01-01T00:00:00'" in text2
    assert write_part21(list(f.instances.values()), header=own) == text2


# --------------------------------------------------------------------------- performance


def test_parses_a_megabyte_quickly():
    rows = []
    n = 0
    size = 0
    while size < 1_000_000:
        i = 3 * n + 1
        rows.append(f"#{i}=CARTESIAN_POINT('POINT {n}',({n * 0.125!r},{-n * 1.5!r},3.E-05));\n"
                    f"#{i + 1}=DIRECTION(' AXIS ',(0.,0.,1.));\n"
                    f"#{i + 2}=AXIS2_PLACEMENT_3D('PL',#{i},#{i + 1},$,.LEFT.,.T.,"
                    f"(LENGTH_MEASURE(2.5)));\n")
        size += len(rows[-1])
        n += 1
    text = wrap("".join(rows))
    start = time.perf_counter()
    f = parse_part21(text)
    elapsed = time.perf_counter() - start
    assert len(f.instances) == 3 * n
    assert f.get(3 * n).params[1] == Ref(3 * n - 2)
    assert elapsed < 2.0, f"parsing {len(text)} characters took {elapsed:.2f} s"
