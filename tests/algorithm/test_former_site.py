"""A searcher released where a regenerated target left it out knows it stands near the
site it held (``former_site``): it takes no site its odometry cannot have taken it to."""

from __future__ import annotations

import math

import numpy as np

from etswarm.algorithm.former_site import (
    ANY_REACH,
    FORMER_PATH_MM,
    former_reach,
    note_former_site,
    out_of_reach,
)
from etswarm.algorithm.homing import ODO_PER_MM
from etswarm.algorithm.localise import find_site, window_centre
from etswarm.algorithm.memory import (
    NB_LAST,
    NO_SITE,
    R_FORMER_X,
    R_ODO_PATH,
    R_ODO_X,
    R_ODO_Y,
    allocate,
)
from etswarm.algorithm.params import ETParams

from .test_pair_side import WINDOW, pair_world
from .traced import SESSION_56_SEARCH

SLACK_MM = ETParams().former_site_slack_mm


def odometry(ri: np.ndarray, x_mm: float, y_mm: float, path_mm: float) -> None:
    """Robot 0's odometric position and path since it started searching."""
    ri[0, R_ODO_X] = round(x_mm * ODO_PER_MM)
    ri[0, R_ODO_Y] = round(y_mm * ODO_PER_MM)
    ri[0, R_ODO_PATH] = round(path_mm * ODO_PER_MM)


def test_a_robot_starts_with_no_former_site_and_any_reach() -> None:
    ri, _, _ = allocate(2)
    _, cf = ETParams().pack(31, gene_x0=0, gene_y0=0)
    assert ri[0, R_FORMER_X] == NO_SITE
    assert former_reach(0, ri, cf) == ANY_REACH
    assert not out_of_reach(0, ri, 9, 9, ANY_REACH, cf)


def test_the_reach_is_the_odometric_distance_plus_the_slack_while_the_path_is_short() -> None:
    ri, _, _ = allocate(1)
    _, cf = ETParams().pack(31, gene_x0=0, gene_y0=0)
    note_former_site(0, ri, 2, 3)
    odometry(ri, 12.0, -9.0, 40.0)
    assert math.isclose(former_reach(0, ri, cf), 15.0 + SLACK_MM, abs_tol=1e-3)
    odometry(ri, 12.0, -9.0, FORMER_PATH_MM + 1.0)  # too far to trust
    assert former_reach(0, ri, cf) == ANY_REACH
    odometry(ri, 12.0, -9.0, 40.0)
    _, off = ETParams(former_site_slack_mm=0.0).pack(31, gene_x0=0, gene_y0=0)
    assert former_reach(0, ri, off) == ANY_REACH


def test_sites_are_measured_on_the_lattice_from_the_former_site() -> None:
    ri, _, _ = allocate(1)
    _, cf = ETParams().pack(31, gene_x0=0, gene_y0=0)
    d = cf[0]
    note_former_site(0, ri, 2, 3)
    # (3, 3), (3, 4) and (2, 4) are neighbours (d away); (3, 5) is across the pair (2, 4)
    # and (3, 4), sqrt(3) d away; (4, 3) two steps along X.
    for (x, y), dist in (((3, 3), d), ((3, 4), d), ((2, 4), d), ((3, 5), math.sqrt(3) * d),
                         ((4, 3), 2 * d), ((2, 3), 0.0)):
        assert not out_of_reach(0, ri, x, y, dist + 0.01, cf)
        if dist > 0:
            assert out_of_reach(0, ri, x, y, dist - 0.01, cf)


def test_a_searcher_beside_a_pair_takes_no_site_across_it_from_where_it_stood() -> None:
    ri, nb, nb_dist, gene_flag, _, ci, cf, held = pair_world()
    nb[0, :2, NB_LAST] = 10
    nb_dist[0, :2] = (40.0, 40.6)
    memory = (held[0], *WINDOW)
    gene_flag = gene_flag.astype(np.int64)  # as test_pair_side: one compilation for both

    def site() -> tuple[bool, int, int]:
        # steering by A (robot 1), which it passed first: (1, 1) by the side of the pair
        found, x, y, _ = find_site(0, 10, 0, True, 1, 1, 0, nb, nb_dist, gene_flag, ci, cf,
                                   1.0, 3, *memory, window_centre(cf, 0), 1.0, NO_SITE,
                                   NO_SITE, ri, former_reach(0, ri, cf))
        return bool(found), int(x), int(y)

    assert site() == (True, 1, 1)
    # It held (0, -1), the pair's other common neighbour, and has gone 5 mm since: it
    # stands there, and (1, 1) is 69 mm away.
    note_former_site(0, ri, 0, -1)
    odometry(ri, 3.0, 4.0, 6.0)
    assert site() == (False, 0, 0)
    # Having gone 45 mm from there, it may have come round to (1, 1).
    odometry(ri, 27.0, 36.0, 80.0)
    assert site() == (True, 1, 1)


def damaged(shape: str, seed: int, damage: str, **options: float) -> dict:
    """The summary of a 4 h run of ``shape`` with one damage and ET options."""
    from etswarm.algorithm.run import ETRun, RunConfig

    config = RunConfig(shape=shape, seed=seed, damage=(damage,), max_time_s=4 * 3600,
                       et=ETParams(**options))
    return ETRun(config).run()


def test_robots_left_out_on_a_cut_crossbar_do_not_grow_it_mirrored() -> None:
    # T kill random=0.1 seed 64 (session 55): the new T is laid one row above the old
    # crossbar, whose lower row is left out. Robots 21 and 27 waited there and, released,
    # took the sites above the upper row's robots across the pair, 69 mm away, so the
    # crossbar's right half grew mirrored and two sites tore.
    default = damaged("T", 64, "kill random=0.1", **SESSION_56_SEARCH)
    assert default["duplicate_tags"] == []
    (remnant,) = [c for c in default["components"] if c["robots"] >= 6]
    assert remnant["formed"] and remnant["jaccard"] == 1.0
    assert remnant["robots"] == remnant["target_cells"] == 41
    off = damaged("T", 64, "kill random=0.1", former_site_slack_mm=0.0, **SESSION_56_SEARCH)
    assert not any(c["formed"] for c in off["components"] if c["robots"] >= 6)


def test_a_searcher_released_from_a_far_site_takes_no_mirror_site_of_a_small_remnant() -> None:
    # L remove random=0.2 seed 40 (session 54's tag held twice): in a 6-robot group only
    # robots 9 on (-1, -5) and 17 on (0, -4) kept their sites. Robot 25, left out on
    # (2, -5), came straight at the pair from 60 mm and took (-1, -4), the mirror of
    # (0, -5) where it stood; the group grew mirrored, and when it met the other group
    # two robots kept (-1, -3). By odometry it had gone 82 mm, and (-1, -4) lies 144 mm
    # from (2, -5).
    default = damaged("L", 40, "remove random=0.2", **SESSION_56_SEARCH)
    assert default["duplicate_tags"] == []
    assert all(c["formed"] and c["jaccard"] == 1.0
               for c in default["components"] if c["robots"] >= 6)
    off = damaged("L", 40, "remove random=0.2", former_site_slack_mm=0.0, **SESSION_56_SEARCH)
    assert off["duplicate_tags"] == [(-1, -3)]
