"""How fast a searcher long at the shape widens its windows: first formation and regrowth."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.params import (
    C_PINCH_REFUSALS,
    C_REGROW_PINCH_REFUSALS,
    F_REGROW_WIDEN_TICKS,
    F_WIDEN_TICKS,
    ETParams,
)
from etswarm.algorithm.search import dive_depth, widening_ticks
from etswarm.errors import EtswarmError

from .traced import NATIVE_MATHS, SESSION_34_FORMATION, SESSION_57_SEARCH


def packed(**options: float) -> tuple[np.ndarray, np.ndarray]:
    ci, cf = ETParams(**options).pack(31, 0, 0)
    return ci, cf


def test_the_first_formation_and_a_regrowth_widen_over_their_own_times() -> None:
    ci, cf = packed(widen_s=400.0, regrowth_widen_s=1200.0, capture_pinch_refusals=4,
                    regrowth_pinch_refusals=2)
    assert cf[F_WIDEN_TICKS] == 400 * 31 and cf[F_REGROW_WIDEN_TICKS] == 1200 * 31
    assert widening_ticks(0, cf) == 400 * 31
    assert widening_ticks(3, cf) == 1200 * 31
    assert (ci[C_PINCH_REFUSALS], ci[C_REGROW_PINCH_REFUSALS]) == (4, 2)


def test_the_dive_follows_the_widening_time_of_its_target() -> None:
    _, cf = packed(widen_s=400.0, regrowth_widen_s=1200.0, dive_mm=3.0, regrowth_dive_mm=3.0)
    # first formation: no dive during the first widening time, full after two
    assert dive_depth(400 * 31, 0, cf) == 0.0
    assert dive_depth(800 * 31, 0, cf) == pytest.approx(3.0)
    # after damage: the dive grows over the regrowth's (longer) widening time
    assert dive_depth(600 * 31, 1, cf) == pytest.approx(1.5)
    assert dive_depth(1200 * 31, 1, cf) == pytest.approx(3.0)


@pytest.mark.parametrize(("name", "value"),
                         [("regrowth_widen_s", 0.0), ("regrowth_pinch_refusals", -1)])
def test_bad_values_are_rejected(name: str, value: float) -> None:
    with pytest.raises(EtswarmError, match=name):
        ETParams(**{name: value})


def test_faster_widening_fills_the_last_site_sooner() -> None:
    from etswarm.algorithm.run import ETRun, RunConfig

    # T seed 30 with windows widening over 20 min: its last searcher went round the
    # shape for 20 min before it could take the last site (session 20).
    slow = ETRun(RunConfig(shape="T", seed=30, max_time_s=3 * 3600,
                           et=ETParams(widen_s=1200.0, capture_pinch_refusals=2,
                                       **SESSION_34_FORMATION)), sim_params=NATIVE_MATHS).run()
    fast = ETRun(RunConfig(shape="T", seed=30, max_time_s=3 * 3600,
                           et=ETParams(**SESSION_34_FORMATION)), sim_params=NATIVE_MATHS).run()
    for summary in (slow, fast):
        assert summary["formed"] and summary["jaccard"] == 1.0
        assert summary["duplicate_tags"] == []
    assert fast["formation_time_s"] <= slow["formation_time_s"] - 600


def test_a_tip_with_two_neighbours_gets_the_wide_window_late_in_the_first_formation() -> None:
    from etswarm.algorithm.run import ETRun, RunConfig

    # H seed 62 (session 27): the last free site, (1, 5), is the top corner of a leg with
    # two placed neighbours, both standing about 30 mm off their sites. Without the wide
    # window there (only pockets of three neighbours got it) the last searcher went round
    # the H for the rest of the 4 h run.
    def run(**options: float) -> dict:
        config = RunConfig(shape="H", seed=62, max_time_s=4 * 3600,
                           et=ETParams(**{**SESSION_34_FORMATION, **options}))
        return ETRun(config, sim_params=NATIVE_MATHS).run()

    default = run()
    assert default["formed"] and default["jaccard"] == 1.0
    assert default["duplicate_tags"] == []
    never = run(two_neighbour_widen_s=0.0)
    assert not never["formed"]
    (group,) = never["components"]
    assert group["free_tags"] == [[1, 5]] and group["searching"] == 1


def test_a_regrowing_leg_gets_the_wide_window_at_two_neighbours_after_half_an_hour() -> None:
    from etswarm.algorithm.run import ETRun, RunConfig

    # H split y=mid seed 13 (sessions 53-54): the cut leaves the crossbar's half and two
    # legs. One leg's last free sites, (0, 1) and (1, 1), have two placed neighbours each
    # heard by the searchers, one of them standing 13 mm into (0, 1); with the pocket rule
    # alone its two searchers went round the leg for the last three hours.
    def run(**options: float) -> dict:
        config = RunConfig(shape="H", seed=13, damage=("split y=mid",), max_time_s=4 * 3600,
                           et=ETParams(**{**SESSION_57_SEARCH, **options}))
        return ETRun(config).run()

    default = run()
    assert default["formed"] and default["duplicate_tags"] == []
    remnants = [c for c in default["components"] if c["robots"] >= 6]
    assert len(remnants) == 3
    assert all(c["formed"] and c["jaccard"] == 1.0 for c in remnants)
    assert max(c["time_to_stable_s"] for c in remnants) > 1800  # the late window did it
    never = run(regrowth_two_neighbour_widen_s=0.0)
    stalled = [c for c in never["components"] if c["robots"] >= 6 and not c["formed"]]
    assert [(c["free_tags"], c["searching"]) for c in stalled] == [([[0, 1], [1, 1]], 2)]
