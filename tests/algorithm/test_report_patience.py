"""A Stable robot waits longer for a neighbour it knew of only through reports.

Where the lattice has stretched, a Stable robot may count a neighbour whose holder stands
out of its range (101 mm on `T` seed 43), because the robots next to both report that
site held. When one such report drops, that is no damage; when a neighbour it heard
itself falls silent, it is.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, STABLE, direction_index
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_MASK,
    NB_STATE,
    NB_TX,
    NB_TY,
    PHASE_ELECTING,
    R_NN,
    R_PHASE,
    R_STATE,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.placed import REPORTED_PATIENCE, placed_rule

TPS = 31
#: Robot 0 at (0, 0) hears the holders of directions 0, 1, 2, 4 and 5; the holder of
#: direction 3 stands out of its range and is reported by the holder of direction 2.
HEARD = (0, 1, 2, 4, 5)
FAR_DIR = 3
REPORTER_DIR = 2
#: The gene's flags round (0, 0) (grid origin (-2, -2), as packed below): all sites.
GENE = np.ones((5, 5), dtype=np.uint8)
#: Robot 0's memory of held sites (empty; window origin as the gene's).
NO_MEMORY = np.zeros((5, 5), dtype=np.uint8)


def stable_robot() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Robot 0 Stable at tag (0, 0) with six neighbour sites; its table as above."""
    ri, nb, nb_dist = allocate(8)
    ri[0, R_STATE] = STABLE
    ri[0, R_NN] = 6
    for slot, k in enumerate(HEARD):
        nb[0, slot, NB_ID] = 1 + k
        nb[0, slot, NB_STATE] = STABLE
        nb[0, slot, NB_TX] = DIR_X[k]
        nb[0, slot, NB_TY] = DIR_Y[k]
        nb[0, slot, NB_EPOCH] = 0
        nb_dist[0, slot] = 40.0
    # the reporter marks the far site, seen from itself, as held
    far = (DIR_X[FAR_DIR] - DIR_X[REPORTER_DIR], DIR_Y[FAR_DIR] - DIR_Y[REPORTER_DIR])
    nb[0, HEARD.index(REPORTER_DIR), NB_MASK] = 1 << direction_index(*far)
    return ri, nb, nb_dist


def ticks_to_election(drop: str, patience: str) -> int:
    """Ticks from the loss until robot 0 starts an election: ``drop`` "report" (the
    reporter stops reporting the far site) or "heard" (the holder of direction 0 falls
    silent)."""
    ri, nb, nb_dist = stable_robot()
    ci, cf = ETParams(report_patience=patience).pack(TPS, gene_x0=-2, gene_y0=-2)
    silent_slot = HEARD.index(0)
    for tick in range(1, 40 * TPS):
        lost = tick > 2 * TPS
        for slot in range(len(HEARD)):
            if not (lost and drop == "heard" and slot == silent_slot):
                nb[0, slot, NB_LAST] = tick
        if lost and drop == "report":
            nb[0, HEARD.index(REPORTER_DIR), NB_MASK] = 0
        placed_rule(0, tick, ri, nb, nb_dist, GENE, ci, cf, NO_MEMORY, -2, -2)
        if ri[0, R_PHASE] == PHASE_ELECTING:
            return tick - 2 * TPS
    return -1


def test_the_count_includes_the_reported_neighbour() -> None:
    ri, nb, nb_dist = stable_robot()
    ci, cf = ETParams().pack(TPS, gene_x0=-2, gene_y0=-2)
    for slot in range(len(HEARD)):
        nb[0, slot, NB_LAST] = 1
    placed_rule(0, 1, ri, nb, nb_dist, GENE, ci, cf, NO_MEMORY, -2, -2)
    assert ri[0, R_STATE] == STABLE and ri[0, R_PHASE] != PHASE_ELECTING


@pytest.mark.parametrize("drop", ["report", "heard"])
def test_patience_for_reported_neighbours_only(drop: str) -> None:
    danger = ETParams().danger_timeout_s * TPS
    fresh = ETParams().neighbour_timeout_s * TPS
    with_patience = ticks_to_election(drop, "on")
    paper = ticks_to_election(drop, "off")
    assert 0 < paper <= danger + fresh + 8  # the paper's rule: one timeout either way
    if drop == "report":
        assert with_patience >= REPORTED_PATIENCE * danger
    else:
        assert with_patience == paper  # a neighbour it heard itself: damage, at once
