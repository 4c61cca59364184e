"""One ET run: a shape, a swarm on the simulator, the ET controller, and its measures.

``ETRun`` sets up the experiment (layout, seeds, robot memory), advances the simulator in
chunks, watches the measures from outside (the robots never see them) and produces the
JSON summary of ``etswarm run --json``.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from etswarm.algorithm.et_controller import ETController
from etswarm.algorithm.layout import plan_layout
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.states import PLACED_STATES, STATE_NAMES, State
from etswarm.errors import EtswarmError
from etswarm.measures.formation import (
    components,
    duplicate_tags,
    is_formed,
    jaccard,
    placement_error_mm,
)
from etswarm.seeding import stream
from etswarm.shapes import load_shape, scale
from etswarm.sim import Simulator
from etswarm.sim.params import SimParams
from etswarm.sim.world import World

#: Ticks per measurement check while running (10 simulated seconds).
CHECK_EVERY_TICKS = 310


@dataclass(frozen=True)
class RunConfig:
    """What ``etswarm run`` takes. Times in simulated seconds, lengths in mm."""

    shape: str = "T"
    robots: int | None = None
    seed: int = 0
    loss: float = 0.2
    noise_mm: float = 2.0
    max_time_s: float = 3 * 3600.0
    layout: str = "queue"
    fit: bool = False
    et: ETParams = field(default_factory=ETParams)

    def __post_init__(self) -> None:
        if not 0.0 <= self.loss < 1.0:
            raise EtswarmError(f"--loss must be in [0, 1), got {self.loss}")
        if self.noise_mm < 0:
            raise EtswarmError(f"--noise must be >= 0 mm, got {self.noise_mm}")
        if self.max_time_s <= 0:
            raise EtswarmError(f"--max-time must be > 0 s, got {self.max_time_s}")
        if self.seed < 0:
            raise EtswarmError(f"--seed must be >= 0, got {self.seed}")
        if self.robots is not None and self.robots < 3:
            raise EtswarmError(f"--robots must be at least 3 (the seeds), got {self.robots}")


class ETRun:
    """A configured ET experiment on the simulator."""

    def __init__(self, config: RunConfig, sim_params: SimParams | None = None) -> None:
        self.config = config
        self.shape = load_shape(config.shape)
        cells = self.shape.cells
        n = config.robots if config.robots is not None else len(cells)
        self.notes: list[str] = []
        if n < len(cells):
            if config.fit:
                cells = scale(self.shape, max(3, n))
                self.notes.append(
                    f"{n} robots for {self.shape.n_cells} cells: forming the scaled shape "
                    f"of {len(cells)} cells (--fit)"
                )
            else:
                self.notes.append(
                    f"{n} robots for {self.shape.n_cells} cells: the shape cannot be completed; "
                    "forming what the robots can (use --fit to form a scaled shape)"
                )
        elif n > len(cells):
            self.notes.append(f"{n - len(cells)} extra robots will stay Queued")
        self.target = cells
        base = sim_params or SimParams()
        self.sim_params = SimParams(
            **{**asdict(base), "loss": config.loss, "dist_noise_mm": config.noise_mm}
        )
        self.layout = plan_layout(
            cells,
            n,
            layout=config.layout,
            spacing_mm=config.et.spacing_mm,
            rng=stream(config.seed, "placement"),
        )
        self.world = World.from_positions(
            self.layout.pos, self.layout.heading, self.sim_params, config.seed
        )
        self.controller = ETController(n, cells, config.et, self.sim_params.ticks_per_s)
        self.controller.seed(self.layout)
        self.sim = Simulator(self.world, self.controller, self.sim_params, config.seed)
        self.events: list[dict[str, Any]] = []
        self.formed_at_s: float | None = None
        self.wall_s = 0.0

    # -- clock -------------------------------------------------------------------------
    @property
    def ticks_per_s(self) -> int:
        return self.sim_params.ticks_per_s

    @property
    def sim_time_s(self) -> float:
        return self.world.tick / self.ticks_per_s

    def advance(self, ticks: int) -> None:
        """Run ``ticks`` ticks, then update the measures."""
        t0 = time.perf_counter()
        self.sim.run_ticks(ticks)
        self.wall_s += time.perf_counter() - t0
        self._check()

    def _check(self) -> None:
        if self.formed_at_s is None and self.formed():
            self.formed_at_s = self.sim_time_s
            self.events.append({"t_s": self.sim_time_s, "kind": "formed"})

    def run(self, progress=None) -> dict[str, Any]:  # type: ignore[no-untyped-def]
        """Advance until formed or ``max_time_s``; return the summary."""
        max_ticks = round(self.config.max_time_s * self.ticks_per_s)
        while self.formed_at_s is None and self.world.tick < max_ticks:
            step = min(CHECK_EVERY_TICKS, max_ticks - self.world.tick)
            self.advance(step)
            if progress is not None:
                progress(self)
        return self.summary()

    # -- measures -----------------------------------------------------------------------
    def _masks(self) -> tuple[np.ndarray, np.ndarray]:
        states = self.controller.states
        live = self.world.present & self.world.alive
        holds = live & np.isin(states, [int(s) for s in PLACED_STATES])
        stable = live & (states == State.STABLE)
        return holds, stable

    def formed(self) -> bool:
        holds, stable = self._masks()
        return is_formed(self.controller.tags, holds, stable, self.target)

    def summary(self) -> dict[str, Any]:
        """The JSON summary (DESIGN §5 measures; keys documented in the README)."""
        holds, stable = self._masks()
        tags = self.controller.tags
        live = self.world.present & self.world.alive
        states = self.controller.states
        comps = []
        for group in components(self.world.pos, live, self.sim_params.comm_range_mm):
            member = np.zeros(self.world.n, dtype=bool)
            member[group] = True
            g_holds = holds & member
            g_formed = is_formed(tags, g_holds, stable & member, self.target)
            comps.append(
                {
                    "robots": len(group),
                    "target_cells": len(self.target),
                    "formed": bool(g_formed),
                    "jaccard": round(jaccard(tags, g_holds, self.target), 6),
                    "census_count": None,
                    "time_to_stable_s": self.formed_at_s if g_formed else None,
                }
            )
        err = placement_error_mm(self.world.pos, tags, holds, self.config.et.spacing_mm)
        return {
            "shape": self.config.shape,
            "robots": int(self.world.n),
            "target_cells": len(self.target),
            "seed": self.config.seed,
            "loss": self.config.loss,
            "noise_mm": self.config.noise_mm,
            "layout": self.config.layout,
            "formed": self.formed_at_s is not None,
            "formation_time_s": self.formed_at_s,
            "sim_time_s": round(self.sim_time_s, 3),
            "wall_time_s": round(self.wall_s, 3),
            "jaccard": round(jaccard(tags, holds, self.target), 6),
            "placement_error_mm": None if err is None else round(err, 3),
            "duplicate_tags": [list(t) for t in duplicate_tags(tags, holds)],
            "states": {
                STATE_NAMES[s]: int(np.sum(live & (states == s))) for s in range(len(State))
            },
            "components": comps,
            "events": list(self.events),
            "notes": list(self.notes),
        }
