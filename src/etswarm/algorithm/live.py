"""The ET run as the viewer's ``LiveRun``: scenes, robot details and mouse damage."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.homing import ODO_PER_MM
from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TS,
    NB_TX,
    NB_TY,
    R_COUNT,
    R_HOME_X,
    R_HOME_Y,
    R_LOST_SINCE,
    R_NN,
    R_ODO_X,
    R_ODO_Y,
    R_OFF_X,
    R_OFF_Y,
    R_PINCH_REFUSED,
    R_TS,
)
from etswarm.algorithm.offsets import FINE_PER_MM
from etswarm.algorithm.run import ETRun
from etswarm.algorithm.states import STATE_NAMES
from etswarm.damage.apply import split_shift_mm
from etswarm.viewer.scene import Scene

Point = tuple[float, float]



class ETLive:
    """Adapter of :class:`ETRun` to :class:`etswarm.viewer.live.LiveRun`."""

    def __init__(self, run: ETRun, title: str = "") -> None:
        self.run = run
        self.title = title or f"ET {run.config.shape}, seed {run.config.seed}"
        self.ticks_per_second = run.ticks_per_s
        self._max_ticks = round(run.config.max_time_s * run.ticks_per_s)

    @property
    def finished(self) -> bool:
        return self.run.finished or self.run.world.tick >= self._max_ticks

    def advance(self, ticks: int) -> None:
        ticks = min(ticks, self._max_ticks - self.run.world.tick)
        if ticks > 0:
            self.run.advance(ticks)

    def scene(self) -> Scene:
        r = self.run
        states = r.controller.states.astype(np.uint8)
        has_tag = r.controller.holds_site
        return Scene(
            pos=r.world.pos.copy(),
            heading=r.world.heading.copy(),
            present=r.world.present.copy(),
            alive=r.world.alive.copy(),
            state=states,
            tag=r.controller.tags.copy(),
            has_tag=has_tag,
            ts=np.where(has_tag, r.controller.ri[:, R_TS], 0),
            target_sites=r.target_sites_world(),
            comm_range_mm=r.sim_params.comm_range_mm,
            body_radius_mm=r.sim_params.body_radius_mm,
            sim_time_s=r.sim_time_s,
            events=[f"{e['t_s'] / 60:.1f} min: {e['kind']}" for e in r.events[-4:]],
            title=self.title,
        )

    def robot_info(self, i: int) -> dict[str, object]:
        r = self.run
        ri = r.controller.ri
        state = int(r.controller.states[i])
        tick = r.world.tick
        table = []
        for m in range(r.controller.nb.shape[1]):
            row = r.controller.nb[i, m]
            if row[NB_ID] < 0:
                continue
            st = int(row[NB_STATE])
            table.append(
                {
                    "id": int(row[NB_ID]),
                    "state": STATE_NAMES[st],
                    "tag": f"({row[NB_TX]},{row[NB_TY]})" if st >= 2 else "-",
                    "TS": int(row[NB_TS]) if st >= 2 else "-",
                    "dist": f"{r.controller.nb_dist[i, m]:.0f}",
                    "age_s": f"{(tick - row[NB_LAST]) / r.ticks_per_s:.1f}",
                }
            )
        placed = bool(r.controller.holds_site[i])
        searching = state == 1
        lost_since = int(ri[i, R_LOST_SINCE])
        from_home = np.hypot(ri[i, R_ODO_X] - ri[i, R_HOME_X], ri[i, R_ODO_Y] - ri[i, R_HOME_Y])
        return {
            "ID": i,
            "state": STATE_NAMES[state],
            "tag": tuple(int(v) for v in r.controller.tags[i]) if placed else "-",
            "NN": int(ri[i, R_NN]) if placed else "-",
            "count": int(ri[i, R_COUNT]) if placed else "-",
            "TS": int(ri[i, R_TS]) if placed else "-",
            # where it estimates it stands off its site's centre (``offsets``)
            "offset_mm": (
                f"({ri[i, R_OFF_X] / FINE_PER_MM:+.1f}, {ri[i, R_OFF_Y] / FINE_PER_MM:+.1f})"
                if placed else "-"
            ),
            # a searcher that hears no stationary robot: for how long, and how far it
            # reckons it is from where it last heard one (``homing``)
            "lost_s": (
                f"{(tick - (lost_since - 1)) / r.ticks_per_s:.0f}"
                if searching and lost_since > 0 else "-"
            ),
            "from_home_mm": f"{from_home / ODO_PER_MM:.0f}" if searching else "-",
            # sites it refused since it left the repository: it stood too far into a
            # free notch site next to them (``pinch``)
            "pinch_refusals": int(ri[i, R_PINCH_REFUSED]) if searching else "-",
            "neighbours": table,
        }

    def damage_split(self, p0: Point, p1: Point) -> None:
        """Move every robot on the left of p0 -> p1 away along the line's normal."""
        w = self.run.world
        a = np.asarray(p0, dtype=float)
        b = np.asarray(p1, dtype=float)
        direction = b - a
        length = float(np.hypot(*direction))
        if length < 1e-9:
            return
        normal = np.array([-direction[1], direction[0]]) / length
        side = ((w.pos - a) @ normal > 0) & w.present
        w.pos[side] += split_shift_mm(w.pos, w.present, normal) * normal
        self.run.record_damage("split (viewer)", int(side.sum()))

    def damage_remove_rect(self, p0: Point, p1: Point) -> None:
        w = self.run.world
        lo = np.minimum(p0, p1)
        hi = np.maximum(p0, p1)
        inside = np.all((w.pos >= lo) & (w.pos <= hi), axis=1) & w.present
        ids = np.flatnonzero(inside)
        if len(ids):
            w.remove(ids)
        self.run.record_damage("remove (viewer)", len(ids))

    def damage_kill(self, ids: list[int]) -> None:
        if ids:
            self.run.world.kill(np.asarray(ids, dtype=np.int64))
        self.run.record_damage("kill (viewer)", len(ids))
