"""A Stable robot pushed out of its neighbours' range leaves its site and takes it again."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    R_EXCUSED,
    R_FIELDS,
    R_GROWTH,
    R_LEFT,
    R_LEFT_X,
    R_LEFT_Y,
    R_STATE,
    R_TAG_X,
    R_TAG_Y,
    allocate,
)
from etswarm.algorithm.params import C_TICKS_REJOIN, ETParams
from etswarm.algorithm.rejoin import ALONE_REJOINS, rejoin_if_alone, rejoin_if_cut_off
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.measures.formation import components

from .traced import NATIVE_MATHS, SESSION_54_REGROWTH

TAG = (2, 1)


def stable_robot() -> tuple[np.ndarray, np.ndarray]:
    """One Stable robot on TAG whose missing neighbours a false alarm excused, and its
    memory of held sites (tags 0..4 in both axes) with its own tag in it."""
    ri = np.zeros((1, R_FIELDS), dtype=np.int64)
    ri[0, R_STATE] = State.STABLE
    ri[0, R_TAG_X], ri[0, R_TAG_Y] = TAG
    ri[0, R_EXCUSED] = 0b000011
    held = np.zeros((5, 5), dtype=np.uint8)
    held[TAG] = 1
    return ri, held


def test_it_leaves_only_after_hearing_nobody_for_the_whole_wait() -> None:
    ci, _ = ETParams().pack(31, gene_x0=-5, gene_y0=-5)
    wait = int(ci[C_TICKS_REJOIN])
    assert wait == 120 * 31
    ri, held = stable_robot()
    assert not rejoin_if_cut_off(0, 100, False, True, ri, ci, held, 0, 0)
    # A placed robot heard in between starts the wait again.
    assert not rejoin_if_cut_off(0, 100 + wait // 2, True, True, ri, ci, held, 0, 0)
    assert not rejoin_if_cut_off(0, 101 + wait // 2, False, True, ri, ci, held, 0, 0)
    assert not rejoin_if_cut_off(0, 100 + wait, False, True, ri, ci, held, 0, 0)
    assert ri[0, R_STATE] == State.STABLE
    assert rejoin_if_cut_off(0, 101 + wait // 2 + wait, False, True, ri, ci, held, 0, 0)
    assert ri[0, R_STATE] == State.SEARCH
    assert (ri[0, R_LEFT], ri[0, R_LEFT_X], ri[0, R_LEFT_Y]) == (1, *TAG)
    assert ri[0, R_EXCUSED] == 0
    assert held[TAG] == 0  # it alone counts its old site free


def test_a_robot_that_counts_heard_or_reported_neighbours_stays() -> None:
    # Not Stable only by excused sites (it is alone after damage, or hears reports): it
    # never leaves; nor does any robot with the rule off.
    ci, _ = ETParams().pack(31, gene_x0=-5, gene_y0=-5)
    off, _ = ETParams(isolated_rejoin_s=0).pack(31, gene_x0=-5, gene_y0=-5)
    for consts, excused_only in ((ci, False), (off, True)):
        ri, held = stable_robot()
        for tick in range(0, 20 * int(ci[C_TICKS_REJOIN]), 500):
            assert not rejoin_if_cut_off(0, tick, False, excused_only, ri, consts, held, 0, 0)
        assert ri[0, R_STATE] == State.STABLE


def run_cut(et: ETParams) -> ETRun:
    run = ETRun(RunConfig(shape="H", seed=0, damage=("split x=mid",), et=et),
                sim_params=NATIVE_MATHS)
    run.run()
    return run


def test_a_tip_robot_shoved_out_of_range_goes_back_to_its_site() -> None:
    # H split x=mid seed 0: searchers going round the right remnant shove robot 31, on
    # its tip (4, 4), 80 mm from its nearest neighbour; two false alarms excuse its
    # missing neighbours. Without the rule every robot ends Stable, robot 31 alone.
    plain = run_cut(ETParams(isolated_rejoin_s=0, **SESSION_54_REGROWTH))
    live = plain.world.present & plain.world.alive
    groups = components(plain.world.pos, live, 70.0)
    assert sorted(len(g) for g in groups) == [1, 23, 26]
    assert np.all(plain.controller.states[live] == State.STABLE)
    assert not plain.summary()["components"][1]["formed"]
    # With it the robot leaves, comes back round the remnant and takes (4, 4) again.
    run = run_cut(ETParams(**SESSION_54_REGROWTH))
    summary = run.summary()
    assert [c["robots"] for c in summary["components"]] == [26, 24]
    assert all(c["formed"] and c["jaccard"] == 1.0 for c in summary["components"])
    assert summary["duplicate_tags"] == []


def table(heard_at: int | None) -> np.ndarray:
    """Robot 0's neighbour table: empty, or robot 5 last heard at tick ``heard_at``."""
    _, nb, _ = allocate(1)
    if heard_at is not None:
        nb[0, 0, NB_ID] = 5
        nb[0, 0, NB_LAST] = heard_at
    return nb


def test_an_active_robot_of_a_regrowth_that_hears_nobody_leaves_after_the_longer_wait() -> None:
    # Session 46, starfish split y=mid seed 14: kept robot 6 stood 81 mm from every other
    # robot and stayed Active for 1.6 h, its site free.
    ci, _ = ETParams().pack(31, gene_x0=-5, gene_y0=-5)
    wait = ALONE_REJOINS * int(ci[C_TICKS_REJOIN])
    ri, held = stable_robot()
    ri[0, R_STATE] = State.ACTIVE
    ri[0, R_GROWTH] = 1  # it works for a regrown target
    assert not rejoin_if_alone(0, 100, ri, table(None), ci, held, 0, 0)
    mid = 100 + wait // 2
    assert not rejoin_if_alone(0, mid, ri, table(mid), ci, held, 0, 0)  # heard one
    assert not rejoin_if_alone(0, 101 + wait // 2, ri, table(None), ci, held, 0, 0)
    assert not rejoin_if_alone(0, 100 + wait, ri, table(None), ci, held, 0, 0)
    assert ri[0, R_STATE] == State.ACTIVE
    assert rejoin_if_alone(0, 101 + wait // 2 + wait, ri, table(None), ci, held, 0, 0)
    assert ri[0, R_STATE] == State.SEARCH
    assert (ri[0, R_LEFT], ri[0, R_LEFT_X], ri[0, R_LEFT_Y]) == (1, *TAG)
    assert held[TAG] == 0


def test_an_active_robot_of_the_first_formation_never_leaves_alone() -> None:
    ci, _ = ETParams().pack(31, gene_x0=-5, gene_y0=-5)
    off, _ = ETParams(isolated_rejoin_s=0).pack(31, gene_x0=-5, gene_y0=-5)
    for consts, growth in ((ci, 0), (off, 1)):
        ri, held = stable_robot()
        ri[0, R_STATE] = State.ACTIVE
        ri[0, R_GROWTH] = growth
        for tick in range(0, 20 * ALONE_REJOINS * int(ci[C_TICKS_REJOIN]), 2000):
            assert not rejoin_if_alone(0, tick, ri, table(None), consts, held, 0, 0)
        assert ri[0, R_STATE] == State.ACTIVE
