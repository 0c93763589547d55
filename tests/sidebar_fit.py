"""Does every text of the CAM tab fit the sidebar? Widths measured with ``blf.dimensions``.

Blender cannot draw a panel without a window, so the panels' ``draw`` functions are run on
:class:`Layout`, a stand-in for ``UILayout`` that records what each call would put on screen
and how wide a button it gets; the property names, enum items and operator labels come from
the RNA (``bl_rna``), the Japanese from the extension's translation table.  The real-window
run (scripts/screenshot_driver.py) uses the same walk with the real region's width.

The geometry is Blender's (source/blender/editors/include/UI_interface_c.hh, screen/area.cc,
interface/interface_layout.cc, interface_widgets.cc), at the default resolution scale (one
widget unit = 20 px, text 11 pt):

- the 3D viewport's sidebar opens ``UI_SIDEBAR_PANEL_WIDTH`` wide: 280 px (Blender 4.2 and
  later; 220 px before).  The category tabs take ``UI_PANEL_CATEGORY_MARGIN_WIDTH`` (1 unit),
  the panel ``UI_PANEL_MARGIN_X`` (0.4 unit) each side, the layout ``style->panelspace``
  (8 px) each side: 280 - 20 - 16 - 16 = 228 px of layout.  (The 4.3 window measured 235 px:
  the model is a little stricter than the real thing.)
- ``use_property_split``: the decorator column (1 unit) at the right, then
  ``UI_ITEM_PROP_SEP_DIVIDE`` = 0.4 of the rest for the right-aligned name, 0.6 for the value.
- text inside a button keeps ``UI_TEXT_MARGIN_X`` = 0.4 unit (8 px) from the aligned edge;
  centred text (buttons, numbers) from both; an icon takes 1 unit, a menu's arrow 1 unit.
"""
from __future__ import annotations

from dataclasses import dataclass

import sys

import blf
import bpy

UNIT = 20                 # U.widget_unit at resolution scale 1
TEXT_POINTS = 11          # UI_DEFAULT_TEXT_POINTS
SIDEBAR = 280             # UI_SIDEBAR_PANEL_WIDTH
TABS = UNIT               # UI_PANEL_CATEGORY_MARGIN_WIDTH
PANEL_MARGIN = 0.4 * UNIT  # UI_PANEL_MARGIN_X, each side
PANELSPACE = 8            # uiStyle.panelspace, each side
SPLIT = 0.4               # UI_ITEM_PROP_SEP_DIVIDE
PAD = 0.4 * UNIT          # UI_TEXT_MARGIN_X
BOX = 2 * 5               # uiStyle.boxspace, each side


def layout_width(region_width: float = SIDEBAR) -> float:
    return region_width - TABS - 2 * PANEL_MARGIN - 2 * PANELSPACE


_FONT = {}


def font() -> int:
    """Blender's interface font (Inter with the CJK fallback) at 11 pt: font id 0 is the UI font."""
    if "id" not in _FONT:
        _FONT["id"] = 0
    blf.size(_FONT["id"], TEXT_POINTS)
    return _FONT["id"]


def text_width(text: str) -> float:
    return blf.dimensions(font(), text)[0]


@dataclass
class Text:
    text: str
    room: float        # pixels the text gets
    where: str

    @property
    def width(self) -> float:
        return text_width(self.text)

    @property
    def fits(self) -> bool:
        return self.width <= self.room


class Translator:
    """English as Blender shows it, or the Japanese Blender would look up for it."""

    def __init__(self, table: dict | None):
        self.table = table

    def __call__(self, text: str, context: str = "*") -> str:
        if self.table is None or not text:
            return text
        return self.table.get((context, text), self.table.get(("*", text), text))


class _Node:
    """A row, column, box or split: its items get their widths once the draw call is done."""

    def __init__(self, kind: str, factor: float = 0.5):
        self.kind, self.factor, self.items = kind, factor, []


class Layout:
    """The calls of ``UILayout`` the extension's panels make, recorded into a tree."""

    def __init__(self, node: _Node | None = None, split: bool = False):
        self._node = node or _Node("column")
        self.use_property_split = split
        self.use_property_decorate = True
        self.scale_y = 1.0
        self.enabled = True
        self.active = True
        self.alignment = "EXPAND"

    def _child(self, kind, factor=0.5):
        node = _Node(kind, factor)
        self._node.items.append(node)
        return Layout(node, self.use_property_split)

    def row(self, align=False, heading=""):
        return self._child("row")

    def column(self, align=False, heading=""):
        return self._child("column")

    def box(self):
        return self._child("box")

    def split(self, factor=0.5, align=False):
        return self._child("split", factor)

    def _add(self, item):
        self._node.items.append(item)
        return _Properties()

    def separator(self, factor=1.0, type="AUTO"):
        pass

    def label(self, text="", icon="NONE", translate=True, text_ctxt=""):
        return self._add(("label", text, icon != "NONE", translate))

    def operator(self, idname, text=None, icon="NONE", translate=True, **_):
        if text is None:
            module, name = idname.split(".")
            text = getattr(getattr(bpy.ops, module), name).get_rna_type().name
        return self._add(("operator", text, icon != "NONE", translate))

    def menu(self, menu, text=None, icon="NONE"):
        label = getattr(bpy.types, menu).bl_label if text is None else text
        return self._add(("menu", label, icon != "NONE", True))

    def prop(self, data, name, text=None, index=-1, icon="NONE", expand=False, toggle=-1, slider=False,
             icon_only=False, translate=True, emboss=True):
        return self._add(("prop", (data, name, text, index, expand), icon != "NONE", self.use_property_split,
                          self.use_property_decorate))

    def template_list(self, listtype, list_id, data, propname, active_data, active_propname, rows=5, **_):
        return self._add(("list", (getattr(bpy.types, listtype), data, propname), False, True))


class _Properties:
    """What ``layout.operator`` returns: operator properties are set on it and ignored."""

    def __setattr__(self, name, value):
        object.__setattr__(self, name, value)


def _enum_names(data, name: str, context) -> list:
    prop = data.bl_rna.properties[name]
    names = [item.name for item in prop.enum_items]
    if not names:                              # a dynamic enum: ask its items callback
        deferred = type(data).__annotations__.get(name)
        if isinstance(deferred, str):          # ``from __future__ import annotations``: the source text
            deferred = eval(deferred, vars(sys.modules[type(data).__module__]))   # noqa: S307
        items = deferred.keywords["items"] if deferred is not None else []
        if callable(items):
            items = items(data, context)
        names = [item[1] for item in items]
    return names


def _value_text(data, name: str, index: int) -> str:
    prop = data.bl_rna.properties[name]
    value = getattr(data, name)
    if index >= 0:
        value = value[index]
    if prop.type == "FLOAT":
        return f"{value:.{prop.precision}f}"
    return str(value)


class Walk:
    """Collects every :class:`Text` of the drawn tree at a given layout width."""

    def __init__(self, translate: Translator, context, width: float):
        self.tr, self.context, self.width, self.texts = translate, context, width, []

    def add(self, text, room, where):
        if text:
            self.texts.append(Text(text, room, where))

    def node(self, node: _Node, width: float, where: str):
        if node.kind == "box":
            width -= BOX
        if node.kind in ("column", "box"):
            for item in node.items:
                self.item(item, width, where)
            return
        if node.kind == "split":
            widths = [width * node.factor] + [width * (1 - node.factor) / max(1, len(node.items) - 1)] * \
                (len(node.items) - 1)
        else:   # a row: icon-only buttons one unit wide, the others share the rest
            fixed = [i for i in node.items if self._icon_only(i)]
            rest = max(1, len(node.items) - len(fixed))
            share = (width - UNIT * len(fixed)) / rest
            widths = [UNIT if self._icon_only(i) else share for i in node.items]
        for item, item_width in zip(node.items, widths):
            self.item(item, item_width, where)

    @classmethod
    def _icon_only(cls, item) -> bool:
        if isinstance(item, _Node):       # a column of icon buttons is one unit wide too
            return item.kind == "column" and bool(item.items) and all(cls._icon_only(i) for i in item.items)
        kind, what = item[0], item[1]
        if kind == "prop":
            data, name, text = what[0], what[1], what[2]
            return text == "" and data.bl_rna.properties[name].type == "BOOLEAN"
        return kind in ("operator", "label") and what == "" and item[2]

    def item(self, item, width: float, where: str):
        if isinstance(item, _Node):
            self.node(item, width, where)
            return
        kind, what, icon = item[0], item[1], item[2]
        room_icon = UNIT if icon else 0
        if kind == "label":
            text = self.tr(what) if item[3] else what
            self.add(text, width - PAD - room_icon, f"{where}: label {what!r}")
        elif kind in ("operator", "menu"):
            text = self.tr(what, "Operator") if kind == "operator" and item[3] else self.tr(what)
            self.add(text, width - 2 * PAD - room_icon, f"{where}: button {what!r}")
        elif kind == "list":
            cls, data, propname = what
            row_width = width - UNIT - PAD     # the list's scroll bar and border
            for element in getattr(data, propname):
                sub = Layout()
                cls.draw_item(cls, self.context, sub, data, element, 0, data, "", 0, 0)
                self.node(sub._node, row_width, f"{where}: list row")
        elif kind == "prop":
            self.prop(what, width - room_icon, item[3], item[4], where)

    def prop(self, what, width, split, decorate, where):
        data, name, text, index, expand = what
        prop = data.bl_rna.properties[name]
        label = self.tr(prop.name if text is None else text)
        if split and decorate:
            width -= UNIT
        if prop.type == "BOOLEAN":
            # a check box with its name beside it, in the value column when split
            room = width * (1 - SPLIT) if split else width
            self.add(label, room - UNIT - PAD, f"{where}: check box {prop.name!r}")
            return
        if split:
            self.add(label, width * SPLIT - PAD, f"{where}: name {prop.name!r}")
            width *= 1 - SPLIT
        elif label and prop.type == "ENUM":
            self.add(label, width / 2 - PAD, f"{where}: name {prop.name!r}")
            width /= 2
        if prop.type == "ENUM":
            names = [self.tr(n) for n in _enum_names(data, name, self.context)]
            if expand:
                for n in names:
                    self.add(n, width / len(names) - 2 * PAD, f"{where}: {prop.name!r} item {n!r}")
            else:
                for n in names:
                    self.add(n, width - PAD - UNIT, f"{where}: {prop.name!r} item {n!r}")
        elif prop.type in ("FLOAT", "INT"):
            value = _value_text(data, name, index)
            shown = value if split or not label else f"{label}: {value}"
            self.add(shown, width - 2 * PAD, f"{where}: value of {prop.name!r}")
        # pointers and strings: the user's own names, clipped like any file name


def panel_texts(panel_cls, context, translate: Translator, width: float) -> list:
    """Every text of one panel (its header and what ``draw`` puts in it)."""
    walk = Walk(translate, context, width)
    if "HIDE_HEADER" not in getattr(panel_cls, "bl_options", set()):
        # the header: the collapse arrow at the left, the drag grip at the right
        walk.add(translate(panel_cls.bl_label), width + 2 * PANELSPACE - 3 * UNIT, f"{panel_cls.__name__} header")
    layout = Layout()
    panel_cls.draw(_Panel(layout), context)
    walk.node(layout._node, width, panel_cls.__name__)
    return walk.texts


class _Panel:
    """``self`` of a panel's draw: only its layout is used."""

    def __init__(self, layout):
        self.layout = layout


def all_texts(panel_classes, context, table: dict | None, width: float | None = None) -> list:
    width = layout_width() if width is None else width
    texts, shown = [], set()
    for cls in panel_classes:     # parents come before their sub-panels
        parent = getattr(cls, "bl_parent_id", "")
        if (parent and parent not in shown) or (getattr(cls, "poll", None) is not None and not cls.poll(context)):
            continue
        shown.add(cls.bl_idname)
        texts.extend(panel_texts(cls, context, Translator(table), width))
    return texts


def too_wide(texts) -> list:
    return [f"{t.where}: {t.text!r} is {t.width:.0f} px, has {t.room:.0f} px" for t in texts if not t.fits]

