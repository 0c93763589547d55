"""The Part 21 reader's fast path (part21_scan) against its token parser (``fast=False``).

Both must give equal files (values, header, DATA parameters and every instance's line number) or
the same error, on the fixtures, on NIST-style text with comments, complex instances, typed
values and escapes, on CR and CR LF line ends, and on thousands of random one-character mutations
of a file; and the big generated file of explicit toolpaths must go through the fast path itself
with the numbers its text holds.
"""
import os
import random
import re
import sys

import pytest

from kezuri.toolpath.operations.stepnc import part21, part21_scan
from kezuri.toolpath.operations.stepnc.part21 import Part21Error, Ref, parse_part21

HERE = os.path.dirname(os.path.abspath(__file__))
FIXTURES = os.path.join(HERE, "fixtures", "iso14649")
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "bench"))

import stepnc_bigfile  # noqa: E402  (bench/: the generator of the big file)
from test_stepnc_freeform import freeform_file  # noqa: E402


def outcome(text, fast):
    try:
        result = parse_part21(text, fast=fast)
    except Part21Error as error:
        return ("error", str(error))
    return ("file", result.header, [e.line for e in result.header], result.data_sections, result.instances,
            {k: v.line for k, v in result.instances.items()})


def same_both_ways(text):
    exact = outcome(text, False)
    assert outcome(text, True) == exact
    return exact


def fast_path_alone(text):
    """The fast path's own result (GiveUp propagates: the test then shows it was not taken)."""
    return part21_scan.parse(text, part21._exact, part21._KINDS)


MIXED = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('MIXED'),'2;1');
FILE_NAME('mixed.stp','2026-11-27T00:00:00',('a'),(''),'','','');
FILE_SCHEMA(('MACHINING_SCHEMA'));
ENDSEC;
DATA;
#1=CARTESIAN_POINT('',(1.,-2.5E-3,+3));
#2 = cartesian_point ( 'p' , ( 0 , 1.5 , 2. ) ) ;
/* #3=CARTESIAN_POINT('commented out',(9.,9.,9.)); */
#3=POLYLINE('line',(#1,#2, #1));
#4=A('it''s',$,*,.T.,.F.,.U.,.right.,(#1,(2.,3.)));
#5=(NAMED_UNIT(*)LENGTH_UNIT()SI_UNIT(.MILLI.,.METRE.));
#6=B(LENGTH_MEASURE(5.),'a;b(c)',(),'\\X2\\00E9\\X0\\');
#7=C('multi
line',(1.,2.));
#8=D((1,2),(#3),'x,y',(.A.,$));
#9=E(((1.)));
ENDSEC;
END-ISO-10303-21;
"""


@pytest.mark.parametrize("name", ["ex1.stp", "ex1_ap238.stp"])
def test_the_fixtures_read_the_same(name):
    with open(os.path.join(FIXTURES, name), encoding="utf-8", errors="replace") as stream:
        text = stream.read()
    assert same_both_ways(text)[0] == "file"
    assert fast_path_alone(text).instances == parse_part21(text, fast=False).instances


def test_nist_style_text_reads_the_same_with_every_line_end():
    for text in (MIXED, MIXED.replace("\n", "\r\n"), MIXED.replace("\n", "\r"), "\ufeff" + MIXED,
                 freeform_file()):
        found = same_both_ways(text)
        assert found[0] == "file"
        fast_path_alone(text)
    instances = parse_part21(MIXED).instances
    assert instances[1].params == ["", [1.0, -0.0025, 3]] and isinstance(instances[1].params[1][2], int)
    assert instances[2].type_name == "CARTESIAN_POINT" and instances[2].params == ["p", [0, 1.5, 2.0]]
    assert instances[3].params == ["line", [Ref(1), Ref(2), Ref(1)]] and instances[3].line == 11
    assert instances[6].params[1:] == ["a;b(c)", [], "\u00e9"]
    assert instances[7].params[0] == "multiline" and instances[8].line == 17


BROKEN = [
    "#1=CARTESIAN_POINT('',(1.,2.,3.)",            # no ';' (runs into ENDSEC)
    "#1=CARTESIAN_POINT('',(1.,2.,3.));\n#1=X();",  # duplicate
    "#1=POLYLINE('',(#2,#3));",                     # undefined references
    "#1=CARTESIAN_POINT('',(.5,2.,3.));",           # no digit before the point
    "#1=CARTESIAN_POINT('',(1E5,2.,3.));",          # exponent without a point
    "#1=CARTESIAN_POINT('',(1.,,3.));",
    "#1=CARTESIAN_POINT('',(1.,2.,3.) x);",
    "#1=CARTESIAN_POINT('oops,(1.,2.,3.));",        # unterminated string
    "/* open comment #1=A();",
    "#1=A(\"0F\");",
    "#1=A(@2);",
]


@pytest.mark.parametrize("data", BROKEN)
def test_broken_text_is_refused_with_the_same_message(data):
    text = MIXED.replace("#9=E(((1.)));", data)
    found = same_both_ways(text)
    assert found[0] == "error"


def test_a_second_data_section_and_text_after_the_end_read_the_same():
    two = MIXED.replace("#9=E(((1.)));\n", "#9=E(((1.)));\nENDSEC;\nDATA;\n#10=F(#9);\n")
    assert same_both_ways(two)[0] == "file"
    assert len(parse_part21(two).data_sections) == 2
    assert same_both_ways(MIXED + "#11=G();\n")[0] == "error"


def test_random_one_character_mutations_read_the_same():
    """Each mutation deletes, doubles or inserts one character (of those that matter to Part 21)."""
    base = freeform_file()
    rng = random.Random(32)
    kinds = {"file": 0, "error": 0}
    for _ in range(1500):
        at = rng.randrange(len(base))
        what = rng.choice(["delete", "double", "insert"])
        if what == "delete":
            text = base[:at] + base[at + 1:]
        elif what == "double":
            text = base[:at] + base[at] + base[at:]
        else:
            text = base[:at] + rng.choice("'();,#$.*/\\= \n\r0123456789EA-+\"") + base[at:]
        kinds[same_both_ways(text)[0]] += 1
    assert kinds["file"] > 100 and kinds["error"] > 100


def test_the_big_file_of_explicit_toolpaths_goes_the_fast_way_with_its_numbers():
    text = stepnc_bigfile.explicit_toolpath_file(0.5)
    fast = fast_path_alone(text)
    assert fast.instances == parse_part21(text, fast=False).instances
    # numbers read from the text by an independent pattern
    for line in text.splitlines()[40:4000:97]:
        point = re.fullmatch(r"#(\d+)= CARTESIAN_POINT\('',\(([-\d.]+),([-\d.]+),([-\d.]+)\)\);", line)
        if point:
            assert fast.instances[int(point.group(1))].params[1] == [float(v) for v in point.groups()[1:]]
            assert fast.instances[int(point.group(1))].line == text[:text.index(line)].count("\n") + 1
    polylines = [inst for inst in fast.instances.values() if inst.type_name == "POLYLINE"]
    assert len(polylines) > 10
    for polyline in polylines:
        assert 2 <= len(polyline.params[1]) <= stepnc_bigfile.POINTS_PER_LINE
        assert all(fast.instances[ref.id].type_name == "CARTESIAN_POINT" for ref in polyline.params[1])


def test_long_runs_of_statements_the_regex_does_not_take_read_the_same():
    """Runs longer than part21_scan.MAX_RUN go to the exact reader in parts (lines kept); a file
    of mostly such statements is left to it whole."""
    head, tail = MIXED.split("#1=", 1)[0], "ENDSEC;\nEND-ISO-10303-21;\n"
    odd = "".join(f"#{i}=A(LENGTH_MEASURE({i}.),'x');\n" for i in range(1, 12_001))
    plain = "".join(f"#{i}=CARTESIAN_POINT('',({i}.,0.,1.));\n" for i in range(20_001, 50_001))
    for text in (head + odd + tail, head + plain + odd + "/* end */\n" + tail):
        found = same_both_ways(text)
        assert found[0] == "file" and found[-1][12_000] == 8 + 11_999 + (30_000 if plain in text else 0)
    fast_path_alone(head + plain + odd + tail)
