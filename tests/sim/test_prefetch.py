"""The prefetch hint changes no value and tolerates any index."""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.sim.prefetch import prefetch


@njit(cache=True)
def sum_with_hints(a, idx, rows):
    """Sum a[idx] while hinting elements ahead, out of range and rows of a 2-D array."""
    total = 0.0
    for k in range(idx.shape[0]):
        prefetch(a, idx[k] + 1_000_000)  # far out of range: must not fault
        prefetch(a, -5)
        prefetch(rows, k)
        total += a[idx[k]]
    return total


def test_prefetch_is_only_a_hint() -> None:
    rng = np.random.default_rng(0)
    a = rng.random(1000)
    idx = rng.integers(0, 1000, 5000)
    rows = np.zeros((64, 9), dtype=np.uint8)
    assert sum_with_hints(a, idx, rows) == sum(float(a[i]) for i in idx)
    assert not rows.any()
