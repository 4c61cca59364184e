"""``regrowth_plunge_aim_mm``: after damage, a plunging searcher edge-follows the placed
robots 31 mm away, under its 33 mm body, so it presses on them and parts a notch's mouth
that a searcher pressing past had narrowed under a body's width.

Traced on `L` `kill random=0.1` seed 109 (session 70): robots 8 and 13 stood 63 mm apart
across the free site (0, -3). Searcher 28 plunged into the mouth 20 times at 35 mm, which
parted them by 4.5 mm in 2.8 h, and it took the site 5.1 h after the damage.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import R_ORBIT, R_PLUNGE_UNTIL
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.search import search_rule
from etswarm.errors import EtswarmError
from etswarm.sim.world import FORWARD, LEFT, RIGHT

from .test_mouth_plunge import GENE_X0, SEARCHER, TICK, TICKS_PER_S, mouth_world

#: The searcher stands against the robot on (1, -1), 33.5 mm centre to centre, and reads
#: the one across the free site at 40 mm.
TOUCHING = (33.5, 40.0)


def plunge(world: tuple) -> tuple[int, int]:
    """Robot 5's plunge deadline and motor command after one evaluation with fresh
    messages in the mouth (it orbits clockwise: it turns right, towards the group)."""
    gene, ci, cf, ri, nb, nb_dist, held = world
    assert ri[SEARCHER, R_ORBIT] == 0
    motor = np.full(30, FORWARD, dtype=np.int64)
    search_rule(SEARCHER, TICK, True, ri, nb, nb_dist, motor, gene, gene, ci, cf, held,
                GENE_X0, GENE_X0)
    return int(ri[SEARCHER, R_PLUNGE_UNTIL]), int(motor[SEARCHER])


def test_a_plunge_after_damage_presses_on_the_robot_it_touches() -> None:
    assert plunge(mouth_world(readings=TOUCHING)) == (TICK + 20 * TICKS_PER_S, RIGHT)


def test_a_plunge_at_35_mm_turns_away_from_the_robot_it_touches() -> None:
    world = mouth_world(readings=TOUCHING, et=ETParams(regrowth_plunge_aim_mm=35.0))
    assert plunge(world) == (TICK + 20 * TICKS_PER_S, LEFT)


def test_a_first_formation_plunge_keeps_35_mm() -> None:
    # ``way_plunge``: a ring's first formation plunges in a mouth too, at 35 mm
    world = mouth_world(readings=TOUCHING, growth=0, at_shape_s=3000.0)
    assert plunge(world) == (TICK + 20 * TICKS_PER_S, LEFT)


def test_a_late_first_formation_plunge_in_a_mouth_presses() -> None:
    # ``late_plunge_aim_mm``: from ``late_plunge_s`` at the shape it presses, on any target
    late = ETParams().late_plunge_s
    for way_plunge in ("on", "off"):
        world = mouth_world(readings=TOUCHING, growth=0, at_shape_s=late + 1.0,
                            et=ETParams(way_plunge=way_plunge))
        assert plunge(world) == (TICK + 20 * TICKS_PER_S, RIGHT)
    world = mouth_world(readings=TOUCHING, growth=0, at_shape_s=late + 1.0,
                        et=ETParams(late_plunge_aim_mm=35.0))
    assert plunge(world) == (TICK + 20 * TICKS_PER_S, LEFT)


@pytest.mark.parametrize("aim", [0.0, -1.0])
def test_an_aim_that_is_no_distance_is_refused(aim: float) -> None:
    with pytest.raises(EtswarmError, match="regrowth_plunge_aim_mm must be > 0"):
        ETParams(regrowth_plunge_aim_mm=aim)


def l_kill_109(aim_mm: float) -> dict:
    config = RunConfig(shape="L", seed=109, damage=("kill random=0.1",),
                       max_time_s=3320 + 4 * 3600, et=ETParams(regrowth_plunge_aim_mm=aim_mm))
    summary = ETRun(config).run()
    assert summary["duplicate_tags"] == []
    assert summary["max_leaders_per_component"] <= 1
    return summary


def test_l_kill_seed_109_reforms_through_the_narrowed_mouth() -> None:
    """The first formation completes at 3320 s either way; at 31 mm the 27 live robots
    re-form within 4 h of the kill, and at 35 mm they are still one site short."""
    pressed = l_kill_109(31.0)
    assert pressed["formation_time_s"] == 3320.0
    [remnant] = pressed["components"]
    assert (remnant["robots"], remnant["target_cells"], remnant["formed"]) == (27, 27, True)
    assert remnant["jaccard"] == 1.0
    assert remnant["time_to_stable_s"] < 4 * 3600

    [stalled] = l_kill_109(35.0)["components"]
    assert (stalled["robots"], stalled["formed"], stalled["free_sites"]) == (27, False, 1)
