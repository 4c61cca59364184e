"""Radio range, loss and distance noise; motion speed and turn rate; payload limit."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.errors import EtswarmError
from etswarm.sim import FORWARD, LEFT, RIGHT, SimParams, Simulator, World


class Silent:
    """Slow-path controller that does nothing (motors and radio as set by the test)."""

    def step(self, view) -> None:
        pass


def ring_world(params: SimParams, seed: int = 0) -> World:
    """Robot 0 at the origin, robots at distances 40..100 mm on a spiral around it."""
    dists = np.array([40.0, 50.0, 60.0, 69.0, 69.9, 70.1, 75.0, 90.0, 100.0])
    ang = np.linspace(0, 2 * np.pi, len(dists), endpoint=False)
    pos = np.vstack([[0.0, 0.0], np.c_[dists * np.cos(ang), dists * np.sin(ang)]])
    return World.from_positions(pos, np.zeros(len(pos)), params, seed)


def test_radio_reaches_exactly_the_robots_within_range() -> None:
    params = SimParams()
    world = ring_world(params)
    world.set_message(0, 7, b"hello")
    world.tx_phase[:] = 0
    sim = Simulator(world, Silent(), params, seed=1)
    sim.run_ticks(1)
    heard = world.in_count[1:] > 0
    assert heard.tolist() == [True, True, True, True, True, False, False, False, False]
    assert world.in_count[0] == 0  # a robot does not hear itself
    assert bytes(world.in_data[1, 0, :5]) == b"hello" and world.in_type[1, 0] == 7
    assert world.in_dist[1, 0] == pytest.approx(40.0)


def test_broadcast_period_and_dead_robots() -> None:
    params = SimParams(tx_period=15)
    world = ring_world(params)
    world.set_message(0, 1, b"x")
    world.tx_phase[0] = 4
    sim = Simulator(world, Silent(), params, seed=1)
    heard_at = []
    for _ in range(40):
        tick = world.tick
        sim.run_ticks(1)
        if world.in_count[1]:
            heard_at.append(tick)
    assert heard_at == [4, 19, 34]
    world.kill(2)
    sim.run_ticks(15)
    assert world.counters[1] > 0
    assert world.in_count[2] == 0


def test_loss_rate_and_distance_noise_match_the_parameters() -> None:
    n_rx = 8
    loss, sigma = 0.2, 2.0
    params = SimParams(loss=loss, dist_noise_mm=sigma, tx_period=1)
    # one sender in the middle, receivers on a 50 mm circle (39 mm apart: no contact)
    ang = np.linspace(0, 2 * np.pi, n_rx, endpoint=False)
    pos = np.vstack([[0.0, 0.0], np.c_[50 * np.cos(ang), 50 * np.sin(ang)]])
    world = World.from_positions(pos, np.zeros(n_rx + 1), params, 3)
    world.set_message(0, 1, b"")
    sim = Simulator(world, Silent(), params, seed=3)
    ticks = 2500
    dists = []
    received = 0
    for _ in range(ticks):
        sim.run_ticks(1)
        got = world.in_count[1:] > 0
        received += int(got.sum())
        dists.append(world.in_dist[1:, 0][got])
    trials = ticks * n_rx
    rate = 1 - received / trials
    # binomial std: sqrt(0.2*0.8/20000) = 0.0028; allow about 5 sigma
    assert abs(rate - loss) < 0.015
    d = np.concatenate(dists)
    assert abs(d.mean() - 50.0) < 0.1  # std of the mean: 2/sqrt(16000) = 0.016
    assert abs(d.std() - sigma) < 0.1
    assert world.counters[2] == trials - received


def test_forward_speed_and_pivot_turn_rate() -> None:
    params = SimParams(speed_mm_s=7.0, turn_rate_deg_s=13.0)
    world = World.from_positions([[0.0, 0.0], [500.0, 0.0], [0.0, 500.0]],
                                 [0.3, 0.0, 0.0], params)
    world.motor[:] = [FORWARD, LEFT, RIGHT]
    sim = Simulator(world, Silent(), params)
    sim.run_ticks(31 * 10)  # 10 s
    moved = np.hypot(*world.pos[0])
    assert moved == pytest.approx(70.0, rel=1e-9)
    assert world.heading[0] == pytest.approx(0.3)
    assert world.heading[1] == pytest.approx(np.deg2rad(130.0))
    assert world.heading[2] == pytest.approx(-np.deg2rad(130.0))
    # pivoting about a leg on the rim keeps the centre at radius r from that leg
    leg = np.deg2rad(params.leg_angle_deg)
    r = params.body_radius_mm
    pivot_start = np.array([500.0, 0.0]) + r * np.array([np.cos(leg), np.sin(leg)])
    h = world.heading[1]
    pivot_now = world.pos[1] + r * np.array([np.cos(h + leg), np.sin(h + leg)])
    assert np.allclose(pivot_now, pivot_start, atol=1e-9)


def test_per_robot_calibration_spread() -> None:
    params = SimParams(speed_spread=0.1, turn_rate_spread=0.2)
    world = World.from_positions(np.c_[np.arange(500) * 40.0, np.zeros(500)], None, params, 1)
    assert world.speed.std() / world.speed.mean() == pytest.approx(0.1, rel=0.15)
    assert world.turn_rate.mean() == pytest.approx(np.deg2rad(13.0), rel=0.05)


def test_payload_limit_is_enforced() -> None:
    world = World(3)
    world.set_message(1, 2, bytes(range(9)))
    assert world.out_on[1] and world.out_data[1].tolist() == list(range(9))
    with pytest.raises(EtswarmError, match="10 bytes; at most 9"):
        world.set_message(1, 2, bytes(10))
    with pytest.raises(EtswarmError, match="type"):
        world.set_message(1, 300, b"")
