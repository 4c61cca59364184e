"""An Active robot far off its site by its own estimate searches for it again
(``ETParams.offset_leave_mm``, ``rejoin.leave_if_far``).

Traced on `T` `kill random=0.1` (session 51): on seed 32 robots 14 and 10 took (3, 1) and
(2, 0) after the damage and refined their offsets from each other's readings; the two
estimates slid the same way, to about 80 mm, while both robots stood within 10 mm of their
sites. Searchers expected to read them from where they claimed to stand, and the free
sites beside them were never taken.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import (
    R_FIELDS,
    R_GROWTH,
    R_LEFT,
    R_LEFT_X,
    R_LEFT_Y,
    R_OFF_REFINE,
    R_OFF_X,
    R_OFF_Y,
    R_STATE,
    R_TAG_X,
    R_TAG_Y,
)
from etswarm.algorithm.offsets import FINE_PER_MM
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.rejoin import leave_if_far
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError

from .traced import NATIVE_MATHS, SESSION_53_REGROWTH

TAG = (2, 1)


def active_robot(off_mm: tuple[float, float], refining: bool,
                 regrowth: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """One Active robot on TAG with offset ``off_mm`` (x, y), of a regenerated target or
    of the first formation, and its memory of held sites (tags 0..4 in both axes) with
    its own tag in it."""
    ri = np.zeros((1, R_FIELDS), dtype=np.int64)
    ri[0, R_GROWTH] = 1 if regrowth else 0
    ri[0, R_STATE] = State.ACTIVE
    ri[0, R_TAG_X], ri[0, R_TAG_Y] = TAG
    ri[0, R_OFF_X] = round(off_mm[0] * FINE_PER_MM)
    ri[0, R_OFF_Y] = round(off_mm[1] * FINE_PER_MM)
    ri[0, R_OFF_REFINE] = int(refining)
    held = np.zeros((5, 5), dtype=np.uint8)
    held[TAG] = 1
    return ri, held


def test_a_robot_whose_estimate_reaches_the_limit_leaves_its_site() -> None:
    ci, _ = ETParams(offset_leave_mm=35).pack(31, gene_x0=-5, gene_y0=-5)
    ri, held = active_robot((-30.0, 18.5), refining=True)  # 35.2 mm
    assert leave_if_far(0, 1000, ri, ci, held, 0, 0)
    assert ri[0, R_STATE] == State.SEARCH
    assert (ri[0, R_LEFT], ri[0, R_LEFT_X], ri[0, R_LEFT_Y]) == (1, *TAG)
    assert held[TAG] == 0  # it alone counts its old site free


def test_a_robot_nearer_its_site_not_refining_or_in_a_first_formation_stays() -> None:
    on, _ = ETParams(offset_leave_mm=35).pack(31, gene_x0=-5, gene_y0=-5)
    off, _ = ETParams(offset_leave_mm=0).pack(31, gene_x0=-5, gene_y0=-5)
    for consts, off_mm, refining, regrowth in (
        (on, (-30.0, 17.5), True, True),  # 34.7 mm
        (on, (60.0, 0.0), False, True),  # a seed, or kept through a regeneration: frozen
        (on, (60.0, 0.0), True, False),  # the first formation
        (off, (60.0, 0.0), True, True),
    ):
        ri, held = active_robot(off_mm, refining, regrowth)
        assert not leave_if_far(0, 1000, ri, consts, held, 0, 0)
        assert ri[0, R_STATE] == State.ACTIVE
        assert held[TAG] == 1


def run_kill(seed: int, **options: float) -> dict:
    """Summary of `T` `kill random=0.1` with ``options`` set, over the default 4 h, with
    the pocket rule alone after damage (``SESSION_53_REGROWTH``): since session 54 the
    two-neighbour window re-forms both seeds without any robot leaving."""
    run = ETRun(RunConfig(shape="T", seed=seed, damage=("kill random=0.1",),
                          et=ETParams(**{**SESSION_53_REGROWTH, **options})),
                sim_params=NATIVE_MATHS)
    return run.run()


@pytest.mark.parametrize("seed", [3, 32])
def test_the_killed_t_re_forms_only_when_far_robots_leave(seed: int) -> None:
    for limit, formed in ((35.0, True), (0.0, False)):
        summary = run_kill(seed, offset_leave_mm=limit)
        (group,) = summary["components"]
        assert group["robots"] == group["census_count"] == 41
        assert group["formed"] is formed
        assert (group["jaccard"] == 1.0) is formed
        assert summary["duplicate_tags"] == []
        assert summary["max_leaders_per_component"] <= 1


def test_offset_leave_mm_may_be_zero_but_not_negative() -> None:
    assert ETParams(offset_leave_mm=0).offset_leave_mm == 0
    with pytest.raises(EtswarmError, match="offset_leave_mm"):
        ETParams(offset_leave_mm=-1)
