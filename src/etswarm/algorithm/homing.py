"""Dead reckoning of a searching robot, and the way back of a lost one.

A Kilobot has no compass and no wheel encoders, but it knows which motor command it
gave on every tick, and its makers calibrate it to a nominal forward speed and turning
rate. From those a searcher keeps an estimate of its own pose, its *odometry*, in a frame
of its own (origin and heading where it left the repository). The estimate is what the
robot believes; how far the robot really went depends on its calibration error (the
simulator's ``speed_spread`` and ``turn_rate_spread``), and shoves from other bodies are
missed altogether.

Every tick it hears a stationary robot (placed or Queued) it notes its odometric
position as *home*. A searcher that hears none (lost) first pivots where it is
(``search.LOST_PIVOT_TICKS``); with ``ETParams.lost_homing`` on it then circles home on
a spiral that widens by about ``RING_SPACING_MM`` per lap (``homing_motion``). Without
it, the lost searcher's spiral was a fixed pattern of commands; each turn away from
another searcher moved its centre, and lost searchers were found 4-5 m from the shape
after 4 h (starfish seed 40, triangle seed 31): 31 of 65 unformed first formations over
13 shapes ended with every remaining searcher lost.

Units: odometric positions in 1 / ``ODO_PER_MM`` mm, heading in 1 / ``ODO_PER_RAD`` rad,
both in ``ri`` (``R_ODO_*``, ``R_HOME_*``).
"""

from __future__ import annotations

import math

from numba import njit

from etswarm.algorithm.kernel_util import FORWARD, LEFT, RIGHT
from etswarm.algorithm.memory import (
    R_HOME_X,
    R_HOME_Y,
    R_LOST_PATH,
    R_ODO_H,
    R_ODO_PATH,
    R_ODO_X,
    R_ODO_Y,
)
from etswarm.algorithm.params import (
    F_ODO_LEG,
    F_ODO_RADIUS,
    F_ODO_STEP,
    F_ODO_TURN,
    F_PORTABLE_MATH,
)
from etswarm.sim.fpmath import atan2_as, hypot_as, sin_cos_as

#: Odometric positions are kept in units of 1 / this many mm ...
ODO_PER_MM = 1024.0
#: ... and the heading in units of 1 / this many radians.
ODO_PER_RAD = 1e9
#: The spiral round home starts at this radius (mm): a Kilobot turning on the spot by
#: pivots cannot follow a circle much tighter at full forward speed.
RING_START_MM = 50.0
#: ... and widens by about this much per lap (mm): less than the width a lap sweeps
#: within radio range (2 x 70 mm), so no robot between two laps goes unheard.
RING_SPACING_MM = 100.0
#: When the ring has grown to this radius (mm) the robot starts again from home: what it
#: lost is within a metre or two (the shape, or the repository's new end), and a crowd of
#: searchers round a few placed robots (a regrowth that never got its third seed) shoves
#: its members out of earshot one by one; unbounded spirals took them metres away.
#: 1.5 m since session 33 (1 m before). Traced on starfish seed 218: robot 66 lost the
#: queue at 3370 s about a metre from the shape; the track it really drove fitted its
#: reckoned one scaled by 0.89, and its laps towards the shape reached 0.66 m from home,
#: 0.34 m short of the nearest placed robot, before the spiral started again; it was
#: still lost 3 h later. Only a robot lost for a whole 1 m spiral (about 75 min) moves
#: otherwise than before.
RING_MAX_MM = 1500.0
#: Radial error (mm) at which the robot steers straight at (or away from) home; nearer
#: the ring it blends towards the ring's tangent.
RING_BAND_MM = 30.0
#: Heading errors under this (rad) drive forward; larger ones pivot.
AIM_TOLERANCE_RAD = math.radians(20.0)
#: ``lost_homing = "ahead"``: a searcher lost on its way along the repository moves the
#: spiral's centre on from home, away from where it left the repository, by this share
#: of its path since it got lost (mm per mm): about a lap's worth of ring spacing per
#: lap of 1 m, so the widening spiral sweeps a band along the repository's line. The
#: shift starts again with the spiral (``RING_MAX_MM``), after about 3 m.
AHEAD_SHARE = 0.1
#: ... but only when home is at least this far (mm) from where it left the repository:
#: nearer, the way it was going is not known.
AHEAD_MIN_MM = 100.0


@njit
def reset_odometry(i, ri):  # type: ignore[no-untyped-def]
    """Robot i starts a new odometric frame where it stands: pose (0, 0, 0), home there."""
    ri[i, R_ODO_X] = 0
    ri[i, R_ODO_Y] = 0
    ri[i, R_ODO_H] = 0
    ri[i, R_HOME_X] = 0
    ri[i, R_HOME_Y] = 0
    ri[i, R_ODO_PATH] = 0
    ri[i, R_LOST_PATH] = 0


@njit
def integrate(i, ri, command, cf):  # type: ignore[no-untyped-def]
    """Advance robot i's odometry by one tick of motor ``command`` (the nominal motion).

    Forward moves the centre ``cf[F_ODO_STEP]`` mm along the heading; LEFT (RIGHT)
    pivots the body by ``cf[F_ODO_TURN]`` rad counter-clockwise (clockwise) about the leg
    on the rim at heading + (-) ``cf[F_ODO_LEG]``, as ``sim.motion`` moves a Kilobot.
    """
    if command != FORWARD and command != LEFT and command != RIGHT:
        return
    x = ri[i, R_ODO_X] / ODO_PER_MM
    y = ri[i, R_ODO_Y] / ODO_PER_MM
    h = ri[i, R_ODO_H] / ODO_PER_RAD
    portable = cf[F_PORTABLE_MATH] > 0.0
    if command == FORWARD:
        sh, ch = sin_cos_as(h, portable)
        x += cf[F_ODO_STEP] * ch
        y += cf[F_ODO_STEP] * sh
        travel = cf[F_ODO_STEP]
    else:
        sign = 1.0 if command == LEFT else -1.0
        leg = h + sign * cf[F_ODO_LEG]
        turn = sign * cf[F_ODO_TURN]
        r = cf[F_ODO_RADIUS]
        s0, c0 = sin_cos_as(leg, portable)
        s1, c1 = sin_cos_as(leg + turn, portable)
        x += r * (c0 - c1)
        y += r * (s0 - s1)
        h += turn
        travel = r * cf[F_ODO_TURN]
        if h > math.pi:
            h -= 2.0 * math.pi
        elif h <= -math.pi:
            h += 2.0 * math.pi
    ri[i, R_ODO_X] = round(x * ODO_PER_MM)
    ri[i, R_ODO_Y] = round(y * ODO_PER_MM)
    ri[i, R_ODO_H] = round(h * ODO_PER_RAD)
    ri[i, R_ODO_PATH] += round(travel * ODO_PER_MM)


@njit
def note_home(i, ri):  # type: ignore[no-untyped-def]
    """Robot i hears a stationary robot: where it stands now is home."""
    ri[i, R_HOME_X] = ri[i, R_ODO_X]
    ri[i, R_HOME_Y] = ri[i, R_ODO_Y]


@njit
def note_lost(i, ri):  # type: ignore[no-untyped-def]
    """Robot i has just lost the group: its spiral grows with the path from here."""
    ri[i, R_LOST_PATH] = ri[i, R_ODO_PATH]


@njit
def ring_radius(path_mm):  # type: ignore[no-untyped-def]
    """Radius (mm) of the spiral round home after a path of ``path_mm`` since lost.

    A lap of radius r is 2 pi r long and the radius grows by ``RING_SPACING_MM`` per
    lap: d(r^2)/d(path) = spacing / pi. Growing with the path, not with time, the
    spiral waits while the robot stands (yielding) instead of leaving gaps. Past
    ``RING_MAX_MM`` it starts again from ``RING_START_MM`` (the robot heads home).
    """
    grow = RING_SPACING_MM / math.pi
    start2 = RING_START_MM * RING_START_MM
    return math.sqrt(start2 + grow * (path_mm % spiral_path()))


@njit(inline="always")
def spiral_path():  # type: ignore[no-untyped-def]
    """Path (mm) of one spiral, from ``RING_START_MM`` to ``RING_MAX_MM``."""
    start2 = RING_START_MM * RING_START_MM
    return (RING_MAX_MM * RING_MAX_MM - start2) * math.pi / RING_SPACING_MM


@njit
def homing_motion(i, ri, ahead, from_x, from_y, portable):  # type: ignore[no-untyped-def]
    """Motor command of lost robot i, circling home (with ``ahead``, a point moved on from
    home away from the odometric point (``from_x``, ``from_y``), 1 / ``ODO_PER_MM`` mm:
    the origin, where it left the repository, or where a leap's walk began,
    ``repository_gap``; ``AHEAD_SHARE``).

    It steers for the clockwise tangent of the ring of radius ``ring_radius`` round home,
    turned towards home (or away) by up to 90 degrees as its odometric distance from home
    exceeds (or falls short of) the radius by ``RING_BAND_MM``: from afar it heads
    straight home, then laps it on a widening spiral. Forward when the heading is within
    ``AIM_TOLERANCE_RAD`` of that course, else a pivot towards it. ``portable``: the
    angle by ``sim.fpmath`` (``F_PORTABLE_MATH``).
    """
    dx = (ri[i, R_ODO_X] - ri[i, R_HOME_X]) / ODO_PER_MM
    dy = (ri[i, R_ODO_Y] - ri[i, R_HOME_Y]) / ODO_PER_MM
    h = ri[i, R_ODO_H] / ODO_PER_RAD
    path = (ri[i, R_ODO_PATH] - ri[i, R_LOST_PATH]) / ODO_PER_MM
    if ahead:
        hx = (ri[i, R_HOME_X] - from_x) / ODO_PER_MM
        hy = (ri[i, R_HOME_Y] - from_y) / ODO_PER_MM
        away = hypot_as(hx, hy, portable)
        if away >= AHEAD_MIN_MM:
            shift = AHEAD_SHARE * (path % spiral_path())
            dx -= shift * hx / away
            dy -= shift * hy / away
    rho = hypot_as(dx, dy, portable)
    outward = atan2_as(dy, dx, portable)
    error = (rho - ring_radius(path)) / RING_BAND_MM
    inward = 0.5 * math.pi * max(-1.0, min(1.0, error))
    course = outward - 0.5 * math.pi - inward
    off = (course - h + math.pi) % (2.0 * math.pi) - math.pi
    if abs(off) < AIM_TOLERANCE_RAD:
        return FORWARD
    return LEFT if off > 0 else RIGHT
