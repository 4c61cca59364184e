"""A :class:`~etswarm.viewer.live.LiveRun` over a recording: advancing moves a cursor.

Damage is disabled: the damage calls raise an :class:`~etswarm.errors.EtswarmError`,
which the window shows as a status message.
"""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.states import STATE_NAMES
from etswarm.errors import EtswarmError
from etswarm.viewer.record import RunRecord
from etswarm.viewer.scene import Scene

_NO_DAMAGE = "damage is disabled while replaying a recording"


def state_name(code: int) -> str:
    """Display name of an ET state code ("no ET state" for 255)."""
    return STATE_NAMES[code] if 0 <= code < len(STATE_NAMES) else "no ET state"


class ReplayRun:
    """Replay ``record`` from its first frame; time advances by ticks like a live run."""

    def __init__(self, record: RunRecord) -> None:
        self.record = record
        self.ticks_per_second = int(record.ticks_per_second)
        self.time_s = float(record.t_s[0])
        self.frame = 0

    @property
    def finished(self) -> bool:
        return self.frame >= self.record.frames - 1

    def advance(self, ticks: int) -> None:
        self.time_s = min(self.time_s + ticks / self.ticks_per_second, float(self.record.t_s[-1]))
        self.frame = max(int(np.searchsorted(self.record.t_s, self.time_s, side="right")) - 1, 0)

    def seek(self, frame: int) -> None:
        """Jump to frame index ``frame``."""
        self.frame = int(np.clip(frame, 0, self.record.frames - 1))
        self.time_s = float(self.record.t_s[self.frame])

    def scene(self) -> Scene:
        return self.record.scene(self.frame)

    def robot_info(self, i: int) -> dict[str, object]:
        r, k = self.record, self.frame
        code = int(r.state[k, i])
        info: dict[str, object] = {"ID": i, "state": state_name(code)}
        if r.has_tag is not None and r.tag is not None and r.has_tag[k, i]:
            info["tag"] = f"({int(r.tag[k, i, 0])}, {int(r.tag[k, i, 1])})"
        if r.nn is not None:
            info["NN"] = int(r.nn[k, i])
        if r.ts is not None:
            info["TS"] = int(r.ts[k, i])
        info["position mm"] = f"({r.pos[k, i, 0]:.1f}, {r.pos[k, i, 1]:.1f})"
        info["alive"] = bool(r.alive[k, i])
        info["present"] = bool(r.present[k, i])
        d = np.linalg.norm(r.pos[k] - r.pos[k, i], axis=1)
        talking = r.present[k] & r.alive[k]
        near = np.flatnonzero((d < r.comm_range_mm) & talking & (np.arange(r.n) != i))
        near = near[np.argsort(d[near])]
        info["neighbours"] = [
            {"id": int(j), "dist mm": float(d[j]), "state": state_name(int(r.state[k, j]))}
            for j in near[:12]
        ]
        return info

    def damage_split(self, p0: tuple[float, float], p1: tuple[float, float]) -> None:
        raise EtswarmError(_NO_DAMAGE)

    def damage_remove_rect(self, p0: tuple[float, float], p1: tuple[float, float]) -> None:
        raise EtswarmError(_NO_DAMAGE)

    def damage_kill(self, ids: list[int]) -> None:
        raise EtswarmError(_NO_DAMAGE)
