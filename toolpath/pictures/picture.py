"""Pictures without a renderer: a small numpy software rasteriser for the batch pictures.

An orthographic view, tilted about the X axis (0 degrees: from above; 90: from the front), shaded
triangles with a per-pixel depth test, polylines (solid or dashed) drawn over them, filled 2-D
polygons, and text in a built-in bitmap font (:mod:`.picture_font`); written as PNG bytes (zlib and
struct only).  What each workflow's picture shows, with its legend and labels, is composed in
:mod:`.picture_jobs`.

Pixel convention: pixel (i, j) is column i from the left, row j from the top, its centre at
(i + 0.5, j + 0.5); a triangle covers the pixels whose centres lie inside it or on its edges.
"""
from __future__ import annotations

import struct
import zlib

import numpy as np

from ..engines import compiled
from . import picture_font as font
from ..ir.errors import InputError

BACKGROUND = (246, 246, 243)
INK = (30, 30, 34)
MAX_FRAGMENTS = 1 << 22        # candidate pixels per rasterising step (memory bound)
SEGMENT_BATCH = 200_000       # straight segments sampled and stamped together (memory bound)


class PictureError(InputError):
    """A picture that cannot be drawn (no size, nothing to frame)."""


def png_bytes(rgb: np.ndarray) -> bytes:
    """An (h, w, 3) uint8 image as PNG bytes: 8-bit RGB, no filter, one zlib stream."""
    rgb = np.ascontiguousarray(rgb, dtype=np.uint8)
    if rgb.ndim != 3 or rgb.shape[2] != 3 or rgb.shape[0] < 1 or rgb.shape[1] < 1:
        raise PictureError(f"an image must be (height, width, 3), got {rgb.shape}")
    height, width = rgb.shape[:2]
    raw = np.concatenate([np.zeros((height, 1), np.uint8), rgb.reshape(height, width * 3)], axis=1)

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw.tobytes(), 6))
            + chunk(b"IEND", b""))


class View:
    """Orthographic projection of world points (mm) into a pixel rectangle ``area`` = (left, top,
    right, bottom), fitted so that every point of ``frame_points`` is inside it with a margin.

    The view looks along -d with d = (0, -sin t, cos t) (t = ``tilt_deg``): screen right is +X,
    screen up is (0, cos t, sin t), and a larger ``depth`` is nearer the viewer."""

    def __init__(self, frame_points, area, tilt_deg: float = 35.0, margin: float = 0.04):
        points = np.asarray(frame_points, float).reshape(-1, 3)
        points = points[np.isfinite(points).all(axis=1)]
        if not len(points):
            raise PictureError("nothing to draw: no finite point to frame")
        t = np.radians(tilt_deg)
        self.up = np.array([0.0, np.cos(t), np.sin(t)])
        self.toward = np.array([0.0, -np.sin(t), np.cos(t)])
        left, top, right, bottom = area
        if right - left < 8 or bottom - top < 8:
            raise PictureError(f"the drawing area {area} is too small")
        sx, sy = points[:, 0], _along(points, self.up)
        span_x, span_y = max(np.ptp(sx), 1e-9), max(np.ptp(sy), 1e-9)
        self.scale = (1 - 2 * margin) * min((right - left) / span_x, (bottom - top) / span_y)
        self.cx, self.cy = (sx.min() + sx.max()) / 2, (sy.min() + sy.max()) / 2
        self.px, self.py = (left + right) / 2, (top + bottom) / 2
        self.area = area

    def project(self, points) -> tuple:
        """(x pixels, y pixels (down), depth mm (larger is nearer)) of (n, 3) points."""
        points = np.asarray(points, float).reshape(-1, 3)
        x = self.px + (points[:, 0] - self.cx) * self.scale
        y = self.py - (_along(points, self.up) - self.cy) * self.scale
        return x, y, _along(points, self.toward)


def _along(points: np.ndarray, direction) -> np.ndarray:
    """(n,) components of (n, 3) points along ``direction``, without BLAS (whose helper threads
    spin on a CPU after every large product)."""
    return points[:, 0] * direction[0] + points[:, 1] * direction[1] + points[:, 2] * direction[2]


class Picture:
    """An RGB canvas with a depth buffer; every text drawn is kept in :attr:`texts`."""

    def __init__(self, width: int = 1200, height: int = 800, background=BACKGROUND):
        if not (isinstance(width, (int, np.integer)) and isinstance(height, (int, np.integer))
                and 16 <= width <= 8192 and 16 <= height <= 8192):
            raise PictureError(f"picture size must be whole pixels, 16..8192, got {width} x {height}")
        self.width, self.height = int(width), int(height)
        self.rgb = np.empty((self.height, self.width, 3), np.float32)
        self.rgb[:] = background
        self.depth = np.full((self.height, self.width), -np.inf)
        self.texts: list = []

    # ----- triangles ----------------------------------------------------------------------
    def triangles(self, view: View, vertices, faces, colours, light=(-0.35, -0.45, 0.82)):
        """Shaded triangles with a depth test.  ``colours``: one RGB (0..255) for all, or one
        per face (f, 3).  Flat shading: 0.45 + 0.55 |n . light| (both sides lit)."""
        vertices = np.asarray(vertices, float).reshape(-1, 3)
        faces = np.asarray(faces, np.int64).reshape(-1, 3)
        if not len(faces):
            return
        colours = np.broadcast_to(np.asarray(colours, np.float32), (len(faces), 3))
        # the normals coordinate by coordinate (as np.cross and np.linalg.norm would, without
        # their reductions over rows of three)
        v = [np.ascontiguousarray(vertices[:, axis]) for axis in range(3)]
        f0, f1, f2 = (np.ascontiguousarray(faces[:, corner]) for corner in range(3))
        ax, ay, az = (w[f1] - w[f0] for w in v)
        bx, by, bz = (w[f2] - w[f0] for w in v)
        nx, ny, nz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
        length = np.sqrt(nx * nx + ny * ny + nz * nz)
        light = np.asarray(light, float) / np.linalg.norm(light)
        shade = 0.45 + 0.55 * np.abs(nx * light[0] + ny * light[1] + nz * light[2]) / np.where(length > 0, length,
                                                                                                1.0)
        x, y, z = view.project(vertices)
        pixel, depth, face = rasterise(x, y, z, faces, self.width, self.height)
        flat_depth = self.depth.reshape(-1)
        nearer = depth > flat_depth[pixel]
        pixel, depth, face = pixel[nearer], depth[nearer], face[nearer]
        flat_depth[pixel] = depth
        shaded = colours * shade[:, None].astype(np.float32)     # per face, then per pixel
        self.rgb.reshape(-1, 3)[pixel] = shaded[face]

    # ----- lines ---------------------------------------------------------------------------
    def segments(self, view: View, a, b, colour, width: int = 2, dash: float = 0.0, over: bool = True):
        """Straight segments a[k] -> b[k] (world mm).  ``dash`` > 0: dashes and gaps of that many
        pixels, counted along the whole run.  ``over``: drawn over the solids (toolpaths inside
        the stock stay visible); else hidden where a solid is nearer."""
        a, b = np.asarray(a, float).reshape(-1, 3), np.asarray(b, float).reshape(-1, 3)
        if not len(a):
            return
        if not dash and len(a) > SEGMENT_BATCH:     # each segment's pixels are its own: drawn a batch at a time
            for k in range(0, len(a), SEGMENT_BATCH):
                self.segments(view, a[k:k + SEGMENT_BATCH], b[k:k + SEGMENT_BATCH], colour, width, dash, over)
            return
        ax, ay, az = view.project(a)
        bx, by, bz = view.project(b)
        length = np.hypot(bx - ax, by - ay)
        count = np.ceil(length).astype(np.int64) + 1
        owner = np.repeat(np.arange(len(a)), count)
        first = np.cumsum(count) - count
        t = (np.arange(len(owner)) - first[owner]) / np.maximum(count[owner] - 1, 1)
        x = ax[owner] + t * (bx - ax)[owner]
        y = ay[owner] + t * (by - ay)[owner]
        z = az[owner] + t * (bz - az)[owner]
        if dash > 0:
            along = (np.cumsum(length) - length)[owner] + t * length[owner]
            keep = (along // dash) % 2 == 0
            x, y, z = x[keep], y[keep], z[keep]
        self._stamp(x, y, z, colour, width, over)

    def polyline(self, view: View, points, colour, width: int = 2, dash: float = 0.0, closed: bool = False,
                 over: bool = True):
        points = np.asarray(points, float).reshape(-1, 3)
        if closed and len(points) > 1:
            points = np.vstack([points, points[:1]])
        if len(points) > 1:
            self.segments(view, points[:-1], points[1:], colour, width, dash, over)

    def _stamp(self, x, y, z, colour, width: int, over: bool):
        offsets = np.arange(width) - (width - 1) // 2
        i = (np.floor(x)[:, None, None] + offsets[None, :, None]).astype(np.int64)
        j = (np.floor(y)[:, None, None] + offsets[None, None, :]).astype(np.int64)
        i, j = np.broadcast_arrays(i, j)
        zz = np.broadcast_to(z[:, None, None], i.shape)
        inside = (i >= 0) & (i < self.width) & (j >= 0) & (j < self.height)
        pixel = (j * self.width + i)[inside]
        if not over:
            seen = zz[inside] >= self.depth.reshape(-1)[pixel] - 1e-6 * max(1.0, abs(float(np.max(z, initial=1))))
            pixel = pixel[seen]
        self.rgb.reshape(-1, 3)[pixel] = colour

    # ----- 2-D fills, boxes, text ---------------------------------------------------------
    def polygon(self, view: View, outline, colour, z: float = 0.0):
        """Fill a closed outline (k, 2) lying in the plane z (even-odd rule), no depth test."""
        outline = np.asarray(outline, float).reshape(-1, 2)
        if len(outline) < 3:
            return
        x, y, _ = view.project(np.column_stack([outline, np.full(len(outline), z)]))
        x1, y1 = np.roll(x, -1), np.roll(y, -1)
        rows = np.arange(max(int(np.floor(y.min())), 0), min(int(np.ceil(y.max())) + 1, self.height))
        flat = self.rgb.reshape(-1, 3)
        for row in rows:
            centre = row + 0.5
            crossing = (y <= centre) != (y1 <= centre)
            if not crossing.any():
                continue
            xs = np.sort(x[crossing] + (centre - y[crossing]) * (x1 - x)[crossing] / (y1 - y)[crossing])
            for start, end in zip(xs[0::2], xs[1::2]):
                i0, i1 = max(int(np.ceil(start - 0.5)), 0), min(int(np.floor(end - 0.5)), self.width - 1)
                if i1 >= i0:
                    flat[row * self.width + i0:row * self.width + i1 + 1] = colour

    def box(self, left: int, top: int, right: int, bottom: int, colour):
        """Fill the pixel rectangle [left, right) x [top, bottom)."""
        self.rgb[max(top, 0):max(bottom, 0), max(left, 0):max(right, 0)] = colour

    def text(self, left: int, top: int, string: str, colour=INK, scale: int = 2) -> int:
        """Draw one line of text with its top-left corner at (left, top); returns its width."""
        self.texts.append(string)
        mask = font.text_mask(string, scale)
        h = min(mask.shape[0], self.height - top)
        w = min(mask.shape[1], self.width - left)
        if h > 0 and w > 0 and left >= 0 and top >= 0:
            self.rgb[top:top + h, left:left + w][mask[:h, :w]] = colour
        return mask.shape[1]

    def image(self) -> np.ndarray:
        return np.clip(np.rint(self.rgb), 0, 255).astype(np.uint8)

    def png(self) -> bytes:
        return png_bytes(self.image())


def _least(corners: np.ndarray) -> np.ndarray:
    """corners.min(axis=1) of an (f, 3) array, three columns at a time (a reduction over rows
    of three is slow)."""
    return np.minimum(np.minimum(corners[:, 0], corners[:, 1]), corners[:, 2])


def _most(corners: np.ndarray) -> np.ndarray:
    return np.maximum(np.maximum(corners[:, 0], corners[:, 1]), corners[:, 2])


def rasterise(x, y, z, faces, width: int, height: int) -> tuple:
    """The nearest fragment of every covered pixel: (flat pixel index, depth, face index); where
    fragments tie for nearest (on an edge two triangles share), each is returned (the numba
    kernel returns the last triangle's, the one drawn on top either way).

    Scan conversion, vectorised over all triangles at once: every (triangle, pixel row) pair
    gets the span of pixel centres between the triangle's edges on that row; depth comes from
    the triangle's plane.  Work is proportional to rows plus covered pixels."""
    faces = np.asarray(faces, np.int64)
    fx, fy, fz = x[faces], y[faces], z[faces]
    lowest, highest = _least(fy), _most(fy)
    j0 = np.clip(np.ceil(lowest - 0.5), 0, height).astype(np.int64)
    j1 = np.clip(np.floor(highest - 0.5), -1, height - 1).astype(np.int64)
    area = (fx[:, 1] - fx[:, 0]) * (fy[:, 2] - fy[:, 0]) - (fx[:, 2] - fx[:, 0]) * (fy[:, 1] - fy[:, 0])
    live = (j1 >= j0) & (_most(fx) >= 0) & (_least(fx) < width) & (np.abs(area) > 1e-12) & np.isfinite(area)
    kernel = compiled.kernel_module("auto", f"{__package__}.picture_kernel", PictureError, "picture kernel")
    if kernel is not None:
        nearest, owner = np.full(width * height, -np.inf), np.full(width * height, -1, np.int64)
        kernel.scan(fx, fy, fz, live, width, height, nearest, owner)
        pixel = np.flatnonzero(owner >= 0)
        return pixel, nearest[pixel], owner[pixel]
    pixels, depths, owners = [], [], []
    chosen = np.flatnonzero(live)
    rows = j1 - j0 + 1
    bounds = np.searchsorted(np.cumsum(rows[chosen]), np.arange(0, rows[chosen].sum() + MAX_FRAGMENTS // 8,
                                                                    MAX_FRAGMENTS // 8)[1:])
    for f in np.split(chosen, np.unique(bounds[bounds < len(chosen)])):
        if not len(f):
            continue
        X, Y, Z, A = fx[f], fy[f], fz[f], area[f]
        # depth plane z = Z0 + gx (x - X0) + gy (y - Y0)
        dz1, dz2 = Z[:, 1] - Z[:, 0], Z[:, 2] - Z[:, 0]
        dx1, dx2, dy1, dy2 = X[:, 1] - X[:, 0], X[:, 2] - X[:, 0], Y[:, 1] - Y[:, 0], Y[:, 2] - Y[:, 0]
        gx, gy = (dz1 * dy2 - dz2 * dy1) / A, (dz2 * dx1 - dz1 * dx2) / A
        count = rows[f]
        owner = np.repeat(np.arange(len(f)), count)
        row = j0[f][owner] + (np.arange(len(owner)) - (np.cumsum(count) - count)[owner])
        centre = row + 0.5
        left = np.full(len(owner), np.inf)
        right = np.full(len(owner), -np.inf)
        for p, q in ((0, 1), (1, 2), (2, 0)):
            yp, yq, xp, xq = Y[owner, p], Y[owner, q], X[owner, p], X[owner, q]
            lo, hi = np.minimum(yp, yq), np.maximum(yp, yq)
            crosses = (centre >= lo) & (centre <= hi) & (hi > lo)
            at = xp + (centre - yp) * (xq - xp) / np.where(hi > lo, yq - yp, 1.0)
            left = np.where(crosses, np.minimum(left, at), left)
            right = np.where(crosses, np.maximum(right, at), right)
        i0 = np.clip(np.ceil(left - 0.5), 0, width).astype(np.int64)
        i1 = np.clip(np.floor(right - 0.5), -1, width - 1).astype(np.int64)
        span = np.maximum(i1 - i0 + 1, 0)
        pixel_owner = np.repeat(np.arange(len(owner)), span)
        column = i0[pixel_owner] + (np.arange(len(pixel_owner)) - (np.cumsum(span) - span)[pixel_owner])
        tri = owner[pixel_owner]
        cy = centre[pixel_owner]
        pixels.append(row[pixel_owner] * width + column)
        depths.append(Z[tri, 0] + gx[tri] * (column + 0.5 - X[tri, 0]) + gy[tri] * (cy - Y[tri, 0]))
        owners.append(f[tri])
    if not pixels:
        return np.zeros(0, np.int64), np.zeros(0), np.zeros(0, np.int64)
    pixel, depth, owner = np.concatenate(pixels), np.concatenate(depths), np.concatenate(owners)
    nearest = np.full(width * height, -np.inf)
    np.maximum.at(nearest, pixel, depth)          # no sort: the nearest depth of every pixel
    won = depth == nearest[pixel]                 # (fragments tied at a shared edge: any one of them)
    return pixel[won], depth[won], owner[won]
