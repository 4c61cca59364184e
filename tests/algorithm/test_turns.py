"""A Leader may turn the scaled shape in 60° steps (``placement_turns``)."""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.memory import SLOT_FIELDS, SLOT_N, SLOT_TURN, SLOT_TX, SLOT_TY, SLOT_USED
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.placement import RemnantView, choose_placement
from etswarm.algorithm.regeneration import TURN_CODE, find_slot, target_code
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.errors import EtswarmError
from etswarm.shapes import load_shape, scale
from etswarm.shapes.lattice import NEIGHBOUR_OFFSETS, neighbour_counts, sort_cells, turn_cells

from .traced import NATIVE_MATHS, SESSION_44_FORMATION

#: A bar of 5 x 2 cells (tags), long along X.
BAR = np.array([[x, y] for y in range(2) for x in range(5)])


def always_fits(_cells: np.ndarray) -> bool:
    return True


def test_a_turn_takes_each_neighbour_offset_to_the_next() -> None:
    turned = turn_cells(NEIGHBOUR_OFFSETS, 1)
    assert np.array_equal(turned, np.roll(NEIGHBOUR_OFFSETS, -1, axis=0))
    assert np.array_equal(turn_cells(BAR, 6), BAR)


def test_a_turned_shape_keeps_every_cell_s_neighbours() -> None:
    cells = scale(load_shape("starfish"), 40)
    for turns in range(1, 6):
        turned = turn_cells(cells, turns)
        assert sorted(neighbour_counts(turned)) == sorted(neighbour_counts(cells))
        moved = sort_cells(turned - turned.min(axis=0))
        assert not np.array_equal(moved, sort_cells(cells - cells.min(axis=0)))


def test_the_leader_turns_the_shape_along_its_remnant() -> None:
    """The remnant is the bar turned twice: only a turned bar covers all of it."""
    remnant = {(int(x) + 20, int(y) + 20) for x, y in turn_cells(BAR, 2)}
    leader = min(remnant)
    view = RemnantView(set(remnant), set(remnant), set(), set(), None, always_fits)
    turn, tx, ty = choose_placement(BAR, leader, view, turns=True)
    sites = {(int(x) + tx, int(y) + ty) for x, y in turn_cells(BAR, turn)}
    assert sites == remnant
    still = choose_placement(BAR, leader, view, turns=False)
    assert still[0] == 0
    kept = {(int(x) + still[1], int(y) + still[2]) for x, y in BAR}
    assert len(kept & remnant) < len(remnant)


def test_an_equal_turn_leaves_the_shape_as_it_was() -> None:
    """The remnant is the bar itself: no turn covers more, so none is taken."""
    remnant = {(int(x), int(y)) for x, y in BAR}
    view = RemnantView(set(remnant), set(remnant), set(), set(), None, always_fits)
    assert choose_placement(BAR, (0, 0), view, turns=True) == (0, 0, 0)


def test_slots_are_told_apart_by_their_turn() -> None:
    slot_info = np.zeros((3, SLOT_FIELDS), dtype=np.int64)
    for slot, turn in ((1, 0), (2, 3)):
        slot_info[slot, [SLOT_N, SLOT_TX, SLOT_TY, SLOT_USED, SLOT_TURN]] = (20, 4, -2, 1, turn)
    assert target_code(slot_info, 1) == 20
    assert target_code(slot_info, 2) == 20 + 3 * TURN_CODE
    assert find_slot(slot_info, 20, 4, -2) == 1
    assert find_slot(slot_info, 20 + 3 * TURN_CODE, 4, -2) == 2
    assert find_slot(slot_info, 20 + TURN_CODE, 4, -2) == -1


def test_a_shape_too_large_for_the_turn_bits_keeps_plain_codes() -> None:
    slot_info = np.zeros((2, SLOT_FIELDS), dtype=np.int64)
    slot_info[0, [SLOT_N, SLOT_USED]] = (TURN_CODE + 5, 1)
    slot_info[1, [SLOT_N, SLOT_TX, SLOT_TY, SLOT_USED]] = (TURN_CODE + 2, 0, 0, 1)
    assert target_code(slot_info, 1) == TURN_CODE + 2
    assert find_slot(slot_info, TURN_CODE + 2, 0, 0) == 1


def test_placement_turns_takes_only_its_two_values() -> None:
    with pytest.raises(EtswarmError, match="placement_turns"):
        ETParams(placement_turns="sometimes")


def test_a_split_starfish_regrows_turned_shapes() -> None:
    """Starfish ``split y=mid`` seed 33: both Leaders turn their scaled starfish (3 and 5
    turns), every robot of the remnants learns the turned target from the announcement,
    and both remnants re-form it."""
    run = ETRun(
        RunConfig(
            shape="starfish", seed=33, damage=("split y=mid",), max_time_s=4 * 3600,
            et=ETParams(placement_turns="on", **SESSION_44_FORMATION),
        ), sim_params=NATIVE_MATHS
    )
    summary = run.run()
    ctl = run.controller
    turns = [int(ctl.slot_info[s, SLOT_TURN]) for s in range(1, len(ctl.slot_cells))]
    assert any(turns)
    for slot in range(1, len(ctl.slot_cells)):
        info = ctl.slot_info[slot]
        expected = turn_cells(scale(run.shape, int(info[SLOT_N])), int(info[SLOT_TURN]))
        expected = expected + np.array([info[SLOT_TX], info[SLOT_TY]])
        assert np.array_equal(sort_cells(ctl.slot_cells[slot]), sort_cells(expected))
    remnants = [c for c in summary["components"] if c["robots"] >= 6]
    assert len(remnants) == 2
    assert all(c["formed"] and c["jaccard"] == 1.0 for c in remnants)
    assert summary["duplicate_tags"] == []
    assert summary["max_leaders_per_component"] <= 1
