"""Where every robot of a formation stands at one moment, and what its searchers are doing.

Runs SHAPE (a shape argument, or a written disc of ``bench_et.DISCS`` such as disc1000)
to ``--at`` simulated s and draws one PNG: Queued robots grey, placed robots green, and
the searchers in three kinds (never at the shape yet, at the shape, lost: they hear no
stationary robot). Prints the counts. Used to see why large formations pile searchers up
("Session 40" in docs/algorithm.md).

    .venv/bin/python benchmarks/swarm_picture.py disc1000 --layout cluster --at 5400 \\
        --png disc1000.png
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import click
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from bench_et import shape_path

from etswarm.algorithm.memory import R_LOST_SINCE, R_SHAPE_SINCE
from etswarm.algorithm.params import ETParams, parse_et_option
from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.algorithm.states import State
from etswarm.errors import EtswarmError


def et_params(_ctx: click.Context, _param: click.Parameter, options: tuple[str, ...]) -> ETParams:
    """``--et NAME=VALUE`` options as ETParams (a bad one is a usage error, not a traceback)."""
    try:
        return ETParams(**dict(parse_et_option(o) for o in options))
    except EtswarmError as err:
        raise click.BadParameter(str(err)) from None


def robot_kinds(run: ETRun) -> dict[str, np.ndarray]:
    """Boolean masks (N,) of the run's robots by kind: queued, placed, and searchers
    never at the shape, at the shape (not lost) and lost."""
    states = run.controller.states
    ri = run.controller.ri
    search = states == State.SEARCH
    lost = search & (ri[:, R_LOST_SINCE] != 0)
    at_shape = search & ~lost & (ri[:, R_SHAPE_SINCE] != 0)
    return {
        "queued": states == State.QUEUED,
        "placed": (states >= State.INACTIVE) & (states <= State.STABLE),
        "searching, never at the shape": search & ~lost & ~at_shape,
        "searching at the shape": at_shape,
        "lost": lost,
    }


@click.command()
@click.argument("shape")
@click.option("--seed", default=0, show_default=True)
@click.option("--at", "at_s", default=5400.0, show_default=True,
              type=click.FloatRange(min=0.0), help="Simulated s.")
@click.option("--layout", type=click.Choice(["queue", "cluster"]), default="cluster",
              show_default=True)
@click.option("--et", "et", multiple=True, metavar="NAME=VALUE", callback=et_params,
              help="An ETParams option (repeatable).")
@click.option("--png", type=click.Path(dir_okay=False), default="swarm.png", show_default=True)
def main(shape: str, seed: int, at_s: float, layout: str, et: ETParams, png: str) -> None:
    """Draw SHAPE's robots at --at simulated s."""
    try:
        config = RunConfig(shape=shape_path(shape, Path(tempfile.mkdtemp())), seed=seed,
                           max_time_s=at_s + 1.0, layout=layout, et=et)
        run = ETRun(config)
    except EtswarmError as err:
        raise click.ClickException(str(err)) from None
    run.advance(round(at_s * run.ticks_per_s))
    colours = {"queued": "lightgrey", "placed": "green", "searching, never at the shape": "blue",
               "searching at the shape": "orange", "lost": "red"}
    fig, ax = plt.subplots(figsize=(10, 10))
    for kind, mask in robot_kinds(run).items():
        ax.scatter(*run.world.pos[mask].T, s=8, c=colours[kind], label=f"{kind}: {mask.sum()}")
        print(f"{kind}: {mask.sum()}")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"{shape}, seed {seed}, {layout}, {at_s:.0f} s")
    ax.legend(loc="upper right")
    fig.savefig(png, dpi=90)
    print(f"picture: {png}")


if __name__ == "__main__":
    main()
