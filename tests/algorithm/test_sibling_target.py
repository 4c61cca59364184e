"""A remnant that still elects does not take over the target of a sibling remnant.

Traced on ``T`` ``remove random=0.2`` seed 10 (session 61): the removal left a 33-robot
remnant and a 3-robot one, out of each other's range, and both elected for epoch 1. The
small one finished first (Leader 38, census 3) and released a searcher, which came within
range of the big one while it still elected. Its robots heard the announcement of the
3-cell target for the epoch they elected for, took it for their own Leader's, and all 36
robots then worked for 3 cells: 33 of them Queued or searching for good, and the summary
called the remnant formed.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import (
    PHASE_ELECTING,
    PHASE_NORMAL,
    R_ELECT_MIN,
    R_EPOCH,
    R_LEADER,
    R_PHASE,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.regeneration import NO_LEADER, from_sibling
from etswarm.algorithm.run import RunConfig
from etswarm.errors import EtswarmError

from .remnant_rows import remnant_rows

GENE_X0 = -3


def electing_robot(candidate: int) -> np.ndarray:
    """The memory rows of one robot at epoch 0, electing for epoch 1, whose lowest
    candidate heard is ``candidate``."""
    ri, _, _ = allocate(1)
    ri[0, R_EPOCH] = 0
    ri[0, R_PHASE] = PHASE_ELECTING
    ri[0, R_LEADER] = candidate
    ri[0, R_ELECT_MIN] = candidate
    return ri


def packed(mode: str) -> np.ndarray:
    ci, _ = ETParams(sibling_target=mode).pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    return ci


def test_a_higher_leader_of_the_epoch_elected_for_is_a_siblings() -> None:
    ri = electing_robot(candidate=0)
    assert from_sibling(0, ri, 1, 38, packed("ignore"))
    assert not from_sibling(0, ri, 1, 38, packed("adopt"))


@pytest.mark.parametrize(
    ("epoch", "leader", "phase"),
    [
        (1, 0, PHASE_ELECTING),  # its own candidate's announcement
        (1, 5, PHASE_NORMAL),  # not electing: catching up is another rule's business
        (2, 38, PHASE_ELECTING),  # a newer epoch: it missed a whole regeneration
        (1, NO_LEADER, PHASE_ELECTING),  # relayed by a robot that caught up: no Leader named
    ],
)
def test_other_announcements_are_taken(epoch: int, leader: int, phase: int) -> None:
    ri = electing_robot(candidate=0 if leader == 0 else 3)
    ri[0, R_PHASE] = phase
    for mode in ("ignore", "strict"):
        assert not from_sibling(0, ri, epoch, leader, packed(mode))


def test_a_lower_leader_than_the_candidate_is_taken_unless_strict() -> None:
    """"ignore" takes it (a robot whose entries aged may hear a higher candidate than
    its Leader); "strict" takes only the lowest candidate heard in the election."""
    ri = electing_robot(candidate=12)
    assert not from_sibling(0, ri, 1, 4, packed("ignore"))
    assert from_sibling(0, ri, 1, 4, packed("strict"))
    assert not from_sibling(0, ri, 1, 12, packed("strict"))


def test_strict_takes_any_leader_before_a_candidate_is_heard() -> None:
    """With census walk a robot that did not see the damage stands for no one, and until
    it hears a candidate it cannot tell its election's Leader from a sibling's."""
    ri = electing_robot(candidate=NO_LEADER)
    assert not from_sibling(0, ri, 1, 4, packed("strict"))


def test_strict_remembers_the_lowest_candidate_heard() -> None:
    """R_LEADER falls back to a higher candidate when the entries of the lowest age;
    the announcement of the lowest is still the robot's own election's."""
    ri = electing_robot(candidate=12)
    ri[0, R_ELECT_MIN] = 4
    assert not from_sibling(0, ri, 1, 4, packed("strict"))
    assert from_sibling(0, ri, 1, 12, packed("strict"))


def test_sibling_target_must_be_a_mode() -> None:
    with pytest.raises(EtswarmError, match="sibling_target must be one of"):
        ETParams(sibling_target="maybe")


def remnants(seed: int, mode: str) -> list[tuple[int, int, int, bool]]:
    """``T`` ``remove random=0.2`` until it settles (at most 4 h after the damage): per
    remnant of the summary, (robots, census count, target cells, formed)."""
    return remnant_rows(RunConfig(shape="T", seed=seed, damage=("remove random=0.2",),
                                  max_time_s=6 * 3600, et=ETParams(sibling_target=mode)))


def test_each_remnant_grows_its_own_scaled_shape() -> None:
    """Seed 10: the 3-robot remnant's Leader (38) has a higher ID than the 33-robot
    remnant's candidates, so "ignore" is enough."""
    assert remnants(10, "ignore") == [(33, 33, 33, True), (3, 3, 3, True)]
    # Taking the sibling's announcement, the big remnant grows the 3-cell target.
    [(robots, count, cells, _)] = remnants(10, "adopt")
    assert (robots, count, cells) == (36, 3, 3)


def test_a_sibling_led_by_a_lower_id_is_ignored_only_when_strict() -> None:
    """Seed 85: the 7-robot remnant's Leader is robot 0. With "strict" the 29-robot
    remnant elects on its own; the two then grow into contact and elect as one
    (``merge``), and the 36 robots grow a 36-cell `T`."""
    assert remnants(85, "strict") == [(36, 36, 36, True)]
    [(robots, count, cells, _)] = remnants(85, "ignore")
    assert (robots, count, cells) == (36, 7, 7)
