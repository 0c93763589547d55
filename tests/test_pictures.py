"""The batch pictures, drawn without a renderer (toolpath/picture*.py), checked by numbers.

Expected pixel positions come from the View's documented contract (the frame's extent fitted to
the drawing area with a 4 % margin, X to the right, the up vector (0, cos t, sin t)), computed
here by hand; the PNG is decoded by Blender's own image loader where bpy is installed.
"""
import os
import zlib

import numpy as np
import pytest

from kezuri.toolpath.pictures import picture_font as font
from kezuri.toolpath.pictures import picture_jobs as pj
from kezuri.toolpath.pictures.picture import BACKGROUND, INK, Picture, PictureError, View, png_bytes
from kezuri.toolpath.ir.program import FEED, RAPID, Operation, Tool
from kezuri.toolpath.simulate import BoxStock, CylinderStock, simulate

W, H = 1200, 800
AREA = (0, pj.HEADER, W, H - pj.LEGEND)


def pocket_operation():
    """Rapid in, plunge 1.5 mm, an L of cuts, a feed retract into the air, a feed move in the
    air, a rapid away to (90, 20)."""
    kind = [RAPID, RAPID, FEED, FEED, FEED, FEED, FEED, RAPID]
    xyz = [(10, 10, 20), (10, 10, 2), (10, 10, -1.5), (60, 10, -1.5), (60, 40, -1.5), (60, 40, 5),
           (80, 40, 5), (90, 20, 20)]
    feed = [np.nan if k == RAPID else 500.0 for k in kind]
    return Operation("pocket", Tool(1, "flat", 3.0), 10000, kind, xyz, feed, start=np.array([10.0, 10.0, 20.0]))


def top_view_pixel(x, y, frame_x, frame_y):
    """Pixel of world (x, y) in a top view (tilt 0) that frames [frame_x] x [frame_y] in AREA."""
    left, top, right, bottom = AREA
    scale = 0.92 * min((right - left) / (frame_x[1] - frame_x[0]), (bottom - top) / (frame_y[1] - frame_y[0]))
    px = (left + right) / 2 + (x - sum(frame_x) / 2) * scale
    py = (top + bottom) / 2 - (y - sum(frame_y) / 2) * scale
    return int(np.floor(px)), int(np.floor(py))


def colour_near(image, px, py, colour, reach=2) -> bool:
    patch = image[py - reach:py + reach + 1, px - reach:px + reach + 1].reshape(-1, 3)
    return bool(np.any(np.all(patch == colour, axis=1)))


def test_move_roles_of_a_known_pocket():
    op = pocket_operation()
    roles = pj.move_roles(op, BoxStock(0, 0, -10, 100, 60, 0))
    # rapid, rapid, plunge (2 -> -1.5 straight down), cut, cut, retract at feed (link), link in air
    assert roles.tolist() == [pj.RAPID_ROLE, pj.RAPID_ROLE, pj.PLUNGE, pj.CUT, pj.CUT, pj.LINK, pj.LINK,
                              pj.RAPID_ROLE]


def test_toolpath_picture_colours_legend_and_labels():
    stock = BoxStock(0, 0, -10, 100, 60, 0)
    picture = pj.toolpath_picture([pocket_operation()], stock, title="POCKET", tilt_deg=0.0)
    image = picture.image()
    frame_x, frame_y = (0, 100), (0, 60)       # stock and moves all inside 0..100 x 0..60 seen from above
    colours = {name: np.array(c, np.uint8) for name, c in pj.ROLE_COLOURS.items()}
    # the rapid from (80, 40) to (90, 20): dashed, 6 px on, 6 off: of three points along it
    # 0.4 mm (about 4 px) apart, one is on a dash
    assert any(colour_near(image, *top_view_pixel(85 + k, 30 - 2 * k, frame_x, frame_y), colours["rapid"], 1)
               for k in (-0.2, 0, 0.2))
    # the feed move in the air from (60, 40) to (80, 40) at z 5: a link
    assert colour_near(image, *top_view_pixel(70, 40, frame_x, frame_y), colours["link"])
    # a cut along y = 10
    assert colour_near(image, *top_view_pixel(35, 10, frame_x, frame_y), colours["cut"])
    assert colour_near(image, *top_view_pixel(60, 25, frame_x, frame_y), colours["cut"])
    # the plunge at (10, 10) is drawn over the rapids (3 px wide)
    assert colour_near(image, *top_view_pixel(10, 10, frame_x, frame_y), colours["plunge"])
    # the legend: a swatch of every role in the bottom strip, and its labels
    legend = image[H - pj.LEGEND:]
    for name in pj.ROLES:
        assert np.any(np.all(legend == colours[name], axis=2)), name
        assert pj.ROLE_LABELS[name] in picture.texts
    # deepest cut: the stock's top is z 0, the lowest feed move z -1.5
    assert "DEEPEST CUT 1.5 MM" in picture.texts and "STOCK 100 x 60 x 10 MM" in picture.texts


def test_a_place_left_uncut_is_marked_red_with_its_label_and_counted_in_the_legend():
    stock = BoxStock(0, 0, -10, 100, 60, 0)
    marks = [(30.0, 45.0, 0.0, "UNCUT 'E' 0.42 MM2")]
    red = np.array(pj.UNCUT_COLOUR, np.uint8)
    for picture in (pj.toolpath_picture([pocket_operation()], stock, title="POCKET", tilt_deg=0.0, marks=marks),
                    pj.simulation_picture(simulate([pocket_operation()], stock, cell=0.5), tilt_deg=0.0,
                                          marks=marks)):
        image = picture.image()
        px, py, _ = picture.view.project([(30.0, 45.0, 0.0)])
        cx, cy, r = int(round(px[0])), int(round(py[0])), pj.MARK_PX
        # the square's four sides are red, its inside is not painted
        for x, y in ((cx, cy - r + 1), (cx, cy + r - 2), (cx - r + 1, cy), (cx + r - 2, cy)):
            assert np.all(image[y, x] == red), (x, y)
        assert not np.all(image[cy, cx] == red)
        assert "UNCUT 'E' 0.42 MM2" in picture.texts
    assert "LEFT UNCUT (1)" in pj.toolpath_picture([pocket_operation()], stock, marks=marks).texts
    assert not any("UNCUT" in text for text in pj.toolpath_picture([pocket_operation()], stock).texts)


def test_text_is_drawn_with_the_font():
    picture = Picture(200, 40)
    width = picture.text(3, 5, "DEEPEST CUT 1.5 MM", INK, 2)
    mask = font.text_mask("DEEPEST CUT 1.5 MM", 2)
    assert width == 6 * 2 * len("DEEPEST CUT 1.5 MM") and mask.shape == (14, width)
    drawn = np.all(picture.image()[5:19, 3:3 + min(width, 197)] == INK, axis=2)
    assert np.array_equal(drawn, mask[:, :min(width, 197)])
    # every glyph differs from every other: the labels can be read
    bitmaps = {c: g.tobytes() for c, g in font.GLYPHS.items()}
    assert len(set(bitmaps.values())) == len(bitmaps)


def drawn_extent(image):
    """Rows and columns of the drawing area that hold anything but the background."""
    area = image[AREA[1]:AREA[3]]
    used = np.any(area != np.array(BACKGROUND, np.uint8), axis=2)
    rows, cols = np.flatnonzero(used.any(axis=1)), np.flatnonzero(used.any(axis=0))
    return used, rows, cols


@pytest.mark.parametrize("tilt", [35.0, 72.0])
def test_a_tall_bar_is_framed_whole(tilt):
    """A bar 40 mm across and 120 mm long (the turn-mill case that was cropped): nothing touches
    the edge of the drawing area, and the bar fills most of one direction of it."""
    stock = CylinderStock(20.0, 120.0, 0.0)
    op = Operation("groove", Tool(1, "ball", 4.0), 8000, [RAPID, FEED, FEED], [(25, 0, -30), (18, 0, -30), (18, 0, -60)],
                   [np.nan, 300, 300], start=np.array([25.0, 0.0, 10.0]))
    picture = pj.toolpath_picture([op], stock, tilt_deg=tilt)
    used, rows, cols = drawn_extent(picture.image())
    assert not used[0].any() and not used[-1].any() and not used[:, 0].any() and not used[:, -1].any()
    height, width = AREA[3] - AREA[1], AREA[2] - AREA[0]
    assert (rows[-1] - rows[0]) / height > 0.85 or (cols[-1] - cols[0]) / width > 0.85
    # every corner of the bar's bounding box projects inside the area (hand-built projection)
    t = np.radians(tilt)
    corners = pj.stock_corners(stock)
    screen_up = corners[:, 1] * np.cos(t) + corners[:, 2] * np.sin(t)
    view = picture.view
    px = view.px + (corners[:, 0] - view.cx) * view.scale
    py = view.py - (screen_up - view.cy) * view.scale
    assert np.all((px >= AREA[0]) & (px <= AREA[2]) & (py >= AREA[1]) & (py <= AREA[3]))


def test_simulation_picture_spreads_the_colours_over_the_jobs_depth():
    """A 1 mm deep pocket in a 20 mm thick plate: the pocket floor gets the deepest colour of
    the ramp, the uncut top the lightest (not one beige for both, as when the range was the
    plate's thickness)."""
    stock = BoxStock(0, 0, -20, 40, 40, 0)
    kind = [RAPID, FEED] + [FEED] * 4
    xyz = [(15, 15, 5), (15, 15, -1), (25, 15, -1), (25, 25, -1), (15, 25, -1), (15, 15, -1)]
    op = Operation("p", Tool(1, "flat", 6.0), 9000, kind, xyz, [np.nan] + [300] * 5)
    result = simulate([op], stock, cell=0.25, kernel="numpy")
    picture = pj.simulation_picture(result, "P", tilt_deg=0.0)
    assert picture.deepest == pytest.approx(1.0, abs=1e-6)
    assert "DEEPEST CUT 1 MM" in picture.texts
    image = picture.image().astype(int)
    floor = image[top_view_pixel(15, 20, (0, 40), (0, 40))[::-1]]     # on the path (the ring it cuts)
    top = image[top_view_pixel(4, 4, (0, 40), (0, 40))[::-1]]
    # flat shading from above: both lit alike, so the colours differ by the ramp alone
    shade = 0.45 + 0.55 * 0.82 / np.linalg.norm([-0.35, -0.45, 0.82])
    assert np.allclose(floor, pj.DEPTH_RAMP[-1] * shade, atol=2)
    assert np.allclose(top, pj.DEPTH_RAMP[0] * shade, atol=2)


def test_sheet_picture_fills_faces_and_dashes_bend_lines():
    outline = np.array([(0, 0), (100, 0), (100, 50), (0, 50)], float)
    pattern = dict(outline=outline, bends=[((50, 0), (50, 50))], contour=None, name="P")
    picture = pj.sheet_picture([pattern], "SHEET")
    image = picture.image()
    fill, bend = np.array(pj.PATTERN_COLOURS[0], np.uint8), np.array(pj.BEND_COLOUR, np.uint8)
    assert np.all(image[top_view_pixel(25, 25, (0, 100), (0, 50))[::-1]] == fill)
    column = [image[top_view_pixel(50, y, (0, 100), (0, 50))[::-1]] for y in np.linspace(5, 45, 60)]
    on = [bool(np.all(c == bend)) for c in column]
    assert 0.3 < np.mean(on) < 0.7       # dashed: about half on
    assert "P: 100 x 50 MM" in picture.texts and "BEND LINE (DASHED)" in picture.texts


def test_png_bytes_are_a_valid_png():
    rgb = (np.arange(5 * 7 * 3) % 256).astype(np.uint8).reshape(5, 7, 3)
    data = png_bytes(rgb)
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    chunks, at = [], 8
    while at < len(data):
        length = int.from_bytes(data[at:at + 4], "big")
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + length]
        assert int.from_bytes(data[at + 8 + length:at + 12 + length], "big") == zlib.crc32(kind + body)
        chunks.append((kind, body))
        at += 12 + length
    assert [k for k, _ in chunks] == [b"IHDR", b"IDAT", b"IEND"]
    assert chunks[0][1] == (7).to_bytes(4, "big") + (5).to_bytes(4, "big") + bytes([8, 2, 0, 0, 0])
    raw = np.frombuffer(zlib.decompress(chunks[1][1]), np.uint8).reshape(5, 1 + 7 * 3)
    assert np.all(raw[:, 0] == 0) and np.array_equal(raw[:, 1:].reshape(5, 7, 3), rgb)


def test_blender_reads_the_png(tmp_path):
    bpy = pytest.importorskip("bpy")
    picture = pj.toolpath_picture([pocket_operation()], BoxStock(0, 0, -10, 100, 60, 0), title="POCKET")
    path = tmp_path / "p.png"
    path.write_bytes(picture.png())
    image = bpy.data.images.load(str(path))
    try:
        assert tuple(image.size) == (W, H)
        pixels = np.empty(W * H * image.channels, np.float32)
        image.pixels.foreach_get(pixels)
        read = np.round(pixels.reshape(H, W, image.channels)[::-1, :, :3] * 255).astype(np.uint8)
        assert np.array_equal(read, picture.image())
    finally:
        bpy.data.images.remove(image)


def test_bad_picture_input_is_refused():
    with pytest.raises(PictureError, match="16..8192"):
        Picture(10, 5000)
    with pytest.raises(PictureError, match="no finite point"):
        View(np.full((2, 3), np.nan), AREA)
    with pytest.raises(PictureError, match="no pattern"):
        pj.sheet_picture([], "EMPTY")


def test_a_failed_picture_writes_nothing(tmp_path):
    pytest.importorskip("bpy")
    from kezuri.operators import preview

    target = tmp_path / "elbow.png"
    target.write_bytes(b"old")
    with pytest.raises(PictureError):
        preview.sheet_png(str(target), [], "EMPTY")
    assert target.read_bytes() == b"old" and sorted(os.listdir(tmp_path)) == ["elbow.png"]
    written = preview.sheet_png(str(target), [dict(outline=np.array([(0, 0), (9, 0), (9, 4)], float))], "T")
    assert written == str(target) and target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(os.listdir(tmp_path)) == ["elbow.png"]


def test_warm_kernels_leaves_nothing_to_compile_for_a_real_job():
    """After the warm-up, simulating a different job (other sizes, every tool shape, a radial
    move) adds no compiled signature to any numba kernel."""
    numba = pytest.importorskip("numba")
    from kezuri.toolpath.engines import dropcutter_kernel, warmup
    from kezuri.toolpath.pictures import picture_kernel
    from kezuri.toolpath.simulate import kernel

    def signatures():
        return {(m.__name__, name): len(f.signatures) for m in (kernel, dropcutter_kernel, picture_kernel)
                for name, f in vars(m).items() if isinstance(f, numba.core.registry.CPUDispatcher)}
    ran = warmup.warm_kernels()
    assert "radius map" in ran and all(f"heightfield {k}" in ran for k in warmup.KINDS)
    before = signatures()
    ops = [warmup._box_operation(k, i) for i, k in enumerate(warmup.KINDS, 1)]
    simulate(ops, BoxStock(-1, -1, -4, 9, 9, 0), cell=0.2, kernel="numba")
    simulate([warmup._radial_operation()], CylinderStock(11.0, 8.0, 0.0), cell=0.3, kernel="numba")
    pj.simulation_picture(simulate(ops[:1], BoxStock(-1, -1, -4, 9, 9, 0), cell=0.2), "WARM")
    assert "picture" in ran and signatures() == before


def test_viewport_depth_colours_span_the_jobs_depth(empty_scene):
    """The simulated stock's "Kezuri depth" colours: the 1 mm pocket floor in a 20 mm plate is
    the ramp's deepest colour, the uncut top its lightest (issue #21: was almost uniform)."""
    from kezuri.operators import convert, simview

    scene = empty_scene
    stock = BoxStock(0, 0, -20, 40, 40, 0)
    op = Operation("p", Tool(1, "flat", 6.0), 9000, [RAPID] + [FEED] * 5,
                   [(15, 15, 5), (15, 15, -1), (25, 15, -1), (25, 25, -1), (15, 25, -1), (15, 15, -1)],
                   [np.nan] + [300] * 5)
    result = simulate([op], stock, cell=0.25, kernel="numpy")
    job = simview.SimulationJob(result, convert.WorkFrame(1.0, (0.0, 0.0, 0.0)), "pocket")
    obj = simview.show_simulation(scene, job)
    colours = np.empty(len(obj.data.vertices) * 4, np.float32)
    obj.data.color_attributes["Kezuri depth"].data.foreach_get("color", colours)
    colours = colours.reshape(-1, 4)[:, :3]
    co = np.empty(len(obj.data.vertices) * 3)
    obj.data.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    floor = np.isclose(co[:, 2], -1.0) & (np.hypot(co[:, 0] - 15, co[:, 1] - 20) < 1.0)
    top = np.isclose(co[:, 2], 0.0) & (co[:, 0] < 6) & (co[:, 1] < 6)
    assert floor.any() and top.any()
    assert np.allclose(colours[floor], pj.DEPTH_RAMP[-1] / 255, atol=1e-3)
    assert np.allclose(colours[top], pj.DEPTH_RAMP[0] / 255, atol=1e-3)


def test_fill_mesh_matches_blenders_from_pydata(empty_scene):
    """The bulk-array mesh fill gives the same mesh as Blender's own ``from_pydata`` (the
    reference), for triangles given as an array and for mixed polygons given as lists."""
    import bpy

    from kezuri.operators import convert

    n = 30
    grid = np.stack(np.meshgrid(np.arange(n), np.arange(n)), -1).reshape(-1, 2).astype(float)
    vertices = np.column_stack([grid, np.sin(grid[:, 0] / 3)])
    a = (np.arange(n - 1)[:, None] * n + np.arange(n - 1)[None, :]).ravel()
    triangles = np.vstack([np.column_stack([a, a + 1, a + n + 1]), np.column_stack([a, a + n + 1, a + n])])
    mixed = [[0, 1, n + 1, n], [1, 2, n + 2], [2, 3, 4, n + 4, n + 3, n + 2]]
    for faces in (triangles, mixed):
        reference, ours = bpy.data.meshes.new("reference"), bpy.data.meshes.new("ours")
        reference.from_pydata(vertices.tolist(), [], [list(map(int, f)) for f in faces])
        convert.fill_mesh(ours, vertices, faces)

        def read(mesh, collection, attribute, count, dtype):
            values = np.empty(count, dtype)
            getattr(mesh, collection).foreach_get(attribute, values)
            return values
        for collection, attribute, size, dtype in (("vertices", "co", 3, np.float32), ("loops", "vertex_index", 1, np.int32),
                                                   ("polygons", "loop_total", 1, np.int32),
                                                   ("polygons", "use_smooth", 1, bool)):
            count = len(getattr(reference, collection)) * size
            assert len(getattr(ours, collection)) * size == count
            assert np.array_equal(read(reference, collection, attribute, count, dtype),
                                  read(ours, collection, attribute, count, dtype)), (collection, attribute)
        assert sorted(e.key for e in reference.edges) == sorted(e.key for e in ours.edges)
        assert not ours.validate()
        bpy.data.meshes.remove(reference)
        bpy.data.meshes.remove(ours)


def test_stepnc_pocket_links_are_marked_and_drawn_as_links():
    """Two passes at depth inside a pocket region: the planner joins them by a feed move at depth
    (a link, not a cut).  It is marked in the IR and drawn green; the passes stay blue."""
    from manifold3d import CrossSection

    from kezuri.toolpath.operations.stepnc.motion import Motion
    region = CrossSection.square((80.0, 40.0)).translate((10.0, 10.0))
    motion = Motion(clearance_z=10.0, feed=400.0, region=region, radius=3.0)
    first, second = np.array([(20.0, 20.0), (80.0, 20.0)]), np.array([(80.0, 40.0), (20.0, 40.0)])
    motion.cut([first, second], z=-2.0, cleared_z=0.0)
    op = motion.operation("pocket", Tool(1, "flat", 6.0), 8000, True, 20.0, False, "")
    # the link: the feed move from the first pass's end (80, 20) to the second's start (80, 40) at z -2
    ends = op.start_points()
    link = (op.kind == FEED) & np.all(np.isclose(ends, (80, 20, -2)), axis=1) & \
        np.all(np.isclose(op.xyz, (80, 40, -2)), axis=1)
    assert link.sum() == 1 and op.links.tolist() == link.tolist()
    stock = BoxStock(0, 0, -10, 100, 60, 0)
    assert pj.move_roles(op, stock)[link].tolist() == [pj.LINK]
    assert pj.move_roles(op.replace(links=None), stock)[link].tolist() == [pj.CUT]   # in the material: a cut by shape
    image = pj.toolpath_picture([op], stock, title="POCKET", tilt_deg=0.0).image()
    colours = {name: np.array(c, np.uint8) for name, c in pj.ROLE_COLOURS.items()}
    frame_x, frame_y = (0, 100), (0, 60)
    assert colour_near(image, *top_view_pixel(80, 30, frame_x, frame_y), colours["link"])
    assert not colour_near(image, *top_view_pixel(80, 30, frame_x, frame_y), colours["cut"])
    assert colour_near(image, *top_view_pixel(50, 20, frame_x, frame_y), colours["cut"])
    assert colour_near(image, *top_view_pixel(50, 40, frame_x, frame_y), colours["cut"])


def test_links_must_mark_feed_moves():
    kind, xyz, feed = [RAPID, FEED], [(0, 0, 5), (1, 0, 0)], [np.nan, 100.0]
    with pytest.raises(ValueError, match="links must mark feed moves"):
        Operation("o", Tool(1, "flat", 3.0), 1000, kind, xyz, feed, links=[True, False])
    with pytest.raises(ValueError, match="links must mark feed moves"):
        Operation("o", Tool(1, "flat", 3.0), 1000, kind, xyz, feed, links=[False])
    assert Operation("o", Tool(1, "flat", 3.0), 1000, kind, xyz, feed, links=[False, True]).links.tolist() == [False, True]


def test_compiled_rasteriser_draws_the_numpy_paths_pixels(monkeypatch):
    """The numba scan conversion against the numpy one (KEZURI_NO_NUMBA=1): 3,000 random
    triangles, many sharing edges and crossing each other and the picture's border, a cube in
    front: the same pixels, depths and colours."""
    rng = np.random.default_rng(7)
    corners = rng.uniform(-60.0, 60.0, (3000, 3))
    vertices = np.vstack([corners, rng.uniform(-60.0, 60.0, (1000, 3))])
    faces = np.column_stack([rng.integers(0, 4000, 3000), rng.integers(0, 4000, 3000), rng.integers(0, 4000, 3000)])
    cube = np.array([(x, y, z) for x in (-5, 5) for y in (-5, 5) for z in (-5, 5)], float)
    cube_faces = np.array([(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
                           (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]) + len(vertices)
    vertices, faces = np.vstack([vertices, cube]), np.vstack([faces, cube_faces])
    colours = rng.uniform(0, 255, (len(faces), 3))
    view = View(vertices[:50] * 0.8, (0, 0, 300, 200), 35.0)
    drawn = []
    for no_numba in ("0", "1"):
        monkeypatch.setenv("KEZURI_NO_NUMBA", no_numba)
        canvas = Picture(300, 200)
        canvas.triangles(view, vertices, faces, colours)
        drawn.append((canvas.rgb.copy(), canvas.depth.copy()))
    (rgb, depth), (rgb_numpy, depth_numpy) = drawn
    assert np.isfinite(depth).mean() > 0.5
    assert np.array_equal(depth, depth_numpy)
    assert np.array_equal(rgb, rgb_numpy)
