"""Controllers shipped with the simulator, by name (for ``etswarm sim --controller``)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from etswarm.sim.controllers.randomwalk import RandomWalk

#: name -> factory(n_robots) returning a controller.
CONTROLLERS: dict[str, Callable[[int], Any]] = {
    "randomwalk": RandomWalk,
}

__all__ = ["CONTROLLERS", "RandomWalk"]
