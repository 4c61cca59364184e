"""What a robot kept on its site through a regeneration does with its offset, and when a
two-neighbour site gets the widened window."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import (
    R_FIELDS,
    R_OFF_REFINE,
    R_OFF_TICK,
    R_OFF_X,
    R_OFF_Y,
)
from etswarm.algorithm.params import C_REGROW_OFFSETS, F_TWO_WIDEN_TICKS, ETParams
from etswarm.algorithm.regeneration import restart_offset
from etswarm.algorithm.search import WIDE_MIN_NEIGHBOURS, wide_minimum
from etswarm.errors import EtswarmError


def kept_robot() -> np.ndarray:
    """Memory of one placed robot standing 12 mm and -5 mm off its site, done refining."""
    ri = np.zeros((1, R_FIELDS), dtype=np.int64)
    ri[0, R_OFF_X] = 12 * 64
    ri[0, R_OFF_Y] = -5 * 64
    ri[0, R_OFF_REFINE] = 0
    return ri


@pytest.mark.parametrize(
    ("mode", "seed", "offset", "refine"),
    [
        ("keep", False, (12 * 64, -5 * 64), 0),
        ("reset", False, (0, 0), 1),
        ("reset", True, (0, 0), 0),  # the new Active seed defines the frame
        ("zero", False, (0, 0), 0),
    ],
)
def test_a_kept_robot_restarts_its_offset_as_the_option_says(
    mode: str, seed: bool, offset: tuple[int, int], refine: int
) -> None:
    ci, _ = ETParams(regrowth_offsets=mode).pack(31, 0, 0)
    ri = kept_robot()
    restart_offset(0, 500, seed, ri, ci)
    assert (ri[0, R_OFF_X], ri[0, R_OFF_Y]) == offset
    assert ri[0, R_OFF_REFINE] == refine
    if mode != "keep":
        assert ri[0, R_OFF_TICK] == 500


def test_reset_does_not_refine_with_site_offsets_off() -> None:
    ci, _ = ETParams(regrowth_offsets="reset", site_offsets="off").pack(31, 0, 0)
    ri = kept_robot()
    restart_offset(0, 500, False, ri, ci)
    assert ri[0, R_OFF_REFINE] == 0


@pytest.mark.parametrize("epoch", [0, 3])
def test_two_neighbour_sites_widen_only_after_the_set_time(epoch: int) -> None:
    """First formation (epoch 0): ``two_neighbour_widen_s``; after damage:
    ``regrowth_two_neighbour_widen_s``; 0 turns it off."""
    name = "two_neighbour_widen_s" if epoch == 0 else "regrowth_two_neighbour_widen_s"
    _, cf = ETParams(**{name: 600.0}).pack(31, 0, 0)
    assert wide_minimum(600 * 31 - 1, epoch, cf) == WIDE_MIN_NEIGHBOURS
    assert wide_minimum(600 * 31, epoch, cf) == 2
    _, off = ETParams(**{name: 0.0}).pack(31, 0, 0)
    assert wide_minimum(10**9, epoch, off) == WIDE_MIN_NEIGHBOURS


def test_by_default_both_growths_widen_at_two_neighbours_after_half_an_hour() -> None:
    _, cf = ETParams().pack(31, 0, 0)
    assert cf[F_TWO_WIDEN_TICKS] == 1800 * 31
    for growth in (0, 1):
        assert wide_minimum(1800 * 31 - 1, growth, cf) == WIDE_MIN_NEIGHBOURS
        assert wide_minimum(1800 * 31, growth, cf) == 2


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("regrowth_offsets", "forget"),
        ("two_neighbour_widen_s", -1.0),
        ("regrowth_two_neighbour_widen_s", -1.0),
    ],
)
def test_bad_values_are_rejected(name: str, value: object) -> None:
    with pytest.raises(EtswarmError, match=name):
        ETParams(**{name: value})


def test_the_codes_follow_the_option() -> None:
    codes = [ETParams(regrowth_offsets=m).pack(31, 0, 0)[0][C_REGROW_OFFSETS]
             for m in ("keep", "reset", "zero")]
    assert codes == [0, 1, 2]
