"""Job files name their tools from the tool library (``tool = 11``, ``tools = { drill = "T11" }``):
the program is the one the same tool typed as settings gives, and a tool the library has not, of
the wrong kind or angle, or given twice, is refused naming the file, the operation and the key."""
import os
import re

import pytest

pytest.importorskip("bpy")
from sheet_reader import read_sheet  # noqa: E402
from test_batch_job import run  # noqa: E402

from kezuri.toolpath.tooling import store  # noqa: E402
from kezuri.toolpath.tooling.library import LibraryTool  # noqa: E402

SETUP = '[setup]\nname = "holes"\nstock = [0, 0, -12, 100, 60, 0]\npost = "linuxcnc"\nmachine = "linuxcnc-manual"\n'
HOLES = "holes = [[20.0, 20.0], [80.0, 40.0]]\n"


@pytest.fixture
def library(tmp_path, monkeypatch):
    path = tmp_path / "config" / "tools.toml"
    store.save(str(path), store.SEEDS.with_tool(LibraryTool(12, "drill", 6.5, angle=135.0, flute_length=60.0))
               .with_tool(LibraryTool(13, "drill", 4.2, flute_length=33.0, stick_out=41.5, name="tap drill")))
    monkeypatch.setenv("KEZURI_TOOL_LIBRARY", str(path))
    return path


def job(tmp_path, operation: str, name="job.toml") -> str:
    path = tmp_path / name
    path.write_text(SETUP + '\n[[operations]]\nkind = "drill"\nname = "holes"\n' + HOLES + operation)
    return str(path)


def program(out) -> str:
    return open(os.path.join(out, "holes.ngc")).read()


def test_a_library_tool_gives_the_program_its_typed_twin(tmp_path, library):
    status, message, out = run("job", job(tmp_path, 'tool = "T13"\nsettings = { depth = 10.0, peck = 3.0 }\n'))
    assert status == 0, message
    typed = job(tmp_path, "settings = { depth = 10.0, peck = 3.0, tool_number = 13, diameter = 4.2, "
                          "flute_length = 33.0 }\n", "typed.toml")
    status, message, out_typed = run("job", typed)
    assert status == 0, message
    text = program(out)
    assert re.findall(r"^T(\d+) M0?6", text, re.M) == ["13"]
    strip = lambda t: re.sub(r"\(.*?\)", "", t)             # noqa: E731 - comments name the file and time
    assert strip(text) == strip(program(out_typed))


def stick_out_column(out) -> dict:
    table = read_sheet(open(os.path.join(out, "setup-sheet.html"), encoding="utf-8").read()).tables["tools"]
    column = table[0].index("Stick-out (mm)")
    return {row[0]: row[column] for row in table[1:]}


def test_the_setup_sheet_lists_the_library_tools_stick_out(tmp_path, library):
    status, message, out = run("job", job(tmp_path, 'tool = 13\nsettings = { depth = 10.0 }\n'))
    assert status == 0, message
    assert stick_out_column(out) == {"T13": "41.5"}
    # the same number typed as another tool (a 4.3 mm drill) is not the library's: its stick-out is not known
    typed = job(tmp_path, "settings = { depth = 10.0, tool_number = 13, diameter = 4.3 }\n", "typed.toml")
    status, message, out = run("job", typed)
    assert status == 0, message
    assert stick_out_column(out) == {"T13": "—"}


def test_slots_by_name(tmp_path, library):
    status, message, out = run("job", job(tmp_path, 'tools = { drill = 4 }\nsettings = { depth = 10.0 }\n'))
    assert status == 0, message
    assert re.findall(r"^T(\d+) M0?6", program(out), re.M) == ["4"]


@pytest.mark.parametrize("operation, words", [
    ("tool = 40\n", ["operation 1 ('holes')", "tool = 40", "no tool T40 in the tool library", "T1, T2"]),
    ("tool = 2\n", ["tool = 2 is T2 6 mm ball end mill", "the drill's drill tool must be a drill"]),
    ("tool = 12\n", ["tool = 12", "135° point", "planned for a 118° one"]),
    ("tool = 4\nsettings = { diameter = 5.0 }\n", ["settings.diameter and tool = 4 both give the drill tool"]),
    ("tool = 4\ntools = { mill = 5 }\n", ["give tool or tools, not both"]),
    ("tools = { router = 5 }\n", ["tools.router is not a tool of a drill; its tools are drill, mill, spot"]),
    ("tool = 4.5\n", ["tool = 4.5", "not a tool number"]),
])
def test_a_tool_that_cannot_be_used_is_refused_by_name(tmp_path, library, operation, words):
    status, message, _ = run("job", job(tmp_path, operation))
    assert status == 2
    for word in words:
        assert word in message, message


def test_the_sample_job_with_library_tools_writes_the_same_program(tmp_path, library):
    """The name plate job naming its tools from the presets (T2 ball, T3 flat, T4 drill) instead of
    the typed defaults: the same program, move for move, and the sheet has the presets' stick-outs."""
    sample = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "samples", "jobs",
                          "nameplate-with-holes.toml")
    text = open(sample, encoding="utf-8").read()
    named = text.replace("settings = { seed = 7 }", 'tools = { rough = 2, finish = "T3" }\nsettings = { seed = 7 }')
    named = named.replace("settings = { tool_number = 4, diameter = 5.0, depth", "tool = 4\nsettings = { depth")
    assert named.count("tool") >= 2 and named != text
    (tmp_path / "named.toml").write_text(named, encoding="utf-8")
    status, message, out_named = run("job", str(tmp_path / "named.toml"))
    assert status == 0, message
    status, message, out_typed = run("job", sample)
    assert status == 0, message
    strip = lambda t: re.sub(r"\(.*?\)", "", t)             # noqa: E731 - comments name the file and time
    named_text = open(os.path.join(out_named, "nameplate.ngc")).read()
    assert strip(named_text) == strip(open(os.path.join(out_typed, "nameplate.ngc")).read())
    assert len(named_text.splitlines()) > 1000
    assert stick_out_column(out_named) == {"T2": "30", "T3": "15", "T4": "50"}


def test_a_library_v_bit_gives_a_v_carve_its_angle(tmp_path):
    """A 60 deg V-bit named from the library: the V-carve's tool is that cone (its tip angle in the
    program's tool), a 90 deg one is the kind's own; the end mill fills the clear slot."""
    from kezuri.toolpath.tooling.library import LibraryTool

    sixty = LibraryTool(number=7, kind="vbit", diameter=12.7, angle=60.0, flutes=2, flute_length=12.0)
    ninety = LibraryTool(number=8, kind="vbit", diameter=12.7, angle=90.0, flutes=2, flute_length=12.0)
    assert sixty.to_ir_tool().shape.tip_angle_deg == pytest.approx(60.0)
    assert ninety.to_ir_tool().tip_angle == 0.0 and ninety.to_ir_tool().shape.tip_angle_deg == pytest.approx(90.0)
    from kezuri.operators import jobtools
    from kezuri.toolpath.tooling.library import ToolLibrary

    library = ToolLibrary((sixty, ninety, LibraryTool(number=4, kind="flat", diameter=3.175, flutes=2,
                                                       flute_length=12.0)))
    found = jobtools.tool_settings({"tools": {"tool": 7, "clear": "T4"}}, "vcarve", {}, "job.toml: sign",
                                   lambda: library)
    assert found == {"tool_number": 7, "diameter": 12.7, "flute_length": 12.0, "angle": 60.0,
                     "clear_tool_number": 4, "clear_diameter": 3.175, "clear_flute_length": 12.0}


def test_the_feeds_check_takes_flutes_and_tool_material_from_the_library(tmp_path, monkeypatch):
    """A job in hardwood drilling with T13, a 1-flute HSS drill in the library: the feeds entry takes
    its flutes and material from the library; a drill's chip load is its feed per revolution,
    feed / rpm, whatever its flutes (the 2-flute carbide assumed without the library too)."""
    import json

    path = tmp_path / "config" / "tools.toml"
    store.save(str(path), store.SEEDS.with_tool(LibraryTool(13, "drill", 4.2, flutes=1, material="hss",
                                                            flute_length=33.0)))
    setup = SETUP.replace('machine = "linuxcnc-manual"\n', 'machine = "linuxcnc-manual"\nmaterial = "hardwood"\n')
    file = tmp_path / "job.toml"
    file.write_text(setup + '\n[[operations]]\nkind = "drill"\nname = "holes"\n' + HOLES
                    + 'tool = 13\nsettings = { depth = 10.0, rpm = 3000.0, feed = 150.0 }\n')
    monkeypatch.setenv("KEZURI_TOOL_LIBRARY", str(path))
    status, message, out = run("job", str(file))
    assert status == 0, message
    entry = json.load(open(os.path.join(out, "report.json")))["feeds"][0]
    assert entry["flutes"] == 1 and entry["tool_material"] == "hss" and entry["assumed"] == []
    assert entry["chip_load_mm"] == pytest.approx(150.0 / 3000.0, abs=1e-4)       # 0.05 mm per tooth
    # a typed tool the library does not hold: assumed 2-flute carbide, and said so
    typed = tmp_path / "typed.toml"
    typed.write_text(setup + '\n[[operations]]\nkind = "drill"\nname = "holes"\n' + HOLES
                     + 'settings = { depth = 10.0, rpm = 3000.0, feed = 150.0, tool_number = 31, diameter = 4.2 }\n')
    status, message, out = run("job", str(typed))
    assert status == 0, message
    entry = json.load(open(os.path.join(out, "report.json")))["feeds"][0]
    assert entry["flutes"] == 2 and set(entry["assumed"]) == {"flutes", "tool material"}
    assert entry["chip_load_mm"] == pytest.approx(150.0 / 3000.0, abs=1e-4)       # per revolution
    assert entry["chip_load_per"] == "revolution"
