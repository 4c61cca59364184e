"""A :class:`~etswarm.viewer.live.LiveRun` over the plain simulator (any controller).

Used by ``etswarm view --controller randomwalk`` and by tests. It reads the world's
arrays for drawing and applies damage directly to them:

- split: the robots on the smaller side of the line (the left side on a tie) move
  straight away from it by 1.5 × the IR range, so no link crosses the cut; in a walled
  arena, where they could leave the floor, they are removed instead;
- remove: robots inside the rectangle leave the world (``World.remove``);
- kill: robots stop and fall silent but stay as obstacles (``World.kill``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from etswarm.viewer.render import format_sim_time
from etswarm.viewer.scene import NO_STATE, Scene

MOTOR_NAMES = ("stop", "forward", "left", "right")


def side_of_line(pos: np.ndarray, p0: tuple[float, float], p1: tuple[float, float]) -> np.ndarray:
    """(N,) float: signed distance (mm) of each point from the line p0 -> p1, left > 0."""
    a = np.asarray(p0, dtype=np.float64)
    d = np.asarray(p1, dtype=np.float64) - a
    length = float(np.hypot(*d))
    if length == 0:
        raise ValueError("a split line needs two different points")
    rel = np.asarray(pos, dtype=np.float64) - a
    return (d[0] * rel[:, 1] - d[1] * rel[:, 0]) / length


def in_rect(pos: np.ndarray, p0: tuple[float, float], p1: tuple[float, float]) -> np.ndarray:
    """(N,) bool: points inside the axis-aligned rectangle with corners p0, p1."""
    lo = np.minimum(p0, p1)
    hi = np.maximum(p0, p1)
    return np.all((pos >= lo) & (pos <= hi), axis=1)


class SimLiveRun:
    """Drive a :class:`etswarm.sim.simulator.Simulator` from the viewer.

    Args:
        sim: the simulator (its ``world`` is drawn and damaged).
        title: shown at the top of the picture.
        max_time_s: the run is finished after this much simulated time (None: never).
        state_of: world -> (N,) uint8 ET state codes; None draws every robot neutral.
        target_sites: (M, 2) mm lattice sites drawn faintly, or None.
    """

    def __init__(
        self,
        sim: Any,
        title: str = "",
        max_time_s: float | None = None,
        state_of: Callable[[Any], np.ndarray] | None = None,
        target_sites: np.ndarray | None = None,
    ) -> None:
        self.sim = sim
        self.world = sim.world
        self.params = sim.params
        self.title = title
        self.ticks_per_second = int(self.params.ticks_per_s)
        self.max_ticks = None if max_time_s is None else round(max_time_s * self.ticks_per_second)
        self.state_of = state_of
        self.target_sites = np.zeros((0, 2)) if target_sites is None else target_sites
        self.events: list[str] = []

    @property
    def finished(self) -> bool:
        return self.max_ticks is not None and self.world.tick >= self.max_ticks

    @property
    def sim_time_s(self) -> float:
        return self.world.tick / self.ticks_per_second

    def advance(self, ticks: int) -> None:
        if self.max_ticks is not None:
            ticks = min(ticks, self.max_ticks - self.world.tick)
        if ticks > 0:
            self.sim.run_ticks(int(ticks))

    def scene(self) -> Scene:
        w = self.world
        n = w.n
        state = (
            np.full(n, NO_STATE, np.uint8)
            if self.state_of is None
            else np.asarray(self.state_of(w), np.uint8)
        )
        return Scene(
            pos=w.pos.copy(),
            heading=w.heading.copy(),
            present=w.present.copy(),
            alive=w.alive.copy(),
            state=state,
            tag=np.zeros((n, 2), np.int64),
            has_tag=np.zeros(n, bool),
            ts=np.zeros(n, np.int64),
            target_sites=self.target_sites,
            comm_range_mm=self.params.comm_range_mm,
            body_radius_mm=self.params.body_radius_mm,
            sim_time_s=self.sim_time_s,
            events=list(self.events[-6:]),
            title=self.title,
        )

    def robot_info(self, i: int) -> dict[str, object]:
        w = self.world
        info: dict[str, object] = {
            "ID": i,
            "state": "no ET state" if self.state_of is None else int(self.state_of(w)[i]),
            "position mm": f"({w.pos[i, 0]:.1f}, {w.pos[i, 1]:.1f})",
            "heading deg": f"{np.degrees(w.heading[i]) % 360:.0f}",
            "alive": bool(w.alive[i]),
            "present": bool(w.present[i]),
            "motor": MOTOR_NAMES[int(w.motor[i])] if 0 <= w.motor[i] < 4 else int(w.motor[i]),
            "LED": int(w.led[i]),
        }
        count = getattr(self.sim.controller, "neighbour_count", None)
        if callable(count):
            info["heard (table)"] = int(count()[i])
        d = np.linalg.norm(w.pos - w.pos[i], axis=1)
        near = np.flatnonzero(
            (d < self.params.comm_range_mm) & w.present & w.alive & (np.arange(w.n) != i)
        )
        near = near[np.argsort(d[near])]
        info["neighbours"] = [{"id": int(j), "dist mm": float(d[j])} for j in near[:12]]
        return info

    def _event(self, text: str) -> None:
        self.events.append(f"t={format_sim_time(self.sim_time_s)} {text}")

    def damage_split(self, p0: tuple[float, float], p1: tuple[float, float]) -> None:
        w = self.world
        s = side_of_line(w.pos, p0, p1)
        live = w.present
        left = live & (s > 0)
        right = live & (s <= 0)
        moving = left if left.sum() <= right.sum() else right
        ids = np.flatnonzero(moving)
        if ids.size == 0:
            self._event("split: no robot on one side")
            return
        if self.params.walls:
            w.remove(ids)
            self._event(f"split: {ids.size} robots removed (walled arena)")
            return
        d = np.asarray(p1, float) - np.asarray(p0, float)
        normal = np.array([-d[1], d[0]]) / np.hypot(*d)  # points to the left side
        sign = 1.0 if moving is left else -1.0
        w.pos[ids] += sign * normal * 1.5 * self.params.comm_range_mm
        self._event(f"split: {ids.size} robots moved away")

    def damage_remove_rect(self, p0: tuple[float, float], p1: tuple[float, float]) -> None:
        w = self.world
        ids = np.flatnonzero(w.present & in_rect(w.pos, p0, p1))
        if ids.size:
            w.remove(ids)
        self._event(f"removed {ids.size} robots")

    def damage_kill(self, ids: list[int]) -> None:
        ids_arr = np.asarray(ids, dtype=np.int64)
        self.world.kill(ids_arr)
        self._event(f"killed {', '.join(f'#{i}' for i in ids_arr.tolist())}")


def randomwalk_live_run(
    n: int, seed: int = 0, params: Any = None, max_time_s: float | None = None
) -> SimLiveRun:
    """``n`` random-walk robots placed uniformly at the benchmark density, ready to view."""
    from etswarm.sim.controllers.randomwalk import RandomWalk
    from etswarm.sim.params import SimParams
    from etswarm.sim.placement import random_world
    from etswarm.sim.simulator import Simulator

    params = params or SimParams()
    world = random_world(n, params, seed)
    sim = Simulator(world, RandomWalk(n), params, seed)
    return SimLiveRun(sim, title=f"random walk, {n} robots, seed {seed}", max_time_s=max_time_s)
