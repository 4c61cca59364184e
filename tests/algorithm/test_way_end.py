"""A ring's last way across closes from the hole's end (``way_end``), and first-formation
searchers at a ring plunge into notches' mouths (``way_plunge``)."""

from __future__ import annotations

from etswarm.algorithm.params import C_WAY_END, C_WAY_PLUNGE, ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.measures.formation import min_pair_distance

#: `O` seed 212 (session 67): without the two rules the run ends on the way (-2, -3) on
#: the hole's edge, (-3, -4), (-4, -5) beside the outside, every capture of it refused.
SEED = 212
WAY = [[-4, -5], [-3, -4], [-2, -3]]


def test_o_closes_its_last_way_across_from_the_holes_end() -> None:
    old = ETRun(RunConfig(shape="O", seed=SEED, max_time_s=14400.0,
                          et=ETParams(way_end="off", way_plunge="off")))
    summary = old.run()
    assert not summary["formed"]
    group = summary["components"][0]
    assert sorted(group["free_tags"]) == WAY
    assert group["way_across"] is True
    run = ETRun(RunConfig(shape="O", seed=SEED, max_time_s=14400.0))
    summary = run.run()
    assert summary["formed"], summary["components"]
    assert summary["jaccard"] == 1.0 and summary["duplicate_tags"] == []
    assert summary["formation_time_s"] < 14400.0
    assert min_pair_distance(run.world.pos, run.world.present) > 2 * 16.5 - 1.0


def test_the_rules_act_only_on_targets_with_holes() -> None:
    flags = {shape: (int(ETRun(RunConfig(shape=shape)).controller.ci[C_WAY_END]),
                     int(ETRun(RunConfig(shape=shape)).controller.ci[C_WAY_PLUNGE]))
             for shape in ("O", "T", "starfish")}
    # way_end acts only beside a hole site, which a shape without holes lacks
    assert flags == {"O": (1, 1), "T": (1, 0), "starfish": (1, 0)}
    off = ETRun(RunConfig(shape="O", et=ETParams(way_end="off", way_plunge="off")))
    assert (off.controller.ci[C_WAY_END], off.controller.ci[C_WAY_PLUNGE]) == (0, 0)
