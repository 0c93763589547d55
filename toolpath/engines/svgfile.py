"""SVG drawings (Inkscape, Illustrator, any SVG 1.1 / 2 writer) read into a :class:`Design` in mm.

What is read, as the SVG 1.1 / SVG 2 specifications and the writers' conventions say:

- **Size**: the root's ``width`` / ``height`` with their units (CSS: 96 px = 1 in = 25.4 mm, 1 pt =
  1/72 in, 1 pc = 12 pt, 1 cm = 10 mm, 1 Q = 0.25 mm; a bare number is px) and its ``viewBox``
  mapped onto them with ``preserveAspectRatio`` (default xMidYMid meet).  Inkscape writes
  ``width="210mm"`` with a viewBox in mm; Illustrator writes ``width="200pt"`` or px.  Without a
  size the user unit is a px.
- **Y up**: SVG's Y runs down the page; the design's runs up, with the page's bottom-left corner
  at (0, 0) (Y mirrored about the page's top when the page has no height).
- **Shapes**: path (all commands, :mod:`.svgpath`), rect (rounded with rx / ry), circle, ellipse,
  line, polyline, polygon; ``<use>`` of any element by id (``href`` or ``xlink:href``, with its x / y);
  transforms nested through groups.  Inkscape's arcs (``sodipodi:type="arc"``) are read from their
  ``d`` as Inkscape draws them.
- **Layers**: Inkscape's ``<g inkscape:groupmode="layer" inkscape:label="...">``; in a file without
  them, Illustrator's top-level groups (``id="Layer_1"``, ``data-name="Cut"``).
- **Skipped**: hidden elements (``display:none`` / ``display="none"``) with what they hold;
  defs, symbols, clip paths, masks, markers, metadata (only through ``<use>``); texts and images
  (listed in the design's notes: convert text to paths in the drawing program).

The file is parsed with expat and refused before any expansion when its document type declares
an external or parameter entity, or an entity that refers to another (the "billion laughs"
file); the plain-text entities old Illustrator files declare (``<!ENTITY ns_svg "...">``) are
read.  Errors name the file, the element (tag, id) and its line.
"""
from __future__ import annotations

import math
import re
from xml.parsers import expat

import numpy as np

from .designshapes import (JOIN_TOLERANCE, Design, DesignFileError, PointBudget, applied, checked_file,
                           arc_points, circle_points, finished, is_similarity, joined_by_layer, largest_scale)
from .region import ARC_TOLERANCE
from .svgpath import NUMBER, PathData, transform_matrix

SVG_NS = "http://www.w3.org/2000/svg"
XLINK_NS = "http://www.w3.org/1999/xlink"
INKSCAPE_NS = "http://www.inkscape.org/namespaces/inkscape"
MM_PER = {"px": 25.4 / 96, "": 25.4 / 96, "pt": 25.4 / 72, "pc": 25.4 / 6, "mm": 1.0, "cm": 10.0, "in": 25.4,
          "q": 0.25}
CONTAINERS = {"g", "a", "switch", "svg"}
SHAPES = {"path", "rect", "circle", "ellipse", "line", "polyline", "polygon"}
TEXTS = {"text", "flowRoot"}
MAX_DEPTH = 200             # elements nested deeper than this are not a drawing
MAX_VISITS = 100_000      # elements drawn, uses counted each time (a sign has 10^3)
MAX_ENTITIES = 100          # entity declarations (Illustrator declares about ten)
MAX_ENTITY_CHARS = 1000


class Node:
    """One element: local ``tag``, ``attrs`` (namespaced names as "namespace local"), children, line."""

    __slots__ = ("tag", "attrs", "children", "line")

    def __init__(self, tag: str, attrs: dict, line: int):
        self.tag, self.attrs, self.children, self.line = tag, attrs, [], line

    def get(self, name: str, default=None):
        return self.attrs.get(name, default)


def parse_tree(data: bytes, name: str) -> Node:
    """The element tree of the file's bytes, refusing entity tricks and absurd nesting."""
    parser = expat.ParserCreate(namespace_separator=" ")
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    stack, roots, entities = [], [], []

    def entity(entity_name, is_parameter, value, base, system_id, public_id, notation):
        line = parser.CurrentLineNumber
        if is_parameter or value is None:
            raise DesignFileError(f"{name}: line {line}: entity {entity_name!r}: external and parameter entities "
                                  "are refused")
        if "&" in value or "<" in value or len(value) > MAX_ENTITY_CHARS:
            raise DesignFileError(f"{name}: line {line}: entity {entity_name!r}: an entity that refers to others or "
                                  "holds markup is refused (it can expand without end)")
        entities.append(entity_name)
        if len(entities) > MAX_ENTITIES:
            raise DesignFileError(f"{name}: line {line}: entity {entity_name!r}: more than {MAX_ENTITIES} entity "
                                  "declarations are refused")

    def start(tag, attrs):
        if len(stack) >= MAX_DEPTH:
            raise DesignFileError(f"{name}: line {parser.CurrentLineNumber}: elements nested more than "
                                  f"{MAX_DEPTH} deep")
        node = Node(tag.rsplit(" ", 1)[-1], attrs, parser.CurrentLineNumber)
        node.attrs["__ns"] = tag.rsplit(" ", 1)[0] if " " in tag else ""
        (stack[-1].children if stack else roots).append(node)
        stack.append(node)

    def external(context, base, system_id, public_id):
        raise DesignFileError(f"{name}: line {parser.CurrentLineNumber}: an external entity is refused")

    parser.EntityDeclHandler = entity
    parser.StartElementHandler = start
    parser.EndElementHandler = lambda tag: stack.pop()
    parser.ExternalEntityRefHandler = external
    try:
        parser.Parse(data, True)
    except expat.ExpatError as error:
        hint = ": is the file cut short?" if "no element found" in str(error) or "unclosed" in str(error) else ""
        raise DesignFileError(f"{name}: not well-formed XML ({expat.ErrorString(error.code)}, line "
                              f"{error.lineno}){hint}") from None
    if not roots or roots[0].tag != "svg":
        raise DesignFileError(f"{name}: not an SVG drawing (the root element is "
                              f"<{roots[0].tag if roots else 'nothing'}>)")
    return roots[0]


def length(text, where: str, attribute: str, default=None, percent_ok: bool = False):
    """A length attribute in user units (px): a number with an optional unit."""
    if text is None:
        if default is None:
            raise DesignFileError(f"{where}: {attribute} is missing")
        return default
    match = re.fullmatch(r"\s*(" + NUMBER.pattern + r")\s*(px|pt|pc|mm|cm|in|q|%)?\s*", str(text), re.IGNORECASE)
    if match is None:
        raise DesignFileError(f"{where}: {attribute}={text!r} is not a length")
    value = float(match.group(1))
    unit = (match.group(2) or "").lower()
    if not math.isfinite(value):
        raise DesignFileError(f"{where}: {attribute}={text!r} is not a finite number")
    if unit == "%":
        if percent_ok:
            return None
        raise DesignFileError(f"{where}: {attribute}={text!r}: a percentage is not a length in a drawing")
    return value * MM_PER[unit] / MM_PER["px"]


def style_of(node: Node) -> dict:
    """Presentation attributes overridden by the ``style`` attribute's declarations."""
    found = {key: node.get(key) for key in ("display", "visibility") if node.get(key) is not None}
    for item in (node.get("style") or "").split(";"):
        if ":" in item:
            key, value = item.split(":", 1)
            found[key.strip()] = value.strip()
    return found


def page_matrix(root: Node, name: str):
    """(matrix from the root's user units to mm with Y up, the page's (width, height) in mm or None)."""
    where = f"{name}: <svg> (line {root.line})"
    width = length(root.get("width"), where, "width", default=-1.0, percent_ok=True)
    height = length(root.get("height"), where, "height", default=-1.0, percent_ok=True)
    width = None if width is None or width < 0 else width * MM_PER["px"]
    height = None if height is None or height < 0 else height * MM_PER["px"]
    box = root.get("viewBox")
    matrix = np.diag([MM_PER["px"], MM_PER["px"], 1.0])
    if box is not None:
        numbers = [float(v) for v in NUMBER.findall(box)]
        if len(numbers) != 4 or not all(map(math.isfinite, numbers)) or numbers[2] <= 0 or numbers[3] <= 0:
            raise DesignFileError(f"{where}: viewBox={box!r} is not four numbers with a positive width and height")
        x0, y0, w, h = numbers
        if width is None and height is not None:
            width = height * w / h
        if height is None and width is not None:
            height = width * h / w
        if width is None:
            width, height = w * MM_PER["px"], h * MM_PER["px"]
        sx, sy = width / w, height / h
        aspect = (root.get("preserveAspectRatio") or "xMidYMid meet").split()
        tx, ty = 0.0, 0.0
        if aspect[0] != "none":
            s = max(sx, sy) if "slice" in aspect else min(sx, sy)
            align = {"Min": 0.0, "Mid": 0.5, "Max": 1.0}
            ax, ay = align.get(aspect[0][1:4], 0.5), align.get(aspect[0][5:8], 0.5)
            tx, ty, sx, sy = ax * (width - w * s), ay * (height - h * s), s, s
        matrix = np.array([[sx, 0, tx - x0 * sx], [0, sy, ty - y0 * sy], [0, 0, 1.0]])
    flip = np.array([[1.0, 0, 0], [0, -1.0, height if height is not None else 0.0], [0, 0, 1]])
    return flip @ matrix, (width, height) if width is not None and height is not None else None


class Reader:
    """Walks the element tree, gathering shapes in mm."""

    def __init__(self, name: str, root: Node, tolerance: float):
        self.name, self.root, self.tolerance = name, root, tolerance
        self.budget = PointBudget(name)
        self.shapes, self.notes = [], []
        self.visits = 0
        self.ids = {}
        pending = [root]
        while pending:
            node = pending.pop()
            if node.get("id") is not None:
                self.ids.setdefault(node.get("id"), node)
            pending += node.children
        inkscape_layers = any(node.get(f"{INKSCAPE_NS} groupmode") == "layer" for node in self.ids.values()) or \
            self.has_layers(root)
        self.illustrator_layers = not inkscape_layers

    def has_layers(self, node: Node) -> bool:
        return node.get(f"{INKSCAPE_NS} groupmode") == "layer" or any(self.has_layers(c) for c in node.children
                                                                       if c.tag in CONTAINERS)

    def where(self, node: Node) -> str:
        ident = node.get("id")
        return f"{self.name}: <{node.tag}{' id=' + repr(ident) if ident else ''}> (line {node.line})"

    def layer_of(self, node: Node, parent_layer: str, top: bool) -> str:
        if node.tag != "g":
            return parent_layer
        if node.get(f"{INKSCAPE_NS} groupmode") == "layer":
            return node.get(f"{INKSCAPE_NS} label") or node.get("id") or parent_layer
        if top and self.illustrator_layers:
            if node.get("data-name"):
                return node.get("data-name")
            if re.fullmatch(r"Layer_\d+", node.get("id") or ""):
                return node.get("id").replace("_", " ")
        return parent_layer

    def walk(self, node: Node, matrix: np.ndarray, layer: str, using: tuple = (), top: bool = False,
             depth: int = 0) -> None:
        if style_of(node).get("display") == "none":
            return
        self.visits += 1
        if self.visits > MAX_VISITS:
            raise DesignFileError(f"{self.where(node)}: more than {MAX_VISITS} elements drawn (uses of uses?)")
        if depth > MAX_DEPTH:
            raise DesignFileError(f"{self.where(node)}: elements and uses nested more than {MAX_DEPTH} deep")
        ns = node.get("__ns")
        if ns not in (SVG_NS, ""):
            return                                   # another program's element (sodipodi:namedview ...)
        where = self.where(node)
        if node.get("transform") is not None:
            matrix = matrix @ transform_matrix(node.get("transform"), where)
        if node.tag in CONTAINERS:
            if node.tag == "svg" and node is not self.root:
                shift = np.eye(3)
                shift[:2, 2] = (length(node.get("x"), where, "x", 0.0), length(node.get("y"), where, "y", 0.0))
                matrix = matrix @ shift
            inner = self.layer_of(node, layer, top)
            for child in node.children:
                self.walk(child, matrix, inner, using, node is self.root, depth + 1)
        elif node.tag == "use":
            self.use(node, matrix, layer, using, where, depth)
        elif node.tag in SHAPES:
            self.shape(node, matrix, layer, where)
        elif node.tag in TEXTS:
            self.notes.append(f"{where}: a text, skipped (convert it to paths in the drawing program)")
        elif node.tag == "image":
            self.notes.append(f"{where}: an image, skipped")

    def use(self, node: Node, matrix, layer: str, using: tuple, where: str, depth: int) -> None:
        reference = node.get("href") or node.get(f"{XLINK_NS} href") or ""
        if not reference.startswith("#") or reference[1:] not in self.ids:
            raise DesignFileError(f"{where}: href={reference!r} names no element of the file")
        if reference in using or len(using) > 32:
            raise DesignFileError(f"{where}: href={reference!r} uses itself (through {' '.join(using) or 'itself'})")
        shift = np.eye(3)
        shift[:2, 2] = (length(node.get("x"), where, "x", 0.0), length(node.get("y"), where, "y", 0.0))
        target = self.ids[reference[1:]]
        matrix = matrix @ shift
        if target.tag == "symbol":
            if style_of(target).get("display") == "none":
                return
            for child in target.children:
                self.walk(child, matrix, layer, using + (reference,), depth=depth + 1)
        else:
            self.walk(target, matrix, layer, using + (reference,), depth=depth + 1)

    def shape(self, node: Node, matrix, layer: str, where: str) -> None:
        scale = largest_scale(matrix)
        if scale == 0 or abs(matrix[0, 0] * matrix[1, 1] - matrix[0, 1] * matrix[1, 0]) < 1e-300:
            self.notes.append(f"{where}: its transform flattens it to nothing, skipped")
            return
        tolerance = self.tolerance / scale              # in this element's user units
        circle = None
        tag = node.tag
        if tag == "path":
            pieces = PathData(node.get("d") or "", where, tolerance, self.budget).subpaths()
        elif tag in ("circle", "ellipse"):
            cx, cy = length(node.get("cx"), where, "cx", 0.0), length(node.get("cy"), where, "cy", 0.0)
            if tag == "circle":
                rx = ry = length(node.get("r"), where, "r", 0.0)
            else:
                rx, ry = length(node.get("rx"), where, "rx", 0.0), length(node.get("ry"), where, "ry", 0.0)
            if rx <= 0 or ry <= 0:
                return                                   # not rendered (SVG 2, 10.3 and 10.4)
            loop = arc_points(cx, cy, rx, ry, 0.0, 0.0, 2 * math.pi, tolerance)[:-1] if rx != ry else \
                circle_points(cx, cy, rx, tolerance)
            pieces = [(loop, True)]
            if rx == ry and is_similarity(matrix):
                centre = applied(matrix, [(cx, cy)])[0]
                circle = (float(centre[0]), float(centre[1]), rx * scale)
        elif tag == "rect":
            pieces = [(self.rect(node, where, tolerance), True)]
            if pieces[0][0] is None:
                return
        elif tag == "line":
            pieces = [(np.array([[length(node.get(k), where, k, 0.0) for k in pair]
                                 for pair in (("x1", "y1"), ("x2", "y2"))]), False)]
        else:   # polyline, polygon
            text = node.get("points") or ""
            numbers = [float(v) for v in NUMBER.findall(text)]
            if NUMBER.sub("", text).strip(" \t\r\n,") or len(numbers) % 2:
                raise DesignFileError(f"{where}: points must be pairs of numbers")
            pieces = [(np.array(numbers).reshape(-1, 2), tag == "polygon")]
        for points, closed in pieces:
            self.budget.spend(len(points), where)
            shape = finished(applied(matrix, points), closed, layer, where, circle)
            if shape is not None:
                self.shapes.append(shape)

    def rect(self, node: Node, where: str, tolerance: float):
        x, y = length(node.get("x"), where, "x", 0.0), length(node.get("y"), where, "y", 0.0)
        w, h = length(node.get("width"), where, "width", 0.0), length(node.get("height"), where, "height", 0.0)
        if w <= 0 or h <= 0:
            return None                                   # not rendered
        rx = length(node.get("rx"), where, "rx", -1.0)
        ry = length(node.get("ry"), where, "ry", -1.0)
        rx, ry = (ry if rx < 0 else rx), (rx if ry < 0 else ry)        # one given: both (SVG 1.1, 9.2)
        rx, ry = min(max(rx, 0.0), w / 2), min(max(ry, 0.0), h / 2)
        if rx == 0 or ry == 0:
            return np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]], float)
        corners = [(x + w - rx, y + ry, -math.pi / 2), (x + w - rx, y + h - ry, 0.0),
                   (x + rx, y + h - ry, math.pi / 2), (x + rx, y + ry, math.pi)]
        return np.vstack([arc_points(cx, cy, rx, ry, 0.0, start, math.pi / 2, tolerance)
                          for cx, cy, start in corners])


def read_svg(path: str, tolerance: float = ARC_TOLERANCE, join_tolerance: float = JOIN_TOLERANCE) -> Design:
    """The SVG file's shapes in mm (Y up, the page's bottom-left at 0, 0), curves within
    ``tolerance`` mm, open pieces of a layer joined where their ends meet within ``join_tolerance``."""
    name = checked_file(path)
    with open(path, "rb") as stream:
        data = stream.read()
    if data[:2] == b"\x1f\x8b":
        raise DesignFileError(f"{name}: a compressed SVG (.svgz): save it as plain SVG")
    root = parse_tree(data, name)
    matrix, _ = page_matrix(root, name)
    reader = Reader(name, root, tolerance)
    reader.walk(root, matrix, "", top=True)
    shapes, notes = joined_by_layer(reader.shapes, join_tolerance)
    if not shapes and reader.notes:
        raise DesignFileError(f"{name}: no lines or curves to cut ({'; '.join(reader.notes[:3])})")
    if not shapes:
        raise DesignFileError(f"{name}: no lines or curves to cut")
    return Design(path, tuple(shapes), tuple(reader.notes + notes))
