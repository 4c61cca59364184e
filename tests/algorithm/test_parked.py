"""Robots parked by a regeneration (their remnant too small to grow) are obstacles to the
searchers of other remnants (``parked_obstacle``), and a placed robot beside one starts a
joint election (``merge_parked``, tested in ``test_merge``).

Traced on `T` `remove random=0.2` seed 14: the removal left robot 41 alone, 150 mm from
the 35-robot remnant; its census of 1 parked it. A searcher of the remnant edge-followed
robot 41 as if it were the repository for the last 2.7 h, and the remnant's last free
site stayed empty.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.kernel_util import FORWARD, QUEUED
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_HOPS,
    NB_ID,
    NB_LAST,
    NB_STATE,
    R_EPOCH,
    R_GROWTH,
    R_LOST_SINCE,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.parked import HOPS_PARKED, parked
from etswarm.algorithm.release import HOPS_NONE
from etswarm.algorithm.search import begin_search, search_rule

TICK = 100_000


def searcher_beside_a_queued_robot(hops: int, epoch: int, mode: str):  # type: ignore[no-untyped-def]
    """Searcher 0 of epoch 1 hearing only Queued robot 1 (``hops``, ``epoch``) 50 mm away:
    ``(ri, nb)`` after one evaluation of its search rule with ``parked_obstacle=mode``."""
    ri, nb, nb_dist = allocate(2)
    begin_search(0, TICK - 3100, ri)
    ri[0, R_EPOCH] = ri[0, R_GROWTH] = 1
    nb[0, 0, NB_ID] = 1
    nb[0, 0, NB_STATE] = QUEUED
    nb[0, 0, NB_EPOCH] = epoch
    nb[0, 0, NB_HOPS] = hops
    nb[0, 0, NB_LAST] = TICK
    nb_dist[0, 0] = 50.0
    gene = np.ones((3, 3), dtype=np.uint8)
    gene_nn = np.full((3, 3), 6, dtype=np.int8)
    ci, cf = ETParams(parked_obstacle=mode).pack(31, gene_x0=-1, gene_y0=-1)
    motor = np.full(2, FORWARD, dtype=np.uint8)
    held = np.zeros((2, 1, 1), dtype=np.uint8)
    search_rule(0, TICK, True, ri, nb, nb_dist, motor, gene, gene_nn, ci, cf, held, 0, 0)
    return ri, nb


def test_a_searcher_that_hears_only_a_parked_robot_is_lost() -> None:
    ri, nb = searcher_beside_a_queued_robot(HOPS_PARKED, 1, "on")
    assert parked(0, 0, nb)
    assert ri[0, R_LOST_SINCE] > 0  # it looks for its own group instead of orbiting


@pytest.mark.parametrize(
    ("hops", "epoch", "mode"),
    [
        (HOPS_PARKED, 1, "off"),  # the option off: it follows any Queued robot
        (HOPS_NONE, 1, "on"),  # a Queued robot of its remnant, waiting for release
        (HOPS_PARKED, 0, "on"),  # a Queued robot of the first formation (0 hops too)
    ],
)
def test_a_searcher_follows_other_queued_robots(hops: int, epoch: int, mode: str) -> None:
    ri, _ = searcher_beside_a_queued_robot(hops, epoch, mode)
    assert ri[0, R_LOST_SINCE] == 0
