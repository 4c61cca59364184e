"""Remnants that grow into contact elect again as one (``ETParams.merge_remnants``).

Each remnant places its scaled shape from what it hears while it elects. Two groups a
lattice gap apart (a removal takes every robot of a row between them) elect apart, and
neither knows of the other. Their targets, in the one frame of tags both kept from the
first formation, can then share sites: traced on `T` `remove random=0.3` seed 16, the
24-robot remnant's target took in four tags that robots of the 7-robot remnant beside it
held, and it could never be filled. Robots carry no mark of their remnant, and sibling
remnants share the epoch.

What a placed robot can see is a robot of its own epoch, right beside it, whose tag is no
site of its own target (``kinship.off_target``). Once it has heard such a robot within
``MERGE_NEAR_MM`` for ``MERGE_AFTER_S`` without a break, it starts an election for the next
epoch. The robots of both remnants hear it (both are at that epoch) and join, so the two
elect one Leader, count themselves together and regrow one shape. The first formation has
one target, so this never happens there.

With ``ETParams.merge_parked``, a Queued robot *parked* beside it (``parked``: its remnant
was too small to grow, and it stays where the damage left it) is contact too: a remnant
whose scaled shape grew round such a robot could never take the site it stands on
(`H` `split y=mid` seed 45), and electing with it counts it in.
"""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import first_growth, is_placed
from etswarm.algorithm.kinship import off_target
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_STATE,
    PHASE_NORMAL,
    R_CONTACT_SINCE,
    R_EPOCH,
    R_PHASE,
)
from etswarm.algorithm.params import C_MERGE, C_MERGE_PARKED, C_TICKS_NB_FRESH
from etswarm.algorithm.parked import parked
from etswarm.algorithm.regeneration import start_election

#: A robot of another remnant this near (mm, a reading) is in contact: two bodies a lattice
#: step apart read about 40 mm; across a free site, 80.
MERGE_NEAR_MM = 50.0
#: ... heard without a break (every reading within the neighbour timeout) this long (s).
MERGE_AFTER_S = 30.0
#: ``MERGE_AFTER_S`` in ticks of the simulator's 31 ticks per second.
MERGE_AFTER_TICKS = round(MERGE_AFTER_S * 31)


@njit
def contact_rule(i, tick, ri, nb, nb_dist, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Placed robot i (normal phase) of a regenerated target, whose target's gene flags are
    ``gene_flag``: start an election once a robot of another remnant has stood beside it
    for ``MERGE_AFTER_TICKS`` (R_CONTACT_SINCE keeps since when). Returns True when it did."""
    if ci[C_MERGE] == 0 or first_growth(i, ri) or ri[i, R_PHASE] != PHASE_NORMAL:
        return False
    fresh = ci[C_TICKS_NB_FRESH]
    epoch = ri[i, R_EPOCH]
    touching = False
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or tick - nb[i, m, NB_LAST] > fresh:
            continue
        if nb_dist[i, m] > MERGE_NEAR_MM:
            continue
        if ci[C_MERGE_PARKED] == 1 and parked(i, m, nb) and nb[i, m, NB_EPOCH] <= epoch:
            touching = True
            break
        if not is_placed(nb[i, m, NB_STATE]) or nb[i, m, NB_EPOCH] != epoch:
            continue
        if off_target(i, m, nb, gene_flag, ci):
            touching = True
            break
    if not touching:
        ri[i, R_CONTACT_SINCE] = 0
        return False
    if ri[i, R_CONTACT_SINCE] == 0:
        ri[i, R_CONTACT_SINCE] = tick + 1
        return False
    if tick - (ri[i, R_CONTACT_SINCE] - 1) < MERGE_AFTER_TICKS:
        return False
    ri[i, R_CONTACT_SINCE] = 0
    start_election(i, tick, ri, ci)
    return True
