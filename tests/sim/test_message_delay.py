"""A message read one tick after its broadcast (``SimParams.message_delay_ticks`` = 1).

With the delay the radio fills the inbox of the next tick, so a controller must see at
tick t + 1 exactly what it sees at tick t without the delay (same loss and noise draws);
the compiled loop, the Python path and the split loop (radio beside the controller on
threads) must agree byte for byte, whatever the kernel calls' lengths.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.cli.main import main
from etswarm.errors import EtswarmError
from etswarm.sim import RandomWalk, SimParams, Simulator, World
from etswarm.sim.simulator import ThreadChooser

from .test_controller_parts import SlowRandomWalk, digest


class InboxLog:
    """Python controller that keeps still, broadcasts its ID and the tick, and logs what
    it reads each tick: (tick, robot, sender byte, tick byte, distance mm)."""

    def __init__(self) -> None:
        self.log: list[tuple[int, int, int, int, float]] = []

    def step(self, view) -> None:  # type: ignore[no-untyped-def]
        n = view.alive.shape[0]
        for i in range(n):
            for k in range(view.in_count[i]):
                self.log.append((view.tick, i, int(view.in_data[i, k, 0]),
                                 int(view.in_data[i, k, 1]), float(view.in_dist[i, k])))
            view.out_on[i] = True
            view.out_type[i] = 3
            view.out_data[i, 0] = i
            view.out_data[i, 1] = view.tick % 256


def logged(delay: int, ticks: int = 60) -> list[tuple[int, int, int, int, float]]:
    params = SimParams(loss=0.3, dist_noise_mm=2.0, tx_period=4,
                       message_delay_ticks=delay)
    pos = [[0.0, 0.0], [40.0, 0.0], [20.0, 35.0], [60.0, 35.0]]
    world = World.from_positions(pos, np.zeros(4), params, 5)
    world.tx_phase[:] = [0, 1, 1, 3]
    ctl = InboxLog()
    sim = Simulator(world, ctl, params, seed=5)
    sim.run_ticks(ticks)
    return ctl.log


def test_a_delayed_message_is_read_one_tick_later_with_the_same_draws() -> None:
    now = logged(0)
    later = logged(1)
    assert len(now) > 50  # messages were heard, and some lost (loss 0.3)
    assert [(t + 1, *rest) for t, *rest in now if t + 1 < 60] == later
    # what a robot reads carries the message sent after the tick before the broadcast
    assert all((t - 1) % 256 == sent for t, _, _, sent, _ in now if t > 0)


def walk_world(params: SimParams) -> World:
    rng = np.random.default_rng(8)
    pos = rng.random((300, 2)) * 700.0
    return World.from_positions(pos, rng.random(300) * 2 * np.pi, params, 8)


def walk_params(delay: int, control_threads: int = 1) -> SimParams:
    return SimParams(loss=0.2, dist_noise_mm=2.0, speed_noise=0.05, heading_noise_deg=2.0,
                     message_delay_ticks=delay, control_threads=control_threads)


def test_compiled_python_and_split_loops_agree_with_the_delay() -> None:
    runs = {}
    for name, ctl_type, threads in (("compiled", RandomWalk, None),
                                    ("python", SlowRandomWalk, None),
                                    ("split on 2", RandomWalk, 2),
                                    ("split on 1", RandomWalk, 1)):
        params = walk_params(1, 2 if threads else 1)
        world = walk_world(params)
        sim = Simulator(world, ctl_type(world.n), params, seed=8)
        if threads:
            sim._chooser = ThreadChooser(threads, adaptive=False)
        for ticks in (1, 2, 7, 30):  # odd and even calls: the inboxes swap after odd ones
            sim.run_ticks(ticks)
        runs[name] = digest(world)
    assert len(set(runs.values())) == 1, runs
    params = walk_params(0)
    world = walk_world(params)
    Simulator(world, RandomWalk(world.n), params, seed=8).run_ticks(40)
    assert digest(world) != runs["compiled"]  # the delay does change the run


def test_one_call_or_many_give_the_same_delayed_run() -> None:
    results = []
    for chunks in ((61,), (3, 17, 1, 40), (1,) * 61):
        params = walk_params(1)
        world = walk_world(params)
        sim = Simulator(world, RandomWalk(world.n), params, seed=8)
        for ticks in chunks:
            sim.run_ticks(ticks)
        results.append(digest(world))
    assert results[0] == results[1] == results[2]


def test_the_delay_is_checked_and_saved_only_when_set() -> None:
    with pytest.raises(EtswarmError, match="message_delay_ticks"):
        SimParams(message_delay_ticks=2)
    with pytest.raises(EtswarmError, match="needs threads 1"):
        SimParams(message_delay_ticks=1, threads=2)
    assert "message_delay_ticks" not in SimParams().to_dict()
    assert SimParams(message_delay_ticks=1).to_dict()["message_delay_ticks"] == 1


@pytest.mark.parametrize(("args", "message"), [
    (["--message-delay", "2"], "--message-delay must be 0 or 1, got 2"),
    (["--message-delay", "1", "--threads", "2"],
     "--message-delay 1 needs --threads 1 (use --control-threads)"),
])
def test_cli_message_delay_errors_are_one_line(
    args: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as stop:
        main(["run", "triangle", *args])
    assert stop.value.code == 2
    assert capsys.readouterr().err == f"etswarm: error: {message}\n"

