"""Searchers shut in a shape's hole: counted per remnant and named in the text summary."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.kernel_util import hex_distance
from etswarm.cli.run_outputs import missing_lines
from etswarm.measures.formation import shut_in_holes
from etswarm.shapes.lattice import tags_to_xy

D = 40.0
#: An ``O``: the sites 3 to 5 steps from (0, 0) round a hole of the sites within 2.
RING = np.array(
    [(x, y) for x in range(-5, 6) for y in range(-5, 6) if 3 <= hex_distance(x, y) <= 5],
    dtype=np.int64,
)


def swarm(searchers_at: list[tuple[int, int]], shift: tuple[float, float] = (250.0, -90.0)):  # type: ignore[no-untyped-def]
    """Robots on every ring site, turned and moved as a whole, and searchers on the
    centres of ``searchers_at``: (pos (N, 2) mm, tags (N, 2), holds (N,), searching (N,))."""
    tags = np.vstack([RING, np.array(searchers_at, dtype=np.int64).reshape(-1, 2)])
    turn = np.radians(25.0)
    rot = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
    pos = tags_to_xy(tags, D) @ rot.T + np.array(shift)
    holds = np.arange(len(tags)) < len(RING)
    return pos, tags, holds, ~holds


def test_searchers_in_the_middle_count_and_those_outside_do_not() -> None:
    pos, tags, holds, searching = swarm([(0, 0), (2, 1), (1, -1), (7, 1), (-6, -6)])
    assert shut_in_holes(pos, tags, holds, searching, RING, D) == 3
    # a few mm off a site's centre changes nothing
    jitter = np.random.default_rng(3).uniform(-6.0, 6.0, pos.shape)
    assert shut_in_holes(pos + jitter * searching[:, None], tags, holds, searching, RING, D) == 3


def test_none_without_a_hole_searchers_or_a_lattice_to_fit() -> None:
    pos, tags, holds, searching = swarm([(0, 0)])
    disc = np.array([(x, y) for x in range(-5, 6) for y in range(-5, 6)
                     if hex_distance(x, y) <= 5], dtype=np.int64)
    assert shut_in_holes(pos, tags, holds, searching, disc, D) == 0  # no hole in the target
    assert shut_in_holes(pos, tags, holds, np.zeros_like(searching), RING, D) == 0
    one = np.zeros_like(holds)
    one[0] = True
    assert shut_in_holes(pos, tags, one, searching, RING, D) == 0  # one holder fits nothing


def test_the_run_summary_says_how_many_searchers_are_in_the_hole() -> None:
    comp = {"formed": False, "too_small": False, "robots": 66, "target_cells": 66,
            "free_sites": 1, "free_tags": [[3, 3]], "searching": 2, "shut_in_holes": 1}
    assert missing_lines([comp]) == [
        "group 0: 1 target sites free: (3,3); 2 robots searching, 1 of them in the shape's hole"
    ]
    del comp["shut_in_holes"]  # a summary written before the count existed
    assert missing_lines([comp]) == ["group 0: 1 target sites free: (3,3); 2 robots searching"]


def test_the_run_summary_says_when_the_free_sites_make_a_way_across() -> None:
    comp = {"formed": False, "too_small": False, "robots": 66, "target_cells": 66,
            "free_sites": 3, "free_tags": [[3, 0], [4, 0], [5, 0]], "searching": 3,
            "shut_in_holes": 0, "way_across": True}
    assert missing_lines([comp]) == [
        "group 0: 3 target sites free: (3,0) (4,0) (5,0); 3 robots searching; the free sites"
        " make a way across the ring"
    ]
    comp["way_across"] = False
    assert missing_lines([comp]) == [
        "group 0: 3 target sites free: (3,0) (4,0) (5,0); 3 robots searching"
    ]
