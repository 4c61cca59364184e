"""An Active robot defers to a lower-TS Active neighbour (Quasi) for ``quasi_patience_s``
at most, then stays Active beside it.

Robot 0 is Active on (0, 0) with TS 5 and six neighbour sites; it hears a Stable robot in
direction 1 and, in direction 0, an Active robot of TS 2 that never turns Stable (it waits
for a site no searcher reaches). The paper's rule keeps robot 0 Quasi for all but one
evaluation in every ``quasi_s``, so a searcher almost never hears it Active and never takes
the free sites beside it.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.kernel_util import ACTIVE, DIR_X, DIR_Y, QUASI, STABLE
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TS,
    NB_TX,
    NB_TY,
    R_NN,
    R_STATE,
    R_TS,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.placed import placed_rule
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.errors import EtswarmError

TPS = 31
GENE = np.ones((5, 5), dtype=np.uint8)  # tags -2 .. 2 (grid origin (-2, -2))
NO_MEMORY = np.zeros((5, 5), dtype=np.uint8)
LOWER_SLOT = 0  # the Active neighbour of lower TS, direction 0
STABLE_SLOT = 1  # a Stable neighbour, direction 1


def active_robot() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Robot 0 as described above; returns (ri, nb, nb_dist)."""
    ri, nb, nb_dist = allocate(4)
    ri[0, R_STATE] = ACTIVE
    ri[0, R_NN] = 6
    ri[0, R_TS] = 5
    for slot, (k, state, ts) in enumerate([(0, ACTIVE, 2), (1, STABLE, 3)]):
        nb[0, slot, NB_ID] = 1 + slot
        nb[0, slot, NB_STATE] = state
        nb[0, slot, NB_TS] = ts
        nb[0, slot, NB_TX] = DIR_X[k]
        nb[0, slot, NB_TY] = DIR_Y[k]
        nb[0, slot, NB_EPOCH] = 0
        nb_dist[0, slot] = 40.0
    return ri, nb, nb_dist


def states_over(seconds: float, patience_s: float, lower_from: int = 0) -> np.ndarray:
    """Robot 0's state at every tick for ``seconds``; the lower-TS neighbour is heard
    from tick ``lower_from`` on (Stable before it)."""
    ri, nb, nb_dist = active_robot()
    ci, cf = ETParams(quasi_patience_s=patience_s).pack(TPS, gene_x0=-2, gene_y0=-2)
    states = np.zeros(round(seconds * TPS), dtype=np.int64)
    for tick in range(1, len(states) + 1):
        nb[0, LOWER_SLOT, NB_STATE] = ACTIVE if tick >= lower_from else STABLE
        nb[0, :2, NB_LAST] = tick
        placed_rule(0, tick, ri, nb, nb_dist, GENE, ci, cf, NO_MEMORY, -2, -2)
        states[tick - 1] = ri[0, R_STATE]
    return states


def test_the_papers_rule_keeps_it_quasi_for_good() -> None:
    states = states_over(1200, 0.0)
    last_minute = states[-60 * TPS:]
    assert (last_minute == QUASI).mean() > 0.9
    assert set(np.unique(states)) == {ACTIVE, QUASI}


def test_after_the_patience_it_stays_active() -> None:
    states = states_over(300, 60.0)
    assert (states[: 50 * TPS] == QUASI).mean() > 0.9  # it defers at first ...
    assert np.all(states[62 * TPS:] == ACTIVE)  # ... and stays Active after 60 s
    assert not np.any(states == STABLE)  # its free sites are still free


def test_the_patience_counts_from_when_a_lower_neighbour_is_heard() -> None:
    # Stable until 100 s: robot 0 has nothing to defer to, then defers for 60 s again.
    states = states_over(300, 60.0, lower_from=100 * TPS)
    assert np.all(states[: 100 * TPS - 1] == ACTIVE)
    assert (states[101 * TPS: 155 * TPS] == QUASI).mean() > 0.9
    assert np.all(states[162 * TPS:] == ACTIVE)


def test_the_option_is_checked() -> None:
    with pytest.raises(EtswarmError, match="quasi_patience_s"):
        ETParams(quasi_patience_s=-1.0)


def test_a_disc_stalled_by_quasi_robots_forms() -> None:
    """disc seed 213 (queue, loss 0.2): with the paper's rule it ended 4 h with three free
    sites beside Quasi robots whose lower-TS Active neighbour waited for a pinched site;
    with 10 min of patience it forms, one robot per tag."""
    config = RunConfig(
        shape="disc", seed=213, max_time_s=4 * 3600, et=ETParams(quasi_patience_s=600.0)
    )
    summary = ETRun(config).run()
    assert summary["formed"] and summary["jaccard"] == 1.0
    assert summary["duplicate_tags"] == []
    assert summary["states"]["Stable"] == summary["robots"]
