"""An election that loses nobody is a false alarm: the robots take up their work again.

Traced on `H` seed 75 (session 25): searchers diving for a free site pushed two Stable
neighbours 94 mm apart; one stopped hearing the other, went to Danger, and the whole `H`
elected, counted all 50 robots and regrew from its seeds, again and again. With
``false_alarm = "resume"`` a census that gives the current target's robot count keeps
the target, every robot goes back to its state, and the robot that started it excuses the
neighbour site it missed.
"""

from __future__ import annotations

import numpy as np
import pytest

from etswarm.algorithm.et_controller import ETController
from etswarm.algorithm.kernel_util import DIR_X, DIR_Y, first_growth
from etswarm.algorithm.memory import (
    NB_EPOCH,
    NB_ID,
    NB_LAST,
    NB_STATE,
    NB_TX,
    NB_TY,
    PHASE_ELECTING,
    PHASE_NORMAL,
    R_EPOCH,
    R_EXCUSED,
    R_GROWTH,
    R_HAS_TAG,
    R_HELD_EPOCH,
    R_MISSING,
    R_NN,
    R_PEND_EPOCH,
    R_PEND_N,
    R_PEND_TX,
    R_PEND_TY,
    R_PHASE,
    R_PRE_SINCE,
    R_PRE_STATE,
    R_RELEASED,
    R_SEEN_FULL,
    R_SINCE,
    R_STATE,
    R_TAG_X,
    R_TAG_Y,
    R_TS,
    R_TSLOT,
    SLOT_SHAPE,
    SLOT_WX,
    SLOT_WY,
)
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.placed import placed_rule
from etswarm.algorithm.regeneration import adopt_target, catch_up
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.cli.run_outputs import describe

from .traced import NATIVE_MATHS, SESSION_34_FORMATION

TPS = 31
TICK = 20_000
#: The first target: a hexagon of seven sites round (0, 0).
HEXAGON = np.array([(0, 0)] + [(DIR_X[k], DIR_Y[k]) for k in range(6)], dtype=np.int64)


def electing_robots(params: ETParams) -> ETController:
    """Three robots electing for epoch 1 of the hexagon: robot 0 was Stable on (0, 0) and
    started the election missing direction 2, robot 1 was searching, robot 2 Queued."""
    ctl = ETController(3, HEXAGON, params, TPS)
    ri = ctl.ri
    ri[:, R_PHASE] = PHASE_ELECTING
    ri[:, R_STATE] = State.DANGER
    ri[:, R_SINCE] = TICK - 100
    ri[0, R_PRE_STATE], ri[0, R_PRE_SINCE] = State.STABLE, 1234
    ri[0, R_HAS_TAG], ri[0, R_TAG_X], ri[0, R_TAG_Y] = 1, 0, 0
    ri[0, R_TS], ri[0, R_NN] = 5, 6
    ri[0, R_MISSING] = 1 << 2
    ctl.nb[0, 0, NB_ID] = 1
    ri[1, R_PRE_STATE] = State.SEARCH
    ri[2, R_PRE_STATE] = State.QUEUED
    ri[2, R_RELEASED] = 4
    return ctl


def adopt(ctl: ETController, slot: int) -> None:
    for i in range(3):
        adopt_target(
            i, TICK, ctl.ri, ctl.nb, slot, 1, 0, ctl.gene_flag, ctl.gene_nn, ctl.slot_info,
            ctl.ci,
        )


def test_a_slot_with_the_same_cells_is_the_same_target() -> None:
    ctl = ETController(3, HEXAGON, ETParams(), TPS)
    same = ctl.add_target(HEXAGON[::-1].copy(), release_limit=7, tx=0, ty=0)
    other = ctl.add_target(HEXAGON[:5].copy(), release_limit=5, tx=0, ty=0)
    assert ctl.slot_info[same, SLOT_SHAPE] == ctl.slot_info[0, SLOT_SHAPE] == 0
    assert ctl.slot_info[other, SLOT_SHAPE] == other


def test_every_robot_goes_back_to_what_it_was() -> None:
    ctl = electing_robots(ETParams())
    slot = ctl.add_target(HEXAGON, release_limit=7, tx=0, ty=0)
    adopt(ctl, slot)
    ri = ctl.ri
    assert list(ri[:, R_STATE]) == [State.STABLE, State.SEARCH, State.QUEUED]
    assert list(ri[:, R_PHASE]) == [PHASE_NORMAL] * 3
    assert list(ri[:, R_EPOCH]) == [1, 1, 1] and list(ri[:, R_TSLOT]) == [slot] * 3
    # the Leader is no new seed: its site, TS and state since are as before
    assert (ri[0, R_HAS_TAG], ri[0, R_TS], ri[0, R_SINCE]) == (1, 5, 1234)
    assert ri[0, R_EXCUSED] == 1 << 2 and ri[0, R_MISSING] == 0
    assert ctl.nb[0, 0, NB_ID] == 1  # its neighbour table stands
    assert ri[2, R_RELEASED] == 4  # the repository goes on where it was
    # still the first formation's growth: its rules (widening times, release order...)
    assert list(ri[:, R_GROWTH]) == [0, 0, 0]
    assert all(first_growth(i, ri) for i in range(3))


@pytest.mark.parametrize("case", ["regrow", "smaller target"])
def test_otherwise_the_shape_regrows_from_its_seeds(case: str) -> None:
    params = ETParams(false_alarm="regrow") if case == "regrow" else ETParams()
    ctl = electing_robots(params)
    cells = HEXAGON if case == "regrow" else HEXAGON[:5].copy()
    slot = ctl.add_target(cells, release_limit=len(cells), tx=0, ty=0)
    adopt(ctl, slot)
    ri = ctl.ri
    assert list(ri[:, R_STATE]) == [State.ACTIVE, State.QUEUED, State.QUEUED]
    assert ri[0, R_TS] == 1 and ri[0, R_EXCUSED] == 0
    assert ctl.nb[0, 0, NB_ID] == -1 and ri[2, R_RELEASED] == 0
    assert list(ri[:, R_GROWTH]) == [1, 1, 1]  # a regrowth: its own rules
    assert not any(first_growth(i, ri) for i in range(3))


@pytest.mark.parametrize("same", [True, False])
def test_a_searcher_that_missed_it_keeps_its_memory_of_held_sites(same: bool) -> None:
    ctl = ETController(1, HEXAGON, ETParams(), TPS)
    cells = HEXAGON if same else HEXAGON[:5].copy()
    slot = ctl.add_target(cells, release_limit=len(cells), tx=0, ty=0)
    ri = ctl.ri
    ri[0, R_STATE] = State.SEARCH
    ri[0, R_HELD_EPOCH] = 1  # its memory is of epoch 0's target
    ri[0, R_PEND_EPOCH], ri[0, R_PEND_N], ri[0, R_PEND_TX], ri[0, R_PEND_TY] = 1, len(cells), 0, 0
    assert catch_up(
        0, TICK, ri, ctl.nb, ctl.nb_dist, ctl.gene_flag, ctl.gene_nn, ctl.slot_info, ctl.ci
    )
    assert ri[0, R_STATE] == State.SEARCH and (ri[0, R_EPOCH], ri[0, R_TSLOT]) == (1, slot)
    assert ri[0, R_HELD_EPOCH] == (2 if same else 1)  # (a stale memory is cleared on use)
    assert ri[0, R_GROWTH] == (0 if same else 1)


def stable_centre(heard_dirs: tuple[int, ...]) -> ETController:
    """Robot 0 Stable on (0, 0) of the hexagon (NN 6), hearing the holders of
    ``heard_dirs`` (robots 1..6 by direction) and nothing of the others."""
    ctl = ETController(7, HEXAGON, ETParams(), TPS)
    ri = ctl.ri
    ri[0, R_STATE], ri[0, R_HAS_TAG], ri[0, R_NN] = State.STABLE, 1, 6
    ri[0, R_SEEN_FULL] = 63  # it heard all six itself when it became Stable
    for row, k in enumerate(heard_dirs):
        ctl.nb[0, row, NB_ID] = 1 + k
        ctl.nb[0, row, NB_STATE] = State.STABLE
        ctl.nb[0, row, NB_EPOCH] = 0
        ctl.nb[0, row, NB_TX], ctl.nb[0, row, NB_TY] = DIR_X[k], DIR_Y[k]
        ctl.nb_dist[0, row] = 40.0
    return ctl


def seconds_to_election(ctl: ETController, seconds: float) -> float | None:
    for tick in range(1, round(seconds * TPS)):
        ctl.nb[0, :, NB_LAST] = tick
        placed_rule(
            0, tick, ctl.ri, ctl.nb, ctl.nb_dist, ctl.gene_flag[0], ctl.ci, ctl.cf,
            ctl.held[0], ctl.slot_info[0, SLOT_WX], ctl.slot_info[0, SLOT_WY],
        )
        if ctl.ri[0, R_PHASE] == PHASE_ELECTING:
            return tick / TPS
    return None


def test_the_robot_that_started_it_notes_the_site_it_missed_and_then_excuses_it() -> None:
    heard = (0, 1, 3, 4, 5)
    ctl = stable_centre(heard)
    after = seconds_to_election(ctl, 60)
    assert after is not None and after <= ETParams().danger_timeout_s + 1
    assert ctl.ri[0, R_MISSING] == 1 << 2
    excused = stable_centre(heard)
    excused.ri[0, R_EXCUSED] = 1 << 2
    assert seconds_to_election(excused, 120) is None
    # ... but a second neighbour lost is damage again
    worse = stable_centre((0, 1, 3, 4))
    worse.ri[0, R_EXCUSED] = 1 << 2
    assert seconds_to_election(worse, 60) is not None


def formed_triangle(false_alarm: str) -> ETRun:
    run = ETRun(
        RunConfig(shape="triangle", seed=0, max_time_s=3 * 3600,
                  et=ETParams(false_alarm=false_alarm, **SESSION_34_FORMATION)),
                sim_params=NATIVE_MATHS
    )
    assert run.run()["formed"]
    return run


def mute(run: ETRun, robot: int, seconds: float) -> None:
    """Robot ``robot`` neither sends nor hears for ``seconds``, then comes back."""
    run.world.alive[robot] = False
    run.advance(round(seconds * TPS))
    run.world.alive[robot] = True


@pytest.mark.parametrize("false_alarm", ["resume", "regrow"])
def test_a_robot_silent_for_a_while_starts_a_false_alarm(false_alarm: str) -> None:
    run = formed_triangle(false_alarm)
    tags = run.controller.tags.copy()
    pos = run.world.pos.copy()
    n = run.world.n
    mute(run, 7, 15.0)
    seen: set[int] = set()
    for _ in range(20 * 60):
        run.advance(TPS)
        seen |= {int(s) for s in run.controller.states}
    events = run.events
    census = [e for e in events if e["kind"] == "census"]
    assert len(census) == 1 and census[0]["count"] == census[0]["robots"] == n
    kept = [e for e in events if e["kind"] == "target_kept"]
    summary = run.summary()
    assert summary["duplicate_tags"] == [] and summary["max_leaders_per_component"] <= 1
    assert run.formed() and summary["states"]["Stable"] == n
    lines = describe(summary)
    if false_alarm == "resume":
        # nothing moved, nothing regrew
        assert len(kept) == 1
        assert "elections: 1, 1 of them false alarms (nobody lost: the target kept)" in lines
        assert np.array_equal(run.controller.tags, tags)
        assert np.abs(run.world.pos - pos).max() < 1.0
        assert State.DANGER in seen and seen <= {State.STABLE, State.DANGER, State.LEADER}
        # epoch 1's target, but still the first formation's growth and rules
        ri = run.controller.ri
        assert set(ri[:, R_EPOCH]) == {1} and set(ri[:, R_GROWTH]) == {0}
    else:
        assert kept == [] and "elections: 1" in lines
        assert State.INACTIVE in seen  # it grew again from its seeds
        assert set(run.controller.ri[:, R_GROWTH]) == {1}
