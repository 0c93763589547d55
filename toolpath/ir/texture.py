"""The gouge texture request: the IR's ``Operation.texture``.

A roughing operation of the engrave workflow (:mod:`engrave`) is planned untextured and carries
this request.  ``engrave.bake`` applies it with a seeded generator; the controller-macro post
(``post/fanuc.py``) instead writes a macro that draws the depths on the control.  It lives here,
apart from the workflow, because it is part of the IR the posts read.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError


class EngraveError(InputError):
    """Input the engrave workflow cannot use; the message names what is wrong."""


GOUGE_MOTIONS = ("ramp", "scoop")


@dataclass(frozen=True)
class GougeTexture:
    """Random chisel-mark depths applied along the raster (paper defaults)."""

    base_depth: float = -2.0
    quantum: float = 0.2
    amplitude: float = 0.8
    spacing: float = 20.0
    motion: str = "ramp"          # "ramp": straight lines between depths; "scoop": dive, then push up
    scoop_dive: float = 0.25      # scoop: fraction of a gouge spent diving
    spacing_jitter: float = 0.0   # 0..0.5: each gouge length varies by +/- this fraction (baked only)
    raster_angle: float = 0.0     # degrees from +X; gouges are spaced along the raster
    seed: int = 0

    def __post_init__(self):
        for name in ("base_depth", "quantum", "amplitude", "spacing", "scoop_dive", "spacing_jitter", "raster_angle"):
            if not math.isfinite(getattr(self, name)):
                raise EngraveError(f"texture {name} must be a finite number")
        if self.quantum <= 0 or self.amplitude < 0 or self.spacing <= 0:
            raise EngraveError("texture quantum and gouge spacing must be > 0, amplitude >= 0")
        if self.motion not in GOUGE_MOTIONS:
            raise EngraveError(f"gouge motion must be one of {GOUGE_MOTIONS}, got {self.motion!r}")
        if not 0 < self.scoop_dive < 1:
            raise EngraveError("scoop dive fraction must be between 0 and 1")
        if not 0 <= self.spacing_jitter <= 0.5:
            raise EngraveError("spacing jitter must be between 0 and 0.5")
        if self.base_depth + self.amplitude > 0:
            raise EngraveError("the shallowest gouge (base depth + amplitude) would lie above the plate top")

    def level(self, k):
        """Depth offset (mm, >= 0) for level k in 0..4."""
        return self.quantum * np.round(np.asarray(k) * self.amplitude / (4 * self.quantum) + 1e-9)

    def depth(self, digit):
        """Target Z for a digit 0..9 (vectorised)."""
        d = np.asarray(digit)
        if np.any((d < 0) | (d > 9)):
            raise EngraveError("gouge digits must be 0..9")
        shallow = d <= 4
        k = np.where(shallow, d, d - 5)
        return np.where(shallow, self.base_depth + self.level(k), self.base_depth - self.level(k))

    @property
    def shallowest(self) -> float:
        return self.base_depth + float(self.level(4))

    @property
    def deepest(self) -> float:
        return self.base_depth - float(self.level(4))
