"""Where a Leader puts the scaled shape: always on a seed triangle of held sites."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.params import ETParams
from etswarm.algorithm.placement import (
    RemnantView,
    choose_translation,
    holds_a_pair,
    triangles_at,
)
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.errors import EtswarmError

from .traced import NATIVE_MATHS, SESSION_34_FORMATION

#: A bar of 3 x 2 cells (tags).
BAR = np.array([[0, 0], [1, 0], [2, 0], [0, 1], [1, 1], [2, 1]])


def always_fits(_cells: np.ndarray) -> bool:
    return True


def view(known: set, remnant: set) -> RemnantView:
    """What a Leader knows with no silent sites and no extent."""
    return RemnantView(known, remnant, set(), set(), None, always_fits)


def sites_after(shift: tuple[int, int]) -> set[tuple[int, int]]:
    return {(int(x) + shift[0], int(y) + shift[1]) for x, y in BAR}


def test_triangles_at_a_site_are_it_and_two_adjacent_held_neighbours() -> None:
    held = {(0, 0), (1, 0), (1, 1), (5, 5)}
    assert len(triangles_at((0, 0), held)) == 1
    assert triangles_at((5, 5), held) == []
    assert triangles_at((9, 9), held) == []  # not held itself


def test_the_leader_seeds_with_two_of_its_neighbours() -> None:
    leader = (10, 10)
    known = {(11, 10), (11, 11), (30, 30)}
    shift = choose_translation(BAR, leader, view(known, set()))
    sites = sites_after(shift)
    assert {leader, (11, 10), (11, 11)} <= sites


def test_a_leader_without_two_adjacent_neighbours_seeds_from_a_remembered_triangle() -> None:
    """Dead robots round the Leader: it hears one neighbour. The remnant it remembers
    holds a triangle a few sites away; the new shape goes there (the Leader may be left
    out), not round the Leader with one seed."""
    leader = (0, 0)
    known = {(1, 0)}
    remnant = {(5, 0), (6, 0), (6, 1), (7, 1)}
    shift = choose_translation(BAR, leader, view(known, remnant))
    sites = sites_after(shift)
    held = known | remnant | {leader}
    assert any(all(c in sites for c in tri) for tag in held for tri in triangles_at(tag, held))
    # with no triangle anywhere it still places the shape round the Leader
    alone = choose_translation(BAR, leader, view(known, set()))
    assert leader in sites_after(alone)


def test_any_seeds_keep_the_most_of_the_remnant_where_the_leader_is_hemmed_in() -> None:
    """The Leader can seed with two neighbours, but a shape kept on it covers one site of
    the remnant; a bar of six held sites stands elsewhere. "leader" keeps the shape on
    the Leader (the paper), "any" lays it over the bar."""
    leader = (0, 0)
    known = {(1, 0), (1, 1)}
    bar = sites_after((10, 0))
    paper = sites_after(choose_translation(BAR, leader, view(known, bar)))
    assert {leader, (1, 0), (1, 1)} <= paper
    assert not paper & bar
    anywhere = sites_after(choose_translation(BAR, leader, view(known, bar), seeds="any"))
    assert anywhere == bar


def test_any_seeds_keep_the_leader_when_it_covers_as_much() -> None:
    """With as much of the remnant either way, the Leader's own placement wins."""
    leader = (0, 0)
    known = {(1, 0), (1, 1), (0, 1)}
    shift = choose_translation(BAR, leader, view(known, set()), seeds="any")
    assert leader in sites_after(shift)
    assert shift == choose_translation(BAR, leader, view(known, set()))


def test_placement_seeds_takes_only_its_two_values() -> None:
    assert ETParams(placement_seeds="any").placement_seeds == "any"
    assert ETParams(placement_seeds="silent").placement_seeds == "silent"
    with pytest.raises(EtswarmError, match="placement_seeds"):
        ETParams(placement_seeds="everywhere")


def test_silent_seeds_move_off_the_leader_only_after_deaths() -> None:
    """"silent" places as "leader" when no site inside the remnant fell silent, and as
    "any" when one did."""
    leader = (0, 0)
    known = {(1, 0), (1, 1)}
    bar = sites_after((10, 0))
    calm = view(known, bar)
    assert choose_translation(BAR, leader, calm, seeds="silent") == choose_translation(
        BAR, leader, calm
    )
    dead = {(20, 20)}
    hemmed = RemnantView(known, bar, dead, dead, None, always_fits)
    assert sites_after(choose_translation(BAR, leader, hemmed, seeds="silent")) == bar


def kept_after_kill(seeds: str) -> tuple[int, int, bool]:
    """`T` seed 15, ``kill random=0.1`` when formed: run until the remnant's Leader has
    its target. Returns how many live robots stand on a site of the new target (by the
    tags they held), how many dead robots' sites it covers, and whether it holds the
    Leader's site. (Traced in session 22.)"""
    run = ETRun(
        RunConfig(shape="T", seed=15, max_time_s=3 * 3600, damage=("kill random=0.1",),
                  et=ETParams(placement_seeds=seeds, **SESSION_34_FORMATION)),
                sim_params=NATIVE_MATHS
    )
    while not any(e["kind"] == "damage" for e in run.events):
        assert run.sim_time_s < 2 * 3600, "the T did not form"
        run.advance(31 * 10)
    tags = run.controller.tags.copy()
    alive = run.world.alive.copy()
    while not any(e["kind"] == "census" for e in run.events):
        assert run.sim_time_s < 3 * 3600, "no regeneration"
        run.advance(31)
    census = next(e for e in run.events if e["kind"] == "census")
    target = {tuple(t) for t in run.controller.slot_cells[census["slot"]].tolist()}
    live = sum(tuple(t) in target for t in tags[alive].tolist())
    dead = sum(tuple(t) in target for t in tags[~alive].tolist())
    return live, dead, tuple(tags[census["leader"]].tolist()) in target


def test_a_leader_hemmed_in_by_dead_robots_seeds_where_the_remnant_is() -> None:
    """Kept on the Leader, the scaled T covers few of the remnant's sites; with the
    default ("silent": the Leader knows robots died round it) it covers most of them and
    leaves the Leader out."""
    live_paper, _, on_leader = kept_after_kill("leader")
    assert on_leader
    live, dead, on_leader_now = kept_after_kill("silent")
    assert live >= 20 and live >= 3 * live_paper, (live, live_paper)
    assert not on_leader_now
    assert dead == 0


def test_fewest_off_shape_prefers_the_old_shape_where_the_remnant_ties() -> None:
    """Two seeded placements through the Leader cover as much of the remnant (none of it
    known). The nearer one puts two cells off the target the remnant was building. Given
    that target (``placement_off_shape = "fewest"``) the Leader takes the placement wholly
    on it; without it ("any") the nearer one."""
    leader = (0, 0)
    known = {(1, 0), (1, 1), (0, 1)}
    old = frozenset(sites_after((-1, 0)))
    plain = RemnantView(known, set(), set(), set(), None, always_fits)
    minding = RemnantView(known, set(), set(), set(), None, always_fits, old)
    assert choose_translation(BAR, leader, plain) == (0, 0)
    assert choose_translation(BAR, leader, minding) == (-1, 0)


def test_fewest_off_shape_still_covers_the_most_of_the_remnant_first() -> None:
    """Covering the remnant comes first: remembered sites at (2, 0) and (2, 1) keep the
    placement that covers them, though two of its cells are off the old target."""
    leader = (0, 0)
    known = {(1, 0), (1, 1), (0, 1)}
    old = frozenset(sites_after((-1, 0)))
    remnant = {(2, 0), (2, 1)}
    minding = RemnantView(known, remnant, set(), set(), None, always_fits, old)
    assert choose_translation(BAR, leader, minding) == (0, 0)


def test_placement_off_shape_is_checked() -> None:
    with pytest.raises(EtswarmError, match="placement_off_shape"):
        ETParams(placement_off_shape="most")


def test_weigh_off_shape_trades_a_remnant_site_for_two_cells_off_the_old_shape() -> None:
    """One remembered site at (2, 0) favours the nearer placement by one site, which puts
    two cells off the old target: "fewest" keeps it, "weigh" counts each off-shape cell
    against it as one site of the remnant left out and moves on to the old target."""
    leader = (0, 0)
    known = {(1, 0), (1, 1), (0, 1)}
    old = frozenset(sites_after((-1, 0)))
    remnant = {(2, 0)}
    fewest = RemnantView(known, remnant, set(), set(), None, always_fits, old)
    weigh = RemnantView(known, remnant, set(), set(), None, always_fits, old, True)
    assert choose_translation(BAR, leader, fewest) == (0, 0)
    assert choose_translation(BAR, leader, weigh) == (-1, 0)


def test_a_leader_with_no_seed_triangle_keeps_two_neighbouring_robots() -> None:
    """No triangle of held sites anywhere: a searcher can still locate a site from two
    robots on neighbouring sites, never from one. Weighing the cells off the old shape,
    the placement through the Leader alone covers as much (none) with no cell off; the
    one that keeps its neighbour too puts (1, 1) off the old shape, and wins."""
    tri = np.array([[0, 0], [1, 0], [1, 1]])
    leader = (0, 0)
    old = frozenset({(-1, 0), (0, 0), (0, 1), (1, 0)})
    weigh = RemnantView({(1, 0)}, {(1, 0)}, set(), set(), None, always_fits, old, True)
    assert choose_translation(tri, leader, weigh) == (0, 0)
    assert holds_a_pair({(0, 0), (1, 0)}) and not holds_a_pair({(0, 0), (1, 2), (2, 0)})
