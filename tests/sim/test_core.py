"""Core invariants of the world simulator: determinism, no overlaps, early stop."""

from __future__ import annotations

import numpy as np
from numba import njit
from scipy.spatial import cKDTree

from etswarm.sim import RandomWalk, SimParams, Simulator, random_world


def run_randomwalk(seed: int, n: int = 200, ticks: int = 600, **params: float) -> Simulator:
    p = SimParams(arena_mm=50.0 * np.sqrt(n), **params)
    world = random_world(n, p, seed)
    sim = Simulator(world, RandomWalk(n), p, seed)
    assert sim.run_ticks(ticks) == ticks
    return sim


def test_same_seed_gives_byte_identical_state_and_other_seed_differs() -> None:
    a = run_randomwalk(3, loss=0.2, dist_noise_mm=2.0, heading_noise_deg=0.5)
    b = run_randomwalk(3, loss=0.2, dist_noise_mm=2.0, heading_noise_deg=0.5)
    c = run_randomwalk(4, loss=0.2, dist_noise_mm=2.0, heading_noise_deg=0.5)
    for name, arr in a.world.state_arrays().items():
        assert arr.tobytes() == b.world.state_arrays()[name].tobytes(), name
    assert a.world.pos.tobytes() != c.world.pos.tobytes()
    assert a.world.tick == b.world.tick == 600


def test_chunking_does_not_change_the_result() -> None:
    p = SimParams(arena_mm=700.0, loss=0.1)
    whole = Simulator(random_world(150, p, 9), RandomWalk(150), p, 9)
    whole.run_ticks(300)
    parts = Simulator(random_world(150, p, 9), RandomWalk(150), p, 9)
    for n in (1, 7, 92, 200):
        parts.run_ticks(n)
    assert whole.world.pos.tobytes() == parts.world.pos.tobytes()
    assert whole.world.led.tobytes() == parts.world.led.tobytes()


def test_no_two_robots_overlap_during_a_long_dense_run() -> None:
    n = 300
    p = SimParams(arena_mm=45.0 * np.sqrt(n))  # denser than the benchmark
    sim = Simulator(random_world(n, p, 5), RandomWalk(n), p, 5)
    limit = 2 * p.body_radius_mm - 0.5  # documented bound on overlaps
    for _ in range(40):
        sim.run_ticks(50)
        pairs = cKDTree(sim.world.pos).query_pairs(limit)
        assert not pairs, f"overlap at tick {sim.world.tick}"
        r = p.body_radius_mm
        assert np.all(sim.world.pos >= r - 1e-9) and np.all(sim.world.pos <= p.arena_mm - r + 1e-9)
    assert sim.world.counters[4] > 0  # robots did collide


@njit(cache=True)
def stop_at_tick_10(tick, alive, in_count, in_type, in_data, in_dist, motor, led, out_on,
                    out_type, out_data, mem, rng):
    for i in range(alive.shape[0]):
        motor[i] = 1
    if tick == 10:
        mem[0][0] = 1


class StopAt10:
    def __init__(self) -> None:
        self.step = stop_at_tick_10
        self.mem = (np.zeros(1, dtype=np.int64),)


def test_controller_stop_flag_ends_the_chunk_after_that_tick() -> None:
    p = SimParams()
    world = random_world(5, p, 1, side_mm=500.0)
    sim = Simulator(world, StopAt10(), p, 1)
    assert sim.run_ticks(100) == 11
    assert world.tick == 11
    assert sim.stop_requested
    sim.controller.mem[0][0] = 0
    assert sim.run_ticks(5) == 5
    assert world.tick == 16


def test_removed_robots_leave_the_world_and_dead_ones_are_obstacles() -> None:
    n = 300
    p = SimParams(arena_mm=45.0 * np.sqrt(n), max_push_passes=1)  # carried work lists
    sim = Simulator(random_world(n, p, 8), RandomWalk(n), p, 8)
    sim.run_ticks(200)
    gone = np.arange(0, n, 3)
    dead = np.arange(1, n, 3)
    sim.world.remove(gone)
    sim.world.kill(dead)
    frozen = sim.world.pos[gone].copy()
    sim.run_ticks(600)
    w = sim.world
    assert np.array_equal(w.pos[gone], frozen)  # absent robots are never pushed
    assert not w.motor[dead].any() and not w.out_on[dead].any()
    assert (w.in_count[dead] == 0).all()
    stay = w.present
    limit = 2 * p.body_radius_mm - 0.5
    assert not cKDTree(w.pos[stay]).query_pairs(limit)
