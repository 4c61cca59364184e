"""Runner pieces without a cluster: lost futures, records of another task, progress display."""

from __future__ import annotations

import io
from collections.abc import Callable
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from distributed import KilledWorker
from distributed.client import FutureCancelledError
from rich.console import Console

from etswarm.experiments.progress import SweepProgress
from etswarm.experiments.runner import _collect, plan_runs
from etswarm.experiments.spec import Run, load_spec
from etswarm.experiments.store import RunStore
from etswarm.experiments.task import execute_run


class StubFuture:
    """Just what ``_collect`` reads from a distributed.Future."""

    def __init__(self, status: str, result: Any = None, error: BaseException | None = None):
        self.status = status
        self._result = result
        self._error = error

    def result(self) -> Any:
        if self._error is not None:
            raise self._error
        return self._result


def test_a_lost_worker_is_an_error_record_and_a_cancelled_future_is_no_record() -> None:
    run = Run("abc", {"robots": 3, "seed": 0})
    last_worker = SimpleNamespace(address="tcp://127.0.0.1:4000")
    died = KilledWorker("etswarm-run-abc", last_worker, 3)
    record = _collect(StubFuture("error", error=died), run, "m:f")
    assert record is not None
    assert record["status"] == "error" and record["run_id"] == "abc"
    assert record["error"].startswith("KilledWorker: ") and "\n" not in record["error"]
    assert "KilledWorker" in record["traceback"]
    assert _collect(StubFuture("cancelled"), run, "m:f") is None
    lost = StubFuture("error", error=FutureCancelledError("etswarm-run-abc", "cancelled"))
    assert _collect(lost, run, "m:f") is None
    assert _collect(StubFuture("finished", result={"run_id": "abc"}), run, "m:f") == {
        "run_id": "abc"
    }


def test_records_of_another_task_do_not_count_as_done(
    tmp_path: Path, write_spec: Callable[..., Path]
) -> None:
    spec = load_spec(
        write_spec(tmp_path, '[sweep]\nname = "x"\ntask = "fake_task:run"\nseeds = [0, 1]\n')
    )
    store = RunStore(tmp_path / "out")
    store.create()
    first, second = spec.runs()
    store.write(execute_run(spec.task, first.params, first.run_id, str(tmp_path)))
    other = execute_run(spec.task, second.params, second.run_id, str(tmp_path))
    store.write({**other, "task": "another:task"})
    todo, skipped = plan_runs(spec, store, retry_failed=False)
    assert skipped == 1 and [r.run_id for r in todo] == [second.run_id]


def test_progress_bar_counts_on_a_terminal_and_prints_lines_otherwise(
    capsys: Any,
) -> None:
    buffer = io.StringIO()
    console = Console(file=buffer, force_terminal=True, width=120)
    with SweepProgress("demo", total=3, skipped=2, console=console) as bar:
        bar.advance(True)
        bar.advance(False)
        bar.advance(True)
    assert (bar.done, bar.failed, bar.remaining) == (2, 1, 0)
    text = buffer.getvalue()
    assert "sweep demo (2 kept from before)" in text
    assert "done 2" in text and "failed 1" in text and "remaining 0" in text

    plain = Console(file=io.StringIO(), force_terminal=False)
    with SweepProgress("demo", total=20, console=plain) as lines:
        for _ in range(20):
            lines.advance(True)
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("sweep demo: started")
    assert len(err) == 11 and err[-1].startswith("sweep demo: progress: done 20, failed 0")
