"""ASCII DXF drawings (R12 and R2000 onwards, as CAD programs and laser shops write them) read into
a :class:`Design` in mm.

A DXF file is pairs of lines: a group code (an integer) and its value.  Read here, as the DXF
reference (AutoCAD's "DXF Reference", group codes by entity) describes them:

- ``$INSUNITS`` of the HEADER (70: 1 inch, 2 foot, 4 mm, 5 cm, 6 m, 8 microinch, 9 mil, 10 yard,
  13 micron, 14 dm); a file without units (0 or no $INSUNITS) is read in mm unless a scale (mm per
  drawing unit) is given, and the design's notes say so.
- LINE (10/20, 11/21); CIRCLE (10/20 centre, 40 radius); ARC (and 50/51: start and end angle in
  degrees, counter-clockwise); LWPOLYLINE (90 count, 70 flag 1 closed, 10/20 per vertex, 42 the
  bulge of the segment that starts there: tan(included angle / 4), > 0 counter-clockwise);
  POLYLINE with its VERTEX entities up to SEQEND (the same bulges; spline frame points, 3-D meshes
  and polyface meshes left out); ELLIPSE (10/20 centre, 11/21 the major axis' end from the centre,
  40 minor / major, 41/42 start and end parameter in radians); SPLINE (71 degree, 40 knots, 41
  weights, 10/20 control points, 11/21 fit points; 70 flag 1 closed), the B-spline evaluated with
  de Boor's algorithm, or, with fit points only, a Catmull-Rom curve through them; INSERT (2 block,
  10/20 insertion point, 41/42 scale, 50 rotation in degrees, 70/71 columns/rows with 44/45 spacing)
  of a BLOCK (10/20 base point), nested, its entities on layer 0 taking the insert's layer.
- The object coordinate system of CIRCLE, ARC, LWPOLYLINE, 2-D POLYLINE and INSERT when the
  extrusion (210/220/230) is (0, 0, -1), as mirrored parts often come: X mirrored (the arbitrary
  axis algorithm); other extrusions are not in the drawing's plane and are refused.
- Layers (8) from the entities, off (colour < 0) and frozen (70 flag 1) layers of the LAYER table
  skipped, and so are entities in paper space (67 = 1: a sheet's frame).  Entities that draw no
  cutting line (TEXT, MTEXT, DIMENSION, HATCH, POINT, ...) and
  unknown ones are skipped and listed in the design's notes with their line.

Open pieces of a layer (LINEs, ARCs, open polylines) are joined end to end into closed loops.
Binary DXF is refused.  Errors name the file, the entity and its line.
"""
from __future__ import annotations

import math

import numpy as np

from .designshapes import (JOIN_TOLERANCE, MAX_SEGMENTS, Design, DesignFileError, PointBudget, checked_file,
                           applied, arc_points, bulge_points, circle_points, finished, is_similarity, joined_by_layer,
                           largest_scale)
from .region import ARC_TOLERANCE
from .svgpath import bezier
from .textfile import read_text

# $INSUNITS -> mm per unit (DXF reference, HEADER section variables)
UNITS = {1: 25.4, 2: 304.8, 4: 1.0, 5: 10.0, 6: 1000.0, 8: 25.4e-6, 9: 0.0254, 10: 914.4, 13: 0.001, 14: 100.0}
UNIT_NAMES = {1: "inches", 2: "feet", 4: "mm", 5: "cm", 6: "m", 8: "microinches", 9: "mils", 10: "yards",
              13: "microns", 14: "decimetres"}
NOT_CUT = {"TEXT", "MTEXT", "DIMENSION", "HATCH", "POINT", "SOLID", "3DFACE", "LEADER", "MLEADER", "VIEWPORT",
           "ATTRIB", "ATTDEF", "IMAGE", "WIPEOUT", "TOLERANCE", "TRACE", "OLE2FRAME", "REGION", "3DSOLID", "BODY",
           "RAY", "XLINE", "MLINE", "ACAD_TABLE", "SEQEND", "VERTEX"}
MAX_INSERT_DEPTH = 16
MAX_DRAWN = 1_000_000     # entities drawn, each insert's counted again


class Entity:
    """One entity: its ``kind`` (LINE ...), first ``line`` in the file and its (code, value, line) groups."""

    __slots__ = ("kind", "line", "groups", "vertices", "name")

    def __init__(self, kind: str, line: int, groups: list, name: str):
        self.kind, self.line, self.groups, self.name = kind, line, groups, name
        self.vertices = []

    def where(self) -> str:
        return f"{self.name}: {self.kind} at line {self.line}"

    def text(self, code: int, default: str = "") -> str:
        for c, value, _ in self.groups:
            if c == code:
                return value
        return default

    def number(self, code: int, default: float | None = None) -> float:
        for c, value, line in self.groups:
            if c == code:
                return parsed(value, line, code, self)
        if default is None:
            raise DesignFileError(f"{self.where()}: group {code} is missing")
        return default

    def numbers(self, code: int) -> list:
        return [parsed(value, line, code, self) for c, value, line in self.groups if c == code]


def parsed(value: str, line: int, code: int, entity) -> float:
    try:
        number = float(value)
    except ValueError:
        raise DesignFileError(f"{entity.where()}: line {line}: group {code} = {value.strip()!r} is not a number") \
            from None
    if not math.isfinite(number):
        raise DesignFileError(f"{entity.where()}: line {line}: group {code} = {value.strip()!r} is not a finite number")
    return number


def group_pairs(text: str, name: str) -> list:
    """(code, value, line of the code) of every pair of lines."""
    lines = text.splitlines()
    while lines and not lines[-1].strip():
        lines.pop()
    if len(lines) % 2:
        raise DesignFileError(f"{name}: {len(lines)} lines, an odd number: a group code without its value at "
                              f"line {len(lines)} (is the file cut short?)")
    pairs = []
    for index in range(0, len(lines), 2):
        code = lines[index].strip()
        if not code.lstrip("-").isdigit():
            raise DesignFileError(f"{name}: line {index + 1}: group code {code[:40]!r} is not a whole number "
                                  "(not an ASCII DXF file?)")
        pairs.append((int(code), lines[index + 1].strip(), index + 1))
    return pairs


def entities_of(pairs: list, start: int, stop: int, name: str) -> list:
    """The entities among pairs[start:stop], a POLYLINE holding its VERTEX entities."""
    found, current = [], None
    for code, value, line in pairs[start:stop]:
        if code == 0:
            current = Entity(value, line, [], name)
            if value in ("VERTEX", "SEQEND") and found and found[-1].kind == "POLYLINE":
                if value == "VERTEX":
                    found[-1].vertices.append(current)
                continue
            found.append(current)
        elif current is not None:
            current.groups.append((code, value, line))
    return found


class Sections:
    """The file's HEADER variables, LAYER table, BLOCKS and ENTITIES."""

    def __init__(self, pairs: list, name: str):
        self.name, self.header, self.layers, self.blocks, self.entities = name, {}, {}, {}, []
        index, saw_entities = 0, False
        while index < len(pairs):
            code, value, line = pairs[index]
            if code == 0 and value == "EOF":
                break
            if code == 0 and value == "SECTION":
                if index + 1 >= len(pairs) or pairs[index + 1][0] != 2:
                    raise DesignFileError(f"{name}: line {line}: a SECTION without its name")
                section = pairs[index + 1][1]
                end = next((i for i in range(index + 2, len(pairs)) if pairs[i][:2] == (0, "ENDSEC")), None)
                if end is None:
                    raise DesignFileError(f"{name}: the {section} section from line {line} has no ENDSEC (is the "
                                          "file cut short?)")
                self.section(section, pairs, index + 2, end)
                saw_entities |= section == "ENTITIES"
                index = end + 1
                continue
            index += 1
        if not saw_entities:
            raise DesignFileError(f"{name}: no ENTITIES section (not a DXF drawing, or cut short?)")

    def section(self, section: str, pairs: list, start: int, end: int) -> None:
        if section == "HEADER":
            for i in range(start, end - 1):
                if pairs[i][0] == 9:
                    self.header[pairs[i][1]] = pairs[i + 1]
        elif section == "TABLES":
            for entity in entities_of(pairs, start, end, self.name):
                if entity.kind == "LAYER":
                    flags = int(entity.number(70, 0.0))
                    color = entity.number(62, 7.0)
                    self.layers[entity.text(2)] = bool(flags & 1) or color < 0
        elif section == "BLOCKS":
            block = None
            for entity in entities_of(pairs, start, end, self.name):
                if entity.kind == "BLOCK":
                    block = (entity, [])
                    self.blocks[entity.text(2)] = block
                elif entity.kind == "ENDBLK":
                    block = None
                elif block is not None:
                    block[1].append(entity)
        elif section == "ENTITIES":
            self.entities = entities_of(pairs, start, end, self.name)


def ocs_matrix(entity: Entity) -> np.ndarray:
    """Object coordinates -> world for an extrusion along +Z or -Z (the arbitrary axis algorithm
    gives X mirrored for -Z); anything else is refused."""
    nx, ny, nz = entity.number(210, 0.0), entity.number(220, 0.0), entity.number(230, 1.0)
    length = math.sqrt(nx * nx + ny * ny + nz * nz)
    if length == 0 or abs(nx) / length > 1e-9 or abs(ny) / length > 1e-9:
        raise DesignFileError(f"{entity.where()}: its extrusion ({nx:g}, {ny:g}, {nz:g}) is not along Z: it does not "
                              "lie in the drawing's plane")
    return np.diag([1.0 if nz > 0 else -1.0, 1.0, 1.0])


def spline_points(entity: Entity, tolerance: float) -> tuple[np.ndarray, bool]:
    """The SPLINE's points within ``tolerance`` (its own units) and whether it is closed."""
    degree = int(entity.number(71, 3.0))
    knots = np.array(entity.numbers(40))
    xs, ys = entity.numbers(10), entity.numbers(20)
    closed = bool(int(entity.number(70, 0.0)) & 1)
    if len(xs) != len(ys):
        raise DesignFileError(f"{entity.where()}: {len(xs)} control point X values but {len(ys)} Y values")
    if not xs:
        fx, fy = entity.numbers(11), entity.numbers(21)
        if len(fx) != len(fy) or len(fx) < 2:
            raise DesignFileError(f"{entity.where()}: neither control points nor two fit points")
        return through_points(np.column_stack([fx, fy]), closed, tolerance), closed
    control = np.column_stack([xs, ys])
    weights = np.array(entity.numbers(41)) if entity.numbers(41) else np.ones(len(control))
    if not 1 <= degree <= 11 or len(control) < degree + 1:
        raise DesignFileError(f"{entity.where()}: degree {degree} with {len(control)} control points")
    if len(knots) != len(control) + degree + 1 or np.any(np.diff(knots) < 0):
        raise DesignFileError(f"{entity.where()}: {len(knots)} knots for {len(control)} control points of degree "
                              f"{degree} (needs {len(control) + degree + 1}, never decreasing)")
    if len(weights) != len(control) or np.any(weights <= 0):
        raise DesignFileError(f"{entity.where()}: the weights must be one positive number per control point")
    return bspline(control, weights, knots, degree, tolerance), closed


def bspline(control: np.ndarray, weights: np.ndarray, knots: np.ndarray, degree: int, tolerance: float) -> np.ndarray:
    """Points of a (rational) B-spline over its domain [t_p, t_n+1], each knot span sampled evenly:
    n segments of a span h long keep the chord error below h^2 max|C''| / (8 n^2), |C''| bounded by
    the second-derivative control points (times the weights' spread for a rational curve)."""
    p, count = degree, len(control)
    homogeneous = np.column_stack([control * weights[:, None], weights])
    bound = 0.0
    if p >= 2:
        d1 = p * np.diff(control, axis=0) / np.maximum(knots[p + 1:count + p] - knots[1:count], 1e-300)[:, None]
        d2 = (p - 1) * np.diff(d1, axis=0) / np.maximum(knots[p + 1:count + p - 1] - knots[2:count], 1e-300)[:, None]
        finite = np.isfinite(d2).all(axis=1)
        bound = float(np.hypot(d2[finite, 0], d2[finite, 1]).max()) if finite.any() else 0.0
        bound *= float(weights.max() / weights.min()) ** 2
    pieces = [homogeneous_point(homogeneous, knots, p, p, knots[p])]
    spans = [k for k in range(p, count) if knots[k + 1] > knots[k]]
    for k in spans:
        h = knots[k + 1] - knots[k]
        n = int(min(max(1, math.ceil(h * math.sqrt(bound / (8 * tolerance)))), MAX_SEGMENTS)) if bound > 0 else 1
        u = knots[k] + h * np.arange(1, n + 1) / n
        pieces.append(homogeneous_point(homogeneous, knots, p, k, u))
    points = np.vstack(pieces)
    return points[:, :2] / points[:, 2:3]


def homogeneous_point(control: np.ndarray, knots: np.ndarray, p: int, k: int, u) -> np.ndarray:
    """de Boor's algorithm on span k for parameter(s) u: (m, 3) homogeneous points."""
    u = np.atleast_1d(np.asarray(u, float))
    d = np.repeat(control[k - p:k + 1][:, None, :], len(u), axis=1)        # (p + 1, m, 3)
    for r in range(1, p + 1):
        for j in range(p, r - 1, -1):
            left, right = knots[j + k - p], knots[j + 1 + k - r]
            alpha = ((u - left) / (right - left))[:, None] if right > left else np.zeros((len(u), 1))
            d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j]
    return d[p]


def through_points(fit: np.ndarray, closed: bool, tolerance: float) -> np.ndarray:
    """A curve through the fit points: Catmull-Rom segments (each a cubic Bezier with the tangent at
    a point parallel to the chord between its neighbours), the ends' tangents along their chords."""
    points = np.vstack([fit[-1], fit, fit[0], fit[1]]) if closed else np.vstack([fit[0], fit, fit[-1]])
    out = [fit[:1]]
    for i in range(1, len(points) - 2):
        p0, p1, p2, p3 = points[i - 1], points[i], points[i + 1], points[i + 2]
        out.append(bezier(np.array([p1, p1 + (p2 - p0) / 6, p2 - (p3 - p1) / 6, p2]), tolerance))
    return np.vstack(out)


def polyline_points(vertices: list, closed: bool, tolerance: float) -> np.ndarray:
    """[(x, y, bulge)] -> points, each bulge an arc to the next vertex."""
    if not vertices:
        return np.empty((0, 2))
    out = [np.array([vertices[0][:2]], float)]
    ends = range(len(vertices)) if closed else range(len(vertices) - 1)
    for i in ends:
        (x0, y0, bulge), (x1, y1, _) = vertices[i], vertices[(i + 1) % len(vertices)]
        out.append(bulge_points((x0, y0), (x1, y1), bulge, tolerance))
    points = np.vstack(out)
    return points[:-1] if closed and len(points) > 1 else points


def lwpolyline_vertices(entity: Entity) -> list:
    vertices = []
    for code, value, line in entity.groups:
        if code == 10:
            vertices.append([parsed(value, line, code, entity), None, 0.0])
        elif code in (20, 42) and vertices:
            vertices[-1][1 if code == 20 else 2] = parsed(value, line, code, entity)
    if any(v[1] is None for v in vertices):
        raise DesignFileError(f"{entity.where()}: a vertex has an X (10) but no Y (20)")
    return [tuple(v) for v in vertices]


class Reader:
    def __init__(self, name: str, sections: Sections, tolerance: float, mm_per_unit: float):
        self.name, self.sections, self.tolerance = name, sections, tolerance
        self.units = np.diag([mm_per_unit, mm_per_unit, 1.0])
        self.budget = PointBudget(name)
        self.shapes, self.skipped, self.drawn = [], {}, 0

    def skip(self, entity: Entity, why: str, detail: str = "") -> None:
        """Skipped for ``why``: "off" (its layer, ``detail``, is off or frozen), "paper", "not cut",
        "unknown", "mesh"."""
        self.skipped.setdefault((why, detail or entity.kind), []).append(entity.line)

    def draw(self, entities: list, matrix: np.ndarray, layer_0: str | None, inserting: tuple, via: str = "") -> None:
        for entity in entities:
            self.drawn += 1
            if self.drawn > MAX_DRAWN:
                raise DesignFileError(f"{entity.where()}: more than {MAX_DRAWN} entities drawn (inserts of inserts?)")
            layer = entity.text(8, "0")
            if layer == "0" and layer_0 is not None:
                layer = layer_0
            if self.sections.layers.get(layer, False):
                self.skip(entity, "off", layer)
                continue
            if entity.text(67, "0").strip() == "1":          # paper space: a title block, a frame
                self.skip(entity, "paper")
                continue
            if entity.kind == "INSERT":
                self.insert(entity, matrix, layer, inserting, via)
            elif entity.kind in NOT_CUT:
                self.skip(entity, "not cut")
            elif entity.kind in ("LINE", "CIRCLE", "ARC", "LWPOLYLINE", "POLYLINE", "ELLIPSE", "SPLINE"):
                self.entity(entity, matrix, layer, via)
            else:
                self.skip(entity, "unknown")

    def insert(self, entity: Entity, matrix: np.ndarray, layer: str, inserting: tuple, via: str) -> None:
        block_name = entity.text(2)
        if block_name not in self.sections.blocks:
            raise DesignFileError(f"{entity.where()}: block {block_name!r} is not in the BLOCKS section")
        if block_name in inserting or len(inserting) >= MAX_INSERT_DEPTH:
            raise DesignFileError(f"{entity.where()}: block {block_name!r} inserts itself (through "
                                  f"{' > '.join(inserting)})")
        block, members = self.sections.blocks[block_name]
        base = np.eye(3)
        base[:2, 2] = (-block.number(10, 0.0), -block.number(20, 0.0))
        sx, sy = entity.number(41, 1.0), entity.number(42, 1.0)
        if sx == 0 or sy == 0:
            raise DesignFileError(f"{entity.where()}: a scale of 0 flattens block {block_name!r} to nothing")
        angle = math.radians(entity.number(50, 0.0))
        c, s = math.cos(angle), math.sin(angle)
        rotate = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
        columns, rows = int(entity.number(70, 1.0)), int(entity.number(71, 1.0))
        if not (1 <= columns <= 10_000 and 1 <= rows <= 10_000 and columns * rows <= 100_000):
            raise DesignFileError(f"{entity.where()}: {columns} columns x {rows} rows of block {block_name!r}")
        for row in range(rows):
            for column in range(columns):
                place = np.eye(3)
                place[:2, 2] = (entity.number(10, 0.0), entity.number(20, 0.0))
                cell = np.eye(3)
                cell[:2, 2] = (column * entity.number(44, 0.0), row * entity.number(45, 0.0))
                inner = matrix @ ocs_matrix(entity) @ place @ rotate @ cell @ np.diag([sx, sy, 1.0]) @ base
                self.draw(members, inner, layer, inserting + (block_name,),
                          f" of block {block_name!r} inserted at line {entity.line}{via}")

    def entity(self, entity: Entity, matrix: np.ndarray, layer: str, via: str) -> None:
        kind = entity.kind
        world = self.units @ matrix
        if kind not in ("LINE", "ELLIPSE", "SPLINE") and not (kind == "POLYLINE" and int(entity.number(70, 0.0)) & 8):
            world = world @ ocs_matrix(entity)
        scale = largest_scale(world)
        tolerance = self.tolerance / scale
        circle, closed = None, False
        if kind == "LINE":
            points = np.array([[entity.number(10), entity.number(20)], [entity.number(11), entity.number(21)]])
        elif kind in ("CIRCLE", "ARC"):
            cx, cy, r = entity.number(10), entity.number(20), entity.number(40)
            if r <= 0:
                raise DesignFileError(f"{entity.where()}: radius {r:g} must be > 0")
            if kind == "CIRCLE":
                points, closed = circle_points(cx, cy, r, tolerance), True
                if is_similarity(world):
                    centre = applied(world, [(cx, cy)])[0]
                    circle = (float(centre[0]), float(centre[1]), r * scale)
            else:
                start, end = math.radians(entity.number(50, 0.0)), math.radians(entity.number(51, 360.0))
                sweep = (end - start) % (2 * math.pi) or 2 * math.pi
                points = arc_points(cx, cy, r, r, 0.0, start, sweep, tolerance)
        elif kind == "LWPOLYLINE":
            closed = bool(int(entity.number(70, 0.0)) & 1)
            points = polyline_points(lwpolyline_vertices(entity), closed, tolerance)
        elif kind == "POLYLINE":
            flags = int(entity.number(70, 0.0))
            if flags & (16 | 64):
                self.skip(entity, "mesh")
                return
            closed = bool(flags & 1)
            vertices = [(v.number(10), v.number(20), v.number(42, 0.0)) for v in entity.vertices
                        if not int(v.number(70, 0.0)) & (16 | 128)]
            points = polyline_points(vertices, closed, tolerance)
        elif kind == "ELLIPSE":
            points, closed = self.ellipse(entity, tolerance)
        else:
            points, closed = spline_points(entity, tolerance)
        self.budget.spend(len(points), entity.where())
        shape = finished(applied(world, points), closed, layer, entity.where() + via, circle)
        if shape is not None:
            self.shapes.append(shape)

    def ellipse(self, entity: Entity, tolerance: float):
        cx, cy = entity.number(10), entity.number(20)
        ax, ay, ratio = entity.number(11), entity.number(21), entity.number(40, 1.0)
        major = math.hypot(ax, ay)
        if major == 0 or not 0 < ratio <= 1:
            raise DesignFileError(f"{entity.where()}: the major axis ({ax:g}, {ay:g}) and ratio {ratio:g} draw no ellipse")
        facing = -1.0 if entity.number(230, 1.0) < 0 else 1.0      # the minor axis: extrusion x major
        start, end = entity.number(41, 0.0), entity.number(42, 2 * math.pi)
        sweep = (end - start) % (2 * math.pi)
        full = sweep < 1e-9 or abs(sweep - 2 * math.pi) < 1e-9
        sweep = 2 * math.pi if full else sweep
        points = arc_points(0.0, 0.0, major, major * ratio, 0.0, start, sweep, tolerance)
        c, s = ax / major, ay / major
        turn = np.array([[c, -s * facing], [s, c * facing]])
        points = points @ turn.T + (cx, cy)
        return (points[:-1], True) if full else (points, False)

    def notes(self) -> list:
        found = []
        for (why, detail), lines in self.skipped.items():
            count, first = len(lines), lines[0]
            if why == "off":
                found.append(f"{self.name}: skipped {count} entities on the layer {detail!r}, which is off or "
                             f"frozen, first at line {first}")
            elif why == "not cut":
                found.append(f"{self.name}: skipped {count} {detail} (draws no cutting line), first at line {first}")
            elif why == "paper":
                found.append(f"{self.name}: skipped {count} {detail} in paper space (a sheet's frame or title "
                             f"block), first at line {first}")
            elif why == "mesh":
                found.append(f"{self.name}: skipped {count} POLYLINE meshes (3-D surfaces, not lines), first at line "
                             f"{first}")
            else:
                found.append(f"{self.name}: skipped {count} {detail} (an entity this reader does not know), first at "
                             f"line {first}")
        return found


def read_dxf(path: str, tolerance: float = ARC_TOLERANCE, scale: float | None = None,
             join_tolerance: float = JOIN_TOLERANCE) -> Design:
    """The DXF file's shapes in mm: units from $INSUNITS, or ``scale`` (mm per drawing unit) for a
    file without units (default 1: its numbers are mm); curves within ``tolerance`` mm; open pieces
    of a layer joined where their ends meet within ``join_tolerance`` mm."""
    name = checked_file(path)
    with open(path, "rb") as stream:
        if stream.read(22).startswith(b"AutoCAD Binary DXF"):
            raise DesignFileError(f"{name}: a binary DXF: save it as ASCII DXF")
    sections = Sections(group_pairs(read_text(path), name), name)
    notes = []
    units = sections.header.get("$INSUNITS")
    code = 0
    if units is not None:
        try:
            code = int(float(units[1]))
        except (ValueError, OverflowError):         # "x", "nan"; "-1e400" (infinity)
            raise DesignFileError(f"{name}: line {units[2]}: $INSUNITS = {units[1]!r} is not a whole number") from None
    if code and code not in UNITS:
        raise DesignFileError(f"{name}: $INSUNITS = {code}: units this reader does not take (mm, cm, m, inches, feet ...)")
    if code and scale is not None:
        raise DesignFileError(f"{name}: the file says its units ({UNIT_NAMES[code]}): a scale is only for a file "
                              "without units")
    if scale is not None and not (math.isfinite(scale) and scale > 0):
        raise DesignFileError(f"{name}: scale {scale!r} must be a positive number of mm per drawing unit")
    if not code:
        notes.append(f"{name}: no units in the file: read as {1.0 if scale is None else scale:g} mm per drawing unit")
    reader = Reader(name, sections, tolerance, UNITS[code] if code else (1.0 if scale is None else scale))
    reader.draw(sections.entities, np.eye(3), None, ())
    shapes, joined_notes = joined_by_layer(reader.shapes, join_tolerance)
    notes += reader.notes()
    if not shapes:
        raise DesignFileError(f"{name}: no lines or curves to cut ({'; '.join(notes) or 'an empty drawing'})")
    return Design(path, tuple(shapes), tuple(notes + joined_notes))
