"""A searcher that keeps steering by the same few robots turns round.

Found on ``T`` ``kill random=0.1`` seed 1: after the regeneration a searcher circled for
2.5 h in the fold between the shape and four Queued robots, steering by two or three of
them in turn; the Queued robots never left because they kept hearing it.
"""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.memory import NB_ID, R_ORBIT, R_REF_ID, RECENT_REFS, allocate
from etswarm.algorithm.search import TRAPPED_TICKS, begin_search, follow_reference


def steer(references: list[int], moving: bool = True) -> np.ndarray:
    """Robot 0 steers by ``references[t]`` at tick t (as ``search_rule`` does); returns
    its orbit direction after each tick, shape (len(references),)."""
    ri, nb, _ = allocate(1)
    begin_search(0, 0, ri)
    orbit = np.zeros(len(references), dtype=np.int64)
    for tick, ref in enumerate(references):
        nb[0, 0, NB_ID] = ref
        follow_reference(0, ri, nb, 0, moving, 0)
        ri[0, R_REF_ID] = ref  # track_trend keeps the current reference here
        orbit[tick] = ri[0, R_ORBIT]
    return orbit


def test_a_searcher_among_the_same_few_robots_turns_round_once_per_period() -> None:
    # Three robots in turn, 200 ticks each: the last new one (12) comes at tick 400.
    few = [10 + (t // 200) % 3 for t in range(3 * TRAPPED_TICKS)]
    turns = np.flatnonzero(np.diff(steer(few))) + 1  # ticks at which the orbit changed
    assert turns[0] == 400 + TRAPPED_TICKS - 1
    assert len(turns) >= 2 and np.diff(turns).min() >= TRAPPED_TICKS


def test_a_searcher_passing_new_robots_keeps_its_direction() -> None:
    # A new reference every 300 ticks, with returns to the previous ones in between.
    refs = [100 + t // 300 - (t // 100) % 2 for t in range(3 * TRAPPED_TICKS)]
    assert not steer(refs).any()
    # ... and the list of recent references is as long as a ring round a few robots.
    assert RECENT_REFS >= 3


def test_standing_still_is_not_being_trapped() -> None:
    assert not steer([7] * (2 * TRAPPED_TICKS), moving=False).any()
