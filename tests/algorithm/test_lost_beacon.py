"""A lost searcher follows a searcher that still hears the group.

Found on `E` seed 0 and `H` seed 3 (queue layout): searchers orbiting the far end of the
repository lost it when its last Queued robots left, and their widening spiral never
caught up with the end of the queue, which moves towards the shape one robot per
release. A searcher tells in its status message whether it hears a stationary robot.
"""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.controller import encode
from etswarm.algorithm.kernel_util import FORWARD, RIGHT, SEARCH, STOP
from etswarm.algorithm.memory import (
    NB_ANCHORED,
    NB_ID,
    NB_LAST,
    NB_STATE,
    R_LOST_SINCE,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.search import begin_search, lost_motion, search_rule

TICK = 100_000
#: Lost this long: the spiral drives forward most of the time (the fixed spiral of
#: commands, ``lost_homing`` off, which these tests compare with).
LOST_FOR = 31 * 2000


def steer_lost(anchored: int, beacon: str = "on", me: int = 0, other: int = 5,
               dist_mm: float = 55.0, lost_yield: str = "on") -> int:
    """Motor command of searcher ``me``, lost for ``LOST_FOR`` ticks, hearing only searcher
    ``other`` at ``dist_mm`` (anchored or not), with the ``lost_beacon`` option ``beacon``
    and the ``lost_yield`` option ``lost_yield``."""
    ri, nb, nb_dist = allocate(max(me, other) + 1)
    begin_search(me, TICK - LOST_FOR - 10, ri)
    ri[me, R_LOST_SINCE] = TICK - LOST_FOR + 1
    nb[me, 0, NB_ID] = other
    nb[me, 0, NB_STATE] = SEARCH
    nb[me, 0, NB_LAST] = TICK
    nb[me, 0, NB_ANCHORED] = anchored
    nb_dist[me, 0] = dist_mm
    gene = np.ones((3, 3), dtype=np.uint8)
    gene_nn = np.full((3, 3), 6, dtype=np.int8)
    ci, cf = ETParams(lost_beacon=beacon, lost_yield=lost_yield, lost_homing="off").pack(
        31, gene_x0=-1, gene_y0=-1
    )
    motor = np.full(ri.shape[0], FORWARD, dtype=np.uint8)
    held = np.zeros((ri.shape[0], 1, 1), dtype=np.uint8)
    search_rule(me, TICK, True, ri, nb, nb_dist, motor, gene, gene_nn, ci, cf, held, 0, 0)
    return int(motor[me])


def test_a_lost_searcher_turns_towards_a_searcher_that_hears_the_group() -> None:
    spiral = int(lost_motion(TICK, TICK - LOST_FOR))
    assert spiral == FORWARD  # what it would do on its own at this tick
    assert steer_lost(anchored=0) == spiral  # another lost searcher is no guide
    assert steer_lost(anchored=1) == RIGHT  # clockwise orbit: the group on its right
    assert steer_lost(anchored=1, beacon="off") == spiral  # the option off: the spiral only


def test_a_searcher_says_whether_it_hears_a_stationary_robot() -> None:
    ri, _, _ = allocate(1)
    begin_search(0, 0, ri)
    out_on = np.zeros(1, dtype=np.bool_)
    out_type = np.zeros(1, dtype=np.uint8)
    out_data = np.zeros((1, 9), dtype=np.uint8)
    encode(0, 10, ri, 0, out_on, out_type, out_data)
    assert out_data[0, 6] == 1
    ri[0, R_LOST_SINCE] = 5
    encode(0, 10, ri, 0, out_on, out_type, out_data)
    assert out_data[0, 6] == 0


def test_a_lost_searcher_need_not_yield() -> None:
    # Traced on T seed 1 (settle retries and release hold on): four searchers pushed off
    # the end of the crossbar lost the group and parked beside each other, each yielding
    # to a lower ID, and drifted 0.5 m away as a clump for 25 min.
    # Searcher 6, lost, hears only searcher 2 (a lower ID) at 45 mm.
    assert steer_lost(0, me=6, other=2, dist_mm=45.0, lost_yield="on") == STOP
    spiral = int(lost_motion(TICK, TICK - LOST_FOR))
    assert steer_lost(0, me=6, other=2, dist_mm=45.0, lost_yield="off") == spiral
