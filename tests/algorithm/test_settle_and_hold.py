"""Options that speed the first formation up: a settled searcher's wider confirmation
window and its retries (``settle_tol_scale``, ``settle_retries``), and the release hold
that searchers queuing at the shape send back along the repository (``release_hold_s``)."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.controller import encode
from etswarm.algorithm.localise import find_site, window_centre
from etswarm.algorithm.memory import (
    NB_ANCHORED,
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_MASK,
    NB_STATE,
    NB_TS,
    NB_TX,
    NB_TY,
    R_HOLD_UNTIL,
    R_QMIN_SINCE,
    R_STATE,
    R_YIELD_SINCE,
    allocate,
)
from etswarm.algorithm.messages import HOLD_UNIT_TICKS, YIELDING_BIT
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.release import queued_rule
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.search import NO_SITE, begin_search
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError

from .find_site_args import ANYWHERE
from .traced import SESSION_57_SEARCH

TICK = 100_000
#: An empty memory of held sites (window, origin) for ``find_site``.
NO_MEMORY = (np.zeros((9, 9), dtype=np.uint8), -4, -4)


def site_between(dist_mm: float, plain_scale: float) -> bool:
    """Robot 0 hears Active A on (0, 0) and Stable B on (1, 0) at ``dist_mm`` each, and
    Stable C on (0, -1) (the mirror site, so it is on (1, 1)) at 69 mm: does the
    confirmation (strict, readings since tick 0) find (1, 1)?"""
    gene = np.ones((7, 7), dtype=np.int64)
    ci, cf = ETParams().pack(31, gene_x0=-3, gene_y0=-3)
    _, nb, nb_dist = allocate(1)
    robots = [((0, 0), State.ACTIVE, dist_mm), ((1, 0), State.STABLE, dist_mm)]
    robots.append(((0, -1), State.STABLE, 69.3))
    for slot, ((x, y), state, dist) in enumerate(robots):
        nb[0, slot, NB_ID] = slot + 1
        nb[0, slot, NB_STATE] = state
        nb[0, slot, NB_TX] = x
        nb[0, slot, NB_TY] = y
        nb[0, slot, NB_MASK] = 0
        nb[0, slot, NB_TS] = 1
        nb[0, slot, NB_LAST] = 10
        nb_dist[0, slot] = dist
    found, x, y, _ = find_site(
        0, 10, 0, True, -1, -1, 0, nb, nb_dist, gene, ci, cf, 1.0, 3, *NO_MEMORY,
        window_centre(cf, 0), plain_scale, NO_SITE, NO_SITE, *ANYWHERE,
    )
    return bool(found) and (x, y) == (1, 1)


def test_a_wider_confirmation_window_takes_a_site_just_beyond_the_capture_window() -> None:
    # The window is d - 2 +- 4 mm: 34-42 mm. Traced on T seed 0: a robot stopped 41-42 mm
    # from both references and read 42.3 mm on confirming.
    assert site_between(40.0, 1.0)
    assert not site_between(42.5, 1.0)
    assert site_between(42.5, 1.5)  # 38 +- 6 mm
    assert not site_between(44.5, 1.5)


def queued_robot(hold_s: float):  # type: ignore[no-untyped-def]
    """Queued robot 0, the lowest ID it hears (Queued robot 5), free to leave but for what
    it hears; returns (ri, nb, ci)."""
    ri, nb, _ = allocate(10)
    ri[:, R_QMIN_SINCE] = 0
    nb[0, 0, NB_ID] = 5
    nb[0, 0, NB_STATE] = State.QUEUED
    nb[0, 0, NB_EPOCH] = 0
    nb[0, 0, NB_LAST] = TICK
    ci, _ = ETParams(release_hold_s=hold_s).pack(31, 0, 0)
    return ri, nb, ci


def hear_searcher(nb: np.ndarray, byte6: int) -> None:
    nb[0, 1, NB_ID] = 8
    nb[0, 1, NB_STATE] = State.SEARCH
    nb[0, 1, NB_EPOCH] = 0
    nb[0, 1, NB_LAST] = TICK
    nb[0, 1, NB_ANCHORED] = byte6


def leaves_at(ri: np.ndarray, nb: np.ndarray, ci: np.ndarray, ticks: list[int]) -> list[bool]:
    """Run the Queued rule at TICK (when it heard its neighbours), then at each of
    ``ticks`` after it; whether robot 0 had left by each."""
    queued_rule(0, TICK, ri, nb, ci, 100)
    out = []
    for t in ticks:
        nb[0, 0, NB_LAST] = TICK + t  # the Queued neighbour is still heard
        queued_rule(0, TICK + t, ri, nb, ci, 100)
        out.append(bool(ri[0, R_STATE] == State.SEARCH))
    return out


@pytest.mark.parametrize("hold_s", [0.0, 20.0])
def test_a_yielding_searcher_holds_the_release(hold_s: float) -> None:
    ri, nb, ci = queued_robot(hold_s)
    hear_searcher(nb, YIELDING_BIT)
    # 16 s after the searcher was heard the clear time (15 s) is over; 21 s after, the hold.
    left = leaves_at(ri, nb, ci, [16 * 31, 21 * 31])
    assert left == ([True, True] if hold_s == 0 else [False, True])


def test_a_searcher_moving_freely_holds_nothing() -> None:
    ri, nb, ci = queued_robot(20.0)
    hear_searcher(nb, 1)  # anchored, not yielding
    assert leaves_at(ri, nb, ci, [16 * 31]) == [True]


def test_the_hold_passes_along_the_repository_one_unit_shorter() -> None:
    ri, nb, ci = queued_robot(20.0)
    nb[0, 0, NB_ANCHORED] = 10  # robot 5 holds for 10 more units
    queued_rule(0, TICK, ri, nb, ci, 100)
    assert ri[0, R_HOLD_UNTIL] == TICK + 9 * HOLD_UNIT_TICKS
    out_on = np.zeros(10, dtype=np.bool_)
    out_type = np.zeros(10, dtype=np.uint8)
    out_data = np.zeros((10, 9), dtype=np.uint8)
    encode(0, TICK, ri, 0, out_on, out_type, out_data)
    assert out_data[0, 6] == 9
    encode(0, TICK + 9 * HOLD_UNIT_TICKS, ri, 0, out_on, out_type, out_data)
    assert out_data[0, 6] == 0  # over: it passes nothing on, so no hold circulates


def test_a_searcher_says_when_it_yields() -> None:
    ri, _, _ = allocate(1)
    begin_search(0, 0, ri)
    out_on = np.zeros(1, dtype=np.bool_)
    out_type = np.zeros(1, dtype=np.uint8)
    out_data = np.zeros((1, 9), dtype=np.uint8)
    encode(0, 10, ri, 0, out_on, out_type, out_data)
    assert not out_data[0, 6] & YIELDING_BIT
    ri[0, R_YIELD_SINCE] = 5
    encode(0, 10, ri, 0, out_on, out_type, out_data)
    assert out_data[0, 6] & YIELDING_BIT


@pytest.mark.parametrize(
    ("name", "value"),
    [("settle_retries", -1), ("release_hold_s", -5.0), ("settle_tol_scale", 0.5),
     ("widen_s", 0.0)],
)
def test_bad_values_are_rejected(name: str, value: float) -> None:
    with pytest.raises(EtswarmError, match=name):
        ETParams(**{name: value})


@pytest.mark.parametrize("seed", [0, 9])
def test_t_forms_with_retries_and_hold(seed: int) -> None:
    # the consistency settings these runs were measured with (session 10), no gossip
    et = ETParams(
        settle_retries=3, release_hold_s=20.0, consistency_widen_max=1.0,
        fill_lookahead="off", held_gossip_every=0, **SESSION_57_SEARCH,
    )
    run = ETRun(RunConfig(shape="T", seed=seed, max_time_s=3 * 3600, et=et))
    summary = run.run()
    assert summary["formed"]
    assert summary["jaccard"] == 1.0
    assert summary["duplicate_tags"] == []
    # Faster than the defaults' median for T (80 min): robots place on their first pass.
    assert summary["formation_time_s"] < 80 * 60
