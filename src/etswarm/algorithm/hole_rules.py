"""Whether taking a site would shut a free shape site off from the searchers outside, judged
from the robots a searcher hears now (``ETParams.hole_memory`` "off"; with it on,
``site_memory`` judges over the whole shape)."""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.algorithm.kernel_util import (
    DIR_X,
    DIR_Y,
    gene_at,
    hex_distance,
)
from etswarm.algorithm.site_memory import site_taken

#: A free site must keep this many consecutive free neighbour sites to stay reachable.
OPENING_SITES = 2
#: Taking a site must not shut free shape sites in a hole (see ``closes_a_hole``), looking
#: this many lattice steps round the site.
HOLE_RADIUS = 3


@njit
def known_held(i, x, y, nb, cx, cy):  # type: ignore[no-untyped-def]
    """Site (x, y) is held, as robot i knows (or is the site (cx, cy) it would take)."""
    if x == cx and y == cy:
        return True
    return site_taken(i, x, y, nb)


@njit
def encloses_a_site(i, cx, cy, nb, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Taking (cx, cy) would leave a free shape site next to it without an opening of
    ``OPENING_SITES`` consecutive free neighbour sites: an edge-following robot, which
    keeps about d from every placed robot, could no longer get onto it."""
    for k in range(6):
        sx = cx + DIR_X[k]
        sy = cy + DIR_Y[k]
        if gene_at(gene_flag, ci, sx, sy) != 1 or site_taken(i, sx, sy, nb):
            continue
        run = 0
        best = 0
        for q in range(12):  # twice round, so a run may wrap
            if known_held(i, sx + DIR_X[q % 6], sy + DIR_Y[q % 6], nb, cx, cy):
                run = 0
            else:
                run += 1
                best = max(best, run)
        if best < OPENING_SITES:
            return True
    return False


# allocates: keeps numba's reference counting (etswarm.sim.borrow)
@njit(_nrt=True)
def open_from(i, cx, cy, sx, sy, center_taken, nb, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Free shape site (cx + sx, cy + sy) reaches, through free shape sites, a site outside
    the shape or the edge of what robot i knows (``HOLE_RADIUS`` lattice steps from
    (cx, cy), beyond which it assumes the way open). Sites robot i knows no holder of
    count as free; (cx, cy) itself counts as held when ``center_taken``."""
    size = 2 * HOLE_RADIUS + 1
    seen = np.zeros((size, size), dtype=np.uint8)
    queue_x = np.empty(size * size, dtype=np.int64)
    queue_y = np.empty(size * size, dtype=np.int64)
    if center_taken:
        seen[HOLE_RADIUS, HOLE_RADIUS] = 1
    seen[sx + HOLE_RADIUS, sy + HOLE_RADIUS] = 1
    queue_x[0] = sx
    queue_y[0] = sy
    head = 0
    tail = 1
    while head < tail:
        qx = queue_x[head]
        qy = queue_y[head]
        head += 1
        if hex_distance(qx, qy) >= HOLE_RADIUS:
            return True
        for q in range(6):
            nx = qx + DIR_X[q]
            ny = qy + DIR_Y[q]
            if seen[nx + HOLE_RADIUS, ny + HOLE_RADIUS]:
                continue
            if gene_at(gene_flag, ci, cx + nx, cy + ny) != 1:
                return True  # the outside of the shape
            seen[nx + HOLE_RADIUS, ny + HOLE_RADIUS] = 1
            if site_taken(i, cx + nx, cy + ny, nb):
                continue
            queue_x[tail] = nx
            queue_y[tail] = ny
            tail += 1
    return False


@njit
def closes_a_hole(i, cx, cy, nb, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Taking (cx, cy) would leave a free shape site next to it in a hole: cut off from the
    outside of the shape (see ``open_from``), where searching robots come from."""
    for k in range(6):
        sx = DIR_X[k]
        sy = DIR_Y[k]
        if gene_at(gene_flag, ci, cx + sx, cy + sy) != 1 or site_taken(i, cx + sx, cy + sy, nb):
            continue
        if not open_from(i, cx, cy, sx, sy, True, nb, gene_flag, ci):
            return True
    return False
