"""``mouth_plunge``: after damage, a searcher long at the shape that passes between the two
robots across a free site of its target (the mouth of a notch) plunges, as it does after a
failed confirmation (``regrowth_plunge_s``).

Traced on `H` `split y=mid` seed 47 (session 56): the crossbar's remnant ended one site
short, (0, -1), at the bottom of a notch whose mouth was 70 mm wide. Its searcher passed
through the mouth every 440 s for 10 000 s, 17-27 mm short of the one point where every
reading fits the site. There it read the two robots across the site at about d, but they
are no pair that locates a site, and the two beyond the site were too far for a window,
so it never stopped to confirm and never plunged.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_GROWTH,
    R_PLUNGE_UNTIL,
    R_SHAPE_SINCE,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.search import MOUTH_READ_MM, begin_search, in_mouth, search_rule
from etswarm.algorithm.states import State
from etswarm.sim.world import FORWARD

from .traced import SESSION_56_SEARCH

TICKS_PER_S = 31
TICK = 200_000
SEARCHER = 5
GENE_X0 = -3
#: Tags of the two robots across the free site (0, -1) from each other, and of the two
#: beyond it, at the bottom of the notch.
ACROSS = ((1, -1), (-1, -1))
BEYOND = ((0, -2), (-1, -2))
FREE = (0, -1)


def mouth_world(*, readings=(38.0, 40.0), tags=ACROSS, free_held: bool = False,
                growth: int = 1, at_shape_s: float = 3 * 1200.0,
                et: ETParams | None = None) -> tuple:
    """Searcher 5 of target epoch ``growth`` (0: the first formation), ``at_shape_s`` at
    the shape, hearing Stable robots on ``tags`` at ``readings`` (mm) and the two beyond
    the free site at 58 mm; the gene holds those sites and (0, -1). With ``free_held`` a
    robot it hears holds (0, -1) too. Returns what ``search_rule`` needs."""
    gene = np.zeros((7, 7), dtype=np.int64)
    for x, y in (*ACROSS, *BEYOND, FREE, *tags):
        gene[x - GENE_X0, y - GENE_X0] = 1
    ci, cf = (et or ETParams()).pack(TICKS_PER_S, gene_x0=GENE_X0, gene_y0=GENE_X0)
    ri, nb, nb_dist = allocate(30)
    begin_search(SEARCHER, TICK - round(at_shape_s * TICKS_PER_S), ri)
    ri[SEARCHER, R_SHAPE_SINCE] = TICK - round(at_shape_s * TICKS_PER_S)
    ri[SEARCHER, R_GROWTH] = growth
    robots = [*zip(tags, readings, strict=True), *((t, 58.0) for t in BEYOND)]
    if free_held:
        robots.append((FREE, 60.0))
    for row, ((x, y), reading) in enumerate(robots):
        nb[SEARCHER, row, NB_ID] = 20 + row
        nb[SEARCHER, row, NB_STATE] = State.STABLE
        nb[SEARCHER, row, NB_LAST] = TICK
        nb[SEARCHER, row, NB_TX] = x
        nb[SEARCHER, row, NB_TY] = y
        nb_dist[SEARCHER, row] = reading
    held = np.zeros((30, 9, 9), dtype=np.uint8)
    return gene, ci, cf, ri, nb, nb_dist, held


def mouth(world: tuple) -> bool:
    gene, ci, _, _, nb, nb_dist, held = world
    reach = 40.0 + MOUTH_READ_MM
    return bool(in_mouth(SEARCHER, TICK - 10, nb, nb_dist, gene, ci, held[SEARCHER],
                         GENE_X0, GENE_X0, reach))


def plunge_until(world: tuple) -> int:
    """Robot 5's plunge deadline after one evaluation with fresh messages."""
    gene, ci, cf, ri, nb, nb_dist, held = world
    motor = np.full(30, FORWARD, dtype=np.int64)
    search_rule(SEARCHER, TICK, True, ri, nb, nb_dist, motor, gene, gene, ci, cf, held,
                GENE_X0, GENE_X0)
    return int(ri[SEARCHER, R_PLUNGE_UNTIL])


def test_two_robots_across_a_free_site_make_a_mouth() -> None:
    assert mouth(mouth_world())


@pytest.mark.parametrize(
    "world",
    [
        pytest.param({"free_held": True}, id="the site between them is held"),
        pytest.param({"readings": (38.0, 49.0)}, id="one of them beyond d + 8 mm"),
        pytest.param({"tags": ((1, -1), (0, -2))}, id="adjacent sites, not across"),
        pytest.param({"tags": ((1, -1), (-2, -1))}, id="three steps apart"),
    ],
)
def test_no_mouth(world: dict) -> None:
    assert not mouth(mouth_world(**world))


def test_a_searcher_long_at_a_regrowing_shape_plunges_in_a_mouth() -> None:
    assert plunge_until(mouth_world()) == TICK + 20 * TICKS_PER_S


def test_a_first_formation_searcher_plunges_in_a_mouth_with_way_plunge() -> None:
    # ``way_plunge`` (the controller keeps it on for a target with holes alone)
    assert plunge_until(mouth_world(growth=0)) == TICK + 20 * TICKS_PER_S


def test_a_first_formation_searcher_long_at_the_shape_plunges_in_a_mouth() -> None:
    # ``late_plunge_s``: on any target, once it has been that long at the shape
    late = ETParams(way_plunge="off").late_plunge_s
    assert late > 0
    world = mouth_world(growth=0, at_shape_s=late + 1.0, et=ETParams(way_plunge="off"))
    assert plunge_until(world) == TICK + 20 * TICKS_PER_S


@pytest.mark.parametrize(
    "world",
    [
        pytest.param({"growth": 0, "et": ETParams(way_plunge="off", late_plunge_s=0.0)},
                     id="first formation"),
        pytest.param({"growth": 0, "at_shape_s": 1000.0, "et": ETParams(way_plunge="off")},
                     id="first formation, not late"),
        pytest.param({"at_shape_s": 600.0}, id="not long at the shape"),
        pytest.param({"free_held": True}, id="no mouth"),
        pytest.param({"et": ETParams(mouth_plunge="off")}, id="option off"),
        pytest.param({"et": ETParams(regrowth_plunge_s=0.0)}, id="plunges off"),
    ],
)
def test_no_plunge(world: dict) -> None:
    assert plunge_until(mouth_world(**world)) == 0


def crossbar(mouth_plunge: str) -> dict:
    config = RunConfig(shape="H", seed=47, damage=("split y=mid",), max_time_s=4 * 3600,
                       et=ETParams(mouth_plunge=mouth_plunge, **SESSION_56_SEARCH))
    summary = ETRun(config).run()
    assert summary["duplicate_tags"] == []
    return summary


def test_h_seed_47_reforms_through_the_notch_mouth() -> None:
    def unformed(summary: dict) -> list[tuple[int, int]]:
        return [(c["robots"], c["target_cells"]) for c in summary["components"]
                if c["robots"] >= 6 and not c["formed"]]

    assert unformed(crossbar("on")) == []
    assert unformed(crossbar("off")) == [(26, 26)]


def starfish_59(late_plunge_s: float) -> dict:
    config = RunConfig(shape="starfish", seed=59, max_time_s=8500,
                       et=ETParams(late_plunge_s=late_plunge_s))
    summary = ETRun(config).run()
    assert summary["duplicate_tags"] == []
    return summary


def test_starfish_seed_59_forms_once_its_last_searcher_plunges_into_the_mouth() -> None:
    """Session 72's trace: the last searcher passed 20 mm from the free site's best point
    every 800 s and never stopped to confirm it. With the late plunge it takes the site;
    without, the run ends one site short."""
    late = starfish_59(ETParams().late_plunge_s)
    assert late["formed"] and late["jaccard"] == 1.0
    assert late["formation_time_s"] > ETParams().late_plunge_s
    [stalled] = starfish_59(0.0)["components"]
    assert (stalled["robots"], stalled["formed"], stalled["free_sites"]) == (91, False, 1)
