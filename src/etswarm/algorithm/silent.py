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

Robots that moved out of range (``split``) fall silent too, and covering their sites does
no harm: they are free. So every silent site carries the sides of it where robots are
known to be alive, merged as it floods (``note_silent``); one with five sides or more
alive or off the shape is enclosed: a dead robot inside the remnant, not a site across a
cut. The Leader keeps the scaled target off enclosed sites first of all, and off the
others only to break ties.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, direction_index, is_placed
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
TAGS_PER_MESSAGE = 2
#: A robot with silent sites to share sends them every this many periods while electing.
SILENT_EVERY_PERIODS = 3
#: A kept silent site's code: its packed tag (low 16 bits) and, from bit 16, the six-bit
#: mask of the lattice directions from it where robots are heard alive (``note_silent``).
TAG_MASK = 0xFFFF
LIVE_SHIFT = 16
ALL_DIRECTIONS = 0x3F
#: A silent site with at least this many of its six sides alive or off the shape is
#: enclosed: a robot killed or removed inside the remnant (two dead side by side still
#: have five), not one cut off along a split (a notch in a ragged cut has three, one where
#: the cut meets the shape's edge three or four).
ENCLOSED_SIDES = 5


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


@njit(inline="always")
def live_sides(code):  # type: ignore[no-untyped-def]
    """How many sides of a kept silent site are known to have live robots."""
    mask = (code >> LIVE_SHIFT) & ALL_DIRECTIONS
    n = 0
    while mask:
        n += mask & 1
        mask >>= 1
    return n


@njit
def add_silent(i, tick, ri, x, y, live):  # type: ignore[no-untyped-def]
    """Add tag (x, y) to robot i's silent sites with ``live``, a mask of the directions
    from it where robots are alive (see ``note_silent``); True if that is news: a new tag
    (when there is room, or in place of one known to have fewer live sides) or new live
    sides of a kept one. News restarts the robot's quiet time."""
    code = pack_tag(x, y)
    count = ri[i, R_SILENT_N]
    at = -1
    for k in range(count):
        kept = ri[i, R_SILENT0 + k]
        if kept & TAG_MASK == code:
            at = k
            break
    if at >= 0:
        kept = ri[i, R_SILENT0 + at]
        code = kept | ((live & ALL_DIRECTIONS) << LIVE_SHIFT)
        if code == kept:
            return False
    else:
        code |= (live & ALL_DIRECTIONS) << LIVE_SHIFT
        if count < SILENT_MAX:
            at = count
            ri[i, R_SILENT_N] = count + 1
        else:
            fewest = live_sides(code)
            for k in range(count):
                sides = live_sides(ri[i, R_SILENT0 + k])
                if sides < fewest:
                    fewest = sides
                    at = k
    if at < 0:
        return False
    ri[i, R_SILENT0 + at] = code
    ri[i, R_SILENT_ADDED] = tick
    ri[i, R_COUNT_SINCE] = tick
    ri[i, R_SETTLED_SINCE] = tick
    return True


@njit
def heard_live(i, tick, ri, nb, x, y):  # type: ignore[no-untyped-def]
    """Robot i hears a placed robot of its target on tag (x, y) (not silent)."""
    for m in range(nb.shape[1]):
        if (
            nb[i, m, NB_ID] >= 0
            and nb[i, m, NB_TX] == x
            and nb[i, m, NB_TY] == y
            and is_placed(nb[i, m, NB_STATE])
            and nb[i, m, NB_EPOCH] == ri[i, R_EPOCH]
            and tick - nb[i, m, NB_LAST] < SILENT_AFTER_TICKS
        ):
            return True
    return False


@njit
def note_silent(i, tick, ri, nb, ci):  # type: ignore[no-untyped-def]
    """Add the placed robots of robot i's target on the sites next to its own that fell
    silent (see module) to its silent sites, each with the sides of it robot i knows to
    be alive: its own, and those of the two sites next to both where it hears a robot of
    its target. The masks of all robots round a silent site merge as it floods."""
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
        k = direction_index(nb[i, m, NB_TX] - x, nb[i, m, NB_TY] - y)
        if k < 0:
            continue
        quiet_for = tick - nb[i, m, NB_LAST]
        if SILENT_AFTER_TICKS <= quiet_for <= SILENT_RECENT_TICKS:
            sx = nb[i, m, NB_TX]
            sy = nb[i, m, NB_TY]
            live = 1 << direction_index(x - sx, y - sy)  # robot i itself
            for turn in (5, 1):  # the two sites next to both
                d = (k + turn) % 6
                if heard_live(i, tick, ri, nb, x + DIR_X[d], y + DIR_Y[d]):
                    live |= 1 << direction_index(x + DIR_X[d] - sx, y + DIR_Y[d] - sy)
            add_silent(i, tick, ri, sx, sy, live)


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
        code = ri[i, R_SILENT0 + (start + k) % count]
        x, y = unpack_tag(code)
        out_data[i, 3 + 3 * k] = x & 0xFF
        out_data[i, 4 + 3 * k] = y & 0xFF
        out_data[i, 5 + 3 * k] = (code >> LIVE_SHIFT) & ALL_DIRECTIONS
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
        x = get_i8(in_data[i, k], 3 + 3 * t)
        y = get_i8(in_data[i, k], 4 + 3 * t)
        add_silent(i, tick, ri, x, y, np.int64(in_data[i, k, 5 + 3 * t]))


def silent_tags(ri, i: int) -> set[tuple[int, int]]:  # type: ignore[no-untyped-def]
    """Robot i's silent sites (host side), as tags."""
    return {unpack_tag.py_func(int(ri[i, R_SILENT0 + k])) for k in range(int(ri[i, R_SILENT_N]))}


def enclosed_tags(ri, i: int, shape: set[tuple[int, int]]) -> set[tuple[int, int]]:  # type: ignore[no-untyped-def]
    """Robot i's enclosed silent sites (host side): those with at least ``ENCLOSED_SIDES``
    sides either known alive or off ``shape``, the tags of the target they were placed
    for (no robot stood there, so no robot went missing there either)."""
    out = set()
    for k in range(int(ri[i, R_SILENT_N])):
        code = int(ri[i, R_SILENT0 + k])
        x, y = unpack_tag.py_func(code)
        live = (code >> LIVE_SHIFT) & ALL_DIRECTIONS
        sides = sum(
            1
            for d, (dx, dy) in enumerate(zip(DIR_X, DIR_Y, strict=True))
            if (live >> d) & 1 or (x + dx, y + dy) not in shape
        )
        if sides >= ENCLOSED_SIDES:
            out.add((x, y))
    return out
