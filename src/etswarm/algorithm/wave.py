"""Growth in waves from the seeds (``ETParams.wave_s``).

A searcher takes the first site it can localise on its way round the group, so a compact
shape grows along its rim in arms, and the arms close a ring round a free middle
(bigdisc). With the wave rule, every site of the first target carries its hop count from
the seed triangle within the target (``ETController.seed`` stores it beside NN in
``gene_nn``: NN in the low ``HOPS_SHIFT`` bits, the hops above). A searcher does not take a
site while a neighbour site of the target nearer the seeds is not known held, for its
first ``wave_s`` seconds at the shape. Targets with holes are left out (``O`` formed
less often with it).

For a target with holes, ``rim_wave_s`` runs the wave out from the holes' edges instead
(``rim_hops``). There a site nearer a hole blocks a capture only while it could be
located (two held neighbour sites, ``fill_order.locatable``): along a ring's rows the
site of the inner row needs the next site of the row beside it first, so the plain
rule would stop both.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from etswarm.algorithm.fill_order import locatable
from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, first_growth, gene_at
from etswarm.algorithm.params import C_RIM_WAVE, C_WAVE
from etswarm.algorithm.site_memory import is_held
from etswarm.shapes.lattice import hole_edge_cells, steps_from

#: ``gene_nn`` holds NN in its low bits and the hop count from the seeds above them.
HOPS_SHIFT = 3
NN_MASK = (1 << HOPS_SHIFT) - 1


@njit(inline="always")
def nn_of(value):  # type: ignore[no-untyped-def]
    """NN of a ``gene_nn`` value."""
    return value & NN_MASK


@njit
def wave_blocks(i, ri, at_shape, cx, cy, gene_flag, gene_nn, ci, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Searcher i must not take site (cx, cy) yet: it keeps to the wave (first formation,
    under ``C_WAVE`` ticks ``at_shape``) and the site is ``behind_wave``."""
    if ci[C_WAVE] == 0 or not first_growth(i, ri) or at_shape >= ci[C_WAVE]:
        return False
    return behind_wave(cx, cy, gene_flag, gene_nn, ci, held_i, ox, oy)


@njit
def behind_wave(cx, cy, gene_flag, gene_nn, ci, held_i, ox, oy):  # type: ignore[no-untyped-def]
    """Site (cx, cy) has a neighbour site of the target with fewer hops from the seeds
    that the memory ``held_i`` ((WX, WY) at tag (ox, oy)) does not know held; with the
    rim wave (``C_RIM_WAVE``), one that could also be located from the sites it knows
    held."""
    hops = gene_at(gene_nn, ci, cx, cy) >> HOPS_SHIFT
    rim = ci[C_RIM_WAVE] > 0
    for k in range(6):
        nx = cx + DIR_X[k]
        ny = cy + DIR_Y[k]
        if gene_at(gene_flag, ci, nx, ny) != 1:
            continue
        nearer = (gene_at(gene_nn, ci, nx, ny) >> HOPS_SHIFT) < hops
        if nearer and not is_held(held_i, nx, ny, ox, oy) and (
            not rim or locatable(nx, ny, held_i, ox, oy)
        ):
            return True
    return False


def seed_hops(cells: np.ndarray, seed_tags: np.ndarray) -> np.ndarray:
    """Hops (P,) int64 of each of ``cells`` ((P, 2) tags) from the nearest of
    ``seed_tags`` ((3, 2)), stepping between neighbouring cells of the shape only;
    cells the seeds do not reach get the largest count plus one."""
    steps = steps_from(cells, seed_tags)
    reached = np.isfinite(steps)
    top = int(steps[reached].max()) + 1 if reached.any() else 0
    return np.where(reached, steps, top).astype(np.int64)


def rim_hops(cells: np.ndarray) -> np.ndarray:
    """Hops (P,) int64 of each of ``cells`` ((P, 2) tags) from the nearest cell on the edge
    of a hole (``lattice.hole_edge_cells``), stepping between
    neighbouring cells of the shape only; 0 on the edges. Cells no edge reaches (a part
    of the shape round no hole) get the largest count plus one."""
    return seed_hops(cells, hole_edge_cells(cells))
