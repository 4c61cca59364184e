"""A status tells a sibling remnant's robots from the robot's own (``status_signature``).

Two remnants of one damage elect for the same epoch, each for its own scaled target, in
the one frame of tags the first formation left. Traced on dumbbell ``split x=mid`` seed
80 (session 62): two searchers of the right half got lost, reached the left half while
it still had Queued robots, took those for their own repository and made their home
there; when the left half had formed they went round it for four hours, its placed
robots' tags being sites of their own target too. With the option on, every status
carries four bits of its sender's target signature, and a robot of the same epoch with
other bits is a sibling's from the first message it hears.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.controller import encode, ingest, status_bits
from etswarm.algorithm.et_controller import ETController
from etswarm.algorithm.kinship import foreign, sibling
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_OTHER,
    R_EPOCH,
    R_STATE,
    R_TSLOT,
    SLOT_FIELDS,
    SLOT_N,
    SLOT_SIG,
    SLOT_USED,
    allocate,
)
from etswarm.algorithm.messages import (
    EPOCH_SHIFT,
    MSG_STATUS,
    PAYLOAD_BYTES,
    status_nibble,
    target_signature,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.regeneration import TURN_CODE
from etswarm.algorithm.run import RunConfig
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError

from .remnant_rows import remnant_rows

GENE_X0 = -3
OWN_BITS = 6


def packed(on: bool, mode: str = "placed") -> np.ndarray:
    et = ETParams(status_signature=mode if on else "off")
    ci, _ = et.pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    return ci


def heard_status(
    epoch: int, bits: int, state: int, sent_epoch: int | None = None, on: bool = True
) -> np.ndarray:
    """Robot 0, working for target slot 1 (signature bits ``OWN_BITS``) of ``epoch``, files
    a status of robot 5 (in ``state``, of ``sent_epoch``, ``epoch`` by default) whose byte
    2 carries ``bits``; returns robot 0's table."""
    sent_epoch = epoch if sent_epoch is None else sent_epoch
    ri, nb, nb_dist = allocate(1)
    ri[0, R_EPOCH] = epoch
    ri[0, R_TSLOT] = 1
    slot_info = np.zeros((2, SLOT_FIELDS), dtype=np.int64)
    slot_info[1, [SLOT_N, SLOT_USED, SLOT_SIG]] = (12, 1, OWN_BITS)
    in_type = np.array([[MSG_STATUS | ((sent_epoch & 31) << EPOCH_SHIFT)]], dtype=np.uint8)
    in_data = np.zeros((1, 1, PAYLOAD_BYTES), dtype=np.uint8)
    in_data[0, 0, 0] = 5
    in_data[0, 0, 2] = state | (bits << 4)
    ingest(0, 0, 100, ri, in_type, in_data, np.array([[45.0]]), nb, nb_dist, slot_info,
           packed(on))
    assert nb[0, 0, NB_ID] == 5
    return nb


@pytest.mark.parametrize("state", [State.QUEUED, State.SEARCH, State.STABLE])
def test_a_status_with_other_bits_of_the_epoch_is_a_siblings(state: int) -> None:
    nb = heard_status(2, OWN_BITS ^ 1, state)
    assert nb[0, 0, NB_EPOCH] == 2
    assert nb[0, 0, NB_OTHER] == 3
    assert sibling(0, 0, nb)


@pytest.mark.parametrize(
    ("epoch", "bits", "sent_epoch", "on"),
    [
        (2, OWN_BITS, None, True),  # its own target's bits
        (2, OWN_BITS ^ 1, 1, True),  # an older epoch: a robot that has not caught up yet
        (0, OWN_BITS ^ 1, None, True),  # the first formation has one target
        (2, OWN_BITS ^ 1, None, False),  # the option off: the bits are not read
    ],
)
def test_other_statuses_mark_nothing(
    epoch: int, bits: int, sent_epoch: int | None, on: bool
) -> None:
    nb = heard_status(epoch, bits, State.STABLE, sent_epoch, on)
    assert nb[0, 0, NB_OTHER] == 0
    assert not sibling(0, 0, nb)


def test_a_placed_sibling_is_foreign_whatever_its_tag() -> None:
    gene_flag = np.ones((7, 7), dtype=np.int64)  # every tag is a site of the target
    nb = heard_status(2, OWN_BITS ^ 3, State.STABLE)
    assert foreign(0, 0, nb, gene_flag, packed(True))
    assert not foreign(0, 0, heard_status(2, OWN_BITS, State.STABLE), gene_flag, packed(True))


def sent_byte_2(on: bool, state: int) -> int:
    """Byte 2 of the status robot 0 (in ``state``, working for slot 1) sends."""
    ri, _, _ = allocate(1)
    ri[0, R_STATE] = state
    ri[0, R_TSLOT] = 1
    slot_info = np.zeros((2, SLOT_FIELDS), dtype=np.int64)
    slot_info[1, SLOT_SIG] = OWN_BITS
    out_on = np.zeros(1, dtype=np.bool_)
    out_type = np.zeros(1, dtype=np.uint8)
    out_data = np.zeros((1, PAYLOAD_BYTES), dtype=np.uint8)
    encode(0, 100, ri, status_bits(0, ri, slot_info, packed(on)), out_on, out_type, out_data)
    assert out_on[0] and out_type[0] & 0x07 == MSG_STATUS
    return int(out_data[0, 2])


@pytest.mark.parametrize("state", [State.QUEUED, State.SEARCH, State.ACTIVE, State.STABLE])
def test_the_status_carries_the_bits_above_the_state(state: int) -> None:
    assert sent_byte_2(True, state) == state | (OWN_BITS << 4)
    assert sent_byte_2(False, state) == state


def test_each_target_slot_holds_the_bits_of_its_announcement() -> None:
    """What a robot works out from the target message it heard: n with its turns, and the
    placement."""
    cells = np.array([(0, 0), (1, 0), (0, 1), (1, 1)])
    ctl = ETController(3, cells, ETParams(), ticks_per_s=31)
    slot = ctl.add_target(cells[:3] + np.array([2, 1]), release_limit=0, tx=2, ty=1, turn=1)
    expected = status_nibble(target_signature(3 + TURN_CODE, 2, 1))
    assert ctl.slot_info[slot, SLOT_SIG] == expected
    assert 0 <= expected < 16


def test_status_signature_takes_one_of_its_modes() -> None:
    with pytest.raises(EtswarmError, match="status_signature must be one of"):
        ETParams(status_signature="yes")


@pytest.mark.parametrize("mode", ["on", "placed"])
def test_both_modes_send_and_read_the_bits(mode: str) -> None:
    """They differ only in what a searcher does with a sibling's Queued robot."""
    ri, _, _ = allocate(1)
    ri[0, R_TSLOT] = 1
    slot_info = np.zeros((2, SLOT_FIELDS), dtype=np.int64)
    slot_info[1, SLOT_SIG] = OWN_BITS
    assert status_bits(0, ri, slot_info, packed(True, mode)) == OWN_BITS << 4


def remnants(mode: str) -> list[tuple[int, int | None, int, bool]]:
    """dumbbell ``split x=mid`` seed 80, 4 h from the damage at most: per remnant of the
    summary, (robots, census count, target cells, formed)."""
    return remnant_rows(RunConfig(shape="dumbbell", seed=80, damage=("split x=mid",),
                                  max_time_s=18500, census="tree",
                                  et=ETParams(status_signature=mode)))


def test_lost_searchers_do_not_make_their_home_at_the_sibling() -> None:
    """With "placed" the two searchers still follow the left half's Queued robots, but
    once those are placed they know its robots for a sibling's, and their spiral round
    the home they made there brings them back to their own half."""
    assert remnants("placed") == [(31, 31, 31, True), (30, 30, 30, True)]
    # Without the bits two of the right half's searchers never come back.
    assert not all(formed for *_, formed in remnants("off"))
