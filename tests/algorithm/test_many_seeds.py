"""The bugs that matter, over many seeds at loss 0.2: two robots on one tag, overlapping
bodies, two Leaders in a remnant, robots left in Danger or Leader, and formation that
stops completing (a floor under today's success share, so a regression shows)."""

from __future__ import annotations

import pytest

from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.measures.formation import min_pair_distance
from etswarm.sim.params import SimParams

from .traced import NATIVE_MATHS

SEEDS = range(20)


def run_summary(shape: str, seed: int, damage: tuple[str, ...] = ()) -> tuple[ETRun, dict]:
    run = ETRun(RunConfig(shape=shape, seed=seed, max_time_s=3600.0, damage=damage))
    return run, run.run()


def formed_keeping_the_invariants(shape: str, max_time_s: float,
                                  sim_params: SimParams | None = None) -> int:
    """Run ``shape`` over ``SEEDS``; assert in every run no tag held twice, no bodies
    overlapping, at most one Leader per remnant and Jaccard 1 when formed. Returns how
    many runs formed."""
    formed = 0
    for seed in SEEDS:
        run = ETRun(RunConfig(shape=shape, seed=seed, max_time_s=max_time_s),
                    sim_params=sim_params)
        summary = run.run()
        assert summary["duplicate_tags"] == [], (seed, summary["duplicate_tags"])
        assert min_pair_distance(run.world.pos, run.world.present) > 2 * 16.5 - 1.0, seed
        assert summary["max_leaders_per_component"] <= 1, seed
        if summary["formed"]:
            assert summary["jaccard"] == 1.0, seed
            formed += 1
    return formed


@pytest.mark.slow
def test_triangle_over_twenty_seeds_keeps_the_invariants() -> None:
    formed = formed_keeping_the_invariants("triangle", 3600.0)
    # Measured 20 of 20 (16 before searchers crept near sites); issue 4 wants 19 of 20.
    assert formed >= 18, formed


@pytest.mark.slow
def test_triangle_split_over_twenty_seeds_elects_one_leader_per_remnant() -> None:
    reformed = 0
    for seed in SEEDS:
        _, summary = run_summary("triangle", seed, damage=("split x=0 at=formed+30",))
        if not summary["formed"]:
            continue  # the damage never came; the formation test covers these seeds
        assert summary["max_leaders_per_component"] <= 1, seed
        for event in summary["events"]:
            if event["kind"] == "census":  # exact: the count is the remnant's true size
                assert event["count"] == event["robots"], (seed, event)
        assert summary["duplicate_tags"] == [], seed
        if summary["settled"]:
            assert summary["states"]["Danger"] == 0, seed
            assert summary["states"]["Leader"] == 0, seed
            reformed += 1
    # Measured: 20 seeds formed, 18 of them re-formed both halves within the hour (13 of
    # 16 before searchers crept near sites).
    assert reformed >= 16, reformed


@pytest.mark.slow
def test_o_over_twenty_seeds_keeps_the_invariants_with_the_hole_watch() -> None:
    # The watch adds a message kind and holds captures back: no tag may be held twice, no
    # bodies overlap, and the ring still closes as often as measured.
    # Traced with the platform's maths: with the portable maths (the default since
    # session 53) these seeds take other courses, and 7 of them formed.
    formed = formed_keeping_the_invariants("O", 4 * 3600.0, NATIVE_MATHS)
    # Measured 15 of 20 (session 43; 8 before the hole watch, "Sessions 42-43" in
    # docs/algorithm.md).
    assert formed >= 12, formed
