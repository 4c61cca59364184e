"""A searching robot's memory of the sites it has heard held, and the hole test on it.

A searcher orbits the growing shape and hears, one after another, most of the robots on
its edge; each status message also reports which of the sender's six neighbour sites are
held. The robot keeps all of it in a bitmap over the target's tags (Kilobot-sized: one
byte per site of a window round the shape), so that before it takes a site it can check
the whole shape for a hole, not just the few sites round it that it hears at that moment.

Memory of robot i: ``held[i]``, (WX, WY) uint8, ``held[i, x - ox, y - oy]`` = 1 when robot
i heard, while searching for its current target, a placed robot at tag (x, y) or one that
reported (x, y) held. The window origin ``(ox, oy)`` of a target (``slot_info`` fields
SLOT_WX, SLOT_WY) is one step below and left of its least tags, so every site of the
shape and its neighbours fit; tags outside the window are never remembered. The memory
is cleared when the robot starts searching for a new target epoch (``R_HELD_EPOCH``).
Placed robots do not leave their sites within an epoch, so what was heard stays true
until damage, and damage starts a new epoch. ``site_taken`` is the narrower knowledge of
the neighbour table alone (robots heard lately and the sites they report held).

With ``held_gossip_every`` > 0 placed robots keep their memory once they have taken a site
and pass it on (``encode_held``, ``merge_held``): every few transmit periods a placed robot
sends one 40-site chunk of it, with its own tag marked, and every robot of the same epoch
that hears the chunk adds it to its own memory. Held sites only accumulate within an
epoch, so the memories converge on the shape's held sites, hop by hop, well beyond what any
one searcher hears. Where the lattice has bent far enough that two growth fronts would
carry the same tag out of each other's earshot, the second front learns that the tag is
held before it takes it.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, direction_index, gene_at, is_placed
from etswarm.algorithm.memory import (
    HOLE_FLAG,
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_MASK,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_EPOCH,
    R_HELD_EPOCH,
    R_LEFT,
    R_LEFT_X,
    R_LEFT_Y,
    R_TAG_X,
    R_TAG_Y,
)
from etswarm.algorithm.messages import CHUNK_FIRST_BYTE, CHUNK_SITES, EPOCH_SHIFT, MSG_HELD
from etswarm.algorithm.params import C_WAY_END

#: A free site must keep this many consecutive free neighbour sites to stay reachable
#: by a robot that keeps about d from every placed robot.
OPENING_SITES = 2


@njit
def site_taken(i, x, y, nb):  # type: ignore[no-untyped-def]
    """Robot i knows that site (x, y) is held: a placed robot in its table holds it (placed
    robots stay put), or a placed robot next to it reports that neighbour site held."""
    for j in range(nb.shape[1]):
        if nb[i, j, NB_ID] < 0 or not is_placed(nb[i, j, NB_STATE]):
            continue
        jx = nb[i, j, NB_TX]
        jy = nb[i, j, NB_TY]
        if jx == x and jy == y:
            return True
        k = direction_index(x - jx, y - jy)
        if k >= 0 and (nb[i, j, NB_MASK] >> k) & 1:
            return True
    return False


@njit(inline="always")
def forget_left_site(held_i, ri, i, ox, oy):  # type: ignore[no-untyped-def]
    """Searcher i that left its site (``R_LEFT``) clears that site from its memory of held
    sites ((WX, WY) at tag (ox, oy)), which gossip keeps refilling."""
    if ri[i, R_LEFT] != 1:
        return
    wx = ri[i, R_LEFT_X] - ox
    wy = ri[i, R_LEFT_Y] - oy
    if 0 <= wx < held_i.shape[0] and 0 <= wy < held_i.shape[1]:
        held_i[wx, wy] = 0


@njit(inline="always")
def mark(held_i, x, y, ox, oy):  # type: ignore[no-untyped-def]
    """Set tag (x, y) in one robot's window ``held_i`` (WX, WY) if it lies inside."""
    wx = x - ox
    wy = y - oy
    if 0 <= wx < held_i.shape[0] and 0 <= wy < held_i.shape[1]:
        held_i[wx, wy] = 1


@njit(inline="always")
def is_held(held_i, x, y, ox, oy):  # type: ignore[no-untyped-def]
    """Tag (x, y) is remembered held (tags outside the window are not)."""
    wx = x - ox
    wy = y - oy
    if 0 <= wx < held_i.shape[0] and 0 <= wy < held_i.shape[1]:
        return held_i[wx, wy] != 0
    return False


@njit(inline="always")
def memory_of_epoch(i, ri, held):  # type: ignore[no-untyped-def]
    """Robot i's memory ``held[i]`` ((WX, WY) uint8) for its current target epoch: a
    memory kept for another epoch is cleared first."""
    held_i = held[i]
    if ri[i, R_HELD_EPOCH] != ri[i, R_EPOCH] + 1:
        held_i[:, :] = 0
        ri[i, R_HELD_EPOCH] = ri[i, R_EPOCH] + 1
    return held_i


@njit
def merge_held(i, k, ri, in_type, in_data, held, signature):  # type: ignore[no-untyped-def]
    """File held-sites message k of robot i's inbox (layout in ``messages``): when it was
    sent for robot i's target (its epoch, and ``signature``, ``target_signature`` of i's
    target), add its sites to i's memory."""
    if (np.int64(in_type[i, k]) >> EPOCH_SHIFT) != (ri[i, R_EPOCH] & 31):
        return
    if np.int64(in_data[i, k, 3]) != signature:
        return  # another remnant's target, over another memory window
    held_i = memory_of_epoch(i, ri, held)
    wy_n = held_i.shape[1]
    size = held_i.shape[0] * wy_n
    base = np.int64(in_data[i, k, 2]) * CHUNK_SITES
    for byte in range(CHUNK_SITES // 8):
        bits = np.int64(in_data[i, k, CHUNK_FIRST_BYTE + byte])
        if bits == 0:
            continue
        for b in range(8):
            site = base + 8 * byte + b
            if (bits >> b) & 1 and site < size:
                held_i[site // wy_n, site % wy_n] = 1


@njit(inline="always")
def gossip_due(tick, every, period):  # type: ignore[no-untyped-def]
    """A placed robot sends a chunk of its memory during every ``every``-th window of
    ``period`` ticks (one transmit period) instead of its status (``every`` 0: never)."""
    if every <= 0:
        return False
    return (tick // period) % every == every - 1


@njit
def encode_held(i, tick, every, period, ri, nb, held, ox, oy, signature, out_type, out_data):  # type: ignore[no-untyped-def]
    """Write a held-sites message of placed robot i (layout in ``messages``) into its
    outgoing buffers, after marking in its memory its own tag and what its table tells of
    its placed neighbours (``(ox, oy)``: its target's window origin; ``signature``: its
    target's ``target_signature``). The chunk sent turns
    with the gossip windows (``gossip_due``) and skips chunks with no site held, so a
    memory of a few held sites spreads as fast as a full one."""
    held_i = memory_of_epoch(i, ri, held)
    mark(held_i, ri[i, R_TAG_X], ri[i, R_TAG_Y], ox, oy)
    for m in range(nb.shape[1]):
        mark_row(held_i, i, m, ri[i, R_EPOCH], nb, ox, oy)  # its neighbours, the front
    flat = held_i.reshape(held_i.size)
    size = flat.size
    # the chunk index is one byte: a window of more sites passes on its first 256 chunks
    n_chunks = min((size + CHUNK_SITES - 1) // CHUNK_SITES, 256)
    start = (tick // (period * every) + i) % n_chunks
    out_type[i] = MSG_HELD | ((ri[i, R_EPOCH] & 31) << EPOCH_SHIFT)
    out_data[i, 3] = signature
    for step in range(n_chunks):
        chunk = (start + step) % n_chunks
        base = chunk * CHUNK_SITES
        if not flat[base:min(base + CHUNK_SITES, size)].any():
            continue
        for byte in range(CHUNK_SITES // 8):
            bits = 0
            for b in range(8):
                site = base + 8 * byte + b
                if site < size and flat[site]:
                    bits |= 1 << b
            out_data[i, CHUNK_FIRST_BYTE + byte] = bits
        out_data[i, 2] = chunk
        return
    out_data[i, 2] = start  # nothing held in the window (its tag lies outside it)
    out_data[i, CHUNK_FIRST_BYTE:] = 0


@njit(inline="always")
def mark_row(held_i, i, m, epoch, nb, ox, oy):  # type: ignore[no-untyped-def]
    """Mark in ``held_i`` the tag of the robot in row m of robot i's table and the
    neighbour sites its status reports held, when it is placed and works for ``epoch``."""
    if nb[i, m, NB_ID] < 0 or not is_placed(nb[i, m, NB_STATE]) or nb[i, m, NB_EPOCH] != epoch:
        return
    x = nb[i, m, NB_TX]
    y = nb[i, m, NB_TY]
    mark(held_i, x, y, ox, oy)
    bits = nb[i, m, NB_MASK]
    for k in range(6):
        if (bits >> k) & 1:
            mark(held_i, x + DIR_X[k], y + DIR_Y[k], ox, oy)


@njit
def remember_heard(i, tick, ri, nb, held, ox, oy):  # type: ignore[no-untyped-def]
    """Add to robot i's memory the placed robots of its target epoch heard this tick:
    their tags and the neighbour sites their status reports held. A memory of another
    epoch is cleared first."""
    held_i = memory_of_epoch(i, ri, held)
    for m in range(nb.shape[1]):
        if nb[i, m, NB_LAST] == tick:
            mark_row(held_i, i, m, ri[i, R_EPOCH], nb, ox, oy)


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(_nrt=True)
def flood_from(sx, sy, held_i, ox, oy, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Breadth-first from site (sx, sy) over the sites not remembered held that are on the
    shape or in one of its holes (``HOLE_FLAG``): (exits, free_sites). ``exits``: the flood
    reaches the outside of the shape (where searching robots come from) or the window's
    edge (assumed open); ``free_sites``: the free shape sites it crossed ((sx, sy)
    included; all of its region's when it does not exit, else those up to the exit).
    Unknown sites count as free. (WX, WY) scratch."""
    wx_n = held_i.shape[0]
    wy_n = held_i.shape[1]
    if not (0 <= sx - ox < wx_n and 0 <= sy - oy < wy_n):
        return True, False
    seen = np.zeros((wx_n, wy_n), dtype=np.uint8)
    queue_x = np.empty(wx_n * wy_n, dtype=np.int64)
    queue_y = np.empty(wx_n * wy_n, dtype=np.int64)
    seen[sx - ox, sy - oy] = 1
    free_sites = 1 if gene_at(gene_flag, ci, sx, sy) == 1 else 0
    queue_x[0] = sx
    queue_y[0] = sy
    head = 0
    tail = 1
    while head < tail:
        qx = queue_x[head]
        qy = queue_y[head]
        head += 1
        for k in range(6):
            nx = qx + DIR_X[k]
            ny = qy + DIR_Y[k]
            flag = gene_at(gene_flag, ci, nx, ny)
            if flag != 1 and flag != HOLE_FLAG:
                return True, free_sites
            wx = nx - ox
            wy = ny - oy
            if not (0 <= wx < wx_n and 0 <= wy < wy_n):
                return True, free_sites  # beyond the window: assume the way open
            if seen[wx, wy] or held_i[wx, wy]:
                continue
            seen[wx, wy] = 1
            if flag == 1:
                free_sites += 1
            queue_x[tail] = nx
            queue_y[tail] = ny
            tail += 1
    return False, free_sites


@njit
def reaches_outside(sx, sy, held_i, ox, oy, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Free shape site (sx, sy) is joined, through shape sites not remembered held and the
    shape's holes, to a site outside the shape (where searching robots come from). A hole
    leads out only through free shape sites: once the ring round it is closed, a robot
    outside cannot get in. Unknown sites count as free."""
    return flood_from(sx, sy, held_i, ox, oy, gene_flag, ci)[0]


@njit(inline="always")
def free_directions(sx, sy, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Bit k set for each lattice direction k (``DIR_X``, ``DIR_Y``) whose neighbour site
    of (sx, sy) is not remembered held."""
    bits = 0
    for k in range(6):
        if not is_held(held_i, sx + DIR_X[k], sy + DIR_Y[k], ox, oy):
            bits |= 1 << k
    return bits


@njit
def narrowed(sx, sy, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Free site (sx, sy) has no ``OPENING_SITES`` consecutive neighbour sites that are not
    remembered held (twice round, so a run may wrap)."""
    bits = free_directions(sx, sy, held_i, ox, oy)
    run = 0
    for q in range(12):
        if (bits >> (q % 6)) & 1:
            run += 1
            if run >= OPENING_SITES:
                return False
        else:
            run = 0
    return True


@njit
def beside_hole(sx, sy, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Site (sx, sy) has a neighbour site in a hole of the shape: robots reach it from the
    hole's side too, so it is never too narrow to enter (searchers go round the inside
    of a ring as well as the outside)."""
    holes = 0
    for k in range(6):
        holes += gene_at(gene_flag, ci, sx + DIR_X[k], sy + DIR_Y[k]) == HOLE_FLAG
    return holes > 0


@njit
def notch_two_deep(sx, sy, held_i, ox, oy, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Free shape site (sx, sy) has exactly one neighbour site not remembered held, a
    shape site beside the outside of the shape (a neighbour off the shape and in no hole)
    that keeps an opening of ``OPENING_SITES`` free neighbour sites: the two make a notch
    two deep, which a searcher enters from the outside."""
    bits = free_directions(sx, sy, held_i, ox, oy)
    if bits == 0 or bits & (bits - 1) != 0:
        return False  # not exactly one free neighbour
    k = 0
    while not (bits >> k) & 1:
        k += 1
    mx = sx + DIR_X[k]
    my = sy + DIR_Y[k]
    if gene_at(gene_flag, ci, mx, my) != 1 or narrowed(mx, my, held_i, ox, oy):
        return False
    for q in range(6):
        flag = gene_at(gene_flag, ci, mx + DIR_X[q], my + DIR_Y[q])
        if flag != 1 and flag != HOLE_FLAG:
            return True
    return False


@njit
def way_corridor(sx, sy, held_i, ox, oy, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Free shape site (sx, sy) has exactly two neighbour sites not remembered held, both
    shape sites: one on a hole's edge, the other not. It lies on a way across a ring
    that stays one: taking a site on the hole's edge beside it leaves a shorter way."""
    bits = free_directions(sx, sy, held_i, ox, oy)
    n_free = 0
    n_edge = 0
    for k in range(6):
        if not (bits >> k) & 1:
            continue
        nx = sx + DIR_X[k]
        ny = sy + DIR_Y[k]
        if gene_at(gene_flag, ci, nx, ny) != 1:
            return False
        n_free += 1
        n_edge += beside_hole(nx, ny, gene_flag, ci)
    return n_free == 2 and n_edge == 1


@njit
def narrows_a_neighbour(cx, cy, held_i, ox, oy, gene_flag, ci, outside):  # type: ignore[no-untyped-def]
    """Taking (cx, cy) would leave a free shape site next to it (as far as ``held_i``
    tells) without an opening of ``OPENING_SITES`` free neighbour sites (unless the site
    lies ``beside_hole``), or, when ``outside``, cut off from the outside of the shape.
    With ``C_WAY_END``, a capture on a hole's edge may leave a ``notch_two_deep`` or a
    ``way_corridor``.
    (cx, cy) must lie in the window; ``held_i`` is restored on return."""
    held_i[cx - ox, cy - oy] = 1
    shut = False
    way_end = ci[C_WAY_END] == 1 and beside_hole(cx, cy, gene_flag, ci)
    for k in range(6):
        sx = cx + DIR_X[k]
        sy = cy + DIR_Y[k]
        flag = gene_at(gene_flag, ci, sx, sy)
        if is_held(held_i, sx, sy, ox, oy):
            continue
        if flag == HOLE_FLAG:
            # The capture may close the ring round a hole whose edge still has free sites.
            if outside:
                exits, free_sites = flood_from(sx, sy, held_i, ox, oy, gene_flag, ci)
                if free_sites > 0 and not exits:
                    shut = True
                    break
            continue
        if flag != 1:
            continue
        if (
            narrowed(sx, sy, held_i, ox, oy)
            and not beside_hole(sx, sy, gene_flag, ci)
            and not (
                way_end
                and (
                    notch_two_deep(sx, sy, held_i, ox, oy, gene_flag, ci)
                    or way_corridor(sx, sy, held_i, ox, oy, gene_flag, ci)
                )
            )
        ) or (outside and not reaches_outside(sx, sy, held_i, ox, oy, gene_flag, ci)):
            shut = True
            break
    held_i[cx - ox, cy - oy] = 0
    return shut


@njit
def shuts_in(cx, cy, held_i, ox, oy, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Taking site (cx, cy) would shut a free shape site next to it in, as far as the
    memory ``held_i`` tells: the site would be left without an opening of
    ``OPENING_SITES`` free neighbour sites, or cut off from the outside of the shape. A
    site that is itself cut off already (the robot got into a closed hole) may be taken.
    ``held_i`` is restored on return."""
    inside = is_held(held_i, cx, cy, ox, oy)
    if inside:
        return False  # remembered held: the caller rejects it on other grounds
    if not (0 <= cx - ox < held_i.shape[0] and 0 <= cy - oy < held_i.shape[1]):
        return False
    shut = narrows_a_neighbour(cx, cy, held_i, ox, oy, gene_flag, ci, True)
    if shut and not reaches_outside(cx, cy, held_i, ox, oy, gene_flag, ci):
        return False  # already in a closed hole: fill it
    return shut


@njit
def walls_a_hole(cx, cy, held_i, ox, oy, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Taking site (cx, cy) would cut a hole site next to it off from the outside of the
    shape, as far as the memory ``held_i`` tells (a searcher still in the hole would be
    shut in). ``held_i`` is restored on return."""
    if not (0 <= cx - ox < held_i.shape[0] and 0 <= cy - oy < held_i.shape[1]):
        return False
    if is_held(held_i, cx, cy, ox, oy):
        return False
    held_i[cx - ox, cy - oy] = 1
    walled = False
    for k in range(6):
        sx = cx + DIR_X[k]
        sy = cy + DIR_Y[k]
        if gene_at(gene_flag, ci, sx, sy) != HOLE_FLAG or is_held(held_i, sx, sy, ox, oy):
            continue
        if not flood_from(sx, sy, held_i, ox, oy, gene_flag, ci)[0]:
            walled = True
            break
    held_i[cx - ox, cy - oy] = 0
    return walled
