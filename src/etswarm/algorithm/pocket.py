"""Pocket capture: a searcher takes a free site from the robots all round it, where the
lattice has stretched too far for the paper's two-reference window.

Placement errors add up as a shape grows, and now and then a free region is left whose
surrounding robots stand 50-75 mm from its sites instead of d: no two of them are ever
at d from a searcher, so ``localise.find_site`` never fires, though searchers cross the
region again and again. A robot standing inside such a pocket hears every placed robot
of the site's neighbour sites, each nearer than ``POCKET_REACH_MM``; standing anywhere
else, it is farther from at least one of them. So a searcher that has been at the shape
for ``POCKET_AFTER_TICKS`` takes free site c when:

- at least ``POCKET_MIN_NEIGHBOURS`` neighbour sites of c are held by placed robots it has
  heard since ``since``, and every robot it knows of on a neighbour site (in its table or
  its memory of held sites) was heard since then, each nearer than ``POCKET_REACH_MM`` and
  not nearer than a body (``POCKET_NEAR_MM``);
- no placed robot heard since then is nearer than its lattice distance from c predicts by
  more than the consistency tolerance (it is not standing on another site);
- c has the least farthest-neighbour reading of all such candidates, by at least
  ``POCKET_MARGIN_MM`` (between two free sites it would be unsure, and moves on);
- the usual rules hold: gene flag 1, not known held, an Active neighbour (the least TS
  among them is its own TS - 1), no hole closed (``site_memory.shuts_in``).

With ``ETParams.pocket = "located"`` (after damage only) the second and third conditions
are replaced: the searcher fixes where it stands by least squares on its readings of the
placed robots in range (``offsets.locate``, from where they report they stand) and takes
c when the fix lies within ``LOCATED_TOL_MM`` of c's centre and leaves no reading more
than ``LOCATED_RESIDUAL_MM`` out (``located_score``). A searcher orbiting a stretched
notch at d from its nearest robot is never in the middle, where the farthest-reading
test wants it, but its fix can land on the site (traced on starfish ``split y=mid`` seed
18: within 3.5-6 mm of (-2, -5)'s centre, no reading more than 16 mm out).
"""

from __future__ import annotations

import math

from numba import njit

from etswarm.algorithm.kernel_util import (
    ACTIVE,
    DIR_X,
    DIR_Y,
    FAR,
    direction_index,
    gene_at,
    is_placed,
    lattice_distance,
)
from etswarm.algorithm.memory import NB_ID, NB_LAST, NB_STATE, NB_TS, NB_TX, NB_TY
from etswarm.algorithm.offsets import (
    anchor_x,
    anchor_y,
    is_anchor,
    locate,
    site_x,
    site_y,
)
from etswarm.algorithm.params import (
    C_POCKET,
    C_TICKS_NB_FRESH,
    F_CONSIST_TOL,
    F_SPACING,
    POCKET_LOCATED,
)
from etswarm.algorithm.site_memory import is_held, shuts_in, site_taken

#: A searcher may use pocket capture after this many ticks at the shape (10 minutes).
POCKET_AFTER_TICKS = 31 * 600
#: Every placed neighbour of the site must be heard nearer than this (mm).
POCKET_REACH_MM = 76.0
#: ... and not nearer than this (mm): a body's width and a little.
POCKET_NEAR_MM = 30.0
#: The site needs this many placed neighbours heard (a pocket, not an edge).
POCKET_MIN_NEIGHBOURS = 3
#: The best site's farthest neighbour must be nearer than the next best's by this (mm).
POCKET_MARGIN_MM = 10.0
#: With ``pocket = "located"``: the robot's least-squares position must lie this near
#: (mm) the site's centre ...
LOCATED_TOL_MM = 8.0
#: ... and leave no reading of a placed robot in range more than this (mm) out.
LOCATED_RESIDUAL_MM = 20.0


@njit
def ring_reading(i, cx, cy, since, nb, nb_dist, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """The farthest reading (mm) of the placed robots of (cx, cy)'s neighbour sites that
    robot i heard since ``since``, or FAR when it does not stand inside their ring: fewer
    than ``POCKET_MIN_NEIGHBOURS`` of them, one it knows of there (in its table, or in its
    memory ``held_i`` of held sites) not heard since then, or one nearer than a body or
    beyond ``POCKET_REACH_MM``."""
    farthest = 0.0
    n_heard = 0
    heard_dirs = 0
    for j in range(nb.shape[1]):
        if nb[i, j, NB_ID] < 0 or not is_placed(nb[i, j, NB_STATE]):
            continue
        k = direction_index(nb[i, j, NB_TX] - cx, nb[i, j, NB_TY] - cy)
        if k < 0:
            continue
        if nb[i, j, NB_LAST] < since:
            return FAR  # a neighbour of the site it no longer hears: not inside
        reading = nb_dist[i, j]
        if reading > POCKET_REACH_MM or reading < POCKET_NEAR_MM:
            return FAR
        farthest = max(farthest, reading)
        n_heard += 1
        heard_dirs |= 1 << k
    if n_heard < POCKET_MIN_NEIGHBOURS:
        return FAR
    for k in range(6):
        if not (heard_dirs >> k) & 1 and is_held(held_i, cx + DIR_X[k], cy + DIR_Y[k], ox, oy):
            return FAR  # part of the ring round the site is held but not near: not inside
    return farthest


@njit
def pocket_score(i, cx, cy, since, nb, nb_dist, cf, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """The farthest reading (mm) of the ring round (cx, cy) (``ring_reading``), or FAR when
    the site is no pocket for robot i (see module): it stands outside the ring, or a
    placed robot it heard since ``since`` that holds no neighbour site reads nearer than
    its lattice distance from the site allows."""
    farthest = ring_reading(i, cx, cy, since, nb, nb_dist, held_i, ox, oy)
    if farthest >= FAR:
        return FAR
    d = cf[F_SPACING]
    consist_tol = cf[F_CONSIST_TOL]
    for j in range(nb.shape[1]):
        if nb[i, j, NB_ID] < 0 or not is_placed(nb[i, j, NB_STATE]):
            continue
        if nb[i, j, NB_LAST] < since:
            continue
        jx = nb[i, j, NB_TX]
        jy = nb[i, j, NB_TY]
        if direction_index(jx - cx, jy - cy) >= 0:
            continue
        if nb_dist[i, j] < lattice_distance(cx, cy, jx, jy) * d - consist_tol:
            return FAR
    return farthest


@njit
def located_score(i, cx, cy, since, nb, nb_dist, cf, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """How far (mm) from the centre of free site (cx, cy) robot i stands by least squares on
    its readings since ``since`` of the placed robots round it (``offsets.locate``, from
    where they report they stand), or FAR when it stands outside their ring
    (``ring_reading``) or the fit leaves a reading of a placed robot in range more than
    ``LOCATED_RESIDUAL_MM`` out."""
    if ring_reading(i, cx, cy, since, nb, nb_dist, held_i, ox, oy) >= FAR:
        return FAR
    d = cf[F_SPACING]
    px0 = site_x(cx, cy, d)
    py0 = site_y(cy, d)
    ok, px, py = locate(i, since, px0, py0, nb, nb_dist, d)
    if not ok:
        return FAR
    for j in range(nb.shape[1]):
        if not is_anchor(i, j, since, nb, nb_dist):
            continue
        ex = px - anchor_x(i, j, nb, d)
        ey = py - anchor_y(i, j, nb, d)
        if abs(nb_dist[i, j] - math.sqrt(ex * ex + ey * ey)) > LOCATED_RESIDUAL_MM:
            return FAR
    return math.sqrt((px - px0) ** 2 + (py - py0) ** 2)


@njit
def min_active_ts(i, tick, cx, cy, nb, ci):  # type: ignore[no-untyped-def]
    """Least TS of the Active robots of (cx, cy)'s neighbour sites heard lately (-1: none)."""
    fresh = ci[C_TICKS_NB_FRESH]
    best = -1
    for j in range(nb.shape[1]):
        if nb[i, j, NB_ID] < 0 or nb[i, j, NB_STATE] != ACTIVE:
            continue
        if tick - nb[i, j, NB_LAST] > fresh:
            continue
        if direction_index(nb[i, j, NB_TX] - cx, nb[i, j, NB_TY] - cy) < 0:
            continue
        ts = nb[i, j, NB_TS]
        if best < 0 or ts < best:
            best = ts
    return best


@njit
def pocket_site(i, tick, since, nb, nb_dist, gene_flag, ci, cf, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Find the free site whose pocket robot i stands in (see module). ``held_i`` (WX, WY)
    is its memory of held sites with window origin at tag (ox, oy).

    Returns ``(found, x, y, min_active_ts)``.
    """
    best = FAR
    second = FAR
    best_x = 0
    best_y = 0
    slots = nb.shape[1]
    located = ci[C_POCKET] == POCKET_LOCATED
    for a in range(slots):
        if nb[i, a, NB_ID] < 0 or not is_placed(nb[i, a, NB_STATE]):
            continue
        if nb[i, a, NB_LAST] < since or nb_dist[i, a] > POCKET_REACH_MM:
            continue
        for k in range(6):
            cx = nb[i, a, NB_TX] + DIR_X[k]
            cy = nb[i, a, NB_TY] + DIR_Y[k]
            if cx == best_x and cy == best_y and best < FAR:
                continue  # met again from another neighbour
            if gene_at(gene_flag, ci, cx, cy) != 1 or site_taken(i, cx, cy, nb):
                continue
            if is_held(held_i, cx, cy, ox, oy):
                continue
            if located:
                score = located_score(i, cx, cy, since, nb, nb_dist, cf, held_i, ox, oy)
                if score > LOCATED_TOL_MM:
                    score = FAR
            else:
                score = pocket_score(i, cx, cy, since, nb, nb_dist, cf, held_i, ox, oy)
            if score >= FAR:
                continue
            if score < best:
                if best < FAR and (best_x != cx or best_y != cy):
                    second = best
                best = score
                best_x = cx
                best_y = cy
            elif (cx != best_x or cy != best_y) and score < second:
                second = score
    if best >= FAR or second - best < POCKET_MARGIN_MM:
        return False, 0, 0, -1
    ts = min_active_ts(i, tick, best_x, best_y, nb, ci)
    if ts < 0 or shuts_in(best_x, best_y, held_i, ox, oy, gene_flag, ci):
        return False, 0, 0, -1
    return True, best_x, best_y, ts
