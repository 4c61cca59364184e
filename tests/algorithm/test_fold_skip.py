"""After damage, a placed robot that the lattice puts out of radio range of a pair's
candidate site, and whose reading does not fit the pair's other site either, is left out of
the candidate's consistency check (``ETParams.regrowth_fold_skip_mm``): only a folded
lattice brings it in range."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.localise import find_site, window_centre
from etswarm.algorithm.memory import NB_ID, NB_LAST, NB_STATE, NB_TS, NB_TX, NB_TY, R_GROWTH
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import RunConfig
from etswarm.algorithm.search import NO_SITE
from etswarm.algorithm.states import State

from .find_site_args import ANYWHERE
from .remnant_rows import remnant_rows
from .test_pair_side import GENE_X0, WINDOW, pair_world

#: The searcher steers by neither robot of the pair, so no side rule picks the site.
NEITHER = 5


def site_with(  # type: ignore[no-untyped-def]
    others: list[tuple[tuple[int, int], float]], fold_skip: float, regrowth: bool = True
):
    """find_site for a searcher midway between the pair of ``pair_world`` (A on (0, 0) and
    B on (1, 0), read at 40 and 40.6 mm) that also reads a Stable robot on each tag of
    ``others`` at the given distance (mm); ``regrowth``: it works for a regenerated target
    (else the first formation)."""
    _, nb, nb_dist, gene_flag, _, _, _, held = pair_world()
    ci, cf = ETParams(regrowth_fold_skip_mm=fold_skip).pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    ri = ANYWHERE[0].copy()
    ri[0, R_GROWTH] = 1 if regrowth else 0
    for slot, (tag, reading) in enumerate(others, start=2):
        gene_flag[tag[0] - GENE_X0, tag[1] - GENE_X0] = 1
        nb[0, slot, NB_ID] = slot + 1
        nb[0, slot, NB_STATE] = State.STABLE
        nb[0, slot, NB_TX], nb[0, slot, NB_TY] = tag
        nb[0, slot, NB_TS] = 2
        nb_dist[0, slot] = reading
    nb[0, : 2 + len(others), NB_LAST] = 10
    nb_dist[0, :2] = (40.0, 40.6)
    found, x, y, _ = find_site(
        0, 10, 0, True, NEITHER, -1, 0, nb, nb_dist, gene_flag.astype(np.int64), ci, cf,
        1.0, 0, held[0], *WINDOW, window_centre(cf, 0), 1.0, NO_SITE, NO_SITE, ri, ANYWHERE[1],
    )
    return found, (x, y)


#: The mirror (0, -1) of the site (1, 1) is held, by a robot read where (1, 1) predicts
#: (sqrt(3) d = 69.3 mm).
MIRROR_HELD = ((0, -1), 69.0)


def test_a_robot_heard_only_where_the_lattice_folds_is_left_out() -> None:
    # (-2, 1) is 3 d = 120 mm from (1, 1) and 139 mm from (0, -1): out of range of both
    # on the lattice. Read at 56 mm, as on H split x=mid seed 106, it vetoed the site.
    folded = ((-2, 1), 56.0)
    assert site_with([MIRROR_HELD, folded], 0.0) == (False, (0, 0))
    assert site_with([MIRROR_HELD, folded], ETParams().regrowth_fold_skip_mm) == (True, (1, 1))
    # In the first formation every robot heard is still checked.
    first = site_with([MIRROR_HELD, folded], ETParams().regrowth_fold_skip_mm, regrowth=False)
    assert first == (False, (0, 0))
    # Without it the site is taken either way.
    assert site_with([MIRROR_HELD], 0.0) == (True, (1, 1))


@pytest.mark.parametrize("fold_skip", [0.0, ETParams().regrowth_fold_skip_mm])
def test_a_robot_far_from_one_site_but_next_to_the_other_still_counts(
    fold_skip: float,
) -> None:
    # (-1, -2) is next to the mirror (0, -1) and 106 mm from (1, 1). Read at 42 mm it
    # fits the mirror: the searcher stands there and takes it, never (1, 1).
    assert site_with([((-1, -2), 42.0)], fold_skip) == (True, (0, -1))


def test_a_robot_in_range_of_the_site_still_vetoes_it() -> None:
    # (3, 1) is 2 d = 80 mm from (1, 1), under the 100 mm bound: read at 40 mm it is off
    # by 40 and the site is refused, as before.
    near = ((3, 1), 40.0)
    assert site_with([MIRROR_HELD, near], ETParams().regrowth_fold_skip_mm) == (False, (0, 0))


def h_split_x_106(**et: object) -> list[tuple[int, int | None, int, bool]]:
    """``H`` ``split x=mid`` seed 106 (formed at 4180 s), 2 h from the damage: its
    remnants as (robots, census count, target cells, formed)."""
    return remnant_rows(RunConfig(shape="H", seed=106, damage=("split x=mid",),
                                  max_time_s=4180 + 2 * 3600, et=ETParams(**et)))


@pytest.mark.slow
def test_the_scaled_h_reforms_where_its_legs_have_bent_together() -> None:
    # The right remnant's scaled H bent its two legs towards each other: its last free
    # site (2, 2) predicts 120 mm to robot (-1, 2) on the other leg, which read 56.
    assert h_split_x_106() == [(25, 25, 25, True), (25, 25, 25, True)]
    rows = h_split_x_106(regrowth_fold_skip_mm=0.0)
    assert (25, 25, 25, False) in rows
