"""The split loop's ranges of robots per thread follow the measured work (sim.balance)."""

from __future__ import annotations

import numpy as np

from etswarm.sim.balance import (
    BAL_BOUNDS,
    balance_size,
    cost_index,
    ready_bounds,
    rebalance,
)


def bounds(bal: np.ndarray, parts: int) -> list[int]:
    return [int(b) for b in bal[BAL_BOUNDS:BAL_BOUNDS + parts + 1]]


def test_ready_bounds_split_evenly_and_keep_a_split_made_for_the_same_parts() -> None:
    bal = np.zeros(balance_size(4), dtype=np.int64)
    ready_bounds(bal, 3, 1000)
    assert bounds(bal, 3) == [0, 333, 666, 1000]
    bal[BAL_BOUNDS + 1] = 100
    ready_bounds(bal, 3, 1000)  # made for 3 parts of 1000 already: kept
    assert bounds(bal, 3)[1] == 100
    ready_bounds(bal, 2, 1000)  # a new thread count: even again
    assert bounds(bal, 2) == [0, 500, 1000]


def test_the_boundary_moves_towards_the_even_cost_point_and_settles_there() -> None:
    n = 1000
    # the work lies in the first 200 robots (searchers, say): 9 cycles each, 1 elsewhere
    work = np.ones(n)
    work[:200] = 9.0
    bal = np.zeros(balance_size(2), dtype=np.int64)
    ready_bounds(bal, 2, n)
    for _ in range(400):
        b = bounds(bal, 2)
        for p in range(2):
            bal[cost_index(2, p)] = int(work[b[p]:b[p + 1]].sum())
        rebalance(bal, 2)
    cut = bounds(bal, 2)[1]
    # half of the 2600 cycles lie before robot 144
    assert abs(cut - 144) <= 2
    assert bounds(bal, 2)[0] == 0 and bounds(bal, 2)[2] == n


def test_boundaries_stay_in_order_with_idle_parts() -> None:
    bal = np.zeros(balance_size(4), dtype=np.int64)
    ready_bounds(bal, 4, 100)
    for _ in range(50):
        for p in range(4):
            bal[cost_index(4, p)] = 1000 if p == 3 else 0
        rebalance(bal, 4)
        b = bounds(bal, 4)
        assert b == sorted(b) and b[0] == 0 and b[4] == 100
    assert bounds(bal, 4)[3] > 90  # the busy last part shrank


def test_a_fixed_cost_on_the_first_part_does_not_bias_the_split() -> None:
    """Thread 0 also runs the radio and the motion, and every robot's work varies from
    tick to tick: on average the two parts must still cost the same."""
    rng = np.random.default_rng(1)
    n = 1000
    mean_work = np.full(n, 25.0)
    mean_work[:240] = 400.0  # searchers and placed robots in the low IDs
    bal = np.zeros(balance_size(2), dtype=np.int64)
    ready_bounds(bal, 2, n)
    diffs = []
    for t in range(6000):
        cut = bounds(bal, 2)[1]
        work = mean_work * rng.exponential(1.0, n)
        costs = (30000.0 * rng.uniform(0.8, 1.2) + work[:cut].sum(), work[cut:].sum())
        for p in range(2):
            bal[cost_index(2, p)] = int(costs[p])
        rebalance(bal, 2)
        if t >= 1000:
            diffs.append(costs[0] - costs[1])
    # (pricing each move at the cost of the part it moves into left the first part
    # 5400 cycles dearer on average here, with a mean imbalance of 7600)
    assert abs(np.mean(diffs)) < 0.1 * np.mean(np.abs(diffs))
