"""A Stable robot pushed out of its neighbours' range leaves its site and takes it again.

Searchers that go round a remnant for hours brush past the robots at its tips, and every
brush shoves the placed robot a millimetre or so (``SimParams.still_push_share``). Traced
on ``H`` ``split x=mid`` seed 0 (``/work/diag/s38/lone.py``): robot 31 on the tip (4, 4)
(NN 2) drifted from 35 mm to 80 mm from its nearest neighbour between 3700 s and 5100 s.
Elections in between found every robot, so they were false alarms and excused its missing
neighbour sites (``regeneration.resume``). From 4860 s on every robot was Stable, robot
31 out of everyone's range, for the last 2.6 h of the run. The same ended ``H`` ``split
x`` seed 6, ``split y`` seed 0 and ``T`` ``kill random=0.1`` seed 5 (seeds 0-19).

Such a robot has heard no placed robot of its target for ``C_TICKS_REJOIN`` and is
Stable only by excused sites. It gives its site up and searches. Every memory of held
sites (its own included, by gossip) still holds its tag, so no other searcher takes the
site; the robot itself knows it left it and counts it free (``R_LEFT``). Lost at first
(it hears nobody), it homes on where it last heard a robot and orbits the group back to
the free site. A robot alone after damage is no such case: its missing neighbours were
not excused, so it starts an election instead (``placed``).
"""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.former_site import note_former_site
from etswarm.algorithm.kernel_util import first_growth
from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NO_SITE,
    R_CUT_OFF_SINCE,
    R_EXCUSED,
    R_LEFT,
    R_LEFT_X,
    R_LEFT_Y,
    R_MISSING,
    R_OFF_REFINE,
    R_OFF_X,
    R_OFF_Y,
    R_RESUMED_AT,
    R_SEEN_FULL,
    R_TAG_X,
    R_TAG_Y,
)
from etswarm.algorithm.offsets import FINE_PER_MM
from etswarm.algorithm.params import C_OFFSET_LEAVE, C_TICKS_NB_FRESH, C_TICKS_REJOIN
from etswarm.algorithm.search import begin_search
from etswarm.algorithm.site_memory import forget_left_site

#: An Active robot that hears nobody leaves after this many times ``C_TICKS_REJOIN``: a kept
#: robot waits longer than a Stable one for the growth to reach it.
ALONE_REJOINS = 5


@njit
def rejoin_if_cut_off(i, tick, heard_placed, excused_only, ri, ci, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Stable robot i, this evaluation: ``heard_placed`` whether it heard any placed robot
    of its target lately, ``excused_only`` whether its count is met only with excused
    sites. Once it has been cut off so for ``C_TICKS_REJOIN`` it leaves its site and
    searches (returns True)."""
    limit = ci[C_TICKS_REJOIN]
    if limit == 0 or not cut_off_for(i, tick, not heard_placed and excused_only, limit, ri):
        return False
    leave_site(i, tick, ri, held_i, ox, oy)
    return True


@njit
def rejoin_if_alone(i, tick, ri, nb, ci, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Active robot i of a regenerated target, this evaluation. Once it has heard no robot
    at all (its table ``nb``, fresh within ``C_TICKS_NB_FRESH``) for ``ALONE_REJOINS`` times
    ``C_TICKS_REJOIN`` it leaves its site and searches for it (returns True), as a cut-off
    Stable robot does. Such a robot was kept where the regrown lattice does not put its
    site: starfish ``split y=mid`` seed 14, robot 6 on (1, 3) stood 57 mm from it and 81
    mm from every other robot, heard nobody, so its memory never learnt its neighbours
    were held, and it stayed Active for the last 1.6 h of the run, its site free."""
    limit = ALONE_REJOINS * ci[C_TICKS_REJOIN]
    alone = not first_growth(i, ri) and not heard_anyone(i, tick, nb, ci[C_TICKS_NB_FRESH])
    if limit == 0 or not cut_off_for(i, tick, alone, limit, ri):
        return False
    leave_site(i, tick, ri, held_i, ox, oy)
    return True


@njit
def leave_if_far(i, tick, ri, ci, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Active robot i of a regenerated target, this evaluation: when it still refines its
    offset (it took its site by search) and the offset puts it ``C_OFFSET_LEAVE`` mm or
    farther from its site's centre, it leaves the site and searches for it again (returns
    True). In first formations this cost runs (dumbbell seeds 13 and 17 did not form in
    4 h with 35 mm, session 51), so it waits for a regrowth there. Traced on `T`
    kill random=0.1: on seed 3 robot 1 took (-4, -5) 25 mm off by its own estimate and
    was shoved 13 mm farther; on seed 32 the estimates of robots 14 and 10 slid together
    to 80 mm while both stood within 10 mm of their sites. Either way the free site
    next to them could not be taken."""
    limit = ci[C_OFFSET_LEAVE]
    if limit == 0 or ri[i, R_OFF_REFINE] == 0 or first_growth(i, ri):
        return False
    fx = ri[i, R_OFF_X]
    fy = ri[i, R_OFF_Y]
    if fx * fx + fy * fy < (limit * FINE_PER_MM) ** 2:
        return False
    leave_site(i, tick, ri, held_i, ox, oy)
    return True


@njit(inline="always")
def heard_anyone(i, tick, nb, fresh):  # type: ignore[no-untyped-def]
    """Robot i heard some robot within the last ``fresh`` ticks."""
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] >= 0 and tick - nb[i, m, NB_LAST] <= fresh:
            return True
    return False


@njit(inline="always")
def cut_off_for(i, tick, cut_off, limit, ri):  # type: ignore[no-untyped-def]
    """Keep in R_CUT_OFF_SINCE since when robot i has been ``cut_off`` at every
    evaluation; whether that is ``limit`` ticks or more."""
    if not cut_off:
        ri[i, R_CUT_OFF_SINCE] = 0
        return False
    if ri[i, R_CUT_OFF_SINCE] == 0:
        ri[i, R_CUT_OFF_SINCE] = tick + 1
        return False
    return tick - (ri[i, R_CUT_OFF_SINCE] - 1) >= limit


@njit
def leave_site(i, tick, ri, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Placed robot i gives its site up and searches for it again (``R_LEFT``)."""
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    begin_search(i, tick, ri)
    ri[i, R_CUT_OFF_SINCE] = 0
    ri[i, R_EXCUSED] = 0
    ri[i, R_MISSING] = 0
    ri[i, R_RESUMED_AT] = 0
    ri[i, R_SEEN_FULL] = 0
    ri[i, R_LEFT] = 1
    ri[i, R_LEFT_X] = x
    ri[i, R_LEFT_Y] = y
    note_former_site(i, ri, NO_SITE, NO_SITE)  # R_LEFT says where it is
    forget_left_site(held_i, ri, i, ox, oy)
