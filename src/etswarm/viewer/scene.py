"""The drawable snapshot of a swarm: what the renderer needs, nothing more.

A :class:`Scene` decouples drawing from simulating. The live simulator, a replayed
recording and a hand-made test case all produce Scenes; the renderer only reads them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from etswarm.algorithm.states import State

#: ``state`` value meaning "this robot has no ET state" (random walk, replay without
#: states); drawn in a neutral colour.
NO_STATE = 255

#: Kilobot body radius (mm), the design brief's default.
DEFAULT_BODY_RADIUS_MM = 16.5
#: IR range centre to centre (mm), the design brief's default.
DEFAULT_COMM_RANGE_MM = 70.0


@dataclass
class Scene:
    """Everything drawable at one instant. ``N`` robots, ``M`` target lattice sites.

    Attributes:
        pos: (N, 2) float, robot centres in mm (x right, y up).
        heading: (N,) float, heading in radians, counter-clockwise from +x.
        present: (N,) bool, robot is in the arena (removed robots are False; not drawn).
        alive: (N,) bool, robot runs and talks (killed robots are False; drawn as dead
            obstacles, no links).
        state: (N,) uint8, ET state code (:class:`etswarm.algorithm.states.State`) or
            :data:`NO_STATE` (255).
        tag: (N, 2) int, lattice tag (X, Y) held by the robot; meaningful where ``has_tag``.
        has_tag: (N,) bool, the robot holds a tag.
        ts: (N,) int, the robot's timestep TS (0 when it has none).
        target_sites: (M, 2) float, world positions (mm) of the current target's lattice
            sites, drawn faintly in the background. May be empty.
        comm_range_mm: IR range, centre to centre (mm); links are drawn below this.
        body_radius_mm: robot body radius (mm).
        sim_time_s: simulated time (s).
        speedup: simulated seconds per wall second, or None when unknown.
        events: short event strings, most recent last.
        title: text shown at the top of the picture ("" for none).
        ids: (N,) int robot IDs shown in labels; None means ID = index.
    """

    pos: np.ndarray
    heading: np.ndarray
    present: np.ndarray
    alive: np.ndarray
    state: np.ndarray
    tag: np.ndarray
    has_tag: np.ndarray
    ts: np.ndarray
    target_sites: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    comm_range_mm: float = DEFAULT_COMM_RANGE_MM
    body_radius_mm: float = DEFAULT_BODY_RADIUS_MM
    sim_time_s: float = 0.0
    speedup: float | None = None
    events: list[str] = field(default_factory=list)
    title: str = ""
    ids: np.ndarray | None = None

    def __post_init__(self) -> None:
        self.pos = np.asarray(self.pos, dtype=np.float64).reshape(-1, 2)
        n = self.pos.shape[0]
        self.heading = _vector(self.heading, n, np.float64, "heading")
        self.present = _vector(self.present, n, np.bool_, "present")
        self.alive = _vector(self.alive, n, np.bool_, "alive")
        self.state = _vector(self.state, n, np.uint8, "state")
        self.tag = np.asarray(self.tag, dtype=np.int64).reshape(n, 2)
        self.has_tag = _vector(self.has_tag, n, np.bool_, "has_tag")
        self.ts = _vector(self.ts, n, np.int64, "ts")
        self.target_sites = np.asarray(self.target_sites, dtype=np.float64).reshape(-1, 2)
        if self.ids is not None:
            self.ids = _vector(self.ids, n, np.int64, "ids")

    @property
    def n(self) -> int:
        """Number of robot slots (present or not)."""
        return int(self.pos.shape[0])

    def robot_ids(self) -> np.ndarray:
        """(N,) int: the ID of every robot slot."""
        return np.arange(self.n) if self.ids is None else self.ids

    def state_counts(self) -> dict[int, int]:
        """Present robots per state code, for every ET state plus :data:`NO_STATE`."""
        codes = self.state[self.present]
        counts = np.bincount(codes, minlength=256)
        out = {int(s): int(counts[int(s)]) for s in State}
        out[NO_STATE] = int(counts[NO_STATE])
        return out

    @classmethod
    def from_positions(cls, pos: np.ndarray, **kwargs: object) -> Scene:
        """A scene of robots at ``pos`` (N, 2 mm), all present, alive, without state or tag.

        Any other field may be given as a keyword argument.
        """
        pos = np.asarray(pos, dtype=np.float64).reshape(-1, 2)
        n = pos.shape[0]
        defaults: dict[str, object] = {
            "heading": np.zeros(n),
            "present": np.ones(n, bool),
            "alive": np.ones(n, bool),
            "state": np.full(n, NO_STATE, np.uint8),
            "tag": np.zeros((n, 2), np.int64),
            "has_tag": np.zeros(n, bool),
            "ts": np.zeros(n, np.int64),
        }
        defaults.update(kwargs)
        return cls(pos=pos, **defaults)  # type: ignore[arg-type]


def _vector(values: object, n: int, dtype: type, name: str) -> np.ndarray:
    arr: np.ndarray = np.asarray(values, dtype=dtype)
    if arr.shape != (n,):
        raise ValueError(f"Scene.{name} must have shape ({n},), got {arr.shape}")
    return arr
