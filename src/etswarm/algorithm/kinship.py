"""Whose robot a neighbour is: a placed robot of another target (a sibling remnant's, or one
that has not adopted the target yet) is foreign to a searcher."""

from __future__ import annotations

from numba import njit

from etswarm.algorithm.kernel_util import gene_at
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_OTHER,
    NB_TX,
    NB_TY,
)
from etswarm.algorithm.params import C_SIGNED_FOREIGN


@njit(inline="always")
def off_target(i, m, nb, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Placed robot m of robot i's table holds a tag that is no site of i's target: it
    belongs to another remnant's shape (a sibling cut from the same lattice) or has not
    adopted the target yet. Every placed robot of the target holds one of its sites."""
    return gene_at(gene_flag, ci, nb[i, m, NB_TX], nb[i, m, NB_TY]) != 1


@njit(inline="always")
def foreign(i, m, nb, gene_flag, ci):  # type: ignore[no-untyped-def]
    """Placed robot m of robot i's table is not of i's shape, to a searcher: its tag is no
    site of i's target (``off_target``) or, with ``ci[C_SIGNED_FOREIGN]``, its held-sites
    message named another target of the epoch it still works for (``NB_OTHER``):
    siblings' scaled targets may share tags."""
    if off_target(i, m, nb, gene_flag, ci):
        return True
    return ci[C_SIGNED_FOREIGN] == 1 and sibling(i, m, nb)


@njit(inline="always")
def sibling(i, m, nb):  # type: ignore[no-untyped-def]
    """Robot m of robot i's table works for another target of the epoch it works for: a
    sibling remnant's (its held-sites message, or with ``ETParams.status_signature`` its
    status, named another target, ``NB_OTHER``)."""
    other = nb[i, m, NB_OTHER]
    return other > 0 and other == nb[i, m, NB_EPOCH] + 1
