"""W5 core: twisted-quad / strip development, tool compensation, CDL reader, segmented elbow."""
import itertools
import math

import numpy as np
import pytest
from manifold3d import CrossSection, JoinType, Manifold

from kezuri.toolpath.operations.sheetmetal.unfold import (UnfoldError, compensate_outline, divide_edge, read_cdl, signed_area, square_to_round_rails, unfold_elbow, unfold_quad_strip, unfold_twisted_quad)

# The seed paper's test data (Table 1 / Fig. 10)
PAPER_CORNERS = np.array([[0, 0, 0], [0, 30, 100], [100, 50, 100], [100, 40, 0]], float)
PAPER_CDL = """LINE 0.0000000000, 0.0000000000, 0.0000000000,
0.0000000000, 30.0000000000, 100.0000000000, 1, 1, 1,
0, 0, 1, 1
LINE 0.0000000000, 30.0000000000, 100.0000000000,
100.0000000000, 50.0000000000, 100.0000000000, 1, 1,
1, 0, 0, 1, 1
LINE 100.0000000000, 50.0000000000, 100.0000000000,
100.0000000000, 40.0000000000, 0.0000000000, 1, 1, 1,
0, 0, 1, 1
LINE 100.0000000000, 40.0000000000, 0.0000000000,
0.0000000000, 0.0000000000, 0.0000000000, 1, 1, 1, 0,
0, 1, 1
"""


def tri_edges(vertices, triangles):
    v = vertices[triangles]                      # (t, 3, dim)
    return np.linalg.norm(v - np.roll(v, -1, axis=1), axis=2)


def tri_areas(v2, triangles):
    p, q, r = (v2[triangles[:, i]] for i in range(3))
    return 0.5 * ((q[:, 0] - p[:, 0]) * (r[:, 1] - p[:, 1]) - (q[:, 1] - p[:, 1]) * (r[:, 0] - p[:, 0]))


def assert_isometric(pattern, tol=1e-9):
    e3 = tri_edges(pattern.vertices_3d, pattern.triangles)
    e2 = tri_edges(pattern.vertices_2d, pattern.triangles)
    np.testing.assert_allclose(e2, e3, rtol=0, atol=tol)
    o3, o2 = pattern.outline_3d, pattern.outline
    np.testing.assert_allclose(np.linalg.norm(np.roll(o2, -1, 0) - o2, axis=1),
                               np.linalg.norm(np.roll(o3, -1, 0) - o3, axis=1), rtol=0, atol=tol)


def random_rotation(seed):
    q, _ = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    return q * np.sign(np.linalg.det(q))


# ---------------------------------------------------------------- the paper's twisted quad


@pytest.mark.parametrize("direction", ["horizontal", "vertical"])
def test_paper_measurements(direction):
    quad = unfold_twisted_quad(PAPER_CORNERS, 5, direction)
    np.testing.assert_allclose(quad.edge_lengths, [104.40307, 101.98039, 100.49876, 107.70330], atol=1e-5)
    np.testing.assert_allclose(quad.diagonals, [150.00000, 141.77447], atol=1e-5)
    # The paper's form prints 20.88061, 20.59008, 20.09975, 21.54088.  L2/5 and L4/5 are misprints:
    # 101.98039 / 5 = 20.39608 and 107.70330 / 5 = 21.54066 (L1 and L3 agree with the form).
    np.testing.assert_allclose(quad.division_lengths, [20.88061, 20.39608, 20.09975, 21.54066], atol=1e-5)
    assert abs(quad.division_lengths[1] - 20.59008) > 0.19
    assert abs(quad.division_lengths[3] - 21.54088) > 2e-4


@pytest.mark.parametrize("direction", ["horizontal", "vertical"])
@pytest.mark.parametrize("n", [1, 5, 17])
def test_twisted_quad_is_isometric_and_never_flips(direction, n):
    quad = unfold_twisted_quad(PAPER_CORNERS, n, direction)
    pat = quad.pattern
    assert pat.triangles.shape == (2 * n, 3)
    assert_isometric(pat)
    assert np.all(tri_areas(pat.vertices_2d, pat.triangles) > 1.0)   # all CCW, none degenerate
    assert signed_area(pat.outline) > 0
    assert len(pat.outline) == 2 * n + 2
    # the flat corners sit where the 3-D corners are; the two rail sides (those whose division
    # points are joined) are N segments of L/N, the first and last rungs are whole edges
    np.testing.assert_array_equal(pat.vertices_3d[quad.corner_index], PAPER_CORNERS)
    rails = (0, 2) if direction == "horizontal" else (1, 3)   # YR joins L1-L3, TR joins L2-L4
    pos = [int(np.flatnonzero(pat.outline_index == c)[0]) for c in quad.corner_index]
    o2 = pat.outline
    for i in range(4):
        parts = n if i in rails else 1
        idx = [(pos[i] + k) % len(o2) for k in range(parts + 1)]
        assert idx[-1] == pos[(i + 1) % 4]          # P1 -> P2 -> P3 -> P4 round the outline, CCW
        seg = np.linalg.norm(np.diff(o2[idx], axis=0), axis=1)
        np.testing.assert_allclose(seg, quad.edge_lengths[i] / parts, atol=1e-9)


def test_division_points_follow_the_paper_formula():
    # P1,i = (P2,1 - P1,1) / n * (i - 1) + P1,1 on every edge
    quad = unfold_twisted_quad(PAPER_CORNERS, 5, "horizontal")
    a = quad.pattern.vertices_3d[:6]
    expected = [(PAPER_CORNERS[1] - PAPER_CORNERS[0]) / 5 * (i - 1) + PAPER_CORNERS[0] for i in range(1, 7)]
    np.testing.assert_allclose(a, expected, atol=1e-12)
    np.testing.assert_allclose(divide_edge(PAPER_CORNERS[3], PAPER_CORNERS[2], 5),
                               quad.pattern.vertices_3d[6:], atol=1e-12)


def test_direction_reference_edges_and_paper_diagonals():
    n = 5
    v = unfold_twisted_quad(PAPER_CORNERS, n, "vertical")
    h = unfold_twisted_quad(PAPER_CORNERS, n, "horizontal")
    # vertical (TR): L1 = P1P2 is the reference edge laid first, on the +Y axis
    p1, p2 = v.pattern.vertices_2d[v.corner_index[:2]]
    np.testing.assert_allclose(p2, [0, 0], atol=1e-12)
    np.testing.assert_allclose(p1, [0, v.edge_lengths[0]], atol=1e-12)
    # horizontal (YR): L4 = P4P1 is the reference edge
    p1, p4 = h.pattern.vertices_2d[h.corner_index[[0, 3]]]
    np.testing.assert_allclose(p1, [0, 0], atol=1e-12)
    np.testing.assert_allclose(p4, [0, h.edge_lengths[3]], atol=1e-12)
    # TRT1,1 = P1,1 - P2,1 - P4,n: the first vertical triangle is P1, P2 and the division point of
    # L4 next to P1; YR1's first triangle is P1, P4 and P1,2.
    def first_triangle(quad):
        return {tuple(np.round(p, 9)) for p in quad.pattern.vertices_3d[quad.pattern.triangles[0]]}
    p4n = PAPER_CORNERS[3] + (PAPER_CORNERS[0] - PAPER_CORNERS[3]) * (n - 1) / n
    assert first_triangle(v) == {tuple(PAPER_CORNERS[0]), tuple(PAPER_CORNERS[1]), tuple(np.round(p4n, 9))}
    p12 = PAPER_CORNERS[0] + (PAPER_CORNERS[1] - PAPER_CORNERS[0]) / n
    assert first_triangle(h) == {tuple(PAPER_CORNERS[0]), tuple(PAPER_CORNERS[3]), tuple(np.round(p12, 9))}


def test_both_directions_are_seen_from_the_same_side():
    # the two developments are different surfaces' patterns but both keep P1 P2 P3 P4 CCW
    for direction in ("vertical", "horizontal"):
        quad = unfold_twisted_quad(PAPER_CORNERS, 5, direction)
        assert signed_area(quad.pattern.vertices_2d[quad.corner_index]) > 0


def test_twisted_quad_is_not_congruent_to_a_plane():
    # a real twist: the flat distance P1-P3 is not the 3-D diagonal (the sheet has to be bent)
    quad = unfold_twisted_quad(PAPER_CORNERS, 5, "horizontal")
    flat = quad.pattern.vertices_2d[quad.corner_index]
    assert abs(np.linalg.norm(flat[2] - flat[0]) - 150.0) > 0.5


@pytest.mark.parametrize("direction", ["horizontal", "vertical"])
def test_planar_quad_unfolds_to_itself(direction):
    quad2d = np.array([[0, 0], [80, -10], [95, 60], [10, 45]], float)
    corners = np.column_stack([quad2d, np.zeros(4)]) @ random_rotation(3).T + [12.0, -7.0, 30.0]
    pat = unfold_twisted_quad(corners, 6, direction).pattern
    # congruent: every pairwise distance of the flat vertices is the 3-D one
    for i, j in itertools.combinations(range(len(pat.vertices_2d)), 2):
        d2 = np.linalg.norm(pat.vertices_2d[i] - pat.vertices_2d[j])
        d3 = np.linalg.norm(pat.vertices_3d[i] - pat.vertices_3d[j])
        assert abs(d2 - d3) < 1e-9
    assert signed_area(pat.outline) == pytest.approx(abs(signed_area(quad2d)), abs=1e-9)


def test_quad_strip_diagonal_choices():
    rail_a = np.array([[0, 0, 0], [30, 0, 5], [60, 0, 0], [90, 0, -5]], float)
    rail_b = np.array([[0, 40, 10], [32, 42, 0], [61, 39, 8], [88, 40, 0]], float)
    for diagonal in ("a_next", "b_next", "shorter"):
        pat = unfold_quad_strip(rail_a, rail_b, diagonal)
        assert_isometric(pat)
        assert np.all(tri_areas(pat.vertices_2d, pat.triangles) > 0)
    with pytest.raises(UnfoldError, match="diagonal"):
        unfold_quad_strip(rail_a, rail_b, "long")


# ---------------------------------------------------------------- square-to-round transition


@pytest.mark.parametrize("offset", [(0.0, 0.0), (12.0, -8.0)])
def test_square_to_round_transition_keeps_lengths(offset):
    side, dia, height, fans = 120.0, 70.0, 90.0, 6
    square, round_ = square_to_round_rails(side, dia, height, fans, offset)
    pat = unfold_quad_strip(square, round_)
    assert len(pat.triangles) == 4 * fans + 5        # 4 fans + 3 sides + 2 half sides at the seam
    assert_isometric(pat)
    assert np.all(tri_areas(pat.vertices_2d, pat.triangles) > 1.0)
    # the square rail unrolls into the sides: s/2, s, s, s, s/2
    flat_a = pat.vertices_2d[: len(square)]
    steps = np.linalg.norm(np.diff(flat_a, axis=0), axis=1)
    np.testing.assert_allclose(steps[steps > 1e-12], [side / 2, side, side, side, side / 2], atol=1e-9)
    # the round rail unrolls to the polygon's perimeter (chord length each step)
    flat_b = pat.vertices_2d[len(square):]
    chord = dia * math.sin(math.pi / (4 * fans))
    flat_steps = np.linalg.norm(np.diff(flat_b, axis=0), axis=1)
    np.testing.assert_allclose(flat_steps[flat_steps > 1e-12], chord, atol=1e-9)
    assert np.sum(flat_steps) == pytest.approx(4 * fans * chord, abs=1e-9)


# ---------------------------------------------------------------- tool compensation


def test_compensated_square_is_grown_with_sharp_corners():
    square = np.array([[0, 0], [100, 0], [100, 100], [0, 100]], float)
    out = compensate_outline(square, 10.0)
    np.testing.assert_allclose(out, [[-5, -5], [105, -5], [105, 105], [-5, 105]], atol=1e-12)
    # clockwise input: still outward, order and orientation kept
    out_cw = compensate_outline(square[::-1], 10.0)
    np.testing.assert_allclose(out_cw, [[-5, 105], [105, 105], [105, -5], [-5, -5]], atol=1e-12)
    # the same as Clipper's mitred offset
    ref = CrossSection([square]).offset(5.0, JoinType.Miter, 100.0)
    assert ref.area() == pytest.approx(abs(signed_area(out)), abs=1e-6)


def test_collinear_points_and_zero_tool():
    square = np.array([[0, 0], [50, 0], [100, 0], [100, 100], [0, 100], [0, 0]], float)  # closing repeat
    out = compensate_outline(square, 4.0)
    np.testing.assert_allclose(out, [[-2, -2], [50, -2], [102, -2], [102, 102], [-2, 102]], atol=1e-12)
    # nearly parallel neighbours: the point moves by r along the normal, no blow-up
    kinked = np.array([[0, 0], [50, 1e-7], [100, 0], [100, 100], [0, 100]], float)
    assert np.linalg.norm(compensate_outline(kinked, 4.0)[1] - [50, -2]) < 1e-6
    np.testing.assert_array_equal(compensate_outline(square, 0.0), square[:-1])


def _point_segment_distance(p, a, b):
    t = np.clip(np.dot(p - a, b - a) / np.dot(b - a, b - a), 0.0, 1.0)
    return np.linalg.norm(p - (a + t * (b - a)))


def test_l_shape_concave_corner_has_no_overcut():
    r = 3.0
    ell = np.array([[0, 0], [60, 0], [60, 20], [20, 20], [20, 50], [0, 50]], float)
    out = compensate_outline(ell, 2 * r)
    concave = out[3]                     # the corner (20, 20) turns right on a CCW outline
    np.testing.assert_allclose(concave, [20 + r, 20 + r], atol=1e-12)
    # the tool centre is exactly r from BOTH edges meeting at the concave corner
    assert _point_segment_distance(concave, ell[2], ell[3]) == pytest.approx(r, abs=1e-12)
    assert _point_segment_distance(concave, ell[3], ell[4]) == pytest.approx(r, abs=1e-12)
    # nowhere along the path does the tool come closer than r to the part: no overcut
    edges = list(zip(ell, np.roll(ell, -1, axis=0)))
    for p, q in zip(out, np.roll(out, -1, axis=0)):
        for t in np.linspace(0.0, 1.0, 201):
            c = p + t * (q - p)
            assert min(_point_segment_distance(c, a, b) for a, b in edges) >= r - 1e-9
    ref = CrossSection([ell]).offset(r, JoinType.Miter, 100.0)
    assert ref.area() == pytest.approx(signed_area(out), abs=1e-6)


def test_compensation_of_a_flat_pattern_matches_clipper():
    outline = unfold_twisted_quad(PAPER_CORNERS, 5, "horizontal").pattern.outline
    out = compensate_outline(outline, 2.0)
    ref = CrossSection([outline]).offset(1.0, JoinType.Miter, 100.0)
    assert ref.area() == pytest.approx(signed_area(out), rel=1e-9)


def test_compensation_rejects_bad_input():
    square = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
    with pytest.raises(UnfoldError, match="tool diameter"):
        compensate_outline(square, -1.0)
    with pytest.raises(UnfoldError, match="tool diameter"):
        compensate_outline(square, float("nan"))
    with pytest.raises(UnfoldError, match="turns straight back"):
        compensate_outline([[0, 0], [10, 0], [5, 0], [5, 5]], 1.0)
    with pytest.raises(UnfoldError, match="fewer than 3"):
        compensate_outline([[0, 0], [10, 0], [10, 0]], 1.0)
    with pytest.raises(UnfoldError, match="no area"):
        compensate_outline([[0, 0], [10, 0], [20, 0]], 1.0)


# ---------------------------------------------------------------- CDL reader


def test_read_paper_cdl_file():
    # Table 1: "14 data in all" counts the word LINE: 13 numbers after it
    np.testing.assert_array_equal(read_cdl(PAPER_CDL), PAPER_CORNERS)
    # 14 numbers after the word (the spec's wording) read the same
    np.testing.assert_array_equal(read_cdl(PAPER_CDL.replace(", 1, 1\n", ", 1, 1, 0\n")), PAPER_CORNERS)


def test_read_cdl_any_order_direction_and_other_records():
    text = """POINT 5.0, 5.0, 5.0, 1, 1
LINE 100, 40, 0, 100, 50, 100, 1, 1, 1, 0, 0, 1, 1
LINE 0, 30, 100,
   100, 50, 100,
   1, 1, 1, 0, 0, 1, 1
ARC 1, 2, 3, 4, 5, 6, 7
LINE 0,0,0, 0,30,100, 1,1,1,0,0,1,1
LINE 0.0000001 0 0 100 40 0 1 1 1 0 0 1 1
"""
    corners = read_cdl(text)
    # P1, P2 = the first LINE as written, then round the loop
    np.testing.assert_allclose(corners, [[100, 40, 0], [100, 50, 100], [0, 30, 100], [0, 0, 0]], atol=1e-6)
    assert unfold_twisted_quad(corners, 5).edge_lengths == pytest.approx(
        [100.49876, 101.98039, 104.40307, 107.70330], abs=1e-5)


def test_read_cdl_errors_name_the_line():
    broken = PAPER_CDL.replace("100.0000000000, 40.0000000000, 0.0000000000,\n0.0000000000",
                               "100.0000000000, 40.0000000000, 0.0000000000,\n7.0000000000")
    with pytest.raises(UnfoldError, match=r"line 10\b.*do not close"):
        read_cdl(broken)
    gap = PAPER_CDL.replace("LINE 100.0000000000, 50.0000000000, 100.0000000000",
                            "LINE 100.0000000000, 55.0000000000, 100.0000000000")
    with pytest.raises(UnfoldError, match=r"CDL line 4\b"):
        read_cdl(gap)
    with pytest.raises(UnfoldError, match="exactly 4 LINE records, found 3"):
        read_cdl(PAPER_CDL.split("LINE 100.0000000000, 40")[0])
    with pytest.raises(UnfoldError, match=r"line 2: LINE record has 12 numbers"):
        read_cdl("POINT 1 2 3\nLINE 0,0,0, 1,1,1, 1,1,1,0,0\n1\n")
    with pytest.raises(UnfoldError, match="line 1: number"):
        read_cdl("1.0, 2.0\nLINE 0,0,0,1,1,1,1,1,1,0,0,1,1")
    with pytest.raises(UnfoldError, match="line 1: LINE has zero length"):
        read_cdl("LINE 1,1,1, 1,1,1, 1,1,1,0,0,1,1")


# ---------------------------------------------------------------- validation


def test_twisted_quad_rejects_bad_input():
    for bad_n in (0, -2, 2.5, True, "5"):
        with pytest.raises(UnfoldError, match="divisions"):
            unfold_twisted_quad(PAPER_CORNERS, bad_n)
    with pytest.raises(UnfoldError, match="direction"):
        unfold_twisted_quad(PAPER_CORNERS, 5, "diagonal")
    same = PAPER_CORNERS.copy()
    same[1] = same[0]
    with pytest.raises(UnfoldError, match="P1 and P2 coincide .zero-length edge"):
        unfold_twisted_quad(same, 5)
    same = PAPER_CORNERS.copy()
    same[2] = same[0]
    with pytest.raises(UnfoldError, match="P1 and P3 coincide .zero-length diagonal"):
        unfold_twisted_quad(same, 5)
    nan = PAPER_CORNERS.copy()
    nan[2, 1] = np.nan
    with pytest.raises(UnfoldError, match="finite"):
        unfold_twisted_quad(nan, 5)
    with pytest.raises(UnfoldError, match="4 corners"):
        unfold_twisted_quad(PAPER_CORNERS[:3], 5)
    with pytest.raises(UnfoldError, match="same number of points"):
        unfold_quad_strip(np.zeros((3, 3)), np.ones((4, 3)))
    with pytest.raises(UnfoldError, match="both rails stand still"):
        unfold_quad_strip([[0, 0, 0], [0, 0, 0]], [[0, 5, 0], [0, 5, 0]])
    with pytest.raises(UnfoldError, match="zero-length rung"):
        unfold_quad_strip([[0, 0, 0], [5, 0, 0]], [[0, 0, 0], [5, 5, 0]])


# ---------------------------------------------------------------- segmented pipe elbow

KD, RT, D = 90.0, 150.0, 100.0


@pytest.mark.parametrize("pieces", [2, 3, 4, 7])
def test_elbow_pieces_angles_and_closed_forms(pieces):
    elbow = unfold_elbow(KD, RT, D, pieces, divisions=48)
    theta = KD / (pieces - 1)
    assert elbow.piece_angle == pytest.approx(theta)
    angles = [p.angle for p in elbow.pieces]
    assert len(angles) == pieces
    assert sum(angles) == pytest.approx(KD, abs=1e-12)
    assert angles[0] == pytest.approx(theta / 2) and angles[-1] == pytest.approx(theta / 2)
    assert all(a == pytest.approx(theta) for a in angles[1:-1])
    tan_half = math.tan(math.radians(theta / 2))
    for piece in elbow.pieces:
        x, h = piece.pattern_x, piece.generatrix_lengths
        assert x[-1] - x[0] == pytest.approx(math.pi * D, abs=1e-12)       # width = pi * D
        full = 2.0 if 0 < piece.index < pieces - 1 else 1.0                  # end pieces: half
        assert h[0] == pytest.approx(full * (RT - D / 2) * tan_half, abs=1e-12)      # throat
        assert h[24] == pytest.approx(full * (RT + D / 2) * tan_half, abs=1e-12)     # back, x = pi D / 2
        assert h.min() == pytest.approx(h[0]) and h.max() == pytest.approx(h[24])
        out = piece.outline
        assert signed_area(out) > 0
        assert out[:, 0].max() - out[:, 0].min() == pytest.approx(math.pi * D)


@pytest.mark.parametrize("pieces", [2, 4, 5])
def test_elbow_pattern_matches_its_3d_model(pieces):
    m = 64
    elbow = unfold_elbow(KD, RT, D, pieces, divisions=m)
    for piece in elbow.pieces:
        low, high = piece.low_ring, piece.high_ring
        # generatrix lengths measured on the 3-D mesh are the pattern heights
        np.testing.assert_allclose(np.linalg.norm(high - low, axis=1), piece.generatrix_lengths[:m], atol=1e-9)
        # the cut rings lie on the mitre planes through the bend axis (Z)
        for ring, deg in ((low, piece.start_angle), (high, piece.end_angle)):
            f = math.radians(deg)
            np.testing.assert_allclose(ring @ [-math.sin(f), math.cos(f), 0.0], 0.0, atol=1e-9)
        # arc length between neighbouring generatrices is the pattern's x step (pi D in all)
        f = math.radians(piece.tangent_angle)
        axis = np.array([-math.sin(f), math.cos(f), 0.0])
        section = low - np.outer(low @ axis, axis)              # project onto a cross-section
        chords = np.linalg.norm(np.roll(section, -1, 0) - section, axis=1)
        np.testing.assert_allclose(chords, D * math.sin(math.pi / m), atol=1e-9)
        np.testing.assert_allclose(np.diff(piece.pattern_x), math.pi * D / m, atol=1e-12)
        # mesh faces point outward (away from the piece's axis)
        v = piece.vertices[piece.faces]
        normals = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
        centre = v.mean(axis=1)
        on_axis = RT * np.array([math.cos(f), math.sin(f), 0.0])
        radial = centre - (on_axis + np.outer((centre - on_axis) @ axis, axis))
        assert np.all(np.sum(normals * radial, axis=1) > 0)
    # neighbouring pieces meet on the same cut curve (the mitre joint closes)
    for p, q in zip(elbow.pieces, elbow.pieces[1:]):
        assert p.end_angle == pytest.approx(q.start_angle)
        np.testing.assert_allclose(p.high_ring, q.low_ring, atol=1e-9)
    # both ends are cut square: circles of diameter D about the centre line, in the end planes
    first, last = elbow.pieces[0].low_ring, elbow.pieces[-1].high_ring
    np.testing.assert_allclose(np.linalg.norm(first - [RT, 0, 0], axis=1), D / 2, atol=1e-9)
    np.testing.assert_allclose(first[:, 1], 0.0, atol=1e-9)
    c = RT * np.array([math.cos(math.radians(KD)), math.sin(math.radians(KD)), 0.0])
    np.testing.assert_allclose(np.linalg.norm(last - c, axis=1), D / 2, atol=1e-9)


def test_elbow_piece_volume_from_manifold_model():
    """Independent 3-D model: a manifold3d cylinder trimmed by the two mitre planes.  A prism cut by
    two planes has volume = section area x length of its axis between the planes, and the pattern's
    mean height over equally spaced generatrices is exactly that axis length."""
    segments = 128
    elbow = unfold_elbow(KD, RT, D, 4, divisions=segments)
    area = 0.5 * segments * (D / 2) ** 2 * math.sin(2 * math.pi / segments)
    for piece in elbow.pieces:
        f = math.radians(piece.tangent_angle)
        e_r = np.array([math.cos(f), math.sin(f), 0.0])
        axis = np.array([-math.sin(f), math.cos(f), 0.0])
        frame = np.column_stack([[0, 0, 1.0], e_r, axis, RT * e_r])      # local Z -> pipe axis
        cyl = Manifold.cylinder(4 * RT, D / 2, D / 2, segments, True).transform(frame)
        a0, a1 = math.radians(piece.start_angle), math.radians(piece.end_angle)
        cut = cyl.trim_by_plane([-math.sin(a0), math.cos(a0), 0.0], 0.0)
        cut = cut.trim_by_plane([math.sin(a1), -math.cos(a1), 0.0], 0.0)
        mean_height = piece.generatrix_lengths[:segments].mean()
        assert cut.volume() == pytest.approx(area * mean_height, rel=1e-6)


def test_elbow_rejects_bad_input():
    with pytest.raises(UnfoldError, match="pieces"):
        unfold_elbow(KD, RT, D, 1)
    with pytest.raises(UnfoldError, match="pieces"):
        unfold_elbow(KD, RT, D, 3.0)
    with pytest.raises(UnfoldError, match="exceed the pipe radius"):
        unfold_elbow(KD, 50.0, D, 4)
    with pytest.raises(UnfoldError, match="at most 180"):
        unfold_elbow(200.0, RT, D, 4)
    with pytest.raises(UnfoldError, match="more than 2 pieces"):
        unfold_elbow(180.0, RT, D, 2)
    with pytest.raises(UnfoldError, match="bend angle"):
        unfold_elbow(0.0, RT, D, 4)
    with pytest.raises(UnfoldError, match="diameter"):
        unfold_elbow(KD, RT, -1.0, 4)
    with pytest.raises(UnfoldError, match="circumference divisions"):
        unfold_elbow(KD, RT, D, 4, divisions=2)


def test_three_collinear_corners_are_refused():
    with pytest.raises(UnfoldError, match="P1, P2 and P3 are collinear"):
        unfold_twisted_quad([[0, 0, 0], [10, 0, 0], [20, 0, 0], [0, 10, 5]], 5)


@pytest.mark.parametrize("corners, edges", [
    ([[0, 0, 0], [100, 50, 0], [100, 0, 0], [0, 50, 0]], "P1-P2 and P3-P4"),      # a planar bow tie
    ([[0, 0, 0], [0, 50, 0], [100, 0, 0], [100, 50, 0]], "P2-P3 and P4-P1"),
    ([[0, 0, 0], [100, 50, 1], [100, 0, 0], [0, 50, 1]], "P1-P2 and P3-P4"),      # crossing at (50, 25, 0.5)
])
def test_a_quad_whose_edges_cross_is_refused(corners, edges):
    """Corners not in order round the quad make opposite edges meet: a bow tie, whose strips fold
    over each other, is no sheet (it used to unfold into a plausible pattern, exit 0)."""
    with pytest.raises(UnfoldError, match=f"edges {edges} cross: give the corners in order round the quad"):
        unfold_twisted_quad(corners, 5)


def test_the_segment_gap_is_the_closest_approach():
    """_segment_gap against dense sampling of both segments, on random pairs (parallel ones too)."""
    from kezuri.toolpath.operations.sheetmetal.unfold import _segment_gap
    rng = np.random.default_rng(5)
    t = np.linspace(0, 1, 401)
    for k in range(60):
        p0, p1, q0 = rng.normal(size=(3, 3)) * 10
        q1 = q0 + (p1 - p0) * rng.uniform(-2, 2) if k % 10 == 0 else rng.normal(size=3) * 10
        a = p0 + t[:, None] * (p1 - p0)
        b = q0 + t[:, None] * (q1 - q0)
        sampled = np.linalg.norm(a[:, None] - b[None], axis=2).min()
        gap = _segment_gap(p0, p1, q0, q1)
        step = (np.linalg.norm(p1 - p0) + np.linalg.norm(q1 - q0)) / 400     # the samples' spacing, both
        assert gap <= sampled + 1e-9 and sampled - gap < step
