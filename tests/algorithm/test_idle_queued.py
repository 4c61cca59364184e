"""Sleeping robots (``ETController.idle``): a Queued robot whose next evaluations could
change nothing sleeps until they could, and skips its rule meanwhile; a placed robot
sleeps till its next due tick (it is not visited while it hears nothing). That must give the
very bytes of a run where every robot evaluates at every due tick: here the reference run
wakes every robot before every tick (``idle`` zeroed), and the two runs' whole memory
and radio output are compared tick for tick. And the host's cheap measure check
(``ETRun._check``'s shortcut and lean report) must note what the full report would."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.controller import busy_robots
from etswarm.algorithm.release import NEVER
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State


def snapshot(run: ETRun) -> list[np.ndarray]:
    """Every array the controller writes, copied."""
    ctl, world = run.controller, run.world
    arrays = (ctl.ri, ctl.nb, ctl.nb_dist, ctl.held, ctl.walk_seen, world.out_on,
              world.out_type, world.out_data, world.motor, world.led, world.pos)
    return [np.array(a) for a in arrays]


@pytest.mark.parametrize(
    ("config", "ticks"),
    [
        (RunConfig(shape="T", seed=1, layout="cluster"), 6000),
        (RunConfig(shape="triangle", seed=2, damage=("remove random=0.3 at=300",)), 12400),
    ],
)
def test_sleeping_gives_the_bytes_of_evaluating_every_due_tick(
    config: RunConfig, ticks: int
) -> None:
    sleeping = ETRun(config)
    awake = ETRun(config)
    slept = 0
    placed_slept = 0
    for _ in range(ticks):
        awake.controller.idle[:] = 0  # wakes every robot: it evaluates at every due tick
        awake.advance(1)
        sleeping.advance(1)
        tick = sleeping.world.tick
        asleep = sleeping.controller.idle > tick
        slept += int(np.count_nonzero(asleep))
        placed_slept += int(np.count_nonzero(asleep & (sleeping.controller.states >= 2)))
        if tick % 31 == 0:
            for a, b in zip(snapshot(sleeping), snapshot(awake), strict=True):
                np.testing.assert_array_equal(a, b)
    assert sleeping.events == awake.events
    assert awake.world.tick == ticks
    # the robots did sleep (a good share of the Queued robot-ticks), and things happened
    queued = np.count_nonzero(sleeping.controller.states == State.QUEUED)
    assert slept > 0.2 * ticks * max(queued, 1)
    assert placed_slept > 0  # placed robots sleep till their next due tick
    assert np.count_nonzero(sleeping.controller.states != State.QUEUED) >= 3


def test_a_queued_robot_beyond_the_release_limit_sleeps_for_good() -> None:
    # 30 robots for a 15-cell triangle: 12 are released at most, the others stay Queued
    run = ETRun(RunConfig(shape="triangle", robots=30, seed=0, layout="cluster"))
    run.advance(31 * 1800)
    queued = run.controller.states == State.QUEUED
    assert queued.sum() >= 5
    # (a robot that heard something this tick is awake until its next due tick)
    assert np.count_nonzero(run.controller.idle[queued] > run.world.tick) >= queued.sum() // 2
    assert np.any(run.controller.idle[queued] == NEVER)


class CheckedRun(ETRun):
    """An ETRun that checks its cheap measure check against the full report."""

    checks = 0
    skipped = 0

    def _check(self) -> None:
        full = self.component_report()
        if not self._may_settle():
            CheckedRun.skipped += 1
            assert not any(c["formed"] or c["too_small"] for c in full)
        lean = self._check_report()
        keys = ("target_cells", "formed", "too_small", "slot")
        assert [{k: c[k] for k in keys} for c in full] == lean
        CheckedRun.checks += 1
        super()._check()


def test_the_cheap_measure_check_notes_what_the_full_report_would() -> None:
    run = CheckedRun(RunConfig(shape="triangle", seed=1, max_time_s=2400,
                               damage=("split x=0",)))
    summary = run.run()
    kinds = [e["kind"] for e in summary["events"]]
    assert "formed" in kinds and "reformed" in kinds
    assert summary["settled"]
    assert CheckedRun.skipped > 0 and CheckedRun.checks > CheckedRun.skipped


@pytest.mark.parametrize(("lo", "hi"), [(0, 200), (37, 151), (5, 5)])
def test_busy_robots_lists_the_alive_robots_awake_with_messages_or_moving(lo: int, hi: int) -> None:
    """``controller.busy_robots`` (the robots ``et_part`` visits) lists, in index order,
    the alive robots of its range that are awake at the tick, heard something or moved."""
    rng = np.random.default_rng(3)
    n, tick = 200, 1000
    alive = rng.random(n) < 0.9
    in_count = np.where(rng.random(n) < 0.3, rng.integers(1, 4, n), 0).astype(np.int32)
    idle = np.where(rng.random(n) < 0.8, rng.integers(990, 1010, n), 0).astype(np.int64)
    motor = np.where(rng.random(n) < 0.1, rng.integers(1, 4, n), 0).astype(np.int8)
    busy, count = busy_robots(lo, hi, tick, alive, in_count, idle, motor)
    want = lo + np.flatnonzero(
        alive[lo:hi] & ((in_count[lo:hi] > 0) | (idle[lo:hi] <= tick) | (motor[lo:hi] != 0))
    )
    assert count == len(want)
    assert busy[:count].tolist() == want.tolist()
