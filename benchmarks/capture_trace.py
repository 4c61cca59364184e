"""How one searcher took its site: its last readings of placed robots before the capture,
and how far off the site it stood.

Runs SHAPE to ``--from`` simulated s, then tick by tick until robot ROBOT stops searching
(it took a site, or the time limit came). Prints the site it took, its distance from that
site's centre on the rigid fit of all placed robots (``measures.formation.rigid_fit``)
and its own offset estimate a few seconds later; then, every ``--every`` ticks over its
last ``--ticks`` ticks of searching, where it stood and the placed robots it heard within
3 s: ID, tag, the distance it reads (``nb_dist``) and the true distance.

    .venv/bin/python benchmarks/capture_trace.py starfish 74 --seed 222 --from 7700
"""

from __future__ import annotations

import click
import numpy as np

from etswarm.algorithm.memory import NB_ID, NB_LAST, NB_STATE, NB_TX, NB_TY, R_OFF_X, R_OFF_Y
from etswarm.algorithm.offsets import FINE_PER_MM
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError
from etswarm.measures.formation import fit_residuals_mm

#: Readings older than this (s) are left out of a line.
FRESH_S = 3.0
#: After the capture, the robot's offset estimate is read this much later (s).
SETTLE_S = 5.0


def heard_placed(run: ETRun, robot: int) -> list[tuple[int, int, int, float, float]]:
    """The placed robots ``robot`` heard within ``FRESH_S``: (ID, tag x, tag y, distance
    read (mm), true distance (mm)), nearest first."""
    ctl = run.controller
    rows = []
    for m in range(ctl.nb.shape[1]):
        sid = int(ctl.nb[robot, m, NB_ID])
        if sid < 0 or not State.INACTIVE <= ctl.nb[robot, m, NB_STATE] <= State.STABLE:
            continue
        if run.world.tick - ctl.nb[robot, m, NB_LAST] > FRESH_S * run.ticks_per_s:
            continue
        true_mm = float(np.hypot(*(run.world.pos[sid] - run.world.pos[robot])))
        rows.append((sid, int(ctl.nb[robot, m, NB_TX]), int(ctl.nb[robot, m, NB_TY]),
                     round(float(ctl.nb_dist[robot, m]), 1), round(true_mm, 1)))
    return sorted(rows, key=lambda row: row[4])


def off_fit_mm(run: ETRun, robot: int) -> float:
    """Distance (mm) of placed ``robot`` from its site's centre on the rigid fit of every
    placed robot's tag to where it stands (``measures.formation.fit_residuals_mm``)."""
    ctl = run.controller
    placed = (ctl.states >= State.INACTIVE) & (ctl.states <= State.STABLE)
    resid = fit_residuals_mm(run.world.pos, ctl.tags, placed, run.config.et.spacing_mm)
    if resid is None:
        return float("nan")
    return float(np.hypot(*resid[np.count_nonzero(placed[:robot])]))


@click.command()
@click.argument("shape")
@click.argument("robot", type=int)
@click.option("--seed", default=0, show_default=True)
@click.option("--from", "from_s", default=0.0, show_default=True,
              help="Simulated s to run before watching.")
@click.option("--max-time", default=14400.0, show_default=True, help="Simulated s in all.")
@click.option("--ticks", default=60, show_default=True, type=click.IntRange(min=1),
              help="Ticks of searching shown.")
@click.option("--every", default=6, show_default=True, type=click.IntRange(min=1),
              help="A line every this many ticks.")
def main(shape: str, robot: int, seed: int, from_s: float, max_time: float, ticks: int,
         every: int) -> None:
    """Watch ROBOT of a SHAPE run take its site."""
    try:
        run = ETRun(RunConfig(shape=shape, seed=seed, max_time_s=max_time))
    except EtswarmError as err:
        raise click.ClickException(str(err)) from None
    if not 0 <= robot < run.world.n:
        raise click.BadParameter(f"no robot {robot} (the run has {run.world.n})",
                                 param_hint="ROBOT")
    tps = run.ticks_per_s
    end = round(max_time * tps)
    run.advance(min(round(from_s * tps), end))
    if run.controller.states[robot] != State.SEARCH:
        raise click.ClickException(
            f"robot {robot} is {State(run.controller.states[robot]).name} at "
            f"{run.sim_time_s:.0f} s, not searching: pick an earlier --from"
        )
    history: list[tuple[float, np.ndarray, list]] = []
    while run.controller.states[robot] == State.SEARCH and run.world.tick < end:
        run.advance(1)
        history.append((run.sim_time_s, run.world.pos[robot].copy(), heard_placed(run, robot)))
        history = history[-ticks:]
    state = State(run.controller.states[robot])
    if state == State.SEARCH:
        print(f"robot {robot} was still searching at {run.sim_time_s:.0f} s")
    else:
        tag = tuple(int(v) for v in run.controller.tags[robot])
        print(f"robot {robot} took {tag} at {run.sim_time_s:.2f} s ({state.name}), "
              f"{off_fit_mm(run, robot):.1f} mm off the rigid fit's site")
        run.advance(round(SETTLE_S * tps))
        ri = run.controller.ri
        off = np.hypot(ri[robot, R_OFF_X], ri[robot, R_OFF_Y]) / FINE_PER_MM
        print(f"its own offset estimate {SETTLE_S:.0f} s later: {off:.1f} mm")
    print("time s, position mm, placed robots heard (ID, tag x, tag y, read mm, true mm)")
    for t_s, pos, rows in history[::every]:
        print(f"{t_s:9.2f}  ({pos[0]:7.1f}, {pos[1]:7.1f})  {rows}")


if __name__ == "__main__":
    main()
