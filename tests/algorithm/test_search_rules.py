"""Site choice rules of a searching robot, on hand-made neighbour tables: holes, the
widened window, and the option checks."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.hole_rules import closes_a_hole, open_from
from etswarm.algorithm.localise import in_window
from etswarm.algorithm.memory import NB_ID, NB_MASK, NB_STATE, NB_TX, NB_TY, allocate
from etswarm.algorithm.params import C_GENE_X0, C_GENE_Y0, ETParams
from etswarm.algorithm.search import NO_SITE
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError

from .find_site_args import ANYWHERE

RING = [(0, 1), (1, 1), (1, 0), (0, -1), (-1, -1), (-1, 0)]
#: An empty memory of held sites (window, origin) for ``find_site``: nothing remembered.
NO_MEMORY = (np.zeros((9, 9), dtype=np.uint8), -4, -4)


def hexagon_world(held: list[tuple[int, int]]):  # type: ignore[no-untyped-def]
    """Gene of the 7 sites within one step of (0, 0) (all else outside the shape) and a
    table of robot 0 that hears a Stable robot on every site of ``held``."""
    gene = np.zeros((5, 5), dtype=np.int64)  # tags -2..2 in both axes
    for x, y in [(0, 0), *RING]:
        gene[x + 2, y + 2] = 1
    ci, _ = ETParams().pack(31, gene_x0=-2, gene_y0=-2)
    assert ci[C_GENE_X0] == -2 and ci[C_GENE_Y0] == -2
    _, nb, _ = allocate(1)
    for slot, (x, y) in enumerate(held):
        nb[0, slot, NB_ID] = slot + 1
        nb[0, slot, NB_STATE] = State.STABLE
        nb[0, slot, NB_TX] = x
        nb[0, slot, NB_TY] = y
        nb[0, slot, NB_MASK] = 0
    return gene, ci, nb


def test_taking_the_last_way_in_to_a_free_site_closes_a_hole() -> None:
    # Ring held except (1, 0): taking it leaves the centre walled in.
    gene, ci, nb = hexagon_world([s for s in RING if s != (1, 0)])
    assert closes_a_hole(0, 1, 0, nb, gene, ci)


def test_a_free_site_with_another_way_out_stays_open() -> None:
    # (1, 0) and (0, 1) free: after taking (1, 0) the centre still reaches (0, 1), and
    # (0, 1) borders the outside of the shape.
    gene, ci, nb = hexagon_world([s for s in RING if s not in ((1, 0), (0, 1))])
    assert not closes_a_hole(0, 1, 0, nb, gene, ci)
    assert open_from(0, 1, 0, -1, 0, True, nb, gene, ci)


def test_a_closed_hole_is_recognised() -> None:
    # The whole ring held: the centre is already shut in, whoever is inside may take it.
    gene, ci, nb = hexagon_world(list(RING))
    assert not open_from(0, 0, 0, 0, 0, False, nb, gene, ci)
    gene, ci, nb = hexagon_world(RING[:-1])
    assert open_from(0, 0, 0, 0, 0, False, nb, gene, ci)


def test_the_window_widens_pair_and_balance_tolerances() -> None:
    _, cf = ETParams(pair_tol_mm=4.0, balance_tol_mm=8.0).pack(31, 0, 0)
    # A window centred on 40 mm.
    assert in_window(41.0, 39.0, 40.0, cf, 1.0)
    assert not in_window(46.0, 43.0, 40.0, cf, 1.0)  # 6 mm off: outside the plain window
    assert in_window(46.0, 43.0, 40.0, cf, 2.0)
    assert not in_window(52.0, 40.0, 40.0, cf, 2.0)  # 12 mm off even when doubled


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("creep", "maybe"),
        ("orbit", "left"),
        ("second_ring", "yes"),
        ("hole_memory", "1"),
        ("pocket", ""),
    ],
)
def test_search_options_are_checked(field: str, value: str) -> None:
    with pytest.raises(EtswarmError, match=field):
        ETParams(**{field: value})


def test_a_reused_table_row_keeps_nothing_of_its_previous_robot() -> None:
    # Found on T split y=2: after a regeneration cleared the table, a row first filled by an
    # election message still held the old robot's epoch and released count, and the stale
    # count (24 of the old target) stopped every release for the new one.
    from etswarm.algorithm.controller import table_slot
    from etswarm.algorithm.memory import NB_EPOCH, NB_RELEASED

    _, nb, _ = allocate(1)
    nb[0, 0, NB_ID] = 5
    nb[0, 0, NB_EPOCH] = 1
    nb[0, 0, NB_RELEASED] = 24
    nb[0, 0, NB_MASK] = 7
    nb[0, :, NB_ID] = -1  # what adopting a new target does
    assert table_slot(0, 9, nb) == -1  # row 0, created
    assert nb[0, 0, NB_ID] == 9
    assert nb[0, 0, NB_EPOCH] == -1
    assert nb[0, 0, NB_RELEASED] == 0
    assert nb[0, 0, NB_MASK] == 0


def test_the_papers_search_is_a_command_line_option() -> None:
    import json

    from click.testing import CliRunner

    from etswarm.cli.run_command import run as run_command

    args = ["triangle", "--seed", "3", "--max-time", "3600", "--json"]
    papers = ["--no-creep", "--orbit", "bounce", "--no-second-ring", "--no-hole-memory"]
    papers.append("--no-pocket")  # the default; --pocket is tested in test_pocket
    papers.append("--no-wave")
    paper = CliRunner().invoke(run_command, [*args, *papers])
    assert paper.exit_code == 0, paper.output
    ours = CliRunner().invoke(run_command, args)
    assert ours.exit_code == 0, ours.output
    paper_summary = json.loads(paper.output)
    ours_summary = json.loads(ours.output)
    # Both search modes grow the triangle, by different paths.
    assert paper_summary["formed"] and ours_summary["formed"]
    assert paper_summary["formation_time_s"] != ours_summary["formation_time_s"]
    bad = CliRunner().invoke(run_command, [*args, "--orbit", "left"])
    assert bad.exit_code != 0 and "--orbit" in bad.output


def two_reference_table(second_ring: str, holder_heard: bool):  # type: ignore[no-untyped-def]
    """Robot 0 hears A (tag (0, 0), Active, reporting its neighbour site (1, 1) held) and B
    (tag (1, 2), Stable), both at d = 40 mm: A and B are sqrt(3) d apart and the sites next
    to both are (0, 1) and (1, 1). With ``holder_heard`` it also hears the holder of (1, 1)."""
    from etswarm.algorithm.memory import NB_LAST, NB_TS

    gene = np.ones((7, 7), dtype=np.int64)  # tags -3..3: every site in the shape
    ci, cf = ETParams(second_ring=second_ring).pack(31, gene_x0=-3, gene_y0=-3)
    _, nb, nb_dist = allocate(1)
    robots = [((0, 0), State.ACTIVE, 1 << RING.index((1, 1)))]
    robots.append(((1, 2), State.STABLE, 0))
    if holder_heard:
        robots.append(((1, 1), State.STABLE, 0))
    for slot, ((x, y), state, mask) in enumerate(robots):
        nb[0, slot, NB_ID] = slot + 1
        nb[0, slot, NB_STATE] = state
        nb[0, slot, NB_TX] = x
        nb[0, slot, NB_TY] = y
        nb[0, slot, NB_MASK] = mask
        nb[0, slot, NB_TS] = 1
        nb[0, slot, NB_LAST] = 10
        nb_dist[0, slot] = 40.0
    return gene, ci, cf, nb, nb_dist


def test_second_ring_pairs_find_the_site_between_them() -> None:
    from etswarm.algorithm.localise import find_site, second_ring_side, window_centre

    for q in range(6):
        dx = RING[q][0] + RING[(q + 1) % 6][0]
        dy = RING[q][1] + RING[(q + 1) % 6][1]
        assert second_ring_side(dx, dy) == q
    for dx, dy in [*RING, (2, 0), (0, 2), (2, 2), (0, 0)]:
        assert second_ring_side(dx, dy) == -1
    # (1, 1) is reported held, so the robot is on (0, 1); the paper's rule needs two
    # lattice neighbours and finds nothing.
    for option, expected in [("on", (True, 0, 1)), ("off", (False, 0, 0))]:
        gene, ci, cf, nb, nb_dist = two_reference_table(option, holder_heard=False)
        found, x, y, _ = find_site(
            0, 10, 0, False, -1, -1, 0, nb, nb_dist, gene, ci, cf, 1.0, 3, *NO_MEMORY,
            window_centre(cf, 0), 1.0, NO_SITE, NO_SITE, *ANYWHERE,
        )
        assert (found, x, y) == expected


def test_a_site_whose_reported_neighbour_is_not_heard_is_refused_on_settling() -> None:
    from etswarm.algorithm.localise import find_site, reported_but_unheard, window_centre

    # A reports (1, 1) held, but nobody of (1, 1) is heard: standing on (0, 1) the robot
    # would hear it at about d, so it is somewhere else. Settling (strict), it refuses.
    gene, ci, cf, nb, nb_dist = two_reference_table("on", holder_heard=False)
    assert reported_but_unheard(0, 0, 1, 0, nb, gene, ci)
    found, *_ = find_site(
        0, 10, 0, True, -1, -1, 0, nb, nb_dist, gene, ci, cf, 1.0, 3, *NO_MEMORY,
            window_centre(cf, 0), 1.0, NO_SITE, NO_SITE, *ANYWHERE,
    )
    assert not found
    # Once the holder of (1, 1) is heard too, the site is confirmed.
    gene, ci, cf, nb, nb_dist = two_reference_table("on", holder_heard=True)
    assert not reported_but_unheard(0, 0, 1, 0, nb, gene, ci)
    found, x, y, _ = find_site(
        0, 10, 0, True, -1, -1, 0, nb, nb_dist, gene, ci, cf, 1.0, 3, *NO_MEMORY,
            window_centre(cf, 0), 1.0, NO_SITE, NO_SITE, *ANYWHERE,
    )
    assert (found, x, y) == (True, 0, 1)
