"""The ET robot controller (paper Algorithm 1), compiled with numba, over all robots.

``et_step`` follows the simulator's fast-path controller contract: it reads each robot's
inbox (messages heard this tick with a distance estimate), updates that robot's own
memory (``memory`` module layout), and writes its motors, LED (= state code) and next
status message. It never reads positions, headings or another robot's memory.

Per robot and tick the phases are: ingest messages into the neighbour table; run the
state's rule (Queued release, Search edge-following and localisation, or the placed
states' Inactive -> Active -> Quasi/Stable transitions); encode the status message.
Placed and Queued robots re-evaluate only every ``C_EVAL_EVERY`` ticks (staggered by ID),
so stationary robots cost a few operations per tick.
"""

from __future__ import annotations

import math

from numba import njit

from etswarm.algorithm.memory import (
    NB_FLOOR,
    NB_ID,
    NB_LAST,
    NB_MASK,
    NB_PREV,
    NB_QMIN,
    NB_RELEASED,
    NB_STATE,
    NB_TS,
    NB_TX,
    NB_TY,
    R_BELOW_SINCE,
    R_CAND_X,
    R_CAND_Y,
    R_COOLDOWN,
    R_COUNT,
    R_EPOCH,
    R_FLOOR,
    R_FLOOR_SINCE,
    R_MASK,
    R_NN,
    R_QMIN,
    R_QMIN_SINCE,
    R_QUASI_UNTIL,
    R_REF_ID,
    R_RELEASED,
    R_SINCE,
    R_STATE,
    R_SUB,
    R_SUB_SINCE,
    R_TAG_X,
    R_TAG_Y,
    R_TS,
    R_YIELD_SINCE,
    R_YLD_ID,
    R_YLD_TREND,
    SUB_FOLLOW,
    SUB_SETTLE,
)
from etswarm.algorithm.messages import MSG_STATUS
from etswarm.algorithm.params import (
    C_EVAL_EVERY,
    C_GENE_X0,
    C_GENE_Y0,
    C_RELEASE_LIMIT,
    C_TICKS_CLEAR,
    C_TICKS_COOLDOWN,
    C_TICKS_DANGER,
    C_TICKS_MOVE_FRESH,
    C_TICKS_NB_FRESH,
    C_TICKS_QUASI,
    C_TICKS_QUIET,
    C_TICKS_RELEASE,
    C_TICKS_SETTLE,
    C_TICKS_YIELD_MAX,
    F_BALANCE_TOL,
    F_CLEARANCE,
    F_CLOSING,
    F_CONSIST_TOL,
    F_FOLLOW_BAND,
    F_FOLLOW_OFFSET,
    F_NB_RADIUS,
    F_PAIR_TOL,
    F_SPACING,
    F_YIELD_DIST,
)

# State codes (mirror of states.State; numba needs plain ints).
QUEUED = 0
SEARCH = 1
INACTIVE = 2
ACTIVE = 3
QUASI = 4
STABLE = 5
DANGER = 6
LEADER = 7

# Motor commands (simulator contract).
STOP = 0
FORWARD = 1
LEFT = 2
RIGHT = 3

HALF_SQRT3 = 0.8660254037844386
FAR = 1.0e9
#: Readings of a searching robot older than this (ticks) are ignored for steering.
SEARCHER_FRESH_TICKS = 31
#: Inactive robots with no Active neighbour for this many evaluations become Active.
INACTIVE_PATIENCE_TICKS = 31 * 60

# The six lattice directions in cyclic order (DESIGN §1).
DIR_X = (0, 1, 1, 0, -1, -1)
DIR_Y = (1, 1, 0, -1, -1, 0)


@njit(cache=True, inline="always")
def is_placed(state):  # type: ignore[no-untyped-def]
    """True for the states that hold a lattice tag."""
    return state >= INACTIVE


@njit(cache=True, inline="always")
def direction_index(dx, dy):  # type: ignore[no-untyped-def]
    """Index 0..5 of the lattice direction (dx, dy), or -1 if not a neighbour offset."""
    if dx == 0 and dy == 1:
        return 0
    if dx == 1 and dy == 1:
        return 1
    if dx == 1 and dy == 0:
        return 2
    if dx == 0 and dy == -1:
        return 3
    if dx == -1 and dy == -1:
        return 4
    if dx == -1 and dy == 0:
        return 5
    return -1


@njit(cache=True, inline="always")
def lattice_distance(ax, ay, bx, by):  # type: ignore[no-untyped-def]
    """Distance between tags (ax, ay) and (bx, by) in lattice spacings."""
    dy = ay - by
    dx = (ax - bx) - 0.5 * dy
    return math.sqrt(dx * dx + (dy * HALF_SQRT3) ** 2)


@njit(cache=True, inline="always")
def gene_flag_at(gene_flag, ci, x, y):  # type: ignore[no-untyped-def]
    gx = x - ci[C_GENE_X0]
    gy = y - ci[C_GENE_Y0]
    if gx < 0 or gy < 0 or gx >= gene_flag.shape[0] or gy >= gene_flag.shape[1]:
        return 0
    return gene_flag[gx, gy]


@njit(cache=True, inline="always")
def gene_nn_at(gene_nn, ci, x, y):  # type: ignore[no-untyped-def]
    gx = x - ci[C_GENE_X0]
    gy = y - ci[C_GENE_Y0]
    if gx < 0 or gy < 0 or gx >= gene_nn.shape[0] or gy >= gene_nn.shape[1]:
        return 0
    return gene_nn[gx, gy]


@njit(cache=True)
def ingest(i, k, tick, in_data, in_dist, nb, nb_dist):  # type: ignore[no-untyped-def]
    """Store message k of robot i's inbox in its neighbour table (oldest slot recycled)."""
    sender = int(in_data[i, k, 0]) | (int(in_data[i, k, 1]) << 8)
    state = int(in_data[i, k, 2]) & 0x0F
    slots = nb.shape[1]
    slot = -1
    free = -1
    oldest = -1
    oldest_tick = 1 << 62
    for m in range(slots):
        sid = nb[i, m, NB_ID]
        if sid == sender:
            slot = m
            break
        if sid < 0:
            if free < 0:
                free = m
        elif nb[i, m, NB_LAST] < oldest_tick:
            oldest_tick = nb[i, m, NB_LAST]
            oldest = m
    if slot < 0:
        slot = free if free >= 0 else oldest
        nb[i, slot, NB_ID] = sender
        nb[i, slot, NB_PREV] = -1
        nb[i, slot, NB_STATE] = state
    elif nb[i, slot, NB_STATE] != state:
        nb[i, slot, NB_PREV] = nb[i, slot, NB_STATE]
        nb[i, slot, NB_STATE] = state
    nb[i, slot, NB_LAST] = tick
    nb_dist[i, slot] = in_dist[i, k]
    if state >= INACTIVE:
        tx = int(in_data[i, k, 3])
        ty = int(in_data[i, k, 4])
        nb[i, slot, NB_TX] = tx - 256 if tx >= 128 else tx
        nb[i, slot, NB_TY] = ty - 256 if ty >= 128 else ty
        nb[i, slot, NB_TS] = int(in_data[i, k, 5]) | (int(in_data[i, k, 6]) << 8)
        nb[i, slot, NB_MASK] = int(in_data[i, k, 7])
    else:
        nb[i, slot, NB_QMIN] = int(in_data[i, k, 3]) | (int(in_data[i, k, 4]) << 8)
        nb[i, slot, NB_FLOOR] = (int(in_data[i, k, 5]) | (int(in_data[i, k, 6]) << 8)) - 1
        nb[i, slot, NB_RELEASED] = int(in_data[i, k, 7]) | (int(in_data[i, k, 8]) << 8)


@njit(cache=True)
def encode(i, ri, out_on, out_type, out_data):  # type: ignore[no-untyped-def]
    """Write robot i's status message (layout in ``messages``)."""
    state = ri[i, R_STATE]
    out_on[i] = True
    out_type[i] = MSG_STATUS
    out_data[i, 0] = i & 0xFF
    out_data[i, 1] = (i >> 8) & 0xFF
    out_data[i, 2] = state
    if state >= INACTIVE:
        out_data[i, 3] = ri[i, R_TAG_X] & 0xFF
        out_data[i, 4] = ri[i, R_TAG_Y] & 0xFF
        out_data[i, 5] = ri[i, R_TS] & 0xFF
        out_data[i, 6] = (ri[i, R_TS] >> 8) & 0xFF
        out_data[i, 7] = ri[i, R_MASK] & 0x3F
        out_data[i, 8] = ri[i, R_EPOCH] & 0xFF
    else:
        out_data[i, 3] = ri[i, R_QMIN] & 0xFF
        out_data[i, 4] = (ri[i, R_QMIN] >> 8) & 0xFF
        floor1 = ri[i, R_FLOOR] + 1
        out_data[i, 5] = floor1 & 0xFF
        out_data[i, 6] = (floor1 >> 8) & 0xFF
        out_data[i, 7] = ri[i, R_RELEASED] & 0xFF
        out_data[i, 8] = (ri[i, R_RELEASED] >> 8) & 0xFF


@njit(cache=True)
def set_state(i, ri, state, tick):  # type: ignore[no-untyped-def]
    ri[i, R_STATE] = state
    ri[i, R_SINCE] = tick


@njit(cache=True)
def queued_rule(i, tick, ri, nb, ci):  # type: ignore[no-untyped-def]
    """Lowest-ID release from the repository (floor/min flooding, see ``messages``).

    A robot leaves only when it has heard no searching robot for ``C_TICKS_CLEAR`` ticks,
    so searchers never start side by side and the traffic around the repository throttles
    the release rate.
    """
    fresh = ci[C_TICKS_NB_FRESH]
    floor = ri[i, R_FLOOR]
    released = ri[i, R_RELEASED]
    slots = nb.shape[1]
    last_searcher = -(1 << 40)
    for m in range(slots):
        if nb[i, m, NB_ID] >= 0 and nb[i, m, NB_STATE] == SEARCH:
            last_searcher = max(last_searcher, nb[i, m, NB_LAST])
        if nb[i, m, NB_ID] >= 0 and tick - nb[i, m, NB_LAST] <= fresh:
            st = nb[i, m, NB_STATE]
            if st <= SEARCH:
                floor = max(floor, nb[i, m, NB_FLOOR])
                released = max(released, nb[i, m, NB_RELEASED])
    qmin = i
    for m in range(slots):
        sid = nb[i, m, NB_ID]
        if sid >= 0 and tick - nb[i, m, NB_LAST] <= fresh and nb[i, m, NB_STATE] == QUEUED:
            if floor < sid < qmin:
                qmin = sid
            q = nb[i, m, NB_QMIN]
            if floor < q < qmin:
                qmin = q
    if floor != ri[i, R_FLOOR]:
        ri[i, R_FLOOR] = floor
        ri[i, R_FLOOR_SINCE] = tick
    ri[i, R_RELEASED] = released
    if qmin != ri[i, R_QMIN]:
        ri[i, R_QMIN] = qmin
        ri[i, R_QMIN_SINCE] = tick
    if (
        qmin == i
        and i > floor
        and tick - last_searcher >= ci[C_TICKS_CLEAR]
        and released < ci[C_RELEASE_LIMIT]
        and tick - ri[i, R_QMIN_SINCE] >= ci[C_TICKS_QUIET]
        and tick - ri[i, R_FLOOR_SINCE] >= ci[C_TICKS_RELEASE]
    ):
        set_state(i, ri, SEARCH, tick)
        ri[i, R_FLOOR] = i
        ri[i, R_FLOOR_SINCE] = tick
        ri[i, R_RELEASED] = released + 1
        ri[i, R_SUB] = SUB_FOLLOW
        ri[i, R_SUB_SINCE] = tick
        ri[i, R_YIELD_SINCE] = -1
        ri[i, R_COOLDOWN] = tick


@njit(cache=True)
def site_taken(i, x, y, nb):  # type: ignore[no-untyped-def]
    """Robot i knows that site (x, y) is held: a placed robot in its table holds it (placed
    robots stay put), or a placed robot next to it reports that neighbour site held."""
    for j in range(nb.shape[1]):
        if nb[i, j, NB_ID] < 0 or not is_placed(nb[i, j, NB_STATE]):
            continue
        jx = nb[i, j, NB_TX]
        jy = nb[i, j, NB_TY]
        if jx == x and jy == y:
            return True
        k = direction_index(x - jx, y - jy)
        if k >= 0 and (nb[i, j, NB_MASK] >> k) & 1:
            return True
    return False


@njit(cache=True)
def known_held(i, x, y, nb, cx, cy):  # type: ignore[no-untyped-def]
    """Site (x, y) is held, as robot i knows (or is the site (cx, cy) it would take)."""
    if x == cx and y == cy:
        return True
    return site_taken(i, x, y, nb)


@njit(cache=True)
def encloses_a_site(i, cx, cy, nb, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Taking (cx, cy) would leave a free shape site next to it with no two adjacent free
    neighbour sites: a robot could no longer reach it between its neighbours."""
    for k in range(6):
        sx = cx + DIR_X[k]
        sy = cy + DIR_Y[k]
        if gene_flag_at(gene_flag, ci, sx, sy) != 1 or site_taken(i, sx, sy, nb):
            continue
        prev_free = not known_held(i, sx + DIR_X[5], sy + DIR_Y[5], nb, cx, cy)
        opening = False
        for q in range(6):
            free = not known_held(i, sx + DIR_X[q], sy + DIR_Y[q], nb, cx, cy)
            if free and prev_free:
                opening = True
                break
            prev_free = free
        if not opening:
            return True
    return False


@njit(cache=True)
def find_site(i, tick, since, strict, nb, nb_dist, gene_flag, ci, cf):  # type: ignore[no-untyped-def]
    """Localise robot i from its placed neighbours (paper Sec. 4.1).

    Two placed robots heard at about d whose tags are adjacent put the robot at one of
    their two common lattice neighbours, ``c`` or its mirror ``c2``. The robot takes ``c``
    only with evidence that it is not at ``c2``: ``c2`` is held by a robot it knows of, or
    a third placed robot heard since ``since`` is at the distance ``c`` predicts and not
    at the one ``c2`` predicts. ``c`` must also have gene flag 1, be held by no robot it
    knows of, agree with every placed robot heard since ``since`` and, when ``strict``,
    every known robot of a neighbouring site must have been heard since ``since``; and
    an Active robot must be adjacent to it (the least TS among them is returned); and
    taking it must not shut a free shape site next to it in (``encloses_a_site``).

    Returns ``(found, x, y, min_active_ts)``; the best-fitting candidate wins.
    """
    d = cf[F_SPACING]
    pair_tol = cf[F_PAIR_TOL]
    balance_tol = cf[F_BALANCE_TOL]
    consist_tol = cf[F_CONSIST_TOL]
    fresh = ci[C_TICKS_NB_FRESH]
    slots = nb.shape[1]
    best_err = FAR
    best_x = 0
    best_y = 0
    best_ts = 0
    for a in range(slots):
        if nb[i, a, NB_ID] < 0 or not is_placed(nb[i, a, NB_STATE]):
            continue
        if nb[i, a, NB_LAST] < since or abs(nb_dist[i, a] - d) > pair_tol:
            continue
        ax = nb[i, a, NB_TX]
        ay = nb[i, a, NB_TY]
        for b in range(a + 1, slots):
            if nb[i, b, NB_ID] < 0 or not is_placed(nb[i, b, NB_STATE]):
                continue
            if nb[i, b, NB_LAST] < since or abs(nb_dist[i, b] - d) > pair_tol:
                continue
            if abs(nb_dist[i, a] - nb_dist[i, b]) > balance_tol:
                # Settle midway between the two references, not where the window opens.
                continue
            k = direction_index(nb[i, b, NB_TX] - ax, nb[i, b, NB_TY] - ay)
            if k < 0:
                continue
            for side in range(2):
                kk = (k + 5) % 6 if side == 0 else (k + 1) % 6
                k2 = (k + 1) % 6 if side == 0 else (k + 5) % 6
                cx = ax + DIR_X[kk]
                cy = ay + DIR_Y[kk]
                c2x = ax + DIR_X[k2]
                c2y = ay + DIR_Y[k2]
                if gene_flag_at(gene_flag, ci, cx, cy) != 1 or site_taken(i, cx, cy, nb):
                    continue
                if encloses_a_site(i, cx, cy, nb, gene_flag, ci):
                    continue
                ruled_out_mirror = site_taken(i, c2x, c2y, nb)
                ok = True
                err = 0.0
                min_ts = -1
                for j in range(slots):
                    if nb[i, j, NB_ID] < 0 or not is_placed(nb[i, j, NB_STATE]):
                        continue
                    jx = nb[i, j, NB_TX]
                    jy = nb[i, j, NB_TY]
                    pred = lattice_distance(cx, cy, jx, jy) * d
                    if nb[i, j, NB_LAST] >= since:
                        e = abs(nb_dist[i, j] - pred)
                        if e > consist_tol:
                            ok = False
                            break
                        err += e
                        pred2 = lattice_distance(c2x, c2y, jx, jy) * d
                        if abs(nb_dist[i, j] - pred2) > consist_tol:
                            ruled_out_mirror = True
                    elif strict and pred < 1.2 * d:
                        # A lattice neighbour of the site must have been heard by now.
                        ok = False
                        break
                    if tick - nb[i, j, NB_LAST] > fresh:
                        continue
                    if nb[i, j, NB_STATE] == ACTIVE and direction_index(jx - cx, jy - cy) >= 0:
                        ts = nb[i, j, NB_TS]
                        if min_ts < 0 or ts < min_ts:
                            min_ts = ts
                if ok and ruled_out_mirror and min_ts >= 0 and err < best_err:
                    best_err = err
                    best_x = cx
                    best_y = cy
                    best_ts = min_ts
    return best_err < FAR, best_x, best_y, best_ts


@njit(cache=True)
def search_rule(i, tick, new_msgs, ri, nb, nb_dist, motor, gene_flag, gene_nn, ci, cf):  # type: ignore[no-untyped-def]
    """Edge-follow the group clockwise at about d, yield, settle on a free site."""
    d = cf[F_SPACING]
    steer_fresh = ci[C_TICKS_MOVE_FRESH]
    closing = cf[F_CLOSING]
    slots = nb.shape[1]
    # Steer by the nearest placed robot once the shape is heard (by the repository
    # before); every other robot heard is an obstacle to keep clear of.
    placed_est = FAR
    placed_slot = -1
    queued_est = FAR
    queued_slot = -1
    nearest_searcher = FAR
    nearest_lower_searcher = FAR
    lower_slot = -1
    for m in range(slots):
        if nb[i, m, NB_ID] < 0 or tick - nb[i, m, NB_LAST] > steer_fresh:
            continue
        # Worst case: the robot closed in at ``closing`` mm per tick since the reading.
        est = nb_dist[i, m] - closing * (tick - nb[i, m, NB_LAST])
        st = nb[i, m, NB_STATE]
        if st == SEARCH:
            if tick - nb[i, m, NB_LAST] > SEARCHER_FRESH_TICKS:
                continue  # a moving robot's old reading says nothing about now
            nearest_searcher = min(nearest_searcher, est)
            if nb[i, m, NB_ID] < i and est < nearest_lower_searcher:
                nearest_lower_searcher = est
                lower_slot = m
        elif is_placed(st):
            if est < placed_est:
                placed_est = est
                placed_slot = m
        elif est < queued_est:
            queued_est = est
            queued_slot = m
    lost = False
    reading = FAR
    if placed_slot >= 0:
        reading = nb_dist[i, placed_slot]
        nearest = placed_est
        obstacle = min(queued_est, nearest_searcher)
        track_trend(i, ri, nb, nb_dist, placed_slot, R_REF_ID)
    elif queued_slot >= 0:
        reading = nb_dist[i, queued_slot]
        nearest = queued_est
        obstacle = nearest_searcher
        track_trend(i, ri, nb, nb_dist, queued_slot, R_REF_ID)
    else:
        # Nothing stationary in earshot: circle clockwise to find the group again.
        lost = True
        nearest = FAR
        obstacle = nearest_searcher

    if ri[i, R_SUB] == SUB_SETTLE:
        motor[i] = STOP
        if tick - ri[i, R_SUB_SINCE] < ci[C_TICKS_SETTLE]:
            return
        found, cx, cy, min_ts = find_site(
            i, tick, ri[i, R_SUB_SINCE], True, nb, nb_dist, gene_flag, ci, cf
        )
        if found and cx == ri[i, R_CAND_X] and cy == ri[i, R_CAND_Y]:
            set_state(i, ri, INACTIVE, tick)
            ri[i, R_TAG_X] = cx
            ri[i, R_TAG_Y] = cy
            ri[i, R_NN] = gene_nn_at(gene_nn, ci, cx, cy)
            ri[i, R_TS] = min_ts + 1
            ri[i, R_COUNT] = 0
            ri[i, R_BELOW_SINCE] = -1
        else:
            ri[i, R_SUB] = SUB_FOLLOW
            ri[i, R_SUB_SINCE] = tick
            ri[i, R_COOLDOWN] = tick + ci[C_TICKS_COOLDOWN]
        return

    # Yield to a lower-ID searcher nearby, unless this robot stands still and that one is
    # closing in: then it comes from behind, and this robot moves on out of its way.
    if lower_slot >= 0:
        track_trend(i, ri, nb, nb_dist, lower_slot, R_YLD_ID)
    chased = motor[i] == STOP and ri[i, R_YLD_TREND] < 0
    if nearest_lower_searcher < cf[F_YIELD_DIST] and not chased:
        if ri[i, R_YIELD_SINCE] < 0:
            ri[i, R_YIELD_SINCE] = tick
        if tick - ri[i, R_YIELD_SINCE] < ci[C_TICKS_YIELD_MAX]:
            motor[i] = STOP
            return
    else:
        ri[i, R_YIELD_SINCE] = -1

    if new_msgs and tick >= ri[i, R_COOLDOWN]:
        found, cx, cy, min_ts = find_site(
            i, tick, tick - steer_fresh, False, nb, nb_dist, gene_flag, ci, cf
        )
        if found:
            motor[i] = STOP
            ri[i, R_SUB] = SUB_SETTLE
            ri[i, R_SUB_SINCE] = tick
            ri[i, R_CAND_X] = cx
            ri[i, R_CAND_Y] = cy
            return

    cf[F_FOLLOW_BAND]
    aim = d + cf[F_FOLLOW_OFFSET]
    # Kilobot orbit (both pivots also move the body forward): pivot away from the group
    # when the last reading of the reference is nearer than the aim, towards it otherwise.
    # Any robot that may have come nearer than the clearance is turned away from.
    clearance = cf[F_CLEARANCE]
    if obstacle < clearance or nearest < clearance:
        motor[i] = LEFT
    elif lost:
        # Pivot on the spot (within a body length of where the group was last heard).
        motor[i] = RIGHT
    elif reading < aim:
        motor[i] = LEFT
    else:
        motor[i] = RIGHT


@njit(cache=True)
def track_trend(i, ri, nb, nb_dist, slot, base):  # type: ignore[no-untyped-def]
    """Update the distance trend of robot i to the robot in nb slot ``slot``.

    ``base`` is the first of the four tracking fields (see ``memory``): ID, tick of the
    last reading used, that reading (1/16 mm) and the trend (-1, 0, +1; changes under
    0.5 mm count as none).
    """
    sid = nb[i, slot, NB_ID]
    reading = int(nb_dist[i, slot] * 16.0)
    if sid != ri[i, base]:
        ri[i, base] = sid
        ri[i, base + 3] = 0
    elif nb[i, slot, NB_LAST] > ri[i, base + 1]:
        change = reading - ri[i, base + 2]
        if change < -8:
            ri[i, base + 3] = -1
        elif change > 8:
            ri[i, base + 3] = 1
    else:
        return
    ri[i, base + 1] = nb[i, slot, NB_LAST]
    ri[i, base + 2] = reading


@njit(cache=True)
def placed_rule(i, tick, ri, nb, nb_dist, ci, cf):  # type: ignore[no-untyped-def]
    """Inactive -> Active -> Quasi/Stable, and Stable -> Danger (paper Table 1)."""
    fresh = ci[C_TICKS_NB_FRESH]
    radius = cf[F_NB_RADIUS]
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    ts = ri[i, R_TS]
    state = ri[i, R_STATE]
    slots = nb.shape[1]
    seen_dirs = 0
    witnessed_stable = False
    lower_active = False
    any_active = False
    for m in range(slots):
        if nb[i, m, NB_ID] < 0:
            continue
        st = nb[i, m, NB_STATE]
        if not is_placed(st):
            continue
        k = direction_index(nb[i, m, NB_TX] - x, nb[i, m, NB_TY] - y)
        if k < 0:
            continue
        if st == STABLE and nb[i, m, NB_PREV] == ACTIVE:
            witnessed_stable = True
        if tick - nb[i, m, NB_LAST] > fresh or nb_dist[i, m] > radius:
            continue
        seen_dirs |= 1 << k
        if st == ACTIVE:
            any_active = True
            if nb[i, m, NB_TS] < ts:
                lower_active = True
    count = 0
    for k in range(6):
        if seen_dirs & (1 << k):
            count += 1
    ri[i, R_COUNT] = count
    ri[i, R_MASK] = seen_dirs
    nn = ri[i, R_NN]

    if state == INACTIVE:
        if witnessed_stable:
            set_state(i, ri, ACTIVE, tick)
        elif any_active:
            ri[i, R_SINCE] = tick
        elif tick - ri[i, R_SINCE] > INACTIVE_PATIENCE_TICKS:
            set_state(i, ri, ACTIVE, tick)
    elif state == ACTIVE:
        if count >= nn:
            set_state(i, ri, STABLE, tick)
            ri[i, R_BELOW_SINCE] = -1
        elif lower_active:
            set_state(i, ri, QUASI, tick)
            ri[i, R_QUASI_UNTIL] = tick + ci[C_TICKS_QUASI]
    elif state == QUASI:
        if tick >= ri[i, R_QUASI_UNTIL]:
            set_state(i, ri, ACTIVE, tick)
    elif state == STABLE:
        if count >= nn:
            ri[i, R_BELOW_SINCE] = -1
        elif ri[i, R_BELOW_SINCE] < 0:
            ri[i, R_BELOW_SINCE] = tick
        elif tick - ri[i, R_BELOW_SINCE] >= ci[C_TICKS_DANGER]:
            set_state(i, ri, DANGER, tick)


@njit(cache=True)
def et_step(  # type: ignore[no-untyped-def]
    tick, alive, in_count, in_type, in_data, in_dist, motor, led, out_on, out_type, out_data,
    mem, rng,
):
    """One control tick for every robot (simulator fast-path contract)."""
    _stop, ri, nb, nb_dist, gene_flag, gene_nn, ci, cf = mem
    n = ri.shape[0]
    every = ci[C_EVAL_EVERY]
    for i in range(n):
        if not alive[i]:
            continue
        new_msgs = False
        for k in range(in_count[i]):
            if in_type[i, k] == MSG_STATUS:
                ingest(i, k, tick, in_data, in_dist, nb, nb_dist)
                new_msgs = True
        state = ri[i, R_STATE]
        due = (tick + i) % every == 0
        if state == SEARCH:
            search_rule(i, tick, new_msgs, ri, nb, nb_dist, motor, gene_flag, gene_nn, ci, cf)
        elif not due:
            continue
        elif state == QUEUED:
            motor[i] = STOP
            queued_rule(i, tick, ri, nb, ci)
        elif INACTIVE <= state <= STABLE:
            motor[i] = STOP
            placed_rule(i, tick, ri, nb, nb_dist, ci, cf)
        else:
            motor[i] = STOP
        if ri[i, R_STATE] != SEARCH:
            motor[i] = STOP
        led[i] = ri[i, R_STATE]
        encode(i, ri, out_on, out_type, out_data)
