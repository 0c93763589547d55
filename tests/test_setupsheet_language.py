"""The setup sheet in Japanese: batch ``--language ja`` and a job file's ``[setup] language``.

A real batch run (in-process, as tests/test_hostile_batch.py runs it) of a drilling job writes the
sheet; its text is read back with html.parser and every text node must be Japanese, or a number or
code, or a name the job itself gives (its file, machine, post, tools).  The English sheet of the
same job stays what it was before the sheet could be translated (the page as main wrote it, kept in
tests/fixtures/setupsheet/ with the pictures' base64 left out).
"""
import contextlib
import io
import json
import os
import re
import shutil
import tempfile
from html.parser import HTMLParser

import pytest

bpy = pytest.importorskip("bpy")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIXTURES = os.path.join(ROOT, "tests", "fixtures", "setupsheet")
JOB = os.path.join(FIXTURES, "shelf-holes.toml")
JAPANESE = re.compile(r"[\u3000-\u303f\u3040-\u30ff\u3400-\u4dbf\u4e00-\u9fff\uff01-\uff9f]")     # CJK punctuation, kana, kanji, full-width
# a number as the sheet writes it (1,234 / -18 / 0.0500 / 0:00:34), a T word, a work offset, a dash, "#"
NUMBER_OR_CODE = re.compile(r"^(?:[-+]?[\d,]+(?:\.\d+)?|\d+:\d\d:\d\d|T\d+|G5[4-9](?:\.\d)?|\u2014|#)$")
# the English words the sheet had: none of them may be left as a text node of the Japanese sheet
ENGLISH_WORDS = {"Setup", "Tools", "Operations", "Export gate", "Program", "Notes", "Pictures", "Machine", "Post",
                 "Work offset", "Stock", "Work zero", "Total time", "Tool", "Kind", "Diameter (mm)", "Corner R (mm)",
                 "Flute length (mm)", "Stick-out (mm)", "Chip load (mm)", "Description", "Operation",
                 "Spindle (rpm)", "Feed (mm/min)", "Plunge (mm/min)", "Moves", "Time (h:mm:ss)", "Total", "File",
                 "Size (bytes)", "Lines", "Toolpaths", "Result", "drill", "ball", "flat"}


from blender_language import japanese_interface  # noqa: E402
from test_hostile_batch import BATCH  # noqa: E402  (batch.py loaded once for the in-process suites)


@pytest.fixture()
def folder():
    path = tempfile.mkdtemp(prefix="kezuri-sheetlang-")
    yield path
    shutil.rmtree(path, ignore_errors=True)


def run(out: str, *argv) -> tuple:
    """(exit status, stderr) of ``batch.py <argv> --out <out>``."""
    stderr = io.StringIO()
    with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(["batch.py", *argv, "--out", out])
        except SystemExit as exit_:
            status = exit_.code
    return status, stderr.getvalue()


class TextNodes(HTMLParser):
    """Every text node of the page outside <style>, with the tag it is in; the <html lang>."""

    def __init__(self, text: str):
        super().__init__()
        self.nodes, self.open, self.lang, self.alts = [], [], None, []
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "html":
            self.lang = attrs.get("lang")
        if tag == "img":
            self.alts.append(attrs.get("alt"))
            return                      # a void element: no end tag
        if tag not in ("meta", "br"):
            self.open.append(tag)

    def handle_endtag(self, tag):
        if self.open and self.open[-1] == tag:
            self.open.pop()

    def handle_data(self, data):
        if data.strip() and "style" not in self.open:
            self.nodes.append((self.open[-1] if self.open else "", data.strip()))


def sheet(out: str) -> str:
    with open(os.path.join(out, "setup-sheet.html"), encoding="utf-8") as stream:
        return stream.read()


def report(out: str) -> dict:
    with open(os.path.join(out, "report.json"), encoding="utf-8") as stream:
        return json.load(stream)


def test_a_japanese_sheet_from_a_batch_run_has_no_english_word_left(folder):
    out = os.path.join(folder, "ja")
    status, message = run(out, "job", JOB, "--language", "ja")
    assert status == 0, message[-2000:]
    text = sheet(out)
    page = TextNodes(text)
    assert page.lang == "ja"
    assert '<meta charset="utf-8">' in text and "<script" not in text and "http" not in text.replace(
        "http-equiv", "")
    from kezuri.operators.batchio import post_label
    data = report(out)
    names = {data["machine"]["label"], post_label(data), *data["tools"], os.path.basename(data["files"][0])}
    assert names == {"LinuxCNC mill, manual tool change", "LinuxCNC", "T4 5 mm drill (5 mm drill)", "棚板-holes.ngc"}
    for tag, node in page.nodes:
        assert JAPANESE.search(node) or NUMBER_OR_CODE.match(node) or node in names, (tag, node)
    shown = {node for _, node in page.nodes}
    assert not shown & ENGLISH_WORDS
    headings = [node for tag, node in page.nodes if tag == "h2"]
    assert headings == ["段取り", "工具", "加工工程", "書き出しゲート", "プログラム", "注記", "図"]
    facts = dict(zip((n for t, n in page.nodes if t == "dt"), (n for t, n in page.nodes if t == "dd")))
    assert facts["ワーク原点"] == "G54: X0 Y0 は素材の左手前の角、Z0 は素材の上面"
    assert facts["素材"] == "直方体 300 × 120 × 18 mm（X 0 … 300、Y 0 … 120、Z -18 … 0）"
    assert facts["合計時間"] == "0:00:34"                         # times stay h:mm:ss
    cells = [node for tag, node in page.nodes if tag == "td"]
    assert cells[:8] == ["T4", "ドリル", "5", "0", "40", "\u2014", "0.0500/回転", "T4 5 mm drill (5 mm drill)"]
    assert "穴あけ" in cells                                     # the operation "drill" (not the tool kind)
    assert [node for tag, node in page.nodes if tag == "strong"] == [
        "合格：シミュレーションでプログラムを止める問題は見つかりませんでした。"]
    notes = [node for tag, node in page.nodes if tag == "li"]
    assert len(notes) == 1 and notes[0].startswith("送り：工程 'drill'") and "0.0508〜0.1016 mm" in notes[0]
    assert page.alts == ["工具経路", "加工結果"]
    assert data.get("setup_sheet_language") is None             # given on the command line, not by the job file


def test_the_english_sheet_is_the_one_main_wrote(folder):
    out = os.path.join(folder, "en")
    status, message = run(out, "job", JOB)
    assert status == 0, message[-2000:]
    text = sheet(out)
    pictures = re.findall(r"data:image/png;base64,([A-Za-z0-9+/=]+)", text)
    assert len(pictures) == 2 and all(len(p) > 1000 for p in pictures)
    with open(os.path.join(FIXTURES, "shelf-holes-en.html"), encoding="utf-8", newline="") as stream:
        before = stream.read()
    assert re.sub(r"data:image/png;base64,[A-Za-z0-9+/=]+", "data:image/png;base64,", text) == before
    assert TextNodes(text).lang == "en"
    # --language en is the same page
    status, message = run(os.path.join(folder, "en2"), "job", JOB, "--language", "en")
    assert status == 0, message[-2000:]
    assert sheet(os.path.join(folder, "en2")) == text


def test_a_language_not_known_is_refused_by_name(folder):
    out = os.path.join(folder, "bad")
    status, message = run(out, "job", JOB, "--language", "fr")
    assert status == 2
    assert "--language" in message and "'fr'" in message and "Traceback" not in message
    assert not os.path.exists(out)
    status, message = run(out, "drill", "--language", "")
    assert status == 2 and "--language" in message and "''" in message


def job_with(folder: str, line: str) -> str:
    with open(JOB, encoding="utf-8") as stream:
        text = stream.read().replace('material = "hardwood"\n', f'material = "hardwood"\n{line}\n')
    assert line in text
    path = os.path.join(folder, "job.toml")
    with open(path, "w", encoding="utf-8") as stream:
        stream.write(text)
    return path


def test_a_job_file_gives_the_language_and_the_command_line_wins(folder):
    path = job_with(folder, 'language = "ja"')
    status, message = run(os.path.join(folder, "ja"), "job", path)
    assert status == 0, message[-2000:]
    assert TextNodes(sheet(os.path.join(folder, "ja"))).lang == "ja"
    assert report(os.path.join(folder, "ja"))["setup_sheet_language"] == "ja"
    status, message = run(os.path.join(folder, "en"), "job", path, "--language", "en")
    assert status == 0, message[-2000:]
    page = TextNodes(sheet(os.path.join(folder, "en")))
    assert page.lang == "en" and [n for t, n in page.nodes if t == "h2"][0] == "Setup"


@pytest.mark.parametrize("value", ['"jp"', '"JA"', "1", '["ja"]'])
def test_a_job_files_language_not_known_is_refused_by_name(folder, value):
    path = job_with(folder, f"language = {value}")
    out = os.path.join(folder, "out")
    status, message = run(out, "job", path)
    assert status == 2, message[-2000:]
    assert f"job file {path}: [setup] language = " in message and "is not one of en, ja" in message
    assert "Traceback" not in message and not os.path.exists(out)


def test_the_job_files_language_error_is_in_japanese_too():
    from kezuri.operators import translations
    english = "job file a.toml: [setup] language = 'jp' is not one of en, ja"
    assert translations.japanese_message(english) == "ジョブファイル a.toml：[setup] の language = 'jp' は en, ja のいずれでもありません"


# ----- the sheet's words: each has its Japanese, listed once -----------------------------------------

def asked_texts() -> set:
    """(text, number of values, context) of every sheet text the core asks ``translate`` for, over
    sheets of every gate status, stock kind and work-zero place (box: each axis low, middle, high,
    inside, below and above; cylinder likewise), empty and full tables."""
    from kezuri.toolpath.pictures import setupsheet as ss
    asked = set()

    def record(text, *values, context=""):
        asked.add((text, len(values), context))
        return ss.english(text, *values)

    png = ss.PNG_SIGNATURE + b"rest"
    places = ((0.0, 10.0), (-10.0, 0.0), (-5.0, 5.0), (-3.0, 7.0), (2.0, 12.0), (-12.0, -2.0))
    stocks = [{"kind": "box", "x0": x0, "x1": x1, "y0": y0, "y1": y1, "z0": z0, "z1": z1}
              for x0, x1 in places for y0, y1 in places for z0, z1 in places]
    stocks[0]["surface"] = True
    stocks += [{"kind": "cylinder", "radius": 10.0, "height": h, "z_top": top}
               for h, top in ((20.0, 0.0), (20.0, 20.0), (20.0, 10.0), (20.0, 15.0), (20.0, 25.0), (20.0, -3.0))]
    stocks += [{"kind": "sheet", "size": [1000.0, 500.0]}, {"kind": "sheet", "size": [1000.0, 500.0], "thickness": 1.6}]
    tools = [ss.SheetTool(n, kind, 6.0, 0.0, 20.0, None, "", ((0.05, "revolution"),) if kind == "drill" else (0.1,))
             for n, kind in enumerate(("ball", "flat", "bull", "drill", "vbit"), 1)]
    operation = ss.SheetOperation("cut out", 1, 12000, 1000, 300, 60.0, 12)
    for status in ss.GATE_STATUSES:
        for stock in stocks:
            sheet = ss.SetupSheet("job", stock=stock, work_offset="G54",
                                  work_zero=ss.work_zero_text(stock, "G54"), gate_status=status)
            ss.setup_sheet(sheet, "ja", record)
        full = ss.SetupSheet("job", tools=tools, operations=[operation], gate_status=status,
                             programs=[ss.SheetProgram("a.ngc", 10, 1)], pictures=[("Toolpaths", png), ("Result", png)],
                             notes=["a note"])
        ss.setup_sheet(full, "ja", record)
    return asked - {("job", 0, ""), ("cut out", 0, ""), ("a note", 0, ""), ("#", 0, "")}   # names and codes


def test_every_word_of_the_sheet_has_its_japanese():
    from kezuri.operators import translations
    asked = asked_texts()
    assert ("X0 at the stock's {}, Y0 at its {}", 2, "") in asked and ("{} mm behind the back", 1, "") in asked
    assert ("drill", 0, "tool kind") in asked and len(asked) > 80
    missing = []
    for text, count, context in sorted(asked):
        values = [str(7 + i) for i in range(count)]
        japanese = translations.sheet_text(text, *values, context=context)
        if not JAPANESE.search(japanese) or any(v not in japanese for v in values):
            missing.append((text, context, japanese))
    assert not missing, missing


def test_the_sheet_lists_only_what_the_interface_does_not_have():
    from kezuri.operators import translations
    ja = translations.TRANSLATIONS["ja_JP"]
    assert not [text for text in translations.SHEET_TEXTS if ("*", text) in ja]
    assert not set(translations.SHEET_TEMPLATES) & set(translations.MESSAGE_TEMPLATES)
    for table in (translations.SHEET_TEXTS, translations.SHEET_TEMPLATES):   # the sheet's words are not Blender's
        assert not [text for text in table if ("*", text) in ja or ("Operator", text) in ja]
    for english, japanese in translations.SHEET_TEMPLATES.items():
        assert sorted(int(i) for i in re.findall(r"\{(\d+)\}", japanese)) == list(range(english.count("{}"))), english


@pytest.mark.parametrize("box, words", [
    ((0, 300, 0, 120, -18, 0), "X0 Y0 は素材の左手前の角、Z0 は素材の上面"),
    ((-300, 0, -120, 0, 0, 18), "X0 Y0 は素材の右奥の角、Z0 は素材の下面"),
    ((-150, 150, -60, 60, -18, 0), "X0 Y0 は素材の中心、Z0 は素材の上面"),
    ((-10, 290, -60, 60, -19, -1), "X0 は素材の左端から 10 mm、Y0 は中央、Z0 は上面の 1 mm 上"),
    ((5, 305, -125, -5, -20, 2), "X0 は素材の左端の 5 mm 左、Y0 は奥の端の 5 mm 奥、Z0 は下面から 20 mm"),
    ((-310, -10, 2.5, 122.5, -9, 9), "X0 は素材の右端の 10 mm 右、Y0 は手前の端の 2.5 mm 手前、Z0 は中央"),
])
def test_the_work_zero_in_japanese(box, words):
    from kezuri.operators.translations import sheet_text
    from kezuri.toolpath.pictures import setupsheet as ss
    x0, x1, y0, y1, z0, z1 = box
    stock = {"kind": "box", "x0": x0, "x1": x1, "y0": y0, "y1": y1, "z0": z0, "z1": z1}
    assert ss.work_zero_text(stock, "", sheet_text) == words
    assert ss.work_zero_text(stock, "G55", sheet_text) == "G55: " + words
    bar = {"kind": "cylinder", "radius": 20.0, "height": 60.0, "z_top": 0.0}
    assert ss.work_zero_text(bar, "", sheet_text) == "X0 Y0 は回転軸上、Z0 は上端面"


def test_a_sheet_in_a_language_not_known_is_refused_by_name():
    from kezuri.operators.translations import japanese_message
    from kezuri.toolpath.pictures import setupsheet as ss
    with pytest.raises(ss.SetupSheetError, match=r"setup sheet language 'de': one of en, ja"):
        ss.setup_sheet(ss.SetupSheet("job"), "de")
    assert japanese_message("setup sheet language 'de': one of en, ja") == "段取りシートの言語 'de'：en, ja のいずれかです"


@pytest.mark.parametrize("jobs", [[], ["--jobs", "2"]])
def test_a_templates_rows_write_their_sheets_in_the_language_asked(folder, jobs):
    """``job --each``: each row's sheet in this process and in worker processes (--language passed on)."""
    with open(JOB, encoding="utf-8") as stream:
        template = stream.read().replace('name = "棚板-holes"', 'name = "{{name}}"')
    path = os.path.join(folder, "shelves.toml")
    with open(path, "w", encoding="utf-8") as stream:
        stream.write(template)
    rows = os.path.join(folder, "rows.csv")
    with open(rows, "w", encoding="utf-8") as stream:
        stream.write("name\n棚板-1\nshelf-2\n")
    out = os.path.join(folder, "rows")
    status, message = run(out, "job", path, "--each", rows, "--language", "ja", *jobs)
    assert status == 0, message[-2000:]
    sheets = sorted(os.path.join(base, "setup-sheet.html") for base, _, files in os.walk(out)
                    if "setup-sheet.html" in files)
    assert len(sheets) == 2
    for name in sheets:
        with open(name, encoding="utf-8") as stream:
            page = TextNodes(stream.read())
        assert page.lang == "ja" and [n for t, n in page.nodes if t == "h2"][0] == "段取り"



def export_sheet(scene, folder) -> TextNodes:
    """The job list's Export of ``scene`` into ``folder``: the sheet written beside the program."""
    from kezuri.operators import joblist
    path = folder / "plate.ngc"
    folder.mkdir()
    joblist.export_job(scene, str(path), "linuxcnc")
    assert sorted(os.listdir(folder)) == ["plate-setup-sheet.html", "plate.ngc"]
    page = TextNodes((folder / "plate-setup-sheet.html").read_text(encoding="utf-8"))
    assert f"{os.path.getsize(path):,}" in [n for t, n in page.nodes if t == "td"]     # the program beside it
    return page


@pytest.fixture()
def plate_job(empty_scene):
    from kezuri.operators import samples
    samples.name_plate(empty_scene)
    empty_scene.kezuri.machine.post = "linuxcnc"
    assert bpy.ops.kezuri.job_add(kind="engrave") == {"FINISHED"}
    return empty_scene


def test_the_job_lists_export_writes_the_sheet_beside_the_program(plate_job, tmp_path):
    from kezuri.operators import translations
    assert translations.interface_language() == "en"
    page = export_sheet(plate_job, tmp_path / "en")
    assert page.lang == "en"
    # the pictures batch job draws: the toolpaths and the simulated result
    assert [n for t, n in page.nodes if t == "h2"] == ["Setup", "Tools", "Operations", "Export gate", "Program",
                                                       "Pictures"]


@pytest.mark.xfail(not bpy.app.build_options.international, strict=True,
                   reason="the bpy wheel is built without translations: its interface cannot be Japanese")
def test_the_job_lists_export_writes_the_sheet_in_the_interface_language(plate_job, tmp_path):
    from kezuri.operators import translations
    with japanese_interface():
        assert translations.interface_language() == "ja"
        page = export_sheet(plate_job, tmp_path / "ja")
    assert page.lang == "ja"
    assert [n for t, n in page.nodes if t == "h2"] == ["段取り", "工具", "加工工程", "書き出しゲート", "プログラム", "図"]
    assert not {n for _, n in page.nodes} & ENGLISH_WORDS
