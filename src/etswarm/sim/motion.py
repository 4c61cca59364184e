"""Phase 3 of a tick: motors move the robots (Kilobot / Kilombo geometry).

Forward (motor 1): the centre advances ``speed * dt`` along the heading. Turning left
(motor 2) pivots the body counter-clockwise by ``turn_rate * dt`` about the left leg, which
sits on the rim at angle ``heading + leg_angle`` (leg_angle = 125.5 deg: the rear-left
leg); turning right (motor 3) pivots clockwise about the rear-right leg at
``heading - leg_angle``. Optional noise while moving: a relative per-tick speed jitter
N(0, speed_noise) and a heading jitter N(0, heading_noise) rad, from the motion stream.
With walls the centre is kept inside [r, arena - r]^2. Dead or absent robots do not move.
Every robot that moved is updated in the grid (rebuilt if one left its slack box); its
travel is taken from its collision budget, and when that is used up it is appended to the
collision work list; one that drifted from its place at the start of the contact-list
epoch raises the grid's drifted flag. Robots are visited in index order, their grid
slots lie scattered in memory: the slot data of the robot a few places ahead is
prefetched.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.sim.fpmath import normal_as, sin_cos_as
from etswarm.sim.neighbours import (
    G_CELL,
    G_DRIFT,
    G_MARGIN,
    P_BUDGET,
    P_X,
    P_Y,
    R_BX,
    R_BY,
    S_DRIFTED,
    drifted,
    rebuild_keeping_list,
)
from etswarm.sim.prefetch import prefetch

#: Robots ahead whose grid slot data a move step asks the cache for (slots are scattered).
PREFETCH_AHEAD = 8


@njit(cache=True, inline="always")
def clamp_to_arena(v, radius, arena):
    """Keep coordinate ``v`` (mm) of a centre inside walls at 0 and ``arena``."""
    if v < radius:
        return radius
    if v > arena - radius:
        return arena - radius
    return v


@njit(cache=True, _nrt=False)
def move_phase(cfg, grid, pos, heading, motor, alive, present, speed, turn_rate,
               dirty, dirty_flag, n_dirty, trig, rng):
    """Advance every robot whose motor is on by one tick; returns the work-list length.

    The collision work list ``dirty`` holds grid slots (flags by slot in ``dirty_flag``).
    ``trig`` (N, 6) float64 caches, per robot, (heading, cos, sin) of the heading and
    (turn_rate, cos, sin) of one tick's turn, so a tick needs no trigonometry; an entry is
    recomputed whenever the heading or turn rate differs from the cached one (outside
    edits, noise). Start it filled with NaN. Compiled without numba's reference counting
    (it allocates nothing; see etswarm.sim.borrow).
    """
    dt = cfg.dt
    r = cfg.radius
    leg = cfg.leg_angle
    sin_leg, cos_leg = sin_cos_as(leg, cfg.portable)
    walls = cfg.arena > 0.0
    two_pi = 2.0 * np.pi
    sxb, slot, sref = grid.sxb, grid.slot, grid.sref
    span = grid.geom[G_CELL] + 2.0 * grid.geom[G_MARGIN]
    drift2 = grid.geom[G_DRIFT] * grid.geom[G_DRIFT]
    stale = False
    drift = False
    n = pos.shape[0]
    for i in range(n):
        if i + PREFETCH_AHEAD < n:
            ahead = slot[i + PREFETCH_AHEAD]
            prefetch(sxb, ahead)
            prefetch(sref, ahead)
            prefetch(dirty_flag, ahead)
        m = motor[i]
        if m == 0 or not alive[i] or not present[i]:
            continue
        h = heading[i]
        if trig[i, 0] != h:
            trig[i, 0] = h
            trig[i, 2], trig[i, 1] = sin_cos_as(h, cfg.portable)
        ch = trig[i, 1]
        sh = trig[i, 2]
        # forward and turning are both computed and one is selected (which one is
        # random per robot: a branch on it is mispredicted often); the values are the
        # same as if only the chosen one were computed
        fwd = m == 1
        step = speed[i] * dt
        if fwd and cfg.speed_noise > 0.0:
            step *= 1.0 + cfg.speed_noise * normal_as(rng, cfg.portable)
        rate = turn_rate[i]
        if trig[i, 3] != rate:
            trig[i, 3] = rate
            trig[i, 5], trig[i, 4] = sin_cos_as(rate * dt, cfg.portable)
        cw = m == 3  # clockwise about the right leg, else counter-clockwise about the left
        cd = trig[i, 4]
        sd = -trig[i, 5] if cw else trig[i, 5]
        dth = -(rate * dt) if cw else rate * dt
        sl = -sin_leg if cw else sin_leg
        # leg direction a = heading +- leg_angle; the centre rotates by dth about
        # the leg at pos + r*(cos a, sin a): new centre = leg - r*(cos(a+dth), ...)
        ca = ch * cos_leg - sh * sl
        sa = sh * cos_leg + ch * sl
        ca2 = ca * cd - sa * sd
        sa2 = sa * cd + ca * sd
        px = pos[i, 0]
        py = pos[i, 1]
        x = px + step * ch if fwd else px + r * (ca - ca2)
        y = py + step * sh if fwd else py + r * (sa - sa2)
        h_new = h if fwd else h + dth
        travel = abs(step) if fwd else r * abs(dth)  # turning: arc length >= chord
        ch_t = ch * cd - sh * sd
        sh_t = sh * cd + ch * sd
        ch = ch if fwd else ch_t
        sh = sh if fwd else sh_t
        if cfg.heading_noise > 0.0:
            h_new += cfg.heading_noise * normal_as(rng, cfg.portable)
            sh, ch = sin_cos_as(h_new, cfg.portable)
        if h_new > np.pi:
            h_new -= two_pi
        elif h_new <= -np.pi:
            h_new += two_pi
        if walls:
            x = clamp_to_arena(x, r, cfg.arena)
            y = clamp_to_arena(y, r, cfg.arena)
        pos[i, 0] = x
        pos[i, 1] = y
        heading[i] = h_new
        trig[i, 0] = h_new
        trig[i, 1] = ch
        trig[i, 2] = sh
        s = slot[i]
        sxb[s, P_X] = x
        sxb[s, P_Y] = y
        bx = sref[s, R_BX]
        by = sref[s, R_BY]
        if x < bx or x >= bx + span or y < by or y >= by + span:
            stale = True
        drift |= drifted(sref, s, x, y, drift2)
        b = sxb[s, P_BUDGET] - travel
        sxb[s, P_BUDGET] = b
        if b <= 0.0 and dirty_flag[s] == 0:
            dirty_flag[s] = 1
            dirty[n_dirty] = s
            n_dirty += 1
    if drift:
        grid.state[S_DRIFTED] = 1  # contact lists are void from here (see neighbours)
    if stale:
        n_dirty = rebuild_keeping_list(grid, pos, present, dirty, n_dirty, dirty_flag)
    return n_dirty
