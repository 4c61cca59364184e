"""Saved runs: loading the simulator's recording, `etswarm replay` and `etswarm plot`."""

from __future__ import annotations

import json

import imageio.v3 as iio
import numpy as np
import pytest
from click.testing import CliRunner

from etswarm.algorithm.states import State
from etswarm.cli.viewer_commands import plot as plot_command
from etswarm.cli.viewer_commands import replay as replay_command
from etswarm.errors import EtswarmError
from etswarm.sim.params import SimParams
from etswarm.sim.recorder import Recorder
from etswarm.sim.world import World
from etswarm.viewer.replay import ReplayRun
from etswarm.viewer.runfiles import load_run_dir
from etswarm.viewer.scene import NO_STATE


def write_et_like_run(run_dir, frames: int = 12) -> None:
    """A recording whose header says ET, robots turning Stable one per frame."""
    params = SimParams()
    world = World.from_positions(
        np.array([[0.0, 0.0], [40.0, 0.0], [20.0, 34.64], [200.0, 0.0]]), params=params
    )
    meta = {"controller": "et", "shape": "tri", "ticks_per_s": 31, "params": params.to_dict()}
    with Recorder(run_dir / "recording.npz", world, every=31, meta=meta) as rec:
        for k in range(frames):
            world.led[:] = State.QUEUED
            world.led[: min(k, 3)] = State.STABLE
            world.pos[3, 0] = 200.0 - 5 * k
            world.tick = 31 * k
            rec.capture()
    summary = {
        "events": [{"t_s": 3.0, "kind": "formed"}, {"t_s": 8.0, "kind": "damage", "how": "kill"}]
    }
    (run_dir / "summary.json").write_text(json.dumps(summary))


def test_an_et_recording_loads_with_states_and_events(tmp_path) -> None:
    write_et_like_run(tmp_path)
    record = load_run_dir(tmp_path)
    assert record.frames == 12 and record.n == 4
    assert np.allclose(record.t_s, np.arange(12))
    assert record.state[5].tolist() == [State.STABLE] * 3 + [State.QUEUED]
    assert [e["kind"] for e in record.events] == ["formed", "damage"]
    run = ReplayRun(record)
    run.advance(31 * 9)
    scene = run.scene()
    assert scene.sim_time_s == 9.0 and scene.events[-1].startswith("t=0:00:08 damage")
    assert scene.pos[3, 0] == pytest.approx(155.0)


def test_a_random_walk_recording_has_no_states(tmp_path) -> None:
    from etswarm.viewer.simrun import randomwalk_live_run

    live = randomwalk_live_run(10, seed=0)
    meta = {"controller": "randomwalk", "ticks_per_s": 31}
    with Recorder(tmp_path / "recording.npz", live.world, every=31, meta=meta) as rec:
        for _ in range(3):
            rec.capture()
            live.advance(31)
    record = load_run_dir(tmp_path / "recording.npz")
    assert record.frames == 3 and (record.state == NO_STATE).all()
    assert record.events == []


def test_missing_and_bad_run_dirs_are_one_line_errors(tmp_path) -> None:
    with pytest.raises(EtswarmError, match="no such run directory"):
        load_run_dir(tmp_path / "nope")
    with pytest.raises(EtswarmError, match=r"no recording\.npz"):
        load_run_dir(tmp_path)
    write_et_like_run(tmp_path)
    (tmp_path / "summary.json").write_text('{"events": [{"kind": "formed"}]}')
    with pytest.raises(EtswarmError, match="event 0 needs"):
        load_run_dir(tmp_path)


def test_replay_writes_a_video_of_the_whole_run(tmp_path) -> None:
    write_et_like_run(tmp_path)
    out = tmp_path / "replay.mp4"
    result = CliRunner().invoke(
        replay_command, [str(tmp_path), "--video", str(out), "--fps", "10", "--size", "320x240"]
    )
    assert result.exit_code == 0, result.output
    frames = iio.imread(out, index=None)
    # default speed: one recorded frame (1 s) per video frame -> 12 frames
    assert frames.shape == (12, 240, 320, 3)


def test_replay_window_runs_headless_for_some_frames(tmp_path) -> None:
    write_et_like_run(tmp_path)
    result = CliRunner().invoke(
        replay_command, [str(tmp_path), "--frames", "3", "--fps", "0", "--size", "320x240"]
    )
    assert result.exit_code == 0, result.output


def test_plot_writes_pngs_into_the_run_dir(tmp_path) -> None:
    write_et_like_run(tmp_path)
    result = CliRunner().invoke(plot_command, [str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "states.png").exists() and (tmp_path / "timeline.png").exists()
    assert "neighbour-count errors not plotted" in result.output
    other = tmp_path / "plots"
    result = CliRunner().invoke(plot_command, [str(tmp_path), "--out", str(other)])
    assert result.exit_code == 0 and (other / "states.png").exists()
