"""Tool shapes (toolpath/ir/tools.py): each kind's profile against closed forms, which kinds plunge,
and unknown kinds refused."""
import math

import numpy as np
import pytest

from kezuri.toolpath.ir import tools
from kezuri.toolpath.ir.program import TOOL_KINDS, ProgramError, Tool

H = np.linspace(0.0, 12.0, 241)     # heights above the tip, past every tool's end


def test_every_kind_has_a_shape():
    assert tools.KINDS == TOOL_KINDS == ("ball", "flat", "bull", "drill", "vbit")
    for kind in TOOL_KINDS:
        shape = Tool(1, kind, 6.0, corner_radius=1.0 if kind == "bull" else 0.0).shape
        assert isinstance(shape, tools.SHAPES[kind]) and shape.kind == kind and shape.radius == 3.0


def test_ball_profile():
    r = 3.0
    shape = Tool(1, "ball", 2 * r).shape
    assert shape.corner_radius == r and shape.flat_radius == 0.0 and shape.tip_tan == 0.0
    below = H <= r
    assert np.allclose(shape.radius_at(H[below]), np.sqrt(r * r - (r - H[below]) ** 2))
    assert np.allclose(shape.radius_at(H[~below]), r)
    d = np.linspace(0.0, r, 61)
    assert np.allclose(shape.height_at(d), r - np.sqrt(r * r - d * d))


def test_flat_profile():
    shape = Tool(1, "flat", 8.0).shape
    assert shape.corner_radius == 0.0 and shape.flat_radius == 4.0
    assert np.allclose(shape.radius_at(H), 4.0)
    assert np.allclose(shape.height_at(np.linspace(0.0, 4.0, 9)), 0.0)


def test_bull_profile():
    big, rc = 5.0, 2.0
    shape = Tool(1, "bull", 2 * big, corner_radius=rc).shape
    assert shape.corner_radius == rc and shape.flat_radius == big - rc
    below = H <= rc
    assert np.allclose(shape.radius_at(H[below]), big - rc + np.sqrt(rc * rc - (rc - H[below]) ** 2))
    assert np.allclose(shape.radius_at(H[~below]), big)
    d = np.linspace(0.0, big, 101)
    off = np.maximum(d - (big - rc), 0.0)
    assert np.allclose(shape.height_at(d), rc - np.sqrt(rc * rc - off * off))
    assert shape.profile() == (0.0, rc, big - rc)


@pytest.mark.parametrize("kind, angle", [("vbit", 90.0), ("drill", 118.0)])
def test_cone_profile(kind, angle):
    r = 3.0
    shape = Tool(1, kind, 2 * r).shape
    half = math.radians(angle / 2)
    assert shape.pointed and shape.tip_angle_deg == angle and shape.tip_tan == pytest.approx(math.tan(half))
    assert np.allclose(shape.radius_at(H), np.minimum(H * math.tan(half), r))
    d = np.linspace(0.0, r, 31)
    assert np.allclose(shape.height_at(d), d / math.tan(half))
    assert shape.corner_radius == 0.0 and shape.flat_radius == 0.0


def test_plunging_and_constructions():
    plunges = {kind: Tool(1, kind, 6.0, corner_radius=1.0 if kind == "bull" else 0.0).shape.plunges
               for kind in TOOL_KINDS}
    assert plunges == {"ball": True, "flat": True, "bull": False, "drill": True, "vbit": False}
    envelope = {kind: cls.envelope for kind, cls in tools.SHAPES.items()}
    assert envelope == {"ball": "sphere", "flat": "disc", "bull": "disc", "drill": "cone", "vbit": "cone"}
    assert [k for k, cls in tools.SHAPES.items() if cls.pointed] == ["drill", "vbit"]
    assert [k for k, cls in tools.SHAPES.items() if cls.spherical] == ["ball"]
    assert [k for k, cls in tools.SHAPES.items() if cls.staircase] == ["ball", "flat"]


def test_describe():
    assert Tool(3, "bull", 10.0, corner_radius=2.0).describe() == "T3 10 mm bull nose end mill R2"
    assert Tool(4, "vbit", 6.0, name="chamfer").describe() == "T4 6 mm V-bit (chamfer)"
    assert Tool(1, "ball", 6.0).describe() == "T1 6 mm ball end mill"


@pytest.mark.parametrize("kind", ["taper", "", "Ball", None])
def test_unknown_kind_is_refused(kind):
    with pytest.raises(tools.ToolShapeError, match="is not one of"):
        tools.shape_class(kind)
    with pytest.raises(ProgramError, match=r"tool kind .* is not one of \('ball', 'flat', 'bull', 'drill', 'vbit'\)"):
        Tool(1, kind, 6.0)
