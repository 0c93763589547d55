"""The drop cutter against closed forms (sphere, plane, edge, vertex), its two kernels against
each other, and random meshes against a brute-force search over each triangle."""
import math

import numpy as np
import pytest

from kezuri.toolpath.engines import dropcutter as dc
from kezuri.toolpath.ir.program import Tool

KERNELS = ["numpy", "numba"]


def icosphere(radius, subdivisions):
    trimesh = pytest.importorskip("trimesh")
    sphere = trimesh.creation.icosphere(subdivisions=subdivisions, radius=radius)
    return np.asarray(sphere.vertices), np.asarray(sphere.faces)


def wall(h0=5.0, h1=5.0, half=20.0):
    """A vertical quad in the plane y = 0, x in [-half, half], bottom z = -100, top edge from
    (-half, 0, h0) to (half, 0, h1): over it only the top edge and its ends can be touched."""
    v = np.array([[-half, 0, -100], [half, 0, -100], [half, 0, h1], [-half, 0, h0]], float)
    return v, np.array([[0, 1, 2], [0, 2, 3]])


def pyramid(height=10.0, base=1.0, drop=10.0):
    """A needle: apex (0, 0, height), four base corners ``base`` from the axis ``drop`` below."""
    angles = np.arange(4) * np.pi / 2
    v = np.vstack([[0, 0, height], np.column_stack([base * np.cos(angles), base * np.sin(angles),
                                                    np.full(4, height - drop)])])
    return v, np.array([[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]])


@pytest.mark.parametrize("kernel", KERNELS)
def test_ball_over_a_sphere_is_bracketed_by_the_closed_forms(kernel):
    """Over a sphere of radius R the ball's tip is sqrt((R + r)^2 - d^2) - r; the mesh lies
    between its circumscribed sphere (R) and the sphere touching its faces (R_in)."""
    R, r = 40.0, 3.0
    v, f = icosphere(R, 5)
    tri = v[f]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    r_in = float(np.min(np.abs(np.einsum("ij,ij->i", normal, tri[:, 0])) / np.linalg.norm(normal, axis=1)))
    assert R - r_in < 0.02
    d = np.linspace(0, 40, 81)
    xy = np.column_stack([d / math.sqrt(2), d / math.sqrt(2)])
    z = dc.DropCutter(v, f, Tool(1, "ball", 2 * r), kernel=kernel).points(xy)
    upper = np.sqrt((R + r) ** 2 - d ** 2) - r
    lower = np.sqrt((r_in + r) ** 2 - d ** 2) - r
    assert np.all(z <= upper + 1e-9)
    assert np.all(z >= lower - 1e-9)


@pytest.mark.parametrize("kernel", KERNELS)
def test_flat_end_over_a_horizontal_plane(kernel):
    v = np.array([[-10, -10, 2.5], [10, -10, 2.5], [10, 10, 2.5], [-10, 10, 2.5]], float)
    f = np.array([[0, 1, 2], [0, 2, 3]])
    cutter = dc.DropCutter(v, f, Tool(1, "flat", 6.0), floor=-50.0, kernel=kernel)
    # inside, and overhanging the edge by up to the radius: the plane's height; beyond: the floor
    xy = np.array([[0, 0], [9.9, 3], [12.9, 0], [-12.99, -10.0], [13.01, 0], [12.2, 12.2]])
    expected = [2.5, 2.5, 2.5, 2.5, -50.0, -50.0]   # (12.2, 12.2) is 3.11 mm from the corner
    assert cutter.points(xy) == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("slope", [0.0, 0.3, -1.7])
def test_ball_over_an_edge(kernel, slope):
    """The ball's centre is r from the edge's line: z_c = z_line(x) + sqrt(1 + m^2) sqrt(r^2 - t^2)."""
    r, half = 2.0, 20.0
    v, f = wall(5.0 - slope * half, 5.0 + slope * half, half)
    x = np.linspace(-10, 10, 7)
    for t in (0.0, 0.7, 1.5, 1.99):
        z = dc.DropCutter(v, f, Tool(1, "ball", 2 * r), kernel=kernel).points(np.column_stack([x, np.full(7, t)]))
        centre = 5.0 + slope * x + math.sqrt(1 + slope ** 2) * math.sqrt(r * r - t * t)
        assert z == pytest.approx(centre - r, abs=1e-9)


@pytest.mark.parametrize("kernel", KERNELS)
def test_flat_cone_and_bull_over_a_level_edge(kernel):
    v, f = wall(5.0, 5.0)
    t = np.linspace(0, 4.0, 41)
    xy = np.column_stack([np.zeros_like(t), t])
    flat = dc.DropCutter(v, f, Tool(1, "flat", 6.0), floor=-99, kernel=kernel).points(xy)
    assert flat == pytest.approx(np.where(t <= 3.0, 5.0, -99), abs=1e-12)
    vbit = dc.DropCutter(v, f, Tool(2, "vbit", 6.0), floor=-99, kernel=kernel).points(xy)
    assert vbit == pytest.approx(np.where(t <= 3.0, 5.0 - t, -99), abs=1e-12)   # 90 degrees: h = d
    bull = dc.DropCutter(v, f, Tool(3, "bull", 6.0, corner_radius=1.0), floor=-99, kernel=kernel).points(xy)
    h = np.where(t <= 2.0, 0.0, 1.0 - np.sqrt(np.maximum(1.0 - (t - 2.0) ** 2, 0)))
    assert bull == pytest.approx(np.where(t <= 3.0, 5.0 - h, -99), abs=1e-9)


@pytest.mark.parametrize("kernel", KERNELS)
def test_bull_over_a_sloped_edge_touches_at_distance_corner(kernel):
    """Every contact of a bull nose lies on its torus: the corner circle's centre (at distance
    R - r from the axis, r above the tip) is r from the edge's line; check that distance."""
    R, rc = 3.0, 1.0
    v, f = wall(2.0, 8.0, 10.0)
    m = 6.0 / 20.0
    xy = np.column_stack([np.linspace(-5, 5, 11), np.linspace(0.1, 2.9, 11)])
    z = dc.DropCutter(v, f, Tool(1, "bull", 2 * R, corner_radius=rc), kernel=kernel).points(xy)
    p0, u = np.array([-10.0, 0, 2.0]), np.array([20.0, 0, 6.0]) / math.hypot(20, 6)
    for (x, y), tip in zip(xy, z):
        theta = np.linspace(0, 2 * np.pi, 200001)
        ring = np.column_stack([x + (R - rc) * np.cos(theta), y + (R - rc) * np.sin(theta),
                                np.full_like(theta, tip + rc)])
        w = ring - p0
        dist = np.linalg.norm(w - np.outer(w @ u, u), axis=1)
        assert dist.min() == pytest.approx(rc, abs=1e-6)
    assert m < 1


@pytest.mark.parametrize("kernel", KERNELS)
def test_vbit_and_ball_over_a_vertex(kernel):
    v, f = pyramid(height=10.0)
    d = np.linspace(0, 2.9, 30)
    xy = np.column_stack([d * 0.6, d * 0.8])
    vbit = dc.DropCutter(v, f, Tool(1, "vbit", 6.0), kernel=kernel).points(xy)
    assert vbit == pytest.approx(10.0 - d, abs=1e-9)       # 90 degree cone: h(d) = d
    ball = dc.DropCutter(v, f, Tool(1, "ball", 6.0), kernel=kernel).points(xy)
    assert ball == pytest.approx(10.0 + np.sqrt(9.0 - d ** 2) - 3.0, abs=1e-9)


@pytest.mark.parametrize("kernel", KERNELS)
def test_allowance_keeps_the_tool_that_far_away(kernel):
    """A flat end mill kept a from a level edge: tip h + a within R, then the offset circle."""
    v, f = wall(5.0, 5.0)
    R, a = 3.0, 0.5
    t = np.linspace(0, 3.5, 36)
    z = dc.DropCutter(v, f, Tool(1, "flat", 2 * R), allowance=a, floor=-99,
                      kernel=kernel).points(np.column_stack([np.zeros_like(t), t]))
    expected = np.where(t <= R, 5.0 + a, np.where(t <= R + a, 5.0 + np.sqrt(np.maximum(a * a - (t - R) ** 2, 0)),
                                                  -99 + a))
    assert z == pytest.approx(expected, abs=1e-9)
    with pytest.raises(dc.DropCutterError, match="V-bit"):
        dc.DropCutter(v, f, Tool(1, "vbit", 6.0), allowance=0.2)


def _brute_force(tri, profile, point, n=160, zooms=6):
    """Highest P_z - h(|P_xy - C|) over the triangle by a barycentric grid, zoomed in on the best."""
    kind, R, rc, fr, k = profile
    best = -np.inf
    centre, span = np.array([1 / 3, 1 / 3]), 1.0
    for _ in range(zooms):
        a = np.linspace(-span, span, n)
        uu, vv = np.meshgrid(centre[0] + a, centre[1] + a)
        uu, vv = uu.ravel(), vv.ravel()
        ok = (uu >= 0) & (vv >= 0) & (uu + vv <= 1)
        uu, vv = uu[ok], vv[ok]
        p = tri[0] + np.outer(uu, tri[1] - tri[0]) + np.outer(vv, tri[2] - tri[0])
        d = np.hypot(p[:, 0] - point[0], p[:, 1] - point[1])
        z = np.where(d <= R, p[:, 2] - dc.underside(profile, np.minimum(d, R)), -np.inf)
        if not np.isfinite(z).any():
            return best
        i = int(np.argmax(z))
        best = max(best, float(z[i]))
        centre, span = np.array([uu[i], vv[i]]), span * 8 / n
    return best


@pytest.mark.parametrize("kind,corner", [("ball", 0.0), ("flat", 0.0), ("bull", 0.8), ("vbit", 0.0)])
def test_random_triangles_against_brute_force(kind, corner):
    """Each triangle alone against a sampled search; the mesh is the highest of its triangles."""
    rng = np.random.default_rng(7)
    v = rng.uniform([-5, -5, -2], [5, 5, 2], size=(24, 3))
    f = np.arange(24).reshape(8, 3)
    tool = Tool(1, kind, 4.0, corner_radius=corner)
    points = rng.uniform(-6, 6, size=(25, 2))
    whole = dc.DropCutter(v, f, tool, kernel="numpy").points(points)
    compiled = dc.DropCutter(v, f, tool, kernel="numba").points(points)
    assert compiled == pytest.approx(whole, abs=1e-9)
    profile = dc.tool_profile(tool)
    single = np.array([dc.DropCutter(v, f[j:j + 1], tool, kernel="numpy").points(points) for j in range(len(f))])
    assert whole == pytest.approx(single.max(axis=0), abs=0)
    compared = 0
    for j, face in enumerate(f):
        for point, z in zip(points, single[j]):
            brute = _brute_force(v[face], profile, point)
            if not np.isfinite(brute):      # only a sliver of the triangle under the tool: the grid missed it
                continue
            compared += 1
            assert brute <= z + 1e-9          # the exact maximum is never below a sampled point
            assert z - brute < 1e-3
    assert compared >= 40


def test_kernels_agree_on_a_random_mesh_with_every_tool():
    trimesh = pytest.importorskip("trimesh")
    rng = np.random.default_rng(3)
    mesh = trimesh.creation.icosphere(subdivisions=3, radius=10.0)
    v = np.asarray(mesh.vertices) + rng.normal(0, 0.4, size=mesh.vertices.shape)
    f = np.asarray(mesh.faces)
    x = np.linspace(-13, 13, 53)
    for tool in (Tool(1, "ball", 6.0), Tool(1, "flat", 4.0), Tool(1, "bull", 6.0, corner_radius=1.0),
                 Tool(1, "vbit", 6.0), Tool(1, "drill", 5.0)):
        a = dc.DropCutter(v, f, tool, kernel="numpy", floor=-20).grid(x, x)
        b = dc.DropCutter(v, f, tool, kernel="numba", floor=-20, bucket=0.7).grid(x, x)
        assert b == pytest.approx(a, abs=1e-9), tool.kind


def test_path_follows_the_surface_and_refines():
    v, f = icosphere(20.0, 4)
    cutter = dc.DropCutter(v, f, Tool(1, "ball", 6.0), floor=-5.0)
    path = cutter.path([[-30, 0.3], [30, 0.3]], spacing=0.5, tolerance=1e-4)
    assert path[:, :2] == pytest.approx(np.column_stack([path[:, 0], np.full(len(path), 0.3)]))
    assert path[:, 2] == pytest.approx(cutter.points(path[:, :2]), abs=1e-12)
    mid = 0.5 * (path[1:] + path[:-1])
    over = cutter.points(mid[:, :2]) - mid[:, 2]
    long_enough = np.linalg.norm(np.diff(path[:, :2], axis=0), axis=1) > 2e-3
    assert over[long_enough].max() <= 1e-4 + 1e-12
    assert np.diff(path[:, 0]).min() > 0


def test_bad_input_is_named():
    with pytest.raises(dc.DropCutterError, match="vertices"):
        dc.DropCutter(np.zeros((3, 2)), [[0, 1, 2]], Tool(1, "ball", 6.0))
    with pytest.raises(dc.DropCutterError, match="vertex 5"):
        dc.DropCutter(np.zeros((3, 3)), [[0, 1, 5]], Tool(1, "ball", 6.0))
    with pytest.raises(dc.DropCutterError, match="allowance"):
        dc.DropCutter(np.eye(3), [[0, 1, 2]], Tool(1, "ball", 6.0), allowance=-1)
    with pytest.raises(dc.DropCutterError, match="kernel"):
        dc.DropCutter(np.eye(3), [[0, 1, 2]], Tool(1, "ball", 6.0), kernel="fortran")


def test_skipping_faces_turned_down_on_a_closed_mesh_changes_nothing():
    """A closed, outward mesh is dropped on its faces that are not turned down; the same
    triangles with every face on its own vertices (not closed: all faces used) give the same tips."""
    trimesh = pytest.importorskip("trimesh")
    rng = np.random.default_rng(11)
    mesh = trimesh.creation.capsule(height=8.0, radius=5.0, count=[16, 16])
    v = np.asarray(mesh.vertices) + rng.normal(0, 0.2, size=mesh.vertices.shape)
    f = np.asarray(mesh.faces)
    assert dc.closed_outward(v, f)
    loose_v, loose_f = v[f].reshape(-1, 3), np.arange(3 * len(f)).reshape(-1, 3)
    assert not dc.closed_outward(loose_v, loose_f)
    xy = rng.uniform(-9, 9, size=(400, 2))
    for tool in (Tool(1, "ball", 4.0), Tool(1, "flat", 3.0), Tool(1, "vbit", 6.0)):
        closed = dc.DropCutter(v, f, tool, floor=-50)
        assert len(closed.mesh.tris) < len(f)
        loose = dc.DropCutter(loose_v, loose_f, tool, floor=-50)
        assert closed.points(xy) == pytest.approx(loose.points(xy), abs=1e-12)


def test_bull_nose_edge_bound_skips_only_edges_that_cannot_lift_the_tip():
    """The compiled kernel stops a bull nose's edge bisection early when a tangent bound says
    the edge stays at or below the best tip so far; otherwise it must return exactly the full
    bisection's point.  Random edges (including nearly grazing ones) against edge_best, with the
    best tip just below, at and above the edge's own maximum."""
    kernel = pytest.importorskip("kezuri.toolpath.engines.dropcutter_kernel")
    rng = np.random.default_rng(5)
    skipped = 0
    for R, rc in ((3.5, 0.5), (3.0, 1.0), (10.0, 0.01), (2.0, 1.999)):
        fr = R - rc
        for _ in range(400):
            t = R * min(1.0, abs(rng.normal(0.6, 0.4)))
            w = math.sqrt(max(R * R - t * t, 0.0))
            ua, ub = np.sort(rng.uniform(-w, w, 2)) if rng.random() < 0.5 else (-w, w)
            m = rng.normal(0, 2.0)
            z0, s0 = rng.uniform(-5, 5), rng.uniform(-3, 3)
            u = kernel.edge_best(kernel.ROUNDED, R, rc, fr, 0.0, m, t, ua, ub)
            top = z0 + m * (s0 + u) - kernel.height(kernel.ROUNDED, R, rc, fr, 0.0, min(math.sqrt(t * t + u * u), R))
            for best in (-np.inf, top - 1e-6, top - 1e-12, top, top + 1e-12, top + 1e-3, top + 1.0):
                got = kernel._bull_edge(R, rc, fr, m, t, ua, ub, z0, s0, best)
                if math.isnan(got):
                    skipped += 1
                    assert top <= best
                else:
                    assert got == u
    assert skipped > 500


def test_compiled_tips_do_not_depend_on_the_order_of_the_points():
    """Each point's tip is its own: the same, bit for bit, dropped alone, along a path or in a
    shuffled order (nothing the kernel skips may depend on its neighbours)."""
    pytest.importorskip("numba")
    trimesh = pytest.importorskip("trimesh")
    rng = np.random.default_rng(9)
    mesh = trimesh.creation.icosphere(subdivisions=3, radius=10.0)
    v = np.asarray(mesh.vertices) + rng.normal(0, 0.3, size=mesh.vertices.shape)
    f = np.asarray(mesh.faces)
    t = np.linspace(0, 1, 300)
    xy = np.column_stack([-12 + 24 * t, 6 * np.sin(7 * t)])          # a path: neighbours close together
    for tool in (Tool(1, "ball", 6.0), Tool(1, "flat", 4.0), Tool(1, "bull", 6.0, corner_radius=1.0),
                 Tool(1, "vbit", 6.0)):
        cutter = dc.DropCutter(v, f, tool, kernel="numba", floor=-20)
        along = cutter.points(xy)
        alone = np.array([cutter.points(p[None])[0] for p in xy])
        order = rng.permutation(len(xy))
        shuffled = np.empty(len(xy))
        shuffled[order] = cutter.points(xy[order])
        assert np.array_equal(along, alone) and np.array_equal(along, shuffled), tool.kind
