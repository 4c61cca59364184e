"""The radio's sender groups: every robot with a valid phase once, in index order."""

from __future__ import annotations

import numpy as np

from etswarm.sim.radio import senders_by_phase


def test_senders_by_phase_groups_robots_in_index_order() -> None:
    rng = np.random.default_rng(3)
    period = 15
    tx_phase = rng.integers(0, period, 500)
    tx_phase[[7, 99]] = [-1, period]  # outside [0, period): never send
    order, first = senders_by_phase(tx_phase, period)
    assert first[0] == 0 and first[period] == 498
    for s in range(period):
        group = order[first[s]:first[s + 1]]
        assert np.array_equal(group, np.flatnonzero(tx_phase == s))
