"""A way across a ring: free sites that join the hole's edge to the outside."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.kernel_util import hex_distance
from etswarm.measures.formation import way_across

#: An ``O``: the sites 3 to 5 steps from (0, 0) round a hole of the sites within 2.
RING = np.array(
    [(x, y) for x in range(-5, 6) for y in range(-5, 6) if 3 <= hex_distance(x, y) <= 5],
    dtype=np.int64,
)
#: A hexagon of the sites within 5 steps: no hole.
FULL = np.array(
    [(x, y) for x in range(-5, 6) for y in range(-5, 6) if hex_distance(x, y) <= 5],
    dtype=np.int64,
)


def test_a_chain_from_the_hole_to_the_outside_is_a_way_across() -> None:
    assert way_across([(3, 0), (4, 0), (5, 0)], RING)
    assert way_across([(5, 1), (3, 0), (4, 1)], RING)  # a zigzag, in any order
    assert way_across([(3, 0), (4, 0), (4, 1), (5, 1), (5, 2)], RING)  # two wide in part


def test_notches_and_lone_sites_are_not() -> None:
    assert not way_across([], RING)
    assert not way_across([(4, 0), (5, 0)], RING)  # a notch open to the outside
    assert not way_across([(3, 0), (4, 0)], RING)  # a notch open to the hole
    assert not way_across([(3, 0), (5, 0)], RING)  # the middle held between them
    assert not way_across([(3, 0), (4, 0), (0, 5)], RING)  # an outer site elsewhere


def test_a_shape_without_a_hole_has_no_way_across() -> None:
    assert not way_across([(0, 0), (1, 0), (5, 0)], FULL)
