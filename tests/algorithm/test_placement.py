"""Where a Leader puts the scaled shape: always on a seed triangle of held sites."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.placement import RemnantView, choose_translation, triangles_at

#: A bar of 3 x 2 cells (tags).
BAR = np.array([[0, 0], [1, 0], [2, 0], [0, 1], [1, 1], [2, 1]])


def always_fits(_cells: np.ndarray) -> bool:
    return True


def view(known: set, remnant: set) -> RemnantView:
    """What a Leader knows with no silent sites and no extent."""
    return RemnantView(known, remnant, set(), set(), None, always_fits)


def sites_after(shift: tuple[int, int]) -> set[tuple[int, int]]:
    return {(int(x) + shift[0], int(y) + shift[1]) for x, y in BAR}


def test_triangles_at_a_site_are_it_and_two_adjacent_held_neighbours() -> None:
    held = {(0, 0), (1, 0), (1, 1), (5, 5)}
    assert len(triangles_at((0, 0), held)) == 1
    assert triangles_at((5, 5), held) == []
    assert triangles_at((9, 9), held) == []  # not held itself


def test_the_leader_seeds_with_two_of_its_neighbours() -> None:
    leader = (10, 10)
    known = {(11, 10), (11, 11), (30, 30)}
    shift = choose_translation(BAR, leader, view(known, set()))
    sites = sites_after(shift)
    assert {leader, (11, 10), (11, 11)} <= sites


def test_a_leader_without_two_adjacent_neighbours_seeds_from_a_remembered_triangle() -> None:
    """Dead robots round the Leader: it hears one neighbour. The remnant it remembers
    holds a triangle a few sites away; the new shape goes there (the Leader may be left
    out), not round the Leader with one seed."""
    leader = (0, 0)
    known = {(1, 0)}
    remnant = {(5, 0), (6, 0), (6, 1), (7, 1)}
    shift = choose_translation(BAR, leader, view(known, remnant))
    sites = sites_after(shift)
    held = known | remnant | {leader}
    assert any(all(c in sites for c in tri) for tag in held for tri in triangles_at(tag, held))
    # with no triangle anywhere it still places the shape round the Leader
    alone = choose_translation(BAR, leader, view(known, set()))
    assert leader in sites_after(alone)
