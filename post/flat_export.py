"""Flat patterns for laser and plasma users: DXF (R12 ASCII, written by hand) and SVG (mm).

Layers: PATTERN holds the developed outline(s) (closed POLYLINEs) and the bend lines (LINEs, the
inner triangle edges where the sheet is bent); CUT holds the tool-compensated contour(s) (closed
POLYLINEs).  Contours are (k, 2) arrays in mm, implicitly closed.

The DXF is the smallest R12 file common readers accept: a HEADER with $ACADVER AC1009 and the drawing
extents, a TABLES section defining the line type CONTINUOUS and the layers, and the ENTITIES.  No
handles ($HANDLING 0), as R12 allows.  R12 has no unit field; the numbers are millimetres.
"""
from __future__ import annotations

import numpy as np

from ..toolpath.errors import InputError


LAYER_PATTERN = "PATTERN"
LAYER_CUT = "CUT"
_LAYER_COLOURS = {"0": 7, LAYER_PATTERN: 7, LAYER_CUT: 1}  # ACI: white/black, red


class ExportError(InputError):
    """A contour the exporters cannot write."""


def _contours(contours, what: str) -> list:
    if contours is None:
        return []
    if isinstance(contours, np.ndarray) and contours.ndim == 2:
        contours = [contours]
    out = []
    for i, c in enumerate(contours):
        pts = np.asarray(c, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2:
            raise ExportError(f"{what} {i}: a contour must be a (k, 2) array with k >= 2, got {pts.shape}")
        if not np.all(np.isfinite(pts)):
            raise ExportError(f"{what} {i}: non-finite coordinate")
        if len(pts) > 2 and np.allclose(pts[0], pts[-1]):
            pts = pts[:-1]
        out.append(pts)
    return out


def _lines(lines) -> np.ndarray:
    if lines is None or len(lines) == 0:
        return np.zeros((0, 2, 2))
    seg = np.asarray(lines, dtype=float)
    if seg.ndim != 3 or seg.shape[1:] != (2, 2):
        raise ExportError(f"bend lines must be a (k, 2, 2) array, got {seg.shape}")
    if not np.all(np.isfinite(seg)):
        raise ExportError("bend lines: non-finite coordinate")
    return seg


def _extents(*groups):
    pts = [g.reshape(-1, 2) for g in groups if g.size]
    if not pts:
        raise ExportError("nothing to export")
    allpts = np.vstack(pts)
    return allpts.min(axis=0), allpts.max(axis=0)


def _f(v: float) -> str:
    text = f"{v:.6f}"
    return "0.000000" if text == "-0.000000" else text


def to_dxf(pattern_outlines, cut_contours=(), bend_lines=()) -> str:
    """DXF R12 ASCII text: outlines and bend lines on PATTERN, compensated contours on CUT."""
    pattern = _contours(pattern_outlines, "pattern outline")
    cut = _contours(cut_contours, "cut contour")
    bends = _lines(bend_lines)
    lo, hi = _extents(*(pattern + cut), bends)

    out = []

    def pair(code, value):
        out.append(f"{code:>3}")
        out.append(str(value))

    pair(0, "SECTION"); pair(2, "HEADER")
    pair(9, "$ACADVER"); pair(1, "AC1009")
    pair(9, "$HANDLING"); pair(70, 0)
    pair(9, "$EXTMIN"); pair(10, _f(lo[0])); pair(20, _f(lo[1])); pair(30, _f(0.0))
    pair(9, "$EXTMAX"); pair(10, _f(hi[0])); pair(20, _f(hi[1])); pair(30, _f(0.0))
    pair(0, "ENDSEC")

    pair(0, "SECTION"); pair(2, "TABLES")
    pair(0, "TABLE"); pair(2, "LTYPE"); pair(70, 1)
    pair(0, "LTYPE"); pair(2, "CONTINUOUS"); pair(70, 0); pair(3, "Solid line")
    pair(72, 65); pair(73, 0); pair(40, _f(0.0))
    pair(0, "ENDTAB")
    pair(0, "TABLE"); pair(2, "LAYER"); pair(70, len(_LAYER_COLOURS))
    for name, colour in _LAYER_COLOURS.items():
        pair(0, "LAYER"); pair(2, name); pair(70, 0); pair(62, colour); pair(6, "CONTINUOUS")
    pair(0, "ENDTAB")
    pair(0, "ENDSEC")

    pair(0, "SECTION"); pair(2, "ENTITIES")
    for layer, contours in ((LAYER_PATTERN, pattern), (LAYER_CUT, cut)):
        for pts in contours:
            pair(0, "POLYLINE"); pair(8, layer); pair(66, 1)
            pair(10, _f(0.0)); pair(20, _f(0.0)); pair(30, _f(0.0)); pair(70, 1)  # 70=1: closed
            for x, y in pts:
                pair(0, "VERTEX"); pair(8, layer)
                pair(10, _f(x)); pair(20, _f(y)); pair(30, _f(0.0))
            pair(0, "SEQEND"); pair(8, layer)
    for (x1, y1), (x2, y2) in bends:
        pair(0, "LINE"); pair(8, LAYER_PATTERN)
        pair(10, _f(x1)); pair(20, _f(y1)); pair(30, _f(0.0))
        pair(11, _f(x2)); pair(21, _f(y2)); pair(31, _f(0.0))
    pair(0, "ENDSEC")
    pair(0, "EOF")
    return "\n".join(out) + "\n"


def to_svg(pattern_outlines, cut_contours=(), bend_lines=(), margin: float = 2.0) -> str:
    """SVG in mm (1 user unit = 1 mm, Y up in the drawing turned to SVG's Y down), one <path> per
    contour, grouped by layer; bend lines are dashed <line>s in the PATTERN group."""
    pattern = _contours(pattern_outlines, "pattern outline")
    cut = _contours(cut_contours, "cut contour")
    bends = _lines(bend_lines)
    if not (margin >= 0 and np.isfinite(margin)):
        raise ExportError(f"margin must be >= 0, got {margin!r}")
    lo, hi = _extents(*(pattern + cut), bends)
    width, height = hi - lo + 2 * margin
    min_x, min_y = lo[0] - margin, -hi[1] - margin   # SVG y = -drawing y

    def path(pts):
        coords = " L ".join(f"{_f(x)} {_f(-y)}" for x, y in pts)
        return f'    <path d="M {coords} Z"/>'

    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{_f(width)}mm" '
        f'height="{_f(height)}mm" viewBox="{_f(min_x)} {_f(min_y)} {_f(width)} {_f(height)}">',
        f'  <g id="{LAYER_PATTERN}" fill="none" stroke="black" stroke-width="0.2">',
    ]
    out += [path(p) for p in pattern]
    for (x1, y1), (x2, y2) in bends:
        out.append(f'    <line x1="{_f(x1)}" y1="{_f(-y1)}" x2="{_f(x2)}" y2="{_f(-y2)}" '
                   f'stroke-dasharray="1 1" stroke-width="0.1"/>')
    out.append("  </g>")
    out.append(f'  <g id="{LAYER_CUT}" fill="none" stroke="red" stroke-width="0.2">')
    out += [path(p) for p in cut]
    out.append("  </g>")
    out.append("</svg>")
    return "\n".join(out) + "\n"
