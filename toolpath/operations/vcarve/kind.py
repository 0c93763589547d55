"""V-carving as an operation kind of the job model (:mod:`.vcarve`)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...engines import region as rg
from ...job import DesignLayer, OperationKind, Part
from ...simulate import BoxStock
from . import vcarve

KEEP_MARGIN = 0.02      # mm: the carved outline may stand this far from the design (the sampling's error)
KEEP_BAND = 2.0         # mm round the carving that must stand


@dataclass(frozen=True)
class VCarveGeometry:
    """The design's loops (work mm, read even-odd: counters are islands), the operation's name,
    the stock's top Z and, for the stock, the plate's outline and thickness (empty: a box 5 mm
    round the design); a text's characters one by one, to name those too fine for the end mill."""

    loops: tuple
    name: str = "vcarve"
    top: float = 0.0
    plate_outline: tuple = ()
    plate_thickness: float = 0.0
    characters: tuple = ()      # ((character, index in the text, loops), ...) of a text, for naming
    letters: str = ""           # what the characters are called in messages (the Text object, the text)


def design_layer(result: vcarve.VCarveResult, settings, top: float) -> DesignLayer:
    """Nothing below the deepest the tip reaches; a band round the carving stands (for a male
    plug, round its waste: the cone there reaches start_depth x tan beyond the waste's edge)."""
    reach = KEEP_MARGIN + (settings.shift() * settings.tip_tan if settings.inlay == "male" else 0.0)
    carved = result.carved
    outers = [loop for loop in rg.loops(carved) if rg.signed_area(loop) > 0]
    filled = rg.from_loops(outers, "carving")
    keep = rg.offset(filled, reach + KEEP_BAND) - rg.offset(carved, reach)
    area = rg.offset(filled, reach + KEEP_BAND)
    floor = top - result.deepest - 1e-3
    return DesignLayer(floor, (list(rg.loops(keep)),) if keep.area() > 0 else (), tuple(rg.loops(area)))


class VCarveKind(OperationKind):
    key = "vcarve"
    label = "V-carve"
    families = ("milling",)
    settings_type = vcarve.VCarveSettings

    def plan(self, setup, settings, geometry: VCarveGeometry, progress=None) -> Part:
        result = vcarve.plan(list(geometry.loops), settings, name=geometry.name, top=geometry.top, progress=progress,
                             characters=geometry.characters, letters=geometry.letters)
        stock = setup.stock or self.stock(geometry, result, settings)
        design = design_layer(result, settings, geometry.top)
        return Part(tuple(result.operations), stock, design, tuple(result.warnings), (), None, result)

    @staticmethod
    def stock(geometry: VCarveGeometry, result, settings) -> BoxStock:
        if geometry.plate_outline:
            points = np.vstack([np.asarray(loop, float) for loop in geometry.plate_outline])
            (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
            bottom = geometry.top - geometry.plate_thickness
        else:
            x0, y0, x1, y1 = result.carved.bounds() if result is not None else \
                rg.from_loops(list(geometry.loops)).bounds()
            x0, y0, x1, y1 = x0 - 5.0, y0 - 5.0, x1 + 5.0, y1 + 5.0
            deepest = result.deepest if result is not None else settings.max_depth
            bottom = geometry.top - deepest - 5.0
        return BoxStock(float(x0), float(y0), float(bottom), float(x1), float(y1), float(geometry.top))
