"""An Inactive robot beside a stalled front turns Active after a while
(``ETParams.inactive_wait_s``, ``regrowth_inactive_wait_s``).

An Inactive robot waits while it hears an Active neighbour: growth follows the front. A
front can stall for good at a site no searcher can take. Traced on dumbbell ``split x=mid``
seed 21 (session 24): in the 31-robot remnant, site (1, -2) was pinched. Robot 39 stood
28 mm from its centre, so robots 28 and 25 beside it stayed Active. Robots 33 and 56 heard
them and stayed Inactive for the last 2.3 h of the run. No searcher may take a site whose
placed neighbours are all Inactive, so 13 sites of the target stayed free while 13
searchers went round the remnant.
"""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.kernel_util import ACTIVE, DIR_X, DIR_Y, INACTIVE, set_state
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TS,
    NB_TX,
    NB_TY,
    R_EPOCH,
    R_NN,
    R_STATE,
    R_TS,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.placed import placed_rule
from etswarm.algorithm.run import ETRun, RunConfig

TPS = 31


def inactive_beside_a_stalled_front(epoch: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Robot 0 Inactive at (0, 0) of target ``epoch`` (NN 6), hearing one neighbour: an
    Active robot at (0, 1) that never turns Stable."""
    ri, nb, nb_dist = allocate(2)
    set_state(0, ri, INACTIVE, 0)
    ri[0, R_NN] = 6
    ri[0, R_TS] = 3
    ri[0, R_EPOCH] = epoch
    nb[0, 0, NB_ID] = 1
    nb[0, 0, NB_STATE] = ACTIVE
    nb[0, 0, NB_TS] = 2
    nb[0, 0, NB_TX] = DIR_X[0]
    nb[0, 0, NB_TY] = DIR_Y[0]
    nb[0, 0, NB_EPOCH] = epoch
    nb_dist[0, 0] = 40.0
    return ri, nb, nb_dist


def seconds_inactive(et: ETParams, epoch: int, limit_s: float = 3600.0) -> float:
    """Simulated seconds robot 0 stays Inactive (``limit_s`` if it never leaves)."""
    ri, nb, nb_dist = inactive_beside_a_stalled_front(epoch)
    ci, cf = et.pack(TPS, gene_x0=-2, gene_y0=-2)
    for tick in range(1, int(limit_s * TPS), 4):  # every evaluation (eval_every_ticks)
        nb[0, 0, NB_LAST] = tick
        placed_rule(0, tick, ri, nb, nb_dist, ci, cf)
        if ri[0, R_STATE] != INACTIVE:
            assert ri[0, R_STATE] == ACTIVE
            return tick / TPS
    return limit_s


def test_by_default_it_waits_for_good_as_in_the_paper() -> None:
    assert seconds_inactive(ETParams(), epoch=0) == 3600.0
    assert seconds_inactive(ETParams(), epoch=1) == 3600.0


def test_with_a_wait_it_turns_active_after_that_long() -> None:
    et = ETParams(regrowth_inactive_wait_s=900.0)
    assert 900.0 <= seconds_inactive(et, epoch=1) < 901.0
    assert seconds_inactive(et, epoch=0) == 3600.0  # not in the first formation
    et = ETParams(inactive_wait_s=600.0)
    assert 600.0 <= seconds_inactive(et, epoch=0) < 601.0
    assert seconds_inactive(et, epoch=1) == 3600.0


def test_the_wait_starts_again_whenever_it_becomes_inactive() -> None:
    ri, nb, nb_dist = inactive_beside_a_stalled_front(epoch=1)
    ci, cf = ETParams(regrowth_inactive_wait_s=100.0).pack(TPS, gene_x0=-2, gene_y0=-2)
    for tick in range(1, 90 * TPS):
        nb[0, 0, NB_LAST] = tick
        placed_rule(0, tick, ri, nb, nb_dist, ci, cf)
    set_state(0, ri, INACTIVE, 90 * TPS)  # placed anew (a new target, say)
    for tick in range(90 * TPS, 150 * TPS):
        nb[0, 0, NB_LAST] = tick
        placed_rule(0, tick, ri, nb, nb_dist, ci, cf)
    assert ri[0, R_STATE] == INACTIVE  # 60 s since it became Inactive again, not 150


def test_a_remnant_stalled_behind_a_pinched_site_regrows() -> None:
    # Without the wait the 31-robot remnant ends the 4 h run with 13 of its 31 sites free.
    et = ETParams(regrowth_inactive_wait_s=900.0)
    run = ETRun(RunConfig(shape="dumbbell", seed=21, damage=("split x=mid",),
                          max_time_s=4 * 3600, et=et))
    summary = run.run()
    groups = summary["components"]
    assert sorted(g["robots"] for g in groups) == [30, 31]
    for group in groups:
        assert group["formed"] and group["jaccard"] == 1.0
        assert group["census_count"] == group["robots"] == group["target_cells"]
    assert summary["duplicate_tags"] == []
    assert summary["max_leaders_per_component"] <= 1
