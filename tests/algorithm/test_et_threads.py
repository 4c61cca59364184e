"""The ET controller on threads: ``SimParams(threads=2)`` runs its per-robot work (``et_part``)
on both threads. Results must not depend on that: the same final world and robot memory
whether the threaded loop runs on two threads, on one, or without the split (``et_step``
on one thread), also through a damage, the election and the host's answer (the stop flag).
And ``et_step`` must be ``et_part`` over all robots (in any split) followed by ``et_rest``.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.controller import et_part, et_rest, et_step
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.sim.params import SimParams
from etswarm.sim.simulator import Simulator, ThreadChooser

from .thread_checks import assert_forming, final_state


def threaded_run(config: RunConfig, seconds: float, mode: str) -> ETRun:
    """``config`` run for ``seconds`` with threads=2: mode "two" (both threads always),
    "one" (the threaded loop on one thread: et_part on all robots) or "whole" (no
    part_step: et_step on one thread while the other builds contact lists)."""
    params = SimParams(threads=2)
    run = ETRun(config, sim_params=params)
    if mode == "whole":
        run.controller.part_step = None  # type: ignore[misc]
        run.sim = Simulator(run.world, run.controller, run.sim_params, config.seed)
    run.sim._chooser = ThreadChooser(1 if mode == "one" else 2, adaptive=False)
    run.advance(round(seconds * run.ticks_per_s))
    return run


FORMING = RunConfig(shape="T", seed=3, max_time_s=3600.0, layout="cluster")


def test_threaded_formation_is_independent_of_the_thread_count() -> None:
    runs = {mode: threaded_run(FORMING, 480.0, mode) for mode in ("two", "one")}
    assert final_state(runs["two"]) == final_state(runs["one"])
    two = runs["two"]
    assert two.sim._chooser.ticks_on[2] == two.world.tick  # really on two threads
    assert_forming(two)


def test_threaded_regeneration_is_independent_of_the_thread_count() -> None:
    # a triangle formed, split in two: elections, Leaders' requests answered by the host
    config = RunConfig(shape="triangle", seed=1, max_time_s=3 * 3600.0, damage=("split x=0",))
    runs = {mode: threaded_run(config, 2700.0, mode) for mode in ("two", "one")}
    assert final_state(runs["two"]) == final_state(runs["one"])
    kinds = [e["kind"] for e in runs["two"].events]
    assert "damage" in kinds and "census" in kinds, kinds


@pytest.mark.slow  # compiles a threaded kernel of its own (a minute or more)
def test_threaded_parts_equal_the_unsplit_step() -> None:
    two = threaded_run(FORMING, 480.0, "two")
    whole = threaded_run(FORMING, 480.0, "whole")
    assert final_state(two) == final_state(whole)


@pytest.mark.slow  # called from Python, et_part compiles on its own (a minute and a half, once:
# numba then keeps it on disk)
@pytest.mark.parametrize("cut", [0, 17, 45])
def test_parts_then_rest_equal_the_step(cut: int) -> None:
    # each tick: the run's own tick (radio, et_step, move, collide), and on a copy of the
    # robots' memory from before it, et_part in two pieces then et_rest on the same inboxes
    run = ETRun(RunConfig(shape="T", seed=0, max_time_s=3600.0, layout="cluster"))
    run.advance(31 * 60)
    w = run.world
    rng = np.random.default_rng(cut)
    for _ in range(300):
        copy = tuple(np.copy(a) for a in run.controller.mem)
        outs = (w.motor.copy(), w.led.copy(), w.out_on.copy(), w.out_type.copy(),
                w.out_data.copy())
        tick = w.tick
        run.sim.run_ticks(1)  # leaves this tick's inboxes in the world
        inbox = (w.alive, w.in_count, w.in_type, w.in_data, w.in_dist)
        et_part(cut, w.n, tick, *inbox, *outs, copy)
        et_part(0, cut, tick, *inbox, *outs, copy)
        et_rest(tick, *inbox, *outs, copy, rng)
        for mine, theirs in zip(copy, run.controller.mem, strict=True):
            assert np.array_equal(mine, theirs)
        assert np.array_equal(outs[1], w.led) and np.array_equal(outs[4], w.out_data)
    assert et_step is run.controller.step
