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

A searcher can also tell by itself (``inside_bit``): while its readings of three or more
placed robots near a hole's edge fit a hole site better than any other free site round
them (``localises_in_hole``), its status carries ``INSIDE_BIT``, and every robot on the
edge that hears it notes a sighting. The robots beside the hole's last free edge site,
its mouth, need this: their free neighbour site keeps them from telling the two sides
apart, and a searcher shut in presses against them (``O`` seed 200: searcher 58 stood
35-40 mm from the mouth's neighbours inside the hole for 200 s, no edge robot noted it,
and a searcher from outside walled it in).

A searcher does not take a site that walls a hole off (``site_memory.walls_a_hole``)
while it knows a sighting younger than ``hole_watch_s`` of a searcher other than itself:
the searchers inside get out first, by the mouth they came in. A searcher inside takes
the last site of the edge when it is the only one seen there lately.

Memory of robot i (``ri`` fields): ``R_WATCH_ID0``, ``R_WATCH_T0``, ``R_WATCH_ID1``,
``R_WATCH_T1``: the two sightings (searcher ID, -1 for none; the tick, on robot i's own
clock, it was heard in the hole).
"""

from __future__ import annotations

import math

from numba import njit

from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, SEARCH, gene_at, is_placed
from etswarm.algorithm.memory import (
    HOLE_FLAG,
    NB_ANCHORED,
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_EPOCH,
    R_INSIDE,
    R_MASK,
    R_TAG_X,
    R_TAG_Y,
    R_WATCH_ID0,
    R_WATCH_ID1,
    R_WATCH_T0,
    R_WATCH_T1,
)
from etswarm.algorithm.messages import EPOCH_SHIFT, INSIDE_BIT, MSG_WATCH, get_u16, put_u16
from etswarm.algorithm.offsets import anchor_x, anchor_y, site_x, site_y
from etswarm.algorithm.params import (
    C_HOLE_TAKER,
    C_HOLE_WATCH,
    C_INSIDE_BIT,
    C_TICKS_NB_FRESH,
    C_TICKS_PER_S,
    F_SPACING,
)
from etswarm.algorithm.site_memory import (
    beside_hole,
    flood_from,
    is_held,
    narrowed,
    walls_a_hole,
)

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
#: A searcher places itself (``localises_in_hole``) once in this many ticks (a transmit
#: period: as often as its status goes out) ...
INSIDE_EVERY_TICKS = 15
#: ... from its fresh readings of at least this many placed robots of its target ...
INSIDE_MIN_READINGS = 3
#: ... trying the free sites next to those read nearer than this many d ...
INSIDE_NEAR = 1.6
#: ... and is in a hole when a hole site fits the readings within this RMS (mm) ...
INSIDE_FIT_MM = 16.0
#: ... and better than every other site tried by this much (mm, RMS).
INSIDE_MARGIN_MM = 4.0
#: A taker (``taker_allows``) was seen in the hole within this many seconds (a searcher
#: seen 51 s before had left the hole on ``O`` seed 201, and the site it was to take
#: stayed free for good).
TAKER_FRESH_S = 10
#: Larger than any RMS (mm).
NO_FIT = 1.0e9


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
    """Placed robot i on a hole's edge notes the searchers of its epoch it heard lately
    that are in the hole: those nearer than ``WATCH_NEAR`` d when every neighbour site off
    the hole is held (its last evaluation's ``R_MASK``), and, with ``C_INSIDE_BIT``, those
    whose status says they are (``INSIDE_BIT``). ``nb_dist`` (N, M) mm."""
    if ci[C_HOLE_WATCH] == 0:
        return
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    holes = 0
    ringed = True
    for k in range(6):
        flag = gene_at(gene, ci, x + DIR_X[k], y + DIR_Y[k])
        if flag == HOLE_FLAG:
            holes += 1
        elif flag != 1 or not (ri[i, R_MASK] >> k) & 1:
            ringed = False  # a free shape site or the outside beside it: distance cannot
            # tell the side
    told = ci[C_INSIDE_BIT] != 0
    if holes == 0 or not (ringed or told):
        return
    near = WATCH_NEAR * cf[F_SPACING] if ringed else 0.0
    fresh = ci[C_TICKS_NB_FRESH]
    epoch = ri[i, R_EPOCH]
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or nb[i, m, NB_STATE] != SEARCH:
            continue
        if nb[i, m, NB_EPOCH] != epoch or tick - nb[i, m, NB_LAST] > fresh:
            continue
        if nb_dist[i, m] < near or (told and nb[i, m, NB_ANCHORED] & INSIDE_BIT):
            note_sighting(i, nb[i, m, NB_ID], nb[i, m, NB_LAST], ri)


@njit(inline="always")
def reads_placed(i, m, tick, epoch, fresh, nb):  # type: ignore[no-untyped-def]
    """Row m of robot i's table is a placed robot of epoch ``epoch`` heard within
    ``fresh`` ticks."""
    return (
        nb[i, m, NB_ID] >= 0
        and is_placed(nb[i, m, NB_STATE])
        and nb[i, m, NB_EPOCH] == epoch
        and tick - nb[i, m, NB_LAST] <= fresh
    )


@njit
def site_fit(i, cx, cy, tick, epoch, fresh, nb, nb_dist, d):  # type: ignore[no-untyped-def]
    """RMS (mm) of the differences between robot i's fresh readings of the placed robots
    of its epoch and their distances from the centre of site (cx, cy), each robot where
    it stands by its tag and offset; ``NO_FIT`` if one of them holds (cx, cy)."""
    px = site_x(cx, cy, d)
    py = site_y(cy, d)
    total = 0.0
    count = 0
    for m in range(nb.shape[1]):
        if not reads_placed(i, m, tick, epoch, fresh, nb):
            continue
        if nb[i, m, NB_TX] == cx and nb[i, m, NB_TY] == cy:
            return NO_FIT
        ex = px - anchor_x(i, m, nb, d)
        ey = py - anchor_y(i, m, nb, d)
        err = math.sqrt(ex * ex + ey * ey) - nb_dist[i, m]
        total += err * err
        count += 1
    return math.sqrt(total / count) if count else NO_FIT


@njit
def localises_in_hole(i, tick, ri, nb, nb_dist, gene, ci, cf):  # type: ignore[no-untyped-def]
    """Searcher i's fresh readings of at least ``INSIDE_MIN_READINGS`` placed robots of its
    target, one of them on a hole's edge, fit a hole site next to one read nearer than
    ``INSIDE_NEAR`` d within ``INSIDE_FIT_MM``, and better by ``INSIDE_MARGIN_MM`` than
    every other site next to those robots (``site_fit``)."""
    d = cf[F_SPACING]
    fresh = ci[C_TICKS_NB_FRESH]
    epoch = ri[i, R_EPOCH]
    readings = 0
    at_edge = False
    for m in range(nb.shape[1]):
        if reads_placed(i, m, tick, epoch, fresh, nb):
            readings += 1
            at_edge = at_edge or beside_hole(nb[i, m, NB_TX], nb[i, m, NB_TY], gene, ci)
    if readings < INSIDE_MIN_READINGS or not at_edge:
        return False
    best_hole = NO_FIT
    best_other = NO_FIT
    near = INSIDE_NEAR * d
    for m in range(nb.shape[1]):
        if not reads_placed(i, m, tick, epoch, fresh, nb) or nb_dist[i, m] >= near:
            continue
        for k in range(6):
            cx = nb[i, m, NB_TX] + DIR_X[k]
            cy = nb[i, m, NB_TY] + DIR_Y[k]
            fit = site_fit(i, cx, cy, tick, epoch, fresh, nb, nb_dist, d)
            if gene_at(gene, ci, cx, cy) == HOLE_FLAG:
                best_hole = min(best_hole, fit)
            else:
                best_other = min(best_other, fit)
    return best_hole < INSIDE_FIT_MM and best_hole + INSIDE_MARGIN_MM < best_other


@njit
def note_inside(i, tick, ri, nb, nb_dist, gene, ci, cf):  # type: ignore[no-untyped-def]
    """Searcher i, once a transmit period with ``C_INSIDE_BIT`` while the watch runs (a
    target with a hole), notes in ``R_INSIDE`` whether its readings place it in a hole
    (``localises_in_hole``)."""
    if ci[C_HOLE_WATCH] == 0 or ci[C_INSIDE_BIT] == 0 or (tick + i) % INSIDE_EVERY_TICKS:
        return
    ri[i, R_INSIDE] = 1 if localises_in_hole(i, tick, ri, nb, nb_dist, gene, ci, cf) else 0


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
    if not walls_a_hole(cx, cy, held_i, ox, oy, gene_flag, ci):
        return False
    return not taker_allows(i, tick, cx, cy, ri, held_i, ox, oy, gene_flag, ci)


@njit(inline="always")
def seen_inside(i, tick, ri, window):  # type: ignore[no-untyped-def]
    """How many searchers other than robot i it knows were seen in a hole within
    ``window`` ticks (0-2: it keeps two sightings)."""
    count = 0
    for f in range(2):
        sid = ri[i, R_WATCH_ID0 + 2 * f]
        if sid >= 0 and sid != i and tick - ri[i, R_WATCH_T0 + 2 * f] < window:
            count += 1
    return count


@njit
def taker_allows(i, tick, cx, cy, ri, held_i, ox, oy, gene_flag, ci):  # type: ignore[no-untyped-def]
    """With ``C_HOLE_TAKER``: searcher i may take (cx, cy) although the capture cuts a hole
    off from the outside (by its memory ``held_i``), because the one free shape site it
    leaves in there, on the hole's edge, has a taker: robot i knows exactly one other
    searcher seen in the hole within ``hole_watch_s``, and that one within
    ``TAKER_FRESH_S``. Every other free neighbour site must keep its way out and its
    opening (``narrowed``), as ``site_memory.shuts_in`` asks. ``held_i`` is restored on
    return."""
    if ci[C_HOLE_TAKER] == 0 or seen_inside(i, tick, ri, ci[C_HOLE_WATCH]) != 1:
        return False
    if seen_inside(i, tick, ri, TAKER_FRESH_S * ci[C_TICKS_PER_S]) != 1:
        return False  # the one seen inside may have come out since
    if not (0 <= cx - ox < held_i.shape[0] and 0 <= cy - oy < held_i.shape[1]):
        return False
    if is_held(held_i, cx, cy, ox, oy):
        return False
    held_i[cx - ox, cy - oy] = 1
    cut_off = 0
    fine = True
    for k in range(6):
        sx = cx + DIR_X[k]
        sy = cy + DIR_Y[k]
        flag = gene_at(gene_flag, ci, sx, sy)
        if (flag != 1 and flag != HOLE_FLAG) or is_held(held_i, sx, sy, ox, oy):
            continue
        exits, free_sites = flood_from(sx, sy, held_i, ox, oy, gene_flag, ci)
        if exits:
            if flag == 1 and narrowed(sx, sy, held_i, ox, oy) and not beside_hole(
                sx, sy, gene_flag, ci
            ):
                fine = False  # a site left too narrow to enter, hole or no hole
            continue
        if flag != HOLE_FLAG and not beside_hole(sx, sy, gene_flag, ci):
            fine = False  # shut in away from any hole: no searcher there to take it
            continue
        # Cut off with the hole: sites next to each other may flood one region twice,
        # which counts as two free sites and refuses (one taker fills one site).
        cut_off += free_sites
    held_i[cx - ox, cy - oy] = 0
    return fine and cut_off == 1
