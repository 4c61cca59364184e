"""Census by walking round the remnant (paper, Shape Regeneration, step 2; census ``walk``).

Once the election has made a robot Leader, it leaves its site and edge-follows the
remnant clockwise at about d from the nearest robot (every other robot stands still while
electing). On the way it records in its own memory (``walk_seen[i]``, a bitmap over the
gene grid) the tag of every placed robot it hears nearer than ``census_collect_mm``: the
robots on the remnant's periphery. Robots that hear a walking Leader's status message send
their own status (which carries their tag) every other message period for a while, so the
walker hears tags and not only election messages.

Coming back. The walker has left once a robot of one of its neighbouring sites (those
held when it set out, R_WALK_DIRS) has been out of earshot for ``GONE_TICKS``. After that
it is back when it localises onto its own tag as a searcher does on a site (paper Sec.
4.1): two robots of neighbouring sites at about d, every robot heard at the distance its
site predicts, and every robot of a neighbouring site heard again (else the mirror site
across two of them looks the same when a third is out of range). It stops, confirms with
readings taken standing still, and counts. Special sites:

- the tip of a line (one neighbour): that neighbour at about d, and every other robot
  heard (there may be none) within twice the pair tolerance of its predicted distance;
- a one-wide pocket (five neighbours held): the walk passes its mouth but cannot get back
  in, so the walker may stop on the doorstep (the free site in front of it) and take that
  site as its own;
- no neighbour: the Leader is alone and counts itself without walking.

Counting. The collected tags (its own included) are mapped onto the current target's
bitmap: the cells a lattice flood fill from the grid's border cannot reach without
crossing a collected tag form the closed area bounded by the remnant, and the 1-cells of
that area are the census count. A remnant with holes inside (robots removed in the middle)
is over-counted: the walk never sees the holes (the paper's method).

Failures. A walk longer than ``census_walk_timeout_s``, or a walker that hears nobody for
``LOST_TICKS``, counts what was collected so far, and the Leader gives up its tag (it is
not on its site), so the new target is grown without it as a seed. Three cases fall back
to the spanning-tree count (the Leader's subtree count when it was declared; the election
builds the tree anyway): a Leader hemmed in (``hemmed``: next to a hole inside the
remnant; it does not walk), one still not gone after ``STUCK_TICKS``, and a walk whose ring
of tags shuts in every free neighbouring site of the Leader's (it went round a hole, not
round the outside). The census event records how the census ended (``RESULT_NAMES``).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.algorithm.kernel_util import (
    DIR_X,
    DIR_Y,
    FAR,
    LEFT,
    RIGHT,
    STOP,
    direction_index,
    gene_at,
    is_placed,
    lattice_distance,
)
from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_MASK,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_CENSUS,
    R_ELECT_SINCE,
    R_HAS_TAG,
    R_REQUEST,
    R_SUBCOUNT,
    R_TAG_X,
    R_TAG_Y,
    R_WALK,
    R_WALK_DIRS,
    R_WALK_DOOR,
    R_WALK_END,
    R_WALK_GONE,
    R_WALK_HEARD,
    R_WALK_RESULT,
    R_WALK_SEEN,
    R_WALK_SINCE,
    R_WALK_SUB_SINCE,
    R_WALK_TAGS,
)
from etswarm.algorithm.params import (
    C_GENE_X0,
    C_GENE_Y0,
    C_TICKS_COOLDOWN,
    C_TICKS_MOVE_FRESH,
    C_TICKS_SETTLE,
    C_TICKS_WALK_MAX,
    F_BALANCE_TOL,
    F_CLEARANCE,
    F_CLOSING,
    F_CONSIST_TOL,
    F_FOLLOW_OFFSET,
    F_PAIR_TOL,
    F_SPACING,
    F_WALK_COLLECT,
)

# Walk phases (R_WALK).
WALK_NONE = 0
WALK_START = 1  # declared Leader; the walk begins at the next tick
WALK_OUT = 2  # edge-following round the remnant
WALK_SETTLE = 3  # stopped where it believes its site is; confirming
WALK_DONE = 4  # counted (R_CENSUS); waiting for its scaled target

# How a census ended (R_WALK_RESULT).
RESULT_NONE = 0
RESULT_TREE = 1  # spanning-tree count (census "tree")
RESULT_RETURNED = 2  # walked round and back onto its site
RESULT_TIMEOUT = 3  # walk took too long: count from the tags collected so far
RESULT_LOST = 4  # heard nobody for LOST_TICKS: count from the tags collected so far
RESULT_STUCK = 5  # never got away from its site in STUCK_TICKS: the tree count instead
RESULT_ENCLOSED = 6  # back, but its ring shuts its own free sites in: the tree count instead
RESULT_DOORSTEP = 7  # back on the free site in front of its pocket site, which it takes

#: Names of the results, indexed by code (for events and summaries).
RESULT_NAMES = ("none", "tree", "returned", "timeout", "lost", "stuck", "enclosed", "doorstep")

#: The walker has left once a robot of a neighbouring site is unheard this long (ticks).
GONE_TICKS = 31 * 5
#: Ticks a robot keeps sending its tag (every other period) after hearing a walker.
RELAY_TICKS = 31 * 15
#: The walker gives up after hearing nobody this long (ticks).
LOST_TICKS = 31 * 120
#: A walker still near its site after this long (ticks) is hemmed in.
STUCK_TICKS = 31 * 180


@njit(inline="always")
def walking(phase):  # type: ignore[no-untyped-def]
    """True while the Leader is away from (or settling back onto) its site."""
    return WALK_START <= phase <= WALK_SETTLE


@njit
def sends_tag(i, tick, ri):  # type: ignore[no-untyped-def]
    """An electing robot i alternates its election message with its status (tag) message:
    the walker itself, and robots that heard a walker in the last ``RELAY_TICKS``."""
    if walking(ri[i, R_WALK]):
        return True
    return ri[i, R_HAS_TAG] == 1 and tick - ri[i, R_WALK_SEEN] < RELAY_TICKS


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(_nrt=True)
def flood_outside(seen):  # type: ignore[no-untyped-def]
    """Cells reachable from the grid's border without crossing a collected tag.

    ``seen`` (GX, GY) uint8: 1 where a tag was collected (the walls). The flood fill runs
    over the six lattice directions from every border cell that is not a wall. Returns a
    (GX, GY) uint8 array, 1 outside.
    """
    gx_n, gy_n = seen.shape
    outside = np.zeros((gx_n, gy_n), dtype=np.uint8)
    stack = np.empty(gx_n * gy_n, dtype=np.int64)
    top = 0
    for gx in range(gx_n):
        for gy in range(gy_n):
            border = gx == 0 or gy == 0 or gx == gx_n - 1 or gy == gy_n - 1
            if border and seen[gx, gy] == 0:
                outside[gx, gy] = 1
                stack[top] = gx * gy_n + gy
                top += 1
    while top > 0:
        top -= 1
        gx = stack[top] // gy_n
        gy = stack[top] % gy_n
        for k in range(6):
            nx = gx + DIR_X[k]
            ny = gy + DIR_Y[k]
            if nx < 0 or ny < 0 or nx >= gx_n or ny >= gy_n:
                continue
            if outside[nx, ny] == 1 or seen[nx, ny] == 1:
                continue
            outside[nx, ny] = 1
            stack[top] = nx * gy_n + ny
            top += 1
    return outside


# takes flood_outside's array back: keeps reference counting (etswarm.sim.borrow)
@njit(_nrt=True)
def walk_count(seen, gene_flag):  # type: ignore[no-untyped-def]
    """Census count from the collected tags: the 1-cells of the closed area they bound.

    ``seen`` (GX, GY) uint8: the collected tags; ``gene_flag`` (GX, GY) uint8: the current
    target's bitmap on the same grid. The 1-cells that ``flood_outside`` does not reach
    (inside the ring of tags and on it) are counted.
    """
    outside = flood_outside(seen)
    count = 0
    for gx in range(gene_flag.shape[0]):
        for gy in range(gene_flag.shape[1]):
            if outside[gx, gy] == 0 and gene_flag[gx, gy] == 1:
                count += 1
    return count


# takes flood_outside's array back: keeps reference counting (etswarm.sim.borrow)
@njit(_nrt=True)
def opens_outside(seen, gx, gy, held):  # type: ignore[no-untyped-def]
    """A free neighbour site of grid cell (gx, gy) (bit k of ``held`` clear: no robot in
    lattice direction k) is outside the ring of ``seen`` tags: a walk that left from there
    went round the outside of the remnant (not round a hole inside it)."""
    outside = flood_outside(seen)
    for k in range(6):
        nx = gx + DIR_X[k]
        ny = gy + DIR_Y[k]
        if (held >> k) & 1 or nx < 0 or ny < 0 or nx >= seen.shape[0] or ny >= seen.shape[1]:
            continue
        if outside[nx, ny] == 1:
            return True
    return False


@njit
def mark_tag(i, x, y, seen, ci):  # type: ignore[no-untyped-def]
    """Record tag (x, y) in robot i's walk bitmap; True if it was new."""
    gx = x - ci[C_GENE_X0]
    gy = y - ci[C_GENE_Y0]
    if gx < 0 or gy < 0 or gx >= seen.shape[1] or gy >= seen.shape[2]:
        return False
    if seen[i, gx, gy] == 1:
        return False
    seen[i, gx, gy] = 1
    return True


@njit
def collect(i, tick, ri, nb, nb_dist, seen, ci, cf):  # type: ignore[no-untyped-def]
    """Record the tags of the placed robots heard this tick nearer than the collect
    distance (their tags come from their status messages)."""
    near = cf[F_WALK_COLLECT]
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or nb[i, m, NB_LAST] != tick:
            continue
        if not is_placed(nb[i, m, NB_STATE]) or nb_dist[i, m] >= near:
            continue
        if mark_tag(i, nb[i, m, NB_TX], nb[i, m, NB_TY], seen, ci):
            ri[i, R_WALK_TAGS] += 1


@njit
def unheard(i, tick, x, y, dirs, nb):  # type: ignore[no-untyped-def]
    """A robot of a neighbouring site of (x, y) (bit k of ``dirs``: the site in direction
    k) has not been heard for ``GONE_TICKS`` (it is out of radio range, over 70 mm away),
    or is no longer in robot i's table."""
    for k in range(6):
        if not (dirs >> k) & 1:
            continue
        last = -1
        for m in range(nb.shape[1]):
            if nb[i, m, NB_ID] < 0 or not is_placed(nb[i, m, NB_STATE]):
                continue
            if nb[i, m, NB_TX] == x + DIR_X[k] and nb[i, m, NB_TY] == y + DIR_Y[k]:
                last = max(last, nb[i, m, NB_LAST])
        if last < 0 or tick - last > GONE_TICKS:
            return True
    return False


@njit
def gone(i, tick, ri, nb):  # type: ignore[no-untyped-def]
    """Robot i has really left its site: a robot of one of its neighbouring sites when the
    walk began (R_WALK_DIRS) is out of earshot, and so is one of the doorstep's (when its
    site is a pocket: on the doorstep some of the site's neighbours are out of range)."""
    if not unheard(i, tick, ri[i, R_TAG_X], ri[i, R_TAG_Y], ri[i, R_WALK_DIRS], nb):
        return False
    found, x, y, door_dirs = doorstep(ri, i)
    return not found or unheard(i, tick, x, y, door_dirs, nb)


@njit
def site_neighbours(i, since, ri, nb):  # type: ignore[no-untyped-def]
    """Bit mask of the lattice directions k in which robot i heard, since ``since``, a
    placed robot on the neighbouring site of its own."""
    hx = ri[i, R_TAG_X]
    hy = ri[i, R_TAG_Y]
    dirs = 0
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or nb[i, m, NB_LAST] < since or not is_placed(nb[i, m, NB_STATE]):
            continue
        k = direction_index(nb[i, m, NB_TX] - hx, nb[i, m, NB_TY] - hy)
        if k >= 0:
            dirs |= 1 << k
    return dirs


@njit
def hemmed(i, ri, nb, dirs):  # type: ignore[no-untyped-def]
    """Robot i cannot get out of its site: at most one neighbouring site s is free (bit
    clear in ``dirs``), and the two held sites on either side of s report (neighbour-site
    bits of their status) the sites beyond s held as well, so s is a pocket (a hole inside
    the remnant, or a dent one body wide)."""
    free = -1
    for k in range(6):
        if not (dirs >> k) & 1:
            if free >= 0:
                return False
            free = k
    if free < 0:
        return True
    hx = ri[i, R_TAG_X]
    hy = ri[i, R_TAG_Y]
    beyond = 0
    for side in range(2):
        kk = (free + 5) % 6 if side == 0 else (free + 1) % 6
        for m in range(nb.shape[1]):
            if nb[i, m, NB_ID] < 0 or not is_placed(nb[i, m, NB_STATE]):
                continue
            if nb[i, m, NB_TX] == hx + DIR_X[kk] and nb[i, m, NB_TY] == hy + DIR_Y[kk]:
                # Seen from that neighbour, the site beyond s lies in direction ``free``.
                beyond += (nb[i, m, NB_MASK] >> free) & 1
                break
    return beyond == 2


@njit
def at_tag(i, since, x, y, dirs, pair_tol, nb, nb_dist, cf):  # type: ignore[no-untyped-def]
    """Robot i localises onto tag (x, y) from the placed robots heard since ``since``.

    Every neighbouring site in ``dirs`` (bit k: a robot holds (x, y) + direction k) has
    been heard from, and every robot heard is at the distance its tag predicts (within
    the consistency tolerance): this tells the site from its mirror across two of its
    neighbours. Two of the neighbours are at d within ``pair_tol`` (mm; and within the
    balance tolerance of each other). A site with one neighbour (the tip of a line, where
    the others may be out of range) needs that one at d within ``pair_tol`` and every
    robot heard within twice that: it places the robot within ~20 mm.
    """
    d = cf[F_SPACING]
    single = dirs != 0 and dirs & (dirs - 1) == 0
    tol = 2.0 * pair_tol if single else cf[F_CONSIST_TOL]
    heard = 0
    pairs = 0
    lo = FAR
    hi = -FAR
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or nb[i, m, NB_LAST] < since or not is_placed(nb[i, m, NB_STATE]):
            continue
        pred = lattice_distance(x, y, nb[i, m, NB_TX], nb[i, m, NB_TY]) * d
        err = abs(nb_dist[i, m] - pred)
        if err > tol:
            return False
        k = direction_index(nb[i, m, NB_TX] - x, nb[i, m, NB_TY] - y)
        if k < 0:
            continue
        heard |= 1 << k
        if err <= pair_tol:
            pairs += 1
            lo = min(lo, nb_dist[i, m])
            hi = max(hi, nb_dist[i, m])
    if dirs & ~heard:
        return False
    if single:
        return pairs >= 1
    return pairs >= 2 and hi - lo <= cf[F_BALANCE_TOL]


@njit
def doorstep(ri, i):  # type: ignore[no-untyped-def]
    """The free site in front of robot i's site when that site is a one-wide pocket (five
    of its neighbouring sites held: the walk passes its mouth but cannot get back in).

    Returns ``(found, x, y, dirs)``: the site and its held neighbouring sites as bits.
    """
    hx = ri[i, R_TAG_X]
    hy = ri[i, R_TAG_Y]
    dirs = ri[i, R_WALK_DIRS]
    free = -1
    for k in range(6):
        if not (dirs >> k) & 1:
            if free >= 0:
                return False, 0, 0, 0
            free = k
    if free < 0:
        return False, 0, 0, 0
    x = hx + DIR_X[free]
    y = hy + DIR_Y[free]
    door_dirs = 0
    for q in range(6):
        j = direction_index(x + DIR_X[q] - hx, y + DIR_Y[q] - hy)
        if j >= 0 and (dirs >> j) & 1:
            door_dirs |= 1 << q
    return True, x, y, door_dirs


@njit
def back(i, since, ri, nb, nb_dist, cf):  # type: ignore[no-untyped-def]
    """Where robot i is back: 1 on its own site, 2 on the doorstep of its pocket site
    (``doorstep``), 0 neither."""
    pair_tol = cf[F_PAIR_TOL]
    hx = ri[i, R_TAG_X]
    hy = ri[i, R_TAG_Y]
    if at_tag(i, since, hx, hy, ri[i, R_WALK_DIRS], pair_tol, nb, nb_dist, cf):
        return 1
    found, x, y, door_dirs = doorstep(ri, i)
    # The doorstep's two held neighbours are not adjacent (1.7 d apart), so the shape's
    # own placement errors add up there: twice the pair tolerance.
    if found and at_tag(i, since, x, y, door_dirs, 2.0 * pair_tol, nb, nb_dist, cf):
        return 2
    return 0


@njit
def orbit(i, tick, nb, nb_dist, motor, ci, cf):  # type: ignore[no-untyped-def]
    """Edge-follow clockwise at about d from the nearest robot heard (every robot of the
    remnant stands still during the census); returns False when nobody was heard lately.

    Same rule as a searcher's: pivot away from the group when the last reading of the
    nearest robot is under the aim, towards it otherwise, and away from any robot that
    may have come nearer than the clearance.
    """
    steer_fresh = ci[C_TICKS_MOVE_FRESH]
    closing = cf[F_CLOSING]
    nearest_est = FAR
    reading = FAR
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or tick - nb[i, m, NB_LAST] > steer_fresh:
            continue
        est = nb_dist[i, m] - closing * (tick - nb[i, m, NB_LAST])
        if est < nearest_est:
            nearest_est = est
            reading = nb_dist[i, m]
    if nearest_est >= FAR:
        motor[i] = RIGHT
        return False
    if nearest_est < cf[F_CLEARANCE] or reading < cf[F_SPACING] + cf[F_FOLLOW_OFFSET]:
        motor[i] = LEFT
    else:
        motor[i] = RIGHT
    return True


@njit
def conclude(i, tick, ri, motor, seen, gene_flag, ci, result, stop):  # type: ignore[no-untyped-def]
    """Count and ask for the scaled target (as the tree census does): from the collected
    tags, or with the tree count when the walk failed without leaving (stuck) or went
    round a hole instead of the outside (enclosed). A walker on the doorstep of its pocket
    site takes the doorstep as its site; one that is lost or out of time gives up its tag.
    """
    motor[i] = STOP
    gx = ri[i, R_TAG_X] - ci[C_GENE_X0]
    gy = ri[i, R_TAG_Y] - ci[C_GENE_Y0]
    back_home = result in (RESULT_RETURNED, RESULT_DOORSTEP)
    if back_home and not opens_outside(seen[i], gx, gy, ri[i, R_WALK_DIRS]):
        result = RESULT_ENCLOSED
    if result in (RESULT_STUCK, RESULT_ENCLOSED):
        ri[i, R_CENSUS] = ri[i, R_SUBCOUNT]
    else:
        ri[i, R_CENSUS] = walk_count(seen[i], gene_flag)
    ri[i, R_WALK] = WALK_DONE
    ri[i, R_WALK_END] = tick
    ri[i, R_WALK_RESULT] = result
    if result in (RESULT_TIMEOUT, RESULT_LOST):
        ri[i, R_HAS_TAG] = 0
    elif result == RESULT_DOORSTEP:
        # It stands on the doorstep: that is its site now (if the shape has it), and its
        # old one is empty.
        seen[i, gx, gy] = 0
        found, x, y, _ = doorstep(ri, i)
        if found and gene_at(gene_flag, ci, x, y) == 1:
            ri[i, R_TAG_X] = x
            ri[i, R_TAG_Y] = y
            mark_tag(i, x, y, seen, ci)
        else:
            ri[i, R_HAS_TAG] = 0
    ri[i, R_REQUEST] = 1
    stop[0] = 1


@njit
def walk_rule(i, tick, ri, nb, nb_dist, motor, seen, gene_flag, ci, cf, stop):  # type: ignore[no-untyped-def]
    """One tick of the Leader's census walk (runs every tick while ``walking``).

    ``seen`` (N, GX, GY) uint8 holds every robot's collected tags; ``gene_flag`` (GX, GY)
    is the current target's bitmap. Sets ``motor[i]``; on conclusion R_CENSUS, R_REQUEST
    = 1 and the stop flag (as the tree census).
    """
    phase = ri[i, R_WALK]
    if phase == WALK_START:
        seen[i, :, :] = 0
        ri[i, R_WALK_TAGS] = 0
        mark_tag(i, ri[i, R_TAG_X], ri[i, R_TAG_Y], seen, ci)
        ri[i, R_WALK] = WALK_OUT
        ri[i, R_WALK_SINCE] = tick
        ri[i, R_WALK_SUB_SINCE] = tick
        ri[i, R_WALK_GONE] = 0
        ri[i, R_WALK_HEARD] = tick
        ri[i, R_WALK_DIRS] = site_neighbours(i, ri[i, R_ELECT_SINCE], ri, nb)
        phase = WALK_OUT
        dirs = ri[i, R_WALK_DIRS]
        if dirs == 0:
            conclude(i, tick, ri, motor, seen, gene_flag, ci, RESULT_RETURNED, stop)
            return
        if hemmed(i, ri, nb, dirs):
            conclude(i, tick, ri, motor, seen, gene_flag, ci, RESULT_STUCK, stop)
            return
    collect(i, tick, ri, nb, nb_dist, seen, ci, cf)
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] >= 0 and nb[i, m, NB_LAST] == tick:
            ri[i, R_WALK_HEARD] = tick
            break
    if tick - ri[i, R_WALK_SINCE] > ci[C_TICKS_WALK_MAX]:
        conclude(i, tick, ri, motor, seen, gene_flag, ci, RESULT_TIMEOUT, stop)
        return
    if tick - ri[i, R_WALK_HEARD] > LOST_TICKS:
        conclude(i, tick, ri, motor, seen, gene_flag, ci, RESULT_LOST, stop)
        return
    if phase == WALK_SETTLE:
        motor[i] = STOP
        if tick - ri[i, R_WALK_SUB_SINCE] < ci[C_TICKS_SETTLE]:
            return
        where = back(i, ri[i, R_WALK_SUB_SINCE], ri, nb, nb_dist, cf)
        if where == 1 or (where == 2 and ri[i, R_WALK_DOOR] == 1):
            result = RESULT_RETURNED if where == 1 else RESULT_DOORSTEP
            conclude(i, tick, ri, motor, seen, gene_flag, ci, result, stop)
            return
        ri[i, R_WALK] = WALK_OUT
        ri[i, R_WALK_SUB_SINCE] = tick
        phase = WALK_OUT
    if ri[i, R_WALK_GONE] == 0:
        if gone(i, tick, ri, nb):
            ri[i, R_WALK_GONE] = 1
        elif tick - ri[i, R_WALK_SINCE] > STUCK_TICKS:
            conclude(i, tick, ri, motor, seen, gene_flag, ci, RESULT_STUCK, stop)
            return
    elif tick - ri[i, R_WALK_SUB_SINCE] >= ci[C_TICKS_COOLDOWN]:
        where = back(i, tick - ci[C_TICKS_MOVE_FRESH], ri, nb, nb_dist, cf)
        if where > 0:
            motor[i] = STOP
            ri[i, R_WALK] = WALK_SETTLE
            ri[i, R_WALK_SUB_SINCE] = tick
            ri[i, R_WALK_DOOR] = 1 if where == 2 else 0
            return
    orbit(i, tick, nb, nb_dist, motor, ci, cf)
