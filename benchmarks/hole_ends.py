"""Where runs of a shape with a hole end when they do not form: which sites stay free
(on the hole's edge or not) and how many searchers are shut in the hole.

Runs SHAPE for each seed to its time limit and prints one line per run that did not
form: the free tags, those on a hole's edge, whether they make a way across the ring (a
chain of free sites, six-neighbour steps, from a hole's edge to a site beside the
outside: every capture rule refuses its sites, session 64), the searchers and how many of
them stand in the hole (the nearest site of the lattice the Stable robots fit is a hole
site: ``measures.formation.in_holes``). Then the counts. Used for ``O`` ("Sessions 42-43"
and "Session 67" in docs/algorithm.md).

    .venv/bin/python benchmarks/hole_ends.py O --seeds 40 --first-seed 100 \\
        [--et hole_watch_s=0] [--max-time 14400]
"""

from __future__ import annotations

from collections.abc import Callable

import click
import numpy as np
from swarm_picture import et_params

from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError
from etswarm.measures.formation import in_holes, way_across
from etswarm.shapes.lattice import hole_edge_cells


def on_hole_edge(free: list[list[int]], target: np.ndarray) -> list[list[int]]:
    """The tags of ``free`` on the edge of a hole of ``target`` ((P, 2) tags)."""
    edge = {(x, y) for x, y in hole_edge_cells(target).tolist()}
    return [f for f in free if tuple(f) in edge]


def run_end(shape: str, seed: int, max_time_s: float, et: ETParams) -> dict[str, object]:
    """One run's end: formed, free tags, those on a hole's edge, searchers, in the hole."""
    run = ETRun(RunConfig(shape=shape, seed=seed, max_time_s=max_time_s, et=et))
    summary = run.run()
    states = run.controller.states
    searching = states == State.SEARCH
    stable = states == State.STABLE
    inside = 0
    if searching.any() and stable.sum() >= 2:
        inside = int(in_holes(run.world.pos[searching], run.world.pos, run.controller.tags,
                              stable, run.target, run.config.et.spacing_mm).sum())
    free = [t for c in summary["components"] for t in c.get("free_tags", [])]
    return {"seed": seed, "formed": summary["formed"], "free": free,
            "edge": on_hole_edge(free, run.target), "way": way_across(free, run.target),
            "searchers": int(searching.sum()), "in_hole": inside}


def run_options(command: Callable[..., None]) -> Callable[..., None]:
    """The arguments of the scripts that run a shape with a hole over seeds (this one and
    ``hole_seal.py``): SHAPE, ``--seeds``, ``--first-seed``, ``--max-time`` and ``--et``."""
    for decorate in reversed((
        click.argument("shape", default="O"),
        click.option("--seeds", default=20, show_default=True, type=click.IntRange(min=1)),
        click.option("--first-seed", default=0, show_default=True,
                     type=click.IntRange(min=0)),
        click.option("--max-time", "max_time_s", default=14400.0, show_default=True,
                     type=click.FloatRange(min=1.0), help="simulated s"),
        click.option("--et", "et", multiple=True, metavar="NAME=VALUE", callback=et_params,
                     help="an ETParams field (repeatable)"),
    )):
        command = decorate(command)
    return command


@click.command()
@run_options
def main(shape: str, seeds: int, first_seed: int, max_time_s: float, et: ETParams) -> None:
    """Print how each unformed run of SHAPE ends."""
    ends = []
    for seed in range(first_seed, first_seed + seeds):
        try:
            end = run_end(shape, seed, max_time_s, et)
        except EtswarmError as err:
            raise click.ClickException(str(err)) from None
        ends.append(end)
        if not end["formed"]:
            way = ", a way across" if end["way"] else ""
            print(f"seed {seed}: free {end['free']}, on the hole's edge {end['edge']}{way}, "
                  f"{end['searchers']} searching, {end['in_hole']} in the hole", flush=True)
    unformed = [e for e in ends if not e["formed"]]
    shut_in = sum(1 for e in unformed if e["in_hole"] > 0)
    edge_free = sum(1 for e in unformed if e["edge"])
    ways = sum(1 for e in unformed if e["way"])
    print(f"{len(ends) - len(unformed)} of {len(ends)} formed; of the {len(unformed)} others, "
          f"{shut_in} with a searcher in the hole, {edge_free} with a free site on the "
          f"hole's edge, {ways} on a way across; searchers in holes "
          f"{int(np.sum([e['in_hole'] for e in unformed]))}")


if __name__ == "__main__":
    main()
