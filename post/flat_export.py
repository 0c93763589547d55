"""Flat patterns for laser, plasma and punch users: DXF (R12 ASCII, written by hand) and SVG (mm).

Layers, so that laser and punch CAM pick the right geometry without editing:

* CUT: the developed outline(s), closed POLYLINEs: the part's true edge, which laser CAM
  compensates for its own kerf;
* BEND: the bend lines (LINEs, the inner triangle edges where the sheet is bent), in the DASHED
  line type, never to be cut;
* PUNCH_PATH: the punch-centre contour(s) (already compensated for the punch, closed POLYLINEs),
  for punch CAM or a check against the turret program; not a cut outline.

Contours are (k, 2) arrays in mm, implicitly closed.

The DXF is the smallest R12 file common readers accept: a HEADER with $ACADVER AC1009 and the drawing
extents, a TABLES section defining the line types CONTINUOUS and DASHED (a 4 mm dash, 2 mm gap) and
the layers, and the ENTITIES.  No handles ($HANDLING 0), as R12 allows.  R12 has no unit field; the
numbers are millimetres.  The SVG has the same three groups (ids and classes CUT, BEND,
PUNCH_PATH), its bend lines dashed.
"""
from __future__ import annotations

import numpy as np

from ..toolpath.ir.errors import InputError


LAYER_CUT = "CUT"
LAYER_BEND = "BEND"
LAYER_PUNCH = "PUNCH_PATH"
LTYPE_DASHED = "DASHED"
DASH_PATTERN = (4.0, -2.0)   # mm: dash, gap (DXF: a negative length is a gap)
# name: (ACI colour, line type); ACI 7 white/black, 1 red, 3 green, 5 blue
_LAYERS = {"0": (7, "CONTINUOUS"), LAYER_CUT: (1, "CONTINUOUS"), LAYER_BEND: (3, LTYPE_DASHED),
           LAYER_PUNCH: (5, "CONTINUOUS")}


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


def to_dxf(pattern_outlines, punch_paths=(), bend_lines=()) -> str:
    """DXF R12 ASCII text: outlines on CUT, bend lines (dashed) on BEND, punch-centre paths on PUNCH_PATH."""
    pattern = _contours(pattern_outlines, "pattern outline")
    punch = _contours(punch_paths, "punch path")
    bends = _lines(bend_lines)
    lo, hi = _extents(*(pattern + punch), bends)

    out = []

    def pair(code, value):
        out.append(f"{code:>3}")
        out.append(str(value))

    pair(0, "SECTION"); pair(2, "HEADER")
    pair(9, "$ACADVER"); pair(1, "AC1009")
    pair(9, "$HANDLING"); pair(70, 0)
    pair(9, "$EXTMIN"); pair(10, _f(lo[0])); pair(20, _f(lo[1])); pair(30, _f(0.0))
    pair(9, "$EXTMAX"); pair(10, _f(hi[0])); pair(20, _f(hi[1])); pair(30, _f(0.0))
    pair(9, "$LTSCALE"); pair(40, _f(1.0))
    pair(0, "ENDSEC")

    pair(0, "SECTION"); pair(2, "TABLES")
    pair(0, "TABLE"); pair(2, "LTYPE"); pair(70, 2)
    pair(0, "LTYPE"); pair(2, "CONTINUOUS"); pair(70, 0); pair(3, "Solid line")
    pair(72, 65); pair(73, 0); pair(40, _f(0.0))
    # R12 line type: 72 alignment 'A', 73 number of elements, 40 pattern length, one 49 per element.
    pair(0, "LTYPE"); pair(2, LTYPE_DASHED); pair(70, 0); pair(3, "Dashed __ __ __")
    pair(72, 65); pair(73, len(DASH_PATTERN)); pair(40, _f(sum(abs(v) for v in DASH_PATTERN)))
    for element in DASH_PATTERN:
        pair(49, _f(element))
    pair(0, "ENDTAB")
    pair(0, "TABLE"); pair(2, "LAYER"); pair(70, len(_LAYERS))
    for name, (colour, linetype) in _LAYERS.items():
        pair(0, "LAYER"); pair(2, name); pair(70, 0); pair(62, colour); pair(6, linetype)
    pair(0, "ENDTAB")
    pair(0, "ENDSEC")

    pair(0, "SECTION"); pair(2, "ENTITIES")
    for layer, contours in ((LAYER_CUT, pattern), (LAYER_PUNCH, punch)):
        for pts in contours:
            pair(0, "POLYLINE"); pair(8, layer); pair(66, 1)
            pair(10, _f(0.0)); pair(20, _f(0.0)); pair(30, _f(0.0)); pair(70, 1)  # 70=1: closed
            for x, y in pts:
                pair(0, "VERTEX"); pair(8, layer)
                pair(10, _f(x)); pair(20, _f(y)); pair(30, _f(0.0))
            pair(0, "SEQEND"); pair(8, layer)
    for (x1, y1), (x2, y2) in bends:
        # the line type is the layer's; named on the entity too, for readers that ignore BYLAYER
        pair(0, "LINE"); pair(8, LAYER_BEND); pair(6, LTYPE_DASHED)
        pair(10, _f(x1)); pair(20, _f(y1)); pair(30, _f(0.0))
        pair(11, _f(x2)); pair(21, _f(y2)); pair(31, _f(0.0))
    pair(0, "ENDSEC")
    pair(0, "EOF")
    return "\n".join(out) + "\n"


def to_svg(pattern_outlines, punch_paths=(), bend_lines=(), margin: float = 2.0) -> str:
    """SVG in mm (1 user unit = 1 mm, Y up in the drawing turned to SVG's Y down), one <path> per
    contour, in the groups CUT (outlines), BEND (dashed <line>s) and PUNCH_PATH (punch centres)."""
    pattern = _contours(pattern_outlines, "pattern outline")
    punch = _contours(punch_paths, "punch path")
    bends = _lines(bend_lines)
    if not (margin >= 0 and np.isfinite(margin)):
        raise ExportError(f"margin must be >= 0, got {margin!r}")
    lo, hi = _extents(*(pattern + punch), bends)
    width, height = hi - lo + 2 * margin
    min_x, min_y = lo[0] - margin, -hi[1] - margin   # SVG y = -drawing y
    dashes = " ".join(f"{abs(v):g}" for v in DASH_PATTERN)

    def path(pts):
        coords = " L ".join(f"{_f(x)} {_f(-y)}" for x, y in pts)
        return f'    <path d="M {coords} Z"/>'

    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{_f(width)}mm" '
        f'height="{_f(height)}mm" viewBox="{_f(min_x)} {_f(min_y)} {_f(width)} {_f(height)}">',
        f'  <g id="{LAYER_CUT}" class="{LAYER_CUT}" fill="none" stroke="red" stroke-width="0.2">',
    ]
    out += [path(p) for p in pattern]
    out.append("  </g>")
    out.append(f'  <g id="{LAYER_BEND}" class="{LAYER_BEND}" fill="none" stroke="green" stroke-width="0.1" '
               f'stroke-dasharray="{dashes}">')
    for (x1, y1), (x2, y2) in bends:
        out.append(f'    <line x1="{_f(x1)}" y1="{_f(-y1)}" x2="{_f(x2)}" y2="{_f(-y2)}"/>')
    out.append("  </g>")
    out.append(f'  <g id="{LAYER_PUNCH}" class="{LAYER_PUNCH}" fill="none" stroke="blue" stroke-width="0.2">')
    out += [path(p) for p in punch]
    out.append("  </g>")
    out.append("</svg>")
    return "\n".join(out) + "\n"
