"""Release from the repository: lowest ID at the start, farthest from the shape after a
regeneration (``release_order``)."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_HOPS,
    NB_ID,
    NB_LAST,
    NB_QRANK,
    NB_STATE,
    R_EPOCH,
    R_GROWTH,
    R_QMIN_SINCE,
    R_QRANK,
    R_SHAPE_HOPS,
    R_STATE,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.release import (
    HOPS_NONE,
    HOPS_PARKED,
    crowded_long,
    queued_rule,
    shape_hops,
)
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State

from .traced import NATIVE_MATHS, SESSION_26_FORMATION

TICK = 10_000


def hear(nb: np.ndarray, i: int, slot: int, sender: int, state: State, hops: int,
         epoch: int = 1) -> None:
    """Robot i heard ``sender`` (in ``state``, ``hops`` to the shape) just now."""
    nb[i, slot, NB_ID] = sender
    nb[i, slot, NB_STATE] = state
    nb[i, slot, NB_HOPS] = hops
    nb[i, slot, NB_EPOCH] = epoch
    nb[i, slot, NB_LAST] = TICK


def chain(order: str):  # type: ignore[no-untyped-def]
    """Queued robots 5 - 0 - 7 in a line from a placed robot (ID 9) of epoch 1: robot 5
    hears the placed robot, 0 hears 5 and 7, 7 hears only 0. Every robot knows the hop
    counts the others send (5: 1, 0: 2, 7: 3)."""
    ri, nb, _ = allocate(10)
    ri[:, R_EPOCH] = ri[:, R_GROWTH] = 1  # a regrowth's target
    ri[:, R_QMIN_SINCE] = 0
    hear(nb, 5, 0, 9, State.STABLE, 0)
    hear(nb, 5, 1, 0, State.QUEUED, 2)
    hear(nb, 0, 0, 5, State.QUEUED, 1)
    hear(nb, 0, 1, 7, State.QUEUED, 3)
    hear(nb, 7, 0, 0, State.QUEUED, 2)
    ci, _ = ETParams(release_order=order).pack(31, 0, 0)
    return ri, nb, ci


def test_hop_counts_grow_away_from_the_shape() -> None:
    ri, nb, ci = chain("far")
    fresh = int(ci[0])
    assert shape_hops(5, TICK, ri, nb, fresh) == 1
    assert shape_hops(0, TICK, ri, nb, fresh) == 2
    assert shape_hops(7, TICK, ri, nb, fresh) == 3
    # Readings older than the neighbour timeout say nothing about a way to the shape.
    assert shape_hops(7, TICK + fresh + 1, ri, nb, fresh) == HOPS_NONE


@pytest.mark.parametrize(("order", "leaves"), [("far", 7), ("id", 0)])
def test_the_far_end_of_a_chain_leaves_first(order: str, leaves: int) -> None:
    ri, nb, ci = chain(order)
    for i in (5, 0, 7):
        queued_rule(i, TICK, ri, nb, ci, 100)
    left = [i for i in (5, 0, 7) if ri[i, R_STATE] == State.SEARCH]
    assert left == [leaves]
    if order == "far":
        assert [ri[i, R_SHAPE_HOPS] for i in (5, 0, 7)] == [1, 2, 3]


def test_a_kept_target_releases_as_the_first_formation_did() -> None:
    # After a false alarm in the first formation the robots work for epoch 1, but their
    # growth is still the first formation's (R_GROWTH 0): the lowest ID leaves first.
    ri, nb, ci = chain("far")
    ri[:, R_GROWTH] = 0
    for i in (5, 0, 7):
        queued_rule(i, TICK, ri, nb, ci, 100)
    assert [i for i in (5, 0, 7) if ri[i, R_STATE] == State.SEARCH] == [0]


@pytest.mark.parametrize("order", ["far", "id"])
def test_a_robot_of_a_remnant_too_small_to_grow_holds_back_no_release(order: str) -> None:
    # Robot 9 is all that is left of its remnant (its target is empty, limit 0); robot 4,
    # of the remnant beside it, hears it and the placed robot 2 of its own shape. (With
    # lowest-ID release robot 9 held back only robots of higher IDs.)
    ri, nb, _ = allocate(10)
    ri[:, R_EPOCH] = ri[:, R_GROWTH] = 1  # a regrowth's target
    ri[:, R_QMIN_SINCE] = 0
    ri[9, R_SHAPE_HOPS] = HOPS_NONE
    ci, _ = ETParams(release_order=order).pack(31, 0, 0)
    hear(nb, 9, 0, 4, State.QUEUED, 1)
    queued_rule(9, TICK, ri, nb, ci, 0)
    assert ri[9, R_STATE] == State.QUEUED and ri[9, R_SHAPE_HOPS] == HOPS_PARKED
    hear(nb, 4, 0, 2, State.STABLE, 0)
    hear(nb, 4, 1, 9, State.QUEUED, int(ri[9, R_SHAPE_HOPS]))
    queued_rule(4, TICK, ri, nb, ci, 23)
    assert ri[4, R_STATE] == State.SEARCH
    # Before session 23 robot 9 sent HOPS_NONE: the farthest from any shape (and, by ID,
    # not the lowest), robot 4 waited for it to leave first, for ever.
    # (robot 5 stands where robot 4 stood, hearing the same)
    hear(nb, 5, 0, 2, State.STABLE, 0)
    hear(nb, 5, 1, 9, State.QUEUED, HOPS_NONE)
    queued_rule(5, TICK, ri, nb, ci, 23)
    assert (ri[5, R_STATE] == State.SEARCH) == (order == "id")


def test_a_parked_robot_is_no_way_to_the_shape() -> None:
    ri, nb, ci = chain("far")
    hear(nb, 7, 1, 3, State.QUEUED, HOPS_PARKED)
    assert shape_hops(7, TICK, ri, nb, int(ci[0])) == 3


def test_a_split_t_regrows_both_remnants_with_far_first_release() -> None:
    # T split through the middle (traced on seed 0 when release was lowest-ID: the left
    # remnant's old stem was taken out of the middle and its far robots were left out of
    # range, so neither remnant re-formed). With the current defaults seed 0 re-forms both
    # remnants (seeds 0-9: 8 of the 9 first formations; see the closing notes for rates).
    run = ETRun(RunConfig(shape="T", seed=0, max_time_s=4 * 3600, damage=("split x=mid",)))
    summary = run.run()
    assert summary["settled"], summary["components"]
    assert len(summary["components"]) == 2
    for comp in summary["components"]:
        assert comp["formed"] and comp["jaccard"] == 1.0, comp
        assert comp["census_count"] == comp["robots"] == comp["target_cells"], comp
    assert summary["max_leaders_per_component"] <= 1
    assert summary["duplicate_tags"] == []
    assert summary["states"]["Danger"] == 0 and summary["states"]["Leader"] == 0


def crowded_far_end(epoch: int):  # type: ignore[no-untyped-def]
    """The chain of ``chain``, with a searcher (ID 8) beside its far end (robot 7), heard
    again at every evaluation; every robot works for target ``epoch``."""
    ri, nb, ci = chain("far")
    ri[:, R_EPOCH] = ri[:, R_GROWTH] = epoch
    for i in range(10):
        for slot in range(nb.shape[1]):
            if nb[i, slot, NB_ID] >= 0:
                nb[i, slot, NB_EPOCH] = epoch
    hear(nb, 7, 1, 8, State.SEARCH, 0, epoch)
    return ri, nb, ci


@pytest.mark.parametrize(("epoch", "leaves"), [(1, True), (0, False)])
def test_a_robot_crowded_by_a_searcher_leaves_after_damage_only(epoch: int, leaves: bool) -> None:
    ri, nb, ci = crowded_far_end(epoch)
    crowded_ticks = round(ETParams().regrowth_crowded_s * 31)
    step = 31
    for tick in range(TICK, TICK + crowded_ticks + 2 * step, step):
        nb[7, 1, NB_LAST] = tick  # the searcher is heard at every evaluation
        for i in (5, 0, 7):
            nb[i, 0, NB_LAST] = tick
            nb[i, 1, NB_LAST] = tick
        queued_rule(7, tick, ri, nb, ci, 100)
        if ri[7, R_STATE] == State.SEARCH:
            break
    # Its wait for the searcher to clear ends after regrowth_crowded_s in a regenerated
    # remnant, not before, and never in the first formation (the repository's rule).
    assert (ri[7, R_STATE] == State.SEARCH) == leaves
    if leaves:
        assert tick - TICK >= crowded_ticks



def test_a_clear_evaluation_restarts_the_crowded_wait() -> None:
    ri, _, _ = allocate(1)
    ci, _ = ETParams().pack(31, 0, 0)
    wait = round(ETParams().regrowth_crowded_s * 31)
    # crowded for two thirds of the wait, one clear evaluation, two thirds again
    assert not crowded_long(0, TICK, ri, ci, False)
    assert not crowded_long(0, TICK + 2 * wait // 3, ri, ci, False)
    assert not crowded_long(0, TICK + 2 * wait // 3 + 31, ri, ci, True)
    again = TICK + 2 * wait // 3 + 62
    assert not crowded_long(0, again, ri, ci, False)
    assert not crowded_long(0, again + 2 * wait // 3, ri, ci, False)
    assert crowded_long(0, again + wait, ri, ci, False)


def broken_queue(wait_s: float):  # type: ignore[no-untyped-def]
    """First formation, a queue sorted by ID: robot 12 (rank 12, learnt from robot 11
    behind it) and robot 13 ahead of it. Robot 11 has been pushed out of earshot while
    still Queued: robot 12 now hears no lower ID."""
    ri, nb, _ = allocate(14)
    ri[:, R_QMIN_SINCE] = 0
    hear(nb, 12, 0, 11, State.QUEUED, HOPS_NONE, epoch=0)
    nb[12, 0, NB_QRANK] = 11
    hear(nb, 12, 1, 13, State.QUEUED, HOPS_NONE, epoch=0)
    nb[12, 1, NB_QRANK] = 13
    ci, _ = ETParams(queue_rank_wait_s=wait_s).pack(31, 0, 0)
    queued_rule(12, TICK, ri, nb, ci, 100)  # it learns its rank while 11 is heard
    assert ri[12, R_QRANK] == 12 and ri[12, R_STATE] == State.QUEUED
    nb[12, 0, NB_LAST] = TICK - 10 * 31 * 60  # robot 11's entry has long gone stale
    return ri, nb, ci


def evaluate_until(ri, nb, ci, end: int) -> int | None:  # type: ignore[no-untyped-def]
    """Evaluate robot 12 every second from TICK + 1 s to ``end``; the tick it left, or None."""
    for tick in range(TICK + 31, end, 31):
        queued_rule(12, tick, ri, nb, ci, 100)
        if ri[12, R_STATE] == State.SEARCH:
            return tick
    return None


def test_a_queue_broken_near_the_shape_waits_for_the_robot_behind() -> None:
    ri, nb, ci = broken_queue(600.0)
    # The piece of queue beyond the break does not take 12 for the queue's end ...
    assert evaluate_until(ri, nb, ci, TICK + 300 * 31) is None
    # ... until robot 11, released at last, comes by as a searcher (rank 11).
    hear(nb, 12, 2, 11, State.SEARCH, HOPS_NONE, epoch=0)
    nb[12, 2, NB_QRANK] = 11
    nb[12, 2, NB_LAST] = TICK + 300 * 31
    left = evaluate_until(ri, nb, ci, TICK + 400 * 31)
    assert left is not None and left >= TICK + 300 * 31 + round(ETParams().release_clear_s * 31)


def test_a_queue_broken_near_the_shape_leaves_when_releases_stop() -> None:
    ri, nb, ci = broken_queue(600.0)
    left = evaluate_until(ri, nb, ci, TICK + 900 * 31)
    assert left is not None and TICK + 599 * 31 <= left <= TICK + 660 * 31
    # The paper's rule (wait 0) lets it go at once.
    ri, nb, ci = broken_queue(0.0)
    assert evaluate_until(ri, nb, ci, TICK + 30 * 31) is not None


def test_a_lone_robot_left_by_a_removal_does_not_stall_the_remnant_beside_it() -> None:
    # Traced (session 23): the removal leaves robot 26 alone, too small a remnant to grow,
    # in earshot of one Queued robot of the 23-robot remnant, which waited for it to leave
    # first until the end of the 4 h run, one site short.
    summary = ETRun(RunConfig(shape="L", seed=30, damage=("remove random=0.2",),
                              max_time_s=5400, et=ETParams(**SESSION_26_FORMATION)),
                    sim_params=NATIVE_MATHS).run()
    groups = summary["components"]
    assert [g["robots"] for g in groups if g["too_small"]] == [1]
    grown = [g for g in groups if not g["too_small"]]
    assert [g["robots"] for g in grown] == [23]
    assert grown[0]["formed"] and grown[0]["jaccard"] == 1.0
    assert summary["states"]["Queued"] == 1
