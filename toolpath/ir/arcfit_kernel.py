"""The arc-fitting search over one run of points (compiled by numba where it can be, else the same
code interpreted: the answers are the same, only slower).

:func:`fit_run` walks a polyline P0..Pm and replaces stretches of it by circular arcs: from the
current point it looks for the farthest point that an arc can reach (galloping, then halving the
step), where an arc through the stretch's first, middle and last points keeps every point of the
stretch within ``tolerance`` of its circle, turns one way only (every chord's angle has the arc's
sign, less than a full turn in all) and bulges beyond no chord by more than ``tolerance`` (the
sagitta of the chord).  The arc's centre lies on the bisector of its end points, so both ends
are at one radius, as G2/G3 need.  Where no arc of at least ``min_segments`` chords fits, one
chord is kept as a line.

Compiling :func:`fit_run` costs about a second of CPU on the first run after an install (numba
keeps it in its cache after that); the interpreted search takes about 5 us a point, so an
operation of fewer than :data:`COMPILE_FROM` points runs :func:`interpreted_fit_run` (the same
code, the same answers) unless the compiled one is loaded in this process already.
"""
from __future__ import annotations

import math
import os
import types

import numpy as np

def _interpreted(function):
    return function


_jit, COMPILED = _interpreted, False
if os.environ.get("KEZURI_NO_NUMBA") != "1":
    try:
        from numba import njit
        _jit, COMPILED = njit(cache=True, nogil=True), True
    except (ImportError, OSError, RuntimeError):     # as compiled.kernel_module: numba is optional
        pass


@_jit
def circle(px, py, s, e):
    """(cx, cy, r, turn) of the circle through points s, (s+e)//2 and e; r = inf when they are
    in a line; turn = +1 counter-clockwise, -1 clockwise."""
    m = (s + e) // 2
    ax, ay, bx, by, cx, cy = px[s], py[s], px[m], py[m], px[e], py[e]
    d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    scale = max(abs(bx - ax), abs(by - ay), abs(cx - ax), abs(cy - ay))
    if scale == 0.0 or abs(d) <= 1e-12 * scale * scale:
        return 0.0, 0.0, math.inf, 0
    a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    ox = (a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / d
    oy = (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / d
    turn = 1 if (bx - ax) * (cy - by) - (by - ay) * (cx - bx) > 0 else -1
    return ox, oy, math.hypot(ax - ox, ay - oy), turn


@_jit
def arc_fits(px, py, s, e, tolerance, max_radius):
    """Whether one arc replaces the chords s..e (see the module's rules); (fits, cx, cy, turn)."""
    ox, oy, r, turn = circle(px, py, s, e)
    if not r <= max_radius or r <= tolerance:
        return False, 0.0, 0.0, 0
    swept = 0.0
    for i in range(s, e + 1):
        if abs(math.hypot(px[i] - ox, py[i] - oy) - r) > tolerance:
            return False, 0.0, 0.0, 0
    for i in range(s, e):
        ux, uy = px[i] - ox, py[i] - oy
        vx, vy = px[i + 1] - ox, py[i + 1] - oy
        step = math.atan2(ux * vy - uy * vx, ux * vx + uy * vy)
        half = 0.5 * math.hypot(vx - ux, vy - uy)
        if step * turn < 0.0 or (step == 0.0 and half > 0.0):   # a chord of no length turns neither way
            return False, 0.0, 0.0, 0
        swept += abs(step)
        if half >= r or r - math.sqrt(r * r - half * half) > tolerance:
            return False, 0.0, 0.0, 0
    if swept >= 2.0 * math.pi - 1e-6:
        return False, 0.0, 0.0, 0
    return True, ox, oy, turn


@_jit
def fit_run(px, py, tolerance, min_segments, max_radius):
    """Pieces of the polyline: (end index, cx, cy, turn) rows, turn 0 for a line."""
    m = px.shape[0] - 1
    out = np.empty((max(m, 1), 4))
    count = 0
    s = 0
    while s < m:
        best = -1
        cx = cy = 0.0
        turn = 0
        first = s + min_segments
        if first <= m:
            ok, ox, oy, t = arc_fits(px, py, s, first, tolerance, max_radius)
            if ok:
                best, cx, cy, turn = first, ox, oy, t
                step = 1
                bad = m + 1
                while best + step <= m:              # gallop until an arc no longer fits
                    ok, ox, oy, t = arc_fits(px, py, s, best + step, tolerance, max_radius)
                    if not ok:
                        bad = best + step
                        break
                    best, cx, cy, turn = best + step, ox, oy, t
                    step *= 2
                while bad - best > 1:                # then halve between the last fit and the first miss
                    mid = (best + bad) // 2
                    ok, ox, oy, t = arc_fits(px, py, s, mid, tolerance, max_radius)
                    if ok:
                        best, cx, cy, turn = mid, ox, oy, t
                    else:
                        bad = mid
        if best < 0:
            out[count, 0], out[count, 1], out[count, 2], out[count, 3] = s + 1, 0.0, 0.0, 0.0
            s += 1
        else:
            out[count, 0], out[count, 1], out[count, 2], out[count, 3] = best, cx, cy, turn
            s = best
        count += 1
    return out[:count]


@_jit
def fit_runs(px, py, firsts, lasts, tolerance, min_segments, max_radius):
    """:func:`fit_run` of every run k, whose points are px[firsts[k]:lasts[k] + 2] (one call for
    all the runs of an operation): rows (k, end index within the run, cx, cy, turn), in order."""
    total = 0
    for k in range(firsts.shape[0]):
        total += max(lasts[k] + 1 - firsts[k], 1)
    out = np.empty((total, 5))
    count = 0
    for k in range(firsts.shape[0]):
        rows = fit_run(px[firsts[k]:lasts[k] + 2], py[firsts[k]:lasts[k] + 2], tolerance, min_segments, max_radius)
        for r in range(rows.shape[0]):
            out[count, 0] = k
            for c in range(4):
                out[count, c + 1] = rows[r, c]
            count += 1
    return out[:count]


# points of one operation from which the compiled search pays for its compiling (about 1 s CPU,
# measured 2026-11-28: the engrave sample's 11,120 points take 0.065 s interpreted)
COMPILE_FROM = 20000


def _interpreted_copies(names: tuple) -> dict:
    """The functions ``names`` of this module as plain Python, calling one another (not the
    compiled dispatchers); looked up by name."""
    space = dict(globals())
    for name in names:
        function = getattr(space[name], "py_func", space[name])
        space[name] = types.FunctionType(function.__code__, space, name, function.__defaults__)
    return {name: space[name] for name in names}


_INTERPRETED = _interpreted_copies(("circle", "arc_fits", "fit_run", "fit_runs"))
interpreted_fit_run, interpreted_fit_runs = _INTERPRETED["fit_run"], _INTERPRETED["fit_runs"]


def fit_runs_for(points: int):
    """:func:`fit_runs` for an operation of ``points`` points: the compiled one where numba is used
    and it is loaded already or the work pays for compiling it, else the interpreted one."""
    if COMPILED and (points >= COMPILE_FROM or fit_runs.signatures):
        return fit_runs
    return interpreted_fit_runs
