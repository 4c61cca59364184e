"""A searcher at the dead end of a broken repository leaps the gap (``repository_gap``).

Traced on starfish seeds 229 and 238: searchers shoved the first formation's queue apart,
and the robots beyond the gap went round their piece of the queue for hours, out of
radio range of the shape.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.homing import ODO_PER_MM
from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_QRANK,
    NB_STATE,
    R_GAP_PHASE,
    R_GAP_SINCE,
    R_GAP_TOP,
    R_GROWTH,
    R_HOME_X,
    R_HOME_Y,
    R_ODO_X,
    R_ODO_Y,
    allocate,
)
from etswarm.algorithm.params import C_TICKS_GAP, ETParams
from etswarm.algorithm.repository_gap import (
    LEAP_AHEAD_MM,
    PHASE_CLIMB,
    PHASE_LEAP,
    PHASE_LOW,
    RANK_STEP,
    leaping,
    left_behind,
    note_walk,
    start_walk,
)
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State

TICKS_PER_S = 31
#: Queue spacing of the walk below (mm along x per robot followed).
STEP_MM = 45.0


def constants(**options: float) -> np.ndarray:
    """The packed integer constants for ``ETParams(**options)``."""
    ci, _ = ETParams(**options).pack(TICKS_PER_S, 0, 0)
    return ci


class Walker:
    """Searcher 0 following Queued robots (table row 0) or a placed one (row 1)."""

    def __init__(self, **options: float) -> None:
        self.ri, self.nb, _ = allocate(2)
        self.ci = constants(**options)
        self.tick = 0
        start_walk(0, self.tick, self.ri)

    def follow(self, rank: int, x_mm: float) -> None:
        """One tick later it stands at (``x_mm``, 0) and reads a Queued robot of ``rank``."""
        self.tick += TICKS_PER_S
        self.ri[0, R_ODO_X] = round(x_mm * ODO_PER_MM)
        self.ri[0, R_ODO_Y] = 0
        self.nb[0, 0, NB_ID] = 1
        self.nb[0, 0, NB_STATE] = State.QUEUED
        self.nb[0, 0, NB_QRANK] = rank
        self.nb[0, 0, NB_LAST] = self.tick
        note_walk(0, self.tick, -1, 0, self.ri, self.nb, self.ci)

    def hear_placed(self) -> None:
        self.tick += TICKS_PER_S
        note_walk(0, self.tick, 1, -1, self.ri, self.nb, self.ci)

    def hear_nothing(self, seconds: float) -> None:
        self.tick += round(seconds * TICKS_PER_S)
        note_walk(0, self.tick, -1, -1, self.ri, self.nb, self.ci)

    def walk_round_dead_end(self, wait_s: float, top: int = 20) -> None:
        """Up the queue from rank 10 to ``top`` (x grows), round its end and back down,
        starting ``wait_s`` after the walk began."""
        self.tick += round(wait_s * TICKS_PER_S)
        for rank in range(10, top + 1):
            self.follow(rank, STEP_MM * rank)
        for rank in range(top, top - RANK_STEP - 1, -1):
            self.follow(rank, STEP_MM * rank)

    @property
    def phase(self) -> int:
        return int(self.ri[0, R_GAP_PHASE])


def test_a_walk_round_the_queue_end_long_after_the_shape_was_heard_is_a_dead_end() -> None:
    walker = Walker()
    walker.walk_round_dead_end(wait_s=400)
    assert walker.phase == PHASE_LEAP
    assert leaping(0, walker.ri)
    assert walker.ri[0, R_GAP_TOP] == 20
    # It heads for a point beyond the top of the climb, along the queue's line.
    assert walker.ri[0, R_HOME_X] / ODO_PER_MM == pytest.approx(20 * STEP_MM + LEAP_AHEAD_MM)
    assert walker.ri[0, R_HOME_Y] == 0


def test_a_walk_round_soon_after_the_shape_starts_a_new_climb_instead() -> None:
    walker = Walker()
    walker.walk_round_dead_end(wait_s=0)
    assert walker.phase == PHASE_LOW


def test_ranks_that_only_fall_are_a_walk_from_the_shape_to_the_queue_tail() -> None:
    walker = Walker()
    walker.tick += 3600 * TICKS_PER_S
    for rank in range(80, 10, -1):
        walker.follow(rank, STEP_MM * (100 - rank))
    assert walker.phase == PHASE_LOW


def test_small_rank_jitter_is_no_dead_end() -> None:
    walker = Walker()
    walker.tick += 3600 * TICKS_PER_S
    for rank in (10, 11, 12, 13, 14, 15, 13, 14, 12, 16, 17, 15):
        walker.follow(rank, STEP_MM * rank)
    assert walker.phase == PHASE_CLIMB


def test_hearing_a_placed_robot_starts_the_walk_afresh() -> None:
    walker = Walker()
    walker.tick += 3600 * TICKS_PER_S
    for rank in range(10, 21):
        walker.follow(rank, STEP_MM * rank)
    walker.hear_placed()
    assert walker.phase == PHASE_LOW
    assert walker.ri[0, R_GAP_SINCE] == walker.tick
    for rank in range(20, 14, -1):
        walker.follow(rank, STEP_MM * rank)
    assert walker.phase == PHASE_LOW


def test_the_queue_beyond_the_gap_ends_the_leap_and_the_walk_goes_on() -> None:
    walker = Walker()
    walker.walk_round_dead_end(wait_s=400)
    since = walker.ri[0, R_GAP_SINCE]
    # Its piece's robots are left behind; one of higher rank is the piece beyond.
    walker.nb[0, 0, NB_STATE] = State.QUEUED
    walker.nb[0, 0, NB_QRANK] = 20
    assert left_behind(0, 0, walker.ri, walker.nb)
    walker.nb[0, 0, NB_QRANK] = 21
    assert not left_behind(0, 0, walker.ri, walker.nb)
    walker.follow(25, 30 * STEP_MM)
    assert walker.phase == PHASE_LOW
    assert walker.ri[0, R_GAP_SINCE] == since  # still no placed robot heard since then


def test_a_leap_that_finds_nothing_ends() -> None:
    walker = Walker(gap_leap_s=600)
    walker.walk_round_dead_end(wait_s=400)
    walker.hear_nothing(599)
    assert walker.phase == PHASE_LEAP
    walker.hear_nothing(2)
    assert walker.phase == PHASE_LOW
    assert walker.ri[0, R_GAP_SINCE] == walker.tick  # it waits afresh before another leap


def test_off_and_after_a_regeneration_nothing_changes() -> None:
    walker = Walker(repository_gap_s=0)
    walker.walk_round_dead_end(wait_s=400)
    assert walker.phase == PHASE_LOW
    walker = Walker()
    walker.ri[0, R_GROWTH] = 1  # working for a regenerated target
    walker.walk_round_dead_end(wait_s=400)
    assert walker.phase == PHASE_LOW


def cut_queue_run(gap_s: float, seed: int, shape: str = "hexagon") -> ETRun:
    """A first formation whose queue is cut after 60 s: all but the five Queued robots
    nearest the shape are carried 250 mm farther along the queue's line, out of radio
    range of the rest."""
    run = ETRun(RunConfig(shape=shape, seed=seed, max_time_s=3 * 3600.0,
                          et=ETParams(repository_gap_s=gap_s)))
    run.advance(60 * run.ticks_per_s)
    pos = run.world.pos
    states = run.controller.states
    queued = np.nonzero(states == State.QUEUED)[0]
    far = queued[queued < np.sort(queued)[-5]]
    line = pos[queued.min()] - pos[queued.max()]
    pos[far] += 250.0 * line / np.hypot(*line)
    return run


@pytest.mark.parametrize("seed", [0, 1])
def test_robots_beyond_a_cut_in_the_queue_leap_it_and_the_shape_forms(seed: int) -> None:
    run = cut_queue_run(300.0, seed)
    summary = run.run()
    assert summary["formed"]
    assert summary["jaccard"] == 1.0
    assert summary["duplicate_tags"] == []


def test_without_the_leap_the_robots_beyond_the_cut_never_arrive() -> None:
    run = cut_queue_run(0.0, 0)
    summary = run.run()
    assert not summary["formed"]


def test_an_unbroken_queue_never_leaps() -> None:
    """`T`'s queue does not break: its runs end the same with the rule as without."""
    ends = []
    for gap_s in (0.0, 300.0):
        run = ETRun(RunConfig(shape="T", seed=0, et=ETParams(repository_gap_s=gap_s)))
        summary = run.run()
        assert summary["formed"]
        ends.append((run.world.pos.copy(), summary["formation_time_s"]))
    assert np.array_equal(ends[0][0], ends[1][0])
    assert ends[0][1] == ends[1][1]


def test_only_a_queue_has_a_line_to_leap_along() -> None:
    """In a packed cluster the ranks climb and fall all round it: the rule is off there."""
    ticks = {}
    for layout in ("queue", "cluster"):
        run = ETRun(RunConfig(shape="T", layout=layout))
        ticks[layout] = int(run.controller.ci[C_TICKS_GAP])
    assert ticks == {"queue": 300 * TICKS_PER_S, "cluster": 0}
