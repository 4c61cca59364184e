"""Searching robots: edge-following, yielding, settling on a site and getting lost (paper
Sec. 4.1); where a searcher stands on the lattice is ``localise``'s answer."""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.former_site import former_reach, note_former_site
from etswarm.algorithm.hole_watch import note_inside, watch_blocks
from etswarm.algorithm.homing import (
    homing_motion,
    integrate,
    note_home,
    note_lost,
    reset_odometry,
)
from etswarm.algorithm.kernel_util import (
    FAR,
    FORWARD,
    INACTIVE,
    LEFT,
    RIGHT,
    SEARCH,
    STOP,
    first_growth,
    gene_at,
    heard_placed_within,
    is_placed,
    set_state,
    two_step_direction,
)
from etswarm.algorithm.kinship import foreign, sibling
from etswarm.algorithm.localise import (
    find_site,
    reported_but_unheard,
    window_centre,
)
from etswarm.algorithm.memory import (
    NB_ANCHORED,
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    NO_SITE,
    R_BELOW_SINCE,
    R_CAND_X,
    R_CAND_Y,
    R_COOLDOWN,
    R_COUNT,
    R_CREEP_UNTIL,
    R_ESCAPE_UNTIL,
    R_FROM_ID,
    R_GAP_LO_X,
    R_GAP_LO_Y,
    R_GROWTH,
    R_HAS_TAG,
    R_HOVER_SINCE,
    R_HOVER_X,
    R_HOVER_Y,
    R_LEFT,
    R_LEFT_X,
    R_LEFT_Y,
    R_LOST_SINCE,
    R_MASK,
    R_NEW_REF_MOVED,
    R_NN,
    R_ON_SHAPE,
    R_ORBIT,
    R_PINCH_REFUSED,
    R_PLUNGE_MOUTH,
    R_PLUNGE_UNTIL,
    R_RECENT0,
    R_REF_ID,
    R_REF_MOVED,
    R_REF_TREND,
    R_SEEN_FULL,
    R_SETTLE_TRIES,
    R_SHAPE_SINCE,
    R_SUB,
    R_SUB_SINCE,
    R_TAG_X,
    R_TAG_Y,
    R_TOWARD_SINCE,
    R_TS,
    R_YIELD_SINCE,
    R_YLD_ID,
    R_YLD_TREND,
    RECENT_REFS,
    SUB_FOLLOW,
    SUB_SETTLE,
)
from etswarm.algorithm.messages import ANCHORED_BIT
from etswarm.algorithm.offsets import estimate_offset
from etswarm.algorithm.params import (
    C_AVOID_FOREIGN,
    C_CREEP,
    C_FIRST_PLUNGE,
    C_HOLE_MEMORY,
    C_LOST_BEACON,
    C_LOST_HOMING,
    C_LOST_YIELD,
    C_MOUTH_PLUNGE,
    C_ORBIT_BOUNCE,
    C_PARKED_OBSTACLE,
    C_PINCH_REFUSALS,
    C_POCKET,
    C_QUEUE_STRIDE,
    C_REGROW_PINCH_REFUSALS,
    C_REGROW_RETRIES,
    C_RIGHT_OF_WAY,
    C_SETTLE_RETRIES,
    C_STATUS_SIG,
    C_TICKS_COOLDOWN,
    C_TICKS_FROM_RETURN,
    C_TICKS_HOVER,
    C_TICKS_LATE_PLUNGE,
    C_TICKS_LOST_ESCAPE,
    C_TICKS_MOVE_FRESH,
    C_TICKS_PLUNGE,
    C_TICKS_SETTLE,
    C_TICKS_YIELD_MAX,
    C_WAY_PLUNGE,
    F_CAPTURE_OFFSET,
    F_CLEARANCE,
    F_CLOSING,
    F_DIVE,
    F_DIVE_FIRST,
    F_FOLLOW_OFFSET,
    F_LATE_PLUNGE_AIM,
    F_PINCH_PATIENCE,
    F_PORTABLE_MATH,
    F_REGROW_CAPTURE_OFFSET,
    F_REGROW_PLUNGE_AIM,
    F_REGROW_TWO_WIDEN_TICKS,
    F_REGROW_WIDEN_TICKS,
    F_SETTLE_SCALE,
    F_SPACING,
    F_TWO_WIDEN_TICKS,
    F_WIDEN_MAX,
    F_WIDEN_TICKS,
    F_YIELD_DIST,
    LOST_HOMING_AHEAD,
    LOST_HOMING_ON,
    POCKET_ON,
    POCKET_REGROWTH,
    RIGHT_OF_WAY_ALWAYS,
    RIGHT_OF_WAY_FIRST_GROWTH,
    STATUS_SIG_ON,
)
from etswarm.algorithm.parked import parked
from etswarm.algorithm.pinch import too_far_off, would_pinch
from etswarm.algorithm.pocket import POCKET_AFTER_TICKS, pocket_site
from etswarm.algorithm.repository_gap import leaping, left_behind, note_walk, start_walk
from etswarm.algorithm.site_memory import (
    forget_left_site,
    is_held,
    remember_heard,
    site_taken,
)
from etswarm.algorithm.wave import nn_of, wave_blocks

#: Readings of a searching robot older than this (ticks) are ignored for steering.
SEARCHER_FRESH_TICKS = 31
#: A lost searcher first pivots where it lost the group for this long (ticks) ...
LOST_PIVOT_TICKS = 310
#: ... then spirals outwards: in every period of this many ticks it drives forward for a
#: growing share (1 - 0.8 / (1 + t / ``SPIRAL_GROW_TICKS``)) and pivots right for the rest.
SPIRAL_PERIOD_TICKS = 124
SPIRAL_GROW_TICKS = 31 * 200
#: Near a free site (pair and balance tolerances times ``CREEP_TOL_SCALE``) a searcher
#: creeps: in every ``CREEP_PERIOD_TICKS`` it stands still for ``CREEP_STOP_TICKS`` and
#: moves for the rest; the mode lasts ``CREEP_HOLD_TICKS`` after the last such reading.
CREEP_TOL_SCALE = 3.0
#: A searcher that has pivoted towards the group this long (ticks) without once being
#: nearer than its aim is circling out of reach; it then drives on while closing in.
CIRCLING_TICKS = 31 * 10
#: A searcher's pair and balance tolerances grow linearly from 1x to ``ETParams.widen_max``
#: x over its first ``ETParams.widen_s`` at the shape (since it first heard a placed robot),
#: ... but only at a site with at least this many placed neighbours heard.
WIDE_MIN_NEIGHBOURS = 3
#: Along the repository (no placed robot heard) a searcher drives straight on while its
#: reading of the nearest Queued robot is within this of its aim (``C_QUEUE_STRIDE``).
STRIDE_BAND_MM = 4.0
#: A diving searcher (``ETParams.dive_mm``) turns away from a placed robot this much
#: nearer than its aim (the clearance, 38 mm, is 2 mm under the undived aim). With 2 mm,
#: diving searchers shoved placed robots apart: 2 of 260 first formations (starfish)
#: and 2 of 6 bigdisc runs started an election with no damage done; with 1 mm, none.
CLEARANCE_BELOW_AIM_MM = 1.0
#: A plunging searcher (``R_PLUNGE_UNTIL``, ``regrowth_plunge_s``) in the first formation
#: edge-follows placed robots at this distance (mm): a 33 mm body and 2 mm (after damage:
#: ``regrowth_plunge_aim_mm``).
PLUNGE_AIM_MM = 35.0
#: ``mouth_plunge``: the two robots across a free site each read within d + this (mm).
MOUTH_READ_MM = 8.0
CREEP_PERIOD_TICKS = 24
CREEP_STOP_TICKS = 16
CREEP_HOLD_TICKS = 62
#: A reference the searcher steered by while moving for at least this many ticks counts as
#: the one it came from once another takes over (``follow_reference``). Passing a robot
#: takes several seconds of pivoting; at the midpoint of a pair the nearest robot flips
#: back and forth with every reading, each time for a fraction of that.
FROM_MOVING_TICKS = 62
#: A searcher that has moved this long (ticks) without steering by a robot other than its
#: last ``memory.RECENT_REFS`` distinct references turns round (``follow_reference``).
TRAPPED_TICKS = 31 * 300


@njit
def begin_search(i, tick, ri):  # type: ignore[no-untyped-def]
    """Robot i leaves the repository: it starts following the group clockwise."""
    set_state(i, ri, SEARCH, tick)
    ri[i, R_HAS_TAG] = 0
    ri[i, R_SUB] = SUB_FOLLOW
    ri[i, R_SUB_SINCE] = tick
    ri[i, R_YIELD_SINCE] = -1
    ri[i, R_COOLDOWN] = tick
    ri[i, R_ORBIT] = 0
    ri[i, R_ON_SHAPE] = 0
    ri[i, R_SHAPE_SINCE] = 0
    ri[i, R_CREEP_UNTIL] = 0
    ri[i, R_LOST_SINCE] = 0
    ri[i, R_TOWARD_SINCE] = tick
    ri[i, R_FROM_ID] = -1
    reset_odometry(i, ri)
    start_walk(i, tick, ri)
    ri[i, R_REF_MOVED] = 0
    ri[i, R_PINCH_REFUSED] = 0
    ri[i, R_PLUNGE_UNTIL] = 0
    ri[i, R_PLUNGE_MOUTH] = 0
    ri[i, R_ESCAPE_UNTIL] = 0
    ri[i, R_LEFT] = 0
    forget_recent_references(i, ri)


@njit(inline="always")
def forget_recent_references(i, ri):  # type: ignore[no-untyped-def]
    """Clear robot i's list of recent references and its count of ticks since a new one."""
    for k in range(RECENT_REFS):
        ri[i, R_RECENT0 + k] = -1
    ri[i, R_NEW_REF_MOVED] = 0


@njit
def follow_reference(i, ri, nb, slot, moving, return_ticks):  # type: ignore[no-untyped-def]
    """Robot i steers by the robot in table row ``slot`` this tick; ``moving``: its last
    motor command was not STOP. When the reference changes, the old one becomes the robot
    it came from (R_FROM_ID), if it steered by it while moving for ``FROM_MOVING_TICKS``;
    a reference that was nearest only for a moment (the two of a pair flicker at its
    midpoint) leaves R_FROM_ID as it was. When the new reference is the robot it came
    from, the old one takes its place only after ``return_ticks`` (``C_TICKS_FROM_RETURN``,
    when longer) of moving: a searcher stopping midway between a pair flips back.

    A searcher that has moved for ``TRAPPED_TICKS`` steering only by its last
    ``RECENT_REFS`` distinct references is trapped where the group's edge folds in (traced
    on ``T`` ``kill random=0.1`` seed 1: a searcher circled for 2.5 h between the
    shape and four Queued robots, which never left because they heard it): it turns round.
    """
    sid = nb[i, slot, NB_ID]
    if sid != ri[i, R_REF_ID]:
        need = FROM_MOVING_TICKS
        if sid == ri[i, R_FROM_ID]:
            need = max(need, return_ticks)
        if ri[i, R_REF_ID] >= 0 and ri[i, R_REF_MOVED] >= need:
            ri[i, R_FROM_ID] = ri[i, R_REF_ID]
        ri[i, R_REF_MOVED] = 0
        known = False
        for k in range(RECENT_REFS):
            known = known or ri[i, R_RECENT0 + k] == sid
        if not known:
            for k in range(RECENT_REFS - 1, 0, -1):
                ri[i, R_RECENT0 + k] = ri[i, R_RECENT0 + k - 1]
            ri[i, R_RECENT0] = sid
            ri[i, R_NEW_REF_MOVED] = 0
    if moving:
        ri[i, R_REF_MOVED] += 1
        ri[i, R_NEW_REF_MOVED] += 1
    if ri[i, R_NEW_REF_MOVED] >= TRAPPED_TICKS:
        ri[i, R_ORBIT] = 1 - ri[i, R_ORBIT]
        ri[i, R_FROM_ID] = -1  # it turned round
        forget_recent_references(i, ri)


@njit(inline="always")
def note_hover(i, tick, x, y, ri):  # type: ignore[no-untyped-def]
    """Creeping robot i found site (x, y) near it: it hovers there since the first time
    in a row it found that site."""
    if ri[i, R_HOVER_SINCE] == 0 or ri[i, R_HOVER_X] != x or ri[i, R_HOVER_Y] != y:
        ri[i, R_HOVER_X] = x
        ri[i, R_HOVER_Y] = y
        ri[i, R_HOVER_SINCE] = tick + 1


@njit(inline="always")
def hovering(i, tick, ri, ci):  # type: ignore[no-untyped-def]
    """Robot i, searching for a regenerated target, has crept near one free site for
    ``regrowth_hover_s`` (``note_hover``). Hovering ends when its creep mode runs out while
    it moves on."""
    if ci[C_TICKS_HOVER] <= 0 or first_growth(i, ri) or ri[i, R_HOVER_SINCE] == 0:
        return False
    if ri[i, R_SUB] == SUB_FOLLOW and tick >= ri[i, R_CREEP_UNTIL]:
        ri[i, R_HOVER_SINCE] = 0
        return False
    return tick - (ri[i, R_HOVER_SINCE] - 1) >= ci[C_TICKS_HOVER]


@njit(inline="always")
def wide_minimum(at_shape, growth, cf):  # type: ignore[no-untyped-def]
    """Placed neighbours a searcher of growth ``growth`` (R_GROWTH), ``at_shape`` ticks at
    the shape, must hear round a site for the site to get its widened window:
    ``WIDE_MIN_NEIGHBOURS``, or two once it has been ``F_TWO_WIDEN_TICKS`` (> 0) at the
    shape in the first formation, ``F_REGROW_TWO_WIDEN_TICKS`` (> 0) after damage."""
    after = cf[F_TWO_WIDEN_TICKS] if growth == 0 else cf[F_REGROW_TWO_WIDEN_TICKS]
    return 2 if after > 0 and at_shape >= after else WIDE_MIN_NEIGHBOURS


@njit(inline="always")
def late_at_shape(at_shape, ci):  # type: ignore[no-untyped-def]
    """A first-formation searcher ``at_shape`` ticks at the shape is late enough to plunge
    in a notch's mouth and press (``ETParams.late_plunge_s``; never when that is 0)."""
    return 0 < ci[C_TICKS_LATE_PLUNGE] <= at_shape


@njit(inline="always")
def widening_ticks(growth, cf):  # type: ignore[no-untyped-def]
    """Ticks at the shape over which a searcher of growth ``growth`` (R_GROWTH) widens its
    windows: ``F_WIDEN_TICKS`` in the first formation, ``F_REGROW_WIDEN_TICKS`` after
    damage."""
    return cf[F_WIDEN_TICKS] if growth == 0 else cf[F_REGROW_WIDEN_TICKS]


@njit(inline="always")
def dive_depth(at_shape, growth, cf):  # type: ignore[no-untyped-def]
    """How much nearer than d + follow offset (mm) a searcher ``at_shape`` ticks at the
    shape edge-follows: after damage (``growth`` > 0, R_GROWTH) up to ``F_DIVE`` over its
    first widening time (``widening_ticks``); in the first formation up to
    ``F_DIVE_FIRST`` over the next widening time after that."""
    widen_ticks = widening_ticks(growth, cf)
    if at_shape <= 0:
        return 0.0
    if growth > 0:
        return cf[F_DIVE] * min(1.0, at_shape / widen_ticks)
    return cf[F_DIVE_FIRST] * min(1.0, max(0.0, at_shape / widen_ticks - 1.0))


@njit(inline="always")
def in_mouth(i, recent, nb, nb_dist, gene_flag, ci, held_i, ox, oy, reach):  # type: ignore[no-untyped-def]
    """Robot i reads two placed robots of its shape, heard since tick ``recent`` and each
    within ``reach`` mm, that hold the two sites across a free site of its target from
    each other (tags two steps apart in one lattice direction): it stands in the mouth of
    a notch whose free site it cannot confirm from there."""
    avoid = ci[C_AVOID_FOREIGN] == 1
    for a in range(nb.shape[1]):
        if not heard_placed_within(i, a, recent, reach, nb, nb_dist):
            continue
        if avoid and foreign(i, a, nb, gene_flag, ci):
            continue
        for b in range(a + 1, nb.shape[1]):
            if not heard_placed_within(i, b, recent, reach, nb, nb_dist):
                continue
            dx = nb[i, b, NB_TX] - nb[i, a, NB_TX]
            dy = nb[i, b, NB_TY] - nb[i, a, NB_TY]
            if two_step_direction(dx, dy) < 0:
                continue
            mx = nb[i, a, NB_TX] + dx // 2
            my = nb[i, a, NB_TY] + dy // 2
            if gene_at(gene_flag, ci, mx, my) != 1 or site_taken(i, mx, my, nb):
                continue
            if is_held(held_i, mx, my, ox, oy):
                continue
            if avoid and foreign(i, b, nb, gene_flag, ci):
                continue
            return True
    return False


@njit
def search_rule(  # type: ignore[no-untyped-def]
    i, tick, new_msgs, ri, nb, nb_dist, motor, gene_flag, gene_nn, ci, cf, held, ox, oy
):
    """Edge-follow the group clockwise at about d, yield, settle on a free site.

    ``held`` (N, WX, WY) uint8: the searchers' memories of held sites, window origin at tag
    (ox, oy) (see ``site_memory``)."""
    if new_msgs and ci[C_HOLE_MEMORY] == 1:
        remember_heard(i, tick, ri, nb, held, ox, oy)
    held_i = held[i]
    forget_left_site(held_i, ri, i, ox, oy)
    left_x = ri[i, R_LEFT_X] if ri[i, R_LEFT] == 1 else NO_SITE
    left_y = ri[i, R_LEFT_Y] if ri[i, R_LEFT] == 1 else NO_SITE
    moving = motor[i] != STOP  # its command since the last tick
    integrate(i, ri, motor[i], cf)
    note_inside(i, tick, ri, nb, nb_dist, gene_flag, ci, cf)
    reach = former_reach(i, ri, cf)
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
    beacon_est = FAR
    beacon_slot = -1
    foreign_est = FAR
    foreign_slot = -1
    behind_est = FAR  # leaping: the Queued robots of the piece it leaps from
    leap = leaping(i, ri)
    look_for_beacon = ci[C_LOST_BEACON] == 1
    avoid_foreign = ci[C_AVOID_FOREIGN] == 1
    parked_obstacle = ci[C_PARKED_OBSTACLE] == 1
    status_sig = ci[C_STATUS_SIG] == STATUS_SIG_ON
    right_of_way = ci[C_RIGHT_OF_WAY] == RIGHT_OF_WAY_ALWAYS or (
        ci[C_RIGHT_OF_WAY] == RIGHT_OF_WAY_FIRST_GROWTH and first_growth(i, ri)
    )
    for m in range(slots):
        if nb[i, m, NB_ID] < 0 or tick - nb[i, m, NB_LAST] > steer_fresh:
            continue
        # Worst case: the robot closed in at ``closing`` mm per tick since the reading.
        est = nb_dist[i, m] - closing * (tick - nb[i, m, NB_LAST])
        st = nb[i, m, NB_STATE]
        if st == SEARCH:
            if tick - nb[i, m, NB_LAST] > SEARCHER_FRESH_TICKS:
                continue  # a moving robot's old reading says nothing about now
            if not right_of_way or nb[i, m, NB_ID] < i:
                nearest_searcher = min(nearest_searcher, est)
            if look_for_beacon and nb[i, m, NB_ANCHORED] & ANCHORED_BIT and est < beacon_est:
                beacon_est = est
                beacon_slot = m
            if nb[i, m, NB_ID] < i and est < nearest_lower_searcher:
                nearest_lower_searcher = est
                lower_slot = m
        elif is_placed(st):
            if avoid_foreign and foreign(i, m, nb, gene_flag, ci):
                if est < foreign_est:  # not its shape: an obstacle
                    foreign_est = est
                    foreign_slot = m
            elif est < placed_est:
                placed_est = est
                placed_slot = m
        elif (parked_obstacle and parked(i, m, nb)) or (status_sig and sibling(i, m, nb)):
            if est < foreign_est:  # of a remnant that grows nothing, or a sibling's: an obstacle
                foreign_est = est
                foreign_slot = m
        elif leap and left_behind(i, m, ri, nb):
            behind_est = min(behind_est, est)
        elif est < queued_est:
            queued_est = est
            queued_slot = m
    lost = False
    beacon = False
    reading = FAR
    if placed_slot >= 0:
        reading = nb_dist[i, placed_slot]
        nearest = placed_est
        obstacle = min(queued_est, nearest_searcher, foreign_est, behind_est)
        follow_reference(i, ri, nb, placed_slot, moving, ci[C_TICKS_FROM_RETURN])
        track_trend(i, ri, nb, nb_dist, placed_slot, R_REF_ID)
        ri[i, R_ON_SHAPE] = 1
        if ri[i, R_SHAPE_SINCE] == 0:
            ri[i, R_SHAPE_SINCE] = tick + 1
    elif queued_slot >= 0:
        if ci[C_ORBIT_BOUNCE] == 1 and ri[i, R_ON_SHAPE] == 1:
            # Left the shape along the repository: go back round the shape the other way
            # instead of walking the repository (and meeting the robots coming along it).
            ri[i, R_ORBIT] = 1 - ri[i, R_ORBIT]
            ri[i, R_ON_SHAPE] = 0
            ri[i, R_FROM_ID] = -1  # it turned round
        reading = nb_dist[i, queued_slot]
        nearest = queued_est
        obstacle = min(nearest_searcher, foreign_est, behind_est)
        follow_reference(i, ri, nb, queued_slot, moving, ci[C_TICKS_FROM_RETURN])
        track_trend(i, ri, nb, nb_dist, queued_slot, R_REF_ID)
    else:
        # Nothing stationary in earshot: circle clockwise to find the group again, or
        # follow a searcher that hears the group (it leads back into earshot).
        lost = True
        nearest = FAR
        obstacle = min(nearest_searcher, foreign_est, behind_est)
        if beacon_slot >= 0:
            beacon = True
            reading = nb_dist[i, beacon_slot]
        elif foreign_slot >= 0 and tick < ri[i, R_ESCAPE_UNTIL]:
            # Blocked by another shape on its way home (``lost_escape_s``): it edge-follows
            # that shape's robots as a beacon, steering only, so it goes round them
            # instead of pivoting into them again and again.
            beacon = True
            reading = nb_dist[i, foreign_slot]

    if not lost:
        ri[i, R_LOST_SINCE] = 0
        ref_slot = placed_slot if placed_slot >= 0 else queued_slot
        if nb[i, ref_slot, NB_LAST] == tick:
            note_home(i, ri)
    elif ri[i, R_LOST_SINCE] == 0:
        ri[i, R_LOST_SINCE] = tick + 1
        note_lost(i, ri)
    note_walk(i, tick, placed_slot, queued_slot, ri, nb, ci)

    # A searcher that has been at the shape for long widens its tolerances: it may be
    # squeezed where the lattice is distorted and never stand within the tight window.
    widen = 1.0
    pocket = False
    at_shape = 0
    if ri[i, R_SHAPE_SINCE] > 0:
        at_shape = tick - ri[i, R_SHAPE_SINCE] + 1
        widen_ticks = widening_ticks(ri[i, R_GROWTH], cf)
        widen = 1.0 + (cf[F_WIDEN_MAX] - 1.0) * min(1.0, at_shape / widen_ticks)
        # Long at the shape, it may also take a site from the robots round it (``pocket``).
        pocket_mode = ci[C_POCKET]
        pocket = at_shape >= POCKET_AFTER_TICKS and (
            pocket_mode == POCKET_ON
            or (pocket_mode >= POCKET_REGROWTH and not first_growth(i, ri))
        )
    pair_aim = window_centre(cf, at_shape)
    if hovering(i, tick, ri, ci):
        pair_aim = d  # long near one site: its pair may stand too far apart for the window
    if ri[i, R_SUB] == SUB_SETTLE:
        motor[i] = STOP
        if tick - ri[i, R_SUB_SINCE] < ci[C_TICKS_SETTLE]:
            return
        ref = ri[i, R_REF_ID]
        came = ri[i, R_FROM_ID]
        since = ri[i, R_SUB_SINCE]
        orbit = ri[i, R_ORBIT]
        first = first_growth(i, ri)
        wide_min = wide_minimum(at_shape, ri[i, R_GROWTH], cf)
        found, cx, cy, min_ts = find_site(
            i, tick, since, True, ref, came, orbit, nb, nb_dist, gene_flag, ci, cf, widen,
            wide_min, held_i, ox, oy, pair_aim, cf[F_SETTLE_SCALE], left_x, left_y, ri, reach,
        )
        same = found and cx == ri[i, R_CAND_X] and cy == ri[i, R_CAND_Y]
        retries = ci[C_SETTLE_RETRIES] if first else ci[C_REGROW_RETRIES]
        if not same and ri[i, R_SETTLE_TRIES] < retries:
            # Noisy readings may have missed the window: stand on with fresh ones while
            # the candidate is still near.
            near, nx, ny, _ = find_site(
                i, tick, since, False, ref, came, orbit, nb, nb_dist, gene_flag, ci, cf,
                CREEP_TOL_SCALE, 0, held_i, ox, oy, pair_aim, 1.0, left_x, left_y, ri, reach,
            )
            if near and nx == ri[i, R_CAND_X] and ny == ri[i, R_CAND_Y]:
                ri[i, R_SETTLE_TRIES] += 1
                ri[i, R_SUB_SINCE] = tick
                return
        if not same and pocket:
            found, cx, cy, min_ts = pocket_site(
                i, tick, since, nb, nb_dist, gene_flag, ci, cf, held_i, ox, oy
            )
            same = found and cx == ri[i, R_CAND_X] and cy == ri[i, R_CAND_Y]
            same = same and not reported_but_unheard(i, cx, cy, since, nb, gene_flag, ci)
        capture_offset = cf[F_CAPTURE_OFFSET] if first else cf[F_REGROW_CAPTURE_OFFSET]
        patient = cf[F_PINCH_PATIENCE] <= 0.0 or at_shape < cf[F_PINCH_PATIENCE]
        if (
            same
            and patient
            and ri[i, R_PINCH_REFUSED]
            < (ci[C_PINCH_REFUSALS] if first else ci[C_REGROW_PINCH_REFUSALS])
            and (
                would_pinch(i, cx, cy, since, nb, nb_dist, gene_flag, ci, cf, held_i, ox, oy)
                or too_far_off(i, cx, cy, since, nb, nb_dist, ci, cf, capture_offset)
            )
        ):
            same = False  # from here it would narrow a free site, or stands far off: it moves on
            ri[i, R_PINCH_REFUSED] += 1
        if same and watch_blocks(i, tick, cx, cy, ri, held_i, ox, oy, gene_flag, ci):
            same = False  # a searcher is in the hole this capture walls off
        if same and wave_blocks(i, ri, at_shape, cx, cy, gene_flag, gene_nn, ci, held_i, ox, oy):
            same = False  # a site nearer the seeds is still free
        if same:
            set_state(i, ri, INACTIVE, tick)
            ri[i, R_TAG_X] = cx
            ri[i, R_TAG_Y] = cy
            ri[i, R_NN] = nn_of(gene_at(gene_nn, ci, cx, cy))
            ri[i, R_TS] = min_ts + 1
            estimate_offset(i, tick, cx, cy, ri[i, R_SUB_SINCE], nb, nb_dist, ri, ci, d)
            ri[i, R_HAS_TAG] = 1
            ri[i, R_LEFT] = 0
            note_former_site(i, ri, NO_SITE, NO_SITE)
            ri[i, R_COUNT] = 0
            # It has observed no neighbour of this site yet; a mask left from a site it
            # held before a regeneration, sent before its first evaluation, would make
            # its neighbours count sites that nobody holds.
            ri[i, R_MASK] = 0
            ri[i, R_SEEN_FULL] = 0
            ri[i, R_BELOW_SINCE] = -1
        else:
            ri[i, R_SUB] = SUB_FOLLOW
            ri[i, R_SUB_SINCE] = tick
            ri[i, R_COOLDOWN] = tick + ci[C_TICKS_COOLDOWN]
            if first:
                may_plunge = ci[C_FIRST_PLUNGE] > 0 and at_shape >= ci[C_FIRST_PLUNGE]
            else:
                may_plunge = at_shape >= widening_ticks(ri[i, R_GROWTH], cf)
            if may_plunge and ci[C_TICKS_PLUNGE] > 0:
                # Long at the shape, it stood near a site and could not take it: it may
                # be in a notch's mouth, short of the site; for a while it edge-follows
                # nearer, into the notch.
                ri[i, R_PLUNGE_UNTIL] = tick + ci[C_TICKS_PLUNGE]
                ri[i, R_PLUNGE_MOUTH] = 0
        return

    # Yield to a lower-ID searcher nearby, unless this robot stands still and that one is
    # closing in: then it comes from behind, and this robot moves on out of its way.
    if lower_slot >= 0:
        track_trend(i, ri, nb, nb_dist, lower_slot, R_YLD_ID)
    chased = motor[i] == STOP and ri[i, R_YLD_TREND] < 0
    # A lost searcher is on no edge: yielding there only parks it beside other lost ones.
    may_yield = not lost or ci[C_LOST_YIELD] == 1
    if nearest_lower_searcher < cf[F_YIELD_DIST] and not chased and may_yield:
        if ri[i, R_YIELD_SINCE] < 0:
            ri[i, R_YIELD_SINCE] = tick
        if tick - ri[i, R_YIELD_SINCE] < ci[C_TICKS_YIELD_MAX]:
            motor[i] = STOP
            return
    else:
        ri[i, R_YIELD_SINCE] = -1

    if new_msgs and tick >= ri[i, R_COOLDOWN]:
        ref = ri[i, R_REF_ID]
        came = ri[i, R_FROM_ID]
        orbit = ri[i, R_ORBIT]
        phase = (tick + i) % CREEP_PERIOD_TICKS
        creeping = ci[C_CREEP] == 1 and tick < ri[i, R_CREEP_UNTIL]
        if not creeping:
            since = tick - steer_fresh
        elif phase < CREEP_STOP_TICKS:
            since = tick - phase + 1  # only readings taken standing still
        else:
            since = tick + 1  # moving: no capture
        wide_min = wide_minimum(at_shape, ri[i, R_GROWTH], cf)
        found, cx, cy, min_ts = find_site(
            i, tick, since, False, ref, came, orbit, nb, nb_dist, gene_flag, ci, cf, widen,
            wide_min, held_i, ox, oy, pair_aim, 1.0, left_x, left_y, ri, reach,
        )
        if not found and pocket:
            found, cx, cy, min_ts = pocket_site(
                i, tick, tick - steer_fresh, nb, nb_dist, gene_flag, ci, cf, held_i, ox, oy
            )
        if found and watch_blocks(i, tick, cx, cy, ri, held_i, ox, oy, gene_flag, ci):
            found = False  # it moves on: a searcher is in the hole this capture walls off
        if found and wave_blocks(i, ri, at_shape, cx, cy, gene_flag, gene_nn, ci, held_i, ox, oy):
            found = False  # a site nearer the seeds is still free
        if found:
            motor[i] = STOP
            ri[i, R_SUB] = SUB_SETTLE
            ri[i, R_SUB_SINCE] = tick
            ri[i, R_SETTLE_TRIES] = 0
            ri[i, R_CAND_X] = cx
            ri[i, R_CAND_Y] = cy
            return
        if ci[C_CREEP] == 1:
            recent = tick - steer_fresh
            near, nx, ny, _ = find_site(
                i, tick, recent, False, ref, came, orbit, nb, nb_dist, gene_flag, ci, cf,
                CREEP_TOL_SCALE, 0, held_i, ox, oy, pair_aim, 1.0, left_x, left_y, ri, reach,
            )
            if near:
                ri[i, R_CREEP_UNTIL] = tick + CREEP_HOLD_TICKS
                if ci[C_TICKS_HOVER] > 0:
                    note_hover(i, tick, nx, ny, ri)
        if (
            ci[C_MOUTH_PLUNGE] == 1
            and ci[C_TICKS_PLUNGE] > 0
            and (
                not first_growth(i, ri)
                or ci[C_WAY_PLUNGE] == 1
                or late_at_shape(at_shape, ci)
            )
            and tick >= ri[i, R_PLUNGE_UNTIL]
            and at_shape >= widening_ticks(ri[i, R_GROWTH], cf)
            and in_mouth(i, tick - steer_fresh, nb, nb_dist, gene_flag, ci, held_i, ox, oy,
                         d + MOUTH_READ_MM)
        ):
            # Long at a regrowing shape, it passes between the two robots across a free
            # site: the site lies inside the notch, so it plunges in (``mouth_plunge``);
            # with ``way_plunge``, in a ring's first formation too, and in any first
            # formation once it has been ``late_plunge_s`` at the shape.
            ri[i, R_PLUNGE_UNTIL] = tick + ci[C_TICKS_PLUNGE]
            ri[i, R_PLUNGE_MOUTH] = 1
    # Near a free site: stop-and-go, so that steering and the capture test use readings
    # taken where the robot is, not up to seconds ago.
    creep_stop = (tick + i) % CREEP_PERIOD_TICKS < CREEP_STOP_TICKS
    if ci[C_CREEP] == 1 and tick < ri[i, R_CREEP_UNTIL] and creep_stop:
        motor[i] = STOP
        return

    # Long at the shape, it edge-follows nearer, into notches the growth pinched: after
    # damage from its arrival (``regrowth_dive_mm``), in the first formation once its
    # tolerances have widened (``dive_mm``). Only placed robots may then come nearer than
    # the clearance.
    dive = dive_depth(at_shape, ri[i, R_GROWTH], cf)
    if tick < ri[i, R_PLUNGE_UNTIL]:
        # plunging (a failed confirmation, or a notch's mouth): in the first formation
        # it keeps PLUNGE_AIM_MM, but presses in a mouth once ``late_plunge_s`` at the
        # shape (``late_plunge_aim_mm``); after damage it presses on the robots it passes
        plunge_aim = cf[F_REGROW_PLUNGE_AIM]
        if first_growth(i, ri):
            late = ri[i, R_PLUNGE_MOUTH] == 1 and late_at_shape(at_shape, ci)
            plunge_aim = cf[F_LATE_PLUNGE_AIM] if late else PLUNGE_AIM_MM
        dive = max(dive, d + cf[F_FOLLOW_OFFSET] - plunge_aim)
    aim = d + cf[F_FOLLOW_OFFSET] - dive
    # Kilobot orbit (both pivots also move the body forward): pivot away from the group
    # when the last reading of the reference is nearer than the aim, towards it otherwise.
    # Any robot that may have come nearer than the clearance is turned away from.
    # Anticlockwise, the group is on the other hand: the pivots swap.
    clearance = cf[F_CLEARANCE]
    away = LEFT if ri[i, R_ORBIT] == 0 else RIGHT
    toward = RIGHT if ri[i, R_ORBIT] == 0 else LEFT
    # Only the first formation's repository is a queue to walk along; after a
    # regeneration the Queued robots stand packed round the shape.
    along_repository = placed_slot < 0 and ci[C_QUEUE_STRIDE] == 1 and first_growth(i, ri)
    placed_clearance = clearance
    if dive > 0 and placed_slot >= 0:
        placed_clearance = min(clearance, aim - CLEARANCE_BELOW_AIM_MM)
    if (
        obstacle < clearance
        or nearest < placed_clearance
        or ((not lost or beacon) and reading < aim)
    ):
        if along_repository and obstacle >= clearance and reading >= aim - STRIDE_BAND_MM:
            motor[i] = FORWARD  # the repository is no place to settle: stride along it
            return
        motor[i] = away
        ri[i, R_TOWARD_SINCE] = tick
        if lost and not beacon and foreign_est < clearance and ci[C_TICKS_LOST_ESCAPE] > 0:
            # its way home runs into another shape: follow that shape's edge a while
            ri[i, R_ESCAPE_UNTIL] = tick + ci[C_TICKS_LOST_ESCAPE]
    elif along_repository and reading <= aim + STRIDE_BAND_MM:
        motor[i] = FORWARD
    elif beacon:
        motor[i] = toward
    elif lost:
        lost_for = tick - (ri[i, R_LOST_SINCE] - 1)
        if ci[C_LOST_HOMING] >= LOST_HOMING_ON and lost_for >= LOST_PIVOT_TICKS:
            # lost on its way along the repository: the shape lies on beyond home
            ahead = (
                ci[C_LOST_HOMING] == LOST_HOMING_AHEAD
                and first_growth(i, ri)
                and ri[i, R_SHAPE_SINCE] == 0
            )
            from_x = 0
            from_y = 0
            if leap:
                # at a dead end of the repository: on the way the queue ranks climbed
                ahead = True
                from_x = ri[i, R_GAP_LO_X]
                from_y = ri[i, R_GAP_LO_Y]
            motor[i] = homing_motion(i, ri, ahead, from_x, from_y, cf[F_PORTABLE_MATH] > 0.0)
        else:
            motor[i] = lost_motion(tick, ri[i, R_LOST_SINCE] - 1)
    elif tick - ri[i, R_TOWARD_SINCE] > CIRCLING_TICKS and ri[i, R_REF_TREND] < 0:
        # Pivoting towards a group that stays beyond the aim only circles on the spot
        # (a pivot turns about a leg): drive straight on while the distance shrinks.
        motor[i] = FORWARD
    else:
        motor[i] = toward


@njit
def lost_motion(tick, since):  # type: ignore[no-untyped-def]
    """Motor command of a searcher that has heard no stationary robot since tick ``since``.

    It first pivots right where it lost the group (which usually finds it again within a
    body length); then it drives an outward spiral, forward for a share of every period
    that grows with time, so the circles widen until a robot of the group is in earshot.
    """
    lost_for = tick - since
    if lost_for < LOST_PIVOT_TICKS:
        return RIGHT
    spiral = lost_for - LOST_PIVOT_TICKS
    # The pivot share falls as 1/(1 + t/T), so the radius keeps growing about linearly
    # (by ~0.2 m per 1000 s), slowly enough that no ring skips over the group.
    share = 1.0 - 0.8 / (1.0 + spiral / SPIRAL_GROW_TICKS)
    if spiral % SPIRAL_PERIOD_TICKS < share * SPIRAL_PERIOD_TICKS:
        return FORWARD
    return RIGHT


@njit
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
