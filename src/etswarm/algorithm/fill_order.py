"""Lookahead on a searcher's memory of held sites: can the shape still be finished?

``site_memory.shuts_in`` looks one step ahead: taking a site must leave every free shape
site next to it an opening of ``OPENING_SITES`` free neighbour sites. That is not enough
where three free sites are mutually adjacent in a pocket. Traced on heart seed 4: the
free sites (2, 0), (3, 0), (3, 1) form a triangle closed on every side but one, and
(4, 0) beyond it has a single held neighbour. Taking (2, 0) leaves (3, 1) one free
neighbour and the other way round; (3, 0) and (4, 0) have no two held neighbours to be
located from. Four searchers orbited for three hours. Each capture that closed the pocket
passed the one-step test.

``strands_a_site`` plays the rest of the growth forward on a copy of the memory. It
repeatedly takes any free shape site that has two held neighbour sites to be located
from and whose capture passes the one-step test, until nothing more can be taken. A
capture is refused when the shape could be finished before it and cannot be after it.
When the shape cannot be finished even before the capture, the lookahead says nothing,
so a run that is stuck already is not stopped altogether. The playout is greedy: it
may miss an order that works, and then it refuses nothing. It rescans its region for
every site it places, so it runs only when a settled searcher confirms its site (once
per stop), not on every candidate of a moving one: run on every candidate it cost
bigdisc 85 % of its speed (472x real time against 2924x) and formed 350 of 390 runs
(13 shapes, seeds 0-29) against 351. Its region is the sites within ``FILL_RADIUS``
steps of the candidate.

Arrays: ``held_i`` (WX, WY) uint8, one robot's memory (window origin at tag (ox, oy),
see ``site_memory``); ``gene_flag`` and ``ci`` as in ``kernel_util.gene_at``.
"""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, gene_at, hex_distance
from etswarm.algorithm.site_memory import is_held, narrows_a_neighbour

#: The playout covers the shape sites within this many lattice steps of the candidate:
#: pockets are local, and over the whole of a 1000-cell shape it halved a run's speed.
FILL_RADIUS = 4


@njit
def locatable(sx, sy, scratch, ox, oy):  # type: ignore[no-untyped-def]
    """Site (sx, sy) has two held neighbour sites a searcher can locate it from: two
    lattice neighbours of each other (consecutive round the site), or two of the second
    ring (one site apart round it)."""
    for k in range(6):
        if not is_held(scratch, sx + DIR_X[k], sy + DIR_Y[k], ox, oy):
            continue
        k1 = (k + 1) % 6
        k2 = (k + 2) % 6
        if is_held(scratch, sx + DIR_X[k1], sy + DIR_Y[k1], ox, oy):
            return True
        if is_held(scratch, sx + DIR_X[k2], sy + DIR_Y[k2], ox, oy):
            return True
    return False


@njit
def held_around(sx, sy, scratch, ox, oy):  # type: ignore[no-untyped-def]
    """Number of held neighbour sites of (sx, sy) in ``scratch``."""
    n = 0
    for k in range(6):
        if is_held(scratch, sx + DIR_X[k], sy + DIR_Y[k], ox, oy):
            n += 1
    return n


@njit
def finishes(scratch, ox, oy, gene_flag, ci, cx, cy):  # type: ignore[no-untyped-def]
    """Greedy playout on ``scratch`` (modified) over the shape sites within
    ``FILL_RADIUS`` steps of (cx, cy): while any free one is ``locatable`` and does not
    ``narrows_a_neighbour``, take the one with the most held neighbour sites (the deepest
    notch first, so the playout does not close pockets itself). True when every shape
    site there ends up held."""
    x0 = max(0, cx - ox - FILL_RADIUS)
    x1 = min(scratch.shape[0], cx - ox + FILL_RADIUS + 1)
    y0 = max(0, cy - oy - FILL_RADIUS)
    y1 = min(scratch.shape[1], cy - oy + FILL_RADIUS + 1)
    while True:
        best = -1
        best_x = 0
        best_y = 0
        free = 0
        for wx in range(x0, x1):
            for wy in range(y0, y1):
                x = wx + ox
                y = wy + oy
                if hex_distance(x - cx, y - cy) > FILL_RADIUS:
                    continue
                if scratch[wx, wy] != 0 or gene_at(gene_flag, ci, x, y) != 1:
                    continue
                free += 1
                n = held_around(x, y, scratch, ox, oy)
                if n <= best or n < 2:
                    continue
                if not locatable(x, y, scratch, ox, oy):
                    continue
                if narrows_a_neighbour(x, y, scratch, ox, oy, gene_flag, ci, False):
                    continue
                best = n
                best_x = wx
                best_y = wy
        if free == 0:
            return True
        if best < 0:
            return False
        scratch[best_x, best_y] = 1


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(_nrt=True)
def strands_a_site(cx, cy, held_i, ox, oy, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Taking site (cx, cy) turns the sites round it from ones the greedy playout
    finishes, as the memory ``held_i`` tells, into ones it cannot finish. ``held_i`` is
    not modified."""
    if not (0 <= cx - ox < held_i.shape[0] and 0 <= cy - oy < held_i.shape[1]):
        return False
    scratch = held_i.copy()
    if not finishes(scratch, ox, oy, gene_flag, ci, cx, cy):
        return False
    scratch[:, :] = held_i
    scratch[cx - ox, cy - oy] = 1
    return not finishes(scratch, ox, oy, gene_flag, ci, cx, cy)
