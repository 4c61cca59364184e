"""Regeneration (paper Algorithm 2): election, census, and adopting a scaled target.

A Stable robot whose neighbour count stays below NN turns Danger and starts an election
for the next *epoch*; every robot of the remnant that hears it joins (and stops). The
election floods the lowest ID together with a hop count, which also builds a spanning
tree (each robot's parent is a neighbour one hop nearer the lowest ID); subtree sizes flow
back up the tree (convergecast). When nothing has changed for the quiet time, the robot
with the lowest ID knows it is the Leader. How it then counts the remnant is the census
method (``ETParams.census``, packed as ``C_CENSUS_WALK``):

- ``tree``: the Leader's subtree count is the census, at once.
- ``walk`` (the paper's): only robots that saw the damage themselves stand (the others
  join with no candidate, ``NO_LEADER``), so the Leader sits on the damaged edge. It walks
  round the remnant collecting the tags of the robots on its periphery, comes back onto
  its site and counts the bitmap's 1-cells in the area those tags bound (``census_walk``).

With its count n the Leader asks for ``scale(bitmap, n)`` placed where it keeps the most
robots it knows of in place (the host computes it: ``R_REQUEST``), adopts it and announces
(epoch, n, tx, ty); every robot adopts the announcement and relays it. Robots whose tag is
in the new shape stay (the Leader Active with TS 1, the others Inactive with TS 2); the
rest become Queued and join again through Search.
"""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.census_walk import RESULT_NONE, RESULT_TREE, WALK_NONE, WALK_START
from etswarm.algorithm.extent import reset_extent
from etswarm.algorithm.former_site import note_former_site
from etswarm.algorithm.kernel_util import (
    ACTIVE,
    DANGER,
    INACTIVE,
    LEADER,
    QUEUED,
    SEARCH,
    STABLE,
    direction_index,
    gene_at,
    is_placed,
    set_state,
)
from etswarm.algorithm.lone_kept import lone_in_new_target
from etswarm.algorithm.memory import (
    NB_EEPOCH,
    NB_EHOP,
    NB_ELAST,
    NB_ELEADER,
    NB_EPARENT,
    NB_EPOCH,
    NB_ESUB,
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    NO_SITE,
    PHASE_ELECTING,
    PHASE_NORMAL,
    R_ADOPTED_AT,
    R_BELOW_SINCE,
    R_BEST_SINCE,
    R_CANDIDATE,
    R_CENSUS,
    R_COUNT,
    R_COUNT_OFF,
    R_COUNT_SINCE,
    R_ELECT_MIN,
    R_ELECT_SINCE,
    R_EPOCH,
    R_EXCUSED,
    R_EXT_GREW,
    R_FLOOR,
    R_FLOOR_SINCE,
    R_GROWTH,
    R_HAS_TAG,
    R_HELD_EPOCH,
    R_HOP,
    R_LEADER,
    R_MASK,
    R_MISSING,
    R_NEWSLOT,
    R_NN,
    R_OFF_REFINE,
    R_OFF_TICK,
    R_OFF_X,
    R_OFF_Y,
    R_PARENT,
    R_PEND_EPOCH,
    R_PEND_N,
    R_PEND_TX,
    R_PEND_TY,
    R_PHASE,
    R_PRE_SINCE,
    R_PRE_STATE,
    R_QMIN,
    R_QMIN_SINCE,
    R_RELEASED,
    R_REMEMBERED_SINCE,
    R_REQUEST,
    R_RESUMED_AT,
    R_SEEN_FULL,
    R_SETTLED_COUNT,
    R_SETTLED_SINCE,
    R_SHAPE_HOPS,
    R_SILENT_N,
    R_SINCE,
    R_STATE,
    R_SUBCOUNT,
    R_TAG_X,
    R_TAG_Y,
    R_TS,
    R_TSLOT,
    R_WALK,
    R_WALK_END,
    R_WALK_RESULT,
    SLOT_N,
    SLOT_SHAPE,
    SLOT_TURN,
    SLOT_TX,
    SLOT_TY,
    SLOT_USED,
)
from etswarm.algorithm.params import (
    C_CENSUS_WALK,
    C_FALSE_ALARM,
    C_OFFSETS,
    C_REGROW_OFFSETS,
    C_SIBLING_TARGET,
    C_TICKS_NB_FRESH,
    C_TICKS_REGEN_QUIET,
    REGROWTH_OFFSETS,
    SIBLING_ADOPT,
    SIBLING_STRICT,
)
from etswarm.algorithm.pinch import pinches_new_target
from etswarm.algorithm.release import HOPS_NONE
from etswarm.algorithm.wave import nn_of

#: A robot catching up with a missed election keeps its site only when a placed robot of
#: the new target on a neighbour site reads nearer than this (mm): d plus the slack of a
#: stretched lattice (``localise.ADJACENT_SLACK_MM``).
CATCH_UP_NEAR_MM = 60.0
#: A target's code (``target_code``) carries its turn in multiples of this: n < 8192, and
#: the turn (0-5) fits the code's top three bits.
TURN_CODE = 8192

#: Codes of ``ETParams.regrowth_offsets`` in ``ci[C_REGROW_OFFSETS]``.
REGROW_OFFSETS_KEEP = REGROWTH_OFFSETS.index("keep")
REGROW_OFFSETS_RESET = REGROWTH_OFFSETS.index("reset")
#: Ticks a robot keeps relaying a newly adopted target (alternating with its status).
TARGET_RELAY_TICKS = 31 * 40
#: Leader field of a robot that has heard of no candidate yet (census walk).
NO_LEADER = 0xFFFF
#: A changed subtree count replaces the settled one after this share of the election's
#: quiet time (``settle_count``): a quarter, 17 s for a ten-hop remnant.
COUNT_GRACE_SHARE = 4
#: After this many quiet times of electing, a root may declare on its settled count
#: (``settle_count``); before, only on a count unchanged for the quiet time, as always.
LONG_ELECTION_SHARE = 4


@njit
def start_election(i, tick, ri, ci):  # type: ignore[no-untyped-def]
    """Robot i joins the election for epoch R_EPOCH + 1 as a candidate of its own."""
    ri[i, R_PRE_STATE] = ri[i, R_STATE]
    ri[i, R_PRE_SINCE] = ri[i, R_SINCE]
    ri[i, R_MISSING] = 0  # (placed_rule notes what a Stable robot missed)
    ri[i, R_PHASE] = PHASE_ELECTING
    ri[i, R_LEADER] = i
    ri[i, R_ELECT_MIN] = i
    ri[i, R_HOP] = 0
    ri[i, R_PARENT] = -1
    ri[i, R_SUBCOUNT] = 1
    ri[i, R_SETTLED_COUNT] = 1
    ri[i, R_SETTLED_SINCE] = tick
    ri[i, R_COUNT_OFF] = 0
    ri[i, R_ELECT_SINCE] = tick
    ri[i, R_BEST_SINCE] = tick
    ri[i, R_COUNT_SINCE] = tick
    ri[i, R_REQUEST] = 0
    ri[i, R_CANDIDATE] = 1
    ri[i, R_WALK] = WALK_NONE
    ri[i, R_WALK_RESULT] = RESULT_NONE
    ri[i, R_WALK_END] = -1
    reset_extent(i, tick, ri, ci)
    set_state(i, ri, DANGER, tick)


@njit
def join_election(i, tick, ri, ci):  # type: ignore[no-untyped-def]
    """Robot i joins an election it heard of. With census ``walk`` only robots that saw
    the damage themselves stand (paper: the Danger robots elect their Leader), so the
    Leader sits on the damaged edge, from where it can walk out; the others relay."""
    start_election(i, tick, ri, ci)
    if ci[C_CENSUS_WALK] == 1:
        ri[i, R_CANDIDATE] = 0
        ri[i, R_LEADER] = NO_LEADER
        ri[i, R_ELECT_MIN] = NO_LEADER


@njit
def settle_count(i, tick, ri, sub, grace):  # type: ignore[no-untyped-def]
    """Track robot i's subtree count ``sub``: a new value replaces the settled one once
    the count has differed from it for ``grace`` ticks. Over a large remnant at loss 0.2
    some child's entry goes stale now and then, and the count dips or doubles for a few
    seconds while the tree mends. A root that has elected for ``LONG_ELECTION_SHARE``
    quiet times may declare on a settled count that has held for the quiet time (traced
    on bigdisc seed 0: 367 robots elected for 2.8 h, the root's count between 290 and 431
    and never unchanged for the 69 s quiet time)."""
    if sub == ri[i, R_SETTLED_COUNT]:
        ri[i, R_COUNT_OFF] = 0
    elif ri[i, R_COUNT_OFF] == 0:
        ri[i, R_COUNT_OFF] = tick + 1
    elif tick - (ri[i, R_COUNT_OFF] - 1) >= grace:
        ri[i, R_SETTLED_COUNT] = sub
        ri[i, R_SETTLED_SINCE] = tick
        ri[i, R_COUNT_OFF] = 0


@njit
def election_rule(i, tick, ri, nb, ci, stop):  # type: ignore[no-untyped-def]
    """Min-ID flooding with hop counts and subtree counts; the quiet Leader asks for n
    (census ``tree``) or starts its walk round the remnant (census ``walk``)."""
    epoch = ri[i, R_EPOCH] + 1
    fresh = ci[C_TICKS_NB_FRESH]
    best_leader = i if ri[i, R_CANDIDATE] == 1 else NO_LEADER
    best_hop = 0
    parent = -1
    slots = nb.shape[1]
    for m in range(slots):
        sid = nb[i, m, NB_ID]
        if sid < 0 or nb[i, m, NB_EEPOCH] != epoch or tick - nb[i, m, NB_ELAST] > fresh:
            continue
        leader = nb[i, m, NB_ELEADER]
        hop = nb[i, m, NB_EHOP] + 1
        if (
            leader < best_leader
            or (leader == best_leader and hop < best_hop)
            or (leader == best_leader and hop == best_hop and parent >= 0 and sid < parent)
        ):
            best_leader = leader
            best_hop = hop
            parent = sid
    if best_leader != ri[i, R_LEADER] or best_hop != ri[i, R_HOP]:
        ri[i, R_BEST_SINCE] = tick
    ri[i, R_LEADER] = best_leader
    ri[i, R_ELECT_MIN] = min(ri[i, R_ELECT_MIN], best_leader)
    ri[i, R_HOP] = best_hop
    ri[i, R_PARENT] = parent
    sub = 1
    for m in range(slots):
        if (
            nb[i, m, NB_ID] >= 0
            and nb[i, m, NB_EEPOCH] == epoch
            and tick - nb[i, m, NB_ELAST] <= fresh
            and nb[i, m, NB_EPARENT] == i
            and nb[i, m, NB_ELEADER] == best_leader
        ):
            sub += nb[i, m, NB_ESUB]
    if sub != ri[i, R_SUBCOUNT]:
        ri[i, R_COUNT_SINCE] = tick
        ri[i, R_SUBCOUNT] = sub
    settle_count(i, tick, ri, sub, ci[C_TICKS_REGEN_QUIET] // COUNT_GRACE_SHARE)
    if best_leader != i:
        if ri[i, R_STATE] == LEADER:
            set_state(i, ri, DANGER, tick)
        ri[i, R_REQUEST] = 0
        return
    quiet = ci[C_TICKS_REGEN_QUIET]
    steady = tick - ri[i, R_COUNT_SINCE] >= quiet  # the count itself unchanged
    settled = (  # a long election: the settled count held, the count back at it
        tick - ri[i, R_ELECT_SINCE] >= LONG_ELECTION_SHARE * quiet
        and tick - ri[i, R_SETTLED_SINCE] >= quiet
        and ri[i, R_COUNT_OFF] == 0
    )
    if (
        ri[i, R_REQUEST] == 0
        and ri[i, R_WALK] == WALK_NONE
        and tick - ri[i, R_ELECT_SINCE] >= quiet
        and tick - ri[i, R_BEST_SINCE] >= quiet
        and tick - ri[i, R_EXT_GREW] >= quiet  # the remnant's extent has all come in
        and (steady or settled)
    ):
        set_state(i, ri, LEADER, tick)
        if ci[C_CENSUS_WALK] == 1:
            ri[i, R_WALK] = WALK_START  # census_walk.walk_rule takes over
            return
        ri[i, R_CENSUS] = sub if steady else ri[i, R_SETTLED_COUNT]
        ri[i, R_WALK_END] = tick
        ri[i, R_WALK_RESULT] = RESULT_TREE
        ri[i, R_REQUEST] = 1
        stop[0] = 1


@njit
def find_slot(slot_info, code, tx, ty):  # type: ignore[no-untyped-def]
    """Slot holding scale(bitmap, n) turned and translated by (tx, ty), where ``code`` is
    ``target_code``'s n + TURN_CODE * turn; -1 when there is none."""
    n = code
    turn = 0
    if turns_coded(slot_info):
        n = code % TURN_CODE
        turn = code // TURN_CODE
    for s in range(1, slot_info.shape[0]):
        if (
            slot_info[s, SLOT_USED] == 1
            and slot_info[s, SLOT_N] == n
            and slot_info[s, SLOT_TURN] == turn
            and slot_info[s, SLOT_TX] == tx
            and slot_info[s, SLOT_TY] == ty
        ):
            return s
    return -1


@njit(inline="always")
def turns_coded(slot_info):  # type: ignore[no-untyped-def]
    """Whether target codes carry a turn: the original shape (slot 0) has fewer than
    ``TURN_CODE`` cells, so every n fits below it. A larger shape is never turned, and
    its codes are n alone."""
    return slot_info[0, SLOT_N] < TURN_CODE


@njit(inline="always")
def target_code(slot_info, slot):  # type: ignore[no-untyped-def]
    """The target of ``slot`` as announced: its cell count n plus ``TURN_CODE`` times its
    turn (16 bits, bytes 3-4 of a target message; n alone for a shape of ``TURN_CODE``
    cells or more, ``turns_coded``)."""
    return slot_info[slot, SLOT_N] + TURN_CODE * slot_info[slot, SLOT_TURN]


@njit
def restart_offset(i, tick, seed, ri, ci):  # type: ignore[no-untyped-def]
    """Robot i keeps its site through a regeneration: with ``regrowth_offsets`` "reset"
    or "zero" its offset, an estimate in the frame of the target before (whose seeds may
    stand far from this remnant, across the drift of the whole lattice), starts again
    from 0; with "reset" a robot other than the new Active seed (``seed``) then refines
    it from its neighbours' readings until it is Stable (``offsets.refine_offset``)."""
    mode = ci[C_REGROW_OFFSETS]
    if mode == REGROW_OFFSETS_KEEP:
        return
    ri[i, R_OFF_X] = 0
    ri[i, R_OFF_Y] = 0
    refine = mode == REGROW_OFFSETS_RESET and not seed and ci[C_OFFSETS] == 1
    ri[i, R_OFF_REFINE] = 1 if refine else 0
    ri[i, R_OFF_TICK] = tick


@njit
def adopt_target(i, tick, ri, nb, slot, epoch, leader, gene_flag, gene_nn, slot_info, ci):  # type: ignore[no-untyped-def]
    """Robot i takes target ``slot`` of ``epoch``: stays on its site if the new shape has
    it (the Leader as the Active seed) and it does not stand far into a free site of it
    (``pinch.pinches_new_target``), else goes back to Queued. Its neighbour table is
    cleared: what it knew describes the old target. When the new target is the one it
    had (a false alarm, ``ETParams.false_alarm`` "resume"), it goes back to what it was
    instead (``resume``)."""
    same = slot_info[slot, SLOT_SHAPE] == slot_info[ri[i, R_TSLOT], SLOT_SHAPE]
    electing = ri[i, R_PHASE] == PHASE_ELECTING
    before = ri[i, R_PRE_STATE] if electing else ri[i, R_STATE]
    old_epoch = ri[i, R_EPOCH]
    ri[i, R_EPOCH] = epoch
    ri[i, R_TSLOT] = slot
    ri[i, R_PHASE] = PHASE_NORMAL
    ri[i, R_REQUEST] = 0
    ri[i, R_WALK] = WALK_NONE
    ri[i, R_ADOPTED_AT] = tick
    ri[i, R_PEND_EPOCH] = epoch
    ri[i, R_PEND_N] = target_code(slot_info, slot)
    ri[i, R_PEND_TX] = slot_info[slot, SLOT_TX]
    ri[i, R_PEND_TY] = slot_info[slot, SLOT_TY]
    ri[i, R_LEADER] = leader
    ri[i, R_BELOW_SINCE] = -1
    ri[i, R_SILENT_N] = 0  # the silent sites were for this election
    if same and ci[C_FALSE_ALARM] == 1 and resumable(i, ri, before):
        resume(i, tick, ri, before, electing, old_epoch)
        return
    ri[i, R_GROWTH] = epoch
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    had = ri[i, R_HAS_TAG] == 1
    keeps = had and gene_at(gene_flag[slot], ci, x, y) == 1
    if keeps and i != leader and pinches_new_target(i, tick, ri, nb, gene_flag[slot], ci):
        keeps = False  # it would narrow a free site of the new shape: it searches again
    if keeps and i != leader and lone_in_new_target(i, tick, ri, nb, gene_flag[slot], ci):
        keeps = False  # no kept neighbour: the growth would bend to meet it
    for m in range(nb.shape[1]):
        nb[i, m, NB_ID] = -1
    ri[i, R_COUNT] = 0
    ri[i, R_MASK] = 0  # what it observed was of the old target (see ``search.search_rule``)
    ri[i, R_SEEN_FULL] = 0
    ri[i, R_MISSING] = 0
    ri[i, R_EXCUSED] = 0
    ri[i, R_REMEMBERED_SINCE] = 0
    ri[i, R_RESUMED_AT] = 0
    if keeps:
        ri[i, R_NN] = nn_of(gene_at(gene_nn[slot], ci, x, y))
        restart_offset(i, tick, i == leader, ri, ci)
        if i == leader:
            set_state(i, ri, ACTIVE, tick)
            ri[i, R_TS] = 1
        else:
            set_state(i, ri, INACTIVE, tick)
            ri[i, R_TS] = 2
    else:
        if had:
            note_former_site(i, ri, x, y)  # it waits where it stood
        elif before != QUEUED:
            note_former_site(i, ri, NO_SITE, NO_SITE)  # a searcher: somewhere else by now
        ri[i, R_HAS_TAG] = 0
        set_state(i, ri, QUEUED, tick)
        ri[i, R_FLOOR] = -1
        ri[i, R_FLOOR_SINCE] = -(1 << 40)
        ri[i, R_RELEASED] = 0
        ri[i, R_QMIN] = i
        ri[i, R_QMIN_SINCE] = tick
        ri[i, R_SHAPE_HOPS] = HOPS_NONE


@njit
def resumable(i, ri, before):  # type: ignore[no-untyped-def]
    """Robot i, whose state was ``before`` the election, can take up its work again for
    the same target: it was Queued or searching, or placed and still holds its tag (a
    placed robot that missed the election may have given it up, see ``catch_up``)."""
    if before in (QUEUED, SEARCH):
        return True
    return INACTIVE <= before <= STABLE and ri[i, R_HAS_TAG] == 1


@njit
def resume(i, tick, ri, before, electing, old):  # type: ignore[no-untyped-def]
    """Robot i, which worked for epoch ``old``, takes up its work again after an election
    that kept its target (a false alarm): if it was ``electing`` it goes back to its state
    ``before``; its site, TS, offset, neighbour table and queue all stay as they were.
    A robot that started the election excuses the neighbour sites it missed (R_MISSING):
    they count as held until it adopts a new target, so the lattice's stretching that
    made it miss them does not start the same election again. Traced on `H` seed 75:
    searchers diving for a free site had pushed two Stable neighbours 94 mm apart, and
    the whole shape, nearly formed, regrew from its seeds again and again."""
    if electing:  # (a robot that missed the election never left its state)
        ri[i, R_STATE] = before
        ri[i, R_SINCE] = ri[i, R_PRE_SINCE]
    ri[i, R_EXCUSED] |= ri[i, R_MISSING]
    ri[i, R_MISSING] = 0
    ri[i, R_REMEMBERED_SINCE] = 0
    ri[i, R_RESUMED_AT] = tick + 1
    carry_memory(i, ri, old, ri[i, R_EPOCH])


@njit
def carry_memory(i, ri, old, new):  # type: ignore[no-untyped-def]
    """Robot i's memory of held sites, kept for epoch ``old``, holds for epoch ``new`` too
    (a kept target: the sites it heard held are still held)."""
    if ri[i, R_HELD_EPOCH] == old + 1:
        ri[i, R_HELD_EPOCH] = new + 1


@njit
def announcement_rule(i, tick, ri, nb, gene_flag, gene_nn, slot_info, ci):  # type: ignore[no-untyped-def]
    """Adopt a heard announcement of the target this robot's election was for (or of a
    newer one); a Leader adopts the target the host computed for it."""
    if ri[i, R_PHASE] != PHASE_ELECTING:
        return False
    epoch = ri[i, R_EPOCH] + 1
    if ri[i, R_REQUEST] == 2:
        slot = ri[i, R_NEWSLOT]
        adopt_target(i, tick, ri, nb, slot, epoch, i, gene_flag, gene_nn, slot_info, ci)
        return True
    if ri[i, R_PEND_EPOCH] >= epoch:
        # The target of this election, or a newer one: a robot that missed a whole
        # regeneration (it kept electing for an epoch the others are past) catches up.
        slot = find_slot(slot_info, ri[i, R_PEND_N], ri[i, R_PEND_TX], ri[i, R_PEND_TY])
        if slot >= 0:
            leader = ri[i, R_LEADER]
            pend = ri[i, R_PEND_EPOCH]
            adopt_target(i, tick, ri, nb, slot, pend, leader, gene_flag, gene_nn, slot_info, ci)
            return True
    return False


@njit
def from_sibling(i, ri, epoch, leader, ci):  # type: ignore[no-untyped-def]
    """Whether robot i should ignore the announcement of target ``epoch`` by Leader
    ``leader`` (``ETParams.sibling_target``). "ignore": it is electing for that epoch and
    hears a lower candidate than that Leader, so the Leader is not its own election's (the
    lowest ID of a remnant wins its election) but that of a sibling remnant of the same
    damage, one of whose robots has come within range while this remnant still elects.
    "strict": it is electing for that epoch and the Leader is not the lowest candidate it
    has heard in this election (``R_ELECT_MIN``). A relay that names no Leader
    (``NO_LEADER``: the relaying robot caught up with the target, ``catch_up``) is never
    ignored, nor, with "strict", any announcement to a robot that has heard no candidate
    yet (census ``walk``: a robot that did not see the damage stands for none)."""
    mode = ci[C_SIBLING_TARGET]
    if (
        mode == SIBLING_ADOPT
        or ri[i, R_PHASE] != PHASE_ELECTING
        or epoch != ri[i, R_EPOCH] + 1
        or leader == NO_LEADER
    ):
        return False
    if mode == SIBLING_STRICT:
        return ri[i, R_ELECT_MIN] != NO_LEADER and leader != ri[i, R_ELECT_MIN]
    return leader > ri[i, R_LEADER]


@njit
def catch_up(i, tick, ri, nb, nb_dist, gene_flag, gene_nn, slot_info, ci):  # type: ignore[no-untyped-def]
    """Robot i, not electing, has heard the announcement of a newer target than its own
    (R_PEND_*): it missed that election (it was searching out of range, or it belongs to
    another remnant that has come within range). It adopts the target as the electing
    robots do, with four differences: it is never the new seed; a searcher goes on
    searching, for the new target; a placed robot gives up its tag when it hears a robot
    of the new target on it (otherwise both would keep it); and a placed robot keeps its
    tag only when it hears a placed robot of the new target on a neighbour site within
    ``CATCH_UP_NEAR_MM`` (``joined_by_a_neighbour``). Returns True when it adopted the
    target.

    Before this, such a robot worked for its old target for good: its neighbours of the
    newer one ignore robots of other epochs, so the remnant could never become Stable
    round it, and a searcher took a site of the old target among the new one's robots."""
    slot = find_slot(slot_info, ri[i, R_PEND_N], ri[i, R_PEND_TX], ri[i, R_PEND_TY])
    if slot < 0:
        return False
    epoch = ri[i, R_PEND_EPOCH]
    if ri[i, R_STATE] == SEARCH:
        if ci[C_FALSE_ALARM] == 1 and (
            slot_info[slot, SLOT_SHAPE] == slot_info[ri[i, R_TSLOT], SLOT_SHAPE]
        ):
            carry_memory(i, ri, ri[i, R_EPOCH], epoch)  # the same target
        else:
            ri[i, R_GROWTH] = epoch
        ri[i, R_EPOCH] = epoch
        ri[i, R_TSLOT] = slot
        ri[i, R_ADOPTED_AT] = tick
        ri[i, R_LEADER] = -1
        return True
    if ri[i, R_HAS_TAG] == 1:
        fresh = ci[C_TICKS_NB_FRESH]
        for m in range(nb.shape[1]):
            if (
                nb[i, m, NB_ID] >= 0
                and is_placed(nb[i, m, NB_STATE])
                and nb[i, m, NB_EPOCH] == epoch
                and tick - nb[i, m, NB_LAST] <= fresh
                and nb[i, m, NB_TX] == ri[i, R_TAG_X]
                and nb[i, m, NB_TY] == ri[i, R_TAG_Y]
            ):
                ri[i, R_HAS_TAG] = 0
                break
        if not joined_by_a_neighbour(i, tick, ri, nb, nb_dist, epoch, fresh):
            ri[i, R_HAS_TAG] = 0  # its tag may be of another piece of lattice: search again
    adopt_target(i, tick, ri, nb, slot, epoch, -1, gene_flag, gene_nn, slot_info, ci)
    return True


@njit
def joined_by_a_neighbour(i, tick, ri, nb, nb_dist, epoch, fresh):  # type: ignore[no-untyped-def]
    """Placed robot i heard, within ``fresh`` ticks, a placed robot of target ``epoch`` on
    one of its own neighbour sites, nearer than ``CATCH_UP_NEAR_MM``: its tag fits the
    lattice of the remnant that elected.

    Traced on `T` `kill random=0.3` seed 4 (session 23): robot 4, Active on (-4, 3) in a
    piece 330-440 mm from the remnant, missed the election, heard of it later and kept
    (-4, 3), a site of the new target; a searcher then took (-4, 3) on the remnant's own
    lattice, 140 mm from robot 4, and the tag was held twice."""
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or not is_placed(nb[i, m, NB_STATE]):
            continue
        if nb[i, m, NB_EPOCH] != epoch or tick - nb[i, m, NB_LAST] > fresh:
            continue
        if nb_dist[i, m] < CATCH_UP_NEAR_MM and (
            direction_index(nb[i, m, NB_TX] - x, nb[i, m, NB_TY] - y) >= 0
        ):
            return True
    return False
