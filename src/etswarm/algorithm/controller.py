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

import numpy as np
from numba import njit

from etswarm.algorithm.census_walk import sends_tag, walk_rule, walking
from etswarm.algorithm.extent import encode_extent, ingest_extent, sends_extent
from etswarm.algorithm.hole_watch import encode_watch, file_watch, sends_watch, watch_edge
from etswarm.algorithm.kernel_util import (
    INACTIVE,
    LEADER,
    QUEUED,
    SEARCH,
    STABLE,
    STOP,
)
from etswarm.algorithm.memory import (
    NB_ANCHORED,
    NB_EEPOCH,
    NB_EHOP,
    NB_ELAST,
    NB_ELEADER,
    NB_EPARENT,
    NB_EPOCH,
    NB_ESUB,
    NB_HOPS,
    NB_ID,
    NB_LAST,
    NB_MASK,
    NB_OTHER,
    NB_OX,
    NB_OY,
    NB_PREV,
    NB_QRANK,
    NB_READINGS,
    NB_RELEASED,
    NB_STATE,
    NB_TS,
    NB_TX,
    NB_TY,
    PHASE_ELECTING,
    PHASE_NORMAL,
    R_ADOPTED_AT,
    R_EPOCH,
    R_HOLD_UNTIL,
    R_HOP,
    R_INSIDE,
    R_LEADER,
    R_LOST_SINCE,
    R_MASK,
    R_MOVED_TICK,
    R_OFF_X,
    R_OFF_Y,
    R_PARENT,
    R_PEND_EPOCH,
    R_PEND_N,
    R_PEND_TX,
    R_PEND_TY,
    R_PHASE,
    R_QMIN,
    R_QRANK,
    R_RELEASED,
    R_SHAPE_HOPS,
    R_STATE,
    R_SUBCOUNT,
    R_TAG_X,
    R_TAG_Y,
    R_TS,
    R_TSLOT,
    R_WALK,
    R_WALK_SEEN,
    R_YIELD_SINCE,
    SLOT_LIMIT,
    SLOT_SIG,
    SLOT_TX,
    SLOT_TY,
    SLOT_WX,
    SLOT_WY,
)
from etswarm.algorithm.merge import contact_rule
from etswarm.algorithm.messages import (
    ANCHORED_BIT,
    EPOCH_SHIFT,
    HOLD_UNIT_TICKS,
    INSIDE_BIT,
    KIND_MASK,
    MSG_ELECT,
    MSG_EXTENT,
    MSG_HELD,
    MSG_SILENT,
    MSG_STATUS,
    MSG_TARGET,
    MSG_WATCH,
    YIELDING_BIT,
    get_i8,
    get_u16,
    put_i8,
    target_signature,
)
from etswarm.algorithm.offsets import sent_offset
from etswarm.algorithm.params import (
    C_EVAL_EVERY,
    C_GOSSIP_EVERY,
    C_HOLE_WATCH,
    C_STATUS_SIG,
    C_STILL_READINGS,
    C_TICKS_NB_FRESH,
)
from etswarm.algorithm.placed import placed_rule
from etswarm.algorithm.regeneration import (
    TARGET_RELAY_TICKS,
    announcement_rule,
    catch_up,
    election_rule,
    from_sibling,
    join_election,
    target_code,
)
from etswarm.algorithm.release import clear_ticks, queued_rule
from etswarm.algorithm.search import search_rule
from etswarm.algorithm.silent import encode_silent, ingest_silent, note_silent, sends_silent
from etswarm.algorithm.site_memory import encode_held, gossip_due, merge_held
from etswarm.sim.prefetch import prefetch

#: The table rows of the busy robot this many places ahead are asked for (``et_part``).
BUSY_AHEAD = 4

#: Ticks of one gossip window: the default transmit period (``SimParams.tx_period``), so
#: that about one transmission in ``held_gossip_every`` carries a memory chunk.
GOSSIP_PERIOD_TICKS = 15
#: Placed robots that are not Stable send a memory chunk this many times less often.
FRONT_GOSSIP_SHARE = 4

#: Added to ``ingest``'s answer for a status message that changed its row (see there).
CHANGED = 8


@njit(inline="always")
def table_row(i, sender, nb):  # type: ignore[no-untyped-def]
    """Index of ``sender``'s row in robot i's neighbour table, -1 if it has none."""
    hit = -1
    for m in range(nb.shape[1] - 1, -1, -1):
        hit = m if nb[i, m, NB_ID] == sender else hit  # the first, found without a branch
    return hit


@njit(inline="always")
def table_slot(i, sender, nb):  # type: ignore[no-untyped-def]
    """Index of ``sender``'s row in robot i's neighbour table; a new robot takes a free
    row, else the one heard longest ago (returned negated minus one: -(row) - 1)."""
    hit = table_row(i, sender, nb)
    if hit >= 0:
        return hit
    free = -1
    oldest = -1
    oldest_tick = 1 << 62
    for m in range(nb.shape[1]):
        sid = nb[i, m, NB_ID]
        if sid < 0:
            if free < 0:
                free = m
        elif nb[i, m, NB_LAST] < oldest_tick:
            oldest_tick = nb[i, m, NB_LAST]
            oldest = m
    row = free if free >= 0 else oldest
    nb[i, row, NB_ID] = sender
    nb[i, row, NB_PREV] = -1
    nb[i, row, NB_STATE] = QUEUED
    nb[i, row, NB_EEPOCH] = -1
    # Nothing of the row's previous robot may pass for this one's until its status is
    # heard (an election or target message creates the row without one): no epoch yet,
    # no released count, no occupancy bits.
    nb[i, row, NB_EPOCH] = -1
    nb[i, row, NB_RELEASED] = 0
    nb[i, row, NB_MASK] = 0
    nb[i, row, NB_ANCHORED] = 0
    nb[i, row, NB_OTHER] = 0
    return -row - 1


@njit
def prefetch_field(i, f, nb):  # type: ignore[no-untyped-def]
    """Ask for field ``f`` of every row of robot i's table (16 int64 in 128 bytes, three
    cache lines at most); changes no value."""
    row = nb[i, :, f]
    prefetch(row, 0)
    prefetch(row, 7)
    prefetch(row, 15)


@njit
def prefetch_memory(i, ri):  # type: ignore[no-untyped-def]
    """Ask for the start of robot i's memory row, fields 0 .. R_EPOCH (what filing and
    the wake test read: state, lowest Queued ID, released count, epoch); changes no
    value."""
    row = ri[i]
    prefetch(row, 0)
    prefetch(row, 7)
    prefetch(row, 15)
    prefetch(row, R_EPOCH)


@njit(inline="always")
def near_epoch(own, wrapped, modulus):  # type: ignore[no-untyped-def]
    """The epoch nearest to ``own`` whose value mod ``modulus`` is ``wrapped``."""
    delta = (wrapped - own) % modulus
    if delta >= modulus // 2:
        delta -= modulus
    return own + delta


@njit(inline="always")
def stands_still(state):  # type: ignore[no-untyped-def]
    """A robot in this state has its motors off: Queued, or placed and not electing."""
    return state == QUEUED or INACTIVE <= state <= STABLE


@njit(inline="always")
def average_reading(i, slot, last_mean, last_count, most, nb, nb_dist):  # type: ignore[no-untyped-def]
    """Fold the reading just filed in ``nb_dist[i, slot]`` (mm) into ``last_mean``, the mean
    of the row's ``last_count`` earlier readings taken since both robots last moved: a
    running mean of up to ``most`` readings, then each new one weighs ``1 / most``."""
    n = min(last_count + 1, most)
    if n > 1:
        nb_dist[i, slot] = last_mean + (nb_dist[i, slot] - last_mean) / n
        nb[i, slot, NB_READINGS] = n


@njit(inline="always")
def note_reading(i, k, tick, in_data, in_dist, nb, nb_dist):  # type: ignore[no-untyped-def]
    """Take message k of robot i's inbox (one that carries no status) as a fresh distance
    reading of its sender when the sender has a row in i's table; True if it had one."""
    return reading_of_row(i, table_row(i, get_u16(in_data[i, k], 0), nb), k, tick, in_dist,
                          nb, nb_dist)


@njit(inline="always")
def reading_of_row(i, m, k, tick, in_dist, nb, nb_dist):  # type: ignore[no-untyped-def]
    """``note_reading`` for the sender's row m of robot i's table (-1: none)."""
    if m < 0:
        return False
    nb[i, m, NB_LAST] = tick
    nb_dist[i, m] = in_dist[i, k]
    nb[i, m, NB_READINGS] = 1
    return True


@njit(inline="always")
def slot_signature(slot, slot_info):  # type: ignore[no-untyped-def]
    """``messages.target_signature`` of the target in ``slot`` (its code and placement)."""
    return target_signature(
        target_code(slot_info, slot), slot_info[slot, SLOT_TX], slot_info[slot, SLOT_TY]
    )


@njit
def file_held(i, k, tick, ri, in_type, in_data, in_dist, nb, nb_dist, held, slot_info):  # type: ignore[no-untyped-def]
    """File held-sites message k of robot i's inbox: its chunk into i's memory when it is
    for i's target (``site_memory.merge_held``); when it is for i's epoch, whether its
    sender works for another target of it (``NB_OTHER``); its distance as a reading of
    the sender (``note_reading``, whose answer it returns). Kept out of line: the loop
    over the inbox of every robot stays small."""
    signature = slot_signature(ri[i, R_TSLOT], slot_info)
    merge_held(i, k, ri, in_type, in_data, held, signature)
    m = table_row(i, get_u16(in_data[i, k], 0), nb)
    if m >= 0 and (np.int64(in_type[i, k]) >> EPOCH_SHIFT) == (ri[i, R_EPOCH] & 31):
        # Sent for robot i's epoch: a placed robot of another target of it belongs to a
        # sibling remnant, whatever its tag (``kinship.foreign``).
        other = np.int64(in_data[i, k, 3]) != signature
        nb[i, m, NB_OTHER] = ri[i, R_EPOCH] + 1 if other else 0
    return reading_of_row(i, m, k, tick, in_dist, nb, nb_dist)


@njit(inline="always")
def ingest(i, k, tick, ri, in_type, in_data, in_dist, nb, nb_dist, slot_info, ci):  # type: ignore[no-untyped-def]
    """Store message k of robot i's inbox in its neighbour table (layouts in ``messages``).

    Returns the message kind, plus ``CHANGED`` for a status message that filled a new row
    (a robot not in the table, or one that took another's row), brought a new state, or
    came from or left the robot's target epoch. A target announcement is kept in R_PEND_*
    when it is newer than the one kept.
    """
    kind = np.int64(in_type[i, k]) & KIND_MASK
    if kind in (MSG_HELD, MSG_WATCH):
        return kind  # no status, no row of its own (``note_reading``, ``merge_held``)
    sender = np.int64(in_data[i, k, 0]) | (np.int64(in_data[i, k, 1]) << 8)
    slot = table_slot(i, sender, nb)
    created = slot < 0
    if created:
        slot = -slot - 1
    # With averaging on (``still_readings`` > 1): whether this robot has stood still since
    # the row's last reading (motors off since then, see R_MOVED_TICK), and that row's
    # mean and count, before they are overwritten.
    still_since_last = False
    last_mean = 0.0
    last_count = 0
    if ci[C_STILL_READINGS] > 1 and not created:
        still_since_last = ri[i, R_MOVED_TICK] < nb[i, slot, NB_LAST]
        last_mean = nb_dist[i, slot]
        last_count = nb[i, slot, NB_READINGS]
    nb[i, slot, NB_LAST] = tick
    nb_dist[i, slot] = in_dist[i, k]
    nb[i, slot, NB_READINGS] = 1
    if kind == MSG_ELECT:
        wrapped = np.int64(in_type[i, k]) >> EPOCH_SHIFT
        nb[i, slot, NB_EEPOCH] = near_epoch(ri[i, R_EPOCH] + 1, wrapped, 32)
        nb[i, slot, NB_ELEADER] = np.int64(in_data[i, k, 2]) | (np.int64(in_data[i, k, 3]) << 8)
        nb[i, slot, NB_EHOP] = np.int64(in_data[i, k, 4])
        parent = np.int64(in_data[i, k, 5]) | (np.int64(in_data[i, k, 6]) << 8)
        nb[i, slot, NB_EPARENT] = -1 if parent == 0xFFFF else parent
        nb[i, slot, NB_ESUB] = np.int64(in_data[i, k, 7]) | (np.int64(in_data[i, k, 8]) << 8)
        nb[i, slot, NB_ELAST] = tick
        if nb[i, slot, NB_EEPOCH] <= ri[i, R_EPOCH] and ri[i, R_EPOCH] > 0:
            # It still elects for a target this robot has adopted: relay the announcement.
            ri[i, R_ADOPTED_AT] = tick
        return kind
    if kind == MSG_SILENT:
        wrapped = np.int64(in_type[i, k]) >> EPOCH_SHIFT
        ingest_silent(i, k, tick, ri, in_data, near_epoch(ri[i, R_EPOCH] + 1, wrapped, 32))
        return kind
    if kind == MSG_EXTENT:
        wrapped = np.int64(in_type[i, k]) >> EPOCH_SHIFT
        elected = near_epoch(ri[i, R_EPOCH] + 1, wrapped, 32)
        ingest_extent(i, k, tick, ri, in_type, in_data, elected)
        return kind
    if kind == MSG_TARGET:
        epoch = near_epoch(ri[i, R_EPOCH] + 1, np.int64(in_data[i, k, 2]), 256)
        leader = np.int64(in_data[i, k, 7]) | (np.int64(in_data[i, k, 8]) << 8)
        if epoch > ri[i, R_PEND_EPOCH] and not from_sibling(i, ri, epoch, leader, ci):
            ri[i, R_PEND_EPOCH] = epoch
            ri[i, R_PEND_N] = np.int64(in_data[i, k, 3]) | (np.int64(in_data[i, k, 4]) << 8)
            tx = np.int64(in_data[i, k, 5])
            ty = np.int64(in_data[i, k, 6])
            ri[i, R_PEND_TX] = tx - 256 if tx >= 128 else tx
            ri[i, R_PEND_TY] = ty - 256 if ty >= 128 else ty
        return kind
    state = np.int64(in_data[i, k, 2]) & 0x0F
    own = ri[i, R_EPOCH]
    changed = created or nb[i, slot, NB_EPOCH] != own or nb[i, slot, NB_STATE] != state
    nb[i, slot, NB_EPOCH] = near_epoch(own, np.int64(in_type[i, k]) >> EPOCH_SHIFT, 32)
    if nb[i, slot, NB_EPOCH] != own:
        changed = True
        if nb[i, slot, NB_EPOCH] < own:
            ri[i, R_ADOPTED_AT] = tick  # it works for an older target: relay the newer one
    if not created and nb[i, slot, NB_STATE] != state:
        nb[i, slot, NB_PREV] = nb[i, slot, NB_STATE]
    if still_since_last and stands_still(nb[i, slot, NB_STATE]) and stands_still(state):
        average_reading(i, slot, last_mean, last_count, ci[C_STILL_READINGS], nb, nb_dist)
    nb[i, slot, NB_STATE] = state
    if ci[C_STATUS_SIG] != 0 and own > 0 and nb[i, slot, NB_EPOCH] == own and (
        np.int64(in_data[i, k, 2]) >> 4 != slot_info[ri[i, R_TSLOT], SLOT_SIG]
    ):
        # A sibling remnant's robot: the same epoch, another target (``NB_OTHER``, as a
        # held-sites message with another signature marks it; a match clears nothing).
        nb[i, slot, NB_OTHER] = own + 1
    if state >= INACTIVE:
        tx = np.int64(in_data[i, k, 3])
        ty = np.int64(in_data[i, k, 4])
        nb[i, slot, NB_TX] = tx - 256 if tx >= 128 else tx
        nb[i, slot, NB_TY] = ty - 256 if ty >= 128 else ty
        nb[i, slot, NB_TS] = np.int64(in_data[i, k, 5])
        nb[i, slot, NB_MASK] = np.int64(in_data[i, k, 7])
        nb[i, slot, NB_OX] = get_i8(in_data[i, k], 6)
        nb[i, slot, NB_OY] = get_i8(in_data[i, k], 8)
    else:
        nb[i, slot, NB_RELEASED] = np.int64(in_data[i, k, 7]) | (np.int64(in_data[i, k, 8]) << 8)
        nb[i, slot, NB_QRANK] = np.int64(in_data[i, k, 3]) | (np.int64(in_data[i, k, 4]) << 8)
        nb[i, slot, NB_HOPS] = np.int64(in_data[i, k, 5])
        nb[i, slot, NB_ANCHORED] = np.int64(in_data[i, k, 6])
    return kind + CHANGED if changed else kind



@njit(inline="always")
def idle_wake(i, k, tick, wake, ri, in_data, ci):  # type: ignore[no-untyped-def]
    """A sleeping Queued robot's wake tick (``wake``, see ``release.queued_rule``) after it
    filed status message k of its inbox, which changed nothing of its row but the time and
    the contents (else it wakes: 0). Its next evaluation could decide otherwise when the
    message brings a higher released count, a lower Queued ID than the lowest it heard,
    or a lower-ID Queued robot's queue rank that raises its own (``release``); hearing
    the lowest again keeps that entry fresh for longer, and a searcher heard by the robot
    that is lowest itself restarts its wait for a clear repository.
    (The robot's ``R_QMIN``, ``R_RELEASED`` and epoch do not change while it sleeps.)
    A placed robot sleeps only till its next due tick, when it evaluates whatever it heard.
    """
    if ri[i, R_STATE] != QUEUED:
        return wake
    state = np.int64(in_data[i, k, 2]) & 0x0F
    if state > SEARCH:
        return wake
    if (np.int64(in_data[i, k, 7]) | (np.int64(in_data[i, k, 8]) << 8)) > ri[i, R_RELEASED]:
        return 0
    qmin = ri[i, R_QMIN]
    if state == SEARCH:
        if qmin == i:
            return max(wake, tick + clear_ticks(i, ri, ci))
        return wake
    sender = np.int64(in_data[i, k, 0]) | (np.int64(in_data[i, k, 1]) << 8)
    if sender < qmin:
        return 0
    if sender < i and get_u16(in_data[i, k], 3) + 1 > ri[i, R_QRANK]:
        return 0  # its rank grows
    if sender == qmin:
        return tick + ci[C_TICKS_NB_FRESH] + 1
    return wake


@njit(inline="always")
def status_bits(i, ri, slot_info, ci):  # type: ignore[no-untyped-def]
    """The high half of byte 2 of robot i's status: with ``ETParams.status_signature``, the
    four signature bits of the target it works for (``SLOT_SIG``), else 0."""
    if ci[C_STATUS_SIG] == 0:
        return 0
    return slot_info[ri[i, R_TSLOT], SLOT_SIG] << 4


@njit(inline="always")
def encode(i, tick, ri, bits, out_on, out_type, out_data):  # type: ignore[no-untyped-def]
    """Write robot i's next broadcast (layouts in ``messages``): its election message while
    electing (every other period its status instead while census walking, see
    ``census_walk.sends_tag``); for a while after adopting a scaled target, every other
    period its announcement; otherwise its status, with ``bits`` (``status_bits``) in the
    high half of byte 2."""
    out_on[i] = True
    out_data[i, 0] = i & 0xFF
    out_data[i, 1] = (i >> 8) & 0xFF
    if ri[i, R_PHASE] == PHASE_ELECTING and not ((tick // 15) % 2 and sends_tag(i, tick, ri)):
        if sends_silent(i, tick, ri):
            encode_silent(i, ri, out_type, out_data)
            return
        if sends_extent(i, tick, ri):
            encode_extent(i, ri, out_type, out_data)
            return
        epoch = ri[i, R_EPOCH] + 1
        out_type[i] = MSG_ELECT | ((epoch & 31) << EPOCH_SHIFT)
        out_data[i, 2] = ri[i, R_LEADER] & 0xFF
        out_data[i, 3] = (ri[i, R_LEADER] >> 8) & 0xFF
        out_data[i, 4] = min(ri[i, R_HOP], 255)
        parent = ri[i, R_PARENT] if ri[i, R_PARENT] >= 0 else 0xFFFF
        out_data[i, 5] = parent & 0xFF
        out_data[i, 6] = (parent >> 8) & 0xFF
        out_data[i, 7] = ri[i, R_SUBCOUNT] & 0xFF
        out_data[i, 8] = (ri[i, R_SUBCOUNT] >> 8) & 0xFF
        return
    if ri[i, R_EPOCH] > 0 and tick - ri[i, R_ADOPTED_AT] < TARGET_RELAY_TICKS and (tick // 15) % 2:
        slot_n = ri[i, R_PEND_N]
        out_type[i] = MSG_TARGET
        out_data[i, 2] = ri[i, R_EPOCH] & 0xFF
        out_data[i, 3] = slot_n & 0xFF
        out_data[i, 4] = (slot_n >> 8) & 0xFF
        out_data[i, 5] = ri[i, R_PEND_TX] & 0xFF
        out_data[i, 6] = ri[i, R_PEND_TY] & 0xFF
        out_data[i, 7] = ri[i, R_LEADER] & 0xFF
        out_data[i, 8] = (ri[i, R_LEADER] >> 8) & 0xFF
        return
    state = ri[i, R_STATE]
    out_type[i] = MSG_STATUS | ((ri[i, R_EPOCH] & 31) << EPOCH_SHIFT)
    out_data[i, 2] = state | bits
    if state >= INACTIVE:
        out_data[i, 3] = ri[i, R_TAG_X] & 0xFF
        out_data[i, 4] = ri[i, R_TAG_Y] & 0xFF
        out_data[i, 5] = min(ri[i, R_TS], 255)
        put_i8(out_data[i], 6, sent_offset(ri[i, R_OFF_X]))
        out_data[i, 7] = ri[i, R_MASK] & 0x3F
        put_i8(out_data[i], 8, sent_offset(ri[i, R_OFF_Y]))
    else:
        out_data[i, 3] = ri[i, R_QRANK] & 0xFF
        out_data[i, 4] = (ri[i, R_QRANK] >> 8) & 0xFF
        out_data[i, 5] = min(ri[i, R_SHAPE_HOPS], 255)
        if state == SEARCH:
            anchored = ANCHORED_BIT if ri[i, R_LOST_SINCE] == 0 else 0
            inside = INSIDE_BIT if ri[i, R_INSIDE] == 1 else 0
            out_data[i, 6] = (
                anchored | (YIELDING_BIT if ri[i, R_YIELD_SINCE] >= 0 else 0) | inside
            )
        else:
            left = (ri[i, R_HOLD_UNTIL] - tick + HOLD_UNIT_TICKS - 1) // HOLD_UNIT_TICKS
            out_data[i, 6] = min(max(left, 0), 255)
        out_data[i, 7] = ri[i, R_RELEASED] & 0xFF
        out_data[i, 8] = (ri[i, R_RELEASED] >> 8) & 0xFF


@njit
def encode_placed(i, tick, ri, nb, ci, held, slot_info, out_on, out_type, out_data):  # type: ignore[no-untyped-def]
    """Write placed robot i's next broadcast with held-site gossip on: a chunk of its
    memory of held sites instead of its status once every ``held_gossip_every`` transmit
    periods if Stable, a quarter as often on the growth front (a free site's neighbours are
    never Stable, and the status messages searchers localise by keep most of their rate);
    otherwise as ``encode``. A chunk is written at the robot's first evaluation in its
    window and kept for the window."""
    every = ci[C_GOSSIP_EVERY]
    if ri[i, R_STATE] != STABLE:
        every *= FRONT_GOSSIP_SHARE
    gossiping = gossip_due(tick, every, GOSSIP_PERIOD_TICKS)
    if gossiping and out_type[i] & KIND_MASK == MSG_HELD:
        return  # the chunk of this window is written already
    encode(i, tick, ri, status_bits(i, ri, slot_info, ci), out_on, out_type, out_data)
    if gossiping and out_type[i] & KIND_MASK == MSG_STATUS:  # not while relaying a target
        slot = ri[i, R_TSLOT]
        encode_held(
            i, tick, every, GOSSIP_PERIOD_TICKS, ri, nb, held, slot_info[slot, SLOT_WX],
            slot_info[slot, SLOT_WY], slot_signature(slot, slot_info), out_type, out_data,
        )


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(_nrt=True)
def busy_robots(lo, hi, tick, alive, in_count, idle, motor):  # type: ignore[no-untyped-def]
    """The robots of ``lo .. hi - 1`` with something to do this tick, in index order: alive,
    and awake (``idle`` <= ``tick``), with messages to file (``in_count`` > 0) or with
    motors that ran over the last tick (``motor``, it notes when it last moved; a robot
    goes to sleep with its motors off, so this adds none but after outside edits); the
    others sleep (see :func:`et_part`). Returns ``(busy, n)``: ``busy[:n]`` their IDs
    (``busy`` (hi - lo,) int64). Listed without a branch per robot: whether a robot heard
    something is as good as random, and a branch on it mispredicted often.
    """
    busy = np.empty(hi - lo, dtype=np.int64)
    n = 0
    for i in range(lo, hi):
        busy[n] = i
        n += np.int64(alive[i] & ((in_count[i] > 0) | (idle[i] <= tick) | (motor[i] != STOP)))
    return busy, n


# takes busy_robots' array back: keeps reference counting (etswarm.sim.borrow)
@njit(cache=True, _nrt=True)
def et_part(  # type: ignore[no-untyped-def]
    lo,
    hi,
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
):
    """One control tick for robots ``lo .. hi - 1`` (the controller protocol's ``part_step``).

    A robot's work reads and writes only its own rows (``ri``, ``nb``, ``nb_dist``,
    ``walk_seen``, ``held``, its motor, LED and outgoing message) and reads the shared
    genes, ``slot_info`` and constants, which change only between kernel calls (the host
    adds targets). The one shared write is the stop flag, set to 1 by a robot that needs
    the host (a Leader's request): parts on different threads may set it at the same time,
    and only ever to the same value, read after the threads meet. So parts may run at once
    on disjoint ranges, in any order, and give what one pass over all robots gives.
    """
    idle = mem[-1]  # ticks until which each robot sleeps (see et_controller)
    busy, n_busy = busy_robots(lo, hi, tick, alive, in_count, idle, motor)
    busy_part(busy, n_busy, tick, alive, in_count, in_type, in_data, in_dist, motor, led,
              out_on, out_type, out_data, mem)


@njit(_nrt=False)
def busy_part(busy, n_busy, tick, alive, in_count, in_type, in_data, in_dist, motor, led,  # type: ignore[no-untyped-def]
              out_on, out_type, out_data, mem):
    """:func:`et_part`'s work for the robots ``busy[:n_busy]`` (``busy`` (n,) int64 IDs).
    Compiled without numba's reference counting (``_nrt=False``, which the functions it
    calls inherit): it allocates nothing, and every array it passes on is held by its
    caller, so the counting would be atomic updates of counters for nothing."""
    stop, ri, nb, nb_dist, gene_flag, gene_nn, slot_info, ci, cf, walk_seen, held, idle = mem
    every = ci[C_EVAL_EVERY]
    for b in range(n_busy):
        i = busy[b]
        # its IDs and epochs (filing reads both) arrive while the robots before it work
        ahead = busy[min(b + BUSY_AHEAD, n_busy - 1)]
        prefetch_field(ahead, NB_ID, nb)
        prefetch_field(ahead, NB_EPOCH, nb)
        prefetch_memory(ahead, ri)
        prefetch(in_data, ahead)
        prefetch(in_dist, ahead)
        if motor[i] != STOP:
            ri[i, R_MOVED_TICK] = tick - 1  # its motors ran over the last tick
        count = in_count[i]
        wake = idle[i]
        new_msgs = False
        election_heard = False
        if count:
            # Filing reads the IDs and then the sender's epoch, which lies far from them:
            # asked for now, the two misses overlap instead of following each other.
            prefetch_field(i, NB_EPOCH, nb)
        for k in range(count):
            kind = ingest(i, k, tick, ri, in_type, in_data, in_dist, nb, nb_dist, slot_info, ci)
            if kind == MSG_STATUS:
                new_msgs = True
                if np.int64(in_data[i, k, 2]) & 0x0F == LEADER:
                    ri[i, R_WALK_SEEN] = tick  # a census walker: send it our tag
                if wake > 0:
                    wake = idle_wake(i, k, tick, wake, ri, in_data, ci)
            elif kind == MSG_STATUS + CHANGED:
                new_msgs = True
                if np.int64(in_data[i, k, 2]) & 0x0F == LEADER:
                    ri[i, R_WALK_SEEN] = tick
                wake = 0
            elif kind == MSG_HELD:
                # a chunk of a placed robot's memory of held sites: a reading of a robot
                # in the table, nothing that wakes a sleeping robot
                new_msgs = file_held(
                    i, k, tick, ri, in_type, in_data, in_dist, nb, nb_dist, held, slot_info
                ) or new_msgs
            elif kind == MSG_WATCH:
                # searchers seen in a hole (``hole_watch``): kept, and a reading of a robot
                # in the table; nothing that wakes a sleeping robot
                file_watch(i, k, tick, ri, in_type, in_data, ci)
                new_msgs = note_reading(i, k, tick, in_data, in_dist, nb, nb_dist) or new_msgs
            else:
                wake = 0
                if kind == MSG_ELECT:
                    election_heard = True
        if count:
            idle[i] = wake
        if wake > tick:
            # Still asleep: it went to sleep in its state's rule as a Queued or placed
            # robot in the normal phase with no newer target pending, and nothing since
            # changed that (an election or target message wakes it), so the rest would
            # skip it too; skipping here spares reading its memory row.
            continue
        due = (tick + i) % every == 0
        if election_heard and ri[i, R_PHASE] == PHASE_NORMAL:
            for m in range(nb.shape[1]):
                if nb[i, m, NB_ID] >= 0 and nb[i, m, NB_EEPOCH] == ri[i, R_EPOCH] + 1:
                    # Another robot of this remnant is electing: join in.
                    join_election(i, tick, ri, ci)
                    motor[i] = STOP
                    break
        if ri[i, R_PHASE] == PHASE_NORMAL and ri[i, R_PEND_EPOCH] > ri[i, R_EPOCH]:
            # It missed the election of a newer target that it has now heard of.
            catch_up(i, tick, ri, nb, nb_dist, gene_flag, gene_nn, slot_info, ci)
        state = ri[i, R_STATE]
        slot = ri[i, R_TSLOT]
        if ri[i, R_PHASE] == PHASE_ELECTING and walking(ri[i, R_WALK]):
            walk_rule(i, tick, ri, nb, nb_dist, motor, walk_seen, gene_flag[slot], ci, cf, stop)
            led[i] = ri[i, R_STATE]
            encode(i, tick, ri, status_bits(i, ri, slot_info, ci), out_on, out_type, out_data)
            continue
        if ri[i, R_PHASE] == PHASE_ELECTING:
            motor[i] = STOP
            if not due:
                continue
            if not announcement_rule(i, tick, ri, nb, gene_flag, gene_nn, slot_info, ci):
                note_silent(i, tick, ri, nb, ci)
                election_rule(i, tick, ri, nb, ci, stop)
        elif state == SEARCH:
            search_rule(
                i, tick, new_msgs, ri, nb, nb_dist, motor, gene_flag[slot], gene_nn[slot], ci,
                cf, held, slot_info[slot, SLOT_WX], slot_info[slot, SLOT_WY],
            )
        elif not due:
            continue
        elif state == QUEUED:
            if wake > tick:
                continue  # asleep: the rule would change nothing (motor stopped, message sent)
            motor[i] = STOP
            wake = queued_rule(i, tick, ri, nb, ci, slot_info[slot, SLOT_LIMIT])
            if ri[i, R_PEND_EPOCH] > ri[i, R_EPOCH] or (
                ri[i, R_EPOCH] > 0 and tick - ri[i, R_ADOPTED_AT] < TARGET_RELAY_TICKS
            ):
                wake = 0  # it has a newer target to catch up with, or relays its target
            idle[i] = wake
        elif INACTIVE <= state <= STABLE:
            motor[i] = STOP
            placed_rule(
                i, tick, ri, nb, nb_dist, gene_flag[slot], ci, cf, held[i],
                slot_info[slot, SLOT_WX], slot_info[slot, SLOT_WY],
            )
            # (a no-op once placed_rule has started an election: it acts in the normal phase)
            contact_rule(i, tick, ri, nb, nb_dist, gene_flag[slot], ci)
            if ci[C_HOLE_WATCH] > 0 and ri[i, R_PHASE] == PHASE_NORMAL:
                watch_edge(i, tick, ri, nb, nb_dist, gene_flag[slot], ci, cf)
            if (
                ri[i, R_PHASE] == PHASE_NORMAL
                and INACTIVE <= ri[i, R_STATE] <= STABLE
                and ri[i, R_PEND_EPOCH] <= ri[i, R_EPOCH]
            ):
                # Until its next due tick it does nothing unless it hears something.
                idle[i] = tick + every
            else:
                idle[i] = 0
        else:
            motor[i] = STOP
        if ri[i, R_STATE] != SEARCH:
            motor[i] = STOP
        led[i] = ri[i, R_STATE]
        if ci[C_GOSSIP_EVERY] > 0 and INACTIVE <= ri[i, R_STATE] <= STABLE:
            encode_placed(i, tick, ri, nb, ci, held, slot_info, out_on, out_type, out_data)
        else:
            encode(i, tick, ri, status_bits(i, ri, slot_info, ci), out_on, out_type, out_data)
        if (
            ci[C_HOLE_WATCH] > 0
            and INACTIVE <= ri[i, R_STATE] <= STABLE
            and out_type[i] & KIND_MASK == MSG_STATUS
            and sends_watch(i, tick, ri, gene_flag[slot], ci)
        ):
            encode_watch(i, tick, ri, ci, out_type, out_data)


@njit(cache=True)
def et_rest(  # type: ignore[no-untyped-def]
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
    """The controller protocol's ``rest_step``: nothing is left after :func:`et_part` (the
    ET controller draws no random numbers and robots share no writes but the stop flag)."""
    return


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
    """One control tick for every robot (simulator fast-path contract): :func:`et_part`
    over all robots, then :func:`et_rest`."""
    et_part(0, alive.shape[0], tick, alive, in_count, in_type, in_data, in_dist, motor, led,
            out_on, out_type, out_data, mem)
    et_rest(tick, alive, in_count, in_type, in_data, in_dist, motor, led, out_on, out_type,
            out_data, mem, rng)
