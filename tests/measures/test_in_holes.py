"""Points in a hole of the target, by the lattice the placed robots fit."""

from __future__ import annotations

import math

import numpy as np

from etswarm.measures.formation import in_holes
from etswarm.shapes.lattice import lattice_distance, tags_to_xy

D = 40.0


def ring_target() -> np.ndarray:
    """An ``O``: the sites 2 to 3 steps from (0, 0), round a hole of 7 sites."""
    sites = np.array([(x, y) for x in range(-3, 4) for y in range(-3, 4)], dtype=np.int64)
    steps = lattice_distance(sites, np.zeros_like(sites))
    return sites[(steps >= 2) & (steps <= 3)]


def test_points_in_the_middle_of_a_turned_ring_are_in_its_hole() -> None:
    target = ring_target()
    angle, shift = 0.4, np.array([250.0, -80.0])
    c, s = math.cos(angle), math.sin(angle)
    turn = np.array([[c, s], [-s, c]])
    pos = tags_to_xy(target, D) @ turn + shift
    holds = np.ones(len(target), dtype=bool)
    # The centre, a point 1 site out of it, a point on the ring, one beyond it.
    ideal = tags_to_xy(np.array([(0, 0), (1, 0), (2, 0), (4, 0)]), D)
    points = (ideal + np.array([3.0, -2.0])) @ turn + shift
    assert in_holes(points, pos, target, holds, target, D).tolist() == [True, True, False, False]
    assert not in_holes(pos, pos, target, holds, target, D).any()


def test_a_shape_without_a_hole_has_no_point_in_one() -> None:
    target = np.array([(x, 0) for x in range(5)], dtype=np.int64)
    pos = tags_to_xy(target, D)
    points = np.array([[80.0, 30.0], [0.0, 0.0]])
    assert not in_holes(points, pos, target, np.ones(5, dtype=bool), target, D).any()
