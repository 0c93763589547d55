"""``batch.py tools list / import / export`` on a library file of the test's own
(KEZURI_TOOL_LIBRARY): JSON out, duplicates refused naming both unless --replace, exit 2 on bad
input with nothing changed."""
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIXTURES = os.path.join(ROOT, "tests", "fixtures", "tools")


def tools(library, *args):
    done = subprocess.run([sys.executable, os.path.join(ROOT, "batch.py"), "tools", *args], capture_output=True,
                          text=True, timeout=300, env=dict(os.environ, KEZURI_TOOL_LIBRARY=str(library)))
    return done.returncode, done.stdout, done.stderr


def test_list_import_export(tmp_path):
    library = tmp_path / "config" / "tools.toml"
    status, out, _ = tools(library, "list")
    listed = json.loads(out)
    assert status == 0 and listed["library"] == str(library) and len(listed["tools"]) == 11
    assert listed["tools"][1] == {"number": 2, "kind": "ball", "diameter": 6.0, "corner_radius": 3.0, "angle": None,
                                  "flutes": 2, "flute_length": 20.0, "stick_out": 30.0, "holder_diameter": None,
                                  "material": "carbide", "vendor": "", "product_id": "", "name": "6 mm ball end mill"}
    before = library.read_text()

    # T1, T4, T8, T9 of the Fusion file clash with the presets: refused, naming both, nothing imported
    status, out, err = tools(library, "import", os.path.join(FIXTURES, "fusion-library.json"))
    assert status == 2 and out == ""
    assert "T8: " in err and "has T8 6.35 mm 60° V-bit (60 degree V groove), the library has T8 6 mm 60° V-bit" in err
    assert library.read_text() == before

    status, out, err = tools(library, "import", os.path.join(FIXTURES, "fusion-library.json"), "--replace")
    report = json.loads(out)
    assert status == 0, err
    assert (report["added"], report["replaced"], report["tools"]) == ([14, 21], [1, 4, 8, 9], 13)
    assert len(report["notes"]) == 2 and "'probe'" in report["notes"][0]
    assert library.with_suffix(".toml.bak1").read_text() == before          # the file before, kept

    exported = tmp_path / "shop.tbl"
    status, out, err = tools(library, "export", str(exported))
    assert status == 0 and json.loads(out)["format"] == "tbl", err
    lines = exported.read_text().splitlines()
    assert len(lines) == 14 and lines[8].startswith("T8 P8 D6.35 ;60 degree V groove kezuri{")

    again = tmp_path / "again.toml"
    tools(tmp_path / "other.toml", "list")
    status, out, err = tools(tmp_path / "other.toml", "import", str(exported), "--replace")
    assert status == 0, err
    tools(tmp_path / "other.toml", "export", str(again))
    tools(library, "export", str(tmp_path / "library.toml"))
    assert again.read_text() == (tmp_path / "library.toml").read_text()      # through the table and back


def test_bad_input_exits_2_with_the_reason(tmp_path):
    library = tmp_path / "tools.toml"
    bad = tmp_path / "bad.tbl"
    bad.write_text("T1 P1 D6\nT2 P2 D0\n")
    status, out, err = tools(library, "import", str(bad))
    assert status == 2 and f"{bad}: line 2 (T2): refused: diameter 0.0 must be positive" in err
    status, _, err = tools(library, "export", str(tmp_path / "x.csv"))
    assert status == 2 and "which tool library format is .csv" in err
    status, _, err = tools(library, "export", str(tmp_path / "x.txt"), "--format", "csv")
    assert status == 2 and "invalid choice: 'csv'" in err
    status, _, err = tools(library, "export", str(library))
    assert status == 2 and "is the tool library itself" in err
    library.write_text(library.read_text()[:-30])
    status, _, err = tools(library, "list")
    assert status == 2 and "cannot be read, and is left as it is" in err


def test_a_freecad_library_out_and_back(tmp_path):
    library = tmp_path / "tools.toml"
    target = tmp_path / "Tools" / "Library" / "shop.fctl"
    status, out, err = tools(library, "export", str(target))
    report = json.loads(out)
    assert status == 0 and report["format"] == "freecad", err
    assert len(report["files"]) == 12 and report["files"][-1] == str(target)
    assert os.path.isfile(tmp_path / "Tools" / "Bit" / "shop-T8.fctb")
    other = tmp_path / "other.toml"
    tools(other, "list")
    status, out, err = tools(other, "import", str(target), "--replace")
    assert status == 0 and json.loads(out)["unchanged"] == list(range(1, 12)), err   # the same tools came back


def test_the_tools_command_is_listed_in_batch_help():
    """``batch.py --help`` names every command the README gives, ``tools`` too (main() runs it
    before the parser, so it was missing from the list), and ``tools --help`` is its own."""
    done = subprocess.run([sys.executable, os.path.join(ROOT, "batch.py"), "--help"], capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0
    listed = done.stdout.split("{", 1)[1].split("}", 1)[0].split(",")
    for command in ("engrave", "rotary", "stepnc", "turnmill", "unfold", "elbow", "carve", "simulate", "job",
                    "profile", "pocket", "drill", "chamfer", "vcarve", "demo", "feeds", "tools"):
        assert command in listed
    assert "the tool library: list, import FILE, export FILE" in " ".join(done.stdout.split())
    done = subprocess.run([sys.executable, os.path.join(ROOT, "batch.py"), "tools", "--help"], capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0 and "{list,import,export}" in done.stdout
