"""Recordings: the replay LiveRun and the plots."""

from __future__ import annotations

import imageio.v3 as iio
import numpy as np
import pytest
from PIL import Image

from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError
from etswarm.viewer.plots import neighbour_errors, phases, plot_run
from etswarm.viewer.record import RunRecord
from etswarm.viewer.replay import ReplayRun
from etswarm.viewer.sample import sample_record


@pytest.fixture(scope="module")
def record() -> RunRecord:
    return sample_record(frames=120, dt_s=60.0)


def test_state_counts_add_up_to_present_robots(record) -> None:
    counts = record.state_counts()
    assert counts.shape == (record.frames, 9)
    assert np.array_equal(counts.sum(axis=1), record.present.sum(axis=1))
    assert counts[0, State.QUEUED] + counts[0, State.SEARCH] == record.n  # none placed yet
    assert counts[-1, State.STABLE] == record.present[-1].sum()


def test_replay_moves_a_cursor_and_refuses_damage(record) -> None:
    run = ReplayRun(record)
    assert run.frame == 0 and not run.finished
    run.advance(31 * 59)  # 59 s: still before the second frame at 60 s
    assert run.frame == 0
    run.advance(31)
    assert run.frame == 1
    assert run.scene().sim_time_s == pytest.approx(60.0)
    run.advance(31 * 10**6)
    assert run.finished and run.frame == record.frames - 1
    scene = run.scene()
    assert scene.n == record.n and scene.events[-1].endswith("formed")
    info = run.robot_info(0)
    assert info["state"] == "Stable" and "NN" in info and "tag" in info
    for call in (
        lambda: run.damage_split((0, 0), (1, 1)),
        lambda: run.damage_remove_rect((0, 0), (1, 1)),
        lambda: run.damage_kill([0]),
    ):
        with pytest.raises(EtswarmError, match="disabled"):
            call()


def test_phases_follow_the_events(record) -> None:
    ph = phases(record)
    assert [p[2] for p in ph] == ["forming", "regenerating"]
    formed, damage, reformed = (e["t_s"] for e in record.events)
    assert ph[0] == (0.0, formed, "forming")
    assert ph[1] == (damage, reformed, "regenerating")


def test_neighbour_errors_vanish_once_formed(record) -> None:
    fewer, more, mean_abs = neighbour_errors(record)
    formed = record.events[0]["t_s"]
    growing = (record.t_s > 600) & (record.t_s < formed - 600)
    assert fewer[growing].max() > 0  # sites still missing neighbours while growing
    assert fewer[-1] == 0 and more[-1] == 0 and mean_abs[-1] == 0
    plain = RunRecord(
        t_s=record.t_s,
        pos=record.pos,
        heading=record.heading,
        state=record.state,
        present=record.present,
        alive=record.alive,
    )
    with pytest.raises(ValueError):
        neighbour_errors(plain)


def test_plot_run_writes_readable_pngs(record, tmp_path) -> None:
    paths = plot_run(record, tmp_path)
    assert sorted(p.name for p in paths) == ["neighbour_errors.png", "states.png", "timeline.png"]
    img = iio.imread(tmp_path / "states.png")
    assert img.shape[0] > 300 and img.shape[1] > 800
    # the stacked area holds the Stable colour
    rgb = np.asarray(Image.open(tmp_path / "states.png").convert("RGB")).reshape(-1, 3)
    assert ((rgb == (0, 158, 115)).all(axis=1)).sum() > 1000


def test_replay_keys_step_back_and_restart(record) -> None:
    import pygame

    from etswarm.viewer.window import Viewer

    run = ReplayRun(record)
    run.seek(10)
    viewer = Viewer(run, size=(320, 240), fps=0, start_paused=True)

    def hook(v, k: int) -> None:
        if k == 0:
            pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_COMMA, mod=0))
        elif k == 1:
            assert run.frame == 9
            pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_HOME, mod=0))

    viewer.run(max_frames=3, frame_hook=hook)
    assert run.frame == 0 and viewer.scene.sim_time_s == 0.0
