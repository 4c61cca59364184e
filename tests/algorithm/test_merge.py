"""Remnants that grow into contact elect again as one (``ETParams.merge_remnants``)."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_HOPS,
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    PHASE_ELECTING,
    R_EPOCH,
    R_GROWTH,
    R_PHASE,
    R_STATE,
    R_TAG_X,
    R_TAG_Y,
    allocate,
)
from etswarm.algorithm.merge import MERGE_AFTER_TICKS, contact_rule
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.parked import HOPS_PARKED
from etswarm.algorithm.release import HOPS_NONE
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State

from .traced import NATIVE_MATHS, SESSION_26_FORMATION, SESSION_31_PLACEMENT

GENE_X0 = -3


def beside_a_stranger(tag: tuple[int, int], reading: float, epoch: int = 1,
                      et: ETParams | None = None):  # type: ignore[no-untyped-def]
    """Stable robot 0 on (0, 0) of a target of the sites (0, 0), (1, 0), (0, 1), hearing
    Stable robot 1 (same epoch as robot 0's ``epoch``) on ``tag`` at ``reading`` mm."""
    gene_flag = np.zeros((7, 7), dtype=np.int64)
    for x, y in [(0, 0), (1, 0), (0, 1)]:
        gene_flag[x - GENE_X0, y - GENE_X0] = 1
    ci, _ = (et or ETParams()).pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    ri, nb, nb_dist = allocate(2)
    ri[0, R_STATE] = State.STABLE
    ri[0, R_EPOCH] = ri[0, R_GROWTH] = epoch
    ri[0, R_TAG_X], ri[0, R_TAG_Y] = 0, 0
    nb[0, 0, NB_ID] = 1
    nb[0, 0, NB_STATE] = State.STABLE
    nb[0, 0, NB_EPOCH] = epoch
    nb[0, 0, NB_TX], nb[0, 0, NB_TY] = tag
    nb_dist[0, 0] = reading
    return ri, nb, nb_dist, gene_flag, ci


def elects_after(ri, nb, nb_dist, gene_flag, ci, ticks: int,  # type: ignore[no-untyped-def]
                 start: int = 1000) -> bool:
    """Run the contact rule every 4 ticks from ``start`` for ``ticks`` ticks, the stranger
    heard at each; True once robot 0 starts an election."""
    for tick in range(start, start + ticks, 4):
        nb[0, 0, NB_LAST] = tick
        if contact_rule(0, tick, ri, nb, nb_dist, gene_flag, ci):
            return True
    return False


def test_a_robot_beside_another_remnants_robot_starts_an_election() -> None:
    world = beside_a_stranger((-1, 0), 40.0)  # (-1, 0) is no site of robot 0's target
    ri = world[0]
    assert not elects_after(*world, MERGE_AFTER_TICKS - 8)
    assert elects_after(*world, 16, start=1000 + MERGE_AFTER_TICKS - 8)
    assert ri[0, R_PHASE] == PHASE_ELECTING and ri[0, R_STATE] == State.DANGER


@pytest.mark.parametrize(
    ("tag", "reading", "epoch", "et"),
    [
        ((1, 0), 40.0, 1, None),  # a robot of its own target
        ((-1, 0), 80.0, 1, None),  # another remnant's, but across a free site
        ((-1, 0), 40.0, 0, None),  # the first formation: one target, nothing to merge
        ((-1, 0), 40.0, 1, ETParams(merge_remnants="off")),
    ],
)
def test_no_election_without_contact_with_another_remnant(
    tag: tuple[int, int], reading: float, epoch: int, et: ETParams | None
) -> None:
    world = beside_a_stranger(tag, reading, epoch, et)
    assert not elects_after(*world, 2 * MERGE_AFTER_TICKS)
    assert world[0][0, R_PHASE] != PHASE_ELECTING


def test_a_break_in_the_contact_restarts_the_wait() -> None:
    ri, nb, nb_dist, gene_flag, ci = beside_a_stranger((-1, 0), 40.0)
    assert not elects_after(ri, nb, nb_dist, gene_flag, ci, MERGE_AFTER_TICKS - 8)
    nb_dist[0, 0] = 90.0  # it stood off for one evaluation
    assert not contact_rule(0, 1000 + MERGE_AFTER_TICKS, ri, nb, nb_dist, gene_flag, ci)
    nb_dist[0, 0] = 40.0
    start = 1004 + MERGE_AFTER_TICKS
    assert not elects_after(ri, nb, nb_dist, gene_flag, ci, MERGE_AFTER_TICKS - 8, start)
    assert elects_after(ri, nb, nb_dist, gene_flag, ci, 16, start + MERGE_AFTER_TICKS - 8)


def beside_a_queued_robot(hops: int, epoch: int = 1, reading: float = 40.0,
                          mode: str = "on"):  # type: ignore[no-untyped-def]
    """``beside_a_stranger``, the stranger a Queued robot of ``epoch`` sending ``hops``."""
    ri, nb, nb_dist, gene_flag, ci = beside_a_stranger(
        (0, 0), reading, et=ETParams(merge_parked=mode)
    )
    nb[0, 0, NB_STATE] = State.QUEUED
    nb[0, 0, NB_EPOCH] = epoch
    nb[0, 0, NB_HOPS] = hops
    return ri, nb, nb_dist, gene_flag, ci


def test_a_robot_beside_a_parked_robot_starts_an_election() -> None:
    world = beside_a_queued_robot(HOPS_PARKED)
    assert elects_after(*world, MERGE_AFTER_TICKS + 8)
    assert world[0][0, R_PHASE] == PHASE_ELECTING


@pytest.mark.parametrize(
    ("hops", "epoch", "reading", "mode"),
    [
        (HOPS_NONE, 1, 40.0, "on"),  # a Queued robot of its own remnant, waiting
        (3, 1, 40.0, "on"),  # one that counts its hops to the shape
        (HOPS_PARKED, 0, 40.0, "on"),  # the first formation's Queued robots send 0 too
        (HOPS_PARKED, 2, 40.0, "on"),  # parked by a newer election than robot 0's
        (HOPS_PARKED, 1, 80.0, "on"),  # parked, but not beside it
        (HOPS_PARKED, 1, 40.0, "off"),
    ],
)
def test_no_election_beside_other_queued_robots(hops: int, epoch: int, reading: float,
                                                mode: str) -> None:
    world = beside_a_queued_robot(hops, epoch, reading, mode)
    assert not elects_after(*world, 2 * MERGE_AFTER_TICKS)


def test_two_remnants_grown_into_each_other_regrow_as_one() -> None:
    # Traced (session 23): the removal leaves a dumbbell in remnants of 29 and 14 robots,
    # a gap apart while they elect; the larger one's target reaches into the smaller's
    # sites. Apart, neither re-forms in 4 h; merged, one shape of 42 re-forms.
    config = {"shape": "dumbbell", "seed": 19, "damage": ("remove random=0.3",),
              "max_time_s": 7200}
    apart = ETRun(
        RunConfig(**config, et=ETParams(merge_remnants="off", **{**SESSION_26_FORMATION,
                                        **SESSION_31_PLACEMENT})), sim_params=NATIVE_MATHS
    ).run()
    assert not any(c["formed"] for c in apart["components"] if c["robots"] >= 6)
    merged = ETRun(
        RunConfig(**config, et=ETParams(**{**SESSION_26_FORMATION, **SESSION_31_PLACEMENT})),
                   sim_params=NATIVE_MATHS
    ).run()
    counts = [e["count"] for e in merged["events"] if e["kind"] == "census"]
    assert counts[:2] == [29, 14] and counts[-1] == 42
    assert [c["formed"] and c["jaccard"] == 1.0 for c in merged["components"]] == [True]
    assert merged["duplicate_tags"] == []
    assert merged["max_leaders_per_component"] <= 1
