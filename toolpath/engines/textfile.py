"""Reading the text files users bring (NC programs, Part 21, CADKEY CDL): one rule for all."""
from __future__ import annotations


def read_text(path) -> str:
    """The file's text: UTF-8 (a byte-order mark dropped: it hid a CDL's first LINE word), or,
    when that fails, ISO 8859-1 (old 8-bit files; Shift-JIS comments keep at least their line
    breaks, which is all the readers need of a comment)."""
    with open(path, "rb") as handle:
        data = handle.read()
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return data.decode("latin-1")
