"""``etswarm sweep``, ``etswarm report`` and ``etswarm reproduce``: experiments at scale."""

from __future__ import annotations

import sys
from pathlib import Path

import click


@click.command()
@click.argument("spec_file", metavar="SPEC.toml", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "--out",
    "out_dir",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="Output folder (default: sweeps/<sweep name> next to the spec).",
)
@click.option(
    "--scheduler",
    default=None,
    metavar="ADDRESS",
    help="Dask scheduler of an existing cluster, e.g. tcp://10.0.0.5:8786.",
)
@click.option(
    "--workers",
    type=int,
    default=None,
    help="Worker processes of the local cluster (default: every core).",
)
@click.option("--retry-failed", is_flag=True, help="Run again the runs recorded as failed.")
@click.option("--no-progress", is_flag=True, help="No progress display.")
@click.option("--dry-run", is_flag=True, help="Only say how many runs there are and are left.")
def sweep(
    spec_file: Path,
    out_dir: Path | None,
    scheduler: str | None,
    workers: int | None,
    retry_failed: bool,
    no_progress: bool,
    dry_run: bool,
) -> None:
    """Run every grid point x seed of SPEC.toml on Dask; results go to OUT.

    Each finished run is kept in OUT/runs/<run id>.json at once, so an interrupted sweep
    loses nothing: run the same command again and it resumes. OUT/results.parquet holds
    one row per run.
    """
    from etswarm.experiments.runner import check_task, plan_runs, run_sweep
    from etswarm.experiments.spec import canonical_json, load_spec
    from etswarm.experiments.store import RunStore

    spec = load_spec(spec_file)
    if out_dir is None:
        out_dir = spec_file.parent / "sweeps" / spec.name
    if dry_run:
        check_task(spec)
        todo, skipped = plan_runs(spec, RunStore(out_dir), retry_failed)
        click.echo(
            f"sweep {spec.name}: {len(spec.points)} points, {len(spec.runs())} runs;"
            f" {skipped} kept in {out_dir}, {len(todo)} to run; task {spec.task}"
        )
        for run in todo[:5]:
            click.echo(f"  {run.run_id}  {canonical_json(run.params)}")
        if len(todo) > 5:
            click.echo(f"  ... and {len(todo) - 5} more")
        return
    outcome = run_sweep(
        spec,
        out_dir,
        scheduler=scheduler,
        workers=workers,
        retry_failed=retry_failed,
        show_progress=not no_progress,
    )
    if outcome.interrupted:
        click.echo(
            f"etswarm: interrupted: {outcome.kept} of {outcome.total} runs are kept in"
            f" {outcome.out_dir / 'runs'} ({outcome.ran} finished in this session,"
            f" {outcome.pending} cancelled); table written to {outcome.table}."
            " Run the same command again to resume.",
            err=True,
        )
        sys.exit(130)
    failed_total = outcome.failed
    click.echo(
        f"sweep {spec.name}: {outcome.total} runs, {outcome.ran} run now"
        f" ({outcome.failed} failed), {outcome.skipped} kept from before;"
        f" table: {outcome.table}",
        err=True,
    )
    if failed_total:
        click.echo(
            "  failed runs are recorded with their error in runs/*.json;"
            " use --retry-failed to run them again",
            err=True,
        )


@click.command()
@click.argument("results", type=click.Path(exists=True, path_type=Path))
@click.option(
    "--out",
    "out_dir",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="Folder for the plots and report.md (default: RESULTS/report).",
)
def report(results: Path, out_dir: Path | None) -> None:
    """Plots and a Markdown summary of a sweep (a sweep folder or its results.parquet)."""
    from etswarm.experiments.report import write_report

    if out_dir is None:
        base = results if results.is_dir() else results.parent
        out_dir = base / "report"
    written = write_report(results, out_dir)
    click.echo(written.markdown_path.read_text(encoding="utf-8"))
    click.echo(f"report written to {written.markdown_path}", err=True)


@click.command()
@click.option(
    "--out",
    "out_dir",
    type=click.Path(file_okay=False, path_type=Path),
    default=Path("paper"),
    show_default=True,
    help="Output folder: sweep, figures and report.md.",
)
@click.option(
    "--seeds", type=click.IntRange(min=1), default=20, show_default=True,
    help="Seeds of T at loss 0.2 (the comparison table).",
)
@click.option(
    "--shape-seeds", type=click.IntRange(min=1), default=None,
    help="Seeds of the dumbbell and starfish (default: seeds / 2); the cut T gets half.",
)
@click.option(
    "--max-time", "max_time_s", type=click.FloatRange(min=1.0), default=4 * 3600.0,
    show_default=True, help="Simulated seconds a run may take.",
)
@click.option("--workers", type=int, default=None, help="Local worker processes (default: all).")
@click.option("--scheduler", default=None, metavar="ADDRESS", help="Existing Dask scheduler.")
@click.option("--no-progress", is_flag=True, help="No progress display.")
def reproduce(
    out_dir: Path,
    seeds: int,
    shape_seeds: int | None,
    max_time_s: float,
    workers: int | None,
    scheduler: str | None,
    no_progress: bool,
) -> None:
    """Re-run the paper's experiments and compare our numbers with the paper's.

    Figures 5, 6, 8, 9 and 10 of the paper and its T formation time (2 h 50 min 8 s), over
    SEEDS seeds. The runs are one sweep in OUT/sweep, so an interrupted reproduction resumes
    when run again; OUT/report.md holds the comparison table and the figures.
    """
    from etswarm.experiments.reproduce import reproduce as run_reproduction

    done = run_reproduction(
        out_dir,
        seeds=seeds,
        shape_seeds=shape_seeds,
        max_time_s=max_time_s,
        workers=workers,
        scheduler=scheduler,
        show_progress=not no_progress,
    )
    outcome = done.sweep
    if outcome.interrupted or done.report is None:
        click.echo(
            f"etswarm: interrupted: {outcome.kept} of {outcome.total} runs are kept in"
            f" {outcome.out_dir / 'runs'}. Run the same command again to resume.",
            err=True,
        )
        sys.exit(130)
    click.echo(done.report.read_text(encoding="utf-8"))
    click.echo(f"report written to {done.report}", err=True)
