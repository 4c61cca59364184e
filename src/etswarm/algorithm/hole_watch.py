"""Searchers inside a hole: the hole's edge watches for them (``hole_watch_s``).

The capture that completes a hole's edge walls the hole off: a searcher still inside is
shut in for good, and the site it would have taken stays free (``O``: half the runs
that did not form ended so, session 42). The edge can see such searchers. A placed robot
whose tag is next to a hole site (``HOLE_FLAG`` in its gene), whose other neighbour sites
are all on the shape and held, has only hole sites free round it; a searcher it hears
nearer than ``WATCH_NEAR`` d is in the hole (outside the ring it would stand 2 d away or
more). The robot notes the searcher's ID and the tick it heard it (a sighting).

Robots on a hole's edge pass their two freshest sightings on to each other, so the news
goes round the whole edge: while a placed robot there knows a sighting younger than
``hole_watch_s``, it sends a watch message instead of its status every third period
(kind ``MSG_WATCH``: bytes 0-1 its ID, 2-3 and 5-6 the two searchers' IDs, 0xFFFF for
none, 4 and 7 their ages in whole seconds, at most 255; the target epoch in the type
byte as for a status). A receiver of the same epoch keeps a sighting one second older
than sent, so a sighting that goes round and round dies out. Searchers keep what they
hear in the same fields.

A searcher does not take a site that walls a hole off (``site_memory.walls_a_hole``)
while it knows a sighting younger than ``hole_watch_s`` of a searcher other than itself:
the searchers inside get out first, by the mouth they came in. A searcher inside takes
the last site of the edge when it is the only one seen there lately.

Memory of robot i (``ri`` fields): ``R_WATCH_ID0``, ``R_WATCH_T0``, ``R_WATCH_ID1``,
``R_WATCH_T1``: the two sightings (searcher ID, -1 for none; the tick, on robot i's own
clock, it was heard in the hole).
"""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, SEARCH, gene_at
from etswarm.algorithm.memory import (
    HOLE_FLAG,
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_STATE,
    R_EPOCH,
    R_MASK,
    R_TAG_X,
    R_TAG_Y,
    R_WATCH_ID0,
    R_WATCH_ID1,
    R_WATCH_T0,
    R_WATCH_T1,
)
from etswarm.algorithm.messages import EPOCH_SHIFT, MSG_WATCH, get_u16, put_u16
from etswarm.algorithm.params import C_HOLE_WATCH, C_TICKS_NB_FRESH, C_TICKS_PER_S, F_SPACING
from etswarm.algorithm.site_memory import beside_hole, walls_a_hole

#: A searcher heard nearer than this many d to a ringed edge robot is in the hole.
WATCH_NEAR = 1.4
#: A robot with a fresh sighting sends it instead of its status once in this many periods.
WATCH_SHARE = 3
#: Ticks of one transmit period (as the other messages that alternate with the status).
PERIOD_TICKS = 15
#: No searcher: the ID field of an empty sighting in a watch message.
NO_ID = 0xFFFF
#: Greatest age (s) a watch message carries.
MAX_AGE_S = 255


@njit(inline="always")
def note_sighting(i, searcher, seen, ri):  # type: ignore[no-untyped-def]
    """Keep the sighting of ``searcher`` at tick ``seen`` in robot i's two fields: a newer
    tick for a searcher kept already, else in place of the older of the two if newer."""
    if ri[i, R_WATCH_ID0] == searcher:
        ri[i, R_WATCH_T0] = max(ri[i, R_WATCH_T0], seen)
    elif ri[i, R_WATCH_ID1] == searcher:
        ri[i, R_WATCH_T1] = max(ri[i, R_WATCH_T1], seen)
    elif ri[i, R_WATCH_T0] <= ri[i, R_WATCH_T1]:
        if seen > ri[i, R_WATCH_T0]:
            ri[i, R_WATCH_ID0] = searcher
            ri[i, R_WATCH_T0] = seen
    elif seen > ri[i, R_WATCH_T1]:
        ri[i, R_WATCH_ID1] = searcher
        ri[i, R_WATCH_T1] = seen


@njit
def watch_edge(i, tick, ri, nb, nb_dist, gene, ci, cf):  # type: ignore[no-untyped-def]
    """Placed robot i on a hole's edge, with every neighbour site off the hole held (its
    last evaluation's ``R_MASK``), notes the searchers of its epoch it heard lately nearer
    than ``WATCH_NEAR`` d: they are in the hole. ``nb_dist`` (N, M) mm."""
    if ci[C_HOLE_WATCH] == 0:
        return
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    holes = 0
    for k in range(6):
        flag = gene_at(gene, ci, x + DIR_X[k], y + DIR_Y[k])
        if flag == HOLE_FLAG:
            holes += 1
        elif flag != 1 or not (ri[i, R_MASK] >> k) & 1:
            return  # a free shape site or the outside beside it: it cannot tell the side
    if holes == 0:
        return
    near = WATCH_NEAR * cf[F_SPACING]
    fresh = ci[C_TICKS_NB_FRESH]
    epoch = ri[i, R_EPOCH]
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or nb[i, m, NB_STATE] != SEARCH:
            continue
        if nb[i, m, NB_EPOCH] != epoch or tick - nb[i, m, NB_LAST] > fresh:
            continue
        if nb_dist[i, m] < near:
            note_sighting(i, nb[i, m, NB_ID], nb[i, m, NB_LAST], ri)


@njit(inline="always")
def knows_sighting(i, tick, ri, ci, other_than):  # type: ignore[no-untyped-def]
    """Robot i knows a sighting younger than ``hole_watch_s`` of a searcher other than
    ``other_than`` (-1: any)."""
    window = ci[C_HOLE_WATCH]
    if window == 0:
        return False
    for f in range(2):
        sid = ri[i, R_WATCH_ID0 + 2 * f]
        if sid >= 0 and sid != other_than and tick - ri[i, R_WATCH_T0 + 2 * f] < window:
            return True
    return False


@njit
def sends_watch(i, tick, ri, gene, ci):  # type: ignore[no-untyped-def]
    """Placed robot i sends a watch message in this period: it is on a hole's edge, knows a
    fresh sighting, and it is the period of ``WATCH_SHARE`` for it."""
    if ci[C_HOLE_WATCH] == 0 or (tick // PERIOD_TICKS) % WATCH_SHARE != WATCH_SHARE - 1:
        return False
    if not knows_sighting(i, tick, ri, ci, -1):
        return False
    return beside_hole(ri[i, R_TAG_X], ri[i, R_TAG_Y], gene, ci)


@njit
def encode_watch(i, tick, ri, ci, out_type, out_data):  # type: ignore[no-untyped-def]
    """Write robot i's watch message (layout in the module docstring)."""
    ticks_per_s = ci[C_TICKS_PER_S]
    out_type[i] = MSG_WATCH | ((ri[i, R_EPOCH] & 31) << EPOCH_SHIFT)
    for f in range(2):
        sid = ri[i, R_WATCH_ID0 + 2 * f]
        age_s = min((tick - ri[i, R_WATCH_T0 + 2 * f]) // ticks_per_s, MAX_AGE_S)
        if sid < 0:
            sid = NO_ID
            age_s = MAX_AGE_S
        put_u16(out_data[i], 2 + 3 * f, sid)
        out_data[i, 4 + 3 * f] = age_s


@njit
def file_watch(i, k, tick, ri, in_type, in_data, ci):  # type: ignore[no-untyped-def]
    """Keep the sightings of watch message k of robot i's inbox when it is of i's epoch,
    each one second older than sent."""
    ticks_per_s = ci[C_TICKS_PER_S]
    if (in_type[i, k] >> EPOCH_SHIFT) != (ri[i, R_EPOCH] & 31):
        return
    for f in range(2):
        sid = get_u16(in_data[i, k], 2 + 3 * f)
        age_s = in_data[i, k, 4 + 3 * f]
        if sid != NO_ID and sid != i and age_s < MAX_AGE_S:
            note_sighting(i, sid, tick - (age_s + 1) * ticks_per_s, ri)


@njit
def watch_blocks(i, tick, cx, cy, ri, held_i, ox, oy, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Searcher i must not take site (cx, cy) yet: the capture walls a hole off (by its
    memory ``held_i``, (WX, WY) at tag (ox, oy)) and another searcher was seen inside
    within ``hole_watch_s``."""
    if not knows_sighting(i, tick, ri, ci, i):
        return False
    return walls_a_hole(cx, cy, held_i, ox, oy, gene_flag, ci)
