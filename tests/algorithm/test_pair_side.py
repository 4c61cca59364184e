"""Which side of a pair a searcher takes its site on: the side it passes on, from the robot
it came from, not from whichever of the two happens to be nearest at the midpoint.

Found on ``T`` ``kill random=0.1`` seed 2: standing between two robots of a row, a
searcher's nearest robot flickered between them with every reading, so it took the
common neighbour site on the wrong side of the row (the mirror site). After a
regeneration the row was the edge of the remnant, the searchers built a mirrored lattice
on from that site, and robots of the two lattices ended up holding one tag.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.localise import came_from, find_site, window_centre
from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TS,
    NB_TX,
    NB_TY,
    R_FROM_ID,
    R_GROWTH,
    R_RECENT0,
    R_REF_ID,
    R_STATE,
    R_TAG_X,
    R_TAG_Y,
    RECENT_REFS,
    allocate,
)
from etswarm.algorithm.params import C_TICKS_FROM_RETURN, ETParams
from etswarm.algorithm.search import (
    FROM_MOVING_TICKS,
    NO_SITE,
    begin_search,
    follow_reference,
    search_rule,
    track_trend,
)
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError
from etswarm.shapes.lattice import neighbour_counts

from .find_site_args import ANYWHERE

#: Tags -3..3 in both axes for the gene grids; the memory window of held sites.
GENE_X0 = -3
WINDOW = (-2, -2)


def test_a_reference_nearest_for_a_moment_is_not_where_the_robot_came_from() -> None:
    ri, nb, nb_dist = allocate(1)
    nb[0, 0, NB_ID] = 7
    nb[0, 1, NB_ID] = 8

    def steer_by(slot: int, moving: bool) -> None:  # as search_rule does every tick
        follow_reference(0, ri, nb, slot, moving, 0)
        track_trend(0, ri, nb, nb_dist, slot, R_REF_ID)

    for _ in range(FROM_MOVING_TICKS):
        steer_by(0, True)  # passing robot 7
    assert ri[0, R_FROM_ID] == -1
    for _ in range(5):  # at the midpoint of 7 and 8 the nearest flickers
        steer_by(1, True)
        steer_by(0, True)
    steer_by(1, False)
    assert ri[0, R_FROM_ID] == 7
    # Standing still by 8 (settling, yielding) does not make 8 a robot it came from.
    for _ in range(3 * FROM_MOVING_TICKS):
        steer_by(1, False)
    steer_by(0, False)
    assert ri[0, R_FROM_ID] == 7
    assert came_from(7, 7, 7, 8) == 7
    assert came_from(8, 7, 7, 8) == 7  # 8 is nearest now, but it came from 7
    assert came_from(8, 5, 7, 8) == 8  # it came from elsewhere: 8 was passed first
    assert came_from(5, 7, 7, 8) == -1  # it steers by neither


@pytest.mark.parametrize("return_s", [0.0, ETParams().from_return_s])
def test_flipping_back_to_the_robot_it_came_from_keeps_it(return_s: float) -> None:
    # Passing 7, then steering by 8 for a few seconds as it closes in on the pair's
    # midpoint, where it stops and 7 is nearest again.
    ci, _ = ETParams(from_return_s=return_s).pack(31, gene_x0=0, gene_y0=0)
    return_ticks = int(ci[C_TICKS_FROM_RETURN])
    ri, nb, nb_dist = allocate(1)
    nb[0, 0, NB_ID] = 7
    nb[0, 1, NB_ID] = 8

    def steer_by(slot: int, ticks: int, moving: bool = True) -> None:
        for _ in range(ticks):
            follow_reference(0, ri, nb, slot, moving, return_ticks)
            track_trend(0, ri, nb, nb_dist, slot, R_REF_ID)

    steer_by(0, FROM_MOVING_TICKS)
    steer_by(1, 2 * FROM_MOVING_TICKS)
    assert ri[0, R_FROM_ID] == 7
    steer_by(0, 1, moving=False)
    # off, 8 became the robot it came from: the mirror of the pair's side
    assert ri[0, R_FROM_ID] == (8 if return_s == 0 else 7)
    if return_s > 0:
        assert return_ticks > 2 * FROM_MOVING_TICKS
        # Round a tip robot 8 and back to 7 on the other side: 8 is where it came from.
        steer_by(1, return_ticks)
        steer_by(0, 1)
        assert ri[0, R_FROM_ID] == 8


def pair_world():  # type: ignore[no-untyped-def]
    """A searcher (robot 0) by the pair A = robot 1 on (0, 0) and B = robot 2 on (1, 0),
    both Active; the gene holds them and both their common neighbour sites, (1, 1) on one
    side of the pair and (0, -1) on the other, and nothing else."""
    cells = np.array([(0, 0), (1, 0), (1, 1), (0, -1)], dtype=np.int64)
    gene_flag = np.zeros((7, 7), dtype=np.uint8)
    gene_nn = np.zeros((7, 7), dtype=np.int8)
    gene_flag[cells[:, 0] - GENE_X0, cells[:, 1] - GENE_X0] = 1
    gene_nn[cells[:, 0] - GENE_X0, cells[:, 1] - GENE_X0] = neighbour_counts(cells)
    ci, cf = ETParams().pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    ri, nb, nb_dist = allocate(1)
    for slot, (rid, (x, y)) in enumerate([(1, (0, 0)), (2, (1, 0))]):
        nb[0, slot, NB_ID] = rid
        nb[0, slot, NB_STATE] = State.ACTIVE
        nb[0, slot, NB_TX] = x
        nb[0, slot, NB_TY] = y
        nb[0, slot, NB_TS] = 1
    held = np.zeros((1, 5, 5), dtype=np.uint8)
    return ri, nb, nb_dist, gene_flag, gene_nn, ci, cf, held


def test_the_site_is_on_the_side_of_the_robot_it_came_from() -> None:
    _, nb, nb_dist, gene_flag, _, ci, cf, held = pair_world()
    nb[0, :2, NB_LAST] = 10
    nb_dist[0, :2] = (40.0, 40.6)
    memory = (held[0], *WINDOW)
    gene_flag = gene_flag.astype(np.int64)  # as test_search_rules: one compilation for both
    # Nearest is A (robot 1); it came from B (robot 2): on the left of B->A, (0, -1).
    found, x, y, _ = find_site(0, 10, 0, True, 1, 2, 0, nb, nb_dist, gene_flag, ci, cf, 1.0, 3,
                               *memory, window_centre(cf, 0), 1.0, NO_SITE, NO_SITE, *ANYWHERE)
    assert (found, x, y) == (True, 0, -1)
    # It came from A, or from elsewhere with A passed first: on the left of A->B, (1, 1).
    for came in (1, 5, -1):
        found, x, y, _ = find_site(0, 10, 0, True, 1, came, 0, nb, nb_dist, gene_flag, ci, cf,
                                   1.0, 3, *memory, window_centre(cf, 0), 1.0, NO_SITE,
                                   NO_SITE, *ANYWHERE)
        assert (found, x, y) == (True, 1, 1)


@pytest.mark.slow
def test_a_searcher_takes_the_site_on_the_side_it_passes_on() -> None:
    # The whole search rule, tick by tick (compiling it takes most of a minute).
    ri, nb, nb_dist, gene_flag, gene_nn, ci, cf, held = pair_world()
    motor = np.zeros(1, dtype=np.int64)
    begin_search(0, 0, ri)

    def tick_with(t: int, dist_a: float, dist_b: float) -> None:
        nb[0, 0, NB_LAST] = t
        nb[0, 1, NB_LAST] = t
        nb_dist[0, 0] = dist_a
        nb_dist[0, 1] = dist_b
        search_rule(
            0, t, True, ri, nb, nb_dist, motor, gene_flag, gene_nn, ci, cf, held, *WINDOW
        )

    # It orbits clockwise round B (42 mm) with A out of the pair window (66 mm) ...
    t = 1
    while t < 300:
        tick_with(t, 66.0, 42.0)
        t += 1
    assert ri[0, R_REF_ID] == 2 and ri[0, R_STATE] == State.SEARCH
    # ... towards A, until it stands midway, where A reads a little nearer than B. Coming
    # from B to A clockwise it is on the left of B->A, the side of (0, -1).
    while t < 600 and ri[0, R_STATE] == State.SEARCH:
        tick_with(t, 40.0, 40.6)
        t += 1
    assert ri[0, R_REF_ID] == 1 and ri[0, R_FROM_ID] == 2
    assert ri[0, R_STATE] == State.INACTIVE
    assert (ri[0, R_TAG_X], ri[0, R_TAG_Y]) == (0, -1)


@pytest.mark.parametrize("mode", ["off", "on", "regrowth"])
@pytest.mark.parametrize("regrowth", [False, True])
def test_the_robot_met_first_of_a_pair_is_the_one_passed_first(mode: str, regrowth: bool) -> None:
    # Steering by A (robot 1) now, it came from robot 5, outside the pair; B (robot 2) was
    # its reference for a moment before A. Going clockwise from B to A it stands on the
    # left of B->A, (0, -1); taking A for the one it passed first puts it on (1, 1).
    _, nb, nb_dist, gene_flag, _, _, cf, held = pair_world()
    ci, _ = ETParams(came_order=mode).pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    nb[0, :2, NB_LAST] = 10
    nb_dist[0, :2] = (40.0, 40.6)
    ri, reach = ANYWHERE
    ri = ri.copy()
    ri[0, R_RECENT0 : R_RECENT0 + RECENT_REFS] = (1, 2, 5, -1)
    ri[0, R_GROWTH] = 1 if regrowth else 0
    memory = (held[0], *WINDOW)
    found, x, y, _ = find_site(0, 10, 0, True, 1, 5, 0, nb, nb_dist, gene_flag.astype(np.int64),
                               ci, cf, 1.0, 3, *memory, window_centre(cf, 0), 1.0, NO_SITE,
                               NO_SITE, ri, reach)
    by_order = mode == "on" or (mode == "regrowth" and regrowth)
    assert (found, x, y) == ((True, 0, -1) if by_order else (True, 1, 1))
    # With only A in its list (B never its reference) the order says nothing: A it is.
    ri[0, R_RECENT0 : R_RECENT0 + RECENT_REFS] = (1, 5, -1, -1)
    found, x, y, _ = find_site(0, 10, 0, True, 1, 5, 0, nb, nb_dist, gene_flag.astype(np.int64),
                               ci, cf, 1.0, 3, *memory, window_centre(cf, 0), 1.0, NO_SITE,
                               NO_SITE, ri, reach)
    assert (found, x, y) == (True, 1, 1)


def test_came_order_must_be_a_mode() -> None:
    with pytest.raises(EtswarmError, match="came_order must be one of"):
        ETParams(came_order="maybe")
