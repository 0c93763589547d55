"""The setup sheet as a reader sees it: the HTML is parsed with the standard library's html.parser
(tests/sheet_reader.py) and its numbers compared with values worked out by hand from the moves."""
import re
import struct
import zlib

import numpy as np
import pytest

from kezuri.toolpath.ir.program import FEED, RAPID, Operation, Program, Tool
from kezuri.toolpath.pictures import setupsheet
from kezuri.toolpath.simulate import BoxStock, CylinderStock
from sheet_reader import read_sheet, seconds


def png(width=2, height=1, rgb=(200, 30, 30)) -> bytes:
    """A PNG written here from the format's chunks (signature, IHDR, IDAT, IEND), not by the code under test."""
    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    rows = b"".join(b"\x00" + bytes(rgb) * width for _ in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def operation(name, tool, rpm, moves, start=(0.0, 0.0, 50.0)):
    kind = [k for k, _, _ in moves]
    xyz = [p for _, p, _ in moves]
    feed = [np.nan if f is None else f for _, _, f in moves]
    return Operation(name, tool, rpm, np.array(kind), np.array(xyz, float), np.array(feed, float),
                     start=np.array(start))


def two_tool_program(name="PLATE-01"):
    """Face: rapids 45 + 51 mm at 5000 mm/min (1.152 s), plunge 6 mm at F200 (1.8 s), 1000 mm at F500
    (120 s): 122.952 s.  Pencil: rapids 48 + 50.5 mm (1.182 s), plunge 2.5 mm at F100 (1.5 s), 3000 mm
    at F1000 (180 s): 182.682 s.  Together 305.634 s."""
    flat = Tool(5, "flat", 6.0, flute_length=22.0, name="facing")
    ball = Tool(12, "ball", 3.0)
    face = operation("face", flat, 10000, [(RAPID, (0, 0, 5), None), (FEED, (0, 0, -1), 200.0),
                                           (FEED, (1000, 0, -1), 500.0), (RAPID, (1000, 0, 50), None)])
    pencil = operation("pencil", ball, 18000, [(RAPID, (0, 0, 2), None), (FEED, (0, 0, -0.5), 100.0),
                                               (FEED, (0, 3000, -0.5), 1000.0), (RAPID, (0, 3000, 50), None)])
    return Program(name, [face, pencil], work_offset="G55", rapid_rate=5000.0)


PASSED = {"findings": [], "overridden": False}


def test_tools_operations_times_and_total_as_worked_out_by_hand():
    sheet = setupsheet.sheet_from(two_tool_program(), {"gate": PASSED}, "Hobby router (GRBL)", "GRBL",
                                  [("Toolpaths", png())], stock=BoxStock(0, 0, -10, 200, 100, 0),
                                  programs=[setupsheet.program_file("plate.nc", b"G21\nG90\nM30\n")])
    page = read_sheet(setupsheet.setup_sheet(sheet))
    tools = page.rows("tools")
    assert [(t["Tool"], t["Kind"], float(t["Diameter (mm)"]), float(t["Flute length (mm)"]), t["Stick-out (mm)"])
            for t in tools] == [("T5", "flat", 6.0, 22.0, "\u2014"), ("T12", "ball", 3.0, 20.0, "\u2014")]
    assert float(tools[1]["Corner R (mm)"]) == 1.5                   # a ball's corner is its radius
    ops = page.rows("operations")
    assert [(o["Operation"], o["Tool"], float(o["Spindle (rpm)"]), float(o["Feed (mm/min)"]),
             float(o["Plunge (mm/min)"]), int(o["Moves"])) for o in ops] == \
        [("face", "T5", 10000, 500, 200, 4), ("pencil", "T12", 18000, 1000, 100, 4)]
    assert [seconds(o["Time (h:mm:ss)"]) for o in ops] == [123, 183]    # 122.952 s, 182.682 s
    total = seconds(page.texts["total"].replace("Total", "").strip())
    assert total == 306                                                  # 305.634 s
    assert abs(sum(seconds(o["Time (h:mm:ss)"]) for o in ops) - total) <= 0.5 * len(ops)
    setup = page.texts["setup"]
    assert "G55" in setup and "Hobby router (GRBL)" in setup and "GRBL" in setup
    assert "block 200 \u00d7 100 \u00d7 10 mm" in setup
    assert "X0 Y0 at the front-left corner of the stock; Z0 on the stock top" in setup
    assert page.rows("programs") == [{"File": "plate.nc", "Size (bytes)": "12", "Lines": "3"}]
    assert page.attrs["gate"]["data-status"] == "passed"
    assert "Setup sheet: PLATE-01" in page.title


def test_times_print_as_hours_minutes_seconds():
    assert [setupsheet.hms(s) for s in (0, 59.4, 59.5, 3725.4, 36000)] == ["0:00:00", "0:00:59", "0:01:00", "1:02:05",
                                                                         "10:00:00"]
    assert setupsheet.hms(None) == "\u2014"


def test_pictures_are_inline_pngs_and_nothing_is_loaded_from_outside():
    picture = png(3, 2)
    sheet = setupsheet.sheet_from(two_tool_program(), {"gate": PASSED}, pictures=[("a", picture), ("b", png(1, 1))])
    text = setupsheet.setup_sheet(sheet)
    page = read_sheet(text)
    decoded = page.picture_bytes()
    assert decoded == [picture, png(1, 1)] and all(d[:8] == b"\x89PNG\r\n\x1a\n" for d in decoded)
    assert all(value.startswith("data:image/png;base64,") for _, _, value in page.references())
    tags = {tag for tag, _ in page.tags}
    assert not tags & {"script", "link", "iframe", "object", "embed", "base"}
    assert not re.search(r"https?:|file:|url\(|@import", page.style)
    # A4 and print rules: a row and a picture are never split, pictures fit the page's width
    assert re.search(r"@page\s*\{[^}]*size:\s*A4", page.style)
    assert re.search(r"tr[^{]*\{[^}]*break-inside:\s*avoid", page.style)
    assert re.search(r"img\s*\{[^}]*max-width:\s*100%", page.style)
    assert ("meta", {"charset": "utf-8"}) in page.tags


def test_a_picture_that_is_not_a_png_is_refused():
    with pytest.raises(setupsheet.SetupSheetError, match="'plan': not a PNG"):
        setupsheet.sheet_from(None, {}, pictures=[("plan", b"GIF89a....")])


def test_hostile_and_japanese_text_comes_out_as_written():
    hostile = '<script>alert("x")</script> & <img src=http://example.com/x.png> \u540d\u672d'
    program = two_tool_program(hostile)
    program.operations[0].name = "</td><td>fake"
    report = {"gate": {"findings": [{"message": "gouge <b>2 mm</b> & more"}], "overridden": True},
              "warnings": ["\u30c6\u30b9\u30c8 <i>"]}
    text = setupsheet.setup_sheet(setupsheet.sheet_from(program, report, post="A&B"))
    page = read_sheet(text)
    assert not {tag for tag, _ in page.tags} & {"script", "b", "i"}
    assert [attrs for attrs in page.images()] == []                      # the name's <img> stayed text
    assert page.texts["job"] == "Setup sheet: " + hostile
    assert page.rows("operations")[0]["Operation"] == "</td><td>fake"
    assert len(page.tables["operations"][1]) == 8                        # no cell was added by the name
    assert page.attrs["gate"]["data-status"] == "written despite findings"
    assert "gouge <b>2 mm</b> & more" in page.texts["gate"]
    assert "\u30c6\u30b9\u30c8 <i>" in page.texts["notes"] and "A&B" in page.texts["setup"]
    assert "&lt;script&gt;" in text and "&amp;" in text
    text.encode("utf-8")                                                 # Japanese kept, in UTF-8
    assert "\u540d\u672d" in text


@pytest.mark.parametrize("gate, status", [(None, "not run"), (PASSED, "passed"),
                                          ({"findings": [{"message": "m"}], "overridden": True},
                                           "written despite findings"),
                                          ({"findings": [{"message": "m"}], "overridden": False}, "refused")])
def test_the_gate_status_follows_the_report(gate, status):
    report = {} if gate is None else {"gate": gate}
    page = read_sheet(setupsheet.setup_sheet(setupsheet.sheet_from(None, report)))
    assert page.attrs["gate"]["data-status"] == status


def test_work_zero_in_words():
    centre = setupsheet.stock_entry(BoxStock(-100, -50, -20, 100, 50, 0))
    assert setupsheet.work_zero_text(centre, "G54") == "G54: X0 Y0 at the centre of the stock; Z0 on the stock top"
    raised = setupsheet.stock_entry(BoxStock(-60, -40, -15, 60, 40, -1))
    assert setupsheet.work_zero_text(raised).endswith("Z0 1 mm above the top")
    bar = setupsheet.stock_entry(CylinderStock(42.5, 60.0, 0.0))
    assert setupsheet.describe_stock(bar) == "round \u00d885 \u00d7 60 mm, axis along Z (Z -60 \u2026 0)"
    assert setupsheet.work_zero_text(bar) == "X0 Y0 on the axis of rotation; Z0 on the top end face"
    with pytest.raises(setupsheet.SetupSheetError, match="neither a box nor a cylinder"):
        setupsheet.stock_entry(object())


def test_a_job_without_a_program_shows_what_the_report_has():
    report = {"workflow": "unfold", "gate": PASSED, "sheet": {"sheet_mm": [1270.0, 1270.0]}}
    sheet = setupsheet.sheet_from(None, report, programs=[setupsheet.program_file("unfold.nc", b"%\nG92\n%")])
    page = read_sheet(setupsheet.setup_sheet(sheet))
    assert "sheet 1270 \u00d7 1270 mm" in page.texts["setup"]
    assert page.rows("programs") == [{"File": "unfold.nc", "Size (bytes)": "7", "Lines": "3"}]
    assert "tools" not in page.tables and "Setup sheet: unfold" in page.title


def test_operation_summaries_carry_the_tool_and_feeds():
    """report.json's operations (read by the batch sheet) hold what the sheet prints."""
    summary = two_tool_program().summary()
    assert [(s["tool_number"], s["tool_kind"], s["tool_diameter_mm"], s["tool_flute_length_mm"], s["spindle_rpm"],
             s["feed_mm_min"], s["plunge_feed_mm_min"]) for s in summary] == \
        [(5, "flat", 6.0, 22.0, 10000.0, 500.0, 200.0), (12, "ball", 3.0, 20.0, 18000.0, 1000.0, 100.0)]
    from_report = setupsheet.sheet_from(None, {"operations": summary, "cycle_time_s": 305.6})
    from_program = setupsheet.sheet_from(two_tool_program(), {})
    assert [(t.number, t.kind, t.diameter) for t in from_report.tools] == \
        [(t.number, t.kind, t.diameter) for t in from_program.tools]
    assert [(o.name, o.feed, o.plunge_feed) for o in from_report.operations] == \
        [(o.name, o.feed, o.plunge_feed) for o in from_program.operations]


def test_the_chip_load_column_says_per_what_in_every_cell():
    """The header gives the unit (mm) and each cell says per what: a router bit's chip load per
    tooth, a drill's feed per revolution (report.json's ``chip_load_per``), so a drill's "/rev"
    does not stand under a header that says per tooth.  A tool not checked shows a dash."""
    report = {"feeds": [{"checked": True, "tool_number": 5, "chip_load_mm": 0.05, "chip_load_per": "tooth"},
                        {"checked": True, "tool_number": 5, "chip_load_mm": 0.0833, "chip_load_per": "tooth"},
                        {"checked": True, "tool_number": 12, "chip_load_mm": 0.0762,
                         "chip_load_per": "revolution"}]}
    page = read_sheet(setupsheet.setup_sheet(setupsheet.sheet_from(two_tool_program(), report)))
    tools = page.rows("tools")
    assert [(t["Tool"], t["Chip load (mm)"]) for t in tools] == \
        [("T5", "0.0500/tooth, 0.0833/tooth"), ("T12", "0.0762/rev")]
    assert not any("tooth" in name for name in tools[0])            # the header names the unit only
    unchecked = read_sheet(setupsheet.setup_sheet(setupsheet.sheet_from(two_tool_program(), {})))
    assert [t["Chip load (mm)"] for t in unchecked.rows("tools")] == ["\u2014", "\u2014"]
