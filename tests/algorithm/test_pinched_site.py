"""A site whose mouth the lattice has pinched: the searcher stops at the mouth, farther
from the robot inside than the site is, and only a widened pocket candidate may take it."""

from __future__ import annotations

import numpy as np

from etswarm.algorithm.localise import find_site, window_centre
from etswarm.algorithm.memory import (
    NB_ID,
    NB_LAST,
    NB_MASK,
    NB_STATE,
    NB_TS,
    NB_TX,
    NB_TY,
    allocate,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.search import NO_SITE
from etswarm.algorithm.states import State

from .find_site_args import ANYWHERE

#: An empty memory of held sites (window, origin) for ``find_site``: nothing remembered.
NO_MEMORY = (np.zeros((9, 9), dtype=np.uint8), -4, -4)


def pinched_table(inner_mm: float, widen_max: float):  # type: ignore[no-untyped-def]
    """Robot 0 hears Active A on (0, 0) and Stable B on (1, 2), both at 38 mm (the second
    ring: the free site (0, 1) lies between them), and Stable C on (1, 1), the site's third
    neighbour, at ``inner_mm`` (40 mm on an exact lattice)."""
    gene = np.ones((7, 7), dtype=np.int64)  # tags -3..3: every site in the shape
    params = ETParams(consistency_widen_max=widen_max)
    ci, cf = params.pack(31, gene_x0=-3, gene_y0=-3)
    _, nb, nb_dist = allocate(1)
    robots = [((0, 0), State.ACTIVE, 38.0), ((1, 2), State.STABLE, 38.0)]
    robots.append(((1, 1), State.STABLE, inner_mm))
    for slot, ((x, y), state, dist) in enumerate(robots):
        nb[0, slot, NB_ID] = slot + 1
        nb[0, slot, NB_STATE] = state
        nb[0, slot, NB_TX] = x
        nb[0, slot, NB_TY] = y
        nb[0, slot, NB_MASK] = 0
        nb[0, slot, NB_TS] = 1
        nb[0, slot, NB_LAST] = 10
        nb_dist[0, slot] = dist
    return gene, ci, cf, nb, nb_dist


def search_at(inner_mm: float, widen_max: float, tol_scale: float, wide_min: int):  # type: ignore[no-untyped-def]
    gene, ci, cf, nb, nb_dist = pinched_table(inner_mm, widen_max)
    found, x, y, _ = find_site(
        0, 10, 0, True, -1, -1, 0, nb, nb_dist, gene, ci, cf, tol_scale, wide_min,
        *NO_MEMORY, window_centre(cf, 0), 1.0, NO_SITE, NO_SITE, *ANYWHERE,
    )
    return found, (x, y)


def test_a_site_is_taken_when_every_neighbour_agrees() -> None:
    assert search_at(41.0, 1.0, 1.0, 3) == (True, (0, 1))


def test_a_pinched_site_needs_a_widened_pocket_candidate() -> None:
    # 58 mm from C where 40 is predicted: 18 mm off, beyond the plain 16 mm tolerance.
    assert not search_at(58.0, 1.0, 3.0, 3)[0]  # widening off
    assert not search_at(58.0, 2.0, 1.0, 3)[0]  # not yet widened: new at the shape
    assert search_at(58.0, 2.0, 1.5, 3) == (True, (0, 1))  # 16 * 1.5 = 24 mm
    # With fewer heard neighbours of the site than a pocket needs, the plain tolerance.
    assert not search_at(58.0, 2.0, 3.0, 4)[0]
    # However wide the tolerance, a neighbour site's robot must stay well within radio
    # range (d + 20 mm): one heard only now and then would send the robot to Danger.
    assert search_at(59.0, 3.0, 3.0, 3)[0]
    assert not search_at(62.0, 3.0, 3.0, 3)[0]
