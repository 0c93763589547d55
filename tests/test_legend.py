"""The move kinds' colours (toolpath/pictures/legend.py): one table, read by the pictures and the
viewport; the scene-linear values Blender holds; the path cut into runs of one move kind.

Expected linear values are decoded here by hand from the sRGB transfer function (IEC 61966-2-1),
not by the code under test; expected runs are read off the operation's moves."""
import math
import os
import re

import numpy as np
import pytest

from kezuri.toolpath.ir.program import ARC_CCW, FEED, RAPID, Operation, Tool
from kezuri.toolpath.pictures import legend
from kezuri.toolpath.pictures import picture_jobs as pj
from kezuri.toolpath.simulate import BoxStock

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STOCK = BoxStock(0, 0, -10, 100, 60, 0)


def decoded(byte: int) -> float:
    c = byte / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def test_the_legend_has_the_four_move_kinds_in_the_pictures_colours():
    assert legend.ROLES == ("cut", "plunge", "link", "rapid")
    assert [legend.ROLES[i] for i in (legend.CUT, legend.PLUNGE, legend.LINK, legend.RAPID_ROLE)] == list(legend.ROLES)
    assert pj.ROLE_COLOURS is legend.ROLE_COLOURS and pj.ROLE_LABELS is legend.ROLE_LABELS
    colours = list(legend.ROLE_COLOURS.values()) + [legend.UNCUT_COLOUR]
    assert len(set(colours)) == len(colours)                        # every kind its own colour


def test_linear_values_decode_the_srgb_bytes():
    # cut (25, 95, 225): 25 / 255 = 0.0980 -> ((0.0980 + 0.055) / 1.055) ** 2.4 = 0.00972
    assert legend.linear_rgba("cut") == pytest.approx((0.009721, 0.114435, 0.752942, 1.0), abs=2e-6)
    for kind, rgb in legend.ROLE_COLOURS.items():
        assert legend.linear_rgba(kind) == pytest.approx(tuple(decoded(v) for v in rgb) + (1.0,), abs=1e-9)
    # the linear segment at the bottom: 10 / 255 = 0.0392 <= 0.04045 -> 0.0392 / 12.92
    assert legend.linear_rgba("link")[0] == pytest.approx(10 / 255 / 12.92, rel=1e-12)


def test_no_colour_of_the_legend_is_written_twice_in_the_sources():
    """The pictures and the viewport read the one table: no other module spells its colours."""
    spelled = {kind: re.compile(r"\(\s*%d\s*,\s*%d\s*,\s*%d\s*[,)]" % rgb) for kind, rgb in legend.ROLE_COLOURS.items()}
    found = []
    for folder in ("toolpath", "operators", "post"):
        for base, _, files in os.walk(os.path.join(ROOT, folder)):
            for name in files:
                path = os.path.join(base, name)
                if name.endswith(".py") and path != os.path.join(ROOT, "toolpath", "pictures", "legend.py"):
                    text = open(path, encoding="utf-8").read()
                    found += [f"{os.path.relpath(path, ROOT)}: {kind}" for kind, rx in spelled.items() if rx.search(text)]
    assert not found


def pocket_operation():
    """Rapid in, plunge 1.5 mm, an L of cuts, a feed retract into the air, a feed move in the
    air, a rapid away (as in test_pictures)."""
    kind = [RAPID, RAPID, FEED, FEED, FEED, FEED, FEED, RAPID]
    xyz = [(10, 10, 20), (10, 10, 2), (10, 10, -1.5), (60, 10, -1.5), (60, 40, -1.5), (60, 40, 5),
           (80, 40, 5), (90, 20, 20)]
    feed = [np.nan if k == RAPID else 500.0 for k in kind]
    return Operation("pocket", Tool(1, "flat", 3.0), 10000, kind, xyz, feed, start=np.array([10.0, 10.0, 20.0]))


def test_role_paths_cut_the_path_where_the_move_kind_changes():
    runs = pj.role_paths(pocket_operation(), STOCK)
    assert [role for role, _ in runs] == [legend.RAPID_ROLE, legend.PLUNGE, legend.CUT, legend.LINK,
                                          legend.RAPID_ROLE]
    expected = [[(10, 10, 20), (10, 10, 20), (10, 10, 2)], [(10, 10, 2), (10, 10, -1.5)],
                [(10, 10, -1.5), (60, 10, -1.5), (60, 40, -1.5)], [(60, 40, -1.5), (60, 40, 5), (80, 40, 5)],
                [(80, 40, 5), (90, 20, 20)]]
    for (_, points), want in zip(runs, expected):
        assert np.array_equal(points, np.array(want, float))


def test_role_paths_walk_arcs_on_their_circle():
    # plunge at (0, 0), a half circle CCW about (10, 0) radius 10 at Z -1 (in the stock), a rapid up
    kind = np.array([FEED, ARC_CCW, RAPID])
    xyz = np.array([[20, 30, -1], [40, 30, -1], [40, 30, 10]], float)
    center = np.full((3, 3), np.nan)
    center[1] = [30, 30, -1]
    op = Operation("arc", Tool(1, "flat", 3.0), 10000, kind, xyz, np.array([300.0, 600.0, np.nan]), center=center,
                   start=np.array([20, 30, 2.0]))
    runs = pj.role_paths(op, STOCK)
    assert [role for role, _ in runs] == [legend.PLUNGE, legend.CUT, legend.RAPID_ROLE]
    plunge, arc, rapid = (points for _, points in runs)
    assert np.array_equal(plunge, [[20, 30, 2], [20, 30, -1]])
    assert len(arc) == 1 + math.ceil(180 / 6)                       # chords of at most 6 degrees
    assert np.allclose(np.hypot(arc[:, 0] - 30, arc[:, 1] - 30), 10.0) and np.allclose(arc[:, 2], -1)
    assert arc[:, 1].min() == pytest.approx(20.0)                  # CCW from (20, 30) passes below the centre
    assert np.array_equal(arc[[0, -1]], [[20, 30, -1], [40, 30, -1]])
    assert np.array_equal(rapid, [[40, 30, -1], [40, 30, 10]])
