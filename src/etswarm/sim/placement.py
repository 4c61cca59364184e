"""Placing robots: uniformly at random without overlap in a square arena with walls."""

from __future__ import annotations

import math

import numpy as np

from etswarm.errors import EtswarmError
from etswarm.seeding import stream
from etswarm.sim.params import SimParams
from etswarm.sim.world import World


def arena_side_for(n: int, mm_per_robot: float = 50.0) -> float:
    """Side (mm) of the benchmark arena for ``n`` robots: ``mm_per_robot * sqrt(n)``."""
    return mm_per_robot * math.sqrt(n)


def place_uniform(n: int, side_mm: float, radius_mm: float, rng: np.random.Generator,
                  gap_mm: float = 0.0, max_tries: int = 5000) -> np.ndarray:
    """(n, 2) mm centres uniform in [r, side - r]^2, no two closer than 2 r + gap.

    Random sequential placement with a cell grid (cell = 2 r + gap, so a conflict can
    only be in the 3 x 3 neighbouring cells). Raises EtswarmError when the square is too
    crowded to place everyone within ``max_tries`` draws per robot.
    """
    if n == 0:
        return np.zeros((0, 2))
    min_d = 2.0 * radius_mm + gap_mm
    lo, hi = radius_mm, side_mm - radius_mm
    if hi < lo:
        raise EtswarmError(f"arena side {side_mm} mm is smaller than one robot")
    cell = min_d
    grid: dict[tuple[int, int], list[int]] = {}
    pos = np.empty((n, 2))
    min_d2 = min_d * min_d
    for i in range(n):
        for _ in range(max_tries):
            x, y = rng.uniform(lo, hi, 2)
            cx, cy = int((x - lo) / cell), int((y - lo) / cell)
            ok = True
            for ax in (cx - 1, cx, cx + 1):
                for ay in (cy - 1, cy, cy + 1):
                    for j in grid.get((ax, ay), ()):
                        dx = pos[j, 0] - x
                        dy = pos[j, 1] - y
                        if dx * dx + dy * dy < min_d2:
                            ok = False
                            break
                    if not ok:
                        break
                if not ok:
                    break
            if ok:
                pos[i] = (x, y)
                grid.setdefault((cx, cy), []).append(i)
                break
        else:
            raise EtswarmError(
                f"cannot place {n} robots of radius {radius_mm} mm in a {side_mm:.0f} mm square"
            )
    return pos


def random_world(n: int, params: SimParams, seed: int, side_mm: float | None = None) -> World:
    """A world of ``n`` robots placed uniformly at random, random headings.

    ``side_mm`` defaults to ``params.arena_mm`` (the walls) or, without walls, to the
    benchmark density 50 mm * sqrt(n). Uses the "placement" stream.
    """
    side = side_mm if side_mm is not None else (params.arena_mm or arena_side_for(n))
    rng = stream(seed, "placement")
    pos = place_uniform(n, side, params.body_radius_mm, rng)
    heading = rng.uniform(-np.pi, np.pi, n)
    return World.from_positions(pos, heading, params, seed)
