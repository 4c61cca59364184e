"""The LiveRun adapter over the plain simulator (random walk), headless video, `etswarm view`."""

from __future__ import annotations

import imageio.v3 as iio
import numpy as np
import pytest
from click.testing import CliRunner

from etswarm.cli.viewer_commands import view as view_command
from etswarm.viewer.headless import live_frames, write_live_video
from etswarm.viewer.live import LiveRun
from etswarm.viewer.scene import NO_STATE
from etswarm.viewer.simrun import SimLiveRun, in_rect, randomwalk_live_run, side_of_line


def test_geometry_helpers() -> None:
    pts = np.array([[0.0, 1.0], [0.0, -1.0], [5.0, 0.0]])
    assert np.allclose(side_of_line(pts, (-1, 0), (1, 0)), [1.0, -1.0, 0.0])
    assert in_rect(pts, (1, 1), (6, -1)).tolist() == [False, False, True]
    with pytest.raises(ValueError):
        side_of_line(pts, (1, 1), (1, 1))


def test_randomwalk_run_advances_and_draws() -> None:
    run = randomwalk_live_run(40, seed=3, max_time_s=2.0)
    assert isinstance(run, LiveRun)
    before = run.scene()
    assert before.n == 40 and (before.state == NO_STATE).all()
    run.advance(31)
    after = run.scene()
    assert after.sim_time_s == pytest.approx(1.0)
    assert not np.allclose(before.pos, after.pos)
    run.advance(1000)
    assert run.finished and run.world.tick == 62
    info = run.robot_info(0)
    assert info["ID"] == 0 and isinstance(info["neighbours"], list)


def test_damage_through_world_arrays() -> None:
    run = randomwalk_live_run(60, seed=1)
    w = run.world
    centre = w.pos.mean(axis=0)
    # split along a vertical line through the centre: the smaller side moves out of range
    p0, p1 = (centre[0], centre[1] - 1000), (centre[0], centre[1] + 1000)
    side = side_of_line(w.pos, p0, p1) > 0
    smaller = side if side.sum() <= (~side).sum() else ~side
    run.damage_split(p0, p1)
    a, b = w.pos[smaller], w.pos[~smaller]
    gaps = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2)
    assert gaps.min() > run.params.comm_range_mm
    # remove a rectangle around one robot
    x, y = w.pos[5]
    run.damage_remove_rect((x - 1, y - 1), (x + 1, y + 1))
    assert not w.present[5]
    run.damage_kill([7])
    assert not w.alive[7] and w.present[7]
    scene = run.scene()
    assert not scene.present[5] and not scene.alive[7]
    assert "killed #7" in scene.events[-1]


def test_split_in_a_walled_arena_removes_the_smaller_side() -> None:
    from etswarm.sim.controllers.randomwalk import RandomWalk
    from etswarm.sim.params import SimParams
    from etswarm.sim.placement import random_world
    from etswarm.sim.simulator import Simulator

    params = SimParams(arena_mm=600.0)
    world = random_world(30, params, 0)
    run = SimLiveRun(Simulator(world, RandomWalk(30), params, 0))
    run.damage_split((200.0, 0.0), (200.0, 600.0))
    assert (
        not world.present[world.pos[:, 0] < 200].any()
        or not world.present[world.pos[:, 0] >= 200].any()
    )


def test_headless_video_of_a_live_run(tmp_path) -> None:
    run = randomwalk_live_run(30, seed=0, max_time_s=3.0)
    frames = list(live_frames(run, fps=10, speed=10, size=(320, 240)))
    # initial frame + one frame per simulated second until finished
    assert len(frames) == 4 and frames[0].shape == (240, 320, 3)
    run = randomwalk_live_run(30, seed=0)
    path = tmp_path / "rw.gif"
    assert (
        write_live_video(run, path, fps=10, speed=20, max_frames=5, size=(320, 240), progress=False)
        == 5
    )
    assert iio.imread(path, index=None).shape[:3] == (5, 240, 320)


def test_view_command_writes_a_video_headless(tmp_path) -> None:
    out = tmp_path / "v.mp4"
    result = CliRunner().invoke(
        view_command,
        [
            "--controller",
            "randomwalk",
            "--robots",
            "20",
            "--video",
            str(out),
            "--frames",
            "4",
            "--size",
            "320x240",
        ],
    )
    assert result.exit_code == 0, result.output
    assert iio.imread(out, index=None).shape == (4, 240, 320, 3)


def test_view_command_runs_the_window_for_some_frames(tmp_path) -> None:
    result = CliRunner().invoke(
        view_command,
        [
            "--controller",
            "randomwalk",
            "--robots",
            "20",
            "--frames",
            "3",
            "--size",
            "320x240",
            "--fps",
            "0",
            "--out",
            str(tmp_path),
        ],
    )
    assert result.exit_code == 0, result.output


def test_view_command_shows_the_et_run(tmp_path) -> None:
    out = tmp_path / "t.gif"
    result = CliRunner().invoke(
        view_command,
        ["T", "--video", str(out), "--frames", "3", "--size", "320x240", "--speed", "60"],
    )
    assert result.exit_code == 0, result.output
    frames = iio.imread(out, index=None)
    assert frames.shape[:3] == (3, 240, 320)


def test_view_command_takes_et_options(tmp_path, monkeypatch) -> None:
    from etswarm.algorithm.live import ETLive

    seen = []
    monkeypatch.setattr(ETLive, "__init__", lambda self, run: seen.append(run.config.et) or None)
    monkeypatch.setattr("etswarm.cli.viewer_commands._write_video", lambda *a, **k: None)
    result = CliRunner().invoke(view_command, ["disc", "--et", "wave_s=0", "--et",
                                               "hole_watch_s=30", "--video", "x.gif"])
    assert result.exit_code == 0, result.output
    assert seen[0].wave_s == 0.0 and seen[0].hole_watch_s == 30.0
    bad = CliRunner().invoke(view_command, ["disc", "--et", "wave_s=abc", "--frames", "1"])
    assert bad.exit_code != 0 and "wave_s" in str(bad.exception)


def test_view_command_takes_portable_maths(monkeypatch) -> None:
    from etswarm.algorithm.live import ETLive

    seen = []
    monkeypatch.setattr(ETLive, "__init__", lambda self, run: seen.append(run.sim_params) or None)
    monkeypatch.setattr("etswarm.cli.viewer_commands._write_video", lambda *a, **k: None)
    for args in (["T", "--native-math"], ["T"]):
        result = CliRunner().invoke(view_command, [*args, "--video", "x.gif"])
        assert result.exit_code == 0, result.output
    assert [p.portable_math for p in seen] == [False, True]  # portable by default


def test_view_command_argument_errors() -> None:
    runner = CliRunner()
    result = runner.invoke(view_command, ["--controller", "randomwalk", "T", "--frames", "1"])
    assert "takes no SHAPE" in str(result.exception)
    result = runner.invoke(view_command, ["--frames", "1"])
    assert "missing SHAPE" in str(result.exception)
    result = runner.invoke(view_command, ["T", "--size", "big", "--frames", "1"])
    assert "--size" in str(result.exception)
