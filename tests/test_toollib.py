"""The tool library's core: its record's checks, the three file formats read from files written by
hand in each format's published conventions (tests/fixtures/tools), round trips field by field,
and hostile files refused with the file, the line or entry and the field named."""
import math
import os
import re

import pytest
import rs274

from kezuri.toolpath.tooling import formats, fusion_library, kezuri_format, linuxcnc_table
from kezuri.toolpath.tooling.library import LibraryTool, ToolLibrary, ToolLibraryError, tool_number

FIXTURES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fixtures", "tools")


def fixture(name):
    return os.path.join(FIXTURES, name)


def fields(library):
    return {t.number: t.as_dict() for t in library}


# ---- the record ----------------------------------------------------------------------------------

def test_a_ball_takes_its_radius_as_corner_and_gives_the_program_tool():
    tool = LibraryTool(2, "ball", 6.0, flute_length=20.0, name="rough")
    assert tool.corner_radius == 3.0
    ir = tool.to_ir_tool()
    assert (ir.number, ir.kind, ir.diameter, ir.corner_radius, ir.flute_length, ir.name) == (2, "ball", 6.0, 3.0,
                                                                                           20.0, "rough")
    engraver = LibraryTool(17, "engraver", 3.175, angle=30.0).to_ir_tool()
    assert (engraver.kind, engraver.label) == ("vbit", "engraver")
    assert LibraryTool(4, "drill", 5.0).angle == 118.0


@pytest.mark.parametrize("args, words", [
    (dict(number=1, kind="flat", diameter=0.0), ["T1", "diameter", "positive"]),
    (dict(number=1, kind="flat", diameter=-3.0), ["T1", "diameter", "positive"]),
    (dict(number=1, kind="flat", diameter=float("nan")), ["T1", "diameter", "not a number"]),
    (dict(number=1, kind="flat", diameter=float("inf")), ["T1", "diameter", "not a number"]),
    (dict(number=1, kind="bull", diameter=6.0, corner_radius=3.5), ["T1", "corner_radius 3.5", "radius 3"]),
    (dict(number=1, kind="bull", diameter=6.0), ["T1", "corner_radius 0"]),
    (dict(number=1, kind="ball", diameter=6.0, corner_radius=2.0), ["T1", "radius 3"]),
    (dict(number=1, kind="flat", diameter=6.0, corner_radius=1.0), ["T1", "no corner radius"]),
    (dict(number=1, kind="vbit", diameter=6.0), ["T1", "needs its included angle"]),
    (dict(number=1, kind="vbit", diameter=6.0, angle=180.0), ["T1", "angle 180.0", "1..179"]),
    (dict(number=1, kind="vbit", diameter=6.0, angle=0.5), ["T1", "angle 0.5", "1..179"]),
    (dict(number=1, kind="flat", diameter=6.0, angle=90.0), ["T1", "no tip angle"]),
    (dict(number=0, kind="flat", diameter=6.0), ["tool number 0", "1..999"]),
    (dict(number=1000, kind="flat", diameter=6.0), ["tool number 1000"]),
    (dict(number=True, kind="flat", diameter=6.0), ["tool number True"]),
    (dict(number=1, kind="router", diameter=6.0), ["T1", "kind 'router'", "flat, ball"]),
    (dict(number=1, kind="flat", diameter=6.0, flutes=0), ["T1", "flutes 0"]),
    (dict(number=1, kind="flat", diameter=6.0, flutes=2.5), ["T1", "flutes 2.5"]),
    (dict(number=1, kind="flat", diameter=6.0, material="cobalt"), ["T1", "material 'cobalt'", "carbide, hss"]),
    (dict(number=1, kind="flat", diameter=6.0, stick_out=0.0), ["T1", "stick_out", "positive"]),
])
def test_the_record_refuses_what_no_tool_is(args, words):
    with pytest.raises(ToolLibraryError) as error:
        LibraryTool(**args)
    for word in words:
        assert word in str(error.value)


def test_a_duplicate_number_is_refused_naming_both():
    with pytest.raises(ToolLibraryError) as error:
        ToolLibrary([LibraryTool(3, "flat", 1.0, name="small"), LibraryTool(3, "ball", 6.0, name="big")],
                    ["line 5", "line 9"])
    text = str(error.value)
    assert "T3" in text and "line 5" in text and "line 9" in text and "small" in text and "big" in text


def test_numbers_as_job_files_give_them():
    assert tool_number(3) == 3 and tool_number("T3") == 3 and tool_number(" t12 ") == 12 and tool_number("7") == 7
    for bad in ("T", "3.5", "T-1", 3.0, True, None):
        with pytest.raises(ToolLibraryError):
            tool_number(bad)
    library = ToolLibrary([LibraryTool(3, "flat", 1.0)])
    with pytest.raises(ToolLibraryError, match=r"no tool T4 in the tool library \(it has T3\)"):
        library.get("T4")


def test_merge_refuses_a_clash_naming_both_and_replaces_only_when_asked():
    library = ToolLibrary([LibraryTool(1, "flat", 6.0, name="old"), LibraryTool(2, "ball", 6.0)])
    incoming = ToolLibrary([LibraryTool(1, "flat", 8.0, name="new"), LibraryTool(5, "drill", 5.0),
                            LibraryTool(2, "ball", 6.0)])
    with pytest.raises(ToolLibraryError) as error:
        library.merged(incoming, source="shop.tbl")
    assert "T1: shop.tbl has T1 8 mm flat end mill (new), the library has T1 6 mm flat end mill (old)" in str(error.value)
    merged, added, replaced = library.merged(incoming, replace=True)
    assert (added, replaced) == ((5,), (1,))            # T2 is the same tool: neither added nor replaced
    assert [(t.number, t.diameter) for t in merged] == [(1, 8.0), (2, 6.0), (5, 5.0)]


# ---- LinuxCNC tool tables ------------------------------------------------------------------------

def test_a_linuxcnc_table_reads_number_diameter_and_kind_from_the_comment():
    library, notes = formats.read_path(fixture("shop.tbl"))
    got = {t.number: (t.kind, t.diameter, t.corner_radius, t.angle, t.name) for t in library}
    assert got == {1: ("flat", 6.0, 0.0, None, "6mm flat 2 flute"),
                   2: ("ball", 6.0, 3.0, None, "6 mm ball nose"),
                   3: ("flat", 1.0, 0.0, None, "1mm end mill for the bands"),
                   7: ("vbit", 12.0, 0.0, 90.0, "90 deg V-Bit"),
                   12: ("drill", 5.0, 0.0, 118.0, "5mm jobber drill"),
                   15: ("flat", 3.175, 0.0, None, "")}
    assert len(notes) == 6 and notes[0].startswith(f"{fixture('shop.tbl')}: line 4 (T1)")
    assert "taken as a vbit from the comment (angle 90°)" in notes[3]
    assert "taken as a drill from the comment (angle 118°)" in notes[4] and "(angle -)" in notes[0]


def test_an_inch_table_is_read_in_inches_when_told():
    library, _ = formats.read_path(fixture("shop-inch.tbl"), units="inch")
    assert [(t.number, t.kind, t.diameter) for t in library] == [(1, "flat", 6.35), (2, "ball", 3.175)]


# ---- Fusion 360 ----------------------------------------------------------------------------------

def test_a_fusion_library_reads_every_field_it_holds():
    library, notes = formats.read_path(fixture("fusion-library.json"))
    assert library.numbers() == (1, 4, 8, 9, 14, 21)
    t1 = library.get(1)
    assert t1.as_dict() == {"number": 1, "kind": "flat", "diameter": 6.0, "corner_radius": 0.0, "angle": None,
                            "flutes": 2, "flute_length": 22.0, "stick_out": 30.0, "holder_diameter": 32.0,
                            "material": "carbide", "vendor": "Example Tools", "product_id": "UC-2F-6",
                            "name": "6mm 2 flute upcut"}
    assert (library.get(8).kind, library.get(8).angle, library.get(8).diameter) == ("vbit", 60.0, 6.35)  # TA 30
    assert (library.get(4).kind, library.get(4).angle, library.get(4).material) == ("drill", 135.0, "hss")
    assert (library.get(9).corner_radius, library.get(14).corner_radius, library.get(14).flutes) == (1.5, 1.0, 4)
    inch = library.get(21)                                  # 1/4 in, 0.75 in of flutes, 1 in below the holder
    assert (inch.diameter, inch.flute_length, inch.stick_out) == pytest.approx((6.35, 19.05, 25.4), rel=1e-12)
    assert len(notes) == 2 and "entry 7" in notes[0] and "'probe'" in notes[0] and "entry 8" in notes[1]


# ---- Kezuri's own file, and round trips ---------------------------------------------------------

KEZURI_EXPECTED = {
    2: {"number": 2, "kind": "ball", "diameter": 6.0, "corner_radius": 3.0, "angle": None, "flutes": 2,
        "flute_length": 20.0, "stick_out": 31.5, "holder_diameter": 19.0, "material": "carbide",
        "vendor": "Example Tools", "product_id": "BN-6-20", "name": "6 mm ball (roughing)"},
    7: {"number": 7, "kind": "vbit", "diameter": 12.0, "corner_radius": 0.0, "angle": 90.0, "flutes": 2,
        "flute_length": 10.0, "stick_out": None, "holder_diameter": None, "material": "carbide", "vendor": "",
        "product_id": "", "name": "90° V-bit; \"sign\" work"},
}


def test_kezuri_file_reads_field_by_field():
    library, notes = formats.read_path(fixture("kezuri-tools.toml"))
    assert notes == [] and library.numbers() == (2, 3, 4, 7, 14, 17)
    got = fields(library)
    assert got[2] == KEZURI_EXPECTED[2] and got[7] == KEZURI_EXPECTED[7]
    assert (got[17]["kind"], got[17]["angle"], got[17]["flutes"], got[17]["diameter"]) == ("engraver", 30.0, 1, 3.175)


@pytest.mark.parametrize("source", ["kezuri-tools.toml", "fusion-library.json", "shop.tbl",
                                    "freecad/Library/shop.fctl"])
@pytest.mark.parametrize("target", formats.NAMES)
def test_every_format_gives_the_same_library_back_field_by_field(source, target, tmp_path):
    library, _ = formats.read_path(fixture(source))
    path = str(tmp_path / "Library" / f"out{formats.EXTENSIONS[target][0]}")
    for name, text in formats.files_for(path, library):
        os.makedirs(os.path.dirname(name), exist_ok=True)
        with open(name, "w", encoding="utf-8") as stream:
            stream.write(text)
    again, notes = formats.read_path(path)
    assert notes == []
    assert fields(again) == fields(library)


def test_an_inch_table_written_reads_back_in_inches():
    library, _ = formats.read_path(fixture("kezuri-tools.toml"))
    text = linuxcnc_table.write_text(library, "inch")
    assert "T3 P3 D0.03937007874" in text               # 1 mm / 25.4
    again, _ = linuxcnc_table.read_text(text, "x.tbl", "inch")
    for a, b in zip(library, again):
        assert math.isclose(a.diameter, b.diameter, rel_tol=1e-9) and a.kind == b.kind and a.angle == b.angle


def test_the_linuxcnc_export_keeps_the_words_linuxcnc_reads():
    library, _ = formats.read_path(fixture("kezuri-tools.toml"))
    lines = linuxcnc_table.write_text(library).splitlines()
    assert lines[0].startswith(";")
    assert lines[1].startswith("T2 P2 D6 ;6 mm ball (roughing) kezuri{")
    for line in lines[1:]:
        words = line.split(";")[0].split()
        assert [w[0] for w in words] == ["T", "P", "D"] and words[0][1:] == words[1][1:]


def test_a_name_a_table_cannot_hold_is_refused_not_changed():
    library = ToolLibrary([LibraryTool(1, "flat", 6.0, name="two\nlines")])
    with pytest.raises(ToolLibraryError, match="T1: its name 'two\\\\nlines' cannot stand"):
        linuxcnc_table.write_text(library)


def test_fusion_export_uses_fusions_keys():
    import json
    library, _ = formats.read_path(fixture("kezuri-tools.toml"))
    data = json.loads(fusion_library.write_text(library))["data"]
    vbit = next(e for e in data if e["post-process"]["number"] == 7)
    assert vbit["type"] == "chamfer mill" and vbit["geometry"]["TA"] == 45.0 and vbit["unit"] == "millimeters"
    ball = next(e for e in data if e["post-process"]["number"] == 2)
    assert ball["geometry"] == {"DC": 6.0, "NOF": 2, "LCF": 20.0, "LB": 31.5, "OAL": 31.5, "RE": 3.0}
    assert ball["holder"]["segments"][0]["lower-diameter"] == 19.0 and ball["product-id"] == "BN-6-20"


# ---- hostile files -------------------------------------------------------------------------------

HEADER = 'format = "kezuri-tools"\nversion = 1\nunits = "mm"\n'
TOOL = '\n[[tools]]\nnumber = 1\nkind = "flat"\ndiameter = 6.0\n'

HOSTILE = [
    ("kezuri", "", ["x.toml", "format = None"]),
    ("kezuri", HEADER + TOOL + '\n[[tools]]\nnumber = 2\nkind = "fla', ["x.toml", "not TOML", "end of document"]),
    ("kezuri", HEADER + TOOL.replace("6.0", "") + TOOL, ["x.toml", "not TOML", "line 8"]),
    ("kezuri", HEADER + TOOL.replace('kind = "flat"\n', ""), ["x.toml: line 5 (tool 1)", "'kind' is missing"]),
    ("kezuri", HEADER + TOOL + "colour = 3\n", ["x.toml: line 5 (tool 1)", "unknown field 'colour'"]),
    ("kezuri", HEADER + "owner = 1\n" + TOOL, ["x.toml", "unknown key 'owner'"]),
    ("kezuri", HEADER + TOOL + TOOL, ["T1 is given twice", "line 5 (tool 1)", "line 10 (tool 2)"]),
    ("kezuri", HEADER.replace('"mm"', '"inch"') + TOOL, ["units = 'inch'"]),
    ("kezuri", HEADER.replace("version = 1", "version = 2") + TOOL, ["version = 2"]),
    ("kezuri", HEADER + TOOL.replace("6.0", "nan"), ["line 5 (tool 1)", "diameter nan is not a number"]),
    ("kezuri", HEADER + TOOL.replace("6.0", '"6"'), ["line 5 (tool 1)", "diameter '6' is not a number"]),
    ("kezuri", HEADER + TOOL + "stick_out = [1]\n", ["line 5 (tool 1)", "stick_out = [1]"]),
    ("tbl", "T1 P1 D6 ;a\nT2 P2 ;no diameter\n", ["x.tbl: line 2 (T2)", "no D word"]),
    ("tbl", "T1 P1 D6\nP2 D3\n", ["x.tbl: line 2", "no T word"]),
    ("tbl", "T1 P1 D6\nT1 P2 D3\n", ["T1 is given twice", "x.tbl: line 1 (T1)", "x.tbl: line 2 (T1)"]),
    ("tbl", "T1 P1 Dnan\n", ["x.tbl: line 1", "'Dnan' is not a finite number"]),
    ("tbl", "T1 P1 D6 K3\n", ["x.tbl: line 1", "'K3' is not a tool table word"]),
    ("tbl", "T1 P1 D6 D7\n", ["x.tbl: line 1", "D is given twice"]),
    ("tbl", "T1.5 P1 D6\n", ["x.tbl: line 1", "'T1.5'", "whole number"]),
    ("tbl", "T1 P1 D6\nT2 P2 D-3\n", ["x.tbl: line 2 (T2)", "diameter -3.0 must be positive"]),
    ("tbl", 'T1 P1 D6 ;x kezuri{"kind":"flat","colour":1}\n', ["line 1 (T1)", "unknown field 'colour'"]),
    ("tbl", 'T1 P1 D6 ;x kezuri{"kind":"flat",\n', ["line 1 (T1)", "is not JSON"]),
    ("fusion", '{"data": [', ["x.json", "not JSON", "line 1"]),
    ("fusion", '{"tools": []}', ["x.json", "no \"data\" list"]),
    ("fusion", '{"data": [{"type": "flat end mill", "unit": "millimeters", "geometry": {"DC": 6}}]}',
     ["x.json: entry 1", "post-process.number"]),
    ("fusion", '{"data": [{"type": "flat end mill", "unit": "millimeters", "geometry": {}, '
               '"post-process": {"number": 3}}]}', ["x.json: entry 1 (T3)", "DC is missing"]),
    ("fusion", '{"data": [{"type": "flat end mill", "unit": "furlongs", "geometry": {"DC": 6}, '
               '"post-process": {"number": 3}}]}', ["entry 1 (T3)", "unit = 'furlongs'"]),
    ("fusion", '{"data": [{"type": "flat end mill", "geometry": {"DC": 6}, "post-process": {"number": 3}}]}',
     ["entry 1 (T3)", "unit = None"]),
    ("fusion", '{"data": [{"type": "flat end mill", "unit": "millimeters", "geometry": {"DC": NaN}, '
               '"post-process": {"number": 3}}]}', ["entry 1 (T3)", "DC = nan is not a number"]),
    ("fusion", '{"data": [{"type": "chamfer mill", "unit": "millimeters", "geometry": {"DC": 6}, '
               '"post-process": {"number": 3}}]}', ["entry 1 (T3)", "TA is missing"]),
    ("fusion", '{"data": [{"type": "flat end mill", "unit": "millimeters", "geometry": {"DC": 6}, "BMC": "wood", '
               '"post-process": {"number": 3}}]}', ["entry 1 (T3)", "BMC = 'wood'"]),
    ("fusion", '{"data": [{"type": "flat end mill", "unit": "millimeters", "geometry": {"DC": 6}, '
               '"post-process": {"number": 3}}, {"type": "drill", "unit": "millimeters", "geometry": {"DC": 5}, '
               '"post-process": {"number": 3}}]}', ["T3 is given twice", "entry 1 (T3)", "entry 2 (T3)"]),
]


@pytest.mark.parametrize("fmt, text, words", HOSTILE)
def test_a_hostile_file_is_refused_naming_file_place_and_field(fmt, text, words):
    path = {"kezuri": "x.toml", "tbl": "x.tbl", "fusion": "x.json"}[fmt]
    with pytest.raises(ToolLibraryError) as error:
        formats.parse(text, path, fmt)
    for word in words:
        assert word in str(error.value), str(error.value)


# ---- FreeCAD ------------------------------------------------------------------------------------

def test_a_freecad_library_reads_its_bits():
    library, notes = formats.read_path(fixture("freecad/Library/shop.fctl"))
    assert library.numbers() == (1, 2, 4, 5, 6, 7)
    assert library.get(1).as_dict() == {"number": 1, "kind": "flat", "diameter": 5.0, "corner_radius": 0.0,
                                         "angle": None, "flutes": 3, "flute_length": 30.0, "stick_out": None,
                                         "holder_diameter": None, "material": "hss", "vendor": "", "product_id": "",
                                         "name": "5mm Endmill"}
    assert (library.get(2).kind, library.get(2).corner_radius, library.get(2).material) == ("ball", 3.0, "carbide")
    assert (library.get(4).kind, library.get(4).corner_radius) == ("bull", 1.5)      # 3 mm radius - 1.5 mm flat
    assert (library.get(5).kind, library.get(5).angle, library.get(5).diameter) == ("vbit", 60.0, 10.0)
    assert (library.get(6).kind, library.get(6).angle) == ("drill", 119.0)
    assert (library.get(7).diameter, library.get(7).flute_length) == pytest.approx((6.35, 19.05), rel=1e-12)
    assert len(notes) == 2 and "FlatRadius 0.5 mm" in notes[0] and "'probe.fcstd'" in notes[1]


def test_a_freecad_export_keeps_freecads_layout(tmp_path):
    import json
    library, _ = formats.read_path(fixture("kezuri-tools.toml"))
    files = dict(formats.files_for(str(tmp_path / "Tools" / "Library" / "shop.fctl"), library))
    bit = json.loads(files[str(tmp_path / "Tools" / "Bit" / "shop-T14.fctb")])
    assert bit["shape"] == "bullnose.fcstd" and bit["parameter"]["FlatRadius"] == "2.0 mm"
    assert json.loads(files[str(tmp_path / "Tools" / "Library" / "shop.fctl")])["tools"][0] == \
        {"nr": 2, "path": "shop-T2.fctb"}
    assert list(files)[-1].endswith("shop.fctl")            # the library last: it never names a bit not written


FREECAD_HOSTILE = [
    ("missing.fctb", None, ["tool 1", "the bit file 'missing.fctb' is not there"]),
    ("b.fctb", '{"version": 2, "name": "x", "shape": "endmill.fcstd", "parameter": {"Diameter": "6 furlong"}}',
     ["tool 1 (T3, b.fctb)", "Diameter = '6 furlong'", "unit 'furlong'"]),
    ("b.fctb", '{"version": 2, "name": "x", "shape": "endmill.fcstd", "parameter": {"Diameter": "nan mm"}}',
     ["tool 1 (T3, b.fctb)", "not a quantity"]),
    ("b.fctb", '{"version": 2, "name": "x", "shape": "endmill.fcstd", "parameter": {}}',
     ["tool 1 (T3, b.fctb)", "Diameter is missing"]),
    ("b.fctb", '{"version": 2, "shape": "endmill.fcstd", "parameter": {"Diameter": "6 mm"}, '
               '"attribute": {"Kezuri": "{\\"colour\\": 1}"}}', ["(T3, b.fctb)", "unknown field 'colour'"]),
    ("b.fctb", '{"version": 2, "shape": "endmill.fcstd", "parameter": {"Diameter": "6 mm"}, '
               '"attribute": {"Material": "Wood"}}', ["(T3, b.fctb)", "Material = 'Wood'"]),
    ("b.fctb", '{"version": 2, "shape": "endmill.fcstd", "parameter": {"Diameter": "6 mm"', ["b.fctb", "not JSON"]),
]


@pytest.mark.parametrize("bit, text, words", FREECAD_HOSTILE)
def test_a_hostile_freecad_library_is_refused_by_name(tmp_path, bit, text, words):
    (tmp_path / "lib.fctl").write_text('{"version": 1, "tools": [{"nr": 3, "path": "%s"}]}' % bit)
    if text is not None:
        (tmp_path / bit).write_text(text)
    with pytest.raises(ToolLibraryError) as error:
        formats.read_path(str(tmp_path / "lib.fctl"))
    for word in words:
        assert word in str(error.value), str(error.value)


def test_files_that_are_not_text_or_not_there(tmp_path):
    with pytest.raises(ToolLibraryError, match="no such file"):
        formats.read_path(str(tmp_path / "none.tbl"))
    binary = tmp_path / "b.tbl"
    binary.write_bytes(b"T1 P1 D6\n\xff\xfe\n")
    with pytest.raises(ToolLibraryError, match=r"b.tbl: line 2: not UTF-8"):
        formats.read_path(str(binary))
    with pytest.raises(ToolLibraryError, match=r"which tool library format is \.xls"):
        formats.read_path(str(tmp_path / "a.xls"))
    with pytest.raises(ToolLibraryError, match="'csv' is not one of kezuri, tbl, fusion, freecad"):
        formats.format_of("a.tbl", "csv")
    with pytest.raises(ToolLibraryError, match="--units is for tool tables"):
        formats.parse("{}", "a.json", "fusion", "inch")


def test_the_kezuri_writer_escapes_what_toml_must():
    library = ToolLibrary([LibraryTool(1, "flat", 6.0, name='quote " back \\ tab\t del\x7f nl\n',
                                       vendor="日本の工具")])
    again, _ = kezuri_format.read_text(kezuri_format.write_text(library), "x.toml")
    assert again == library


@pytest.mark.skipif(not rs274.available(), reason="LinuxCNC's rs274 is not installed")
def test_linuxcnc_reads_the_exported_table(tmp_path):
    """LinuxCNC's own tool-table reader (rs274 -t) loads the export: each tool's diameter, as the
    controller's #5410 gives it after T.. M6, is the library's."""
    import subprocess

    library, _ = formats.read_path(fixture("kezuri-tools.toml"))
    table = tmp_path / "tool.tbl"
    table.write_text(linuxcnc_table.write_text(library))
    program = "".join(f"T{t.number} M6\n(DEBUG, T{t.number} D#5410)\n" for t in library) + "M2\n"
    (tmp_path / "p.ngc").write_text(program)
    done = subprocess.run([rs274.RS274, "-t", str(table), "-g", str(tmp_path / "p.ngc"), str(tmp_path / "out.txt")],
                          stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60,
                          env=dict(os.environ, HOME=str(tmp_path)))
    out = (tmp_path / "out.txt").read_text()
    assert done.returncode == 0, done.stdout + done.stderr
    said = dict(re.findall(r'MESSAGE\(" T(\d+) D([-0-9.]+)"\)', out))
    assert {int(k): float(v) for k, v in said.items()} == {2: 6.0, 3: 1.0, 4: 5.0, 7: 12.0, 14: 6.0, 17: 3.175}
