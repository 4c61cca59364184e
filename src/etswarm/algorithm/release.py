"""Queued robots: release from the repository (paper Table 1, Queued).

At the start the Queued robot with the lowest ID leaves first (the paper). After a
regeneration the robots that are not on the scaled shape turn Queued where they stand, in
no order of ID, often in a chain away from the shape (the old stem of a ``T``). Lowest-ID
release then takes robots out of the middle of the chain, and the robots beyond lose
every link to the shape: traced on ``T`` ``split x=mid`` (10 seeds), in most remnants
that never re-formed the robots missing from the shape sat in a separate group of Queued
and searching robots out of range, searchers orbiting a lone Queued robot that never left
because it kept hearing them. So a regenerated remnant (``C_RELEASE_FAR``) releases the
robot farthest from the shape first: every Queued robot keeps its hop count to the robots
placed on the target (1 when it hears one, else one more than the least count heard),
sends it in its status, and leaves when no Queued robot it hears has a higher count (or
the same count and a lower ID). A chain is then taken from its far end, as the paper's
queue is.
"""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import (
    QUEUED,
    SEARCH,
    first_growth,
    is_placed,
)
from etswarm.algorithm.kinship import sibling
from etswarm.algorithm.memory import (
    NB_ANCHORED,
    NB_EPOCH,
    NB_HOPS,
    NB_ID,
    NB_LAST,
    NB_QRANK,
    NB_RELEASED,
    NB_STATE,
    R_CROWDED_SINCE,
    R_EPOCH,
    R_FLOOR,
    R_FLOOR_RANK,
    R_FLOOR_SINCE,
    R_HOLD_UNTIL,
    R_QMIN,
    R_QMIN_SINCE,
    R_QRANK,
    R_RANK_NEWS,
    R_RELEASED,
    R_SHAPE_HOPS,
)
from etswarm.algorithm.messages import HOLD_UNIT_TICKS, YIELDING_BIT
from etswarm.algorithm.params import (
    C_RELEASE_FAR,
    C_STATUS_SIG,
    C_TICKS_CLEAR,
    C_TICKS_CLEAR_FIRST,
    C_TICKS_CROWDED,
    C_TICKS_HOLD,
    C_TICKS_NB_FRESH,
    C_TICKS_QUIET,
    C_TICKS_RANK_WAIT,
    C_TICKS_RELEASE,
)
from etswarm.algorithm.parked import HOPS_PARKED
from etswarm.algorithm.search import begin_search

#: Hop count of a Queued robot that knows no way to the shape (also the largest count).
HOPS_NONE = 255
#: ``queued_rule``'s answer for a robot whose evaluation nothing but a message can change.
NEVER = 1 << 62


@njit
def shape_hops(i, tick, ri, nb, fresh):  # type: ignore[no-untyped-def]
    """Robot i's hops to the robots placed on its target: 1 when it heard one within
    ``fresh`` ticks, else one more than the least count of the Queued robots it heard
    (``HOPS_NONE`` when none knows a way)."""
    epoch = ri[i, R_EPOCH]
    least = HOPS_NONE
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or nb[i, m, NB_EPOCH] != epoch:
            continue
        if tick - nb[i, m, NB_LAST] > fresh:
            continue
        st = nb[i, m, NB_STATE]
        if is_placed(st):
            return 1
        hops = nb[i, m, NB_HOPS]
        if st == QUEUED and hops != HOPS_PARKED and hops < least:
            least = hops
    return min(least + 1, HOPS_NONE)


@njit(inline="always")
def crowded_long(i, tick, ri, ci, clear):  # type: ignore[no-untyped-def]
    """Queued robot i has heard a searcher within the clearing time at every evaluation
    for ``C_TICKS_CROWDED`` ticks (``clear``: it has not now); keeps ``R_CROWDED_SINCE``."""
    if clear:
        ri[i, R_CROWDED_SINCE] = 0
        return False
    if ri[i, R_CROWDED_SINCE] == 0:
        ri[i, R_CROWDED_SINCE] = tick + 1
    return tick - (ri[i, R_CROWDED_SINCE] - 1) >= ci[C_TICKS_CROWDED]


@njit(inline="always")
def clear_ticks(i, ri, ci):  # type: ignore[no-untyped-def]
    """How long Queued robot i must hear no searcher before it may leave: the first
    formation's ``C_TICKS_CLEAR_FIRST`` (a thin shape's own), else ``C_TICKS_CLEAR``."""
    return ci[C_TICKS_CLEAR_FIRST] if first_growth(i, ri) else ci[C_TICKS_CLEAR]


@njit
def queued_rule(i, tick, ri, nb, ci, limit):  # type: ignore[no-untyped-def]
    """Lowest-ID release from the repository.

    A Queued robot leaves (becomes Search) when its ID is the lowest among the Queued
    robots it hears, it has heard no searching robot for ``clear_ticks`` ticks (so
    searchers never start side by side and the traffic around the repository throttles
    the release rate), no release was heard of for ``C_TICKS_RELEASE`` ticks, and fewer
    than ``limit`` robots were released so far (the count floods as a maximum; robots
    beyond the target's needs stay Queued). In a queue sorted by ID this releases the end
    of the queue one robot after another, as in the paper; in a cluster or after a
    regeneration, robots far apart may leave at the same time. With ``C_RELEASE_FAR``, in
    a regenerated remnant the robot that leaves is the one with the most hops to the shape
    among those it hears (ties: the lowest ID), see the module docstring. With
    ``C_TICKS_HOLD`` (``release_hold_s``) it also waits out the release hold it heard of
    (``R_HOLD_UNTIL``, see ``ETParams.release_hold_s``). In a regenerated remnant a robot
    that has waited ``C_TICKS_CROWDED`` ticks for the searchers to clear leaves anyway
    (``crowded_long``, ``ETParams.regrowth_crowded_s``). A robot whose regenerated target
    is empty (``limit`` 0: its remnant was too small to seed) sends ``HOPS_PARKED``, and
    the Queued robots that hear it leave it out: it would be the lowest or farthest for
    ever (traced on `L` `remove random=0.2` seed 30: a lone robot cut off by the removal
    held back the last release of the 23-robot remnant beside it for 3 h).

    Returns the first tick at which a later evaluation could give something else if the
    robot hears nothing new meanwhile (``NEVER``: none), or 0 when that is not known (it
    left, it releases farthest first, or the release hold is on). Without new messages the
    table only ages, and an entry that ages out of ``fresh`` can only lower the released
    count it gave, which the robot keeps; so what changes is: the lowest Queued ID heard
    falls stale (at its last hearing + ``fresh`` + 1), or, when the robot is the lowest
    itself, its waits end (the release count below ``limit``; it never leaves otherwise).
    The controller lets the robot sleep till then (``controller.idle_wake``).
    """
    fresh = ci[C_TICKS_NB_FRESH]
    released = ri[i, R_RELEASED]
    last_searcher = -(1 << 40)
    lowest = i
    epoch = ri[i, R_EPOCH]
    regrowth = not first_growth(i, ri)  # (a false alarm's kept target is no regrowth)
    far_first = ci[C_RELEASE_FAR] == 1 and regrowth
    parked = regrowth and limit == 0
    if parked:
        ri[i, R_SHAPE_HOPS] = HOPS_PARKED  # its remnant grows nothing: it stays put
    elif far_first:
        ri[i, R_SHAPE_HOPS] = shape_hops(i, tick, ri, nb, fresh)
    lowest_hops = ri[i, R_SHAPE_HOPS]
    hold_ticks = ci[C_TICKS_HOLD]
    hold = ri[i, R_HOLD_UNTIL]
    lowest_last = 0  # tick the lowest Queued robot heard was last heard
    ranked = not regrowth and ci[C_TICKS_RANK_WAIT] > 0
    rank = ri[i, R_QRANK]
    floor_rank = ri[i, R_FLOOR_RANK]
    status_sig = ci[C_STATUS_SIG] != 0
    for m in range(nb.shape[1]):
        sid = nb[i, m, NB_ID]
        if sid < 0 or nb[i, m, NB_EPOCH] != epoch:
            continue  # empty, or a robot still working for an older target
        if status_sig and sibling(i, m, nb):
            continue  # a sibling remnant's: its count and rank are of another repository
        st = nb[i, m, NB_STATE]
        if st == SEARCH:
            last_searcher = max(last_searcher, nb[i, m, NB_LAST])
            floor_rank = max(floor_rank, nb[i, m, NB_QRANK])
        if tick - nb[i, m, NB_LAST] > fresh or st > SEARCH:
            continue
        released = max(released, nb[i, m, NB_RELEASED])
        if hold_ticks > 0:
            # Back-pressure (``release_hold_s``): a yielding searcher starts a hold, a
            # Queued robot passes its own on, one unit shorter.
            byte6 = nb[i, m, NB_ANCHORED]
            if st == SEARCH and byte6 & YIELDING_BIT:
                hold = max(hold, nb[i, m, NB_LAST] + hold_ticks)
            elif st == QUEUED and byte6 > 1:
                hold = max(hold, nb[i, m, NB_LAST] + (byte6 - 1) * HOLD_UNIT_TICKS)
        if st != QUEUED or (regrowth and nb[i, m, NB_HOPS] == HOPS_PARKED):
            continue  # (a parked robot of a remnant too small to grow never leaves)
        if sid < i:
            rank = max(rank, nb[i, m, NB_QRANK] + 1)
        if far_first:
            hops = nb[i, m, NB_HOPS]
            if hops > lowest_hops or (hops == lowest_hops and sid < lowest):
                lowest = sid
                lowest_hops = hops
        elif sid < lowest:
            lowest = sid
            lowest_last = nb[i, m, NB_LAST]
    ri[i, R_HOLD_UNTIL] = hold
    if floor_rank > ri[i, R_FLOOR_RANK] or released > ri[i, R_RELEASED]:
        ri[i, R_RANK_NEWS] = tick
    ri[i, R_QRANK] = rank
    ri[i, R_FLOOR_RANK] = floor_rank
    # The robot just behind it in the queue left (a searcher of the next lower rank came
    # by), or releases have stopped altogether: the queue's end is here.
    rank_waits = ranked and floor_rank < rank - 1
    if released != ri[i, R_RELEASED]:
        ri[i, R_RELEASED] = released
        ri[i, R_FLOOR_SINCE] = tick
    if lowest != ri[i, R_QMIN]:
        ri[i, R_QMIN] = lowest
        ri[i, R_QMIN_SINCE] = tick
    # (counted from when it became the lowest, too: news it missed while asleep are old)
    rank_ends = max(ri[i, R_RANK_NEWS], ri[i, R_QMIN_SINCE]) + ci[C_TICKS_RANK_WAIT]
    clear_after = clear_ticks(i, ri, ci)
    clear = tick - last_searcher >= clear_after
    crowded_waits = regrowth and ci[C_TICKS_CROWDED] > 0
    if crowded_waits:
        # (called even when clear: a clear evaluation ends the crowded stretch)
        crowded = crowded_long(i, tick, ri, ci, clear)
        clear = clear or crowded
    if (
        lowest == i
        and released < limit
        and clear
        and tick - ri[i, R_QMIN_SINCE] >= ci[C_TICKS_QUIET]
        and tick - ri[i, R_FLOOR_SINCE] >= ci[C_TICKS_RELEASE]
        and tick >= hold
        and (not rank_waits or tick >= rank_ends)
    ):
        begin_search(i, tick, ri)
        ri[i, R_FLOOR] = i
        ri[i, R_FLOOR_SINCE] = tick
        ri[i, R_RELEASED] = released + 1
        return 0
    if far_first or hold_ticks > 0 or crowded_waits:
        # (with the release hold its status changes with every tick, and a crowded
        # robot's wait runs out without a message: it stays awake)
        return 0
    if lowest != i:
        return lowest_last + fresh + 1
    if released >= limit:
        return NEVER
    return max(
        last_searcher + clear_after,
        ri[i, R_QMIN_SINCE] + ci[C_TICKS_QUIET],
        ri[i, R_FLOOR_SINCE] + ci[C_TICKS_RELEASE],
        rank_ends if rank_waits else 0,
    )
