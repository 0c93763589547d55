"""Tests of the test-side Fanuc Custom Macro B interpreter (tests/macrob.py).

Every expected number here is worked out by hand in the comments, not by the interpreter.
"""
import itertools

import pytest

from macrob import MacroAlarm, MacroError, Move, eval_expression, parse_programs, run_program


def prog(*blocks, number=1):
    """A main program from blocks, with a % frame."""
    return "%\n" + f"O{number:04d}\n" + "\n".join(blocks) + "\n%\n"


def approx_xyz(moves):
    return [pytest.approx(m.end, abs=1e-9) for m in moves]


# ----------------------------------------------------------------------------------------------
# Arithmetic and functions
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("expr, expected", [
    ("2+3*4", 14.0),
    ("[2+3]*4", 20.0),
    ("2+3*4-1", 13.0),
    ("8/2/2", 2.0),            # left associative
    ("10/4", 2.5),
    ("-2*-3", 6.0),
    ("FIX[3.7]", 3.0),
    ("FIX[-3.7]", -3.0),       # towards zero
    ("FUP[3.2]", 4.0),
    ("FUP[-3.2]", -4.0),       # away from zero
    ("FUP[3]", 3.0),
    ("ROUND[2.5]", 3.0),
    ("ROUND[-2.5]", -3.0),
    ("ROUND[2.49]", 2.0),
    ("ABS[-4.25]", 4.25),
    ("SQRT[16]", 4.0),
    ("SIN[30]", 0.5),
    ("COS[60]", 0.5),
    ("FIX[1237/10]*10", 1230.0),
    ("1237-FIX[1237/10]*10", 7.0),   # the paper's "last digit of the clock"
    ("[[[[[1+1]]]]]", 2.0),          # 5 levels of brackets is the limit
])
def test_expression_values(expr, expected):
    assert eval_expression(expr) == pytest.approx(expected, abs=1e-12)


def test_arithmetic_in_a_program_and_indirect_variables():
    run = run_program(prog(
        "#1=7.",
        "#100=#1*2+1",                 # 15
        "#101=FIX[#100/4]",            # FIX[3.75] = 3
        "#102=FUP[#100/4]",            # 4
        "#[100+#101]=-#1",             # #103 = -7
        "#104=#[100+#101]*2",          # -14
        "#105=ROUND[SQRT[#100+1]*10]", # sqrt(16)=4 -> 40
        "#500=#500+1",                 # preset 41 -> 42
        "M30"), variables={500: 41})
    assert run.var(1) == 7.0
    assert [run.var(n) for n in range(100, 106)] == [15.0, 3.0, 4.0, -7.0, -14.0, 40.0]
    assert run.var(500) == 42.0
    assert run.ended_by == "M30"


def test_expression_errors():
    with pytest.raises(MacroError, match="division by zero"):
        eval_expression("1/[2-2]")
    with pytest.raises(MacroError, match="SQRT"):
        eval_expression("SQRT[-1]")
    with pytest.raises(MacroError, match="deeper than 5"):
        eval_expression("[[[[[[1]]]]]]")
    with pytest.raises(MacroError, match="chained"):
        eval_expression("#1GT0AND#2GT0")      # Fanuc precedence: #1 GT [0 AND #2] GT 0
    with pytest.raises(MacroError, match="only supported between bracketed conditions"):
        eval_expression("#1AND#2", {1: 1.0, 2: 1.0})
    with pytest.raises(MacroError, match="chained"):
        eval_expression("1LT2LT3")
    assert eval_expression("[#1GT0]AND[#2GT0]", {1: 1.0, 2: 0.0}) is False
    assert eval_expression("[#1GT0]OR[#2GT0]", {1: 1.0, 2: 0.0}) is True


# ----------------------------------------------------------------------------------------------
# Vacancy
# ----------------------------------------------------------------------------------------------
def test_vacancy_rules():
    run = run_program(prog(
        "#1=5.",
        "#1=#0",                      # vacant again
        "#2=#24+#25",                 # vacant + vacant = 0, not vacant
        "#3=#24",                     # plain copy keeps vacancy
        "#4=#24*5",                   # arithmetic: 0
        "#5=-#24",                    # arithmetic: 0
        "IF[#1EQ#0]THEN#101=1.",      # yes
        "IF[#2EQ#0]THEN#102=1.",      # no: #2 is 0
        "IF[#2EQ0]THEN#103=1.",       # yes
        "IF[#3EQ0]THEN#104=1.",       # no: vacant is not 0 for EQ
        "IF[#3NE0]THEN#105=1.",       # yes
        "IF[#3GE0]THEN#106=1.",       # yes: vacant acts as 0 for GE
        "IF[#3LT0]THEN#107=1.",       # no
        "IF[[#24+#25]EQ#0]THEN#108=1.",           # no: the paper's mistake, the sum is 0
        "IF[[#24EQ#0]AND[#25EQ#0]]THEN#109=1.",   # yes: the right test
        "M30"))
    assert run.var(1) is None
    assert run.var(2) == 0.0
    assert run.var(3) is None
    assert run.var(4) == 0.0
    assert run.var(5) == 0.0
    assert [run.var(n) for n in range(101, 110)] == [1.0, None, 1.0, None, 1.0, 1.0, None, None, 1.0]


def test_vacant_words_are_omitted():
    run = run_program(prog(
        "G90G00X10.Y20.Z30.",
        "#24=1.",
        "#25=2.",
        "G01X#24Y#25Z#26F100.",       # Z omitted: (1, 2, 30)
        "#1=#0",
        "G#1X5.",                     # G omitted: still G01 -> feed to (5, 2, 30)
        "G00X#0Y#0Z#0",               # only G00 remains: no move
        "X6.",                        # rapid (G00 is modal now)
        "M30"))
    assert [m.kind for m in run.moves] == ["rapid", "feed", "feed", "rapid"]
    assert approx_xyz(run.moves) == [(10, 20, 30), (1, 2, 30), (5, 2, 30), (6, 2, 30)]
    assert run.moves[1].feed == 100.0 and run.moves[3].feed is None


# ----------------------------------------------------------------------------------------------
# Control flow
# ----------------------------------------------------------------------------------------------
def test_while_loops_nested_and_moving():
    run = run_program(prog(
        "#1=1",
        "#100=0",
        "WHILE[#1LE10]DO1",           # 1+2+...+10 = 55
        "#100=#100+#1",
        "#1=#1+1",
        "END1",
        "#101=0",
        "#2=0",
        "WHILE[#2LT3]DO1",            # 3 x 4 = 12 inner passes
        "#3=0",
        "WHILE[#3LT4]DO2",
        "#101=#101+1",
        "#3=#3+1",
        "END2",
        "#2=#2+1",
        "END1",
        "G91G01F200.",
        "#4=0",
        "WHILE[#4LT5]DO3",            # five incremental 2 mm steps: X 2, 4, 6, 8, 10
        "X2.",
        "#4=#4+1",
        "END3",
        "G90",
        "#102=#5001",                 # 10: #5001 is absolute even after G91 moves
        "M30"))
    assert run.var(100) == 55.0
    assert run.var(101) == 12.0
    assert [m.x for m in run.moves] == pytest.approx([2, 4, 6, 8, 10])
    assert run.var(102) == 10.0


def test_goto_forward_backward_and_computed():
    run = run_program(prog(
        "#100=0",
        "N1#100=#100+1",
        "IF[#100LT5]GOTO1",           # loops until 5
        "#101=30",
        "GOTO#101",                   # computed target N30
        "#102=1.",                    # skipped
        "N30#103=7.",
        "GOTO40",
        "N35#104=1.",                 # skipped
        "N40M30"))
    assert run.var(100) == 5.0
    assert run.var(102) is None
    assert run.var(103) == 7.0
    assert run.var(104) is None
    assert run.ended_by == "M30"


# ----------------------------------------------------------------------------------------------
# Calls
# ----------------------------------------------------------------------------------------------
CALLS = """%
O0001
#1=11.
#2=22.
G65P9000A1.B2.X3.Y4.Z5.
#100=#1
#101=#2
M30
O9000
#110=#1+#2*10+#24*100+#25*1000+#26*10000
#111=#3
#1=99.
G65P9001X7.
#112=#24
M99
O9001
#113=#24*2
M99
%
"""


def test_g65_arguments_and_local_levels():
    run = run_program(CALLS)
    assert run.var(110) == 54321.0          # 1 + 2*10 + 3*100 + 4*1000 + 5*10000
    assert run.var(111) is None             # C (#3) was not passed
    assert run.var(112) == 3.0              # the nested call has its own #24
    assert run.var(113) == 14.0             # 7 * 2
    assert (run.var(100), run.var(101)) == (11.0, 22.0)   # main locals untouched by the macro
    assert run.locals == {1: 11.0, 2: 22.0}


def test_g65_nesting_limit_and_missing_program():
    with pytest.raises(MacroError, match="nested deeper than 4"):
        run_program(prog("G65P9000", "M30") + "O9000\nG65P9000\nM99\n")
    with pytest.raises(MacroError, match="O1234 not found") as err:
        run_program(prog("G90", "G65P1234A1.", "M30"))
    assert err.value.line == 4 and err.value.text == "G65P1234A1."


MODAL = """%
O0001
#101=0
F100.
G90G00X1.Y2.Z3.
G01Z2.
G66.1P9001X5.
Y7.
X9.F50.
(A COMMENT LINE DOES NOT CALL)
N50
G67
G00Z10.
X0
M30
%
O9001
#101=#101+1
#[130+#101]=#5001
#[150+#101]=#5002
#[170+#101]=#9
G01X#24Y#25Z#26
M99
%
"""


def test_g66_1_calls_the_macro_on_every_block_until_g67():
    run = run_program(MODAL)
    # calls: the G66.1 block (X5.), Y7., X9.F50.  -- not the comment, not N50, not G67
    assert run.var(101) == 3.0
    assert [run.var(130 + k) for k in range(1, 4)] == [1.0, 5.0, 5.0]   # #5001: X before the block
    assert [run.var(150 + k) for k in range(1, 4)] == [2.0, 2.0, 7.0]   # #5002
    assert [run.var(170 + k) for k in range(1, 4)] == [None, None, 50.0]  # F -> #9
    assert [m.kind for m in run.moves] == ["rapid", "feed", "feed", "feed", "feed", "rapid", "rapid"]
    assert approx_xyz(run.moves) == [(1, 2, 3), (1, 2, 2), (5, 2, 2), (5, 7, 2), (9, 7, 2), (9, 7, 10), (0, 7, 10)]
    # the F50. of a called block is an argument only: the modal feed stays 100
    assert [m.feed for m in run.moves] == [None, 100.0, 100.0, 100.0, 100.0, None, None]
    macro_move_line = MODAL.splitlines().index("G01X#24Y#25Z#26") + 1
    assert [m.line for m in run.moves[2:5]] == [macro_move_line] * 3
    assert [m.main_line for m in run.moves] == [5, 6, 7, 8, 9, 13, 14]   # the calling blocks
    assert run.modal["modal_call"] is None


# Where the manual leaves the behaviour to the machine, the interpreter refuses instead of guessing.
@pytest.mark.parametrize("old, new, line, message", [
    ("G66.1P9001X5.", "G66.1P9001", 7, "a G66.1 block without an X, Y or Z word"),
    ("Y7.", "F50.", 8, "a block under G66.1 without an X, Y or Z word"),
    ("Y7.", "M08", 8, "a block under G66.1 without an X, Y or Z word"),
    ("Y7.", "G01Y7.", 8, "G1 in a block under G66.1"),
    ("Y7.", "G00Y7.", 8, "G0 in a block under G66.1"),                    # a rapid under the call
    ("G01Z2.", "G00Z2.", 7, r"a G66\.1 block in G00 \(a rapid\)"),         # the call made in G00
    ("#[130+#101]=#5001", "#[130+#101]=#4001", 19, "#4001 read in a macro called by G66.1"),
    ("G01X#24Y#25Z#26", "G00X#24Y#25Z#26", 8, r"a block under G66\.1 in G00"),  # the macro left G00 modal
])
def test_g66_1_refuses_what_the_manual_leaves_to_the_machine(old, new, line, message):
    assert MODAL.count(old) == 1
    with pytest.raises(MacroError, match=message) as err:
        run_program(MODAL.replace(old, new))
    assert err.value.line == line


def test_modal_information_is_read_in_a_g65_call():
    # #4001 after a G01 block, in a macro called by G65 (not G66.1): the preceding block's G01
    text = prog("G90G01X1.F100.", "G65P9001", "M30") + "O9001\n#100=#4001\nM99\n%\n"
    assert run_program(text).var(100) == 1.0


def test_an_argument_that_is_an_axis_of_the_machine_is_refused():
    text = prog("G90G01X1.F100.", "G65P9001X2.B1.C0.5", "M30") + "O9001\n#100=#2+#3\nM99\n%\n"
    assert run_program(text).var(100) == 1.5                        # a 3-axis machine: B and C are letters
    with pytest.raises(MacroError, match="address B is an axis of this machine") as err:
        run_program(text, axes="XYZB")
    assert err.value.line == 4
    with pytest.raises(MacroError, match="address C is an axis"):
        run_program(text, axes="XYZC")
    modal = MODAL.replace("X9.F50.", "X9.F50.C1.")
    assert run_program(modal, axes="XYZB").var(101) == 3.0          # C is no axis of an X Y Z B machine
    with pytest.raises(MacroError, match="address C is an axis") as err:
        run_program(modal, axes="XYZAC")
    assert err.value.line == 9
    with pytest.raises(MacroError, match="axes must name"):
        run_program(text, axes="XY")


def test_g66_1_refuses_program_end_while_active():
    with pytest.raises(MacroError, match=r"M30 while the G66\.1 modal call is active") as err:
        run_program(prog("G01X0F100.", "G66.1P9001X1.", "M30") + "O9001\nM99\n")
    assert err.value.line == 5


# ----------------------------------------------------------------------------------------------
# The clock #3001
# ----------------------------------------------------------------------------------------------
def test_clock_reads_consume_the_sequence():
    text = prog(
        "#32=#3001",
        "#100=#32-FIX[#32/10]*10",    # last digit of 1234 -> 4
        "#32=#3001",
        "#101=#32-FIX[#32/10]*10",    # 5678 -> 8
        "#102=#3001-#3001",           # 90 - 100 = -10 (two reads, left first)
        "M30")
    run = run_program(text, clock=[1234, 5678, 90, 100])
    assert (run.var(100), run.var(101), run.var(102)) == (4.0, 8.0, -10.0)
    assert run.clock_reads == 4
    with pytest.raises(MacroError, match="ran out after 3 reads"):
        run_program(text, clock=[1234, 5678, 90])
    with pytest.raises(MacroError, match="no clock"):
        run_program(text)


def test_clock_wait_loop():
    run = run_program(prog(
        "#100=#3001",                       # 0
        "WHILE[[#3001-#100]LT1000]DO1",     # reads 300, 600, 900 (loop), 1200 (exit)
        "#101=#101+1",
        "END1",
        "M30"), clock=itertools.count(0, 300))
    assert run.var(101) == 3.0
    assert run.clock_reads == 5


# ----------------------------------------------------------------------------------------------
# Errors
# ----------------------------------------------------------------------------------------------
def test_unbalanced_brackets_of_the_published_macro_raise():
    text = prog("G90", "M30") + "O7023\n#1=#4001\nIF[#24+#25]EQ#0]GOTO25\nN25\nM99\n"
    with pytest.raises(MacroError, match="unbalanced brackets") as err:
        run_program(text)
    assert err.value.line == 8
    assert "IF[#24+#25]EQ#0]GOTO25" in str(err.value)
    # the corrected test parses and runs
    fixed = text.replace("IF[#24+#25]EQ#0]GOTO25", "IF[[#24EQ#0]AND[#25EQ#0]]GOTO25")
    assert run_program(fixed).ended_by == "M30"


@pytest.mark.parametrize("block, message", [
    ("G01K5.F100.", "address K"),
    ("G41X5.", "G41 is not supported"),
    ("G07X5.", "G7 is not supported"),
    ("M50", "M50 is not supported"),
    ("GOTO99", "no block N99"),
    ("IF[#1]GOTO1", "needs a condition"),
    ("G01X5.", "without a feed rate"),
    ("G02X10.I3.F100.", "not on the circle"),
    ("X5.X6.", "given twice"),
    ("#34=1.", "#34 is not supported"),
    ("#5001=1.", "cannot be assigned"),
    ("G01X", "has no value"),
    ("M99", "M99 in the main program"),
    ("WHILE[#1LT2]DO1", "without a matching END1"),
])
def test_errors_name_the_block(block, message):
    text = prog("G90", block, "M30")
    with pytest.raises(MacroError, match=message) as err:
        run_program(text)
    assert err.value.line == 4
    assert err.value.text == block


def test_runaway_loop_and_missing_m99():
    with pytest.raises(MacroError, match="max_blocks=1000") as err:
        run_program(prog("N1#100=#100+1", "GOTO1"), max_blocks=1000)
    assert err.value.line in (3, 4)
    with pytest.raises(MacroError, match="O9001 ends without M99"):
        run_program(prog("G65P9001", "M30") + "O9001\n#100=1\n")


def test_macro_alarm():
    with pytest.raises(MacroAlarm, match="TOO DEEP") as err:
        run_program(prog("#3000=12(TOO DEEP)", "M30"))
    assert err.value.number == 12.0 and err.value.line == 3


# ----------------------------------------------------------------------------------------------
# Motion details
# ----------------------------------------------------------------------------------------------
def test_arcs_ij_and_r():
    run = run_program(prog(
        "G90G17G00X10.Y0Z0",
        "G03X0Y10.I-10.J0F100.",      # CCW quarter about (0, 0)
        "G02X10.Y0R10.",              # CW short way (90 deg, from 90 to 0 deg) about (0, 0)
        "G02X0Y10.R-10.",             # CW long way (270 deg, from 0 down to 90) about (0, 0)
        "G03X10.Y0R10.",              # CCW short way about (10, 10): from 180 to 270 deg
        "G03X0Y10.R-10.",             # CCW long way about (10, 10): from 270 up to 180 deg
        "M30"))
    assert run.moves[0].kind == "rapid"
    arcs = run.moves[1:]
    assert [m.kind for m in arcs] == ["ccw", "cw", "cw", "ccw", "ccw"]
    assert (arcs[0].i, arcs[0].j) == (-10.0, 0.0)
    centres = [(0, 0), (0, 0), (0, 0), (10, 10), (10, 10)]
    for move, centre in zip(arcs, centres):
        assert move.center == pytest.approx(centre, abs=1e-9)
    assert arcs[2].start == pytest.approx((10, 0, 0))
    assert arcs[3].i == pytest.approx(10) and arcs[3].j == pytest.approx(0, abs=1e-9)


def test_incremental_g28_home_and_events():
    run = run_program(prog(
        "G59G90G00X96.521Y-58.024S6000T02",
        "G43Z100.H21",
        "Z20.M03",
        "G91G01X-10.F500.",           # incremental: 86.521
        "G00Z30.",                    # 50
        "G28Z0",                      # intermediate = here, then Z home
        "G28X0Y0M19",                 # no X/Y home configured: recorded only
        "M06",
        "M30"), home={"Z": 150.0})
    assert approx_xyz(run.moves) == [(96.521, -58.024, 0), (96.521, -58.024, 100), (96.521, -58.024, 20),
                                     (86.521, -58.024, 20), (86.521, -58.024, 50),
                                     (86.521, -58.024, 150)]
    kinds = [(e.kind, e.value) for e in run.events]
    assert ("WCS", 59.0) in kinds and ("T", 2.0) in kinds and ("S", 6000.0) in kinds
    assert ("G43", 21.0) in kinds and ("M", 19.0) in kinds and ("M", 6.0) in kinds
    assert [e.kind for e in run.events].count("G28") == 2
    assert run.modal["absolute"] is False and run.modal["wcs"] == 59


def test_several_programs_comments_and_sequence_numbers():
    programs = parse_programs("%\n(HEADER)\nO0001 (MAIN)\nN10 G90 (SET)\nN20 M30\n%\nO7023\nM99\n%\n")
    assert list(programs) == [1, 7023]
    assert [b.n for b in programs[1].blocks] == [10, 20]
    run = run_program("%\nO0001\nN10 G90 G00 X 1. Y 2. (spaces are ignored)\nN20 M30\n%\n")
    assert run.moves[0].end == (1.0, 2.0, 0.0)


# ----------------------------------------------------------------------------------------------
# A macro that splits X moves into 20 mm pieces with a depth per piece
# ----------------------------------------------------------------------------------------------
SPLIT = """%
O0001(SPLIT TEST)
G90G17G21G54
G00X0Y0Z2.
G01Z-0.5F300.
G66.1P7023X50.F600.
Y10.
X-5.
G67
G00Z5.
M30
%
O7023
IF[#9EQ#0]GOTO5
F#9
N5
IF[#24NE#0]GOTO20
G01Y#25Z#26
M99
N20
#11=#5001
#14=1.
IF[#24GE#11]GOTO30
#14=-1.
N30
#15=#11
WHILE[ABS[#24-#15]GT0.0001]DO1
#16=#15+#14*20.
IF[[#14*[#24-#16]]LT0]THEN#16=#24
#17=[#15+#16]/2
#18=-[0.5+0.01*ABS[#17]]
G01X#16Y#25Z#18
#15=#16
END1
M99
%
"""


def test_split_x_moves_into_20mm_pieces_with_computed_depth():
    run = run_program(SPLIT)
    # Each piece ends 20 mm further (the last one shorter) at depth -(0.5 + 0.01*|piece mid X|).
    # X0 -> X50: pieces [0,20] [20,40] [40,50], mids 10 30 45 -> Z -0.6 -0.8 -0.95
    # Y10. (no X): passed through, Z unchanged
    # X50 -> X-5: pieces [50,30] [30,10] [10,-5], mids 40 20 2.5 -> Z -0.9 -0.7 -0.525
    expected = [("rapid", (0, 0, 2)), ("feed", (0, 0, -0.5)),
                ("feed", (20, 0, -0.6)), ("feed", (40, 0, -0.8)), ("feed", (50, 0, -0.95)),
                ("feed", (50, 10, -0.95)),
                ("feed", (30, 10, -0.9)), ("feed", (10, 10, -0.7)), ("feed", (-5, 10, -0.525)),
                ("rapid", (-5, 10, 5))]
    assert [m.kind for m in run.moves] == [k for k, _ in expected]
    for move, (_, xyz) in zip(run.moves, expected):
        assert move.end == pytest.approx(xyz, abs=1e-9)
    assert [m.feed for m in run.moves] == [None, 300.0] + [600.0] * 7 + [None]
    assert [m.main_line for m in run.moves[2:9]] == [6, 6, 6, 7, 8, 8, 8]
    assert run.clock_reads == 0 and run.ended_by == "M30"


# ----------------------------------------------------------------------------------------------
# The published gouge macro, with its two defects corrected, on the paper's program frame
# ----------------------------------------------------------------------------------------------
def _gouge_pieces(body_sign):
    n = "23" if body_sign > 0 else "56"
    cmp_ = "GE" if body_sign > 0 else "LE"
    step = "+" if body_sign > 0 else "-"
    return f"""WHILE[#120{cmp_}#16]DO{1 if body_sign > 0 else 2}
#32=#3001
#30=FIX[#32/10]*10
#28=#32-#30
#110=#28*#29
IF[#28GE5]GOTO{n[0]}
#111=#18+#110
G#1X#16Y#25Z#111F#9
GOTO{n[1]}
N{n[0]}
#112=#28-5
#113=#112*#29
#114=#18-#113
G#1X#16Y#25Z#114F#9
N{n[1]}
#16=#16{step}20
END{1 if body_sign > 0 else 2}"""


GOUGE = f"""%
O0001
G59G90G00X96.521Y-58.024S6000T02
G43Z100.H21
Z20.M03
G01Z2.0F1000
Z-1.0F20
G66.1P7023X106.F20
Y-61.
X-106.
Y-64.
X-50.
G02X-40.Y-64.I5.J0
G00Z2.54
X-85.207Y-25.293
G01Z0.
G67
G00Z100.M05
G91G28Z0
G28X0Y0M19
M06
M30
%
O7023
N101
#1=#4001
#120=#24
IF[#1EQ0]GOTO10
IF[[#24EQ#0]AND[#25EQ#0]]GOTO25
#29=0.2
#18=-2.0
IF[#24EQ#0]GOTO20
#15=#5001
#16=#15
IF[#1GT1]GOTO10
#6=#16-#120
IF[ABS[#6]LE20]GOTO10
IF[#120LT#16]GOTO4
#16=#16+20
{_gouge_pieces(+1)}
GOTO10
N4
#16=#16-20
{_gouge_pieces(-1)}
N10
G#1X#120Y#25Z#26I#4J#5F#9
GOTO30
N20
G01Y#25F#9
GOTO30
N25
G01Z#26F10
N30
M99
%
"""


def test_the_papers_frame_is_refused():
    # The paper keeps G66.1 modal over an arc and rapids and has O7023 tell them apart by #4001:
    # refused at the first call, where the macro reads #4001.
    with pytest.raises(MacroError, match="#4001 read in a macro called by G66.1") as err:
        run_program(GOUGE, clock=itertools.count(12340, 11))
    assert err.value.text == "#1=#4001"
    # Without the #4001 read, at the arc kept under the modal call.
    without_4001 = GOUGE.replace("#1=#4001", "#1=1")
    with pytest.raises(MacroError, match="G2 in a block under G66.1") as err:
        run_program(without_4001, clock=itertools.count(12340, 11))
    assert err.value.text == "G02X-40.Y-64.I5.J0"


def _confined(text):
    """The paper's program with the macro confined to cutting: G67 before the arc and the
    rapids, which become ordinary blocks; O7023 writes G01 and reads no #4001."""
    for old, new in (("X-50.\nG02", "X-50.\nG67\nG02"), ("G01Z0.\nG67\n", "G01Z0.F10\n"),
                     ("#1=#4001\n", ""), ("IF[#1EQ0]GOTO10\n", ""), ("IF[#1GT1]GOTO10\n", "")):
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    return text.replace("G#1", "G01")


GOUGE_CONFINED = _confined(GOUGE)


def test_corrected_paper_macro_confined_to_cutting():
    # last clock digits 0..9, then 5, 4 -> depths -2.0 + 0.2 d (d <= 4) or -2.0 - 0.2 (d - 5) (d >= 5)
    clock = [12340, 12351, 12362, 12373, 12384, 12395, 12406, 12417, 12428, 12439, 12445, 12454]
    depth = [-2.0, -1.8, -1.6, -1.4, -1.2, -2.0, -2.2, -2.4, -2.6, -2.8, -2.0, -1.2]
    run = run_program(GOUGE_CONFINED, clock=clock)
    assert run.clock_reads == 12 and run.ended_by == "M30"
    y0 = -58.024
    expected = [
        ("rapid", (96.521, y0, 0)), ("rapid", (96.521, y0, 100)), ("rapid", (96.521, y0, 20)),
        ("feed", (96.521, y0, 2)), ("feed", (96.521, y0, -1)),
        ("feed", (106, y0, -1)),                      # G66.1 block: 9.479 mm <= 20, passed through
        ("feed", (106, -61, -1)),                     # stepover: no X word
    ]
    # X106 -> X-106: pieces end at 86, 66, ..., -94 (10 pieces), then the rest to -106 at the last depth
    expected += [("feed", (86 - 20 * k, -61, depth[k])) for k in range(10)]
    expected += [("feed", (-106, -61, depth[9])), ("feed", (-106, -64, depth[9]))]
    # X-106 -> X-50: pieces end at -86, -66, then the rest to -50
    expected += [("feed", (-86, -64, depth[10])), ("feed", (-66, -64, depth[11])),
                 ("feed", (-50, -64, depth[11]))]
    expected += [("cw", (-40, -64, depth[11])),      # the arc and the rapids after G67: as programmed
                 ("rapid", (-40, -64, 2.54)), ("rapid", (-85.207, -25.293, 2.54)),
                 ("feed", (-85.207, -25.293, 0)),    # Z-only move: G01 Z F10
                 ("rapid", (-85.207, -25.293, 100))]
    assert [m.kind for m in run.moves] == [k for k, _ in expected]
    for move, (_, xyz) in zip(run.moves, expected):
        assert move.end == pytest.approx(xyz, abs=1e-9)
    arc = run.moves[len(expected) - 5]
    assert arc.center == pytest.approx((-45, -64)) and arc.feed == 20.0
    assert run.moves[-2].feed == 10.0
    cutting = [m for m in run.moves[7:20]]
    assert all(m.feed == 20.0 for m in cutting)


def test_move_is_a_plain_record():
    m = Move("feed", 1.0, 2.0, 3.0, feed=100.0, line=5, start=(0.0, 0.0, 0.0))
    assert m.end == (1.0, 2.0, 3.0) and m.center is None


def test_significant_digits_round_stored_values():
    text = "%\nO0001\n#100=123456789\n#101=2987*32748\n#102=1/3\nM30\n%\n"
    run = run_program(text, significant_digits=8)
    assert run.var(100) == 123456790.0           # 9 digits do not fit: rounded to 8
    assert run.var(101) == 97818276.0            # below 1e8: an integer is kept exactly
    assert run.var(102) == 0.33333333
    assert run_program(text).var(100) == 123456789.0
    with pytest.raises(MacroError, match="significant_digits"):
        run_program(text, significant_digits=0)
