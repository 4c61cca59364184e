"""How far the robots of a first formation stand off their sites when it completes.

For each seed, runs SHAPE until it forms (or ``--max-time``) and lists the robots that
stand more than ``--over`` mm off their site's centre on the rigid fit of every robot's
tag to where it stands, with their own offset estimate (``offsets``) beside it. A robot
that stands far off and knows it shows both numbers large; a lattice bent as a whole
shows large fit distances but small estimates.

    .venv/bin/python benchmarks/offsets_at_formed.py starfish --seeds 20 --jobs 2
"""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor

import click
import numpy as np

from etswarm.algorithm.memory import R_OFF_X, R_OFF_Y
from etswarm.algorithm.offsets import FINE_PER_MM
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.errors import EtswarmError
from etswarm.measures.formation import fit_residuals_mm
from etswarm.shapes import load_shape

#: Simulated s between the checks for formation.
CHECK_S = 30.0


def far_off(shape: str, seed: int, max_time_s: float, over_mm: float) -> dict:
    """One run: whether and when it formed, and (robot, mm off the fit, mm by its own
    estimate) for each robot more than ``over_mm`` off the fit."""
    run = ETRun(RunConfig(shape=shape, seed=seed, max_time_s=max_time_s))
    end = round(max_time_s * run.ticks_per_s)
    while not run.formed() and run.world.tick < end:
        run.advance(min(round(CHECK_S * run.ticks_per_s), end - run.world.tick))
    ctl = run.controller
    rows = []
    if run.formed():  # (every robot holds a site: robots = cells)
        every = np.ones(run.world.n, dtype=bool)
        resid = fit_residuals_mm(run.world.pos, ctl.tags, every, run.config.et.spacing_mm)
        off_fit = np.linalg.norm(resid, axis=1)
        estimate = np.hypot(ctl.ri[:, R_OFF_X], ctl.ri[:, R_OFF_Y]) / FINE_PER_MM
        rows = [(int(r), round(float(off_fit[r]), 1), round(float(estimate[r]), 1))
                for r in np.flatnonzero(off_fit > over_mm)]
    return {"seed": seed, "formed": run.formed(), "t_s": round(run.sim_time_s), "far": rows}


@click.command()
@click.argument("shape")
@click.option("--seeds", default=20, show_default=True, type=click.IntRange(min=1))
@click.option("--first-seed", default=0, show_default=True)
@click.option("--max-time", default=14400.0, show_default=True, help="Simulated s per run.")
@click.option("--over", "over_mm", default=20.0, show_default=True,
              help="List robots farther than this (mm) off the fit.")
@click.option("--jobs", default=1, show_default=True, type=click.IntRange(min=1),
              help="Worker processes.")
def main(shape: str, seeds: int, first_seed: int, max_time: float, over_mm: float,
         jobs: int) -> None:
    """Robots far off their sites when SHAPE forms, seed by seed."""
    try:
        load_shape(shape)
    except EtswarmError as err:
        raise click.ClickException(str(err)) from None
    seed_list = list(range(first_seed, first_seed + seeds))
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        results = pool.map(far_off, [shape] * seeds, seed_list, [max_time] * seeds,
                           [over_mm] * seeds)
        for r in results:
            if not r["formed"]:
                print(f"seed {r['seed']}: not formed in {r['t_s']} s")
                continue
            listed = ", ".join(f"{rid} ({fit} / {est})" for rid, fit, est in r["far"])
            print(f"seed {r['seed']}: formed at {r['t_s']} s; {len(r['far'])} robots over "
                  f"{over_mm:.0f} mm (ID (mm off the fit / own estimate)): {listed}")


if __name__ == "__main__":
    main()
