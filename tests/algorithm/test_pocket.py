"""Pocket capture on hand-made neighbour tables: a searcher inside a stretched ring of
placed robots takes the site in the middle, and nowhere else."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.localise import find_site, window_centre
from etswarm.algorithm.memory import NB_ID, NB_LAST, NB_STATE, NB_TS, NB_TX, NB_TY, allocate
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.pocket import LOCATED_TOL_MM, located_score, pocket_site
from etswarm.algorithm.search import NO_SITE
from etswarm.algorithm.states import State

from .find_site_args import ANYWHERE

TICK = 100
ORIGIN = -5  # memory window: tags -5..5
SIZE = 11


def pocket_world(readings: dict[tuple[int, int], float], active: tuple[int, int] = (1, 1)):  # type: ignore[no-untyped-def]
    """Robot 0 hears, this tick, a placed robot on each tag of ``readings`` at that
    distance (mm); the one on ``active`` is Active with TS 5, the others Stable. Every
    site of tags -4..4 is in the shape; nothing is remembered held."""
    gene = np.ones((9, 9), dtype=np.uint8)
    ci, cf = ETParams().pack(31, gene_x0=-4, gene_y0=-4)
    _, nb, nb_dist = allocate(1)
    for slot, ((x, y), dist) in enumerate(readings.items()):
        nb[0, slot, NB_ID] = slot + 1
        nb[0, slot, NB_STATE] = State.ACTIVE if (x, y) == active else State.STABLE
        nb[0, slot, NB_TX] = x
        nb[0, slot, NB_TY] = y
        nb[0, slot, NB_TS] = 5
        nb[0, slot, NB_LAST] = TICK
        nb_dist[0, slot] = dist
    held = np.zeros((SIZE, SIZE), dtype=np.uint8)
    return gene, ci, cf, nb, nb_dist, held


def test_a_searcher_inside_a_stretched_ring_takes_its_middle() -> None:
    # The four robots round (0, 0) stand 55-62 mm from the searcher: no two at d = 40, so
    # the paper's localisation finds nothing, but the pocket does.
    ring = {(0, 1): 55.0, (1, 1): 60.0, (1, 0): 58.0, (0, -1): 62.0}
    gene, ci, cf, nb, nb_dist, held = pocket_world(ring)
    found, *_ = find_site(0, TICK, TICK - 10, False, -1, -1, 0, nb, nb_dist, gene, ci, cf, 3.0, 3,
                          held, ORIGIN, ORIGIN, window_centre(cf, 0), 1.0, NO_SITE, NO_SITE,
                          *ANYWHERE)
    assert not found
    found, x, y, ts = pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                                  ORIGIN)
    assert (found, x, y, ts) == (True, 0, 0, 5)


def test_no_pocket_when_part_of_the_ring_is_far_or_unheard() -> None:
    ring = {(0, 1): 55.0, (1, 1): 60.0, (1, 0): 58.0, (0, -1): 62.0}
    # One neighbour farther than the reach: the searcher is outside the ring.
    gene, ci, cf, nb, nb_dist, held = pocket_world({**ring, (0, -1): 80.0})
    assert not pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                           ORIGIN)[0]
    # A neighbour heard before but not since ``since``.
    gene, ci, cf, nb, nb_dist, held = pocket_world(ring)
    nb[0, 3, NB_LAST] = TICK - 20
    assert not pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                           ORIGIN)[0]
    # (-1, 0) is remembered held but not heard now: its holder stands elsewhere.
    gene, ci, cf, nb, nb_dist, held = pocket_world(ring)
    held[-1 - ORIGIN, 0 - ORIGIN] = 1
    assert not pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                           ORIGIN)[0]
    # Only two neighbours: an edge, not a pocket.
    gene, ci, cf, nb, nb_dist, held = pocket_world({(0, 1): 55.0, (1, 1): 60.0})
    assert not pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                           ORIGIN)[0]


def test_between_two_equally_likely_pockets_it_moves_on() -> None:
    # (0, 0) and (1, 2) both have three neighbours heard, farthest at 66 mm, and the
    # robots two steps from each are not nearer than that site predicts: a tie.
    readings = {(0, 1): 50.0, (1, 1): 50.0, (1, 0): 66.0, (2, 2): 66.0}
    gene, ci, cf, nb, nb_dist, held = pocket_world(readings)
    assert not pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                           ORIGIN)[0]
    # Nearer to (2, 2) than (0, 0) allows (80 mm predicted): only (1, 2) remains.
    gene, ci, cf, nb, nb_dist, held = pocket_world({**readings, (2, 2): 60.0})
    found, x, y, _ = pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                                 ORIGIN)
    assert (found, x, y) == (True, 1, 2)


def test_without_an_active_neighbour_the_site_waits() -> None:
    ring = {(0, 1): 55.0, (1, 1): 60.0, (1, 0): 58.0, (0, -1): 62.0}
    gene, ci, cf, nb, nb_dist, held = pocket_world(ring, active=(3, 3))
    assert not pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                           ORIGIN)[0]


def located_world(readings: dict[tuple[int, int], float]):  # type: ignore[no-untyped-def]
    """``pocket_world`` with ``pocket = "located"``."""
    gene, _, cf, nb, nb_dist, held = pocket_world(readings)
    ci, cf = ETParams(pocket="located").pack(31, gene_x0=-4, gene_y0=-4)
    return gene, ci, cf, nb, nb_dist, held


def test_a_located_searcher_takes_the_site_its_fix_lands_on() -> None:
    # All six robots round (0, 0) read 52 mm: the lattice has stretched evenly round the
    # searcher, whose least-squares fix is the site's centre (each reading 12 mm out).
    ring = {(1, 0): 52.0, (1, 1): 52.0, (0, 1): 52.0, (-1, 0): 52.0, (-1, -1): 52.0,
            (0, -1): 52.0}
    gene, ci, cf, nb, nb_dist, held = located_world(ring)
    assert located_score(0, 0, 0, TICK - 10, nb, nb_dist, cf, held, ORIGIN, ORIGIN) < 0.5
    found, x, y, ts = pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                                  ORIGIN)
    assert (found, x, y, ts) == (True, 0, 0, 5)


def test_a_located_searcher_off_the_centre_moves_on() -> None:
    # Readings of a robot 20 mm from (0, 0)'s centre towards (1, 0) (gene frame x): its
    # fix lands there, beyond the tolerance, so it takes no site.
    ring = {(1, 0): 20.0 + 12.0, (1, 1): 34.6 + 12.0, (0, 1): 52.9 + 12.0,
            (-1, 0): 60.0 + 12.0, (0, -1): 34.6 + 12.0}
    gene, ci, cf, nb, nb_dist, held = located_world(ring)
    score = located_score(0, 0, 0, TICK - 10, nb, nb_dist, cf, held, ORIGIN, ORIGIN)
    assert LOCATED_TOL_MM < score < 1e9
    assert not pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                           ORIGIN)[0]


def test_a_located_fix_that_leaves_a_reading_far_out_is_refused() -> None:
    # Five robots fit the centre within 12 mm, but the sixth reads 30 mm more than the
    # others: no point agrees with all of them.
    ring = {(1, 0): 52.0, (1, 1): 52.0, (0, 1): 52.0, (-1, 0): 52.0, (-1, -1): 52.0,
            (0, -1): 74.0}
    gene, ci, cf, nb, nb_dist, held = located_world(ring)
    assert located_score(0, 0, 0, TICK - 10, nb, nb_dist, cf, held, ORIGIN, ORIGIN) >= 1e9
    assert not pocket_site(0, TICK, TICK - 10, nb, nb_dist, gene, ci, cf, held, ORIGIN,
                           ORIGIN)[0]
