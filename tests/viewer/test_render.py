"""Renderer pixels for known scenes."""

import numpy as np
import pytest

from etswarm.algorithm.states import State
from etswarm.viewer import palette
from etswarm.viewer.render import format_sim_time, render, status_text
from etswarm.viewer.sample import sample_scene
from etswarm.viewer.scene import NO_STATE, Scene
from etswarm.viewer.view import Trails, ViewState

W, H = 400, 300


def bare_view(**kw) -> ViewState:
    """Zoom 1 px/mm, world origin at the canvas centre, no overlays."""
    opts = dict(show_legend=False, show_status=False, show_trails=False, show_labels=False)
    opts.update(kw)
    return ViewState(width=W, height=H, centre_mm=(0, 0), zoom=1.0, **opts)


def px(x_mm: float, y_mm: float) -> tuple[int, int]:
    """(row, col) of world point (x, y) under bare_view."""
    return round(H / 2 - y_mm), round(W / 2 + x_mm)


def test_each_state_has_its_colour_at_the_robot_centre() -> None:
    codes = [*list(State), NO_STATE]
    pos = np.array([(-160 + 40 * k, 0.0) for k in range(len(codes))])
    scene = Scene.from_positions(
        pos, state=np.array(codes, np.uint8), heading=np.full(len(codes), 1.0)
    )
    rgb = render(scene, bare_view(show_links=False))
    assert rgb.shape == (H, W, 3) and rgb.dtype == np.uint8
    for (x, y), code in zip(pos, codes, strict=True):
        r, c = px(x, y)
        assert tuple(rgb[r, c]) == palette.state_colour(code), f"state code {code}"
    # the eight state colours are all different
    assert len({palette.state_colour(s) for s in State}) == 8


def test_dead_robots_are_grey_and_absent_robots_are_not_drawn() -> None:
    pos = np.array([(-50.0, 0.0), (50.0, 0.0)])
    scene = Scene.from_positions(
        pos,
        state=np.array([State.STABLE, State.STABLE], np.uint8),
        alive=np.array([False, True]),
        present=np.array([True, False]),
    )
    rgb = render(scene, bare_view(show_links=False))
    # dead robot: grey fill away from its cross
    r, c = px(-50, 0)
    assert tuple(rgb[r - 12, c]) == palette.DEAD
    # absent robot: background
    r, c = px(50, 0)
    assert tuple(rgb[r, c]) == palette.BACKGROUND
    assert (rgb[r - 20 : r + 20, c - 20 : c + 20] == palette.BACKGROUND).all()


def test_links_only_between_talking_robots_within_range() -> None:
    # a pair 60 mm apart (in range) above, a pair 80 mm apart (out of range) below,
    # a pair 60 mm apart with one dead robot in the middle row
    pos = np.array([(-30.0, 80.0), (30.0, 80.0), (-40.0, -80.0), (40.0, -80.0), (-30, 0), (30, 0)])
    alive = np.array([True, True, True, True, True, False])
    scene = Scene.from_positions(pos, state=np.full(6, State.STABLE, np.uint8), alive=alive)
    assert scene.comm_range_mm == 70.0
    on = render(scene, bare_view(show_links=True))
    off = render(scene, bare_view(show_links=False))
    assert tuple(on[px(0, 80)]) == palette.LINK
    assert tuple(off[px(0, 80)]) == palette.BACKGROUND
    assert tuple(on[px(0, -80)]) == palette.BACKGROUND
    assert tuple(on[px(0, 0)]) == palette.BACKGROUND


def test_target_sites_are_drawn_faintly_under_robots() -> None:
    scene = Scene.from_positions(
        np.array([(0.0, 0.0)]), target_sites=np.array([(0.0, 0.0), (80.0, 0.0)])
    )
    rgb = render(scene, bare_view())
    assert tuple(rgb[px(80, 0)]) == palette.TARGET_SITE
    assert tuple(rgb[px(0, 0)]) == palette.NEUTRAL
    rgb = render(scene, bare_view(show_targets=False))
    assert tuple(rgb[px(80, 0)]) == palette.BACKGROUND


def test_trails_follow_a_moving_robot_and_break_at_a_teleport() -> None:
    view = bare_view(show_trails=True, show_links=False)
    scene = Scene.from_positions(
        np.array([(-150.0, 50.0)]), state=np.array([State.SEARCH], np.uint8)
    )
    for k in range(30):
        scene.pos = np.array([(-150.0 + 4 * k, 50.0)])
        scene.sim_time_s = float(k)
        rgb = render(scene, view)
    trail = tuple(rgb[px(-120, 50)])
    assert trail == palette.blend(palette.state_colour(State.SEARCH), palette.BACKGROUND, 0.55)
    # jump far away: no line is drawn across the gap
    scene.pos = np.array([(-40.0, -100.0)])
    scene.sim_time_s = 30.0
    rgb = render(scene, view)
    mid = px((-34 - 40) / 2, (50 - 100) / 2)
    assert tuple(rgb[mid]) == palette.BACKGROUND
    # the trail can be turned off
    view.show_trails = False
    rgb = render(scene, view)
    assert tuple(rgb[px(-120, 50)]) == palette.BACKGROUND


def test_trails_sample_once_per_time_and_reset_when_time_goes_back() -> None:
    trails = Trails(length=5)
    scene = Scene.from_positions(np.zeros((3, 2)))
    for t in (0.0, 1.0, 1.0, 2.0):
        scene.sim_time_s = t
        trails.push(scene)
    assert len(trails) == 3
    for t in range(3, 12):
        scene.sim_time_s = float(t)
        trails.push(scene)
    pos, present = trails.history()
    assert pos.shape == (5, 3, 2) and present.all()
    scene.sim_time_s = 0.5
    trails.push(scene)
    assert len(trails) == 1


def test_view_transforms_round_trip_and_zoom_keeps_the_anchor() -> None:
    view = ViewState(width=W, height=H, centre_mm=(10, -5), zoom=2.5)
    pts = np.array([[0.0, 0.0], [33.0, -17.5]])
    assert np.allclose(view.screen_to_world(view.world_to_screen(pts)), pts)
    assert np.allclose(view.world_to_screen(np.array([10.0, -5.0])), [W / 2, H / 2])
    # y up in the world is up on screen
    assert view.world_to_screen(np.array([10.0, 0.0]))[1] < H / 2
    anchor = view.screen_to_world((50, 60))
    view.zoom_at(1.7, (50, 60))
    assert view.zoom == pytest.approx(4.25)
    assert np.allclose(view.screen_to_world((50, 60)), anchor)


def test_fit_shows_every_robot_and_labels_appear_when_zoomed_in() -> None:
    scene = sample_scene()
    view = ViewState.fitted(scene, 800, 600, show_labels=True)
    on = view.world_to_screen(scene.pos)
    assert (on[:, 0] > 0).all() and (on[:, 0] < 800).all()
    assert (on[:, 1] > 0).all() and (on[:, 1] < 600).all()
    # zoomed in so a body is > 20 px: labels change the pixels near a robot's centre
    view.zoom = 2.0
    view.centre_mm = scene.pos[0]
    with_labels = render(scene, view)
    view.show_labels = False
    without = render(scene, view)
    r, c = 300, 400
    assert (
        with_labels[r - 10 : r + 10, c - 15 : c + 15] != without[r - 10 : r + 10, c - 15 : c + 15]
    ).any()


def test_status_line_and_legend_are_drawn() -> None:
    scene = sample_scene()
    assert format_sim_time(3 * 3600 + 25 * 60 + 7.9) == "3:25:07"
    assert status_text(scene).startswith("t 3:25:07")
    assert "28 robots (1 dead)" in status_text(scene)
    view = ViewState.fitted(scene, 800, 600)
    rgb = render(scene, view)
    # status bar: panel colour across the bottom, with dark text pixels in it
    bar = rgb[-48:, :, :]
    near_panel = (np.abs(bar.astype(int) - palette.PANEL) <= 3).all(axis=2)
    assert near_panel.mean() > 0.5
    assert (bar.sum(axis=2) < 150).any()
    # legend: a swatch of every state colour in the top-left box
    box = rgb[8:260, 8:200].reshape(-1, 3)
    colours = {tuple(c) for c in box}
    for s in State:
        assert palette.state_colour(s) in colours
