"""Every NC line within the length its control reads.

LinuxCNC's rs274 refuses a line that fills its 255-byte buffer ("Command too long"): NIST-style files
with long workingstep names and our NOTE comments ran past it.  The posts declare each control's
limit (ControllerLimits.max_line_length) and wrap comments to it; tests/controller_rules.py checks
the raw lines independently.  Here a workplan with a 1,000-character workingstep name, a 1,000-character
tool name (in the header, and in Grbl's load/change prompts) and a warning over 1,000 characters (the
switched-off workingstep, named in full) goes through every milling post that writes STEP-NC."""
import os

import pytest

import controller_rules as rules
import rs274
from kezuri.post import registry
from kezuri.toolpath.operations.stepnc.workplan import load_workplan, to_program
from test_stepnc import ex1_text, replace_instance

# the independent checker's name for each post's control
CONTROLS = {"fanuc": "fanuc-mill", "linuxcnc": "linuxcnc", "grbl": "grbl"}
LONG_NAME = ("WS FINISH PLANAR FACE1 " * 50)[:1000]
LONG_TOOL = "MILL-" + "X" * 995            # no space to wrap at: cut within the word


def long_program():
    text = replace_instance(ex1_text(), 10, f"#10= MACHINING_WORKINGSTEP('{LONG_NAME}',#62,#16,#19,$);")
    text = replace_instance(text, 14, f"#14= MACHINING_WORKINGSTEP('{LONG_NAME[:-1]}2',#62,#18,#23,$);")
    text = replace_instance(text, 39, f"#39= MILLING_CUTTING_TOOL('{LONG_TOOL}',#29,(#125),80.000,$,$);")
    return to_program(load_workplan(text), enabled=[10, 11, 12, 13])       # #14 switched off: a long warning


def milling_posts():
    return [cls for cls in registry.posts("milling", texture=False)]


def test_every_milling_post_declares_its_line_length():
    found = {cls.name: (cls.limits.max_line_length, cls.limits.line_length_source) for cls in milling_posts()}
    assert set(found) == set(CONTROLS), "a new milling post needs its control in CONTROLS"
    assert {name: limit for name, (limit, _) in found.items()} == {"fanuc": 252, "linuxcnc": 252, "grbl": 79}
    assert all(len(source) > 40 for _, source in found.values())


@pytest.mark.parametrize("name", sorted(CONTROLS))
def test_long_names_and_warnings_stay_within_the_line(name):
    program = long_program()
    assert max(len(note) for note in program.notes) > 1000
    cls = registry.find("milling", name)
    text = cls().to_text(program)
    lines = text.splitlines()
    assert max(len(line) for line in lines) <= cls.limits.max_line_length
    assert rules.check(text, CONTROLS[name]) == []
    # nothing is lost: the wrapped NOTE of the switched-off workingstep reads back whole
    notes, current = [], None
    for line in lines:
        if line.startswith("(NOTE: "):
            current = [line[len("(NOTE: "):-1]]
            notes.append(current)
        elif line.startswith("(  ") and current is not None:
            current.append(line[3:-1])
        else:
            current = None
    skipped = [" ".join(parts) for parts in notes if parts[0].startswith("WORKINGSTEP #14 ")]
    assert len(skipped) == 1
    # the reader keeps the first MAX_NAME (200) characters of a workingstep's name and says so
    name = (LONG_NAME[:-1] + "2")[:200] + "..."
    assert skipped[0].replace(" ", "") == (f"WORKINGSTEP #14 '{name}' SKIPPED: SWITCHED OFF [LEFT OUT "
                                           "OF THE ORDER TO CUT]").replace(" ", "")


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")
def test_rs274_accepts_the_long_program():
    text = registry.find("milling", "linuxcnc")().to_text(long_program())
    calls = rs274.run(text)
    assert sum(1 for name, _ in calls if name == "COMMENT") > 20


def test_the_rules_checker_finds_a_line_too_long():
    program = "%\nG21 G90\n(" + "A" * 251 + ")\nM30\n%\n"
    assert [rule for rule, _, _ in rules.check(program, "linuxcnc")] == ["length"]
    assert rules.check(program.replace("A" * 251, "A" * 250), "linuxcnc") == []
    grbl = "G21 G90\nG01 X" + "1" * 77 + " F100\nM30\n"     # 'G01X' + 77 digits + 'F100' = 85 > 79
    assert "length" in [rule for rule, _, _ in rules.check(grbl, "grbl")]


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC rs274 is not installed (.ci/run installs it)")
def test_252_characters_is_what_rs274_reads():
    """The LinuxCNC figure, measured on the interpreter itself: 252 characters pass, 253 do not."""
    ok = "(" + "A" * 250 + ")\nG00 X1\nM2\n"
    rs274.run(ok)
    with pytest.raises(AssertionError, match="too long"):
        rs274.run("(" + "A" * 251 + ")\nG00 X1\nM2\n")
    assert os.linesep == "\n"


def test_a_long_project_name_is_cut_like_a_workingstep_s_with_a_note():
    text = ex1_text()
    start = text.index("#1= PROJECT('") + len("#1= PROJECT('")
    end = text.index("'", start)
    text = text[:start] + "P" * 100_000 + text[end:]
    loaded = load_workplan(text)
    assert loaded.project.its_id == "P" * 200 + "..."
    assert "project #1: its name is 100000 characters; the first 200 are used, followed by ..." in loaded.warnings
    program = to_program(loaded)
    for name in sorted(CONTROLS):
        cls = registry.find("milling", name)
        lines = cls().to_text(program).splitlines()
        assert max(len(line) for line in lines) <= cls.limits.max_line_length
        assert len(lines) < 400           # the name's comment is a few lines, not 100,000 characters of them
