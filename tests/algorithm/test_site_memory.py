"""A searcher's memory of held sites and the whole-shape hole test built on it."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.kernel_util import hex_distance
from etswarm.algorithm.memory import (
    HOLE_FLAG,
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_MASK,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_EPOCH,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.site_memory import remember_heard, shuts_in
from etswarm.algorithm.states import State

RADIUS = 5
#: Window origin and size: tags -6..6 in both axes.
ORIGIN = -RADIUS - 1
SIZE = 2 * RADIUS + 3


def hexagon_gene():  # type: ignore[no-untyped-def]
    """Gene of every site within RADIUS lattice steps of (0, 0), on a grid of tags
    -6..6, and the packed constants that index it."""
    gene = np.zeros((SIZE, SIZE), dtype=np.uint8)
    for x in range(-RADIUS, RADIUS + 1):
        for y in range(-RADIUS, RADIUS + 1):
            if hex_distance(x, y) <= RADIUS:
                gene[x - ORIGIN, y - ORIGIN] = 1
    ci, _ = ETParams().pack(31, gene_x0=ORIGIN, gene_y0=ORIGIN)
    return gene, ci


def memory_of(held: list[tuple[int, int]]) -> np.ndarray:
    """A window (SIZE, SIZE) with the given tags remembered held."""
    window = np.zeros((SIZE, SIZE), dtype=np.uint8)
    for x, y in held:
        window[x - ORIGIN, y - ORIGIN] = 1
    return window


def remembered(window: np.ndarray) -> set[tuple[int, int]]:
    """The tags a window (SIZE, SIZE) holds."""
    return {(int(x) + ORIGIN, int(y) + ORIGIN) for x, y in np.argwhere(window)}


def ring(r: int) -> list[tuple[int, int]]:
    """The sites exactly r lattice steps from (0, 0)."""
    return [(x, y) for x in range(-r, r + 1) for y in range(-r, r + 1) if hex_distance(x, y) == r]


def test_closing_a_ring_round_a_wide_free_area_is_refused() -> None:
    # Ring 4 held but for one gap; 37 free sites inside, ring 5 free outside. Taking the
    # gap would wall the inside in: its free sites are 4 steps and more from the gap,
    # beyond what a robot hears, but the memory holds the whole ring.
    gene, ci = hexagon_gene()
    gap = (4, 0)
    window = memory_of([s for s in ring(4) if s != gap])
    before = window.copy()
    assert shuts_in(gap[0], gap[1], window, ORIGIN, ORIGIN, gene, ci)
    assert np.array_equal(window, before)  # the test leaves the memory as it was
    # With a second gap the inside keeps a way out: either gap may be taken.
    window = memory_of([s for s in ring(4) if s not in (gap, (-4, 0))])
    assert not shuts_in(gap[0], gap[1], window, ORIGIN, ORIGIN, gene, ci)


def test_unknown_sites_count_as_free() -> None:
    # Half of ring 4 never heard: the robot assumes the way out is there.
    gene, ci = hexagon_gene()
    known = [s for s in ring(4) if s[0] > 0 and s != (4, 0)]
    assert not shuts_in(4, 0, memory_of(known), ORIGIN, ORIGIN, gene, ci)


def test_a_robot_inside_a_closed_hole_may_fill_it() -> None:
    # Ring 2 held all round: (0, 0) and (1, 0) are free but already shut in. Taking (1, 0)
    # leaves (0, 0) walled in too, which does no further harm.
    gene, ci = hexagon_gene()
    window = memory_of(ring(2) + [s for s in ring(1) if s != (1, 0)])
    assert not shuts_in(1, 0, window, ORIGIN, ORIGIN, gene, ci)
    # Open ring 2 at (2, 0): now (1, 0) is the way in to (0, 0) and must stay free.
    window = memory_of([s for s in ring(2) if s != (2, 0)] + [s for s in ring(1) if s != (1, 0)])
    assert shuts_in(1, 0, window, ORIGIN, ORIGIN, gene, ci)


def test_a_site_left_without_an_opening_is_refused() -> None:
    # (1, 0) free with every neighbour held but (0, 0) and (2, 0): after (0, 0) is taken
    # its one free neighbour (2, 0) is too narrow a way in, though it leads outside.
    gene, ci = hexagon_gene()
    around = [(1, 1), (2, 1), (1, -1), (0, -1)]
    assert shuts_in(0, 0, memory_of(around), ORIGIN, ORIGIN, gene, ci)
    assert not shuts_in(0, 0, memory_of(around[:2]), ORIGIN, ORIGIN, gene, ci)


def test_the_memory_keeps_what_was_heard_for_the_robots_target() -> None:
    ri, nb, _ = allocate(1)
    held = np.zeros((1, SIZE, SIZE), dtype=np.uint8)
    rows = [
        # (tag, state, mask, epoch, tick heard)
        ((2, 3), State.STABLE, 0b000001, 0, 50),  # reports (2, 4) held (direction 0)
        ((-1, -1), State.ACTIVE, 0, 0, 49),  # heard earlier: remembered then, not now
        ((0, 3), State.STABLE, 0, 1, 50),  # works for another target: not its sites
        ((3, 3), State.SEARCH, 0, 0, 50),  # holds no site
    ]
    for slot, ((x, y), state, mask, epoch, tick) in enumerate(rows):
        nb[0, slot, NB_ID] = slot + 1
        nb[0, slot, NB_STATE] = state
        nb[0, slot, NB_TX] = x
        nb[0, slot, NB_TY] = y
        nb[0, slot, NB_MASK] = mask
        nb[0, slot, NB_EPOCH] = epoch
        nb[0, slot, NB_LAST] = tick
    remember_heard(0, 50, ri, nb, held, ORIGIN, ORIGIN)
    assert remembered(held[0]) == {(2, 3), (2, 4)}
    # Later ticks add to it; a new target epoch starts it afresh.
    remember_heard(0, 49, ri, nb, held, ORIGIN, ORIGIN)
    assert held[0, -1 - ORIGIN, -1 - ORIGIN] == 1 and held[0, 2 - ORIGIN, 3 - ORIGIN] == 1
    ri[0, R_EPOCH] = 1
    remember_heard(0, 50, ri, nb, held, ORIGIN, ORIGIN)
    assert remembered(held[0]) == {(0, 3)}


def ring_gene():  # type: ignore[no-untyped-def]
    """Gene of an ``O``: the sites 3 to 5 steps from (0, 0) (flag 1) round a hole of the
    sites within 2 steps (``HOLE_FLAG``), on the hexagon's grid."""
    gene, ci = hexagon_gene()
    for x in range(-2, 3):
        for y in range(-2, 3):
            if hex_distance(x, y) <= 2:
                gene[x - ORIGIN, y - ORIGIN] = HOLE_FLAG
    return gene, ci


def test_closing_the_ring_round_a_hole_with_a_free_edge_site_is_refused() -> None:
    # The ring held but for (3, 1) on the hole's edge, (4, 1), (5, 1) and (5, 2) outside
    # it, and (-3, -1) on the hole's edge across it. Taking (4, 1) walls (3, 1) and the
    # hole off from the outside: (-3, -1) could then be reached only through the hole,
    # and the hole only through (3, 1).
    gene, ci = ring_gene()
    shape_sites = [s for r in (3, 4, 5) for s in ring(r)]
    free = [(3, 1), (4, 1), (5, 1), (5, 2), (-3, -1)]
    window = memory_of([s for s in shape_sites if s not in free])
    assert shuts_in(4, 1, window, ORIGIN, ORIGIN, gene, ci)
    # With the hole counted as the outside (no flag), the same capture would pass.
    plain = np.where(gene == HOLE_FLAG, 0, gene).astype(np.uint8)
    assert not shuts_in(4, 1, window, ORIGIN, ORIGIN, plain, ci)
    # Once the hole's edge is held all round but for (3, 1), taking (3, 1) closes the
    # hole with nothing left to fill inside it; (4, 1) still may not be taken first.
    window = memory_of([s for s in shape_sites if s not in free[:4]])
    assert not shuts_in(3, 1, window, ORIGIN, ORIGIN, gene, ci)
    assert shuts_in(4, 1, window, ORIGIN, ORIGIN, gene, ci)


def test_a_site_on_the_holes_edge_is_open_from_the_hole_side_too() -> None:
    # Traced on O seed 4: free (3, 1) and (3, 0) on the hole's edge, (4, 0) and (5, 1)
    # beyond, (5, 0) outside the shape. Taking (3, 1) leaves (3, 0) free neighbours only
    # on opposite sides, (4, 0) and the hole; a site elsewhere would count as too narrow
    # to enter, but robots reach this one from the hole as well, and pass through it.
    gene, ci = ring_gene()
    gene[5 - ORIGIN, 0 - ORIGIN] = 0
    free = [(3, 1), (3, 0), (4, 0), (5, 1)]
    shape_sites = [s for r in (3, 4, 5) for s in ring(r) if s != (5, 0)]
    window = memory_of([s for s in shape_sites if s not in free])
    assert not shuts_in(3, 1, window, ORIGIN, ORIGIN, gene, ci)
    # Taking (4, 0) still walls the hole off with (3, 1) and (3, 0) free on its edge.
    assert shuts_in(4, 0, window, ORIGIN, ORIGIN, gene, ci)


def test_a_ways_hole_end_may_be_taken_leaving_a_notch_two_deep() -> None:
    # The ring held but for a way across it: (3, 1) on the hole's edge, (4, 1) in the
    # middle and (5, 1) beside the outside. Each capture narrows or cuts off another,
    # so the one-step test refuses all three. With ``way_end`` the hole's end may go: it
    # leaves (4, 1) and (5, 1) a notch two deep, which a searcher enters from outside.
    gene, _ = ring_gene()
    way = [(3, 1), (4, 1), (5, 1)]
    shape_sites = [s for r in (3, 4, 5) for s in ring(r)]
    window = memory_of([s for s in shape_sites if s not in way])
    plain_ci, _ = ETParams(way_end="off").pack(31, gene_x0=ORIGIN, gene_y0=ORIGIN)
    way_ci, _ = ETParams().pack(31, gene_x0=ORIGIN, gene_y0=ORIGIN)
    for x, y in way:
        assert shuts_in(x, y, window, ORIGIN, ORIGIN, gene, plain_ci)
    assert not shuts_in(3, 1, window, ORIGIN, ORIGIN, gene, way_ci)
    assert shuts_in(4, 1, window, ORIGIN, ORIGIN, gene, way_ci)
    assert shuts_in(5, 1, window, ORIGIN, ORIGIN, gene, way_ci)
    # Then the notch fills from its end: (4, 1) leaves (5, 1) open to the outside.
    window[3 - ORIGIN, 1 - ORIGIN] = 1
    assert not shuts_in(4, 1, window, ORIGIN, ORIGIN, gene, way_ci)
    assert shuts_in(5, 1, window, ORIGIN, ORIGIN, gene, way_ci)


def test_only_a_site_on_a_holes_edge_may_leave_a_notch_two_deep() -> None:
    # The same three sites as a notch three deep into a shape with no hole: its end,
    # (3, 1), would leave (4, 1) with one free neighbour, which ``way_end`` does not
    # allow away from a hole.
    gene, _ = hexagon_gene()
    notch = [(3, 1), (4, 1), (5, 1)]
    window = memory_of(
        [(x, y) for x in range(-5, 6) for y in range(-5, 6)
         if hex_distance(x, y) <= RADIUS and (x, y) not in notch]
    )
    way_ci, _ = ETParams().pack(31, gene_x0=ORIGIN, gene_y0=ORIGIN)
    assert shuts_in(3, 1, window, ORIGIN, ORIGIN, gene, way_ci)


def test_a_way_with_two_sites_on_the_holes_edge_shortens_from_one_of_them() -> None:
    # Free: (3, 1) and (3, 2) on the hole's edge, (4, 2) between them and (5, 3) beside
    # the outside. Taking (3, 1) leaves (4, 2) free neighbours on opposite sides, (3, 2)
    # and (5, 3); with ``way_end`` that is allowed, since (4, 2) stays on a way across
    # (``way_corridor``), the three-site way the notch rule then closes.
    gene, _ = ring_gene()
    way = [(3, 1), (3, 2), (4, 2), (5, 3)]
    shape_sites = [s for r in (3, 4, 5) for s in ring(r)]
    window = memory_of([s for s in shape_sites if s not in way])
    plain_ci, _ = ETParams(way_end="off").pack(31, gene_x0=ORIGIN, gene_y0=ORIGIN)
    way_ci, _ = ETParams().pack(31, gene_x0=ORIGIN, gene_y0=ORIGIN)
    assert all(shuts_in(x, y, window, ORIGIN, ORIGIN, gene, plain_ci) for x, y in way)
    assert [s for s in way if not shuts_in(*s, window, ORIGIN, ORIGIN, gene, way_ci)] == [
        (3, 1), (3, 2)
    ]
    window[3 - ORIGIN, 1 - ORIGIN] = 1
    assert not shuts_in(3, 2, window, ORIGIN, ORIGIN, gene, way_ci)
