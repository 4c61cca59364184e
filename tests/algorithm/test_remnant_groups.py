"""The summary's remnants are the radio groups of robots that work for one target (for a
remnant too small to regrow, the robots its census counted), not whoever stands within
radio range at the end."""

from __future__ import annotations

from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.cli.run_outputs import describe

from .traced import NATIVE_MATHS, SESSION_44_FORMATION


def test_a_robot_the_cut_left_alone_stays_a_remnant_of_its_own() -> None:
    # `T` seed 7 cut at x=0: robot 12 is left alone on the cut line, counts itself and
    # stays put; the 11-robot half regrows to within radio range of it without merging.
    run = ETRun(RunConfig(shape="T", seed=7, max_time_s=3 * 3600, damage=("split x=0",),
                          et=ETParams(**SESSION_44_FORMATION)), sim_params=NATIVE_MATHS)
    summary = run.run()
    assert summary["settled"], summary["components"]
    comps = summary["components"]
    assert sum(c["robots"] for c in comps) == 45
    alone = [c for c in comps if c["too_small"]]
    assert [c["robots"] for c in alone] == [1]
    for comp in comps:
        assert comp["census_count"] == comp["robots"], comp
        assert comp["formed"] == (not comp["too_small"]), comp
    # It does stand within radio range of the regrown half.
    (stray,) = [e["leader"] for e in summary["events"]
                if e["kind"] == "census" and e["count"] == 1]
    near = run._radio_group_of(stray)
    assert len(near) > 1


def test_three_robots_with_no_two_neighbours_are_too_small_and_stay_put() -> None:
    # `T` seed 4 cut at x=0 leaves robots 30, 32 and 41 on (-1, -2), (0, 0) and (-2, -4),
    # about 70 mm apart: no two on neighbouring sites. Before session 46 their Leader
    # kept one of them on a scaled `T`, the other two searched for hours and got lost,
    # as no site can be located from one robot, and the run never settled.
    run = ETRun(RunConfig(shape="T", seed=4, max_time_s=4 * 3600, damage=("split x=0",),
                          et=ETParams(**SESSION_44_FORMATION)), sim_params=NATIVE_MATHS)
    summary = run.run()
    assert summary["settled"] and summary["sim_time_s"] < 4 * 3600, summary["components"]
    (small,) = [c for c in summary["components"] if c["too_small"]]
    assert small["robots"] == small["census_count"] == 3 and small["target_cells"] == 0
    assert summary["states"]["Search"] == 0
    assert any(line.endswith("3 robots, census 3 (tree), too small to seed a scaled shape, "
                             "stays put") for line in describe(summary)), describe(summary)
    for comp in summary["components"]:
        if not comp["too_small"]:
            assert comp["formed"] and comp["census_count"] == comp["robots"], comp
