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
def sweep(
    spec_file: Path,
    out_dir: Path | None,
    scheduler: str | None,
    workers: int | None,
    retry_failed: bool,
    no_progress: bool,
) -> None:
    """Run every grid point x seed of SPEC.toml on Dask; results go to OUT.

    Each finished run is kept in OUT/runs/<run id>.json at once, so an interrupted sweep
    loses nothing: run the same command again and it resumes. OUT/results.parquet holds
    one row per run.
    """
    from etswarm.experiments.runner import run_sweep
    from etswarm.experiments.spec import load_spec

    spec = load_spec(spec_file)
    if out_dir is None:
        out_dir = spec_file.parent / "sweeps" / spec.name
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
