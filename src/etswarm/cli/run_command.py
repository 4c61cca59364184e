"""``etswarm run``: grow a shape headless and print a summary."""

from __future__ import annotations

import json
from pathlib import Path

import click

from etswarm.algorithm.layout import LAYOUTS


def _hms(seconds: float) -> str:
    s = round(seconds)
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}"


@click.command()
@click.argument("shape")
@click.option("--robots", type=int, default=None, help="Swarm size (default: cells of the shape).")
@click.option("--seed", type=int, default=0, show_default=True)
@click.option("--loss", type=float, default=0.2, show_default=True, help="Message loss.")
@click.option("--noise", type=float, default=2.0, show_default=True, help="Distance noise, mm.")
@click.option("--max-time", type=float, default=3 * 3600.0, show_default=True,
              help="Simulated seconds before giving up.")
@click.option("--layout", type=click.Choice(LAYOUTS), default="queue", show_default=True)
@click.option("--release-interval", type=float, default=None,
              help="Seconds between releases from the repository.")
@click.option("--fit", is_flag=True, help="With fewer robots than cells, form scale(shape, N).")
@click.option("--out", type=click.Path(path_type=Path), default=None,
              help="Directory for summary.json.")
@click.option("--json", "as_json", is_flag=True, help="Print only the JSON summary.")
def run(shape: str, robots: int | None, seed: int, loss: float, noise: float, max_time: float,
        layout: str, release_interval: float | None, fit: bool, out: Path | None,
        as_json: bool) -> None:
    """Grow SHAPE (a library name or a bitmap file) with the ET algorithm."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    from etswarm.algorithm.params import ETParams
    from etswarm.algorithm.run import ETRun, RunConfig

    et = ETParams() if release_interval is None else ETParams(release_interval_s=release_interval)
    config = RunConfig(shape=shape, robots=robots, seed=seed, loss=loss, noise_mm=noise,
                       max_time_s=max_time, layout=layout, fit=fit, et=et)
    et_run = ETRun(config)
    for note in et_run.notes:
        click.echo(f"etswarm: {note}", err=True)
    with Progress(
        TextColumn("[bold]{task.description}"), BarColumn(), TextColumn("{task.fields[status]}"),
        TimeElapsedColumn(), transient=True, disable=as_json,
    ) as bar:
        task = bar.add_task(f"forming {shape}", total=max_time, status="")

        def progress(r: ETRun) -> None:
            states = r.controller.states
            placed = int((states >= 2).sum())
            bar.update(task, completed=r.sim_time_s,
                       status=f"sim {_hms(r.sim_time_s)}  placed {placed}/{len(r.target)}")

        summary = et_run.run(progress)
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    if as_json:
        click.echo(json.dumps(summary))
        return
    t = summary["formation_time_s"]
    click.echo(
        f"{shape}: {'formed' if summary['formed'] else 'NOT formed'}"
        + (f" in {_hms(t)} simulated" if t is not None else "")
        + f"; {summary['robots']} robots, jaccard {summary['jaccard']:.3f}, "
        f"placement error {summary['placement_error_mm']} mm, "
        f"wall {summary['wall_time_s']:.1f} s, "
        f"x{summary['sim_time_s'] / max(summary['wall_time_s'], 1e-9):.0f} real time"
    )
    click.echo("states: " + ", ".join(f"{k} {v}" for k, v in summary["states"].items() if v))
