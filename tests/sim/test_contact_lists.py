"""Contact lists (etswarm.sim.neighbours): a pure speed-up of the collision phase.

The lists hold every robot a cell query would find while no robot drifts further than
the drift from where it stood at the start of the epoch, so results must not depend on
the drift at all: a drift so small that epochs end on every tick (lists rebuilt at
nearly every examination), the default, and one so large that lists overflow and the
cell query takes over must all give byte-identical runs, with one thread and with two.
"""

from __future__ import annotations

import hashlib

import numpy as np
import pytest

import etswarm.sim.simulator as simulator_module
from etswarm.sim import RandomWalk, SimParams, Simulator, random_world
from etswarm.sim.neighbours import (
    L_COUNT,
    L_FIRST,
    LIST_CAP,
    S_EPOCH,
    build_contact_list,
    grid_rebuild,
    make_grid,
)


def run_digest(threads: int, drift: float, monkeypatch: pytest.MonkeyPatch) -> tuple[str, int]:
    monkeypatch.setattr(simulator_module, "DRIFT_MM", drift)
    params = SimParams(arena_mm=900.0, loss=0.1, dist_noise_mm=1.0, speed_noise=0.05,
                       heading_noise_deg=2.0, threads=threads)
    world = random_world(300, params, 7)
    sim = Simulator(world, RandomWalk(300), params, 7)
    sim.run_ticks(300)
    h = hashlib.sha256()
    for arr in (world.pos, world.heading, world.led, world.counters):
        h.update(arr.tobytes())
    return h.hexdigest(), int(sim.grid.state[S_EPOCH])


@pytest.mark.parametrize("threads", [1, 2])
def test_results_do_not_depend_on_the_drift(threads: int,
                                            monkeypatch: pytest.MonkeyPatch) -> None:
    default_drift = simulator_module.DRIFT_MM
    tiny, epochs_tiny = run_digest(threads, 0.01, monkeypatch)
    default, epochs_default = run_digest(threads, default_drift, monkeypatch)
    huge, _ = run_digest(threads, 40.0, monkeypatch)  # every list overflows
    assert tiny == default == huge
    # the default drift keeps epochs several ticks long; a tiny one ends them every tick
    assert epochs_tiny >= 300 and epochs_default < epochs_tiny / 2


def test_contact_list_holds_every_robot_within_its_radius_in_slot_order() -> None:
    rng = np.random.default_rng(3)
    n = 400
    pos = rng.uniform(0.0, 600.0, (n, 2))
    grid = make_grid(n, 80.0, 2.5, 1.0)
    grid_rebuild(grid, pos, np.ones(n, dtype=np.bool_))
    list_r = 35.0 + 4.0 * 1.0
    buf = np.zeros(n, dtype=np.uint32)
    for a in range(0, n, 7):
        xy = grid.sxb[:, :2]
        count = build_contact_list(grid, a, xy[a, 0], xy[a, 1], 35.0, 0, grid.dims[1] - 1,
                                   buf)
        d = np.hypot(xy[:n, 0] - xy[a, 0], xy[:n, 1] - xy[a, 1])
        want = [s for s in range(n) if s != a and d[s] < list_r]
        if len(want) > LIST_CAP:
            assert count == -1
        else:
            assert list(grid.near_slots[a, L_FIRST:L_FIRST + count]) == want
            assert grid.near_slots[a, L_COUNT] == count
