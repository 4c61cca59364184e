"""Phase 4 of a tick: collisions. Bodies are discs of radius r; no two present robots
may overlap.

Only robots on the work list (those that moved this tick, were pushed, or were edited
from outside) are examined, so a still swarm costs nothing here. Each pass takes every
listed robot i, finds the present robots j with centre distance < 2r (grid query of
radius 2r) and pushes the pair apart along the centre line, half the overlap each, so
they just touch; walls clamp afterwards. Every robot that a pass moved goes on the next
pass's list: a pushed robot moves, and may push others. Passes repeat until nothing moves
or ``max_passes`` is reached (then the tick ends with the remaining small overlaps, counted
in counters[5]). Alive and dead robots are pushed alike.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.sim.motion import clamp_to_arena
from etswarm.sim.neighbours import bucket_of, cell_of, relink

#: Overlap (mm) below which a pair counts as touching, not overlapping.
SLOP_MM = 0.02
#: Extra separation (mm) a push leaves between the two bodies.
GAP_MM = 1e-6


@njit(cache=True)
def collide_phase(cfg, grid, pos, dirty, dirty_flag, n_dirty, spare, counters):
    """Resolve overlaps starting from the work list ``dirty[:n_dirty]``.

    ``spare`` is a second (N,) int32 work array. On return the work list is empty and all
    flags are cleared.
    """
    r = cfg.radius
    contact = 2.0 * r
    # pairs closer than contact - SLOP are resolved, to contact + GAP (avoids endless
    # re-pushing of touching pairs through rounding)
    resolve2 = (contact - SLOP_MM) * (contact - SLOP_MM)
    walls = cfg.arena > 0.0
    arena = cfg.arena
    head, nxt, prv, cell_x, cell_y = grid.head, grid.nxt, grid.prv, grid.cell_x, grid.cell_y
    known_pos = grid.known_pos
    inv = grid.inv_cell[0]
    mask = head.shape[0] - 1
    cur = dirty
    nxt_list = spare
    n_cur = n_dirty
    passes = 0
    pushes = 0
    while n_cur > 0 and passes < cfg.max_passes:
        for k in range(n_cur):
            dirty_flag[cur[k]] = 0
        n_next = 0
        for k in range(n_cur):
            i = cur[k]
            xi = pos[i, 0]
            yi = pos[i, 1]
            moved_i = False
            for cx in range(cell_of(xi - contact, inv), cell_of(xi + contact, inv) + 1):
                for cy in range(cell_of(yi - contact, inv), cell_of(yi + contact, inv) + 1):
                    j = head[bucket_of(cx, cy, mask)]
                    while j >= 0:
                        j_next = nxt[j]
                        if j != i and cell_x[j] == cx and cell_y[j] == cy:
                            dx = pos[j, 0] - xi
                            dy = pos[j, 1] - yi
                            d2 = dx * dx + dy * dy
                            if d2 < resolve2:
                                d = np.sqrt(d2)
                                if d > 1e-9:
                                    ux = dx / d
                                    uy = dy / d
                                else:  # coincident centres: a fixed direction per pair
                                    ang = 2.399963229728653 * ((i + 1) * (j + 1) % 1024)
                                    ux = np.cos(ang)
                                    uy = np.sin(ang)
                                half = 0.5 * (contact + GAP_MM - d)
                                xi -= half * ux
                                yi -= half * uy
                                xj = pos[j, 0] + half * ux
                                yj = pos[j, 1] + half * uy
                                if walls:
                                    xi = clamp_to_arena(xi, r, arena)
                                    yi = clamp_to_arena(yi, r, arena)
                                    xj = clamp_to_arena(xj, r, arena)
                                    yj = clamp_to_arena(yj, r, arena)
                                pos[j, 0] = xj
                                pos[j, 1] = yj
                                known_pos[j, 0] = xj
                                known_pos[j, 1] = yj
                                ncx = cell_of(xj, inv)
                                ncy = cell_of(yj, inv)
                                if ncx != cell_x[j] or ncy != cell_y[j]:
                                    relink(head, nxt, prv, cell_x, cell_y, j, ncx, ncy)
                                if dirty_flag[j] == 0:
                                    dirty_flag[j] = 1
                                    nxt_list[n_next] = j
                                    n_next += 1
                                moved_i = True
                                pushes += 1
                        j = j_next
            if moved_i:
                pos[i, 0] = xi
                pos[i, 1] = yi
                known_pos[i, 0] = xi
                known_pos[i, 1] = yi
                ncx = cell_of(xi, inv)
                ncy = cell_of(yi, inv)
                if ncx != cell_x[i] or ncy != cell_y[i]:
                    relink(head, nxt, prv, cell_x, cell_y, i, ncx, ncy)
                if dirty_flag[i] == 0:
                    dirty_flag[i] = 1
                    nxt_list[n_next] = i
                    n_next += 1
        tmp = cur
        cur = nxt_list
        nxt_list = tmp
        n_cur = n_next
        passes += 1
    if n_cur > 0:
        counters[5] += 1
        for k in range(n_cur):
            dirty_flag[cur[k]] = 0
    counters[4] += pushes
