"""Localisation of a searching robot from its placed neighbours (paper Sec. 4.1): the pair
window, the mirror test and the consistency of every other reading (``find_site``)."""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.fill_order import strands_a_site
from etswarm.algorithm.former_site import out_of_reach
from etswarm.algorithm.hole_rules import (
    closes_a_hole,
    encloses_a_site,
    open_from,
)
from etswarm.algorithm.hole_watch import taker_allows
from etswarm.algorithm.kernel_util import (
    ACTIVE,
    DIR_X,
    DIR_Y,
    FAR,
    STABLE,
    direction_index,
    first_growth,
    gene_at,
    is_placed,
)
from etswarm.algorithm.kinship import foreign
from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_MASK,
    NB_STATE,
    NB_TS,
    NB_TX,
    NB_TY,
    NO_SITE,
)
from etswarm.algorithm.met_order import by_met_order, first_met
from etswarm.algorithm.offsets import expected_distance
from etswarm.algorithm.params import (
    C_AVOID_FOREIGN,
    C_FILL_LOOKAHEAD,
    C_HOLE_MEMORY,
    C_OFFSETS,
    C_SECOND_RING,
    C_TICKS_NB_FRESH,
    F_AIM_RELAX,
    F_BALANCE_TOL,
    F_CONSIST_TOL,
    F_CONSIST_WIDEN,
    F_MIRROR_MARGIN,
    F_PAIR_AIM,
    F_PAIR_TOL,
    F_REGROW_FOLD_SKIP,
    F_SPACING,
)
from etswarm.algorithm.site_memory import (
    is_held,
    shuts_in,
    site_taken,
)

#: A widened candidate's heard lattice neighbours must stand within d + this (mm): a
#: neighbour much farther is heard only now and then, and a placed robot that stops
#: hearing its neighbours goes to Danger (radio range 70 mm for d = 40 mm).
ADJACENT_SLACK_MM = 20.0
#: With site offsets on, a reference is considered for the pair window when its reading
#: is within the pair tolerance plus this (mm) of the window's centre; the window itself
#: is tested on readings corrected for where the references stand (``offsets``).
OFFSET_PREFILTER_MM = 25.0


@njit(inline="always")
def came_from(ref_id, from_id, a_id, b_id):  # type: ignore[no-untyped-def]
    """Which of the pair (a_id, b_id) a searcher that steers by ``ref_id`` and came from
    ``from_id`` (see ``follow_reference``) passed first; -1 when it steers by neither."""
    if ref_id != a_id and ref_id != b_id:
        return -1
    if from_id in (a_id, b_id):
        return from_id
    return ref_id


@njit
def reported_but_unheard(i, cx, cy, since, nb, gene_flag, ci):  # type: ignore[no-untyped-def]
    """A neighbour site of (cx, cy) is reported held by a placed robot heard since tick
    ``since``, yet robot i has heard no robot of that site since then. Its holder stands
    about d from the site, so a robot truly at (cx, cy) hears it: robot i is elsewhere
    (on the mirror site of its pair, or where the lattice has torn). With
    ``foreign_robots`` "avoid", reports of ``foreign`` robots (``gene_flag``: robot i's
    target) count for nothing: they are of another remnant's lattice."""
    avoid_foreign = ci[C_AVOID_FOREIGN] == 1
    slots = nb.shape[1]
    for k in range(6):
        sx = cx + DIR_X[k]
        sy = cy + DIR_Y[k]
        reported = False
        heard = False
        for j in range(slots):
            if nb[i, j, NB_ID] < 0 or not is_placed(nb[i, j, NB_STATE]):
                continue
            if nb[i, j, NB_LAST] < since:
                continue
            jx = nb[i, j, NB_TX]
            jy = nb[i, j, NB_TY]
            if jx == sx and jy == sy:
                heard = True
                break
            q = direction_index(sx - jx, sy - jy)
            if (
                q >= 0
                and (nb[i, j, NB_MASK] >> q) & 1
                and not (avoid_foreign and foreign(i, j, nb, gene_flag, ci))
            ):
                reported = True
        if reported and not heard:
            return True
    return False


@njit
def in_window(dist_a, dist_b, aim, cf, tol_scale):  # type: ignore[no-untyped-def]
    """Two references heard at ``dist_a`` and ``dist_b`` mm are both within the pair
    tolerance of ``aim`` (mm, the window's centre) and within the balance tolerance of
    each other (both times ``tol_scale``)."""
    pair_tol = cf[F_PAIR_TOL] * tol_scale
    return (
        abs(dist_a - aim) <= pair_tol
        and abs(dist_b - aim) <= pair_tol
        and abs(dist_a - dist_b) <= cf[F_BALANCE_TOL] * tol_scale
    )


@njit(inline="always")
def second_ring_side(dx, dy):  # type: ignore[no-untyped-def]
    """For tags that differ by (dx, dy) = DIR[q] + DIR[q + 1] (the second ring, sqrt(3)
    spacings apart), return q: the sites next to both are at DIR[q] and DIR[q + 1] from
    the first; -1 for any other difference."""
    for q in range(6):
        if DIR_X[q] + DIR_X[(q + 1) % 6] == dx and DIR_Y[q] + DIR_Y[(q + 1) % 6] == dy:
            return q
    return -1


@njit(inline="always")
def window_centre(cf, at_shape):  # type: ignore[no-untyped-def]
    """Centre of the pair window (mm) for a searcher ``at_shape`` ticks at the shape:
    d + ``pair_aim_mm``, moving back to d over ``pair_aim_relax_s`` when that is set."""
    offset = cf[F_PAIR_AIM]
    if cf[F_AIM_RELAX] > 0.0:
        offset *= max(0.0, 1.0 - at_shape / cf[F_AIM_RELAX])
    return cf[F_SPACING] + offset


@njit
def find_site(  # type: ignore[no-untyped-def]
    i, tick, since, strict, ref_id, from_id, orbit, nb, nb_dist, gene_flag, ci, cf, tol_scale,
    wide_min, held_i, ox, oy, pair_aim, plain_scale, left_x, left_y, ri, reach,
):
    """Localise robot i from its placed neighbours (paper Sec. 4.1).

    Two placed robots heard at about d whose tags are adjacent put the robot at one of their
    two common lattice neighbours, ``c`` or its mirror ``c2``. The robot takes ``c`` only
    with evidence that it is not at ``c2``: ``c2`` is held by a robot it knows of, a third
    placed robot heard since ``since`` is at the distance ``c`` predicts and not at the one
    ``c2`` predicts (off that by more than the consistency tolerance, and by
    ``F_MIRROR_MARGIN`` more than off ``c``'s), or ``c`` is on the outer side of the pair
    for a robot that orbits clockwise (``orbit`` 0; the other side for 1) from the one of
    the two it came from: ``from_id`` if it is one of them, else the reference ``ref_id`` it
    steers by (see ``came_from``; nothing when it steers by neither), or with
    ``ETParams.came_order`` the one of the two it met first (``met_order``). ``c`` must also have
    gene flag 1, be held by no robot it knows of, agree with every placed robot heard since
    ``since`` (but, after damage, one more than ``F_REGROW_FOLD_SKIP`` mm from ``c`` on the
    lattice whose reading does not fit ``c2`` either: only a fold brought it in range) and,
    when ``strict``, every known robot of a neighbouring site must have been heard since
    ``since``; and an Active robot must be adjacent to it (the least TS among them is
    returned); and taking it must not shut a free shape site next to it in: with
    ``C_HOLE_MEMORY`` by the robot's memory ``held_i`` ((WX, WY) window at tag (ox, oy), see
    ``site_memory``) over the whole shape, else from the robots it hears
    (``encloses_a_site``, ``closes_a_hole``).
    ``tol_scale`` widens the pair and balance tolerances; a candidate gets the wider window
    only when at least ``wide_min`` placed robots of its neighbour sites were heard (a
    pocket, where the site is hard to mistake), else the plain one; such a pocket candidate
    may also disagree with a heard robot by up to the consistency tolerance times
    ``min(tol_scale, consistency_widen_max)``, but never hear a robot of a neighbouring
    site farther than d + ``ADJACENT_SLACK_MM``. ``pair_aim`` (mm) is
    the window's centre (``window_centre``); ``plain_scale`` (>= 1) widens the plain window
    (a settled robot's confirmation, ``settle_tol_scale``). (left_x, left_y): the site robot
    i left when it was cut off (``rejoin``; ``NO_SITE`` for none): it takes no other, and
    its Stable neighbours stand in for the Active one it needs. ``reach`` (mm,
    ``former_site.former_reach``): it takes no site farther than this from the position
    of the site it held before it was left out (``ri``: its memory).

    Returns ``(found, x, y, min_active_ts)``; the best-fitting candidate wins.
    """
    d = cf[F_SPACING]
    scale = max(tol_scale, plain_scale)
    pair_tol = cf[F_PAIR_TOL] * scale
    consist_tol = cf[F_CONSIST_TOL]
    mirror_margin = cf[F_MIRROR_MARGIN]
    fold_skip = 0.0 if first_growth(i, ri) else cf[F_REGROW_FOLD_SKIP]
    # a pocket candidate may disagree more (checked against the plain one below)
    consist_wide = consist_tol * min(tol_scale, cf[F_CONSIST_WIDEN])
    second_ring = ci[C_SECOND_RING]
    hole_memory = ci[C_HOLE_MEMORY] == 1
    fresh = ci[C_TICKS_NB_FRESH]
    slots = nb.shape[1]
    best_err = FAR
    best_x = 0
    best_y = 0
    best_ts = 0
    # With site offsets a reference's expected reading is not d but its distance from the
    # site's centre; the window is tested on readings corrected by the difference.
    offsets_on = ci[C_OFFSETS] == 1
    pre_tol = pair_tol + OFFSET_PREFILTER_MM if offsets_on else pair_tol
    avoid_foreign = ci[C_AVOID_FOREIGN] == 1
    by_order = by_met_order(i, ri, ci)
    for a in range(slots):
        if nb[i, a, NB_ID] < 0 or not is_placed(nb[i, a, NB_STATE]):
            continue
        if nb[i, a, NB_LAST] < since or abs(nb_dist[i, a] - pair_aim) > pre_tol:
            continue
        if avoid_foreign and foreign(i, a, nb, gene_flag, ci):
            continue
        ax = nb[i, a, NB_TX]
        ay = nb[i, a, NB_TY]
        for b in range(a + 1, slots):
            if nb[i, b, NB_ID] < 0 or not is_placed(nb[i, b, NB_STATE]):
                continue
            if nb[i, b, NB_LAST] < since or abs(nb_dist[i, b] - pair_aim) > pre_tol:
                continue
            if avoid_foreign and foreign(i, b, nb, gene_flag, ci):
                continue
            if not offsets_on and not in_window(nb_dist[i, a], nb_dist[i, b], pair_aim, cf, scale):
                # Settle midway between the two references, not where the window opens.
                continue
            dx = nb[i, b, NB_TX] - ax
            dy = nb[i, b, NB_TY] - ay
            k = direction_index(dx, dy)
            outer_side = -1
            if k >= 0:
                # Lattice neighbours: the two sites next to both flank the edge a-b.
                s0 = (k + 5) % 6
                s1 = (k + 1) % 6
                # Orbiting clockwise from the one it came from towards the other, the
                # robot is on the outer side: left of a->b when it came from a.
                a_id = nb[i, a, NB_ID]
                b_id = nb[i, b, NB_ID]
                came = came_from(ref_id, from_id, a_id, b_id)
                if by_order and came == ref_id and from_id != a_id and from_id != b_id:
                    came = first_met(i, ri, a_id, b_id, came)
                if came >= 0 and came == nb[i, a, NB_ID]:
                    outer_side = 0
                elif came >= 0 and came == nb[i, b, NB_ID]:
                    outer_side = 1
                if outer_side >= 0 and orbit == 1:
                    outer_side = 1 - outer_side  # anticlockwise: the mirror image
            else:
                # Second ring (sqrt(3) d apart): the two sites next to both lie between
                # them, each at d from both. Where growth has squeezed a and b together
                # this pair still finds the site between them, just outside the notch.
                s0 = second_ring_side(dx, dy)
                if s0 < 0 or second_ring == 0:
                    continue
                s1 = (s0 + 1) % 6
            for side in range(2):
                kk = s0 if side == 0 else s1
                k2 = s1 if side == 0 else s0
                cx = ax + DIR_X[kk]
                cy = ay + DIR_Y[kk]
                c2x = ax + DIR_X[k2]
                c2y = ay + DIR_Y[k2]
                if gene_at(gene_flag, ci, cx, cy) != 1 or site_taken(i, cx, cy, nb):
                    continue
                if left_x != NO_SITE and (cx != left_x or cy != left_y):
                    continue  # every other memory holds the site it left: it takes that one
                if out_of_reach(i, ri, cx, cy, reach, cf):
                    continue  # it stands near its former site, not there
                dist_a = nb_dist[i, a]
                dist_b = nb_dist[i, b]
                if offsets_on:
                    dist_a += d - expected_distance(i, a, cx, cy, nb, ci, cf)
                    dist_b += d - expected_distance(i, b, cx, cy, nb, ci, cf)
                    if not in_window(dist_a, dist_b, pair_aim, cf, scale):
                        continue
                if hole_memory and is_held(held_i, cx, cy, ox, oy):
                    continue  # heard held before: its holder is elsewhere, the lattice torn
                # Keep the free sites reachable from outside; in a hole that is closed
                # already, a robot that got in may take any site.
                if not hole_memory and (
                    encloses_a_site(i, cx, cy, nb, gene_flag, ci)
                    or closes_a_hole(i, cx, cy, nb, gene_flag, ci)
                ) and open_from(i, cx, cy, 0, 0, False, nb, gene_flag, ci):
                    continue
                ruled_out_mirror = side == outer_side or site_taken(i, c2x, c2y, nb)
                ok = True
                err = 0.0
                worst = 0.0
                min_ts = -1
                n_adjacent = 0
                for j in range(slots):
                    if nb[i, j, NB_ID] < 0 or not is_placed(nb[i, j, NB_STATE]):
                        continue
                    if avoid_foreign and foreign(i, j, nb, gene_flag, ci):
                        # another remnant's robot: its tag is in the same frame, but it
                        # stands on a lattice of its own, so it says nothing of this site
                        continue
                    jx = nb[i, j, NB_TX]
                    jy = nb[i, j, NB_TY]
                    pred = expected_distance(i, j, cx, cy, nb, ci, cf)
                    if (
                        fold_skip > 0
                        and pred > fold_skip
                        and abs(nb_dist[i, j] - expected_distance(i, j, c2x, c2y, nb, ci, cf))
                        > consist_tol
                    ):
                        continue  # out of the site's range and not at the mirror: a fold
                    if nb[i, j, NB_LAST] >= since:
                        e = abs(nb_dist[i, j] - pred)
                        if e > consist_wide or (
                            pred < 1.2 * d and nb_dist[i, j] > d + ADJACENT_SLACK_MM
                        ):
                            ok = False
                            break
                        err += e
                        worst = max(worst, e)
                        pred2 = expected_distance(i, j, c2x, c2y, nb, ci, cf)
                        e2 = abs(nb_dist[i, j] - pred2)
                        if e2 > consist_tol and (mirror_margin <= 0 or e2 - e >= mirror_margin):
                            ruled_out_mirror = True
                        if direction_index(jx - cx, jy - cy) >= 0:
                            n_adjacent += 1
                    elif strict and pred < 1.2 * d:
                        # A lattice neighbour of the site must have been heard by now.
                        ok = False
                        break
                    if tick - nb[i, j, NB_LAST] > fresh:
                        continue
                    st = nb[i, j, NB_STATE]
                    own = st == STABLE and cx == left_x and cy == left_y
                    if (st == ACTIVE or own) and direction_index(jx - cx, jy - cy) >= 0:
                        ts = nb[i, j, NB_TS]
                        if min_ts < 0 or ts < min_ts:
                            min_ts = ts
                if ok and strict and reported_but_unheard(i, cx, cy, since, nb, gene_flag, ci):
                    ok = False
                if ok and tol_scale > plain_scale and n_adjacent < wide_min:
                    ok = worst <= consist_tol and in_window(
                        dist_a, dist_b, pair_aim, cf, plain_scale
                    )
                if ok and ruled_out_mirror and min_ts >= 0 and err < best_err:
                    if (
                        hole_memory
                        and shuts_in(cx, cy, held_i, ox, oy, gene_flag, ci)
                        and not taker_allows(i, tick, cx, cy, ri, held_i, ox, oy, gene_flag, ci)
                    ):
                        continue
                    # the playout is costly: only when a settled robot confirms its site
                    if (
                        strict
                        and hole_memory
                        and ci[C_FILL_LOOKAHEAD] == 1
                        and strands_a_site(cx, cy, held_i, ox, oy, gene_flag, ci)
                    ):
                        continue
                    best_err = err
                    best_x = cx
                    best_y = cy
                    best_ts = min_ts
    return best_err < FAR, best_x, best_y, best_ts
