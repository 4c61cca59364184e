"""The measures count a site as held only by a robot that stands on it
(``ETController.holds_site``): an election's flood pulls searchers into Danger too, and a
searcher's tag fields hold its last candidate, not a site. Seen on `T` `kill random=0.1`
seed 0: a run that ended during a false alarm reported Jaccard 1 with a site still free."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import R_HAS_TAG, R_STATE, R_TAG_X, R_TAG_Y
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.shapes.shape import load_shape


@pytest.fixture(scope="module")
def formed_triangle() -> ETRun:
    """A triangle formed with one robot to spare, which stays Queued."""
    cells = load_shape("triangle").n_cells
    run = ETRun(RunConfig(shape="triangle", seed=0, robots=cells + 1, max_time_s=3 * 3600))
    summary = run.run()
    assert summary["formed"] and summary["jaccard"] == 1.0
    return run


def pulled_into_an_election(run: ETRun, had_site: bool) -> dict:
    """The spare robot, in Danger with a Stable robot's tag in its tag fields; with
    ``had_site`` it says it held that site (a second robot on one tag). Returns the
    summary; the robot's memory is restored afterwards."""
    ri = run.controller.ri
    spare = int(np.flatnonzero(ri[:, R_STATE] == State.QUEUED)[0])
    stable = int(np.flatnonzero(ri[:, R_STATE] == State.STABLE)[0])
    saved = ri[spare].copy()
    # put it where the group hears it, beside the Stable robot
    pos = run.world.pos[spare].copy()
    run.world.pos[spare] = run.world.pos[stable] + np.array([0.0, 35.0])
    try:
        ri[spare, R_STATE] = State.DANGER
        ri[spare, R_TAG_X] = ri[stable, R_TAG_X]
        ri[spare, R_TAG_Y] = ri[stable, R_TAG_Y]
        ri[spare, R_HAS_TAG] = 1 if had_site else 0
        assert bool(run.controller.holds_site[spare]) == had_site
        return run.summary()
    finally:
        ri[spare] = saved
        run.world.pos[spare] = pos


def test_a_searcher_in_danger_holds_no_site(formed_triangle: ETRun) -> None:
    summary = pulled_into_an_election(formed_triangle, had_site=False)
    assert summary["duplicate_tags"] == []
    assert summary["jaccard"] == 1.0


def test_a_placed_robot_in_danger_still_holds_its_site(formed_triangle: ETRun) -> None:
    # the same robot, had it held the site, shares a tag: the measures see it
    summary = pulled_into_an_election(formed_triangle, had_site=True)
    assert len(summary["duplicate_tags"]) == 1


def test_every_working_robot_holds_its_site(formed_triangle: ETRun) -> None:
    ri = formed_triangle.controller.ri
    working = (ri[:, R_STATE] >= State.INACTIVE) & (ri[:, R_STATE] <= State.STABLE)
    assert working.sum() > 0
    assert np.array_equal(formed_triangle.controller.holds_site, working)
