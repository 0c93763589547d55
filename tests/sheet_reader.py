"""An independent reader of a setup sheet (HTML), with the standard library's html.parser only: the
tables by id (rows of cell texts), the text of elements with an id, every tag's attributes, the
document's title.  It knows nothing of toolpath/pictures/setupsheet.py."""
from __future__ import annotations

import base64
from html.parser import HTMLParser

VOID = {"meta", "img", "br", "hr", "link", "input", "source", "area", "base", "col", "embed", "wbr"}


class SheetReader(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tags = []             # (tag, attrs dict) of every start tag
        self.texts = {}            # id -> text inside the element
        self.attrs = {}            # id -> its attributes
        self.tables = {}           # table id -> [[cell text, ...], ...] (head, body and foot rows)
        self.title = ""
        self.style = ""
        self._open = []            # stack of (tag, id or None)
        self._table = None
        self._row = None
        self._cell = None
        self._in = None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        self.tags.append((tag, attrs))
        ident = attrs.get("id")
        if ident:
            self.texts.setdefault(ident, "")
            self.attrs[ident] = attrs
        if tag == "table":
            self._table = ident
            self.tables[ident] = []
        elif tag == "tr" and self._table is not None:
            self._row = []
        elif tag in ("td", "th") and self._row is not None:
            self._cell = ""
        if tag not in VOID:
            self._open.append((tag, ident))
        self._in = tag

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self._cell is not None:
            self._row.append(self._cell.strip())
            self._cell = None
        elif tag == "tr" and self._row is not None:
            self.tables[self._table].append(self._row)
            self._row = None
        elif tag == "table":
            self._table = None
        while self._open:
            top, _ = self._open.pop()
            if top == tag:
                break

    def handle_data(self, data):
        for _, ident in self._open:
            if ident:
                self.texts[ident] += data
        if self._cell is not None:
            self._cell += data
        if self._open and self._open[-1][0] == "title":
            self.title += data
        if self._open and self._open[-1][0] == "style":
            self.style += data

    # ----- questions -----
    def rows(self, table: str) -> list:
        """The table's body rows (the header row left out) as dicts by header text."""
        head, *body = self.tables[table]
        return [dict(zip(head, row)) for row in body if len(row) == len(head)]

    def images(self) -> list:
        return [attrs for tag, attrs in self.tags if tag == "img"]

    def picture_bytes(self) -> list:
        prefix = "data:image/png;base64,"
        found = []
        for attrs in self.images():
            source = attrs.get("src", "")
            assert source.startswith(prefix), source[:60]
            found.append(base64.b64decode(source[len(prefix):], validate=True))
        return found

    def references(self) -> list:
        """Every attribute value that could load or link something (src, href, srcset, action, ...)."""
        keys = {"src", "href", "srcset", "action", "data", "poster", "background", "formaction", "xlink:href"}
        return [(tag, key, value) for tag, attrs in self.tags for key, value in attrs.items() if key in keys]


def read_sheet(text: str) -> SheetReader:
    reader = SheetReader()
    reader.feed(text)
    reader.close()
    return reader


def seconds(hms: str) -> int:
    """h:mm:ss as seconds."""
    h, m, s = (int(part) for part in hms.split(":"))
    assert 0 <= m < 60 and 0 <= s < 60, hms
    return h * 3600 + m * 60 + s
