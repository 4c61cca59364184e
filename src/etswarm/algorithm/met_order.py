"""Which robot of a pair a searcher passed first, from the order it first steered by them.

A searcher takes a common neighbour site of two placed robots on the outer side of the
pair, the side it passes on going round the group clockwise; which side that is depends
on which of the two it passed first (``localise.find_site``). ``follow_reference`` keeps
the robot it came from, ``R_FROM_ID``: the reference before the present one, if it
steered by it while moving for 2 s. A robot of the pair that was nearest only for a
moment never becomes that, so when the searcher came from a robot outside the pair,
``localise.came_from`` guesses that the one it steers by now was passed first.

The guess is wrong where the searcher passes the first robot of the pair at the fringe
of its window and steers by the second at once. Traced on dumbbell ``split y=mid`` seed
77 (``docs/algorithm.md``, "Session 60"): robot 11 went along the top of the row (0, 0),
(1, 0), (2, 0) of the regrowing remnant, steered by (0, 0), by (1, 0) for less than 2 s,
then by (2, 0), and stopped above (1, 0) and (2, 0). Taking (2, 0) for the robot it came
from, it put itself below the pair, on (1, -1), 80 mm from where it stood. Robots 17
and 21 then took (0, -1) and (-1, -1) from it, a row of the lattice's mirror image, and
the two free sites of the target beside them could never be taken.

The searcher's list of recent distinct references (``R_RECENT0``, newest first) enters
each robot when it first becomes the reference and does not reorder it when the nearest
robot flickers between the two of a pair, so it keeps the order in which they were met.
With ``ETParams.came_order`` on, a searcher that came from outside the pair and has both
robots of the pair in that list takes the one it met first for the one it passed first.
"""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import first_growth
from etswarm.algorithm.memory import R_RECENT0, RECENT_REFS
from etswarm.algorithm.params import C_CAME_ORDER, CAME_ORDER_ON, CAME_ORDER_REGROWTH


@njit(inline="always")
def by_met_order(i, ri, ci):  # type: ignore[no-untyped-def]
    """Whether robot i decides which of a pair it passed first by ``first_met`` now (the
    option, and for "regrowth" a regenerated target)."""
    mode = ci[C_CAME_ORDER]
    return mode == CAME_ORDER_ON or (mode == CAME_ORDER_REGROWTH and not first_growth(i, ri))


@njit(inline="always")
def first_met(i, ri, a_id, b_id, fallback):  # type: ignore[no-untyped-def]
    """Which of robots ``a_id`` and ``b_id`` robot i first steered by, by its list of recent
    distinct references; ``fallback`` when the list does not hold both."""
    at_a = -1
    at_b = -1
    for k in range(RECENT_REFS):
        ref = ri[i, R_RECENT0 + k]
        if ref == a_id:
            at_a = k
        elif ref == b_id:
            at_b = k
    if at_a < 0 or at_b < 0:
        return fallback
    return a_id if at_a > at_b else b_id
