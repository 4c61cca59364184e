"""A third robot tells a pair's site from its mirror only when it fits one clearly better
(``ETParams.mirror_margin_mm``)."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.localise import find_site, window_centre
from etswarm.algorithm.memory import NB_ID, NB_LAST, NB_STATE, NB_TS, NB_TX, NB_TY
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.search import NO_SITE
from etswarm.algorithm.states import State

from .find_site_args import ANYWHERE
from .test_pair_side import GENE_X0, WINDOW, pair_world

#: The pair's robots A and B steer no side here: the searcher steers by neither.
NEITHER = 5


def site_with_third(tag: tuple[int, int], reading: float, margin: float, widen: float):  # type: ignore[no-untyped-def]
    """find_site for a searcher midway between the pair of ``pair_world`` that also reads
    a third placed robot on ``tag`` at ``reading`` mm; ``widen``: its tolerance scale."""
    _, nb, nb_dist, gene_flag, _, _, _, held = pair_world()
    gene_flag[tag[0] - GENE_X0, tag[1] - GENE_X0] = 1  # the third robot is of the shape
    ci, cf = ETParams(mirror_margin_mm=margin).pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    nb[0, 2, NB_ID] = 3
    nb[0, 2, NB_STATE] = State.STABLE
    nb[0, 2, NB_TX], nb[0, 2, NB_TY] = tag
    nb[0, 2, NB_TS] = 2
    nb[0, :3, NB_LAST] = 10
    nb_dist[0, :3] = (40.0, 40.6, reading)
    found, x, y, _ = find_site(
        0, 10, 0, True, NEITHER, -1, 0, nb, nb_dist, gene_flag.astype(np.int64), ci, cf,
        widen, 0, held[0], *WINDOW, window_centre(cf, 0), 1.0, NO_SITE, NO_SITE, *ANYWHERE,
    )
    return found, (x, y)


@pytest.mark.parametrize("margin", [0.0, ETParams().mirror_margin_mm])
def test_a_robot_next_to_one_site_and_far_from_the_other_tells_them_apart(
    margin: float,
) -> None:
    # (2, 1) is next to (1, 1) and two steps from the mirror (0, -1): 40 mm against 80.
    assert site_with_third((2, 1), 41.0, margin, 1.0) == (True, (1, 1))


def test_a_robot_equally_far_from_both_sites_tells_nothing() -> None:
    # (2, 0) is sqrt(3) d = 69.3 mm from both (1, 1) and (0, -1). Read at 52 mm, it is
    # off both by 17 mm: past the plain consistency tolerance (16), within a widened one.
    assert site_with_third((2, 0), 52.0, ETParams().mirror_margin_mm, 1.5) == (False, (0, 0))
    # Before, being off the mirror by more than the tolerance ruled the mirror out, so
    # whichever site came first was taken.
    found, _ = site_with_third((2, 0), 52.0, 0.0, 1.5)
    assert found
