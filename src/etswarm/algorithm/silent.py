"""Silent sites: where robots fell silent, so a regenerated target can keep clear of them.

A killed robot stops and stays where it was (``kill`` damage). If the scaled target of its
remnant has a site under it, no robot can ever stand there and the remnant never
re-forms (traced on ``L`` ``kill random=0.1``: in 4 of 6 failed runs the last free site had
a dead robot within 2-7 mm of it). The robots next to it know: it was placed, of their
target, and they have not heard it since. So while electing, every robot notes the tags
of the placed robots on the lattice sites next to its own that it heard within
``SILENT_RECENT_TICKS`` but not for ``SILENT_AFTER_TICKS`` (longer than any run of lost
messages, as long as it takes a neighbour to turn Danger; robots of the second ring, at
69 mm, are left out: near the 70 mm range they drop in and out of earshot). It keeps up to
``SILENT_MAX`` of them in ``R_SILENT0..`` and floods them through the remnant in a
silent-sites message (``messages``; kind ``MSG_SILENT``), sent instead of its election
message every third period for ``SILENT_RELAY_TICKS`` after it learnt of the last one (the
election's subtree counts need the election messages; sent for good, every third period
lost made them flicker and the Leader never saw them quiet). A robot that learns a new one
restarts its quiet time like a change of its subtree count, so the Leader declares itself
only once the list has reached it; it then asks for a placement that covers as few silent
sites as it can (``ETRun._scaled_placement``).

Robots that moved out of range (``split``) fall silent too; avoiding their sites only
keeps the scaled target on the side where the remnant stands.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.algorithm.kernel_util import direction_index, is_placed
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_COUNT_SINCE,
    R_EPOCH,
    R_HAS_TAG,
    R_SETTLED_SINCE,
    R_SILENT0,
    R_SILENT_ADDED,
    R_SILENT_N,
    R_SILENT_NEXT,
    R_TAG_X,
    R_TAG_Y,
    SILENT_MAX,
)
from etswarm.algorithm.messages import EPOCH_SHIFT, MSG_SILENT, get_i8
from etswarm.algorithm.params import C_SILENT_SITES

#: A placed neighbour not heard for this long (ticks) has fallen silent ...
SILENT_AFTER_TICKS = 31 * 8
#: ... if it was heard within this long (ticks); older entries say nothing of now.
SILENT_RECENT_TICKS = 31 * 180
#: A robot relays its silent sites for this long (ticks) after it learnt of the last one.
SILENT_RELAY_TICKS = 31 * 20
#: Tags per silent-sites message.
TAGS_PER_MESSAGE = 3
#: A robot with silent sites to share sends them every this many periods while electing.
SILENT_EVERY_PERIODS = 3


@njit(inline="always")
def pack_tag(x, y):  # type: ignore[no-untyped-def]
    """One int for tag (x, y), each -128..127."""
    return (x & 0xFF) | ((y & 0xFF) << 8)


@njit(inline="always")
def unpack_tag(code):  # type: ignore[no-untyped-def]
    """Tag (x, y) of ``pack_tag``'s code."""
    x = code & 0xFF
    y = (code >> 8) & 0xFF
    return (x - 256 if x >= 128 else x), (y - 256 if y >= 128 else y)


@njit
def add_silent(i, tick, ri, x, y):  # type: ignore[no-untyped-def]
    """Add tag (x, y) to robot i's silent sites; True if it is new (and there was room).
    A new one restarts the robot's quiet time."""
    code = pack_tag(x, y)
    count = ri[i, R_SILENT_N]
    for k in range(count):
        if ri[i, R_SILENT0 + k] == code:
            return False
    if count >= SILENT_MAX:
        return False
    ri[i, R_SILENT0 + count] = code
    ri[i, R_SILENT_N] = count + 1
    ri[i, R_SILENT_ADDED] = tick
    ri[i, R_COUNT_SINCE] = tick
    ri[i, R_SETTLED_SINCE] = tick
    return True


@njit
def note_silent(i, tick, ri, nb, ci):  # type: ignore[no-untyped-def]
    """Add the placed robots of robot i's target on the sites next to its own that fell
    silent (see module) to its silent sites."""
    epoch = ri[i, R_EPOCH]
    if ri[i, R_HAS_TAG] == 0 or ci[C_SILENT_SITES] == 0:
        return
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or not is_placed(nb[i, m, NB_STATE]):
            continue
        if nb[i, m, NB_EPOCH] != epoch:
            continue
        if direction_index(nb[i, m, NB_TX] - x, nb[i, m, NB_TY] - y) < 0:
            continue
        quiet_for = tick - nb[i, m, NB_LAST]
        if SILENT_AFTER_TICKS <= quiet_for <= SILENT_RECENT_TICKS:
            add_silent(i, tick, ri, nb[i, m, NB_TX], nb[i, m, NB_TY])


@njit
def sends_silent(i, tick, ri):  # type: ignore[no-untyped-def]
    """Robot i sends its silent sites this period: it has some, learnt of the last one
    less than ``SILENT_RELAY_TICKS`` ago, and it is every third period."""
    return (
        ri[i, R_SILENT_N] > 0
        and tick - ri[i, R_SILENT_ADDED] < SILENT_RELAY_TICKS
        and (tick // 15) % SILENT_EVERY_PERIODS == 2
    )


@njit
def encode_silent(i, ri, out_type, out_data):  # type: ignore[no-untyped-def]
    """Write robot i's silent-sites message: the epoch elected for (mod 32, in the type
    byte), then up to three tags from its list, taken in turn; unused tags repeat the
    first."""
    epoch = ri[i, R_EPOCH] + 1
    out_type[i] = MSG_SILENT | ((epoch & 31) << EPOCH_SHIFT)
    count = ri[i, R_SILENT_N]
    start = ri[i, R_SILENT_NEXT] % count
    for k in range(TAGS_PER_MESSAGE):
        x, y = unpack_tag(ri[i, R_SILENT0 + (start + k) % count])
        out_data[i, 3 + 2 * k] = x & 0xFF
        out_data[i, 4 + 2 * k] = y & 0xFF
    out_data[i, 2] = min(count, TAGS_PER_MESSAGE)
    ri[i, R_SILENT_NEXT] = (start + TAGS_PER_MESSAGE) % count


@njit
def ingest_silent(i, k, tick, ri, in_data, elected_epoch):  # type: ignore[no-untyped-def]
    """Merge the tags of silent-sites message k of robot i's inbox, sent for
    ``elected_epoch``, if robot i elects for that epoch too."""
    if elected_epoch != ri[i, R_EPOCH] + 1:
        return
    n_tags = min(np.int64(in_data[i, k, 2]), TAGS_PER_MESSAGE)
    for t in range(n_tags):
        x = get_i8(in_data[i, k], 3 + 2 * t)
        y = get_i8(in_data[i, k], 4 + 2 * t)
        add_silent(i, tick, ri, x, y)


def silent_tags(ri, i: int) -> set[tuple[int, int]]:  # type: ignore[no-untyped-def]
    """Robot i's silent sites (host side), as tags."""
    count = int(ri[i, R_SILENT_N])
    return {unpack_tag.py_func(int(ri[i, R_SILENT0 + k])) for k in range(count)}
