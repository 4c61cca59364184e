"""Real ET formations on the simulator: small shapes, several seeds, loss 0.2."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.measures.formation import duplicate_tags, in_holes, min_pair_distance
from etswarm.sim.params import SimParams

from .traced import NATIVE_MATHS, SESSION_57_SEARCH


def run_formation(shape: str, seed: int, max_time_s: float = 3600.0,
                  sim_params: SimParams | None = None, et: ETParams | None = None) -> ETRun:
    run = ETRun(RunConfig(shape=shape, seed=seed, max_time_s=max_time_s, et=et or ETParams()),
                sim_params=sim_params)
    run.run()
    return run


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_triangle_forms_at_loss_02(seed: int) -> None:
    run = run_formation("triangle", seed)
    summary = run.summary()
    assert summary["formed"], summary["states"]
    assert summary["jaccard"] == 1.0
    assert summary["duplicate_tags"] == []
    assert summary["formation_time_s"] is not None
    assert summary["formation_time_s"] < 3600
    # ... and the robots stand as their tags say: no neighbours torn apart.
    assert [c["stretched_links"] for c in summary["components"]] == [0]
    # Every target cell is held by exactly one Stable robot.
    stable = run.controller.states == State.STABLE
    held = {tuple(t) for t in run.controller.tags[stable].tolist()}
    assert held == {tuple(c) for c in run.target.tolist()}
    # Bodies never overlap beyond the collision tolerance.
    present = run.world.present
    assert min_pair_distance(run.world.pos, present) > 2 * 16.5 - 1.0


def test_same_seed_same_run() -> None:
    a = ETRun(RunConfig(shape="triangle", seed=5, max_time_s=600))
    b = ETRun(RunConfig(shape="triangle", seed=5, max_time_s=600))
    sa, sb = a.run(), b.run()
    assert np.array_equal(a.world.pos, b.world.pos)
    assert np.array_equal(a.controller.ri, b.controller.ri)
    for key in ("formed", "formation_time_s", "jaccard", "states", "placement_error_mm"):
        assert sa[key] == sb[key]


def test_extra_robots_stay_queued() -> None:
    run = ETRun(RunConfig(shape="triangle", robots=18, seed=1, max_time_s=3600))
    summary = run.run()
    assert summary["formed"], summary["states"]
    assert summary["states"]["Queued"] == 3
    assert duplicate_tags(run.controller.tags, run.controller.states >= State.INACTIVE) == []


def test_fewer_robots_than_cells_says_so() -> None:
    run = ETRun(RunConfig(shape="triangle", robots=10, seed=0, max_time_s=60))
    assert any("cannot be completed" in note for note in run.notes)
    fitted = ETRun(RunConfig(shape="triangle", robots=10, seed=0, max_time_s=60, fit=True))
    assert len(fitted.target) == 10


def test_a_queue_too_long_to_walk_says_so_and_names_the_cluster() -> None:
    long_queue = ETRun(RunConfig(shape="bigH", seed=0, max_time_s=60))
    assert any("queue of 318 robots is 14.3 m" in note and "--layout cluster" in note
               for note in long_queue.notes)
    cluster = ETRun(RunConfig(shape="bigH", seed=0, max_time_s=60, layout="cluster"))
    short_queue = ETRun(RunConfig(shape="starfish", seed=0, max_time_s=60))
    assert not any("queue" in note for note in cluster.notes + short_queue.notes)


def test_an_unfinished_run_says_which_sites_are_free_and_who_searches() -> None:
    from etswarm.algorithm.states import PLACED_STATES
    from etswarm.cli.run_outputs import describe

    run = run_formation("T", 0, max_time_s=900.0)
    summary = run.summary()
    assert not summary["formed"] and not summary["settled"]
    states = run.controller.states
    live = run.world.present & run.world.alive
    placed = live & np.isin(states, [int(s) for s in PLACED_STATES])
    held = {tuple(t) for t in run.controller.tags[placed].tolist()}
    target = {tuple(t) for t in run.target.tolist()}
    # The group holding the shape's robots lists exactly the target sites nobody holds.
    main = max(summary["components"], key=lambda c: c["robots"])
    assert main["free_sites"] == len(target - held) > 0
    assert {tuple(t) for t in main["free_tags"]} <= target - held
    assert len(main["free_tags"]) == min(main["free_sites"], 20)
    assert sum(c["searching"] for c in summary["components"]) == int(
        np.count_nonzero(live & (states == State.SEARCH))
    )
    assert any(f"{main['free_sites']} target sites free" in line for line in describe(summary))


#: bigplus seeds for the 300-cell test, and how many of them must form within 12 h. Since
#: session 53's portable maths a run is the same on every machine: session 58 measured
#: seeds 2, 5 and 6 formed in 7.1, 6.6 and 5.9 h (160, 38 and 33 s wall; session 47's
#: machine, before portable maths: 7.8, 7.0 and 6.6 h). Seed 2 was dropped to keep the
#: suite's time; 19 of seeds 0-19 formed within 12 h on session 45's machine.
BIGPLUS_SEEDS = (5, 6)
BIGPLUS_FORMED = 2


@pytest.mark.slow
def test_a_shape_of_300_cells_forms_from_the_cluster() -> None:
    """bigplus (300 cells, 300 robots) from a packed repository: in most runs every site
    is held by one Stable robot, with no bodies overlapping (docs/algorithm.md, "Thin
    shapes of 300+ cells" and "Session 45")."""
    formed = 0
    for seed in BIGPLUS_SEEDS:
        run = ETRun(RunConfig(shape="bigplus", seed=seed, max_time_s=12 * 3600.0,
                              layout="cluster"))
        summary = run.run()
        assert summary["duplicate_tags"] == []
        assert min_pair_distance(run.world.pos, run.world.present) > 2 * 16.5 - 1.0
        if not summary["formed"]:
            continue
        formed += 1
        assert summary["robots"] == 300 and summary["jaccard"] == 1.0
        stable = run.controller.states == State.STABLE
        held = {tuple(t) for t in run.controller.tags[stable].tolist()}
        assert held == {tuple(c) for c in run.target.tolist()}
    assert formed >= BIGPLUS_FORMED, f"{formed} of seeds {BIGPLUS_SEEDS} formed"


def test_the_ring_of_o_closes_only_once_the_edge_of_its_hole_is_held() -> None:
    # Seed 2 without the hole flag: a robot closes the ring while (-3, -2), on the hole's
    # edge, is free; the last searcher orbits outside, and the site is left to the hole.
    # With the flag the same seed forms.
    plain = ETRun(RunConfig(shape="O", seed=2, max_time_s=10800,
                            et=ETParams(hole_flag="off", **SESSION_57_SEARCH)),
                  sim_params=NATIVE_MATHS)
    summary = plain.run()
    assert not summary["formed"]
    assert [-3, -2] in summary["components"][0]["free_tags"]
    run = run_formation("O", 2, max_time_s=10800, sim_params=NATIVE_MATHS,
                        et=ETParams(**SESSION_57_SEARCH))
    summary = run.summary()
    assert summary["formed"], summary["components"]
    assert summary["jaccard"] == 1.0 and summary["duplicate_tags"] == []
    assert min_pair_distance(run.world.pos, run.world.present) > 2 * 16.5 - 1.0


def test_the_ring_of_o_stays_open_while_its_edge_sees_a_searcher_in_the_hole() -> None:
    # Seed 0 without the hole watch: the ring closes with every searcher shut in the hole,
    # and the sites they would take stay free outside. With the watch (the default) the
    # same seed forms (session 42).
    plain = ETRun(RunConfig(shape="O", seed=0, max_time_s=10800,
                            et=ETParams(hole_watch_s=0, **SESSION_57_SEARCH)),
                  sim_params=NATIVE_MATHS)
    summary = plain.run()
    assert not summary["formed"]
    states = plain.controller.states
    searching = states == State.SEARCH
    assert searching.sum() == len(summary["components"][0]["free_tags"])
    stable = states == State.STABLE
    assert in_holes(
        plain.world.pos[searching], plain.world.pos, plain.controller.tags, stable,
        plain.target, plain.config.et.spacing_mm,
    ).all()
    assert not in_holes(
        plain.world.pos[stable], plain.world.pos, plain.controller.tags, stable,
        plain.target, plain.config.et.spacing_mm,
    ).any()
    # the summary says so: every searcher of the group is shut in the hole
    assert summary["components"][0]["shut_in_holes"] == searching.sum() > 0
    assert summary["components"][0]["way_across"] is False  # the hole's edge is all held
    run = run_formation("O", 0, max_time_s=10800, sim_params=NATIVE_MATHS,
                        et=ETParams(**SESSION_57_SEARCH))
    summary = run.summary()
    assert summary["formed"], summary["components"]
    assert summary["jaccard"] == 1.0 and summary["duplicate_tags"] == []
    assert min_pair_distance(run.world.pos, run.world.present) > 2 * 16.5 - 1.0
