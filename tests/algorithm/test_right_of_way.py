"""Right of way between searchers (``right_of_way``): a searcher keeps the clearance from
lower-ID searchers only, on hand-made neighbour tables; and a formation with it on."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import NB_ID, NB_LAST, NB_STATE, NB_TX, NB_TY, allocate
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.search import begin_search, search_rule
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError
from etswarm.sim.world import FORWARD, LEFT, RIGHT, STOP

TICK = 1000
#: Robot 5 searches; it hears the Stable robot 20 on tag (0, 0) at exactly d (40 mm).
SEARCHER = 5


def motor_with(other_id: int, other_mm: float, right_of_way: str) -> int:
    """The motor command searcher 5 gives while it orbits a placed robot at d and hears
    another searcher ``other_id`` at ``other_mm``."""
    gene = np.ones((5, 5), dtype=np.int64)  # tags -2..2: every site in the shape
    ci, cf = ETParams(right_of_way=right_of_way).pack(31, gene_x0=-2, gene_y0=-2)
    ri, nb, nb_dist = allocate(30)
    begin_search(SEARCHER, TICK - 600, ri)
    rows = [(20, State.STABLE, 40.0), (other_id, State.SEARCH, other_mm)]
    for slot, (sid, state, mm) in enumerate(rows):
        nb[SEARCHER, slot, NB_ID] = sid
        nb[SEARCHER, slot, NB_STATE] = state
        nb[SEARCHER, slot, NB_LAST] = TICK
        nb[SEARCHER, slot, NB_TX] = 0
        nb[SEARCHER, slot, NB_TY] = 0
        nb_dist[SEARCHER, slot] = mm
    motor = np.full(30, FORWARD, dtype=np.int64)
    held = np.zeros((30, 5, 5), dtype=np.uint8)
    search_rule(SEARCHER, TICK, False, ri, nb, nb_dist, motor, gene, gene, ci, cf, held, -2, -2)
    return int(motor[SEARCHER])


def test_a_higher_id_searcher_within_the_clearance_is_no_obstacle_with_right_of_way() -> None:
    # Off: it turns away from the searcher 30 mm off (clockwise orbit: away is left).
    assert motor_with(9, 30.0, "off") == LEFT
    # On: that searcher yields to it, so it steers by the placed robot as if alone.
    alone = motor_with(9, 500.0, "off")
    assert alone in (RIGHT, FORWARD)
    assert motor_with(9, 30.0, "on") == alone


def test_a_lower_id_searcher_is_yielded_to_either_way() -> None:
    assert motor_with(2, 34.0, "off") == STOP
    assert motor_with(2, 34.0, "on") == STOP


def test_the_option_is_checked() -> None:
    with pytest.raises(EtswarmError, match="right_of_way"):
        ETParams(right_of_way="yes")


@pytest.mark.parametrize("seed", [0, 1])
def test_a_t_forms_with_right_of_way(seed: int) -> None:
    run = ETRun(RunConfig(shape="T", seed=seed, max_time_s=3 * 3600.0,
                          et=ETParams(right_of_way="on")))
    summary = run.run()
    assert summary["formed"]
    assert summary["jaccard"] == 1.0
    assert summary["duplicate_tags"] == []
