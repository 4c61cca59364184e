"""The live viewer loop, headless: injected events and pixels."""

from __future__ import annotations

import imageio.v3 as iio
import numpy as np
import pygame
import pytest

from etswarm.algorithm.states import State
from etswarm.viewer import palette
from etswarm.viewer.live import LiveRun
from etswarm.viewer.scene import Scene
from etswarm.viewer.view import ViewState
from etswarm.viewer.window import PANEL_WIDTH, Viewer, run_viewer


class FakeRun:
    """Three robots standing on a row at y = 0, x = -60, 0, 60 mm."""

    ticks_per_second = 31

    def __init__(self, finish_after_ticks: int | None = None) -> None:
        self.tick = 0
        self.finish_after_ticks = finish_after_ticks
        self.pos = np.array([(-60.0, 0.0), (0.0, 0.0), (60.0, 0.0)])
        self.present = np.ones(3, bool)
        self.alive = np.ones(3, bool)
        self.calls: list[tuple] = []

    @property
    def finished(self) -> bool:
        return self.finish_after_ticks is not None and self.tick >= self.finish_after_ticks

    def advance(self, ticks: int) -> None:
        if self.finish_after_ticks is not None:
            ticks = min(ticks, self.finish_after_ticks - self.tick)
        self.tick += ticks
        self.calls.append(("advance", ticks))

    def scene(self) -> Scene:
        return Scene.from_positions(
            self.pos.copy(),
            present=self.present.copy(),
            alive=self.alive.copy(),
            state=np.array([State.STABLE, State.ACTIVE, State.DANGER], np.uint8),
            sim_time_s=self.tick / self.ticks_per_second,
            title="fake",
        )

    def robot_info(self, i: int) -> dict[str, object]:
        return {
            "state": "Stable",
            "tag": (i, 0),
            "NN": 2,
            "TS": i + 1,
            "neighbours": [
                {"id": j, "dist mm": 60.0, "state": "Stable"} for j in range(3) if j != i
            ],
        }

    def damage_split(self, p0, p1) -> None:
        self.calls.append(("split", p0, p1))

    def damage_remove_rect(self, p0, p1) -> None:
        self.calls.append(("remove", p0, p1))

    def damage_kill(self, ids) -> None:
        self.calls.append(("kill", list(ids)))
        self.alive[list(ids)] = False


W, H = 480, 360


def make_viewer(run: FakeRun, tmp_path, **kw) -> Viewer:
    view = ViewState(width=W, height=H, centre_mm=(0, 0), zoom=2.0, show_labels=False)
    kw.setdefault("fps", 0)
    return Viewer(run, size=(W, H), speed=31.0, output_dir=tmp_path, view=view, **kw)


def key(k: int) -> pygame.event.Event:
    return pygame.event.Event(pygame.KEYDOWN, key=k, mod=0, unicode="", scancode=0)


def mouse(kind: int, pos: tuple[int, int], button: int) -> pygame.event.Event:
    return pygame.event.Event(kind, pos=pos, button=button)


def drag(p0: tuple[int, int], p1: tuple[int, int]) -> None:
    pygame.event.post(mouse(pygame.MOUSEBUTTONDOWN, p0, 1))
    pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=p1, rel=(0, 0), buttons=(1, 0, 0)))
    pygame.event.post(mouse(pygame.MOUSEBUTTONUP, p1, 1))


def screen_rgb(viewer: Viewer) -> np.ndarray:
    assert viewer.last_frame is not None
    return viewer.last_frame


def test_fake_run_satisfies_the_protocol() -> None:
    assert isinstance(FakeRun(), LiveRun)


def test_frames_advance_the_run_and_show_robots_in_state_colours(tmp_path) -> None:
    run = FakeRun()
    viewer = make_viewer(run, tmp_path, fps=30)
    result = viewer.run(max_frames=3)
    assert result.frames == 3
    # speed x31 at 30 frames/s and 31 ticks/s: 32.03 ticks a frame
    assert run.tick == 96
    rgb = screen_rgb(viewer)
    # robot 1 (Active) at the world origin = canvas centre
    assert tuple(rgb[H // 2, W // 2]) == palette.state_colour(3)
    # robot 0 (Stable) at x = -60 mm, zoom 2 -> 120 px left of centre
    assert tuple(rgb[H // 2, W // 2 - 120]) == palette.state_colour(5)


def test_pause_step_speed_and_toggles(tmp_path) -> None:
    run = FakeRun()
    viewer = make_viewer(run, tmp_path)
    seen: dict[int, tuple] = {}

    def hook(v: Viewer, k: int) -> None:
        if k == 0:
            pygame.event.post(key(pygame.K_SPACE))
        elif k == 1:
            seen[1] = (v.paused, run.tick)
        elif k == 2:
            seen[2] = run.tick
            pygame.event.post(key(pygame.K_PERIOD))
        elif k == 3:
            seen[3] = run.tick
            for k2 in (pygame.K_PLUS, pygame.K_l, pygame.K_t, pygame.K_n, pygame.K_g):
                pygame.event.post(key(k2))
        elif k == 4:
            seen[4] = (v.speed, v.view.show_links, v.view.show_trails, v.view.show_labels)

    viewer.run(max_frames=6, frame_hook=hook)
    paused, tick_at_pause = seen[1]
    assert paused
    assert seen[2] == tick_at_pause  # nothing advanced while paused
    assert seen[3] == tick_at_pause + 31  # '.' steps one simulated second
    assert seen[4] == (62.0, False, False, True)  # labels start off here


def test_wheel_zooms_and_arrow_keys_pan(tmp_path) -> None:
    viewer = make_viewer(FakeRun(), tmp_path)
    zoom0 = viewer.view.zoom

    def hook(v: Viewer, k: int) -> None:
        if k == 0:
            pygame.event.post(pygame.event.Event(pygame.MOUSEWHEEL, x=0, y=1, flipped=False))
        elif k == 1:
            assert v.view.zoom == pytest.approx(zoom0 * 1.2)
            pygame.event.post(key(pygame.K_RIGHT))

    viewer.run(max_frames=3, frame_hook=hook)
    assert viewer.view.zoom == pytest.approx(zoom0 * 1.2)
    assert viewer.view.centre_mm[0] > 0


def test_mouse_damage_calls_the_run_with_world_coordinates(tmp_path) -> None:
    run = FakeRun()
    viewer = make_viewer(run, tmp_path, start_paused=True)

    def hook(v: Viewer, k: int) -> None:
        if k == 0:
            drag((240, 100), (240, 300))  # vertical line through the centre
        elif k == 1:
            pygame.event.post(key(pygame.K_LSHIFT))
            drag((300, 150), (400, 250))
            pygame.event.post(pygame.event.Event(pygame.KEYUP, key=pygame.K_LSHIFT, mod=0))
        elif k == 2:
            # right-click on robot 2 (x = 60 mm -> 120 px right of centre)
            pygame.event.post(mouse(pygame.MOUSEBUTTONDOWN, (W // 2 + 120, H // 2), 3))

    viewer.run(max_frames=4, frame_hook=hook)
    damage = [c for c in run.calls if c[0] != "advance"]
    # zoom 2 px/mm, centre (0, 0): px (240, 100) -> (0, 40) mm; (240, 300) -> (0, -60) mm
    assert damage[0] == ("split", (0.0, 40.0), (0.0, -60.0))
    assert damage[1] == ("remove", (30.0, 15.0), (80.0, -35.0))
    assert damage[2] == ("kill", [2])
    rgb = screen_rgb(viewer)
    assert tuple(rgb[H // 2 - 12, W // 2 + 120]) == palette.DEAD


def test_click_selects_a_robot_and_opens_the_side_panel(tmp_path) -> None:
    viewer = make_viewer(FakeRun(), tmp_path, start_paused=True)

    def hook(v: Viewer, k: int) -> None:
        if k == 0:
            pygame.event.post(mouse(pygame.MOUSEBUTTONDOWN, (W // 2 + 2, H // 2 + 1), 1))
            pygame.event.post(mouse(pygame.MOUSEBUTTONUP, (W // 2 + 2, H // 2 + 1), 1))

    viewer.run(max_frames=2, frame_hook=hook)
    assert viewer.view.selected == 1
    rgb = screen_rgb(viewer)
    panel = rgb[:, W - PANEL_WIDTH + 5 :]
    near_panel = (np.abs(panel.astype(int) - palette.PANEL) <= 3).all(axis=2)
    assert near_panel.mean() > 0.6
    assert (panel.sum(axis=2) < 150).any()  # text in it


def test_snapshot_recording_and_quit(tmp_path) -> None:
    run = FakeRun()

    def hook(v: Viewer, k: int) -> None:
        if k == 0:
            pygame.event.post(key(pygame.K_s))
            pygame.event.post(key(pygame.K_r))
        elif k == 5:
            pygame.event.post(key(pygame.K_r))
        elif k == 6:
            pygame.event.post(key(pygame.K_q))

    result = run_viewer(
        run, size=(W, H), fps=0, output_dir=tmp_path, max_frames=50, frame_hook=hook
    )
    assert result.quit_by_user and result.frames == 7
    assert len(result.snapshots) == 1 and result.snapshots[0].exists()
    snap = iio.imread(result.snapshots[0])
    assert snap.shape == (H, W, 3)
    assert len(result.videos) == 1
    frames = iio.imread(result.videos[0], index=None)
    assert frames.shape == (5, H, W, 3)


def test_recording_is_finalized_when_the_frame_limit_ends_the_loop(tmp_path) -> None:
    def hook(v: Viewer, k: int) -> None:
        if k == 0:
            pygame.event.post(key(pygame.K_r))

    result = run_viewer(
        FakeRun(), size=(W, H), fps=0, output_dir=tmp_path, max_frames=4, frame_hook=hook
    )
    assert len(result.videos) == 1
    assert iio.imread(result.videos[0], index=None).shape[0] == 3


def test_a_finished_run_is_not_advanced(tmp_path) -> None:
    run = FakeRun(finish_after_ticks=5)
    viewer = make_viewer(run, tmp_path)
    viewer.speed = 1000.0
    viewer.run(max_frames=5)
    assert run.tick == 5 and run.finished
