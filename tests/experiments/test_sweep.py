"""The sweep runner on a real Dask LocalCluster over loopback: table, crashes, resume."""

from __future__ import annotations

import glob
import json
import os
import signal
import subprocess
import sys
import time
from collections import Counter
from collections.abc import Callable
from pathlib import Path

import pandas as pd
import pytest

from etswarm.cli.main import main as cli_main
from etswarm.errors import EtswarmError
from etswarm.experiments.runner import check_task, interrupt_signals, run_sweep
from etswarm.experiments.spec import load_spec, run_id
from etswarm.experiments.store import RunStore

SPEC = """
[sweep]
name = "small"
task = "fake_task:run"
seeds = [0, 1, 2]

[fixed]
log = "{log}"
crash_robots = 13
sleep_s = {sleep}

[grid]
robots = [10, 13]
loss = [0.0, 0.2]
"""


def executions(log: Path) -> Counter[str]:
    """How many times the fake task started each run id (from its log)."""
    if not log.exists():
        return Counter()
    lines = log.read_text(encoding="utf-8").splitlines()
    return Counter(run_id(json.loads(line)) for line in lines)


@pytest.fixture
def make_spec(write_spec: Callable[..., Path]) -> Callable[..., tuple[Path, Path]]:
    """``make_spec(folder, sleep)``: the 2x2 grid x 3 seeds spec and its call log path."""

    def make(folder: Path, sleep: float = 0.02) -> tuple[Path, Path]:
        log = folder / "calls.log"
        return write_spec(folder, SPEC.format(log=log, sleep=sleep)), log

    return make


def test_sweep_writes_records_and_table_and_records_crashes(
    tmp_path: Path, scheduler_address: str, make_spec: Callable[..., tuple[Path, Path]]
) -> None:
    spec_path, log = make_spec(tmp_path)
    spec = load_spec(spec_path)
    out = tmp_path / "out"
    outcome = run_sweep(spec, out, scheduler=scheduler_address, show_progress=False)
    assert (outcome.total, outcome.ran, outcome.failed, outcome.skipped) == (12, 12, 6, 0)
    assert not outcome.interrupted and outcome.kept == 12
    assert sorted(executions(log).values()) == [1] * 12
    assert len(list((out / "runs").glob("*.json"))) == 12
    assert (out / "spec.toml").read_text() == spec_path.read_text()

    table = pd.read_parquet(out / "results.parquet")
    assert len(table) == 12
    assert set(table["run_id"]) == {r.run_id for r in spec.runs()}
    for column in ("robots", "loss", "seed", "status", "error", "formed", "formation_time_s",
                   "jaccard", "states.Stable", "n_components", "component_jaccard_mean",
                   "census_error_mean", "wall_time_s", "version"):
        assert column in table.columns, column
    crashed = table[table["robots"] == 13]
    assert (crashed["status"] == "error").all() and len(crashed) == 6
    assert crashed["error"].eq("ValueError: fake task crashed on robots=13").all()
    fine = table[table["robots"] == 10]
    assert (fine["status"] == "ok").all() and fine["error"].isna().all()
    assert fine["formation_time_s"].notna().any()

    one = RunStore(out).read(crashed["run_id"].iloc[0])
    assert one is not None and "Traceback" in one["traceback"]


def test_rerun_skips_finished_runs_and_retries_failed_only_on_request(
    tmp_path: Path, scheduler_address: str, make_spec: Callable[..., tuple[Path, Path]]
) -> None:
    spec_path, log = make_spec(tmp_path)
    spec = load_spec(spec_path)
    out = tmp_path / "out"
    run_sweep(spec, out, scheduler=scheduler_address, show_progress=False)

    again = run_sweep(spec, out, scheduler=scheduler_address, show_progress=False)
    assert (again.ran, again.skipped) == (0, 12)
    assert sum(executions(log).values()) == 12

    # records lost as if the sweep had been killed before they finished
    store = RunStore(out)
    ok_ids = [r.run_id for r in spec.runs() if store.status(r.run_id) == "ok"]
    for rid in ok_ids[:2]:
        store.record_path(rid).unlink()
    resumed = run_sweep(spec, out, scheduler=scheduler_address, show_progress=False)
    assert (resumed.ran, resumed.skipped, resumed.failed) == (2, 10, 0)
    counts = executions(log)
    assert {rid for rid, n in counts.items() if n == 2} == set(ok_ids[:2])

    retried = run_sweep(
        spec, out, scheduler=scheduler_address, retry_failed=True, show_progress=False
    )
    assert (retried.ran, retried.failed, retried.skipped) == (6, 6, 6)
    assert len(pd.read_parquet(out / "results.parquet")) == 12


@pytest.mark.parametrize("how", ["ctrl-c", "sigterm"])
def test_interrupted_cli_sweep_keeps_results_and_resumes(
    tmp_path: Path,
    scheduler_address: str,
    make_spec: Callable[..., tuple[Path, Path]],
    how: str,
) -> None:
    """Ctrl-C (SIGINT to the whole process group) or SIGTERM to the sweep process alone,
    on a sweep with its own LocalCluster."""
    spec_path, log = make_spec(tmp_path, sleep=0.4)
    out = tmp_path / "out"
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    proc = subprocess.Popen(
        [sys.executable, "-m", "etswarm.cli.main", "sweep", str(spec_path),
         "--out", str(out), "--workers", "2", "--no-progress"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
        start_new_session=True,
    )
    deadline = time.monotonic() + 60
    while len(glob.glob(str(out / "runs" / "*.json"))) < 3 and time.monotonic() < deadline:
        time.sleep(0.05)
    if how == "ctrl-c":
        os.killpg(proc.pid, signal.SIGINT)
    else:
        os.kill(proc.pid, signal.SIGTERM)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Run the same command again to resume" in err
    assert "Traceback" not in err
    store = RunStore(out)
    kept = {p.stem for p in (out / "runs").glob("*.json")}
    assert 3 <= len(kept) < 12
    assert len(pd.read_parquet(out / "results.parquet")) == len(kept)

    outcome = run_sweep(
        load_spec(spec_path), out, scheduler=scheduler_address, show_progress=False
    )
    assert outcome.skipped == len(kept) and outcome.kept == 12
    counts = executions(log)
    assert all(counts[rid] == 1 for rid in kept), "a finished run was executed again"
    assert all(store.status(r.run_id) for r in load_spec(spec_path).runs())


def test_task_problems_fail_before_any_run(
    tmp_path: Path, write_spec: Callable[..., Path]
) -> None:
    text = '[sweep]\nname = "x"\ntask = "fake_task:absent"\nseeds = [0]\n'
    with pytest.raises(EtswarmError, match=r"sweep\.task: .*no function absent"):
        check_task(load_spec(write_spec(tmp_path, text)))
    text = '[sweep]\nname = "x"\ntask = "fake_task:strict"\nseeds = [0]\n[grid]\nrobot = [1]\n'
    with pytest.raises(EtswarmError, match=r"robot: not a parameter of fake_task:strict"):
        check_task(load_spec(write_spec(tmp_path, text)))


def test_cli_reports_spec_errors_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], write_spec: Callable[..., Path]
) -> None:
    path = write_spec(tmp_path, '[sweep]\nname = "x"\nseeds = [0]\n[grid]\nrobots = []\n')
    with pytest.raises(SystemExit) as info:
        cli_main(["sweep", str(path)])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert err.strip() == f"etswarm: error: {path}: grid.robots: empty list"


def test_dry_run_counts_runs_without_running(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    make_spec: Callable[..., tuple[Path, Path]],
) -> None:
    spec_path, log = make_spec(tmp_path)
    cli_main(["sweep", str(spec_path), "--out", str(tmp_path / "out"), "--dry-run"])
    out = capsys.readouterr().out
    expected = f"sweep small: 4 points, 12 runs; 0 kept in {tmp_path / 'out'}, 12 to run"
    assert out.startswith(expected)
    assert "... and 7 more" in out
    assert not log.exists()


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_interrupt_signals_are_remembered_and_handlers_restored(sig: int) -> None:
    """The first signal is only recorded (raising it could land in library cleanup, which
    prints a traceback); a second one raises while armed; the old handlers come back."""
    before = signal.getsignal(sig)

    def send_and_wait(seen: list[int], count: int) -> None:
        os.kill(os.getpid(), sig)
        deadline = time.monotonic() + 5
        while len(seen) < count and time.monotonic() < deadline:
            time.sleep(0.01)

    with interrupt_signals() as interrupts:
        send_and_wait(interrupts.seen, 1)
        send_and_wait(interrupts.seen, 2)  # not armed (a cluster starting): recorded only
        assert interrupts.seen == [sig, sig]
        interrupts.armed = True
        with pytest.raises(KeyboardInterrupt):
            os.kill(os.getpid(), sig)
            time.sleep(5)  # the handler runs at once; never reached
        assert interrupts.seen == [sig, sig, sig]
    assert signal.getsignal(sig) is before
