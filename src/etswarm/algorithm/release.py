"""Queued robots: lowest-ID release from the repository (paper Table 1, Queued)."""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import (
    QUEUED,
    SEARCH,
    set_state,
)
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_FLOOR,
    NB_ID,
    NB_LAST,
    NB_QMIN,
    NB_RELEASED,
    NB_STATE,
    R_COOLDOWN,
    R_EPOCH,
    R_FLOOR,
    R_FLOOR_SINCE,
    R_QMIN,
    R_QMIN_SINCE,
    R_RELEASED,
    R_SUB,
    R_SUB_SINCE,
    R_YIELD_SINCE,
    SUB_FOLLOW,
)
from etswarm.algorithm.params import (
    C_TICKS_CLEAR,
    C_TICKS_NB_FRESH,
    C_TICKS_QUIET,
    C_TICKS_RELEASE,
)


@njit
def queued_rule(i, tick, ri, nb, ci, limit):  # type: ignore[no-untyped-def]
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
    epoch = ri[i, R_EPOCH]
    for m in range(slots):
        if nb[i, m, NB_ID] >= 0 and nb[i, m, NB_EPOCH] != epoch:
            continue  # a robot still working for an older target
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
        if sid < 0 or nb[i, m, NB_EPOCH] != epoch:
            continue
        if tick - nb[i, m, NB_LAST] <= fresh and nb[i, m, NB_STATE] == QUEUED:
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
        and released < limit
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
