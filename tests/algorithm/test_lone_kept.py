"""A robot kept through a regeneration with no kept neighbour site searches again
(``lone_kept_leave``, ``lone_kept.lone_in_new_target``).

Robot 0 holds (0, 0) and adopts a new target. It hears placed robots on some of its
neighbour sites; the new target's gene says which of those sites it still has.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, QUEUED, STABLE
from etswarm.algorithm.lone_kept import LONE_FRESH_S, lone_in_new_target
from etswarm.algorithm.memory import NB_ID, NB_LAST, NB_STATE, NB_TX, NB_TY, allocate
from etswarm.algorithm.params import ETParams

TICK = 10_000
TICKS_PER_S = 31
GENE_X0 = -3  # gene grid columns and rows hold tags -3 .. 3


def gene(sites: list[tuple[int, int]]) -> np.ndarray:
    """(7, 7) gene flags with the given tags set."""
    flags = np.zeros((7, 7), dtype=np.uint8)
    for x, y in sites:
        flags[x - GENE_X0, y - GENE_X0] = 1
    return flags


def kept_robot(held: list[tuple[tuple[int, int], int, int]]):  # type: ignore[no-untyped-def]
    """Robot 0 on (0, 0), hearing one robot per ``(tag, state, seconds ago)``."""
    ri, nb, _ = allocate(1)
    for slot, (tag, state, ago) in enumerate(held):
        nb[0, slot, NB_ID] = 1 + slot
        nb[0, slot, NB_STATE] = state
        nb[0, slot, NB_TX], nb[0, slot, NB_TY] = tag
        nb[0, slot, NB_LAST] = TICK - ago * TICKS_PER_S
    return ri, nb


def constants(mode: str = "on") -> np.ndarray:
    ci, _ = ETParams(lone_kept_leave=mode).pack(TICKS_PER_S, gene_x0=GENE_X0, gene_y0=GENE_X0)
    return ci


NEXT = (DIR_X[0], DIR_Y[0])


def test_a_robot_with_a_kept_neighbour_keeps_its_site() -> None:
    ri, nb = kept_robot([(NEXT, STABLE, 1)])
    assert not lone_in_new_target(0, TICK, ri, nb, gene([(0, 0), NEXT]), constants())


def test_a_robot_whose_neighbours_the_new_target_leaves_out_is_lone() -> None:
    ri, nb = kept_robot([(NEXT, STABLE, 1), ((2, 0), STABLE, 1)])
    # (2, 0) is in the new target but two steps away: no neighbour of robot 0
    assert lone_in_new_target(0, TICK, ri, nb, gene([(0, 0), (2, 0)]), constants())
    assert not lone_in_new_target(0, TICK, ri, nb, gene([(0, 0), (2, 0)]), constants("off"))


@pytest.mark.parametrize(
    ("state", "ago"),
    [(QUEUED, 1), (STABLE, LONE_FRESH_S + 1)],  # no tag to hold; not heard lately (dead)
)
def test_only_placed_robots_heard_lately_count(state: int, ago: int) -> None:
    ri, nb = kept_robot([(NEXT, state, ago)])
    assert lone_in_new_target(0, TICK, ri, nb, gene([(0, 0), NEXT]), constants())


def test_a_robot_that_hears_nobody_is_lone() -> None:
    ri, nb = kept_robot([])
    assert lone_in_new_target(0, TICK, ri, nb, gene([(0, 0), NEXT]), constants())
