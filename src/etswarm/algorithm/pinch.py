"""A searcher does not take a site from where it would pinch a free neighbour site.

Pinched last sites were the main way first formations stalled after session 18: 32 of
the 40 unformed runs over 13 shapes (seeds 30-89) ended with a free site whose placed
neighbours stood 15-20 mm into it, so that no 33 mm body fits there (disc seed 34:
the best point of the free site (-3, 0) keeps 28.8 mm from every body). Regrowths stall
the same way: most unformed remnants end with one to four free sites and as many
searchers beside them.

Those robots were captured there: a searcher long at the shape widens its pair window
(``ETParams.widen_max``) and may take a site from 10-15 mm off its centre. A placed
robot cannot put that right: it has no compass and no reverse gear, it turns only by
pivoting about a leg on its rim (its centre swings on a 16.5 mm circle), and between
its neighbours there is room for a few mm of that (branch ``exp/reseat``, session 19).
A searcher can: it is still on the move.

With ``ETParams.capture_pinch_mm`` = P > 0 (default 10), a searcher confirming a site
estimates where it stands (``offsets.locate``, the estimate it would keep as its offset)
and does not take the site when that puts it P mm or more into a free neighbour site of
the gene (one it knows no robot to hold: not in its table, not reported, not in its
memory of held sites) that has ``NOTCH_HELD`` or more neighbour sites held once the
searcher takes its own, so that a later searcher has to come in between placed robots.
It moves on as after any failed confirmation. A searcher refuses at most
``ETParams.capture_pinch_refusals`` (default 4; 2 until session 20, when windows came to
widen three times faster) sites between leaving the repository and taking one: where the
lattice is stretched, every capture may stand far off.

With ``ETParams.capture_mouth_mm`` = M > 0 (default 68, since session 21) it also refuses
the site when it reads, since it stopped, the placed robot across such a free site (two
steps from its own site through the free one) nearer than M mm (``narrow_mouth``): two
33 mm bodies need 66 mm between their centres for a third to come in between, where the
lattice puts 2 d = 80. Regrowths used to stall this way with no capture more than a few
mm off: the last free site had four held neighbours in a row, and the two at the ends
stood 59-70 mm apart. Both tests share the count of refusals.

Measured over 13 shapes, seeds 30-49 (4 h limit; the defaults before formed 241 of 260):

- every free neighbour site counting, no limit on refusals: 232 (disc 19, heart 20,
  dumbbell 20 of 20, but plus 12 and starfish 10 against 19 and 17: the tips of growing
  arms, and stretched corners where every capture stands far off, were refused for ever);
- the same with P = 14 mm: 236;
- free sites with three held neighbours: 243; with two: 244;
- with two, and at most two refusals: 250 (every shape 18 or more but starfish, 16).
"""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import (
    DIR_X,
    DIR_Y,
    direction_index,
    gene_at,
    is_placed,
    two_step_direction,
)
from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_OFF_X,
    R_OFF_Y,
    R_TAG_X,
    R_TAG_Y,
)
from etswarm.algorithm.offsets import FINE_PER_MM, locate, site_x, site_y
from etswarm.algorithm.params import (
    C_OFFSETS,
    C_REGROW_UNPINCH,
    C_TICKS_NB_FRESH,
    F_CAPTURE_MOUTH,
    F_CAPTURE_PINCH,
    F_PORTABLE_MATH,
    F_SPACING,
)
from etswarm.algorithm.site_memory import is_held, site_taken
from etswarm.sim.fpmath import hypot_as

#: A free neighbour site counts when this many of its neighbour sites are held once the
#: searcher takes its site.
NOTCH_HELD = 2


@njit(inline="always")
def toward_free(ox, oy, free_mask):  # type: ignore[no-untyped-def]
    """The largest component (mm) of the offset (ox, oy) (mm, gene frame) from a site's
    centre towards one of its neighbour sites in ``free_mask`` (bit k for lattice
    direction k); -1e9 when the mask is empty."""
    worst = -1e9
    for k in range(6):
        if (free_mask >> k) & 1:
            # direction k's unit vector is the centre of tag (DX, DY) at spacing 1
            ux = site_x(DIR_X[k], DIR_Y[k], 1.0)
            uy = site_y(DIR_Y[k], 1.0)
            worst = max(worst, ox * ux + oy * uy)
    return worst


@njit
def held_for_all_i_knows(i, x, y, nb, held_i, wx, wy):  # type: ignore[no-untyped-def]
    """Robot i knows site (x, y) held: in its table, reported by a neighbour, or in its
    memory ``held_i`` (window origin at tag (wx, wy))."""
    return site_taken(i, x, y, nb) or is_held(held_i, x, y, wx, wy)


@njit
def free_neighbours(i, cx, cy, nb, gene_flag, ci, held_i, wx, wy):  # type: ignore[no-untyped-def]
    """Bits k of site (cx, cy)'s neighbour sites of the gene that robot i knows of no
    robot holding (``held_for_all_i_knows``) and that, once (cx, cy) is held, have at least
    ``NOTCH_HELD`` neighbour sites held: a free site that a searcher has to enter between
    placed robots. (A free site on an open edge, as at the tip of a growing arm, is
    reached from outside whatever stands next to it.)"""
    mask = 0
    for k in range(6):
        x = cx + DIR_X[k]
        y = cy + DIR_Y[k]
        if gene_at(gene_flag, ci, x, y) != 1 or held_for_all_i_knows(i, x, y, nb, held_i, wx, wy):
            continue
        n_held = 1  # (cx, cy) itself
        for kk in range(6):
            nx = x + DIR_X[kk]
            ny = y + DIR_Y[kk]
            if (nx != cx or ny != cy) and held_for_all_i_knows(i, nx, ny, nb, held_i, wx, wy):
                n_held += 1
        if n_held >= NOTCH_HELD:
            mask |= 1 << k
    return mask


@njit
def narrow_mouth(i, cx, cy, since, free_mask, nb, nb_dist, cf):  # type: ignore[no-untyped-def]
    """Robot i, standing to take site (cx, cy), read since ``since`` the placed robot
    across one of the free sites of ``free_mask`` (two steps from (cx, cy) through it)
    nearer than ``capture_mouth_mm``: the free site would be left between two bodies too
    close for a third to come in."""
    limit = cf[F_CAPTURE_MOUTH]
    if limit <= 0.0:
        return False
    for j in range(nb.shape[1]):
        if nb[i, j, NB_ID] < 0 or not is_placed(nb[i, j, NB_STATE]) or nb[i, j, NB_LAST] < since:
            continue
        dx = nb[i, j, NB_TX] - cx
        dy = nb[i, j, NB_TY] - cy
        if nb_dist[i, j] >= limit:
            continue
        k = two_step_direction(dx, dy)
        if k >= 0 and (free_mask >> k) & 1:
            return True
    return False


@njit
def too_far_off(i, cx, cy, since, nb, nb_dist, ci, cf, limit):  # type: ignore[no-untyped-def]
    """Robot i, confirming site (cx, cy) on readings since ``since``, stands ``limit`` mm or
    more from the site's centre by its own estimate (``capture_offset_mm``, or
    ``regrowth_capture_offset_mm`` for a regenerated target). False with the rule off
    (``limit`` 0), with offsets off, or when it cannot locate itself."""
    if limit <= 0.0 or ci[C_OFFSETS] == 0:
        return False
    d = cf[F_SPACING]
    x0 = site_x(cx, cy, d)
    y0 = site_y(cy, d)
    ok, x, y = locate(i, since, x0, y0, nb, nb_dist, d)
    return ok and hypot_as(x - x0, y - y0, cf[F_PORTABLE_MATH] > 0.0) >= limit


@njit
def would_pinch(i, cx, cy, since, nb, nb_dist, gene_flag, ci, cf, held_i, wx, wy):  # type: ignore[no-untyped-def]
    """Robot i, confirming site (cx, cy) on readings since ``since``, stands
    ``capture_pinch_mm`` or more into a free neighbour site (see module). False with the
    rule off, with offsets off, or when it cannot locate itself."""
    limit = cf[F_CAPTURE_PINCH]
    if limit <= 0.0 or ci[C_OFFSETS] == 0:
        return False
    free = free_neighbours(i, cx, cy, nb, gene_flag, ci, held_i, wx, wy)
    if free == 0:
        return False
    if narrow_mouth(i, cx, cy, since, free, nb, nb_dist, cf):
        return True
    d = cf[F_SPACING]
    x0 = site_x(cx, cy, d)
    y0 = site_y(cy, d)
    ok, x, y = locate(i, since, x0, y0, nb, nb_dist, d)
    if not ok:
        return False
    return toward_free(x - x0, y - y0, free) >= limit


@njit
def pinches_new_target(i, tick, ri, nb, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Robot i, on a site of the target a regeneration replaces, adopts the new target
    ``gene_flag`` (its table not yet cleared): its own offset puts it ``C_REGROW_UNPINCH``
    mm or more into a neighbour site of the new target that no placed robot it heard
    within the neighbour timeout holds. Such a site is most often a notch the old shape
    left empty, beside which a robot could stand far off its own site (traced on starfish
    ``split x=mid`` seed 7: robot 59, kept on (1, 2) 24 mm into the new target's free
    (0, 2), left it 17 mm of room for 4 h). Always False with offsets off or the option 0.
    """
    limit = ci[C_REGROW_UNPINCH]
    if limit <= 0 or ci[C_OFFSETS] == 0:
        return False
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    held = 0
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or not is_placed(nb[i, m, NB_STATE]):
            continue
        if tick - nb[i, m, NB_LAST] > ci[C_TICKS_NB_FRESH]:
            continue
        k = direction_index(nb[i, m, NB_TX] - x, nb[i, m, NB_TY] - y)
        if k >= 0:
            held |= 1 << k
    free = 0
    for k in range(6):
        if not (held >> k) & 1 and gene_at(gene_flag, ci, x + DIR_X[k], y + DIR_Y[k]) == 1:
            free |= 1 << k
    if free == 0:
        return False
    ox = ri[i, R_OFF_X] / FINE_PER_MM
    oy = ri[i, R_OFF_Y] / FINE_PER_MM
    return toward_free(ox, oy, free) >= limit
