"""W5 sheet-metal unfolding: twisted quads, strips of quads, segmented pipe elbows, CADKEY .CDL input.

Triangulation development (the seed paper's method): a surface is cut into triangles whose 3-D edge
lengths are known; the triangles are laid flat one after another, each new vertex being the
intersection of two circles centred on the ends of the edge already laid, with the other two edge
lengths as radii.  The flat pattern is therefore an exact isometry of the triangulated surface; how
well it matches the real (curved) sheet depends on the number of divisions.

Conventions used throughout:
  * A *strip* is two rails (polylines) ``a`` and ``b`` of equal point count n+1; rung k joins a[k] and
    b[k]; quad k is a[k], a[k+1], b[k+1], b[k], split by one diagonal into two triangles.
  * Rung 0 is laid on the +Y axis (a[0] at the origin, b[0] above it) and the strip grows towards +X.
    Every flat triangle is counter-clockwise, so each new triangle lies on the far side of the edge
    it shares with the one before (no folding back, no flips).  The pattern is seen from the side the
    3-D normal (a[1] - a[0]) x (b[0] - a[0]) points to.
  * 2-D outlines are (k, 2) arrays, implicitly closed (the last point joins the first), CCW.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from ...ir.errors import InputError

# Points closer than this (mm) are the same point (rails that stand still, CDL line ends).
POINT_TOL = 1e-9
# The seed: "LINE, start X Y Z, end X Y Z, colour, line type, ... 14 data in all" counting the word;
# its Table 1 has 13 numbers after LINE.  14 numbers after the word (as the spec words it) also pass.
CDL_NUMBERS_PER_LINE = (13, 14)
DIRECTIONS = ("vertical", "horizontal")
DIAGONALS = ("a_next", "b_next", "shorter")


class UnfoldError(InputError):
    """Bad unfolding input: unreadable CDL, degenerate corners, impossible elbow, bad counts."""


# --------------------------------------------------------------------------------------------
# Validation helpers


MAX_DIVISIONS = 1000        # more strips than this are finer than any sheet can be bent or punched


def _check_count(value, what: str, minimum: int, maximum: int = MAX_DIVISIONS) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise UnfoldError(f"{what} must be an integer, got {value!r}")
    if value < minimum:
        raise UnfoldError(f"{what} must be at least {minimum}, got {value}")
    if value > maximum:
        raise UnfoldError(f"{what} must be from {minimum} to {maximum}, got {value}")
    return int(value)


def _check_positive(value, what: str, allow_zero: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise UnfoldError(f"{what} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        need = "zero or more" if allow_zero else "more than zero"
        raise UnfoldError(f"{what} must be a finite number {need}, got {value!r}")
    return v


def _check_corners(corners) -> np.ndarray:
    pts = np.asarray(corners, dtype=float)
    if pts.shape != (4, 3):
        raise UnfoldError(f"a twisted quad needs 4 corners (x, y, z), got an array of shape {pts.shape}")
    if not np.all(np.isfinite(pts)):
        raise UnfoldError("corner coordinates must be finite (no NaN or infinity)")
    for i in range(4):
        for j in range(i + 1, 4):
            if np.linalg.norm(pts[i] - pts[j]) <= POINT_TOL:
                kind = "edge" if (j - i) in (1, 3) else "diagonal"
                raise UnfoldError(f"corners P{i + 1} and P{j + 1} coincide (zero-length {kind})")
    # Three corners on one straight line make a triangle, not a quad: two edges fold onto one line.
    scale = max(np.ptp(pts, axis=0).max(), POINT_TOL)
    for i in range(4):
        a, b, c = pts[i - 1], pts[i], pts[(i + 1) % 4]
        if np.linalg.norm(np.cross(b - a, c - b)) <= 1e-9 * scale * scale:
            before, here, after = (i - 1) % 4 + 1, i + 1, (i + 1) % 4 + 1
            raise UnfoldError(f"corners P{before}, P{here} and P{after} are collinear: the edges meeting at "
                              f"P{here} lie on one straight line")
    # Opposite edges that meet make a bow tie, not a sheet: the corners are not in order round it.
    for i, j in ((0, 2), (1, 3)):
        gap = _segment_gap(pts[i], pts[(i + 1) % 4], pts[j], pts[(j + 1) % 4])
        if gap <= 1e-6 * scale:
            raise UnfoldError(f"edges P{i + 1}-P{i + 2} and P{j + 1}-P{(j + 1) % 4 + 1} cross: give the corners "
                              f"in order round the quad")
    return pts


def _segment_gap(p0, p1, q0, q1) -> float:
    """The shortest distance between the segments p0-p1 and q0-q1 in space (the closest points
    of the two lines, each clamped to its segment, the other then re-projected)."""
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a, e, f = float(d1 @ d1), float(d2 @ d2), float(d2 @ r)
    c, b = float(d1 @ r), float(d1 @ d2)
    denom = a * e - b * b
    s = min(max((b * f - c * e) / denom, 0.0), 1.0) if denom > 1e-12 * a * e else 0.0
    t = (b * s + f) / e
    if t < 0.0 or t > 1.0:
        t = min(max(t, 0.0), 1.0)
        s = min(max((b * t - c) / a, 0.0), 1.0)
    return float(np.linalg.norm(p0 + d1 * s - (q0 + d2 * t)))


def _check_rail(rail, what: str) -> np.ndarray:
    pts = np.asarray(rail, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 3 or len(pts) < 2:
        raise UnfoldError(f"{what} must be an (n+1, 3) array with n >= 1, got shape {pts.shape}")
    if not np.all(np.isfinite(pts)):
        raise UnfoldError(f"{what} has a non-finite coordinate (NaN or infinity)")
    return pts


def _distance(p, q) -> float:
    return float(np.linalg.norm(np.asarray(p) - np.asarray(q)))


def signed_area(outline) -> float:
    """Shoelace area of an implicitly closed 2-D polygon; > 0 when counter-clockwise."""
    pts = np.asarray(outline, dtype=float)
    x, y = pts[:, 0], pts[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


# --------------------------------------------------------------------------------------------
# CADKEY .CDL reader

_CDL_TOKEN = re.compile(r"[^\s,]+")


def read_cdl(text: str, tol: float = 1e-6) -> np.ndarray:
    """Corners P1..P4 of the twisted quad in a CADKEY .CDL intermediate file, as a (4, 3) array.

    A record is a word followed by numbers, separated by commas and/or white space, and may wrap over
    several lines; it ends where the next word begins.  ``LINE x1, y1, z1, x2, y2, z2, colour, type,
    ...`` is 14 data items with the word (13 numbers, as in the seed's Table 1; 14 numbers are
    accepted too); records with other words are skipped.  Exactly four LINEs must form one
    closed loop (each end meets one other LINE's start or end within ``tol`` mm, in any order and
    direction).  P1, P2 are the start and end of the first LINE in the file, P3, P4 follow round the
    loop.  Errors name the line number in the file.
    """
    tol = _check_positive(tol, "CDL joint tolerance")
    records = []  # [word, line number, numbers]
    # lines end at LF, CR LF or CR: str.splitlines also broke at form feeds and U+0085 (a byte of
    # latin-1 text), so the line numbers of the messages ran ahead of the file's
    for line_no, line in enumerate(re.split(r"\r\n|\r|\n", text), start=1):
        for token in _CDL_TOKEN.findall(line):
            try:
                value = float(token)
            except ValueError:
                records.append([token.upper(), line_no, []])
                continue
            if not records:
                raise UnfoldError(f"CDL line {line_no}: number {token!r} before any record word")
            records[-1][2].append(value)

    lines = []  # (line number, start, end)
    for word, line_no, numbers in records:
        if word != "LINE":
            continue
        if len(numbers) not in CDL_NUMBERS_PER_LINE:
            raise UnfoldError(f"CDL line {line_no}: LINE record has {len(numbers)} numbers, expected 13 "
                              f"or 14 (x1, y1, z1, x2, y2, z2, colour, type, ...)")
        start, end = np.array(numbers[0:3]), np.array(numbers[3:6])
        if not (np.all(np.isfinite(start)) and np.all(np.isfinite(end))):
            raise UnfoldError(f"CDL line {line_no}: LINE has a non-finite coordinate")
        if _distance(start, end) <= tol:
            raise UnfoldError(f"CDL line {line_no}: LINE has zero length")
        lines.append((line_no, start, end))
    if len(lines) != 4:
        where = ", ".join(str(ln) for ln, _, _ in lines) or "none"
        raise UnfoldError(f"CDL: a twisted quad needs exactly 4 LINE records, found {len(lines)} "
                          f"(at lines: {where})")

    line_no, start, point = lines[0]
    corners = [start, point]
    unused = [1, 2, 3]
    for _ in range(3):
        joins = [j for j in unused
                 if _distance(lines[j][1], point) <= tol or _distance(lines[j][2], point) <= tol]
        if len(joins) != 1:
            raise UnfoldError(
                f"CDL line {line_no}: the LINE ends at {tuple(np.round(point, 6))} where "
                f"{len(joins)} other LINEs begin or end (a closed loop needs exactly 1)")
        j = joins[0]
        unused.remove(j)
        line_no, s, e = lines[j]
        point = e if _distance(s, corners[-1]) <= tol else s
        corners.append(point)
    if _distance(corners[-1], corners[0]) > tol:
        raise UnfoldError(f"CDL line {line_no}: the four LINEs do not close: the loop ends at "
                          f"{tuple(np.round(corners[-1], 6))}, not at P1 {tuple(np.round(corners[0], 6))}")
    return _check_corners(np.array(corners[:4]))


# --------------------------------------------------------------------------------------------
# Strip of quads -> flat pattern


@dataclass(frozen=True)
class FlatPattern:
    """A triangulated surface and its development.

    ``vertices_3d[i]`` and ``vertices_2d[i]`` are the same point of the sheet; ``triangles`` index both
    (CCW in 2-D).  ``outline_index`` lists the vertices of the flat outline in order; ``outline`` is
    ``vertices_2d[outline_index]`` (CCW, implicitly closed, no repeated points).
    """

    vertices_3d: np.ndarray
    vertices_2d: np.ndarray
    triangles: np.ndarray
    outline_index: np.ndarray

    @property
    def outline(self) -> np.ndarray:
        return self.vertices_2d[self.outline_index]

    @property
    def outline_3d(self) -> np.ndarray:
        return self.vertices_3d[self.outline_index]

    def bend_lines(self) -> np.ndarray:
        """Flat (k, 2, 2) segments of the inner triangle edges: where the sheet is bent."""
        count = {}
        for tri in self.triangles:
            for i in range(3):
                edge = tuple(sorted((int(tri[i]), int(tri[(i + 1) % 3]))))
                count[edge] = count.get(edge, 0) + 1
        inner = [e for e, c in count.items() if c == 2]
        if not inner:
            return np.zeros((0, 2, 2))
        return self.vertices_2d[np.array(inner)]


def _third_vertex(p: np.ndarray, q: np.ndarray, dist_p: float, dist_q: float) -> np.ndarray:
    """Point at ``dist_p`` from p and ``dist_q`` from q, on the LEFT of the directed line p -> q.

    The intersection of the circles (X-px)^2+(Y-py)^2 = dist_p^2 and (X-qx)^2+(Y-qy)^2 = dist_q^2
    (the seed's equations 2 and 3); always taking the left one keeps every triangle CCW.
    """
    u = q - p
    d = math.hypot(u[0], u[1])
    if d <= POINT_TOL:
        raise UnfoldError("cannot lay a triangle on a zero-length edge (two strip points coincide)")
    u = u / d
    along = (dist_p * dist_p - dist_q * dist_q + d * d) / (2.0 * d)
    h2 = dist_p * dist_p - along * along
    scale = max(dist_p, dist_q, d)
    if h2 < -1e-9 * scale * scale:
        raise UnfoldError("edge lengths violate the triangle inequality (corrupt strip geometry)")
    h = math.sqrt(max(h2, 0.0))
    return p + along * u + h * np.array([-u[1], u[0]])


def unfold_quad_strip(rail_a, rail_b, diagonal: str = "a_next") -> FlatPattern:
    """Develop the strip of quads between two polylines (each (n+1, 3)) into a flat pattern.

    ``diagonal`` splits quad k: "a_next" joins a[k+1]-b[k], "b_next" joins a[k]-b[k+1], "shorter"
    takes the shorter of the two in 3-D (the better approximation of a curved quad).  A rail may
    stand still (a[k+1] == a[k]): the quad is then one triangle, as in the corner fans of a
    square-to-round transition.  Vertex i < n+1 is a[i], vertex n+1+i is b[i].
    """
    a = _check_rail(rail_a, "rail a")
    b = _check_rail(rail_b, "rail b")
    if a.shape != b.shape:
        raise UnfoldError(f"the two rails need the same number of points, got {len(a)} and {len(b)}")
    if diagonal not in DIAGONALS:
        raise UnfoldError(f"diagonal must be one of {DIAGONALS}, got {diagonal!r}")
    n = len(a) - 1
    nb = n + 1                # vertex index of b[k] is nb + k, of a[k] is k
    for k in range(n + 1):
        if _distance(a[k], b[k]) <= POINT_TOL:
            raise UnfoldError(f"rung {k}: the rails touch (zero-length rung a[{k}]-b[{k}])")

    A = np.zeros((n + 1, 2))
    B = np.zeros((n + 1, 2))
    B[0] = (0.0, _distance(a[0], b[0]))
    triangles = []
    for k in range(n):
        a_moves = _distance(a[k], a[k + 1]) > POINT_TOL
        b_moves = _distance(b[k], b[k + 1]) > POINT_TOL
        if not (a_moves or b_moves):
            raise UnfoldError(f"strip step {k}: both rails stand still (rungs {k} and {k + 1} coincide)")
        diag = diagonal
        if diag == "shorter":
            diag = "a_next" if _distance(a[k + 1], b[k]) <= _distance(a[k], b[k + 1]) else "b_next"
        if diag == "a_next":
            # triangle a[k], a[k+1], b[k] on rung k, then a[k+1], b[k+1], b[k] on the diagonal
            if a_moves:
                A[k + 1] = _third_vertex(B[k], A[k], _distance(a[k + 1], b[k]), _distance(a[k + 1], a[k]))
                triangles.append((k, k + 1, nb + k))
            else:
                A[k + 1] = A[k]
            if b_moves:
                B[k + 1] = _third_vertex(B[k], A[k + 1], _distance(b[k + 1], b[k]),
                                         _distance(b[k + 1], a[k + 1]))
                triangles.append((k + 1, nb + k + 1, nb + k))
            else:
                B[k + 1] = B[k]
        else:
            # triangle a[k], b[k+1], b[k] on rung k, then a[k], a[k+1], b[k+1] on the diagonal
            if b_moves:
                B[k + 1] = _third_vertex(B[k], A[k], _distance(b[k + 1], b[k]), _distance(b[k + 1], a[k]))
                triangles.append((k, nb + k + 1, nb + k))
            else:
                B[k + 1] = B[k]
            if a_moves:
                A[k + 1] = _third_vertex(B[k + 1], A[k], _distance(a[k + 1], b[k + 1]),
                                         _distance(a[k + 1], a[k]))
                triangles.append((k, k + 1, nb + k + 1))
            else:
                A[k + 1] = A[k]

    vertices_2d = np.vstack([A, B])
    ring = list(range(n + 1)) + [nb + k for k in range(n, -1, -1)]
    outline_index = [ring[0]]
    for i in ring[1:]:
        if not np.array_equal(vertices_2d[i], vertices_2d[outline_index[-1]]):
            outline_index.append(i)
    outline_index = np.array(outline_index, dtype=np.int64)
    if signed_area(vertices_2d[outline_index]) <= 0:
        raise UnfoldError("the flat pattern overlaps itself; split the strip into shorter pieces")
    return FlatPattern(np.vstack([a, b]), vertices_2d, np.array(triangles, dtype=np.int64), outline_index)


# --------------------------------------------------------------------------------------------
# Twisted quad (捻れ面)


@dataclass(frozen=True)
class TwistedQuad:
    """The seed's twisted quad: its measurements (the paper's form, Fig. 10) and its flat pattern.

    ``edge_lengths`` are L1 = P1P2, L2 = P2P3, L3 = P3P4, L4 = P4P1; ``diagonals`` P1P3, P2P4;
    ``division_lengths`` = edge_lengths / divisions; ``corner_index`` = pattern vertices of P1..P4.
    """

    corners: np.ndarray
    divisions: int
    direction: str
    edge_lengths: np.ndarray
    diagonals: np.ndarray
    division_lengths: np.ndarray
    pattern: FlatPattern
    corner_index: np.ndarray


def divide_edge(p, q, divisions: int) -> np.ndarray:
    """N equal parts of segment p-q: (N+1, 3) points, p first (the seed's P1,i formula)."""
    t = np.arange(divisions + 1, dtype=float)[:, None] / divisions
    return np.asarray(p, float) + (np.asarray(q, float) - np.asarray(p, float)) * t


def twisted_quad_rails(corners, divisions: int, direction: str):
    """The two rails, diagonal rule and corner vertex indices of the paper's TR or YR strips.

    "vertical" (縦, TR1..TRn): the rungs join division points of L2 and L4, so the strips are stacked
    from L1 (TR1, the reference edge laid first) to L3 (TRn).  Rails: a = L2 (P2 -> P3),
    b = L4 reversed (P1 -> P4); diagonal P2,i - P4,n+1-i as in TRT1,1 = P1,1-P2,1-P4,n ("b_next").
    "horizontal" (横, YR1..YRn): the rungs join division points of L1 and L3, stacked from L4 (YR1,
    reference) to L2 (YRn).  Rails: a = L1 (P1 -> P2), b = L3 reversed (P4 -> P3); diagonal P4 - P1,2
    and so on, the same rule ("a_next").  Both are seen from the side where P1 P2 P3 P4 run CCW.
    """
    p1, p2, p3, p4 = corners
    n = divisions
    if direction == "vertical":
        return divide_edge(p2, p3, n), divide_edge(p1, p4, n), "b_next", np.array([n + 1, 0, n, 2 * n + 1])
    if direction == "horizontal":
        return divide_edge(p1, p2, n), divide_edge(p4, p3, n), "a_next", np.array([0, n, 2 * n + 1, n + 1])
    raise UnfoldError(f"direction must be one of {DIRECTIONS}, got {direction!r}")


def unfold_twisted_quad(corners, divisions: int, direction: str = "horizontal") -> TwistedQuad:
    """Develop the quad P1..P4 (four straight edges, corners not coplanar) by the seed's method.

    Every edge is divided into ``divisions`` equal parts, opposite division points are joined into
    ``divisions`` strip quads (see :func:`twisted_quad_rails` for "vertical" / "horizontal"), each quad
    is split by a diagonal, and the 2 * divisions triangles are laid flat one after another.
    """
    pts = _check_corners(corners)
    n = _check_count(divisions, "number of divisions N", 1)
    if direction not in DIRECTIONS:
        raise UnfoldError(f"direction must be one of {DIRECTIONS}, got {direction!r}")
    rail_a, rail_b, diagonal, corner_index = twisted_quad_rails(pts, n, direction)
    pattern = unfold_quad_strip(rail_a, rail_b, diagonal)
    edges = np.array([_distance(pts[i], pts[(i + 1) % 4]) for i in range(4)])
    diagonals = np.array([_distance(pts[0], pts[2]), _distance(pts[1], pts[3])])
    return TwistedQuad(pts, n, direction, edges, diagonals, edges / n, pattern, corner_index)


# --------------------------------------------------------------------------------------------
# Square-to-round transition (beyond the paper; the classic triangulation job)


def square_to_round_rails(side: float, diameter: float, height: float, fan_divisions: int = 4,
                          centre_offset=(0.0, 0.0)):
    """Rails (square, round) of a square-to-round transition, for :func:`unfold_quad_strip`.

    The square (side ``side``, centred on the origin at z = 0) and the circle (``diameter``, centred on
    ``centre_offset`` at z = ``height``).  The classic triangulation: each square corner fans to a
    quarter of the circle in ``fan_divisions`` triangles, each square side makes one triangle with
    the circle point between two fans.  The seam is the middle of the +X side, so both rails start
    and end at the same 3-D points.  In every step exactly one rail moves.
    """
    side = _check_positive(side, "square side")
    diameter = _check_positive(diameter, "round diameter")
    height = _check_positive(height, "transition height")
    m = _check_count(fan_divisions, "fan divisions", 1)
    cx, cy = (float(v) for v in centre_offset)
    if not (math.isfinite(cx) and math.isfinite(cy)):
        raise UnfoldError("round centre offset must be finite")
    h = side / 2.0

    def circle(deg):
        t = math.radians(deg)
        return (cx + diameter / 2.0 * math.cos(t), cy + diameter / 2.0 * math.sin(t), height)

    corners = [(h, h, 0.0), (-h, h, 0.0), (-h, -h, 0.0), (h, -h, 0.0)]
    square = [(h, 0.0, 0.0)]
    round_ = [circle(0.0)]
    for j, corner in enumerate(corners):
        square.append(corner)            # along the side: the square rail moves
        round_.append(round_[-1])
        for i in range(1, m + 1):        # the corner's fan: the round rail moves
            square.append(corner)
            round_.append(circle(90.0 * j + 90.0 * i / m))
    square.append((h, 0.0, 0.0))         # back to the seam
    round_.append(round_[-1])
    return np.array(square), np.array(round_)


# --------------------------------------------------------------------------------------------
# Tool compensation


def compensate_outline(outline, tool_diameter: float) -> np.ndarray:
    """The tool-centre path around a flat outline: every segment offset outward by the tool radius,
    neighbouring offset lines intersected (a sharp mitre corner).

    This is the seed's method (the straight lines a*X+b = Y offset by the radius and solved in pairs);
    at a concave corner the path point lies exactly one radius from both edges, so the tool cannot cut
    into the neighbouring edge (no overcut).  The intersection is written in its vector form
    p + r (n1 + n2) / (1 + n1.n2) (n1, n2 the outward unit normals), which also holds for parallel
    neighbours (collinear points) where the slope form divides by zero.  The result keeps the input's
    point order and orientation; "outward" follows the orientation (the part is inside).
    Limitation: short segments between concave corners shrink and invert when the tool is too large
    for them; a convex spike gives a far mitre point (no miter limit, as in the seed).
    """
    r = _check_positive(tool_diameter, "tool diameter", allow_zero=True) / 2.0
    pts = np.asarray(outline, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise UnfoldError(f"an outline must be a (k, 2) array, got shape {pts.shape}")
    if not np.all(np.isfinite(pts)):
        raise UnfoldError("outline has a non-finite coordinate (NaN or infinity)")
    keep = [0]
    for i in range(1, len(pts)):
        if np.linalg.norm(pts[i] - pts[keep[-1]]) > POINT_TOL:
            keep.append(i)
    pts = pts[keep]
    if len(pts) > 1 and np.linalg.norm(pts[0] - pts[-1]) <= POINT_TOL:
        pts = pts[:-1]
    if len(pts) < 3:
        raise UnfoldError("outline has fewer than 3 distinct points")
    area = signed_area(pts)
    if abs(area) <= POINT_TOL:
        raise UnfoldError("outline encloses no area")
    if r == 0.0:
        return pts.copy()
    seg = np.roll(pts, -1, axis=0) - pts              # segment i: pts[i] -> pts[i+1]
    seg /= np.linalg.norm(seg, axis=1)[:, None]
    normal = np.column_stack([seg[:, 1], -seg[:, 0]])  # right of travel: outward for a CCW outline
    if area < 0:
        normal = -normal
    n_in = np.roll(normal, 1, axis=0)                  # segment arriving at pts[i]
    denom = 1.0 + np.sum(n_in * normal, axis=1)
    bad = np.flatnonzero(denom < 1e-9)
    if len(bad):
        raise UnfoldError(f"outline turns straight back on itself at point {int(bad[0])}")
    return pts + r * (n_in + normal) / denom[:, None]


# --------------------------------------------------------------------------------------------
# Segmented pipe elbow


@dataclass(frozen=True)
class ElbowPiece:
    """One cylindrical piece of a segmented elbow, its 3-D side wall and its flat pattern.

    The piece is a cylinder of the elbow's diameter whose axis touches the centre-line circle (radius
    RT about the bend axis, the Z axis) at ``tangent_angle``; it is cut by two mitre planes through
    the bend axis at ``start_angle`` and ``end_angle`` (degrees around Z from +X).
    ``pattern_x`` is the arc length round the circumference from the throat (the generatrix nearest
    the bend axis) 0..pi*D, ``pattern_low`` / ``pattern_high`` the flat cut curves, measured along the
    generatrix from the cross-section through the tangent point.  ``low_ring[i]`` / ``high_ring[i]``
    are the 3-D cut points of generatrix i (i < divisions; pattern sample ``divisions`` repeats 0).
    ``vertices`` / ``faces`` are the open tube wall between the rings (outward normals).
    """

    index: int
    start_angle: float
    end_angle: float
    tangent_angle: float
    pattern_x: np.ndarray
    pattern_low: np.ndarray
    pattern_high: np.ndarray
    vertices: np.ndarray
    faces: np.ndarray

    @property
    def angle(self) -> float:
        return self.end_angle - self.start_angle

    @property
    def generatrix_lengths(self) -> np.ndarray:
        return self.pattern_high - self.pattern_low

    @property
    def low_ring(self) -> np.ndarray:
        return self.vertices[: len(self.vertices) // 2]

    @property
    def high_ring(self) -> np.ndarray:
        return self.vertices[len(self.vertices) // 2:]

    @property
    def outline(self) -> np.ndarray:
        """Closed CCW flat outline: the low cut curve left to right, the high one back."""
        low = np.column_stack([self.pattern_x, self.pattern_low])
        high = np.column_stack([self.pattern_x, self.pattern_high])[::-1]
        return np.vstack([low, high])


@dataclass(frozen=True)
class Elbow:
    bend_angle: float
    bend_radius: float
    diameter: float
    pieces: tuple

    @property
    def piece_angle(self) -> float:
        """Angle of a middle (full) piece; the two end pieces have half of it."""
        return self.bend_angle / (len(self.pieces) - 1)


def unfold_elbow(bend_angle: float, bend_radius: float, diameter: float, pieces: int,
                 divisions: int = 48) -> Elbow:
    """Segmented (lobster-back) elbow: ``pieces`` cylinders in all, the two end pieces half pieces.

    bend_angle KD (degrees), bend_radius RT (centre line), diameter D (the neutral diameter: the
    pattern is pi*D wide), ``divisions`` generatrices round the circumference.  A middle piece spans
    theta = KD / (pieces - 1); the end pieces theta / 2 and are cut square where they meet the
    straight pipe.  The pieces' axes form the polygon circumscribed about the centre-line circle, so
    a generatrix at distance rho = RT - (D/2) cos(alpha) from the bend axis (alpha = 0 at the throat)
    runs rho * tan(theta/2) from the tangent point to each mitre plane: a middle piece's generatrices
    run 2 (RT - D/2) tan(theta/2) .. 2 (RT + D/2) tan(theta/2), an end piece's half that.

    ``pieces`` counts every piece (the seed's "BN + 1" wording with the two half pieces makes
    pieces - 1 full-piece angles in the bend).  The seed's printed formulas (BK = KD/(BN+1); LU = (RT-DH) tan(BK); D_i = D cos(pi - i RD);
    Y_i = (RT - D_i) tan(BK) + LU) are garbled: D_i multiplies the diameter where the radius belongs
    and LU is added on top of a length that already contains it.  This function does not use them;
    the 3-D mesh is built from the construction itself (each generatrix intersected with the mitre
    planes) and the tests check the pattern against that mesh.
    """
    kd = _check_positive(bend_angle, "bend angle KD")
    rt = _check_positive(bend_radius, "bend radius RT")
    d = _check_positive(diameter, "pipe diameter D")
    n_pieces = _check_count(pieces, "number of elbow pieces", 2)
    m = _check_count(divisions, "circumference divisions", 3)
    if kd > 180.0:
        raise UnfoldError(f"bend angle KD must be at most 180 degrees, got {kd}")
    if rt <= d / 2.0:
        raise UnfoldError(f"bend radius RT ({rt}) must exceed the pipe radius D/2 ({d / 2.0})")
    theta = kd / (n_pieces - 1)
    if theta / 2.0 >= 90.0:
        raise UnfoldError(f"a {kd} degree bend needs more than {n_pieces} pieces")

    alpha = 2.0 * math.pi * np.arange(m + 1) / m
    pattern_x = d / 2.0 * alpha
    rho = rt - d / 2.0 * np.cos(alpha)
    result = []
    for k in range(n_pieces):
        tangent = k * theta
        half_low = 0.0 if k == 0 else theta / 2.0
        half_high = 0.0 if k == n_pieces - 1 else theta / 2.0
        low = -rho * math.tan(math.radians(half_low))
        high = rho * math.tan(math.radians(half_high))
        start, end = tangent - half_low, tangent + half_high
        vertices, faces = _elbow_piece_mesh(rt, d, tangent, start, end, alpha[:m])
        result.append(ElbowPiece(k, start, end, tangent, pattern_x, low, high, vertices, faces))
    return Elbow(kd, rt, d, tuple(result))


def _elbow_piece_mesh(rt, d, tangent_deg, start_deg, end_deg, alpha):
    """Side wall of one piece: each generatrix cut by the two mitre planes through the Z axis."""
    ft = math.radians(tangent_deg)
    e_r = np.array([math.cos(ft), math.sin(ft), 0.0])
    axis = np.array([-math.sin(ft), math.cos(ft), 0.0])
    z = np.array([0.0, 0.0, 1.0])
    base = (rt - d / 2.0 * np.cos(alpha))[:, None] * e_r + (d / 2.0 * np.sin(alpha))[:, None] * z

    def cut(plane_deg):
        f = math.radians(plane_deg)
        normal = np.array([-math.sin(f), math.cos(f), 0.0])  # plane through Z at angle f
        s = -(base @ normal) / float(axis @ normal)
        return base + s[:, None] * axis

    m = len(alpha)
    vertices = np.vstack([cut(start_deg), cut(end_deg)])
    i = np.arange(m)
    j = (i + 1) % m
    faces = np.vstack([np.column_stack([i, j, m + j]), np.column_stack([i, m + j, m + i])])
    return vertices, faces
