"""Damage applied to a world: how far a split moves the cut-off side."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.damage import apply_damage, parse_damage
from etswarm.damage.apply import SPLIT_SHIFT_MM, split_shift_mm
from etswarm.sim.params import SimParams
from etswarm.sim.world import World


def row_world(width_mm: float) -> World:
    """Robots 40 mm apart along x from 0 to ``width_mm``, at y = 0."""
    xs = np.arange(0.0, width_mm + 1e-9, 40.0)
    pos = np.column_stack([xs, np.zeros_like(xs)])
    return World.from_positions(pos, np.zeros(len(xs)), SimParams(), 0)


def test_a_split_moves_the_cut_off_side_clear_of_the_swarm_s_own_width() -> None:
    for width in (400.0, 2000.0):  # a T, and a 300-cell plus (2.2 m)
        world = row_world(width)
        before = world.pos.copy()
        ids = apply_damage(parse_damage("split x=5"), world, 40.0, np.random.default_rng(0))
        moved = np.zeros(world.n, dtype=bool)
        moved[ids] = True
        assert moved.any() and not moved.all()
        gap = world.pos[moved, 0].min() - world.pos[~moved, 0].max()
        # one spacing apart before the cut; then 600 mm more, or the row's whole width
        assert gap == pytest.approx(40.0 + max(SPLIT_SHIFT_MM, width))
        assert np.array_equal(world.pos[~moved], before[~moved])
        assert np.allclose(world.pos[moved, 1], 0.0)


def test_the_shift_counts_present_robots_only() -> None:
    world = row_world(2000.0)
    present = np.zeros(world.n, dtype=bool)
    present[:3] = True  # 0, 40 and 80 mm
    shift = split_shift_mm(world.pos, present, np.array([1.0, 0.0]))
    assert shift == SPLIT_SHIFT_MM
    present[-1] = True  # 2000 mm
    assert split_shift_mm(world.pos, present, np.array([1.0, 0.0])) == 2000.0
    assert split_shift_mm(world.pos, np.zeros(world.n, dtype=bool), np.array([0.0, 1.0])) == (
        SPLIT_SHIFT_MM
    )
