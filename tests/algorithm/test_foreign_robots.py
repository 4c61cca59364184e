"""Searchers and placed robots of another remnant's shape (``ETParams.foreign_robots``).

A split can leave remnants side by side: the bottom half of an `H` cut through the middle
is its two legs, each a remnant of its own within a few lattice steps of the other. Both
regrow a scaled `H` for the same epoch, in the same frame of tags. Traced on `H` `split
y=mid` seed 0 (session 23): the two searchers of one leg's remnant went round the other
leg's finished shape, from 5700 s to the end of the run, and their own shape stayed two
sites short. A placed robot whose tag is no site of a searcher's target is now an
obstacle to it, not a robot to follow or to localise from.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.controller import file_held
from etswarm.algorithm.kinship import foreign
from etswarm.algorithm.localise import find_site, window_centre
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_OTHER,
    NB_STATE,
    NB_TX,
    NB_TY,
    R_EPOCH,
    R_TSLOT,
    SLOT_FIELDS,
    SLOT_N,
    SLOT_TX,
    SLOT_TY,
    SLOT_USED,
    allocate,
)
from etswarm.algorithm.messages import EPOCH_SHIFT, MSG_HELD, target_signature
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.search import NO_SITE
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError

from .find_site_args import ANYWHERE
from .test_pair_side import GENE_X0, WINDOW, pair_world
from .traced import NATIVE_MATHS, SESSION_26_FORMATION, SESSION_31_PLACEMENT


def pair_off_the_target(et: ETParams):  # type: ignore[no-untyped-def]
    """``test_pair_side.pair_world`` (a searcher hearing Active robots at d on (0, 0) and
    (1, 0)) with only their common neighbour sites (1, 1) and (0, -1) left in the target:
    the two belong to some other shape."""
    _, nb, nb_dist, gene_flag, _, _, _, _ = pair_world()
    gene_flag = gene_flag.astype(np.int64)
    for x, y in [(0, 0), (1, 0)]:
        gene_flag[x - GENE_X0, y - GENE_X0] = 0
    ci, cf = et.pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    nb[0, :2, NB_LAST] = 10
    nb_dist[0, :2] = (40.0, 40.6)
    return nb, nb_dist, gene_flag, ci, cf


def site_from_pair(et: ETParams) -> tuple[bool, int, int]:
    nb, nb_dist, gene_flag, ci, cf = pair_off_the_target(et)
    held = np.zeros((5, 5), dtype=np.uint8)
    found, x, y, _ = find_site(0, 10, 0, True, 1, -1, 0, nb, nb_dist, gene_flag, ci, cf, 1.0,
                               3, held, *WINDOW, window_centre(cf, 0), 1.0, NO_SITE, NO_SITE,
                               *ANYWHERE)
    return bool(found), int(x), int(y)


def test_a_robot_is_foreign_when_its_tag_is_no_site_of_the_target() -> None:
    nb, _, gene_flag, ci, _ = pair_off_the_target(ETParams())
    assert foreign(0, 0, nb, gene_flag, ci) and foreign(0, 1, nb, gene_flag, ci)
    nb[0, 1, NB_TX], nb[0, 1, NB_TY] = 1, 1
    assert not foreign(0, 1, nb, gene_flag, ci)
    nb[0, 1, NB_TX] = 40  # beyond the gene grid: no site either
    assert foreign(0, 1, nb, gene_flag, ci)


def test_a_searcher_does_not_localise_from_robots_of_another_shape() -> None:
    # Before session 23 the pair put the searcher on (1, 1), a site of its own target,
    # measured from a lattice that is not its own.
    assert site_from_pair(ETParams(foreign_robots="follow")) == (True, 1, 1)
    assert site_from_pair(ETParams())[0] is False


def test_foreign_robots_takes_only_its_two_values() -> None:
    with pytest.raises(EtswarmError, match="foreign_robots"):
        ETParams(foreign_robots="ignore")


def test_each_leg_of_a_cut_h_regrows_with_its_own_searchers() -> None:
    # Traced: with "follow" the 11-robot leg ends the 4 h run with two free sites and its
    # two searchers going round the 12-robot leg's finished shape.
    run = ETRun(RunConfig(shape="H", seed=0, damage=("split y=mid",), max_time_s=2 * 3600,
                          et=ETParams(**{**SESSION_26_FORMATION, **SESSION_31_PLACEMENT})),
                sim_params=NATIVE_MATHS)
    summary = run.run()
    groups = summary["components"]
    assert sorted(c["robots"] for c in groups) == [11, 12, 27]
    for group in groups:
        assert group["formed"] and group["jaccard"] == 1.0
        assert group["census_count"] == group["robots"] == group["target_cells"]
    assert summary["duplicate_tags"] == []
    assert summary["max_leaders_per_component"] <= 1


def site_beside_a_foreign_robot(et: ETParams) -> tuple[bool, int, int]:
    """``test_pair_side.pair_world``'s own pair at d, and a Stable robot of another shape
    on (3, -3) (no site of the target) heard 45 mm away: on the searcher's lattice that tag
    lies more than 100 mm from (1, 1), so the reading contradicts the site."""
    _, nb, nb_dist, gene_flag, _, _, _, _ = pair_world()
    gene_flag = gene_flag.astype(np.int64)
    ci, cf = et.pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    nb[0, 2, NB_ID] = 3
    nb[0, 2, NB_STATE] = State.STABLE
    nb[0, 2, NB_TX], nb[0, 2, NB_TY] = 3, -3
    nb[0, :3, NB_LAST] = 10
    nb_dist[0, :3] = (40.0, 40.6, 45.0)
    held = np.zeros((5, 5), dtype=np.uint8)
    found, x, y, _ = find_site(0, 10, 0, True, 1, -1, 0, nb, nb_dist, gene_flag, ci, cf, 1.0,
                               3, held, *WINDOW, window_centre(cf, 0), 1.0, NO_SITE, NO_SITE,
                               *ANYWHERE)
    return bool(found), int(x), int(y)


def test_a_robot_of_another_shape_does_not_veto_a_site() -> None:
    # Session 46, traced on `H` `split y=mid` seed 11: the last free site of one leg's
    # scaled `H` had its two holders at d, but a robot of the other leg, 70 mm away,
    # contradicted it on every pass; the searcher went round for 2 h.
    assert site_beside_a_foreign_robot(ETParams(foreign_robots="follow"))[0] is False
    assert site_beside_a_foreign_robot(ETParams()) == (True, 1, 1)


def sibling_held_message(epoch: int, signature: int, sent_epoch: int | None = None):  # type: ignore[no-untyped-def]
    """Robot 0 (working for target slot 1 of ``epoch``) has robot 5, a Stable robot on
    (1, 1), in its table and receives robot 5's held-sites message of ``sent_epoch``
    (``epoch`` by default) naming the target ``signature``; returns robot 0's table after
    ``controller.file_held``."""
    sent_epoch = epoch if sent_epoch is None else sent_epoch
    ri, nb, nb_dist = allocate(1)
    slot_info = np.zeros((2, SLOT_FIELDS), dtype=np.int64)
    slot_info[1, [SLOT_N, SLOT_TX, SLOT_TY, SLOT_USED]] = (12, 0, 0, 1)
    ri[0, R_TSLOT] = 1
    ri[0, R_EPOCH] = epoch
    nb[0, 0, [NB_ID, NB_STATE, NB_TX, NB_TY, NB_EPOCH]] = (5, State.STABLE, 1, 1, epoch)
    in_type = np.array([[MSG_HELD | ((sent_epoch & 31) << EPOCH_SHIFT)]], dtype=np.uint8)
    in_data = np.zeros((1, 1, 9), dtype=np.uint8)
    in_data[0, 0, 0] = 5
    in_data[0, 0, 3] = signature
    held = np.zeros((1, 4, 4), dtype=np.uint8)
    file_held(0, 0, 100, ri, in_type, in_data, np.array([[45.0]]), nb, nb_dist, held,
              slot_info)
    return nb


def test_a_robot_that_gossips_another_target_of_the_epoch_is_foreign_whatever_its_tag() -> None:
    # Session 50, `H` `split y=mid` seed 5: far-half robots held tags that are sites of a
    # leg's scaled `H` too; a searcher of the leg took them for its own shape.
    own = target_signature(12, 0, 0)
    gene_flag = np.ones((7, 7), dtype=np.int64)  # every tag is a site of the target
    ci, _ = ETParams().pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    ci_off, _ = ETParams(signed_foreign="off").pack(31, gene_x0=GENE_X0, gene_y0=GENE_X0)
    nb = sibling_held_message(3, (own + 1) % 256)
    assert nb[0, 0, NB_OTHER] == 4
    assert foreign(0, 0, nb, gene_flag, ci)
    assert not foreign(0, 0, nb, gene_flag, ci_off)
    nb[0, 0, NB_EPOCH] = 4  # it has since adopted a newer target: the mark is stale
    assert not foreign(0, 0, nb, gene_flag, ci)
    # Its own target's signature, or a message of another epoch, marks nothing.
    assert sibling_held_message(3, own)[0, 0, NB_OTHER] == 0
    nb = sibling_held_message(3, (own + 1) % 256, sent_epoch=2)
    assert nb[0, 0, NB_OTHER] == 0
    assert not foreign(0, 0, nb, gene_flag, ci)
