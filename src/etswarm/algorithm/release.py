"""Queued robots: lowest-ID release from the repository (paper Table 1, Queued)."""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import (
    QUEUED,
    SEARCH,
)
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_RELEASED,
    NB_STATE,
    R_EPOCH,
    R_FLOOR,
    R_FLOOR_SINCE,
    R_QMIN,
    R_QMIN_SINCE,
    R_RELEASED,
)
from etswarm.algorithm.params import (
    C_TICKS_CLEAR,
    C_TICKS_NB_FRESH,
    C_TICKS_QUIET,
    C_TICKS_RELEASE,
)
from etswarm.algorithm.search import begin_search


@njit
def queued_rule(i, tick, ri, nb, ci, limit):  # type: ignore[no-untyped-def]
    """Lowest-ID release from the repository.

    A Queued robot leaves (becomes Search) when its ID is the lowest among the Queued
    robots it hears, it has heard no searching robot for ``C_TICKS_CLEAR`` ticks (so
    searchers never start side by side and the traffic around the repository throttles
    the release rate), no release was heard of for ``C_TICKS_RELEASE`` ticks, and fewer
    than ``limit`` robots were released so far (the count floods as a maximum; robots
    beyond the target's needs stay Queued). In a queue sorted by ID this releases the end
    of the queue one robot after another, as in the paper; in a cluster or after a
    regeneration, robots far apart may leave at the same time.
    """
    fresh = ci[C_TICKS_NB_FRESH]
    released = ri[i, R_RELEASED]
    last_searcher = -(1 << 40)
    lowest = i
    epoch = ri[i, R_EPOCH]
    for m in range(nb.shape[1]):
        sid = nb[i, m, NB_ID]
        if sid < 0 or nb[i, m, NB_EPOCH] != epoch:
            continue  # empty, or a robot still working for an older target
        st = nb[i, m, NB_STATE]
        if st == SEARCH:
            last_searcher = max(last_searcher, nb[i, m, NB_LAST])
        if tick - nb[i, m, NB_LAST] > fresh or st > SEARCH:
            continue
        released = max(released, nb[i, m, NB_RELEASED])
        if st == QUEUED and sid < lowest:
            lowest = sid
    if released != ri[i, R_RELEASED]:
        ri[i, R_RELEASED] = released
        ri[i, R_FLOOR_SINCE] = tick
    if lowest != ri[i, R_QMIN]:
        ri[i, R_QMIN] = lowest
        ri[i, R_QMIN_SINCE] = tick
    if (
        lowest == i
        and released < limit
        and tick - last_searcher >= ci[C_TICKS_CLEAR]
        and tick - ri[i, R_QMIN_SINCE] >= ci[C_TICKS_QUIET]
        and tick - ri[i, R_FLOOR_SINCE] >= ci[C_TICKS_RELEASE]
    ):
        begin_search(i, tick, ri)
        ri[i, R_FLOOR] = i
        ri[i, R_FLOOR_SINCE] = tick
        ri[i, R_RELEASED] = released + 1
