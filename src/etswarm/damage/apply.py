"""Applying a damage to the world: which robots, and what happens to them."""

from __future__ import annotations

import numpy as np

from etswarm.damage.spec import DamageSpec
from etswarm.errors import EtswarmError
from etswarm.sim.world import World

#: The least distance a split moves the cut-off side, mm: far beyond the 70 mm radio range.
SPLIT_SHIFT_MM = 600.0


def split_shift_mm(pos: np.ndarray, present: np.ndarray, normal: np.ndarray) -> float:
    """How far (mm) a split moves the cut-off side along the unit vector ``normal`` (2,):
    ``SPLIT_SHIFT_MM``, or the present robots' extent along it (``pos`` (N, 2) mm,
    ``present`` (N,) bool) when that is more. Each part regrows its scaled shape over
    itself, and a shape may reach about as far from the part as the whole swarm was wide;
    a fixed 600 mm let the two parts of a 300-cell plus (2.2 m wide) grow back into each
    other and elect again as one. Swarms up to 15 spacings across keep the 600 mm."""
    along = pos[present] @ normal
    width = float(along.max() - along.min()) if along.size else 0.0
    return max(SPLIT_SHIFT_MM, width)


def select(
    spec: DamageSpec, world: World, spacing_mm: float, rng: np.random.Generator
) -> np.ndarray:
    """IDs ((K,) int64) of the present robots the damage's region holds."""
    present = world.present
    xy = world.pos / spacing_mm
    if spec.region in ("line", "half"):
        coord = xy[:, 0] if spec.axis == "x" else xy[:, 1]
        value = spec.values[0]
        if spec.mid:
            span = coord[present]
            value = 0.5 * (span.min() + span.max()) if len(span) else 0.0
        inside = coord < value if spec.op == "<" else coord > value
    elif spec.region == "disc":
        cx, cy, r = spec.values
        inside = np.hypot(xy[:, 0] - cx, xy[:, 1] - cy) <= r
    elif spec.region == "band":
        coord = xy[:, 0] if spec.axis == "x" else xy[:, 1]
        lo, hi = spec.values
        inside = (coord >= lo) & (coord <= hi)
    elif spec.region == "random":
        candidates = np.flatnonzero(present)
        count = round(spec.values[0] * len(candidates))
        chosen = rng.choice(candidates, size=count, replace=False) if count else []
        inside = np.zeros(world.n, dtype=bool)
        inside[np.asarray(chosen, dtype=np.int64)] = True
    else:
        ids = np.asarray(spec.values, dtype=np.int64)
        if np.any(ids >= world.n):
            raise EtswarmError(
                f"--damage {spec.text!r}: robot IDs must be below {world.n}, got {ids.max()}"
            )
        inside = np.zeros(world.n, dtype=bool)
        inside[ids] = True
    return np.flatnonzero(inside & present)


def apply_damage(
    spec: DamageSpec, world: World, spacing_mm: float, rng: np.random.Generator
) -> np.ndarray:
    """Damage ``world`` in place; return the IDs affected.

    split: the selected side moves away along the axis, ``split_shift_mm`` (its robots
    keep running); remove: they leave the world; kill: they stop and fall silent.
    """
    ids = select(spec, world, spacing_mm, rng)
    if spec.kind == "split":
        normal = np.array([1.0, 0.0] if spec.axis == "x" else [0.0, 1.0])
        world.pos[ids] += split_shift_mm(world.pos, world.present, normal) * normal
    elif spec.kind == "remove":
        world.remove(ids)
    else:
        world.kill(ids)
    return ids
