"""A robot that missed an election catches up with the newer target when it hears of it.

Found on ``T`` ``kill random=0.1`` seed 2: robot 3 was searching, out of range, during the
third election; it heard the new robots (and the announcement they relay to robots of
older targets) but, not electing, never adopted it, and at 12846 s took a site of the
old target among them. On ``L`` ``kill random=0.1`` seed 1 the kill cut a remnant of six
robots off; it formed its own target, and when the two remnants came back within range
its robots kept the old target for good, so the merged group could never become Stable.
"""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.et_controller import ETController
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_EPOCH,
    R_HAS_TAG,
    R_PEND_EPOCH,
    R_PEND_N,
    R_PEND_TX,
    R_PEND_TY,
    R_STATE,
    R_TAG_X,
    R_TAG_Y,
    R_TS,
    R_TSLOT,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.regeneration import catch_up
from etswarm.algorithm.states import State

TICK = 10_000
#: The newer target: a triangle of three sites and one more.
NEW_CELLS = np.array([(0, 0), (1, 0), (1, 1), (2, 1)], dtype=np.int64)


def controller_with_newer_target() -> tuple[ETController, int]:
    """Four robots of a first target (epoch 0) that heard of target NEW_CELLS, epoch 2."""
    original = np.array([(x, y) for x in range(-2, 4) for y in range(-2, 3)], dtype=np.int64)
    ctl = ETController(4, original, ETParams(), 31)
    slot = ctl.add_target(NEW_CELLS, release_limit=len(NEW_CELLS), tx=0, ty=0)
    ri = ctl.ri
    ri[:, R_PEND_EPOCH] = 2
    ri[:, R_PEND_N] = len(NEW_CELLS)
    ri[:, R_PEND_TX] = 0
    ri[:, R_PEND_TY] = 0
    return ctl, slot


def place(ctl: ETController, i: int, tag: tuple[int, int]) -> None:
    ctl.ri[i, R_STATE] = State.STABLE
    ctl.ri[i, R_HAS_TAG] = 1
    ctl.ri[i, R_TAG_X], ctl.ri[i, R_TAG_Y] = tag


def run_catch_up(ctl: ETController, i: int) -> bool:
    return bool(
        catch_up(
            i, TICK, ctl.ri, ctl.nb, ctl.nb_dist, ctl.gene_flag, ctl.gene_nn, ctl.slot_info,
            ctl.ci,
        )
    )


def test_a_searcher_goes_on_searching_for_the_newer_target() -> None:
    ctl, slot = controller_with_newer_target()
    ctl.ri[0, R_STATE] = State.SEARCH
    assert run_catch_up(ctl, 0)
    assert ctl.ri[0, R_STATE] == State.SEARCH
    assert (ctl.ri[0, R_EPOCH], ctl.ri[0, R_TSLOT]) == (2, slot)


def hears_placed(ctl: ETController, i: int, sender: int, tag: tuple[int, int],
                 reading: float, epoch: int = 2) -> None:
    """Robot i heard placed robot ``sender`` of ``epoch`` on ``tag`` just now."""
    row = int(np.flatnonzero(ctl.nb[i, :, NB_ID] < 0)[0])
    ctl.nb[i, row, NB_ID] = sender
    ctl.nb[i, row, NB_STATE] = State.STABLE
    ctl.nb[i, row, NB_EPOCH] = epoch
    ctl.nb[i, row, NB_LAST] = TICK - 5
    ctl.nb[i, row, NB_TX], ctl.nb[i, row, NB_TY] = tag
    ctl.nb_dist[i, row] = reading


def test_a_placed_robot_keeps_a_site_of_the_newer_target_but_is_not_its_seed() -> None:
    ctl, slot = controller_with_newer_target()
    place(ctl, 1, (1, 0))
    hears_placed(ctl, 1, 0, (0, 0), 41.0)  # a robot of the newer target, a site away
    place(ctl, 2, (-2, 2))  # not in the newer target
    assert run_catch_up(ctl, 1) and run_catch_up(ctl, 2)
    assert ctl.ri[1, R_STATE] == State.INACTIVE and ctl.ri[1, R_TS] == 2
    assert (ctl.ri[1, R_EPOCH], ctl.ri[1, R_TSLOT]) == (2, slot)
    assert ctl.ri[2, R_STATE] == State.QUEUED and ctl.ri[2, R_HAS_TAG] == 0


def test_a_placed_robot_gives_up_a_tag_a_robot_of_the_newer_target_holds() -> None:
    ctl, _ = controller_with_newer_target()
    place(ctl, 3, (1, 1))
    nb = ctl.nb
    nb[3, 0, NB_ID] = 0
    nb[3, 0, NB_STATE] = State.STABLE
    nb[3, 0, NB_EPOCH] = 2
    nb[3, 0, NB_LAST] = TICK - 5
    nb[3, 0, NB_TX], nb[3, 0, NB_TY] = 1, 1
    assert run_catch_up(ctl, 3)
    assert ctl.ri[3, R_STATE] == State.QUEUED and ctl.ri[3, R_HAS_TAG] == 0


def test_nothing_happens_without_the_newer_targets_gene() -> None:
    ctl, _ = controller_with_newer_target()
    ctl.ri[0, R_PEND_N] = 99  # a target this robot has no gene for (never answered)
    place(ctl, 0, (1, 0))
    assert not run_catch_up(ctl, 0)
    assert ctl.ri[0, R_STATE] == State.STABLE and ctl.ri[0, R_EPOCH] == 0


def test_a_placed_robot_away_from_the_newer_targets_robots_searches_again() -> None:
    # Traced on T kill random=0.3 seed 4 (session 23): robot 4 kept (-4, 3) in a piece
    # of lattice 330-440 mm from the remnant that elected; a searcher took (-4, 3) on the
    # remnant's lattice and the tag was held twice.
    for heard in ([], [((0, 0), 90.0)], [((3, 0), 40.0)], [((0, 0), 41.0, 1)]):
        ctl, _ = controller_with_newer_target()
        place(ctl, 1, (1, 0))
        for k, args in enumerate(heard):
            hears_placed(ctl, 1, 2 + k, *args)
        assert run_catch_up(ctl, 1)
        assert ctl.ri[1, R_STATE] == State.QUEUED and ctl.ri[1, R_HAS_TAG] == 0, heard
