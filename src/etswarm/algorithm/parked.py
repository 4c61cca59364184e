"""Robots parked by a regeneration: the remnant they counted was too small to grow.

A remnant of fewer than three robots, or one whose scaled shape keeps no two of them on
neighbouring sites, gets an empty target (``ETRun._scaled_placement``): its robots wait
Queued where the damage left them, for good, and send ``HOPS_PARKED`` as their hop count
(``release.queued_rule``). Robots of the other remnants can tell them from this: the
first formation's Queued robots send 0 hops too, but at epoch 0, and after a regeneration
every other Queued robot counts at least 1.
"""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import QUEUED
from etswarm.algorithm.memory import NB_EPOCH, NB_HOPS, NB_STATE

#: Hop count sent after a regeneration by a Queued robot whose target is empty (its
#: remnant was too small to seed a shape): it never leaves, and the Queued robots that
#: hear it, of a neighbouring remnant, leave it out of their release (a real count is at
#: least 1).
HOPS_PARKED = 0


@njit(inline="always")
def parked(i, m, nb):  # type: ignore[no-untyped-def]
    """Row m of robot i's table is a Queued robot parked by a regeneration."""
    return (
        nb[i, m, NB_STATE] == QUEUED
        and nb[i, m, NB_HOPS] == HOPS_PARKED
        and nb[i, m, NB_EPOCH] >= 1
    )
