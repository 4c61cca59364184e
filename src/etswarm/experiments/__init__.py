"""Experiments at scale: sweep specs, the Dask sweep runner, the results table, reports.

Public API::

    load_spec(path) -> SweepSpec              # TOML spec -> validated runs
    run_sweep(spec, out_dir, scheduler=None, workers=None, retry_failed=False)
        -> SweepOutcome                        # runs on Dask, one JSON record per run
    read_table(results) -> (DataFrame, meta)  # results.parquet or a sweep folder
    write_report(results, out_dir) -> ReportFiles

Heavy imports (dask, matplotlib) happen in the submodules, not here.
"""

from etswarm.experiments.spec import DEFAULT_TASK, Run, SweepSpec, load_spec, parse_spec, run_id

__all__ = ["DEFAULT_TASK", "Run", "SweepSpec", "load_spec", "parse_spec", "run_id"]
