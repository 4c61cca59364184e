"""SimParams.threads: the threaded phases (etswarm.sim.parallel, etswarm.sim.sync).

Checks determinism, independence from the thread count, the compiled threaded loop
against the phase-by-phase threaded functions, physics (no overlaps, radio range, loss and
noise statistics) and that threads=1 still gives the results it gave before threads
existed.
"""

from __future__ import annotations

import hashlib

import numpy as np
import pytest

from etswarm.errors import EtswarmError
from etswarm.sim import FORWARD, RandomWalk, SimParams, Simulator, World, random_world
from etswarm.sim.controllers.randomwalk import randomwalk_step
from etswarm.sim.parallel import hash_draws
from etswarm.sim.simulator import ThreadChooser


def digest(world: World) -> str:
    """Hash of everything a run leaves in the world."""
    h = hashlib.sha256()
    for arr in (world.pos, world.heading, world.motor, world.led, world.in_count,
                world.in_type, world.in_data, world.in_dist, world.counters):
        h.update(arr.tobytes())
    return h.hexdigest()


def noisy_params(**kw: float) -> SimParams:
    """Dense arena, loss, distance, speed and heading noise (every random draw used)."""
    base = {"arena_mm": 1000.0, "loss": 0.2, "dist_noise_mm": 2.0, "speed_noise": 0.05,
            "heading_noise_deg": 2.0}
    base.update(kw)
    return SimParams(**base)


def run_randomwalk(params: SimParams, n: int, ticks: int, seed: int,
                   parts: int | None = None) -> tuple[World, Simulator]:
    world = random_world(n, params, seed)
    sim = Simulator(world, RandomWalk(n), params, seed)
    if parts is not None:  # run the threaded algorithm on this many threads
        sim._chooser = ThreadChooser(parts)
    done = 0
    while done < ticks:  # several calls: the host/kernel hand-over is part of the test
        done += sim.run_ticks(min(97, ticks - done))
    return world, sim


class SlowRandomWalk:
    """The random walk through the slow (Python) path: same step, same memory layout."""

    def __init__(self, n: int) -> None:
        self.mem = RandomWalk(n).mem

    def step(self, view) -> None:  # type: ignore[no-untyped-def]
        randomwalk_step(view.tick, view.alive, view.in_count, view.in_type, view.in_data,
                        view.in_dist, view.motor, view.led, view.out_on, view.out_type,
                        view.out_data, self.mem, view.rng)


def test_threads_one_gives_the_results_from_before_threads_existed() -> None:
    # hash recorded with the simulator before SimParams.threads was added (commit 7068f49)
    # (the platform's maths then, as every run until session 53)
    params = SimParams(arena_mm=1000.0, loss=0.2, dist_noise_mm=2.0, speed_noise=0.05,
                       heading_noise_deg=2.0, portable_math=False)
    world = random_world(300, params, 11)
    Simulator(world, RandomWalk(300), params, 11).run_ticks(620)
    got = hashlib.sha256(world.pos.tobytes() + world.heading.tobytes()).hexdigest()
    assert got == "cb470cdcecb419312ebf3231980d4b522c9730df03b83e6b74c711359e927985"
    assert world.counters[1] == 40428 and world.counters[4] == 61077


def test_threads_are_deterministic_and_independent_of_the_thread_count() -> None:
    params = noisy_params(threads=2)
    a, _ = run_randomwalk(params, 250, 400, seed=5, parts=2)
    b, _ = run_randomwalk(params, 250, 400, seed=5)
    c, _ = run_randomwalk(params, 250, 400, seed=5, parts=1)
    assert digest(a) == digest(b) == digest(c)
    d, _ = run_randomwalk(params, 250, 400, seed=6)
    assert digest(d) != digest(a)
    assert a.counters[2] > 0 and a.counters[4] > 0  # losses and pushes happened


def test_compiled_threaded_loop_equals_the_threaded_phase_functions() -> None:
    # the slow path runs the same phases one at a time (on one thread)
    params = noisy_params(threads=2)
    n, ticks = 150, 120
    fast, _ = run_randomwalk(params, n, ticks, seed=3)
    world = random_world(n, params, 3)
    sim = Simulator(world, SlowRandomWalk(n), params, 3)
    assert not sim.fast
    sim.run_ticks(ticks)
    assert digest(world) == digest(fast)


def test_no_overlaps_in_a_long_dense_threaded_random_walk() -> None:
    params = SimParams(arena_mm=50.0 * np.sqrt(600), threads=2)
    n = 600
    world = random_world(n, params, 2)
    sim = Simulator(world, RandomWalk(n), params, 2)
    contact = 2.0 * params.body_radius_mm
    worst = 0.0
    for _ in range(12):
        sim.run_ticks(250)  # 3000 ticks = 97 s in all
        d = np.sqrt(((world.pos[:, None, :] - world.pos[None, :, :]) ** 2).sum(-1))
        d[np.arange(n), np.arange(n)] = np.inf
        worst = max(worst, contact - float(d.min()))
        r = params.body_radius_mm
        assert np.all(world.pos >= r) and np.all(world.pos <= params.arena_mm - r)
    assert worst < 0.5, f"overlap of {worst:.3f} mm"
    assert world.counters[4] > 10_000  # robots did push each other


class Silent:
    """Slow-path controller that does nothing (motors and radio as set by the test)."""

    def step(self, view) -> None:  # type: ignore[no-untyped-def]
        pass


def test_threaded_radio_equals_the_serial_radio_without_loss_and_noise() -> None:
    params1 = SimParams(arena_mm=800.0, tx_period=3)
    worlds = []
    for threads in (1, 2):
        params = params1.with_overrides(threads=threads)
        world = random_world(120, params, 9)
        for i in range(world.n):
            world.set_message(i, 1 + i % 5, bytes([i % 256, 7, 9]))
        sim = Simulator(world, Silent(), params, 9)
        sums = []
        for _ in range(6):
            sim.run_ticks(1)
            sums.append((world.in_count.copy(), world.in_data.copy(), world.in_dist.copy(),
                         world.in_type.copy()))
        worlds.append(sums)
    for one, two in zip(worlds[0], worlds[1], strict=True):
        for x, y in zip(one, two, strict=True):
            assert np.array_equal(x, y)
    assert sum(int(s[0].sum()) for s in worlds[0]) > 100


def test_threaded_motion_equals_the_serial_motion_without_contacts() -> None:
    pos = np.array([[100.0, 100.0], [400.0, 100.0], [100.0, 400.0], [400.0, 400.0]])
    out = []
    for threads in (1, 2):
        params = SimParams(threads=threads)
        world = World.from_positions(pos, np.array([0.0, 1.0, 2.0, 3.0]), params, 1)
        world.motor[:] = [FORWARD, 2, 3, FORWARD]
        Simulator(world, Silent(), params, 1).run_ticks(200)
        out.append((world.pos.copy(), world.heading.copy()))
    assert np.array_equal(out[0][0], out[1][0]) and np.array_equal(out[0][1], out[1][1])


def test_threaded_radio_range_loss_and_noise_statistics() -> None:
    n_rx = 8
    loss, sigma = 0.2, 2.0
    params = SimParams(loss=loss, dist_noise_mm=sigma, tx_period=1, threads=2)
    ang = np.linspace(0, 2 * np.pi, n_rx, endpoint=False)
    # receivers on a 50 mm circle, one more robot at 75 mm between two: out of range
    far = [[75.0 * np.cos(np.pi / 8), 75.0 * np.sin(np.pi / 8)]]
    pos = np.vstack([[0.0, 0.0], np.c_[50 * np.cos(ang), 50 * np.sin(ang)], far])
    world = World.from_positions(pos, np.zeros(n_rx + 2), params, 3)
    world.set_message(0, 1, b"")
    sim = Simulator(world, Silent(), params, seed=3)
    ticks = 2500
    received = 0
    dists = []
    for _ in range(ticks):
        sim.run_ticks(1)
        assert world.in_count[-1] == 0
        got = world.in_count[1:-1] > 0
        received += int(got.sum())
        dists.append(world.in_dist[1:-1, 0][got])
    trials = ticks * n_rx
    assert abs((1 - received / trials) - loss) < 0.015  # 5 sigma of the binomial
    d = np.concatenate(dists)
    assert abs(d.mean() - 50.0) < 0.1
    assert abs(d.std() - sigma) < 0.1
    assert world.counters[2] == trials - received  # every loss counted
    assert world.counters[4] == 0  # nobody touched: the distances are the true 50 mm


def test_hash_draws_are_uniform_and_independent_of_neighbouring_counters() -> None:
    u = hash_draws(np.uint64(12345), 7, 0, 1, 200_000)
    assert u.min() > 0.0 and u.max() <= 1.0
    assert abs(u.mean() - 0.5) < 0.003
    hist = np.histogram(u, bins=20, range=(0, 1))[0]
    assert hist.min() > 9_000 and hist.max() < 11_000
    assert abs(np.corrcoef(u[:-1], u[1:])[0, 1]) < 0.01


def test_threads_parameter_is_checked() -> None:
    with pytest.raises(EtswarmError, match="threads"):
        SimParams(threads=0)
    assert "threads" not in SimParams().to_dict()
    assert SimParams(threads=2).to_dict()["threads"] == 2


def test_cli_threads_option() -> None:
    from click.testing import CliRunner

    from etswarm.cli.sim_command import sim

    ok = CliRunner().invoke(sim, ["-n", "200", "-s", "5", "--threads", "2", "--no-progress"])
    assert ok.exit_code == 0 and "robot-ticks/s" in ok.output
    bad = CliRunner().invoke(sim, ["-n", "200", "--threads", "0", "--no-progress"])
    assert bad.exit_code != 0 and "--threads" in str(bad.exception)


def test_thread_chooser_falls_back_to_one_thread_when_that_is_faster() -> None:
    chooser = ThreadChooser(2)
    for _ in range(200):
        threads = chooser.pick()
        chooser.record(threads, 100, 0.3 if threads == 2 else 0.1)
    assert chooser.current == 1 and chooser.ticks_on[1] > 10 * chooser.ticks_on[2]
    for _ in range(400):  # the machine got quiet: back to two
        threads = chooser.pick()
        chooser.record(threads, 100, 0.05 if threads == 2 else 0.1)
    assert chooser.current == 2
    fixed = ThreadChooser(2, adaptive=False)
    assert all(fixed.pick() == 2 for _ in range(50))


def test_thread_chooser_does_not_time_the_first_call_on_a_count() -> None:
    chooser = ThreadChooser(2)
    chooser.record(2, 16, 10.0)  # the threads starting up
    assert chooser.sec_per_tick[2] is None and chooser.ticks_on[2] == 16
    chooser.record(2, 100, 0.1)
    assert chooser.sec_per_tick[2] == pytest.approx(0.001)
    assert chooser.pick() == 1  # one thread not timed yet: tried next
