"""A searcher does not take a site from where it would pinch a free neighbour site.

Robot 0 confirms site (0, 0); the holders of its neighbour sites in directions 1-5
stand on their centres, the site in direction 0 is free. It stands ``into`` mm from
(0, 0) towards that free site and reads its neighbours without noise.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, STABLE
from etswarm.algorithm.memory import NB_ID, NB_LAST, NB_STATE, NB_TX, NB_TY, allocate
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.pinch import (
    NOTCH_HELD,
    free_neighbours,
    narrow_mouth,
    too_far_off,
    toward_free,
    would_pinch,
)
from etswarm.shapes.lattice import tags_to_xy

from .traced import NATIVE_MATHS, SESSION_19_WIDENING, SESSION_33_PLACEMENT, SESSION_44_FORMATION

D = 40.0
HELD_DIRS = (1, 2, 3, 4, 5)
GENE = np.ones((7, 7), dtype=np.int64)  # tags -3 .. 3 (gene origin at (-3, -3))
EMPTY_MEMORY = np.zeros((9, 9), dtype=np.uint8)  # window origin at tag (-4, -4)


def direction_xy(k: int) -> np.ndarray:
    """Gene-frame centre (mm, (2,)) of (0, 0)'s neighbour site in direction k."""
    return tags_to_xy(np.array([(DIR_X[k], DIR_Y[k])]), D)[0]


def confirming(into: float) -> tuple[np.ndarray, np.ndarray]:
    """Robot 0's table, ``into`` mm from (0, 0) towards direction 0: ``(nb, nb_dist)``."""
    _, nb, nb_dist = allocate(1)
    here = into * direction_xy(0) / D
    for slot, k in enumerate(HELD_DIRS):
        nb[0, slot, NB_ID] = 1 + slot
        nb[0, slot, NB_STATE] = STABLE
        nb[0, slot, NB_TX] = DIR_X[k]
        nb[0, slot, NB_TY] = DIR_Y[k]
        nb[0, slot, NB_LAST] = 10
        nb_dist[0, slot] = float(np.hypot(*(direction_xy(k) - here)))
    return nb, nb_dist


def pinches(into: float, limit: float, memory: np.ndarray = EMPTY_MEMORY) -> bool:
    """Whether robot 0, ``into`` mm towards the free site, may not take (0, 0)."""
    ci, cf = ETParams(capture_pinch_mm=limit).pack(31, -3, -3)
    nb, nb_dist = confirming(into)
    return bool(would_pinch(0, 0, 0, 5, nb, nb_dist, GENE, ci, cf, memory, -4, -4))


def test_the_offset_towards_a_free_site() -> None:
    ux, uy = direction_xy(2) / D  # direction 2 is tag (1, 0), along x
    assert toward_free(12.0 * ux, 12.0 * uy, 1 << 2) == pytest.approx(12.0)
    assert toward_free(12.0, 0.0, 1 << 5) == pytest.approx(-12.0)  # away from it
    assert toward_free(12.0, 0.0, 0) < -1e8  # no free site


def test_free_neighbours_are_those_nobody_is_known_to_hold() -> None:
    nb, _ = confirming(0.0)
    assert free_neighbours(0, 0, 0, nb, GENE, ETParams().pack(31, -3, -3)[0],
                           EMPTY_MEMORY, -4, -4) == 1 << 0
    remembered = EMPTY_MEMORY.copy()
    remembered[DIR_X[0] + 4, DIR_Y[0] + 4] = 1
    assert free_neighbours(0, 0, 0, nb, GENE, ETParams().pack(31, -3, -3)[0],
                           remembered, -4, -4) == 0


@pytest.mark.parametrize(("into", "limit", "expected"), [
    (14.0, 10.0, True),   # deep into the free site: it moves on
    (6.0, 10.0, False),   # a few mm off, as most captures are
    (14.0, 0.0, False),   # the rule off
])
def test_a_capture_deep_into_a_free_site_is_refused(into: float, limit: float,
                                                    expected: bool) -> None:
    assert pinches(into, limit) is expected


@pytest.mark.parametrize(("into", "limit", "expected"), [
    (20.0, 18.0, True),   # half a spacing off: most of the way to the next site
    (12.0, 18.0, False),
    (20.0, 0.0, False),   # the rule off (the default)
])
def test_a_capture_far_off_the_centre_is_refused_in_any_direction(
    into: float, limit: float, expected: bool
) -> None:
    ci, cf = ETParams().pack(31, -3, -3)
    nb, nb_dist = confirming(into)
    assert bool(too_far_off(0, 0, 0, 5, nb, nb_dist, ci, cf, limit)) is expected
    remembered = EMPTY_MEMORY.copy()
    remembered[DIR_X[0] + 4, DIR_Y[0] + 4] = 1  # no free site next to it: no pinch ...
    assert not pinches(into, 10.0, remembered)  # ... but still far off its centre


def test_a_capture_next_to_no_free_site_is_never_refused() -> None:
    remembered = EMPTY_MEMORY.copy()
    remembered[DIR_X[0] + 4, DIR_Y[0] + 4] = 1  # the site in direction 0 is held
    assert not pinches(14.0, 10.0, remembered)


def test_a_free_site_counts_once_enough_of_its_neighbours_are_held() -> None:
    ci = ETParams().pack(31, -3, -3)[0]
    nb, _ = confirming(0.0)
    # The free site in direction 0, (0, 1), has two neighbours among (0, 0)'s: (1, 1)
    # (direction 1) and (-1, 0) (direction 5). Without their holders only (0, 0) itself
    # is held next to it: the tip of an arm, reached from outside.
    nb[0, HELD_DIRS.index(1), NB_ID] = -1
    nb[0, HELD_DIRS.index(5), NB_ID] = -1
    counted = []
    for restored in (None, 1, 5):
        if restored is not None:
            nb[0, HELD_DIRS.index(restored), NB_ID] = restored
        mask = free_neighbours(0, 0, 0, nb, GENE, ci, EMPTY_MEMORY, -4, -4)
        counted.append(bool(mask & 1))
    held_next_to_it = np.array([1, 2, 3])
    assert counted == list(held_next_to_it >= NOTCH_HELD)
    assert counted[0] is False and counted[-1] is True


def with_robot_across(across_mm: float, tag_step: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """Robot 0 on the centre of (0, 0), also reading a placed robot ``tag_step`` steps
    away in direction 0 (through the free site) at ``across_mm``: ``(nb, nb_dist)``."""
    nb, nb_dist = confirming(0.0)
    slot = len(HELD_DIRS)
    nb[0, slot, NB_ID] = 9
    nb[0, slot, NB_STATE] = STABLE
    nb[0, slot, NB_TX] = tag_step * DIR_X[0]
    nb[0, slot, NB_TY] = tag_step * DIR_Y[0]
    nb[0, slot, NB_LAST] = 10
    nb_dist[0, slot] = across_mm
    return nb, nb_dist


@pytest.mark.parametrize(("across_mm", "limit", "expected"), [
    (62.0, 68.0, True),   # two bodies 62 mm apart: no third fits between them
    (79.0, 68.0, False),  # about 2 d: room for one
    (62.0, 0.0, False),   # the rule off
])
def test_a_capture_that_narrows_a_free_sites_mouth_is_refused(
    across_mm: float, limit: float, expected: bool
) -> None:
    ci, cf = ETParams(capture_mouth_mm=limit).pack(31, -3, -3)
    nb, nb_dist = with_robot_across(across_mm)
    # It stands on its site's centre: the offset rule alone would let it take the site.
    assert narrow_mouth(0, 0, 0, 5, 1 << 0, nb, nb_dist, cf) is expected
    assert bool(would_pinch(0, 0, 0, 5, nb, nb_dist, GENE, ci, cf, EMPTY_MEMORY, -4, -4)) is (
        expected
    )


def test_only_the_robot_across_a_free_site_narrows_its_mouth() -> None:
    _, cf = ETParams(capture_mouth_mm=68.0).pack(31, -3, -3)
    nb, nb_dist = with_robot_across(62.0, tag_step=3)  # one step farther: not across it
    assert not narrow_mouth(0, 0, 0, 5, 1 << 0, nb, nb_dist, cf)
    nb, nb_dist = with_robot_across(62.0)
    assert not narrow_mouth(0, 0, 0, 5, 1 << 3, nb, nb_dist, cf)  # that site is not free
    assert not narrow_mouth(0, 0, 0, 11, 1 << 0, nb, nb_dist, cf)  # read before `since`


def nearest_to_a_free_site_mm(run) -> float:  # type: ignore[no-untyped-def]
    """Over the target's free sites at the end of ``run``: the least distance (mm) from a
    free site's centre (the rigid fit of the placed robots' tags) to a robot holding a
    neighbour site of it."""
    from etswarm.measures.formation import apply_fit, rigid_fit
    from etswarm.shapes.lattice import NEIGHBOUR_OFFSETS

    states = run.controller.states
    live = run.world.present & run.world.alive
    placed = np.flatnonzero(live & (states >= 2) & (states <= 7))
    tags = run.controller.tags[placed]
    holder = {tuple(int(v) for v in t): r for t, r in zip(tags, placed, strict=True)}
    fit = rigid_fit(tags_to_xy(tags, D), run.world.pos[placed])
    nearest = np.inf
    for cell in (tuple(int(v) for v in c) for c in run.target):
        if cell in holder:
            continue
        centre = apply_fit(fit, tags_to_xy(np.array([cell]), D))[0]
        for dx, dy in NEIGHBOUR_OFFSETS:
            r = holder.get((cell[0] + dx, cell[1] + dy))
            if r is not None:
                nearest = min(nearest, float(np.hypot(*(run.world.pos[r] - centre))))
    return nearest


@pytest.mark.parametrize(("shape", "seed"), [("heart", 39), ("hexagon", 33)])
def test_refusing_pinching_captures_lets_the_last_sites_fill(shape: str, seed: int) -> None:
    from etswarm.algorithm.run import ETRun, RunConfig

    # Without the rule the run stalls with a robot 36 mm or nearer a free site's centre
    # (a body is 33 mm across): no searcher fits in.
    off = ETRun(RunConfig(shape=shape, seed=seed, max_time_s=4 * 3600,
                          et=ETParams(capture_pinch_mm=0.0, **SESSION_19_WIDENING)),
                sim_params=NATIVE_MATHS)
    assert not off.run()["formed"]
    assert nearest_to_a_free_site_mm(off) < 36.0
    # With it the same swarm forms the shape.
    summary = ETRun(RunConfig(shape=shape, seed=seed, max_time_s=4 * 3600,
                              et=ETParams(**SESSION_19_WIDENING)), sim_params=NATIVE_MATHS).run()
    assert summary["formed"] and summary["jaccard"] == 1.0
    assert summary["duplicate_tags"] == []


def test_the_viewer_shows_a_searchers_refusals() -> None:
    from etswarm.algorithm.live import ETLive
    from etswarm.algorithm.memory import R_PINCH_REFUSED
    from etswarm.algorithm.run import ETRun, RunConfig

    live = ETLive(ETRun(RunConfig(shape="triangle", seed=0, max_time_s=3600)))
    states = live.run.controller.states
    while not (states == 1).any():
        live.advance(31 * 10)
    searcher = int(np.flatnonzero(states == 1)[0])
    live.run.controller.ri[searcher, R_PINCH_REFUSED] = 2
    assert live.robot_info(searcher)["pinch_refusals"] == 2
    assert live.robot_info(int(np.flatnonzero(states == 0)[0]))["pinch_refusals"] == "-"


def narrowest_mouth_mm(run) -> float:  # type: ignore[no-untyped-def]
    """Over every remnant's free target sites at the end of ``run``: the least distance
    (mm) between the holders of two opposite neighbour sites of a free site."""
    from etswarm.shapes.lattice import NEIGHBOUR_OFFSETS

    holds, _ = run._masks()
    narrowest = np.inf
    for group in run._groups():
        held = {tuple(int(v) for v in run.controller.tags[r]): r for r in group[holds[group]]}
        target = run.controller.slot_cells[run._slot_of(group)]
        for cell in (tuple(int(v) for v in c) for c in target):
            if cell in held:
                continue
            for dx, dy in NEIGHBOUR_OFFSETS:
                a = held.get((cell[0] + dx, cell[1] + dy))
                b = held.get((cell[0] - dx, cell[1] - dy))
                if a is not None and b is not None:
                    gap = float(np.hypot(*(run.world.pos[a] - run.world.pos[b])))
                    narrowest = min(narrowest, gap)
    return narrowest


def test_refusing_narrow_mouths_lets_a_regrowth_fill_its_last_site() -> None:
    from etswarm.algorithm.run import ETRun, RunConfig

    # Traced (session 21): without the rule the upper remnant's last free site is left
    # between two placed robots too close for a body to pass, and its searcher goes round
    # for hours; with it every remnant re-forms.
    config = {"shape": "dumbbell", "seed": 5, "damage": ("split y=mid",),
              "max_time_s": 4 * 3600}
    off = ETRun(RunConfig(**config, et=ETParams(capture_mouth_mm=0.0, **{**SESSION_33_PLACEMENT,
                                                 **SESSION_44_FORMATION})), sim_params=NATIVE_MATHS)
    summary = off.run()
    assert summary["formed"]  # the first formation
    assert not all(c["formed"] for c in summary["components"])
    assert narrowest_mouth_mm(off) < 68.0
    on = ETRun(RunConfig(**config, et=ETParams(**{**SESSION_33_PLACEMENT,
                                                **SESSION_44_FORMATION})),
               sim_params=NATIVE_MATHS).run()
    assert len(on["components"]) >= 2
    assert all(c["formed"] and c["jaccard"] == 1.0 for c in on["components"])
    assert on["duplicate_tags"] == []
