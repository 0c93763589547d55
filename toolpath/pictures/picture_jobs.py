"""What each batch picture shows (drawn by :mod:`.picture`): one look for every workflow.

* toolpaths: cuts, plunges, links and rapids in their own colours (:data:`.legend.ROLE_COLOURS`), over the
  part's solids and the stock's outline, with a legend, the stock's size and the deepest cut;
* the simulated stock: shaded, coloured by depth over the job's own depth range (0 .. deepest cut),
  with a colour bar;
* sheet patterns: filled faces, dashed bend lines, the cut contour, each pattern's size;
* on the toolpaths and the simulated stock, what a workflow leaves uncut (``marks``): a red square
  round each place with its label, and "LEFT UNCUT" in the legend, so nothing is skipped unseen.

Every picture frames all it draws (the part's corners, the stock and every toolpath point).
"""
from __future__ import annotations

import numpy as np

from . import picture_font as font
from .legend import CUT, LINK, PLUNGE, RAPID_ROLE, ROLE_COLOURS, ROLE_LABELS, ROLES, UNCUT_COLOUR
from .picture import INK, Picture, PictureError, View
from ..ir.program import ARC_CCW, ARC_CW, RAPID, arc_sweep, walked

CAPTION_INK = (170, 30, 20)        # what was not cut, in red under the header
STOCK_COLOUR = (222, 196, 150)
PART_COLOUR = (178, 186, 198)
SIDE_COLOUR = (200, 184, 150)
GHOST_COLOUR = (236, 228, 212)
OUTLINE_COLOUR = (120, 110, 95)
DEPTH_RAMP = np.array([(236, 218, 178), (232, 160, 70), (190, 70, 40), (95, 25, 70), (30, 20, 90)], float)
PATTERN_COLOURS = ((150, 190, 235), (160, 215, 170), (240, 200, 140), (210, 175, 230))
BEND_COLOUR, CONTOUR_COLOUR = (40, 40, 160), (230, 70, 20)
HEADER, LEGEND, SCALE = 58, 44, 2
MARK_PX = 12           # half the side of the square round a place left uncut
STEEP = 0.25           # a plunge: at most this much sideways per mm along the tool axis
ARC_STEP = np.radians(6.0)


# ----- moves ------------------------------------------------------------------------------
def part_points(op) -> np.ndarray:
    """Start and end points of every move of ``op`` in part coordinates (n + 1, 3): X-Z-C and
    C-X-Z moves turned back by C."""
    from ..ir.kinematics import machine_to_part

    if "c" in (op.rotary or {}):
        c = np.asarray(op.rotary["c"], float)
        start = machine_to_part(op.start, c[:1])
        return np.vstack([start, machine_to_part(op.xyz, c)])
    return np.vstack([np.asarray(op.start, float)[None, :], op.xyz])


def stock_depth(stock, points) -> np.ndarray:
    """How far (n, 3) points lie inside the stock, below its nearest machined face (negative:
    outside).  A box is machined from its top; a bar from its end face and its outside."""
    points = np.asarray(points, float).reshape(-1, 3)
    depth = stock.top - points[:, 2]
    if hasattr(stock, "radius"):
        return np.minimum(depth, stock.radius - np.hypot(points[:, 0], points[:, 1]))
    outside = np.maximum.reduce([stock.x0 - points[:, 0], points[:, 0] - stock.x1,
                                 stock.y0 - points[:, 1], points[:, 1] - stock.y1])
    return np.where(outside > 0, -outside, depth)


def move_roles(op, stock) -> np.ndarray:
    """Per move of ``op``: RAPID_ROLE, PLUNGE (a feed move into the stock along the tool's axis),
    LINK (a feed move the planner marked as a link (:attr:`Operation.links`), one with both ends and
    its middle outside the stock, or a feed retract along the axis) or CUT."""
    points = part_points(op)
    a, b = points[:-1], points[1:]
    step = b - a
    axis = np.tile([0.0, 0.0, 1.0], (len(op), 1))
    if getattr(op, "direction", "") == "radial":       # a turret tool pointing at the bar's axis
        r = np.hypot(a[:, 0], a[:, 1])
        axis = np.column_stack([a[:, 0], a[:, 1], np.zeros(len(op))]) / np.where(r > 1e-9, r, 1.0)[:, None]
    along = np.einsum("ij,ij->i", step, axis)
    sideways = np.linalg.norm(step - along[:, None] * axis, axis=1)
    air = (stock_depth(stock, a) <= 1e-6) & (stock_depth(stock, b) <= 1e-6) & \
        (stock_depth(stock, (a + b) / 2) <= 1e-6)
    arcs = (op.kind == ARC_CW) | (op.kind == ARC_CCW)
    roles = np.full(len(op), CUT)
    roles[(along < -1e-9) & (sideways <= STEEP * -along) & ~arcs] = PLUNGE
    roles[air | ((along > 1e-9) & (sideways <= STEEP * along) & ~arcs)] = LINK
    if getattr(op, "links", None) is not None:
        roles[op.links] = LINK
    roles[op.kind == RAPID] = RAPID_ROLE
    return roles


def toolpath_segments(op, stock) -> tuple:
    """Straight pieces of ``op`` in part coordinates: (a (m, 3), b (m, 3), role (m,)); arcs are
    split into chords of at most 6 degrees."""
    points = part_points(op)
    roles = move_roles(op, stock)
    a, b = points[:-1], points[1:]
    arcs = np.flatnonzero((op.kind == ARC_CW) | (op.kind == ARC_CCW))
    if not len(arcs) or "c" in (op.rotary or {}):
        return a, b, roles
    centre = op.center[arcs]
    sweep = arc_sweep(a[arcs], b[arcs], centre, op.kind[arcs] == ARC_CW)
    count = np.maximum(np.ceil(np.abs(sweep) / ARC_STEP).astype(np.int64), 1)
    owner = np.repeat(np.arange(len(arcs)), count)
    index = np.arange(len(owner)) - (np.cumsum(count) - count)[owner]
    angle0 = np.arctan2(a[arcs, 1] - centre[:, 1], a[arcs, 0] - centre[:, 0])
    radius = np.hypot(a[arcs, 0] - centre[:, 0], a[arcs, 1] - centre[:, 1])

    def at(fraction):
        t = fraction
        angle = angle0[owner] + sweep[owner] * t
        return np.column_stack([centre[owner, 0] + radius[owner] * np.cos(angle),
                                centre[owner, 1] + radius[owner] * np.sin(angle),
                                a[arcs, 2][owner] + (b[arcs, 2] - a[arcs, 2])[owner] * t])
    arc_a, arc_b = at(index / count[owner]), at((index + 1) / count[owner])
    straight = np.ones(len(op), bool)
    straight[arcs] = False
    return (np.vstack([a[straight], arc_a]), np.vstack([b[straight], arc_b]),
            np.concatenate([roles[straight], roles[arcs][owner]]))


def role_paths(op, stock) -> list:
    """The path of ``op`` in part coordinates, cut where its move kind (:func:`move_roles`)
    changes: [(role, points (k, 3))] in the path's order, each run starting where the one
    before it ended; 3-axis arcs walked in chords of at most 6 degrees (for drawing them)."""
    roles = move_roles(op, stock)
    if op.rotary:
        points, owner = part_points(op), np.arange(len(op))
    else:
        _, points = walked(op, ARC_STEP)
        count = np.ones(len(op), np.int64)       # the pieces walked() makes of each move
        arcs = np.flatnonzero((op.kind == ARC_CW) | (op.kind == ARC_CCW))
        sweep = arc_sweep(op.start_points()[arcs, :2], op.xyz[arcs, :2], op.center[arcs, :2], op.kind[arcs] == ARC_CW)
        count[arcs] = np.maximum(np.ceil(np.abs(sweep) / ARC_STEP).astype(np.int64), 1)
        owner = np.repeat(np.arange(len(op)), count)
    piece_roles = roles[owner]
    change = (np.flatnonzero(piece_roles[1:] != piece_roles[:-1]) + 1).tolist()
    return [(int(piece_roles[start]), points[start:end + 1])
            for start, end in zip([0] + change, change + [len(piece_roles)]) if end > start]


def deepest_cut(operations, stock) -> float:
    """The deepest point any feed move reaches below the stock's surface (mm, 0 if none)."""
    deepest = 0.0
    for op in operations:
        points = part_points(op)[1:][op.kind != RAPID]
        if len(points):
            deepest = max(deepest, float(stock_depth(stock, points).max()))
    return deepest


# ----- labels -----------------------------------------------------------------------------
def mm(value: float) -> str:
    return f"{value:.2f}".rstrip("0").rstrip(".") if abs(value) < 1000 else f"{value:.0f}"


def stock_label(stock) -> str:
    if hasattr(stock, "radius"):
        return f"STOCK BAR DIA {mm(2 * stock.radius)} x {mm(stock.top - stock.bottom)} MM"
    return f"STOCK {mm(stock.x1 - stock.x0)} x {mm(stock.y1 - stock.y0)} x {mm(stock.z1 - stock.z0)} MM"


def stock_corners(stock) -> np.ndarray:
    if hasattr(stock, "radius"):
        r = stock.radius
        x0, y0, x1, y1, z0, z1 = -r, -r, r, r, stock.bottom, stock.top
    else:
        x0, y0, z0, x1, y1, z1 = stock.x0, stock.y0, stock.z0, stock.x1, stock.y1, stock.z1
    return np.array([(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)], float)


def stock_mesh(stock) -> tuple:
    """(vertices, triangles) of the stock: a box, or a bar as a 48-sided prism."""
    if hasattr(stock, "radius"):
        n = 48
        angle = 2 * np.pi * np.arange(n) / n
        ring = np.column_stack([stock.radius * np.cos(angle), stock.radius * np.sin(angle)])
        vertices = np.vstack([np.column_stack([ring, np.full(n, z)]) for z in (stock.bottom, stock.top)]
                             + [[(0, 0, stock.bottom), (0, 0, stock.top)]])
        k, k1 = np.arange(n), (np.arange(n) + 1) % n
        faces = np.vstack([np.column_stack([k, k1, n + k1]), np.column_stack([k, n + k1, n + k]),
                           np.column_stack([np.full(n, 2 * n), k1, k]), np.column_stack([np.full(n, 2 * n + 1), n + k, n + k1])])
        return vertices, faces
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6),
             (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    return stock_corners(stock), np.array(faces)


def stock_outline(picture: Picture, view: View, stock):
    """The stock's edges, thin: a box's 12 edges, a bar's two end circles and two side lines."""
    if hasattr(stock, "radius"):
        angle = np.linspace(0, 2 * np.pi, 97)
        ring = np.column_stack([stock.radius * np.cos(angle), stock.radius * np.sin(angle), np.zeros(97)])
        for z in (stock.bottom, stock.top):
            picture.polyline(view, ring + [0, 0, z], OUTLINE_COLOUR, 1)
        for x in (-stock.radius, stock.radius):
            picture.segments(view, [(x, 0, stock.bottom)], [(x, 0, stock.top)], OUTLINE_COLOUR, 1)
        return
    c = stock_corners(stock)
    edges = [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (1, 3), (4, 6), (5, 7), (0, 4), (1, 5), (2, 6), (3, 7)]
    picture.segments(view, c[[e[0] for e in edges]], c[[e[1] for e in edges]], OUTLINE_COLOUR, 1)


def _header(picture: Picture, title: str, lines: list):
    picture.text(12, 10, title, INK, SCALE + 1)
    left = 12
    for line in lines:
        left += picture.text(left, 40, line, INK, SCALE) + 36


def _caption(picture: Picture, text: str):
    """One line of text under the header, shortened with '...' to the picture's width."""
    text = "".join(ch if ch.upper() in font.GLYPHS else " " for ch in text.upper())
    while len(text) > 3 and text_width(text) > picture.width - 24:
        text = text[:-4].rstrip() + "..."
    picture.text(12, HEADER + 4, text, CAPTION_INK, SCALE)


def _legend(picture: Picture, entries: list):
    """Swatches and labels along the bottom: (label, colour, dashed)."""
    top = picture.height - LEGEND + 10
    picture.box(0, picture.height - LEGEND, picture.width, picture.height - LEGEND + 1, (200, 200, 196))
    left = 12
    for label, colour, dashed in entries:
        for k in range(0, 28, 8 if dashed else 28):
            picture.box(left + k, top + 5, left + k + (5 if dashed else 28), top + 10, colour)
        left += 36
        left += picture.text(left, top, label, INK, SCALE) + 28


def mark_uncut(picture: Picture, view: View, marks) -> None:
    """A square of :data:`UNCUT_COLOUR` round each place of ``marks`` = [(x, y, z, label)] (work
    mm), its label beside it."""
    for x, y, z, label in marks:
        px, py, _ = view.project([(x, y, z)])
        cx, cy, r = int(round(px[0])), int(round(py[0])), MARK_PX
        for left, top, right, bottom in ((cx - r, cy - r, cx + r, cy - r + 3), (cx - r, cy + r - 3, cx + r, cy + r),
                                         (cx - r, cy - r, cx - r + 3, cy + r), (cx + r - 3, cy - r, cx + r, cy + r)):
            picture.box(left, top, right, bottom, UNCUT_COLOUR)
        picture.text(cx + r + 4, cy - 7, label, UNCUT_COLOUR, SCALE)


# ----- pictures ---------------------------------------------------------------------------
def toolpath_picture(operations, stock, solids=(), title: str = "", size=(1200, 800), tilt_deg: float = 35.0,
                     caption: str = "", marks=(), highlights=()):
    """The toolpaths over the part: ``solids`` = [(vertices (k, 3), faces (f, 3), rgb), ...] in
    the same work mm as the moves; ``caption``: a line of text drawn over the picture's top edge
    below the header (e.g. what was not cut), cut short with '...' where the picture ends;
    ``marks``: places left uncut, [(x, y, z, label)]; ``highlights`` = [(vertices, faces, rgb,
    label), ...]: faces drawn over the solids (seen through them, so a cross hole inside the part
    shows) and named in the legend, such as the faces no tool reaches."""
    from ..simulate.stock import as_stock

    stock = as_stock(stock)
    pieces = [toolpath_segments(op, stock) for op in operations]
    frame = [stock_corners(stock)] + [v for v, _, _ in solids] + [p for a, b, _ in pieces for p in (a, b)]
    picture = Picture(*size)
    view = View(np.vstack(frame), (0, HEADER, picture.width, picture.height - LEGEND), tilt_deg)
    picture.triangles(view, *stock_mesh(stock), STOCK_COLOUR if not solids else GHOST_COLOUR)
    if solids:
        picture.depth[:] = -np.inf        # the part inside the stock is drawn over the stock
    for vertices, faces, colour in solids:
        picture.triangles(view, vertices, faces, colour)
    for vertices, faces, colour, _ in highlights:
        solid_depth = picture.depth.copy()
        picture.depth[:] = -np.inf        # over the part: what lies inside it shows
        picture.triangles(view, vertices, faces, colour)
        np.maximum(picture.depth, solid_depth, out=picture.depth)   # the part still hides the paths behind it
    stock_outline(picture, view, stock)
    counts = {}
    thin = sum(len(a) for a, _, _ in pieces) > 20_000      # dense paths: 1 px lines, the part shows through
    for role in (RAPID_ROLE, LINK, CUT, PLUNGE):
        name = ROLES[role]
        a = np.vstack([a[r == role] for a, _, r in pieces]) if pieces else np.zeros((0, 3))
        b = np.vstack([b[r == role] for _, b, r in pieces]) if pieces else np.zeros((0, 3))
        counts[name] = len(a)
        picture.segments(view, a, b, ROLE_COLOURS[name], (3 if role == PLUNGE else 2) - thin,
                         dash=6.0 if role == RAPID_ROLE else 0.0)
    deepest = deepest_cut(operations, stock)
    mark_uncut(picture, view, marks)
    _header(picture, title, [stock_label(stock), f"DEEPEST CUT {mm(deepest)} MM"])
    if caption:
        _caption(picture, caption)
    _legend(picture, [(ROLE_LABELS[name], ROLE_COLOURS[name], name == "rapid") for name in ROLES]
            + ([(f"LEFT UNCUT ({len(marks)})", UNCUT_COLOUR, False)] if len(marks) else [])
            + [(label, colour, False) for _, _, colour, label in highlights])
    picture.deepest = deepest
    picture.view = view
    return picture


def surface_depth(result, vertices) -> tuple:
    """(depth of each vertex below the stock's surface, the deepest cut): the deepest cut leaves
    out the stock's bottom face, which lies a whole thickness down without being cut."""
    vertices = np.asarray(vertices, float).reshape(-1, 3)
    depth = result.depth_at(vertices)
    cut = vertices[:, 2] > result.stock.bottom + 1e-6
    deepest = float(depth[cut].max()) if cut.any() else 0.0
    return np.minimum(depth, deepest), deepest


def depth_colours(depth, deepest: float) -> np.ndarray:
    """RGB of each depth on :data:`DEPTH_RAMP`, 0 (uncut) .. ``deepest``."""
    t = np.clip(np.asarray(depth, float) / max(deepest, 1e-9), 0, 1) * (len(DEPTH_RAMP) - 1)
    k = np.minimum(np.floor(t).astype(np.int64), len(DEPTH_RAMP) - 2)
    f = (t - k)[:, None]
    return DEPTH_RAMP[k] * (1 - f) + DEPTH_RAMP[k + 1] * f


def simulation_picture(result, title: str = "", size=(1200, 800), tilt_deg: float = 35.0, max_cells: int = 160_000,
                       mesh=None, marks=()):
    """The simulated stock, shaded and coloured by depth over 0 .. its deepest cut; ``mesh``:
    its (vertices, faces) when the caller has them already (else ``result.surface(max_cells)``);
    ``marks``: places left uncut, [(x, y, z, label)]."""
    vertices, faces = result.surface(max_cells) if mesh is None else mesh
    vertices = np.asarray(vertices, float)
    faces = np.asarray(faces, np.int64)
    depth, deepest = surface_depth(result, vertices)
    f0, f1, f2 = faces[:, 0], faces[:, 1], faces[:, 2]
    colours = depth_colours((depth[f0] + depth[f1] + depth[f2]) / 3, deepest)      # each face's mean depth
    # The stock's sides and bottom (faces reaching its bottom face) are uncut material.
    low = vertices[:, 2] <= result.stock.bottom + 1e-6
    colours[low[f0] | low[f1] | low[f2]] = SIDE_COLOUR
    picture = Picture(*size)
    view = View(np.vstack([vertices, stock_corners(result.stock)]),
                (0, HEADER, picture.width, picture.height - LEGEND), tilt_deg)
    picture.triangles(view, vertices, faces, colours)
    mark_uncut(picture, view, marks)
    _header(picture, title, [stock_label(result.stock), f"DEEPEST CUT {mm(deepest)} MM",
                             f"REMOVED {result.removed_volume_mm3:.0f} MM3"]
            + ([f"LEFT UNCUT: {len(marks)} (RED)"] if len(marks) else []))
    top = picture.height - LEGEND + 10
    picture.box(0, picture.height - LEGEND, picture.width, picture.height - LEGEND + 1, (200, 200, 196))
    left = 12 + picture.text(12, top, "DEPTH 0", INK, SCALE) + 10
    ramp = depth_colours(np.linspace(0, deepest, 240), deepest)
    for k, colour in enumerate(ramp):
        picture.box(left + k, top - 2, left + k + 1, top + 16, colour)
    picture.text(left + 250, top, f"{mm(deepest)} MM", INK, SCALE)
    picture.deepest = deepest
    picture.view = view
    return picture


def sheet_picture(patterns, title: str = "", size=(1200, 800)):
    """Flat patterns seen from above: ``patterns`` = [dict(outline=(k, 2), bends=[(a, b) 2-D
    pairs], contour=(m, 2) or None, name=str)], already placed side by side (mm)."""
    if not patterns:
        raise PictureError("no pattern to draw")
    frame = [np.column_stack([p["outline"], np.zeros(len(p["outline"]))]) for p in patterns]
    frame += [np.column_stack([p["contour"], np.zeros(len(p["contour"]))]) for p in patterns
              if p.get("contour") is not None]
    picture = Picture(*size)
    view = View(np.vstack(frame), (0, HEADER, picture.width, picture.height - LEGEND), 0.0)
    sizes = []
    for index, pattern in enumerate(patterns):
        outline = np.asarray(pattern["outline"], float)
        picture.polygon(view, outline, PATTERN_COLOURS[index % len(PATTERN_COLOURS)])
        picture.polyline(view, np.column_stack([outline, np.zeros(len(outline))]), INK, 1, closed=True)
        for a, b in pattern.get("bends", ()):
            picture.segments(view, [(a[0], a[1], 0)], [(b[0], b[1], 0)], BEND_COLOUR, 2, dash=7.0)
        contour = pattern.get("contour")
        if contour is not None:
            contour = np.asarray(contour, float)
            picture.polyline(view, np.column_stack([contour, np.zeros(len(contour))]), CONTOUR_COLOUR, 2,
                             closed=True)
        extent = np.ptp(outline, axis=0)
        sizes.append(f"{pattern.get('name', index + 1)}: {mm(extent[0])} x {mm(extent[1])} MM")
    if len(sizes) > 2:
        every = np.vstack([p["outline"] for p in patterns])
        extent = np.ptp(every, axis=0)
        sizes = [f"{len(sizes)} PATTERNS, {mm(extent[0])} x {mm(extent[1])} MM OVERALL"]
    _header(picture, title, sizes)
    entries = [("FLAT PATTERN", PATTERN_COLOURS[0], False), ("CUT CONTOUR (PUNCH PATH)", CONTOUR_COLOUR, False)]
    if any(len(p.get("bends", ())) for p in patterns):
        entries.insert(1, ("BEND LINE (DASHED)", BEND_COLOUR, True))
    _legend(picture, entries)
    picture.view = view
    return picture


def text_width(text: str) -> int:
    return font.text_size(text, SCALE)[0]
