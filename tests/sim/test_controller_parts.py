"""Controllers split into part_step (per robot, any thread) and rest_step (one thread).

The random walk's parts over all robots followed by its rest must be its step; the
threaded loop, which runs the parts on every thread right after filing inboxes, must give
what the step run on one thread gives, also in a tick whose radio falls back to one
thread (more copies than the threaded radio's streams hold).
"""

from __future__ import annotations

import hashlib

import numpy as np
import pytest

from etswarm.sim import RandomWalk, SimParams, Simulator, World
from etswarm.sim.controllers.randomwalk import (
    MSG_HELLO,
    randomwalk_part,
    randomwalk_rest,
    randomwalk_step,
)
from etswarm.sim.kernel import load_kernel
from etswarm.sim.parallel import make_scratch, no_part_step
from etswarm.sim.simulator import ThreadChooser


def random_inboxes(n: int, k: int, rng: np.random.Generator) -> tuple[np.ndarray, ...]:
    """Inboxes of hello messages from random senders (some heard twice, some not hello)."""
    in_count = rng.integers(0, k + 1, n).astype(np.int32)
    in_type = np.where(rng.random((n, k)) < 0.9, MSG_HELLO, 7).astype(np.uint8)
    in_data = np.zeros((n, k, 9), dtype=np.uint8)
    sender = rng.integers(0, 300, (n, k))
    in_data[:, :, 0] = sender & 0xFF
    in_data[:, :, 1] = sender >> 8
    in_dist = rng.random((n, k)).astype(np.float32) * 70
    return in_count, in_type, in_data, in_dist


def control_state(n: int) -> tuple[np.ndarray, ...]:
    """motor, led, out_on, out_type, out_data as a world holds them."""
    return (np.zeros(n, np.int8), np.zeros(n, np.uint8), np.zeros(n, np.bool_),
            np.zeros(n, np.uint8), np.zeros((n, 9), np.uint8))


def test_random_walk_parts_then_rest_equal_its_step() -> None:
    n, k, ticks = 200, 6, 150
    rng = np.random.default_rng(4)
    alive = rng.random(n) < 0.9
    a_ctl, b_ctl = RandomWalk(n), RandomWalk(n)
    a_out, b_out = control_state(n), control_state(n)
    a_rng, b_rng = np.random.default_rng(9), np.random.default_rng(9)
    for tick in range(ticks):
        inbox = random_inboxes(n, k, rng)
        randomwalk_step(tick, alive, *inbox, *a_out, a_ctl.mem, a_rng)
        cut = (n * tick) // ticks  # parts of changing sizes, in any order
        randomwalk_part(cut, n, tick, alive, *inbox, *b_out, b_ctl.mem)
        randomwalk_part(0, cut, tick, alive, *inbox, *b_out, b_ctl.mem)
        randomwalk_rest(tick, alive, *inbox, *b_out, b_ctl.mem, b_rng)
    for x, y in zip((*a_out, *a_ctl.mem), (*b_out, *b_ctl.mem), strict=True):
        assert np.array_equal(x, y)
    assert (a_ctl.mem[2] >= 0).sum() > n  # tables were filled


def digest(world: World) -> str:
    h = hashlib.sha256()
    for arr in (world.pos, world.heading, world.motor, world.led, world.in_count,
                world.in_type, world.in_data, world.in_dist, world.counters):
        h.update(arr.tobytes())
    return h.hexdigest()


class SlowRandomWalk:
    """The random walk's step through the slow (Python) path."""

    def __init__(self, n: int) -> None:
        self.mem = RandomWalk(n).mem

    def step(self, view) -> None:  # type: ignore[no-untyped-def]
        randomwalk_step(view.tick, view.alive, view.in_count, view.in_type, view.in_data,
                        view.in_dist, view.motor, view.led, view.out_on, view.out_type,
                        view.out_data, self.mem, view.rng)


#: Robots of the crowd world's pile.
PILE = 60


def crowd_world(params: SimParams) -> World:
    """PILE robots piled within a few mm (every one hears all others), and a ring of
    robots around them."""
    rng = np.random.default_rng(2)
    pile = 400.0 + rng.random((PILE, 2)) * 4.0
    ang = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    ring = 400.0 + 150.0 * np.stack([np.cos(ang), np.sin(ang)], axis=1)
    world = World.from_positions(np.concatenate([pile, ring]), params=params, seed=2)
    for i in range(world.n):  # everyone broadcasts from tick 0, while the pile is whole
        world.set_message(i, MSG_HELLO, bytes([i, 0, 0]))
    return world


@pytest.mark.parametrize("parts", [1, 2])
def test_threaded_parts_equal_the_step_when_the_radio_falls_back(parts: int) -> None:
    params = SimParams(arena_mm=800.0, tx_period=2, threads=2)
    fast_world = crowd_world(params)
    n = fast_world.n
    fast = Simulator(fast_world, RandomWalk(n), params, 3)
    fast._chooser = ThreadChooser(parts, adaptive=False)
    # streams of one copy per robot of a part: n // 2 + 1 copies from one part to
    # another; at tick 0 the pile's senders send more than all four streams hold, so
    # the threaded radio files that tick on one thread
    assert fast._scratch is not None
    fast._scratch = make_scratch(n, 2, int(fast._scratch.key[0]), rx_per_robot=1)
    pile = PILE
    senders = int(np.sum(fast_world.tx_phase[:pile] == 0))
    assert senders * (pile - 1) > 4 * (n // 2 + 1)
    spread = fast_world.pos[:pile].max(axis=0) - fast_world.pos[:pile].min(axis=0)
    assert np.hypot(*spread) < params.comm_range_mm
    slow_world = crowd_world(params)
    slow = Simulator(slow_world, SlowRandomWalk(n), params, 3)
    for _ in range(4):  # the pile spreads out over the first ticks
        fast.run_ticks(5)
        slow.run_ticks(5)
    assert digest(fast_world) == digest(slow_world)
    assert fast_world.counters[1] > 0 and fast_world.counters[4] > 0


def test_part_step_must_be_compiled() -> None:
    with pytest.raises(TypeError, match="part_step and rest_step"):
        load_kernel(randomwalk_step, threaded=True, part_step=lambda *a: None,
                    rest_step=randomwalk_rest)


def test_threaded_kernel_binds_the_parts_or_the_whole_step() -> None:
    # (not called here, so nothing is compiled: only what the generated module holds)
    whole = load_kernel(randomwalk_step, threaded=True).py_func.__globals__
    assert whole["controller_part"] is no_part_step
    assert whole["controller_rest"] is randomwalk_step
    split = load_kernel(randomwalk_step, threaded=True, part_step=randomwalk_part,
                        rest_step=randomwalk_rest).py_func.__globals__
    assert split["controller_part"] is randomwalk_part
    assert split["controller_rest"] is randomwalk_rest
    assert whole["__name__"] != split["__name__"]  # two kernels, two cache files
