"""Growth in waves from the seeds (``ETParams.wave_s``).

A searcher takes the first site it can localise on its way round the group, so a compact
shape grows along its rim in arms, and the arms close a ring round a free middle
(bigdisc). With the wave rule, every site of the first target carries its hop count from
the seed triangle within the target (``ETController.seed`` stores it beside NN in
``gene_nn``: NN in the low ``HOPS_SHIFT`` bits, the hops above). A searcher does not take a
site while a neighbour site of the target nearer the seeds is not known held, for its
first ``wave_s`` seconds at the shape. Targets with holes are left out (``O`` formed
less often with it).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, gene_at
from etswarm.algorithm.site_memory import is_held
from etswarm.shapes.lattice import NEIGHBOUR_OFFSETS

#: ``gene_nn`` holds NN in its low bits and the hop count from the seeds above them.
HOPS_SHIFT = 3
NN_MASK = (1 << HOPS_SHIFT) - 1


@njit(inline="always")
def nn_of(value):  # type: ignore[no-untyped-def]
    """NN of a ``gene_nn`` value."""
    return value & NN_MASK


@njit
def behind_wave(cx, cy, gene_flag, gene_nn, ci, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Site (cx, cy) has a neighbour site of the target with fewer hops from the seeds
    that the memory ``held_i`` ((WX, WY) at tag (ox, oy)) does not know held."""
    hops = gene_at(gene_nn, ci, cx, cy) >> HOPS_SHIFT
    for k in range(6):
        nx = cx + DIR_X[k]
        ny = cy + DIR_Y[k]
        if gene_at(gene_flag, ci, nx, ny) != 1:
            continue
        if (gene_at(gene_nn, ci, nx, ny) >> HOPS_SHIFT) < hops and not is_held(
            held_i, nx, ny, ox, oy
        ):
            return True
    return False


def seed_hops(cells: np.ndarray, seed_tags: np.ndarray) -> np.ndarray:
    """Hops (P,) int64 of each of ``cells`` ((P, 2) tags) from the nearest of
    ``seed_tags`` ((3, 2)), stepping between neighbouring cells of the shape only
    (breadth-first); cells the seeds do not reach get the largest count plus one."""
    index = {(int(x), int(y)): k for k, (x, y) in enumerate(np.asarray(cells).tolist())}
    hops = np.full(len(index), -1, dtype=np.int64)
    frontier = [index[(int(x), int(y))] for x, y in seed_tags.tolist() if (x, y) in index]
    for k in frontier:
        hops[k] = 0
    cells_list = np.asarray(cells).tolist()
    while frontier:
        nxt = []
        for k in frontier:
            x, y = cells_list[k]
            for dx, dy in NEIGHBOUR_OFFSETS:
                j = index.get((x + int(dx), y + int(dy)))
                if j is not None and hops[j] < 0:
                    hops[j] = hops[k] + 1
                    nxt.append(j)
        frontier = nxt
    hops[hops < 0] = hops.max() + 1
    return hops
