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

from numba import njit

from etswarm.algorithm.kernel_util import (
    INACTIVE,
    QUEUED,
    SEARCH,
    STABLE,
    STOP,
)
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
    R_EPOCH,
    R_FLOOR,
    R_MASK,
    R_QMIN,
    R_RELEASED,
    R_STATE,
    R_TAG_X,
    R_TAG_Y,
    R_TS,
)
from etswarm.algorithm.messages import MSG_STATUS
from etswarm.algorithm.params import (
    C_EVAL_EVERY,
)
from etswarm.algorithm.placed import placed_rule
from etswarm.algorithm.release import queued_rule
from etswarm.algorithm.search import search_rule


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
def et_step(  # type: ignore[no-untyped-def]
    tick,
    alive,
    in_count,
    in_type,
    in_data,
    in_dist,
    motor,
    led,
    out_on,
    out_type,
    out_data,
    mem,
    rng,
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
