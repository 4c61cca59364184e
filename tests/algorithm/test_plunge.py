"""``regrowth_plunge_s``: a searcher long at the shape that stopped on a site and could not
confirm it edge-follows at ``PLUNGE_AIM_MM`` for a while, so that it gets through a notch's
mouth narrower than twice its usual aim to the site at the bottom. After damage "long" is
``regrowth_widen_s``; in the first formation it is ``first_plunge_after_s``, and never on
a target with holes."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_CAND_X,
    R_CAND_Y,
    R_GROWTH,
    R_PLUNGE_UNTIL,
    R_SHAPE_SINCE,
    R_SUB,
    R_SUB_SINCE,
    SUB_FOLLOW,
    SUB_SETTLE,
    allocate,
)
from etswarm.algorithm.params import C_FIRST_PLUNGE, ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.search import PLUNGE_AIM_MM, begin_search, search_rule
from etswarm.algorithm.states import State
from etswarm.measures.formation import duplicate_tags, min_pair_distance
from etswarm.sim.world import FORWARD, LEFT, RIGHT

from .traced import NATIVE_MATHS, SESSION_54_REGROWTH, SESSION_57_SEARCH

TICKS_PER_S = 31
TICK = 200_000
SEARCHER = 5
#: A searcher this long at the shape has finished widening and diving (regrowth_widen_s).
LONG_AT_SHAPE_TICKS = 3 * 1200 * TICKS_PER_S


def searcher(growth: int, reading_mm: float, *, settling: bool = False,
             plunge_s: float = 20.0, first_after_s: float = 800.0,
             at_shape_s: float = 3 * 1200, plunge_aim_mm: float = PLUNGE_AIM_MM) -> tuple:
    """Searcher 5, ``at_shape_s`` at the shape, hearing one Stable robot on tag (0, 0) at
    ``reading_mm``; ``growth`` 0 is the first formation, 1 a regenerated target, whose
    plunges keep ``plunge_aim_mm`` (35 mm, as every plunge before session 70). With
    ``settling`` it has stood on site (1, 0) for its settle time, where it cannot confirm
    the site (one robot locates nothing). Returns what ``search_rule`` needs."""
    gene = np.ones((5, 5), dtype=np.int64)
    params = ETParams(regrowth_plunge_s=plunge_s, first_plunge_after_s=first_after_s,
                      regrowth_plunge_aim_mm=plunge_aim_mm)
    ci, cf = params.pack(TICKS_PER_S, gene_x0=-2, gene_y0=-2)
    ri, nb, nb_dist = allocate(30)
    begin_search(SEARCHER, TICK - LONG_AT_SHAPE_TICKS, ri)
    ri[SEARCHER, R_SHAPE_SINCE] = TICK - round(at_shape_s * TICKS_PER_S)
    ri[SEARCHER, R_GROWTH] = growth
    nb[SEARCHER, 0, NB_ID] = 20
    nb[SEARCHER, 0, NB_STATE] = State.STABLE
    nb[SEARCHER, 0, NB_LAST] = TICK
    nb[SEARCHER, 0, NB_TX] = 0
    nb[SEARCHER, 0, NB_TY] = 0
    nb_dist[SEARCHER, 0] = reading_mm
    if settling:
        ri[SEARCHER, R_SUB] = SUB_SETTLE
        ri[SEARCHER, R_SUB_SINCE] = TICK - 10 * TICKS_PER_S
        ri[SEARCHER, R_CAND_X] = 1
        ri[SEARCHER, R_CAND_Y] = 0
    motor = np.full(30, FORWARD, dtype=np.int64)
    held = np.zeros((30, 5, 5), dtype=np.uint8)
    return gene, ci, cf, ri, nb, nb_dist, motor, held


def step(gene, ci, cf, ri, nb, nb_dist, motor, held) -> int:  # type: ignore[no-untyped-def]
    search_rule(SEARCHER, TICK, False, ri, nb, nb_dist, motor, gene, gene, ci, cf, held, -2, -2)
    return int(motor[SEARCHER])


def test_a_failed_confirmation_after_damage_starts_a_plunge() -> None:
    world = searcher(growth=1, reading_mm=40.0, settling=True)
    step(*world)
    ri = world[3]
    assert ri[SEARCHER, R_SUB] == SUB_FOLLOW  # it could not confirm, and moves on
    assert ri[SEARCHER, R_PLUNGE_UNTIL] == TICK + 20 * TICKS_PER_S


@pytest.mark.parametrize(("at_shape_s", "plunges"), [(790.0, False), (810.0, True)])
def test_in_the_first_formation_a_searcher_plunges_after_first_plunge_after_s(
    at_shape_s: float, plunges: bool
) -> None:
    world = searcher(growth=0, reading_mm=40.0, settling=True, at_shape_s=at_shape_s)
    step(*world)
    assert world[3][SEARCHER, R_SUB] == SUB_FOLLOW
    expected = TICK + 20 * TICKS_PER_S if plunges else 0
    assert world[3][SEARCHER, R_PLUNGE_UNTIL] == expected


@pytest.mark.parametrize(("growth", "plunge_s", "first_after_s"),
                         [(0, 20.0, 0.0), (1, 0.0, 800.0), (0, 0.0, 800.0)])
def test_no_plunge_with_the_options_off(
    growth: int, plunge_s: float, first_after_s: float
) -> None:
    world = searcher(growth=growth, reading_mm=40.0, settling=True, plunge_s=plunge_s,
                     first_after_s=first_after_s)
    step(*world)
    assert world[3][SEARCHER, R_SUB] == SUB_FOLLOW
    assert world[3][SEARCHER, R_PLUNGE_UNTIL] == 0


def test_first_formations_plunge_except_on_targets_with_holes() -> None:
    after = {shape: int(ETRun(RunConfig(shape=shape)).controller.ci[C_FIRST_PLUNGE])
             for shape in ("starfish", "T", "O")}
    assert after == {"starfish": 800 * TICKS_PER_S, "T": 800 * TICKS_PER_S, "O": 0}
    off = ETRun(RunConfig(shape="starfish", et=ETParams(first_plunge_after_s=0.0)))
    assert off.controller.ci[C_FIRST_PLUNGE] == 0


def test_a_plunging_searcher_keeps_nearer_to_the_group() -> None:
    # Read at 36 mm: nearer than a dived searcher's aim (d - 3 = 37 mm), so it turns away
    # (clockwise orbit: away is left) ...
    reading = PLUNGE_AIM_MM + 1.0
    assert step(*searcher(growth=1, reading_mm=reading)) == LEFT
    # ... unless it plunges: then 36 mm is beyond its aim, and it turns towards the group.
    world = searcher(growth=1, reading_mm=reading)
    world[3][SEARCHER, R_PLUNGE_UNTIL] = TICK + 1
    assert step(*world) == RIGHT
    # Nearer than the plunging aim it still turns away ...
    world = searcher(growth=1, reading_mm=PLUNGE_AIM_MM - 1.5)
    world[3][SEARCHER, R_PLUNGE_UNTIL] = TICK + 1
    assert step(*world) == LEFT
    # ... but not when its plunges after damage aim under its body
    # (``regrowth_plunge_aim_mm``, 31 mm by default): touching the robot, it presses on.
    world = searcher(growth=1, reading_mm=PLUNGE_AIM_MM - 1.5,
                     plunge_aim_mm=ETParams().regrowth_plunge_aim_mm)
    world[3][SEARCHER, R_PLUNGE_UNTIL] = TICK + 1
    assert step(*world) == RIGHT


def regrowth(plunge_s: float) -> dict:
    config = RunConfig(shape="starfish", seed=1, damage=("split y=mid",), max_time_s=4 * 3600,
                       et=ETParams(regrowth_plunge_s=plunge_s, **SESSION_54_REGROWTH))
    summary = ETRun(config, sim_params=NATIVE_MATHS).run()
    assert summary["duplicate_tags"] == []
    return summary


def test_the_starfish_half_reaches_the_site_in_its_notch() -> None:
    # Traced (session 47): the 50-robot half's last free site, (3, 0), lies in a notch
    # whose mouth robots stand 71 mm apart; a searcher orbiting 37 mm from every robot
    # stopped 18 mm short of the site on every pass for 1.5 h.
    level = regrowth(0.0)
    assert not all(c["formed"] for c in level["components"])
    summary = regrowth(20.0)
    assert len(summary["components"]) == 2
    for component in summary["components"]:
        assert component["formed"] and component["jaccard"] == 1.0
        assert component["census_count"] == component["robots"]


@pytest.mark.parametrize("seed", [11, 18])
def test_starfish_first_formations_that_form_only_with_the_first_formation_plunge(
    seed: int,
) -> None:
    # Session 48, starfish seeds 0-19: 18 formed either way, but these two only with the
    # plunge (seeds 0 and 4 went the other way); without it they end 4 h with two and six
    # free sites.
    def run(first_after_s: float) -> ETRun:
        r = ETRun(RunConfig(shape="starfish", seed=seed, max_time_s=4 * 3600,
                            et=ETParams(first_plunge_after_s=first_after_s,
                                        **SESSION_57_SEARCH)),
                  sim_params=NATIVE_MATHS)
        r.run()
        return r

    assert not run(0.0).summary()["formed"]
    plunging = run(800.0)
    summary = plunging.summary()
    assert summary["formed"] and summary["jaccard"] == 1.0, summary["states"]
    assert duplicate_tags(plunging.controller.tags, plunging.controller.holds_site) == []
    assert min_pair_distance(plunging.world.pos, plunging.world.present) > 2 * 16.5 - 1.0
