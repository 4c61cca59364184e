"""A searcher's odometry, and the spiral a lost searcher drives round where it lost the group.

Traced on triangle seed 31 and starfish seed 40: lost searchers drove a fixed spiral of
commands whose centre every turn away from another robot moved, and ended 1.6-4 m from
the shape after 4 h, while the shape waited for them.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from etswarm.algorithm.homing import (
    AHEAD_SHARE,
    ODO_PER_MM,
    ODO_PER_RAD,
    RING_MAX_MM,
    homing_motion,
    integrate,
    note_home,
    note_lost,
    reset_odometry,
    ring_radius,
    spiral_path,
)
from etswarm.algorithm.live import ETLive
from etswarm.algorithm.memory import (
    R_LOST_PATH,
    R_ODO_H,
    R_ODO_PATH,
    R_ODO_X,
    R_ODO_Y,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.sim import FORWARD, LEFT, RIGHT, SimParams, Simulator, World

from .traced import NATIVE_MATHS, SESSION_19_WIDENING, SESSION_57_SEARCH


class Silent:
    """Slow-path controller that does nothing (motors as set by the test)."""

    def step(self, view) -> None:
        pass


def lone_robot(params: SimParams, heading: float = 0.7) -> tuple[World, Simulator]:
    """One robot at (500, 500) mm with the given heading, nothing else in the world."""
    world = World.from_positions(np.array([[500.0, 500.0]]), np.array([heading]), params, 0)
    return world, Simulator(world, Silent(), params, seed=0)


def odometry_cf(params: SimParams) -> np.ndarray:
    """The packed float constants of a controller for robots of ``params``."""
    _, cf = ETParams().pack(
        params.ticks_per_s, 0, 0,
        nominal_motion=(params.speed_mm_s, params.turn_rate_deg_s, params.leg_angle_deg,
                        params.body_radius_mm),
    )
    return cf


def odometric_pose(ri: np.ndarray) -> tuple[float, float, float]:
    """Robot 0's odometric (x mm, y mm, heading rad)."""
    return (ri[0, R_ODO_X] / ODO_PER_MM, ri[0, R_ODO_Y] / ODO_PER_MM, ri[0, R_ODO_H] / ODO_PER_RAD)


def in_start_frame(world: World, start: np.ndarray, heading0: float) -> np.ndarray:
    """Robot 0's true position in the frame of its start pose (mm, (2,))."""
    c, s = math.cos(-heading0), math.sin(-heading0)
    dx, dy = world.pos[0] - start
    return np.array([c * dx - s * dy, s * dx + c * dy])


def drive(commands: np.ndarray, params: SimParams) -> tuple[np.ndarray, np.ndarray]:
    """Drive a lone robot through ``commands`` (one per tick); return its true and its
    odometric position, both in the frame of its start pose (mm, (2,) each)."""
    world, sim = lone_robot(params)
    start, heading0 = world.pos[0].copy(), float(world.heading[0])
    ri, _, _ = allocate(1)
    reset_odometry(0, ri)
    cf = odometry_cf(params)
    for command in commands:
        world.motor[0] = command
        sim.run_ticks(1)
        integrate(0, ri, command, cf)
    x, y, _ = odometric_pose(ri)
    return in_start_frame(world, start, heading0), np.array([x, y])


def test_odometry_follows_the_robot_it_rides_on() -> None:
    rng = np.random.default_rng(5)
    # runs of 5-60 ticks of one command, about 80 s in all
    runs = rng.integers(5, 60, size=80)
    commands = np.repeat(rng.choice([FORWARD, LEFT, RIGHT], size=80), runs).astype(np.uint8)
    true_xy, odo_xy = drive(commands, SimParams())
    assert np.hypot(*true_xy) > 50.0  # it went somewhere
    assert np.hypot(*(true_xy - odo_xy)) < 0.5


def test_odometry_drifts_with_the_calibration_error_it_cannot_know() -> None:
    commands = np.full(31 * 30, FORWARD, dtype=np.uint8)  # 30 s straight on
    true_xy, odo_xy = drive(commands, SimParams(speed_spread=0.2))
    travelled = np.hypot(*true_xy)
    assert odo_xy[0] == pytest.approx(7.0 * 30, rel=1e-3)  # it believes the nominal speed
    assert abs(travelled - odo_xy[0]) > 1.0  # its own speed is off by its calibration


def circle_home(
    start_xy: tuple[float, float],
    path_mm: float,
    home_xy: tuple[float, float] = (0.0, 0.0),
    ahead: bool = False,
) -> np.ndarray:
    """A lone robot lost at ``home_xy`` of its odometry (origin (0, 0): where it left the
    repository), standing at ``start_xy`` (odometric and true, mm, in its start frame),
    drives ``homing_motion`` (``ahead`` as given) until it has gone ``path_mm`` by its
    odometry; return its true track (T, 2) in that frame and, in column 2, the path
    (mm) it had gone since it got lost at each point."""
    params = SimParams()
    world, sim = lone_robot(params, heading=0.0)
    world.pos[0] += start_xy
    origin = world.pos[0] - start_xy
    ri, _, _ = allocate(1)
    reset_odometry(0, ri)
    ri[0, R_ODO_X] = round(home_xy[0] * ODO_PER_MM)
    ri[0, R_ODO_Y] = round(home_xy[1] * ODO_PER_MM)
    note_home(0, ri)
    note_lost(0, ri)
    ri[0, R_ODO_X] = round(start_xy[0] * ODO_PER_MM)
    ri[0, R_ODO_Y] = round(start_xy[1] * ODO_PER_MM)
    cf = odometry_cf(params)
    track = []
    while (ri[0, R_ODO_PATH] - ri[0, R_LOST_PATH]) / ODO_PER_MM < path_mm:
        command = homing_motion(0, ri, ahead, 0, 0, False)
        world.motor[0] = command
        sim.run_ticks(1)
        integrate(0, ri, command, cf)
        gone = (ri[0, R_ODO_PATH] - ri[0, R_LOST_PATH]) / ODO_PER_MM
        track.append((*(world.pos[0] - origin), gone))
    return np.array(track)


def test_a_lost_robot_heads_home_from_afar() -> None:
    track = circle_home((400.0, -250.0), path_mm=600.0)[:, :2]
    distance = np.hypot(*track.T)
    # straight back, then round home near the ring's radius
    assert distance[-1] < ring_radius(600.0) + 40.0
    assert distance.min() < 150.0


def test_the_spiral_sweeps_every_point_round_home_within_radio_range() -> None:
    path = 12_000.0  # mm: a few laps
    track = circle_home((0.0, 0.0), path_mm=path)[:, :2]
    reach = ring_radius(path) - 40.0
    assert reach > 250.0
    # every point of a grid within ``reach`` of home came within radio range (70 mm)
    g = np.arange(-reach, reach + 1, 20.0)
    gx, gy = np.meshgrid(g, g)
    points = np.c_[gx.ravel(), gy.ravel()]
    points = points[np.hypot(*points.T) <= reach]
    seen = np.zeros(len(points), dtype=bool)
    for chunk in np.array_split(track[::4], 20):
        d = np.hypot(points[:, None, 0] - chunk[None, :, 0], points[:, None, 1] - chunk[None, :, 1])
        seen |= (d < 70.0).any(axis=1)
    assert seen.all(), f"{(~seen).sum()} of {len(points)} points never in range"
    # and the centre stayed home: over its last quarter the track keeps to its ring
    last = np.hypot(*track[3 * len(track) // 4:].T)
    assert last.min() > ring_radius(0.7 * path) - 40.0
    assert last.max() < ring_radius(path) + 40.0


def ring_errors(track: np.ndarray, home_xy: tuple[float, float], shifted: bool) -> np.ndarray:
    """How far (mm) each point of ``track`` (T, 3: x, y, path since lost) is from the ring
    it should keep: ``ring_radius(path)`` round home, moved on along home's direction
    from the origin by AHEAD_SHARE of the path when ``shifted``."""
    home = np.asarray(home_xy)
    way = home / np.hypot(*home)
    shift = AHEAD_SHARE * track[:, 2] if shifted else np.zeros(len(track))
    centres = home[None, :] + shift[:, None] * way[None, :]
    rho = np.hypot(*(track[:, :2] - centres).T)
    return rho - np.array([ring_radius(p) for p in track[:, 2]])


@pytest.mark.parametrize("ahead", [False, True])
def test_a_searcher_lost_along_the_repository_moves_its_spiral_on(ahead: bool) -> None:
    """Home 400 mm from where it left the repository, along +x: with ``ahead`` the
    spiral's centre moves on along +x by AHEAD_SHARE of the path (800 mm here), else it
    stays home; either way the robot keeps to its ring round that centre."""
    home = (400.0, 0.0)
    track = circle_home(home, path_mm=8000.0, home_xy=home, ahead=ahead)
    late = track[len(track) // 2:]
    assert np.abs(ring_errors(late, home, shifted=ahead)).max() < 40.0
    # ... and not round the other centre
    assert np.abs(ring_errors(late, home, shifted=not ahead)).max() > 200.0


def test_no_spiral_moves_on_from_a_home_next_to_the_repository() -> None:
    """Lost within AHEAD_MIN_MM of where it left: no known way on, so it circles home."""
    home = (50.0, 0.0)
    track = circle_home(home, path_mm=6000.0, home_xy=home, ahead=True)
    late = track[len(track) // 2:]
    assert np.abs(ring_errors(late, home, shifted=False)).max() < 40.0


@pytest.mark.parametrize("homing", ["on", "ahead"])
def test_square_seed_228_waits_for_a_searcher_lost_along_the_repository(homing: str) -> None:
    """Traced on square seed 228 (fresh seeds of session 29): searcher 15 was shoved out of
    earshot while yielding along the repository, before it heard the shape. By the time
    it had circled the place where it last heard a Queued robot, they had all left, and
    that place is 1.2 m from the shape. With "ahead" its spiral moves on along the way
    it was going and it finds the shape. With "on" it circled there for good while its
    spiral started again at 1 m (until session 33), and the square stayed one robot
    short; the spiral now widens to 1.5 m, and its last laps find the shape."""
    run = ETRun(RunConfig(shape="square", seed=228, max_time_s=4 * 3600,
                          et=ETParams(lost_homing=homing, **SESSION_57_SEARCH)),
                          sim_params=NATIVE_MATHS)
    summary = run.run()
    assert summary["formed"]
    assert not summary["duplicate_tags"]
    if homing == "on":
        # later than a whole 1 m spiral (about 75 min) after it got lost
        assert summary["formation_time_s"] > 2 * 3600


def test_the_spiral_starts_again_from_home_past_a_metre() -> None:
    one_spiral = spiral_path()
    radii = [ring_radius(p) for p in np.arange(0.0, 1.5 * one_spiral, 100.0)]
    assert max(radii) <= RING_MAX_MM
    assert max(radii) > RING_MAX_MM - 10.0
    assert min(radii[2 * len(radii) // 3:]) < 100.0  # it went back to the first rings
    assert np.all(np.diff(radii[:100]) >= 0)  # growing at first


def test_home_is_where_it_last_heard_the_group() -> None:
    ri, _, _ = allocate(1)
    reset_odometry(0, ri)
    ri[0, R_ODO_X] = 5 * ODO_PER_MM
    note_home(0, ri)
    ri[0, R_ODO_X] = 205 * ODO_PER_MM  # 200 mm on, facing away (+x)
    note_lost(0, ri)
    # far out, facing away from home: it pivots to turn round
    assert homing_motion(0, ri, False, 0, 0, False) in (LEFT, RIGHT)
    ri[0, R_ODO_H] = round(math.pi * ODO_PER_RAD)  # facing home
    assert homing_motion(0, ri, False, 0, 0, False) == FORWARD
    ri[0, R_ODO_H] = round(0.5 * math.pi * ODO_PER_RAD)  # facing +y: home on its right
    note_home(0, ri)  # ... but now home is here, and the ring is 50 mm out
    assert homing_motion(0, ri, False, 0, 0, False) in (LEFT, RIGHT)


@pytest.mark.parametrize("homing", ["on", "off"])
def test_triangle_seed_31_waits_for_a_lost_searcher_without_homing(homing: str) -> None:
    """The traced run: with the fixed spiral, its last searchers never came back."""
    run = ETRun(RunConfig(shape="triangle", seed=31, max_time_s=2 * 3600,
                          et=ETParams(lost_homing=homing, **SESSION_19_WIDENING)),
                sim_params=NATIVE_MATHS)
    summary = run.run()
    assert summary["formed"] == (homing == "on")
    assert not summary["duplicate_tags"]
    if homing == "off":
        lost = np.flatnonzero(run.controller.states == int(State.SEARCH))
        assert len(lost)
        # the viewer's details of a lost searcher say how long it has been lost
        info = ETLive(run).robot_info(int(lost[0]))
        assert info["lost_s"] != "-" and float(info["lost_s"]) > 60
        assert float(info["from_home_mm"]) >= 0
