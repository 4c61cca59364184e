"""The remnant's extent, flooded while electing, so the Leader can lay the scaled shape
over the remnant.

The Leader places ``scale(bitmap, n)`` so that it holds the Leader's site and two of its
neighbours' (the new seeds). Among those placements it used to keep as many of the sites
it heard held as it could, which are only the sites round itself: a Leader on the edge of
its remnant (the lowest ID, often an old seed) then put most of the new shape beside the
remnant, and nearly every robot went back to the repository to grow it again from
scratch. Traced on starfish ``split y=mid`` seed 0: the 49-robot remnant kept 3 robots on
sites of its new target, and regrowth stalled with searchers lost round a repository of
46.

So, while electing, every robot keeps the least and greatest tag its remnant holds along
the lattice's three axes (X, Y and X - Y) as far as it has heard: its own tag if it has
one, merged with every extent message of its election it hears. It floods them in an
extent message (kind ``MSG_EXTENT``, every third period instead of its election message,
for ``EXTENT_RELAY_TICKS`` after its extent last grew): bytes 0-1 robot ID, 2-7 the least
and greatest X, Y and X - Y (int8 each); the epoch elected for is in the type byte. Least
and greatest merge in any order and any number of times, so loss and repeats do no harm
and the flood needs no tree. The Leader then picks the placement with the most cells in
that hexagon (host side, ``cells_in``), counting first the cells on sites it remembers
held there (its memory of held sites, ``site_memory``, passed on by gossip), which follow
the remnant's outline within the hexagon. Option ``ETParams.placement``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.algorithm.memory import (
    EXTENT_FIELDS,
    PHASE_ELECTING,
    R_EPOCH,
    R_EXT0,
    R_EXT_GREW,
    R_HAS_TAG,
    R_PHASE,
    R_TAG_X,
    R_TAG_Y,
)
from etswarm.algorithm.messages import EPOCH_SHIFT, MSG_EXTENT, get_i8
from etswarm.algorithm.params import C_EXTENT

#: A robot sends its extent for this long (ticks) after it last grew.
EXTENT_RELAY_TICKS = 31 * 30
#: It sends it in every this many transmit periods (the others carry the election).
EXTENT_EVERY_PERIODS = 3
#: Which of those periods (the silent sites use another, see ``silent``).
EXTENT_PERIOD = 1
#: Ticks per transmit period.
PERIOD_TICKS = 15
#: An extent that holds no tag yet: least above greatest.
EMPTY_LEAST = 127
EMPTY_GREATEST = -128
#: Long enough ago that the relay window is over: the robot does not send.
NEVER = -(1 << 40)


@njit(inline="always")
def _grow(i, tick, ri, axis, least, greatest):  # type: ignore[no-untyped-def]
    grew = False
    if least < ri[i, R_EXT0 + 2 * axis]:
        ri[i, R_EXT0 + 2 * axis] = least
        grew = True
    if greatest > ri[i, R_EXT0 + 2 * axis + 1]:
        ri[i, R_EXT0 + 2 * axis + 1] = greatest
        grew = True
    if grew:
        ri[i, R_EXT_GREW] = tick


@njit
def reset_extent(i, tick, ri, ci):  # type: ignore[no-untyped-def]
    """Robot i starts electing: its extent is its own tag (empty without one); with the
    option off (or no held-site gossip, see ``ETParams.pack``) it stays empty and is never
    sent."""
    for axis in range(EXTENT_FIELDS // 2):
        ri[i, R_EXT0 + 2 * axis] = EMPTY_LEAST
        ri[i, R_EXT0 + 2 * axis + 1] = EMPTY_GREATEST
    ri[i, R_EXT_GREW] = NEVER
    if ci[C_EXTENT] == 0 or ri[i, R_HAS_TAG] == 0:
        return
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    _grow(i, tick, ri, 0, x, x)
    _grow(i, tick, ri, 1, y, y)
    _grow(i, tick, ri, 2, x - y, x - y)


@njit
def ingest_extent(i, k, tick, ri, in_type, in_data, elected_epoch):  # type: ignore[no-untyped-def]
    """Merge extent message k of robot i's inbox, sent for ``elected_epoch``, if robot i
    elects for that epoch too."""
    if ri[i, R_PHASE] != PHASE_ELECTING or elected_epoch != ri[i, R_EPOCH] + 1:
        return
    for axis in range(EXTENT_FIELDS // 2):
        least = get_i8(in_data[i, k], 2 + 2 * axis)
        greatest = get_i8(in_data[i, k], 3 + 2 * axis)
        if least <= greatest:
            _grow(i, tick, ri, axis, least, greatest)


@njit
def sends_extent(i, tick, ri):  # type: ignore[no-untyped-def]
    """Robot i sends its extent this period: it grew less than ``EXTENT_RELAY_TICKS``
    ago, and it is the extent's period of three."""
    return (
        tick - ri[i, R_EXT_GREW] < EXTENT_RELAY_TICKS
        and (tick // PERIOD_TICKS) % EXTENT_EVERY_PERIODS == EXTENT_PERIOD
    )


@njit
def encode_extent(i, ri, out_type, out_data):  # type: ignore[no-untyped-def]
    """Write robot i's extent message (layout in the module docstring)."""
    epoch = ri[i, R_EPOCH] + 1
    out_type[i] = MSG_EXTENT | ((epoch & 31) << EPOCH_SHIFT)
    for f in range(EXTENT_FIELDS):
        out_data[i, 2 + f] = ri[i, R_EXT0 + f] & 0xFF
    out_data[i, 8] = 0


def extent_of(ri: np.ndarray, i: int) -> np.ndarray | None:
    """Robot i's extent (host side): (3, 2) int64, least and greatest X, Y and X - Y of
    the tags it heard of while electing; None when it holds none (or the option is off)."""
    ext = np.asarray(ri[i, R_EXT0 : R_EXT0 + EXTENT_FIELDS], dtype=np.int64).reshape(3, 2)
    if (ext[:, 0] > ext[:, 1]).any():
        return None
    return ext


def cells_in(cells: np.ndarray, extent: np.ndarray) -> np.ndarray:
    """(K,) bool: which of ``cells`` (K, 2) tags lie in the hexagon ``extent`` (3, 2)
    spans."""
    axes = np.stack([cells[:, 0], cells[:, 1], cells[:, 0] - cells[:, 1]], axis=1)
    return ((axes >= extent[:, 0]) & (axes <= extent[:, 1])).all(axis=1)
