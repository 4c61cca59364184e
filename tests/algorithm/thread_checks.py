"""Checks shared by the tests that run the ET controller's parts on threads."""

from __future__ import annotations

import hashlib

import numpy as np

from etswarm.algorithm.run import ETRun
from etswarm.algorithm.states import PLACED_STATES, State


def final_state(run: ETRun) -> str:
    """Hash of the world's poses, the robots' outputs and counters, and every robot's
    memory."""
    digest = hashlib.sha256()
    ctl = run.controller
    for arr in (run.world.pos, run.world.heading, run.world.motor, run.world.led,
                run.world.counters, ctl.ri, ctl.nb, ctl.nb_dist, ctl.walk_seen, ctl.held):
        digest.update(np.ascontiguousarray(arr).tobytes())
    return digest.hexdigest()


def assert_forming(run: ETRun) -> None:
    """The run did something: robots left the repository and search round the seeds, and
    some took sites."""
    states = run.controller.states
    assert np.count_nonzero(states == State.SEARCH) >= 5
    assert np.count_nonzero(np.isin(states, [int(s) for s in PLACED_STATES])) >= 3
