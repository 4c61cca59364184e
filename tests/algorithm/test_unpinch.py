"""A robot kept through a regeneration gives up its site when its own offset puts it far
into a free site of the new target (``regrowth_unpinch_mm``, ``pinch.pinches_new_target``).

Robot 0 holds (0, 0); it hears the holders of its neighbour sites in directions 1-5 and
none in direction 0, (0, 1). Its offset points ``into`` mm towards (0, 1).
"""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, STABLE
from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_OFF_X,
    R_OFF_Y,
    allocate,
)
from etswarm.algorithm.offsets import FINE_PER_MM
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.pinch import pinches_new_target
from etswarm.shapes.lattice import tags_to_xy

TICK = 1000
GENE = np.ones((7, 7), dtype=np.uint8)  # tags -3 .. 3 (gene origin at (-3, -3))


def kept_robot(into: float, held_dirs: tuple[int, ...] = (1, 2, 3, 4, 5), heard_at: int = TICK):  # type: ignore[no-untyped-def]
    """Robot 0's memory row and table: ``(ri, nb)``."""
    ri, nb, _ = allocate(1)
    toward = tags_to_xy(np.array([(DIR_X[0], DIR_Y[0])]), 1.0)[0]
    ri[0, R_OFF_X] = round(into * toward[0] * FINE_PER_MM)
    ri[0, R_OFF_Y] = round(into * toward[1] * FINE_PER_MM)
    for slot, k in enumerate(held_dirs):
        nb[0, slot, NB_ID] = 1 + slot
        nb[0, slot, NB_STATE] = STABLE
        nb[0, slot, NB_TX] = DIR_X[k]
        nb[0, slot, NB_TY] = DIR_Y[k]
        nb[0, slot, NB_LAST] = heard_at
    return ri, nb


def constants(unpinch_mm: int) -> np.ndarray:
    ci, _ = ETParams(regrowth_unpinch_mm=unpinch_mm).pack(31, gene_x0=-3, gene_y0=-3)
    return ci


def test_a_robot_far_into_a_free_site_gives_its_own_up() -> None:
    ri, nb = kept_robot(into=15.0)
    assert pinches_new_target(0, TICK, ri, nb, GENE, constants(12))
    assert not pinches_new_target(0, TICK, ri, nb, GENE, constants(16))
    assert not pinches_new_target(0, TICK, ri, nb, GENE, constants(0))  # the paper: it stays


def test_a_robot_a_little_off_keeps_its_site() -> None:
    ri, nb = kept_robot(into=8.0)
    assert not pinches_new_target(0, TICK, ri, nb, GENE, constants(12))


def test_only_free_sites_of_the_new_target_count() -> None:
    # (0, 1) held: the robot leans on a neighbour, which narrows nothing.
    ri, nb = kept_robot(into=15.0, held_dirs=(0, 1, 2, 3, 4, 5))
    assert not pinches_new_target(0, TICK, ri, nb, GENE, constants(12))
    # (0, 1) off the new target: nobody will need the room.
    gene = GENE.copy()
    gene[0 + 3, 1 + 3] = 0
    ri, nb = kept_robot(into=15.0)
    assert not pinches_new_target(0, TICK, ri, nb, gene, constants(12))


def test_holders_not_heard_lately_leave_their_sites_free() -> None:
    # Its neighbours were last heard long ago (across the cut, say): every neighbour site
    # of the new target is free, and the offset towards (0, 1) decides.
    ri, nb = kept_robot(into=15.0, held_dirs=(0, 1, 2, 3, 4, 5), heard_at=TICK - 500)
    assert pinches_new_target(0, TICK, ri, nb, GENE, constants(12))
