"""The ET controller's parts on threads in the serial loop (``SimParams.control_threads``).

Only the controller's per-robot work (``et_part``) runs on several threads; radio, motion
and collisions stay on one with the serial loop's random draws. So a run must end in the
same world and robot memory, byte for byte, as the plain serial loop, on two threads or
one, through a formation and through a damage with its election and the host's answers
(the stop flag ends kernel calls early). With a message delay of one tick the radio too
runs beside the controller's pieces, and the same holds.
"""

from __future__ import annotations

import json
import os

import pytest
from click.testing import CliRunner

from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.cli.main import cli, main
from etswarm.errors import EtswarmError
from etswarm.sim.params import SimParams, default_control_threads
from etswarm.sim.simulator import ThreadChooser

from .thread_checks import assert_forming, final_state


def advanced(config: RunConfig, seconds: float, threads: int | None, delay: int = 0) -> ETRun:
    """``config`` run for ``seconds``: the serial loop (``threads`` None) or the split loop
    held on ``threads`` threads, with ``delay`` ticks of message delay."""
    if threads is None:
        run = ETRun(config, sim_params=SimParams(message_delay_ticks=delay))
    else:
        run = ETRun(config, sim_params=SimParams(control_threads=2, message_delay_ticks=delay))
        run.sim._chooser = ThreadChooser(threads, adaptive=False)
    run.advance(round(seconds * run.ticks_per_s))
    return run


FORMING = RunConfig(shape="T", seed=3, max_time_s=3600.0, layout="cluster")


@pytest.mark.parametrize("delay", [0, 1])
def test_split_formation_equals_the_serial_loop(delay: int) -> None:
    # with a delay the radio runs on one thread beside the controller's pieces
    serial = advanced(FORMING, 480.0, None, delay)
    two = advanced(FORMING, 480.0, 2, delay)
    one = advanced(FORMING, 480.0, 1, delay)
    assert final_state(two) == final_state(serial) == final_state(one)
    assert two.sim._chooser.ticks_on[2] == two.world.tick  # really on two threads
    assert_forming(two)


@pytest.mark.parametrize("delay", [0, 1])
def test_split_regeneration_equals_the_serial_loop(delay: int) -> None:
    # a triangle formed, split in two: elections, Leaders' requests answered by the host
    config = RunConfig(shape="triangle", seed=1, max_time_s=3 * 3600.0, damage=("split x=0",))
    serial = advanced(config, 2700.0, None, delay)
    two = advanced(config, 2700.0, 2, delay)
    assert final_state(two) == final_state(serial)
    assert two.events == serial.events
    kinds = [e["kind"] for e in two.events]
    assert "damage" in kinds and "census" in kinds, kinds


def test_split_summary_is_the_serial_summary() -> None:
    config = RunConfig(shape="triangle", seed=2, max_time_s=1800.0, layout="cluster")
    summaries = []
    for params in (SimParams(), SimParams(control_threads=2)):
        summary = ETRun(config, sim_params=params).run()
        summary.pop("wall_time_s")
        summaries.append(json.dumps(summary, sort_keys=True))
    assert summaries[0] == summaries[1]
    assert "control_threads" not in SimParams(control_threads=2).to_dict()


def test_control_threads_is_checked(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(EtswarmError, match="control_threads"):
        SimParams(control_threads=0)
    with pytest.raises(SystemExit) as stop:
        main(["run", "triangle", "--control-threads", "0"])
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert err == "etswarm: error: --control-threads must be in [1, 256], got 0\n"
    with pytest.raises(SystemExit):
        main(["run", "triangle", "--control-threads", "2", "--threads", "2"])
    assert "--control-threads needs --threads 1" in capsys.readouterr().err


@pytest.mark.parametrize("delay", [[], ["--message-delay", "1"]])
def test_cli_control_threads_gives_the_serial_json(delay: list[str]) -> None:
    # (a triangle traced before session 35's thin-shape settings and session 53's portable
    # maths: it forms after 900 s)
    args = ["run", "triangle", "--seed", "4", "--max-time", "900", "--json",
            "--et", "thin_depth=0", "--native-math", *delay]
    outputs = []
    for extra in (["--control-threads", "1"], ["--control-threads", "2"], []):
        result = CliRunner().invoke(cli, args + extra)
        assert result.exit_code == 0, result.output
        summary = json.loads(result.output)
        summary.pop("wall_time_s")
        outputs.append(summary)
    assert outputs[0] == outputs[1] == outputs[2]
    assert outputs[0]["sim_time_s"] == 900.0
    assert outputs[0]["message_delay_ticks"] == (1 if delay else 0)


def test_a_single_run_uses_two_cores_where_there_are_two(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    assert default_control_threads(1) == 2
    assert default_control_threads(2) == 1  # --threads 2 runs the control on both already
    monkeypatch.setattr(os, "cpu_count", lambda: 1)
    assert default_control_threads(1) == 1
    monkeypatch.setattr(os, "cpu_count", lambda: None)
    assert default_control_threads(1) == 1
