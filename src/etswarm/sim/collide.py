"""Phase 4 of a tick: collisions. Bodies are discs of radius r; no two present robots
may overlap.

Only robots on the work list are examined: robots that were pushed or edited from
outside, and robots that moved further than their budget. Budgets keep this exact: for
every pair of robots, budget_i + budget_j <= (centre distance - 2r), and no budget
exceeds margin/2 (the grid's slack). Travelling d mm costs d mm of budget and cannot
shrink a distance by more, so two robots with budget left cannot touch. An examined robot
that does not move gets budget min(margin/2, min_j gap_j/2) over its neighbours j
within 2r + margin, whose budgets are lowered to gap_j/2 where needed; a pushed robot
gets budget 0. A still swarm costs nothing here, and a robot in open space is examined
only every few ticks. Each pass takes every
listed robot i, finds the present robots j with centre distance < 2r - slop (cell-list
query of radius 2r) and pushes the pair apart along the centre line, half the overlap
each, so they stand 2r apart (when exactly one of the two has its motors on, the still
one takes only ``still_push_share`` of the overlap: it grips the ground); walls clamp
afterwards. Every robot that a pass moved goes on the next pass's list: a pushed robot
moves, and may push others. Passes repeat until
nothing moves or ``max_passes`` is reached (then the tick ends with the remaining small
overlaps, counted in counters[5], and the robots still to examine start the next tick's
list, so nothing is forgotten). Alive and dead robots are pushed alike. Overlaps
below ``push_slop_mm`` (0.1 mm) are left alone: chasing them would ripple tiny pushes
through every cluster of touching robots on every tick.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.sim.fpmath import sin_cos
from etswarm.sim.motion import clamp_to_arena
from etswarm.sim.neighbours import (
    G_CELL,
    G_DRIFT,
    G_INV,
    G_MARGIN,
    G_OX,
    G_OY,
    L_COUNT,
    L_EPOCH,
    L_FIRST,
    P_BUDGET,
    P_X,
    P_Y,
    R_BX,
    R_BY,
    S_DRIFTED,
    S_EPOCH,
    cell_range,
    contact_list_from,
    drifted,
    list_reach,
    new_epoch,
    rebuild_keeping_list,
)


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def collide_phase(cfg, grid, pos, present, motor, dirty, dirty_flag, n_dirty, spare, counters):
    """Resolve overlaps starting from the work list ``dirty[:n_dirty]`` (grid slots).

    ``dirty_flag`` (N,) uint8 marks listed slots; ``spare`` is a second (N,) int32 work
    array. Works in slot order (robots that are near each other are near in memory) and
    writes every displacement to ``pos`` too; a long work list is processed in slot
    order, so consecutive examinations touch the same cells. On return the work list is
    empty, all flags are cleared and the grid is valid, unless ``max_passes`` ran out:
    then the robots still to examine stay listed in ``dirty`` (and flagged) and their
    number is returned (also kept in ``grid.state[2]``) to start the next tick's list.
    """
    # slots near the robot being examined and their squared distances (mm^2); slots are
    # unsigned here and below so that indexing needs no negative-index wraparound
    n_slots = dirty_flag.shape[0]
    near = np.empty(n_slots, dtype=np.uint32)
    near_d2 = np.empty(n_slots)
    return resolve_overlaps(cfg, grid, pos, present, motor, dirty, dirty_flag, n_dirty, spare,
                            counters, near, near_d2)


@njit(cache=True, _nrt=False)
def resolve_overlaps(cfg, grid, pos, present, motor, dirty, dirty_flag, n_dirty, spare,
                     counters, near, near_d2):
    """:func:`collide_phase`'s work, in the scratch rows ``near`` (N,) uint32 and
    ``near_d2`` (N,) float64. Compiled without numba's reference counting: it allocates
    nothing and its arrays are held by its caller."""
    r = cfg.radius
    still_share = cfg.still_share
    contact = 2.0 * r
    resolve2 = (contact - cfg.slop) * (contact - cfg.slop)
    walls = cfg.arena > 0.0
    arena = cfg.arena
    start, sxb, sidx, sref = grid.start, grid.sxb, grid.sidx, grid.sref
    # robots filed up to `margin` away from their cell: a query of contact + 2 margin
    # finds every robot within contact + margin, the range that budgets depend on
    margin = grid.geom[G_MARGIN]
    reach = contact + 2.0 * margin
    near2 = (contact + margin) * (contact + margin)
    half_margin = 0.5 * margin
    contact2 = contact * contact
    share_k = 0.5 / (2.0 * contact + margin)
    n_slots = dirty_flag.shape[0]
    cur = dirty
    nxt_list = spare
    swapped = False
    n_cur = n_dirty
    passes = 0
    pushes = 0
    examined = 0
    stale = False
    near_r = contact + margin
    drift2 = grid.geom[G_DRIFT] * grid.geom[G_DRIFT]
    near_slots = grid.near_slots
    list_r2, list_reach_mm = list_reach(grid, near_r)
    while n_cur > 0 and passes < cfg.max_passes:
        if stale:
            n_cur = rebuild_keeping_list(grid, pos, present, cur, n_cur, dirty_flag)
            stale = False
        if grid.state[S_DRIFTED] != 0:
            new_epoch(grid)
        # contact lists may be used and built while nobody drifted (see neighbours)
        lists_ok = True
        epoch = grid.state[S_EPOCH]
        epoch32 = np.int32(epoch)
        # grid geometry (changes only at a rebuild)
        span = grid.geom[G_CELL] + 2.0 * grid.geom[G_MARGIN]
        inv = grid.geom[G_INV]
        ox = grid.geom[G_OX]
        oy = grid.geom[G_OY]
        nx = grid.dims[0]
        ny = grid.dims[1]
        if 8 * n_cur > n_slots:
            # a long list: take it in slot order (neighbours in memory) by scanning flags
            # (branch-free: every slot is written, the count advances on flagged ones)
            n_cur = 0
            for a in range(n_slots):
                cur[n_cur] = a
                n_cur += dirty_flag[a] != 0
                dirty_flag[a] = 0
        else:
            for k in range(n_cur):
                dirty_flag[cur[k]] = 0
        n_next = 0
        examined += n_cur
        for k in range(n_cur):
            a = cur[k]
            xi = sxb[a, P_X]
            yi = sxb[a, P_Y]
            moved_i = False
            own = half_margin
            still_a = motor[sidx[a]] == 0
            n_list = -1
            if lists_ok:
                if near_slots[a, L_EPOCH] != epoch32:
                    contact_list_from(start, sxb, near_slots, a, xi, yi, list_r2,
                                      list_reach_mm, ox, oy, inv, nx, ny, 0, ny - 1, epoch,
                                      near)
                n_list = near_slots[a, L_COUNT]
            if n_list >= 0:
                # the listed slots (a superset of those within contact + margin, in slot
                # order) in one loop: budgets and the choice of pairs to push from the
                # position at the start of the examination (x0, y0), as the cell query
                # does; beyond contact + margin the share is half the margin, which
                # changes no budget (none exceeds it), selected by arithmetic that gives
                # exactly one of the two values (a branch here is mispredicted often)
                x0 = xi
                y0 = yi
                for q in range(L_FIRST, L_FIRST + n_list):
                    s = np.uint32(near_slots[a, q])
                    xs = sxb[s, P_X]
                    ys = sxb[s, P_Y]
                    dx = xs - x0
                    dy = ys - y0
                    d2 = dx * dx + dy * dy
                    within = np.float64(d2 < near2)
                    share = (within * max((d2 - contact2) * share_k, 0.0)
                             + (1.0 - within) * half_margin)
                    own = min(own, share)
                    sxb[s, P_BUDGET] = min(sxb[s, P_BUDGET], share)
                    if d2 >= resolve2:
                        continue
                    # a pair to push, from where robot a stands now
                    dx = xs - xi
                    dy = ys - yi
                    d2 = dx * dx + dy * dy
                    if d2 >= resolve2:  # no longer overlapping after earlier pushes
                        continue
                    j = sidx[s]
                    xi, yi, xj, yj = push_apart(a, s, dx, dy, d2, xi, yi, xs, ys, still_a,
                                                motor[j] == 0, contact, still_share, r,
                                                walls, arena)
                    far, left_box = place_pushed(s, j, xj, yj, sxb, sref, pos, drift2, span)
                    lists_ok = lists_ok and not far
                    stale = stale or left_box
                    # listed once: written always, kept if new (no branch to mispredict;
                    # the bound check fails only when every slot is listed)
                    if n_next < n_slots:
                        nxt_list[n_next] = s
                    n_next += dirty_flag[s] == 0
                    dirty_flag[s] = 1
                    moved_i = True
                    pushes += 1
            else:
                n_over, own = gather_overlaps(a, xi, yi, own, reach, near2, contact2,
                                              share_k, resolve2, ox, oy, inv, nx, ny, start,
                                              sxb, near, near_d2)
                for q in range(n_over):
                    s = near[q]
                    xs = sxb[s, P_X]
                    ys = sxb[s, P_Y]
                    dx = xs - xi
                    dy = ys - yi
                    d2 = dx * dx + dy * dy
                    if d2 >= resolve2:  # no longer overlapping after earlier pushes
                        continue
                    j = sidx[s]
                    xi, yi, xj, yj = push_apart(a, s, dx, dy, d2, xi, yi, xs, ys, still_a,
                                                motor[j] == 0, contact, still_share, r,
                                                walls, arena)
                    far, left_box = place_pushed(s, j, xj, yj, sxb, sref, pos, drift2, span)
                    lists_ok = lists_ok and not far
                    stale = stale or left_box
                    if n_next < n_slots:
                        nxt_list[n_next] = s
                    n_next += dirty_flag[s] == 0
                    dirty_flag[s] = 1
                    moved_i = True
                    pushes += 1
            i = sidx[a]
            if not moved_i:
                sxb[a, P_BUDGET] = own
            else:
                sxb[a, P_BUDGET] = 0.0
                sxb[a, P_X] = xi
                sxb[a, P_Y] = yi
                pos[i, 0] = xi
                pos[i, 1] = yi
                if drifted(sref, a, xi, yi, drift2):
                    lists_ok = False
                bx = sref[a, R_BX]
                by = sref[a, R_BY]
                if xi < bx or xi >= bx + span or yi < by or yi >= by + span:
                    stale = True
                if n_next < n_slots:
                    nxt_list[n_next] = a
                n_next += dirty_flag[a] == 0
                dirty_flag[a] = 1
        if not lists_ok:
            grid.state[S_DRIFTED] = 1
        tmp = cur
        cur = nxt_list
        nxt_list = tmp
        swapped = not swapped
        n_cur = n_next
        passes += 1
    if n_cur > 0:
        # out of passes: the rest of the list (flags set, budgets 0) is carried over to
        # the next tick's list, so the remaining overlaps are resolved there
        counters[5] += 1
        if swapped:
            for k in range(n_cur):
                dirty[k] = cur[k]
    if stale:
        n_cur = rebuild_keeping_list(grid, pos, present, dirty, n_cur, dirty_flag)
    grid.state[2] = n_cur
    counters[4] += pushes
    counters[6] += examined
    return n_cur


@njit(cache=True)
def place_pushed(s, j, xj, yj, sxb, sref, pos, drift2, span):
    """Slot ``s`` (robot ``j``) was pushed to (xj, yj) mm: write it to the slot row (its
    budget used up) and to ``pos``. Returns (moved beyond the epoch's drift, left its
    slack box), the two conditions that make contact lists or the grid stale."""
    sxb[s, P_X] = xj
    sxb[s, P_Y] = yj
    sxb[s, P_BUDGET] = 0.0
    pos[j, 0] = xj
    pos[j, 1] = yj
    bx = sref[s, R_BX]
    by = sref[s, R_BY]
    left_box = xj < bx or xj >= bx + span or yj < by or yj >= by + span
    return drifted(sref, s, xj, yj, drift2), left_box


@njit(cache=True)
def push_apart(a, s, dx, dy, d2, xi, yi, xs, ys, still_a, still_s, contact, still_share, r,
               walls, arena):
    """Push slots ``a`` at (xi, yi) and ``s`` at (xs, ys) apart along their centre line,
    (dx, dy) = s - a, d2 its squared length (< contact^2), so that they stand ``contact``
    apart: half each, or when exactly one of them is still (``still_a``, ``still_s``:
    motors off) the still one takes ``still_share``; walls at 0 and ``arena`` if
    ``walls``. Returns the new (xi, yi, xs, ys)."""
    d = np.sqrt(d2)
    if d > 1e-9:
        ux = dx / d
        uy = dy / d
    else:  # coincident centres: a fixed direction per pair
        ang = 2.399963229728653 * ((a + 1) * (s + 1) % 1024)
        uy, ux = sin_cos(ang)  # the same bits everywhere (``fpmath``)
    # a robot standing on its legs slides less than a vibrating one
    share_j = 0.5
    if still_a != still_s:
        share_j = still_share if still_s else 1.0 - still_share
    depth = contact - d
    xi -= (1.0 - share_j) * depth * ux
    yi -= (1.0 - share_j) * depth * uy
    xj = xs + share_j * depth * ux
    yj = ys + share_j * depth * uy
    if walls:
        xi = clamp_to_arena(xi, r, arena)
        yi = clamp_to_arena(yi, r, arena)
        xj = clamp_to_arena(xj, r, arena)
        yj = clamp_to_arena(yj, r, arena)
    return xi, yi, xj, yj


@njit(cache=True)
def gather_overlaps(a, xi, yi, own, reach, near2, contact2, share_k, resolve2, ox, oy, inv,
                    nx, ny, start, sxb, near, near_d2):
    """The cell query of an examination: lower the budgets of the slots within
    contact + margin of slot ``a`` at (xi, yi) to their share of the gap, write the
    overlapping ones to ``near`` in slot order; returns (their number, own budget)."""
    cx0, cx1 = cell_range(xi, reach, ox, inv, nx)
    cy0, cy1 = cell_range(yi, reach, oy, inv, ny)
    # gather the slots within contact + margin without branching on distances
    n_near = 0
    ua = np.uint64(a)
    # a query covers at most 2 rows (cell = query width); each row's cells are
    # one run of slots, and both runs are walked as one loop (one loop exit to
    # mispredict instead of two); the step of 2 keeps larger queries correct
    for cy in range(cy0, cy1 + 1, 2):
        row = cy * nx
        b0 = np.uint64(start[row + cx0])
        len0 = np.uint64(start[row + cx1 + 1]) - b0
        if cy + 1 <= cy1:
            b1 = np.uint64(start[row + nx + cx0])
            len1 = np.uint64(start[row + nx + cx1 + 1]) - b1
        else:
            b1 = np.uint64(0)
            len1 = np.uint64(0)
        gap = b1 - len0  # modulo 2^64: t + gap = b1 + (t - len0) for t >= len0
        for t in range(len0 + len1):
            s = t + (b0 if t < len0 else gap)
            dx = sxb[s, P_X] - xi
            dy = sxb[s, P_Y] - yi
            d2 = dx * dx + dy * dy
            near[n_near] = s
            near_d2[n_near] = d2
            n_near += (d2 < near2) & (s != ua)
    # share the gaps between budgets (lowering a budget is always safe) and
    # pick out the overlapping ones, again without branches on distances
    n_over = 0
    for q in range(n_near):
        s = near[q]
        d2 = near_d2[q]
        # half the gap d - 2r, bounded below without a sqrt:
        # d - c = (d^2 - c^2) / (d + c) and d + c <= 2c + margin
        share = max((d2 - contact2) * share_k, 0.0)
        own = min(own, share)
        sxb[s, P_BUDGET] = min(sxb[s, P_BUDGET], share)
        near[n_over] = s
        n_over += d2 < resolve2
    return n_over, own
