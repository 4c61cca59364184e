"""A saved run as the viewer and the plots need it: frames of arrays plus events.

:class:`RunRecord` is filled from the simulator's recording file (and the optional
``summary.json`` of the ET runner) by :func:`etswarm.viewer.runfiles.load_run_dir`;
tests build one directly. ``F`` frames, ``N`` robots.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from etswarm.viewer.scene import DEFAULT_BODY_RADIUS_MM, DEFAULT_COMM_RANGE_MM, NO_STATE, Scene


@dataclass
class RunRecord:
    """A recorded run.

    Attributes:
        t_s: (F,) float simulated time of each frame (s), increasing.
        pos: (F, N, 2) float robot centres (mm).
        heading: (F, N) float headings (rad).
        state: (F, N) uint8 ET state codes, or 255 where unknown.
        present: (F, N) bool.
        alive: (F, N) bool.
        tag: (F, N, 2) int, or None when not recorded.
        has_tag: (F, N) bool, or None.
        ts: (F, N) int, or None.
        nn: (F, N) int expected neighbour count NN of each robot's site, or None.
        events: ``[{"t_s": float, "kind": str, ...}]`` sorted by time.
        ticks_per_second: control ticks per simulated second.
        comm_range_mm, body_radius_mm: robot model.
        spacing_mm: lattice spacing d (mm), used for neighbour counts.
        target_sites: (M, 2) mm sites of the target, or empty.
        title: a name for the run (shown in pictures).
        meta: anything else the recording's header held.
    """

    t_s: np.ndarray
    pos: np.ndarray
    heading: np.ndarray
    state: np.ndarray
    present: np.ndarray
    alive: np.ndarray
    tag: np.ndarray | None = None
    has_tag: np.ndarray | None = None
    ts: np.ndarray | None = None
    nn: np.ndarray | None = None
    events: list[dict[str, Any]] = field(default_factory=list)
    ticks_per_second: int = 31
    comm_range_mm: float = DEFAULT_COMM_RANGE_MM
    body_radius_mm: float = DEFAULT_BODY_RADIUS_MM
    spacing_mm: float = 40.0
    target_sites: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    title: str = ""
    meta: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.t_s = np.asarray(self.t_s, dtype=np.float64).reshape(-1)
        f = self.t_s.shape[0]
        self.pos = np.asarray(self.pos, dtype=np.float64)
        if self.pos.ndim != 3 or self.pos.shape[0] != f or self.pos.shape[2] != 2:
            raise ValueError(f"RunRecord.pos must be ({f}, N, 2), got {self.pos.shape}")
        if f == 0:
            raise ValueError("a recording needs at least one frame")
        self.events = sorted(self.events, key=lambda e: float(e.get("t_s", 0.0)))

    @property
    def frames(self) -> int:
        return int(self.t_s.shape[0])

    @property
    def n(self) -> int:
        return int(self.pos.shape[1])

    def has_states(self) -> bool:
        """True when at least one robot has an ET state in some frame."""
        return bool((self.state != NO_STATE).any())

    def state_counts(self) -> np.ndarray:
        """(F, 9) int: present robots per ET state 0..7, then without state (255)."""
        out = np.zeros((self.frames, 9), np.int64)
        for code in range(8):
            out[:, code] = ((self.state == code) & self.present).sum(axis=1)
        out[:, 8] = ((self.state > 7) & self.present).sum(axis=1)
        return out

    def event_lines(self, upto_s: float, limit: int = 6) -> list[str]:
        """Short strings of the events at or before ``upto_s`` (the last ``limit``)."""
        from etswarm.viewer.render import format_sim_time

        lines = []
        for e in self.events:
            if float(e.get("t_s", 0.0)) > upto_s:
                break
            extra = {k: v for k, v in e.items() if k not in ("t_s", "kind")}
            detail = " ".join(f"{k}={v}" for k, v in list(extra.items())[:2])
            lines.append(
                f"t={format_sim_time(float(e['t_s']))} {e.get('kind', '?')} {detail}".strip()
            )
        return lines[-limit:]

    def scene(self, k: int) -> Scene:
        """Frame ``k`` as a drawable scene."""
        n = self.n
        zeros2 = np.zeros((n, 2), np.int64)
        return Scene(
            pos=self.pos[k],
            heading=self.heading[k],
            present=self.present[k],
            alive=self.alive[k],
            state=self.state[k],
            tag=self.tag[k] if self.tag is not None else zeros2,
            has_tag=self.has_tag[k] if self.has_tag is not None else np.zeros(n, bool),
            ts=self.ts[k] if self.ts is not None else np.zeros(n, np.int64),
            target_sites=self.target_sites,
            comm_range_mm=self.comm_range_mm,
            body_radius_mm=self.body_radius_mm,
            sim_time_s=float(self.t_s[k]),
            events=self.event_lines(float(self.t_s[k])),
            title=self.title,
        )
