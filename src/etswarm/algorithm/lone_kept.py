"""A robot kept on its site by a regeneration, with no kept neighbour site, searches again.

After damage the Leader lays the scaled target over the remnant where it keeps the most
robots in place (``extent``), and every robot whose site the new target has stays on it
(``regeneration.adopt_target``). Where the new shape is narrower than the old one, some
of them stand alone: none of the six sites around them is both in the new target and
held. Each stands where the old lattice put it, and the old lattice drifted as it grew
(``docs/algorithm.md``, "Large shapes: the lattice drifts as it grows"), so it may stand
20-30 mm from where the growth from the new seeds will reach. Traced on `T` `kill
random=0.1` seed 36: robots 33 and 41 kept (-1, -2) and (-2, -4), 18 and 30 mm off the
new stem's line; the stem grew from (0, 0) to meet them and bent, three sites beside it
were never taken, and eight robots ended 26-197 mm from their sites by the remnant's
rigid fit.

With ``ETParams.lone_kept_leave`` "on", such a robot gives the site up and joins again
through Queued and Search, as a robot the new target leaves out does. It decides from
its neighbour table as it adopts the target (before the table is cleared): the placed
robots it heard within ``LONE_FRESH_S``, their tags, and the new target's gene.
"""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import direction_index, gene_at, is_placed
from etswarm.algorithm.memory import NB_ID, NB_LAST, NB_STATE, NB_TX, NB_TY, R_TAG_X, R_TAG_Y
from etswarm.algorithm.params import C_LONE_KEPT, C_TICKS_PER_S

#: Seconds within which a placed robot must have been heard to count as a kept neighbour.
#: Electing robots send a message every few ticks, so a live neighbour is heard well
#: within this even at loss 0.2; a robot killed by the damage (before the election) is not.
LONE_FRESH_S = 10


@njit
def lone_in_new_target(i, tick, ri, nb, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Robot i, on a site of the target a regeneration replaces, adopts the new target
    ``gene_flag`` (its table not yet cleared): True when the option is on and no placed
    robot it heard within ``LONE_FRESH_S`` holds one of its six neighbour sites that the
    new target has."""
    if ci[C_LONE_KEPT] == 0:
        return False
    x = ri[i, R_TAG_X]
    y = ri[i, R_TAG_Y]
    fresh = LONE_FRESH_S * ci[C_TICKS_PER_S]
    for m in range(nb.shape[1]):
        if nb[i, m, NB_ID] < 0 or not is_placed(nb[i, m, NB_STATE]):
            continue
        if tick - nb[i, m, NB_LAST] > fresh:
            continue
        tx = nb[i, m, NB_TX]
        ty = nb[i, m, NB_TY]
        if direction_index(tx - x, ty - y) >= 0 and gene_at(gene_flag, ci, tx, ty) == 1:
            return False
    return True
