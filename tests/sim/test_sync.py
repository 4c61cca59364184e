"""The split loop's barrier that lets one chosen thread through (sim.sync.arrive_as)."""

from __future__ import annotations

import numba
import numpy as np
import pytest
from numba import njit, prange

from etswarm.sim.sync import arrive_as, release


@njit(parallel=True)
def _rounds(threads, rounds, chosen):  # type: ignore[no-untyped-def]
    """Every thread marks each round done, then meets the others at ``arrive_as``; the
    thread let through records who it was and how many rounds it saw done in all."""
    sync = np.zeros(2, dtype=np.int64)
    done = np.zeros(threads, dtype=np.int64)
    seen = np.zeros(rounds, dtype=np.int64)
    by = np.full(rounds, -1, dtype=np.int64)
    for p in prange(threads):
        for r in range(rounds):
            done[p] = r + 1
            if arrive_as(sync, threads, p == chosen):
                total = 0
                for q in range(threads):
                    total += done[q]
                seen[r] = total
                by[r] = p
                release(sync)
    return seen, by


@pytest.mark.skipif(numba.config.NUMBA_NUM_THREADS < 2, reason="needs two threads")
@pytest.mark.parametrize("chosen", [0, 1])
def test_only_the_chosen_thread_passes_and_only_after_everyone_arrived(chosen: int) -> None:
    rounds = 2000
    seen, by = _rounds(2, rounds, chosen)
    assert (by == chosen).all()
    # every thread had finished round r (and none had started round r + 1) when the
    # chosen one ran that round's one-thread work
    assert (seen == 2 * np.arange(1, rounds + 1)).all()


def test_one_thread_passes_at_once() -> None:
    seen, by = _rounds(1, 5, 0)
    assert (by == 0).all() and (seen == np.arange(1, 6)).all()
