"""How a shape's holes were closed: who took the last free site of a hole's edge, and
who was inside then.

For each seed, runs SHAPE (a shape with a hole, ``O``) until it forms or its time limit,
checking every ``--every`` simulated seconds which sites of the holes' edges are held.
When the last of them is taken, it prints the time, the robot that took it, the sightings
of searchers in the hole that robot knew at the check before (``hole_watch``: searcher ID
and age in seconds then; a sighting younger than ``hole_watch_s`` would have kept it from
walling the hole off) and the searchers standing in the hole at that check
(``measures.formation.in_holes``). A hole closed with searchers inside shuts them in for
good. Used for ``O`` seed 200 in session 64 (``docs/algorithm.md``).

    .venv/bin/python benchmarks/hole_seal.py O --seeds 20 --first-seed 200 \\
        [--et hole_watch_s=0] [--every 10]
"""

from __future__ import annotations

import click
import numpy as np
from hole_ends import run_options

from etswarm.algorithm.memory import R_WATCH_ID0, R_WATCH_ID1, R_WATCH_T0, R_WATCH_T1
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError
from etswarm.measures.formation import in_holes
from etswarm.shapes.lattice import hole_edge_cells


def sealing(run: ETRun, every_ticks: int, max_ticks: int) -> dict[str, object] | None:
    """Run until the holes' edges are all held (or the run ends); what stood then."""
    edge = {(x, y) for x, y in hole_edge_cells(run.target).tolist()}
    if not edge:
        raise click.ClickException("the shape has no hole")
    free_before: set[tuple[int, int]] = set(edge)
    fields = [R_WATCH_ID0, R_WATCH_T0, R_WATCH_ID1, R_WATCH_T1]
    # every robot's sightings at the check before: a closer notes new ones once placed
    watch_before = run.controller.ri[:, fields].copy()
    tick_before = run.world.tick
    while not run.finished and run.world.tick < max_ticks:
        run.advance(min(every_ticks, max_ticks - run.world.tick))
        holds = run.controller.holds_site & run.world.alive
        tags = run.controller.tags
        held = {(int(x), int(y)) for x, y in tags[holds]}
        free = edge - held
        if free:
            free_before = free
            watch_before = run.controller.ri[:, fields].copy()
            tick_before = run.world.tick
            continue
        closers = [int(i) for i in np.nonzero(holds)[0]
                   if (int(tags[i, 0]), int(tags[i, 1])) in free_before]
        known = {}
        for i in closers:
            for f in (0, 2):
                if watch_before[i, f] >= 0:
                    age = (tick_before - watch_before[i, f + 1]) / run.ticks_per_s
                    known[int(watch_before[i, f])] = round(age)
        searching = np.nonzero(run.controller.states == State.SEARCH)[0]
        inside = searching[in_holes(run.world.pos[searching], run.world.pos, tags, holds,
                                    run.target, run.config.et.spacing_mm)] if len(searching) else []
        return {"t_s": run.sim_time_s, "closers": closers, "sites": sorted(free_before),
                "sightings_s": known, "inside": [int(i) for i in inside]}
    return None


@click.command()
@run_options
@click.option("--every", "every_s", default=10.0, show_default=True,
              type=click.FloatRange(min=0.1), help="simulated s between checks")
def main(shape: str, seeds: int, first_seed: int, max_time_s: float, et: ETParams,
         every_s: float) -> None:
    """Print how each run of SHAPE closed its holes."""
    shut_in = 0
    for seed in range(first_seed, first_seed + seeds):
        try:
            run = ETRun(RunConfig(shape=shape, seed=seed, max_time_s=max_time_s, et=et))
        except EtswarmError as err:
            raise click.ClickException(str(err)) from None
        every = max(1, round(every_s * run.ticks_per_s))
        seal = sealing(run, every, round(max_time_s * run.ticks_per_s))
        if seal is None:
            print(f"seed {seed}: the holes' edges never all held", flush=True)
            continue
        shut_in += bool(seal["inside"])
        print(f"seed {seed}: closed at {seal['t_s']:.0f} s by {seal['closers']} on "
              f"{seal['sites']}; sightings it knew (searcher: age s) {seal['sightings_s']}; "
              f"in the hole then {seal['inside']}", flush=True)
    print(f"{shut_in} of {seeds} runs closed a hole with searchers inside")


if __name__ == "__main__":
    main()
