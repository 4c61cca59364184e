"""``still_readings``: a robot standing still keeps the mean of its readings of a still
neighbour; each reading carries its own N(0, 2 mm) noise."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.memory import NB_ID, NB_READINGS, NB_STATE
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State


def queued_reading_errors(still_readings: int) -> tuple[np.ndarray, np.ndarray]:
    """|distance kept - true distance| (mm) and readings averaged, over every pair of Queued
    robots that know each other after 200 s of a `T` formation (seed 1)."""
    config = RunConfig(
        shape="T", seed=1, max_time_s=200, et=ETParams(still_readings=still_readings)
    )
    run = ETRun(config)
    run.run()
    ctl = run.controller
    pos = run.world.pos
    queued = ctl.states == State.QUEUED
    errors, counts = [], []
    for i in np.flatnonzero(queued):
        for slot in range(ctl.nb.shape[1]):
            j = ctl.nb[i, slot, NB_ID]
            if j < 0 or not queued[j] or ctl.nb[i, slot, NB_STATE] != State.QUEUED:
                continue
            errors.append(abs(ctl.nb_dist[i, slot] - np.hypot(*(pos[i] - pos[j]))))
            counts.append(ctl.nb[i, slot, NB_READINGS])
    return np.array(errors), np.array(counts)


def test_still_robots_average_their_readings() -> None:
    single, single_counts = queued_reading_errors(1)
    mean, mean_counts = queued_reading_errors(8)
    assert len(single) > 50 and len(mean) > 50
    assert single_counts.max() == 1
    assert np.median(mean_counts) == 8  # Queued robots in the queue stand still for long
    # N(0, 2 mm): the mean absolute error of one reading is 1.6 mm, of a mean of 8, 0.56.
    assert 1.2 < single.mean() < 2.0
    assert mean.mean() < 0.8
