"""The tool library's file: presets on a first run, a backup before every write (the last five),
atomic writes, and a file that cannot be read left exactly as it is."""
import os

import pytest

from kezuri.toolpath.tooling import store
from kezuri.toolpath.tooling.library import LibraryTool, ToolLibraryError


def test_a_first_run_writes_the_presets(tmp_path):
    path = str(tmp_path / "config" / "kezuri" / "tools.toml")
    library = store.load(path)
    assert os.path.isfile(path)
    assert library.numbers() == tuple(range(1, 12))
    assert (library.get(2).kind, library.get(2).diameter) == ("ball", 6.0)          # the engraving's roughing ball
    assert (library.get(3).kind, library.get(3).diameter) == ("flat", 1.0)          # its band finishing end mill
    assert sorted(t.angle for t in library if t.kind == "vbit") == [60.0, 90.0]
    assert [t.diameter for t in library if t.kind == "drill"] == [5.0, 10.0, 3.0, 8.0]
    assert store.load(path) == library                                              # read back, not re-seeded


def test_every_write_keeps_the_file_before_it_and_five_at_most(tmp_path):
    path = str(tmp_path / "tools.toml")
    library = store.load(path)
    texts = [open(path, encoding="utf-8").read()]
    for size in range(1, 8):
        library = library.with_tool(LibraryTool(20, "flat", float(size)), replace=True)
        store.save(path, library)
        texts.append(open(path, encoding="utf-8").read())
    backups = [open(f"{path}.bak{i}", encoding="utf-8").read() for i in range(1, 6)]
    assert backups == texts[-2:-7:-1]                   # .bak1 the one just before, .bak5 five writes back
    assert not os.path.exists(f"{path}.bak6")
    assert store.load(path).get(20).diameter == 7.0
    assert [name for name in os.listdir(tmp_path) if name.endswith(".tmp")] == []


def test_a_file_that_cannot_be_read_is_left_as_it_is(tmp_path):
    path = str(tmp_path / "tools.toml")
    store.load(path)
    store.save(path, store.SEEDS.without(11))
    broken = open(path, encoding="utf-8").read()[:-40]           # truncated mid-table
    with open(path, "w", encoding="utf-8") as stream:
        stream.write(broken)
    with pytest.raises(ToolLibraryError) as error:
        store.load(path)
    assert "left as it is" in str(error.value) and f"{path}.bak1" in str(error.value)
    assert open(path, encoding="utf-8").read() == broken            # no preset written over it


def test_a_write_that_fails_leaves_the_file(tmp_path):
    path = str(tmp_path / "tools.toml")
    store.load(path)
    before = open(path, encoding="utf-8").read()
    os.chmod(tmp_path, 0o500)                                       # the folder refuses new files
    try:
        if os.access(tmp_path, os.W_OK):
            pytest.skip("running as a user every folder lets write")
        with pytest.raises(ToolLibraryError, match="cannot be written"):
            store.save(path, store.SEEDS.without(1))
    finally:
        os.chmod(tmp_path, 0o700)
    assert open(path, encoding="utf-8").read() == before
