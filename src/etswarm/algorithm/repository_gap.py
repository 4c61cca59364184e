"""A searcher that walks a broken repository to its dead end leaps the gap to the shape.

In the first formation the repository is the paper's queue, sorted by ID, lowest at the
far end: a Queued robot's queue rank (``release``, ``R_QRANK``) grows towards the shape,
and a searcher walking along the queue towards the shape hears the ranks of the Queued
robots it follows climb until it hears the shape. Searchers shove the queue's robots a
little at every pass, and on a long queue they open a gap wider than radio range (traced
on starfish seeds 229 and 238, ``docs/algorithm.md``, "Session 69": robot 84 pushed 34
mm off the line, 88 mm from robot 85; 85-87 then took sites, and the 53 robots beyond
the gap, 25 of them searching, went round their piece of the queue for the last 2.5 h).

A searcher of the first formation notes the rank of the Queued robot it follows. When
the ranks have climbed by ``RANK_STEP`` and then fallen by as much, with no placed robot
of its target heard for ``C_TICKS_GAP`` ticks, it has gone round the queue's end towards
the shape without finding the shape: a dead end. It then leaps: the Queued robots of its
piece (rank at most the highest it heard) become obstacles only, and it heads as a lost
searcher does (``homing``) for a point ``LEAP_AHEAD_MM`` beyond the dead end, on the
line from where the ranks were lowest to where they were highest (the queue's line),
and circles it on a widening spiral whose centre moves on along that line. The leap ends
when it hears a placed robot or a Queued robot of higher rank (the piece of the queue
beyond the gap, where it walks on and may leap again), or after ``C_TICKS_LEAP`` ticks.
Only robots programmed for the queue layout do this (``ETRun`` zeroes ``C_TICKS_GAP`` for a
packed cluster, whose ranks climb and fall all round it).

Fields (``memory``): ``R_GAP_PHASE`` (``PHASE_LOW``, ``PHASE_CLIMB``, ``PHASE_LEAP``),
``R_GAP_LO`` / ``R_GAP_TOP`` the lowest and highest rank of the walk and
``R_GAP_LO_X``/``_Y`` and ``R_GAP_TOP_X``/``_Y`` the odometric points where the searcher
heard them (1 / ``homing.ODO_PER_MM`` mm), ``R_GAP_SINCE`` the tick it last heard a placed
robot (or left the repository, or gave a leap up), ``R_LEAP_SINCE`` the tick its leap
began.
"""

from __future__ import annotations

import math

from numba import njit

from etswarm.algorithm.homing import ODO_PER_MM
from etswarm.algorithm.kernel_util import QUEUED, first_growth
from etswarm.algorithm.memory import (
    NB_LAST,
    NB_QRANK,
    NB_STATE,
    R_GAP_LO,
    R_GAP_LO_X,
    R_GAP_LO_Y,
    R_GAP_PHASE,
    R_GAP_SINCE,
    R_GAP_TOP,
    R_GAP_TOP_X,
    R_GAP_TOP_Y,
    R_HOME_X,
    R_HOME_Y,
    R_LEAP_SINCE,
    R_ODO_X,
    R_ODO_Y,
)
from etswarm.algorithm.params import C_TICKS_GAP, C_TICKS_LEAP

#: The ranks must climb, and then fall, by this many before a walk counts as a dead end:
#: four robots of the queue (about 180 mm), more than the one or two a shoved robot out of
#: line or a switch to the queue's other side may give.
RANK_STEP = 4
#: The leap heads for a point this far (mm) beyond the dead end along the queue's line:
#: gaps seen were 90-200 mm wide between the two pieces' ends.
LEAP_AHEAD_MM = 250.0
#: ... when the climb was at least this long (mm); shorter, it circles the dead end.
LEAP_LINE_MM = 100.0
#: Walk phases: looking for the lowest rank, climbing, leaping.
PHASE_LOW = 0
PHASE_CLIMB = 1
PHASE_LEAP = 2
#: A rank above any real one (``R_GAP_LO`` before the first reading).
NO_RANK = 1 << 30


@njit
def start_walk(i, tick, ri):  # type: ignore[no-untyped-def]
    """Robot i left the repository or heard its shape: its walk starts afresh."""
    ri[i, R_GAP_PHASE] = PHASE_LOW
    ri[i, R_GAP_LO] = NO_RANK
    ri[i, R_GAP_TOP] = -1
    ri[i, R_GAP_SINCE] = tick


@njit(inline="always")
def leaping(i, ri):  # type: ignore[no-untyped-def]
    """Robot i is leaping a gap in the repository."""
    return ri[i, R_GAP_PHASE] == PHASE_LEAP


@njit(inline="always")
def left_behind(i, m, ri, nb):  # type: ignore[no-untyped-def]
    """Row m of leaping robot i's table is a Queued robot of the piece it leaps from."""
    return nb[i, m, NB_STATE] == QUEUED and nb[i, m, NB_QRANK] <= ri[i, R_GAP_TOP]


@njit
def note_walk(i, tick, placed_slot, queued_slot, ri, nb, ci):  # type: ignore[no-untyped-def]
    """Update robot i's walk along the repository after it picked its reference
    (``placed_slot`` / ``queued_slot``: the nearest placed and Queued robots it follows,
    -1 for none). Starts the leap at a dead end, ends it; first formation only."""
    if ci[C_TICKS_GAP] == 0 or not first_growth(i, ri):
        return
    phase = ri[i, R_GAP_PHASE]
    if placed_slot >= 0:
        start_walk(i, tick, ri)
        return
    if phase == PHASE_LEAP:
        if queued_slot >= 0:
            # the queue beyond the gap: it walks on (and may leap again at its end)
            ri[i, R_GAP_PHASE] = PHASE_LOW
            ri[i, R_GAP_LO] = NO_RANK
        elif tick - ri[i, R_LEAP_SINCE] >= ci[C_TICKS_LEAP]:
            start_walk(i, tick, ri)  # it gives up and follows the repository again
        return
    if queued_slot < 0 or nb[i, queued_slot, NB_LAST] != tick:
        return  # no fresh reading of a Queued robot
    rank = nb[i, queued_slot, NB_QRANK]
    if phase == PHASE_LOW:
        if rank < ri[i, R_GAP_LO]:
            note_low(i, ri, rank)
        elif rank >= ri[i, R_GAP_LO] + RANK_STEP:
            ri[i, R_GAP_PHASE] = PHASE_CLIMB
            ri[i, R_GAP_TOP] = -1
            phase = PHASE_CLIMB
    if phase != PHASE_CLIMB:
        return
    if rank > ri[i, R_GAP_TOP]:
        ri[i, R_GAP_TOP] = rank
        ri[i, R_GAP_TOP_X] = ri[i, R_ODO_X]
        ri[i, R_GAP_TOP_Y] = ri[i, R_ODO_Y]
    elif rank <= ri[i, R_GAP_TOP] - RANK_STEP:
        if tick - ri[i, R_GAP_SINCE] >= ci[C_TICKS_GAP]:
            begin_leap(i, tick, ri)
        else:
            # Too soon after the shape (a searcher turned back in mid-queue): a new climb.
            ri[i, R_GAP_PHASE] = PHASE_LOW
            note_low(i, ri, rank)


@njit(inline="always")
def note_low(i, ri, rank):  # type: ignore[no-untyped-def]
    """Robot i's walk is lowest here: ``rank``, at its odometric position."""
    ri[i, R_GAP_LO] = rank
    ri[i, R_GAP_LO_X] = ri[i, R_ODO_X]
    ri[i, R_GAP_LO_Y] = ri[i, R_ODO_Y]


@njit
def begin_leap(i, tick, ri):  # type: ignore[no-untyped-def]
    """Robot i is at a dead end of the repository: it leaps, heading for a point
    ``LEAP_AHEAD_MM`` beyond where the ranks were highest, along the line from where they
    were lowest (its new home, ``homing``)."""
    ri[i, R_GAP_PHASE] = PHASE_LEAP
    ri[i, R_LEAP_SINCE] = tick
    dx = (ri[i, R_GAP_TOP_X] - ri[i, R_GAP_LO_X]) / ODO_PER_MM
    dy = (ri[i, R_GAP_TOP_Y] - ri[i, R_GAP_LO_Y]) / ODO_PER_MM
    line = math.sqrt(dx * dx + dy * dy)
    ahead = LEAP_AHEAD_MM / line if line >= LEAP_LINE_MM else 0.0
    ri[i, R_HOME_X] = ri[i, R_GAP_TOP_X] + round(dx * ahead * ODO_PER_MM)
    ri[i, R_HOME_Y] = ri[i, R_GAP_TOP_Y] + round(dy * ahead * ODO_PER_MM)
