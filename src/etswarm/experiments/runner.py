"""Run a sweep on Dask: every (point, seed) a future, each record stored as it arrives.

By default the runs execute on a ``distributed.LocalCluster`` started here (one process
per core, one thread each, loopback only); with ``scheduler`` they go to an existing
cluster. Records are written by this process (the client), so workers need no access to
the output folder. Runs whose record exists (made by the same task) are skipped; failed
ones rerun only with ``retry_failed``. On Ctrl-C (SIGINT) or SIGTERM the pending futures
are cancelled, the table is written from what finished and the cluster is closed; the
outcome says so.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import logging
import os
import signal
import threading
import time
import traceback
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from distributed import Client, LocalCluster, as_completed
from distributed.diagnostics.plugin import WorkerPlugin

from etswarm.errors import EtswarmError
from etswarm.experiments.progress import SweepProgress
from etswarm.experiments.spec import Run, SweepSpec
from etswarm.experiments.store import RunStore, atomic_write_bytes
from etswarm.experiments.table import build_table, write_table
from etswarm.experiments.task import error_record, execute_run, resolve_task

POLL_S = 0.1  # s between looks for finished runs and for an interrupt


@dataclass(frozen=True)
class SweepOutcome:
    """What a sweep session did.

    ``total`` runs in the spec; ``skipped`` had a record already; ``ran`` finished in this
    session, ``failed`` of them with an error; ``pending`` were not finished (interrupted);
    ``kept`` runs of the spec have a record now; ``table`` is the Parquet file.
    """

    out_dir: Path
    total: int
    skipped: int
    ran: int
    failed: int
    pending: int
    kept: int
    interrupted: bool
    table: Path


class _IgnoreSigint(WorkerPlugin):
    """Make a local worker process ignore Ctrl-C: the client handles it and shuts it down.

    A terminal sends SIGINT to every process of the foreground group, workers included;
    without this they would die mid-task while the client is still collecting results.
    Only applies in a worker's own process (main thread), never in the client.
    """

    def __init__(self) -> None:
        self.client_pid = os.getpid()

    def setup(self, worker: Any) -> None:
        in_main_thread = threading.current_thread() is threading.main_thread()
        if in_main_thread and os.getpid() != self.client_pid:
            signal.signal(signal.SIGINT, signal.SIG_IGN)


def plan_runs(spec: SweepSpec, store: RunStore, retry_failed: bool) -> tuple[list[Run], int]:
    """The runs to execute now, and how many are skipped because their record exists."""
    todo: list[Run] = []
    skipped = 0
    for run in spec.runs():
        status = _status(store, run, spec.task)
        if status == "ok" or (status == "error" and not retry_failed):
            skipped += 1
        else:
            todo.append(run)
    return todo, skipped


def _status(store: RunStore, run: Run, task: str) -> str | None:
    """The status of ``run``'s record, None when absent or made by another task."""
    record = store.read(run.run_id)
    if record is None or record.get("task", task) != task:
        return None
    return record.get("status")


def check_task(spec: SweepSpec) -> None:
    """Fail early, on the client, when the task cannot be imported or rejects a parameter.

    A task function may declare the parameter names it accepts in a ``parameters``
    attribute (any collection of str); unknown names are then a spec error.
    """
    try:
        func = resolve_task(spec.task, spec.path.parent)
    except EtswarmError as err:
        raise EtswarmError(f"{spec.path}: sweep.task: {err}") from err
    accepted = getattr(func, "parameters", None)
    if accepted is None:
        return
    for point in spec.points:
        for name in point:
            if name not in accepted:
                known = ", ".join(sorted(accepted))
                raise EtswarmError(
                    f"{spec.path}: {name}: not a parameter of {spec.task} (known: {known})"
                )


@dataclass
class Interrupts:
    """The signals a sweep received (``seen``, signal numbers in order); while ``armed``,
    a second one raises KeyboardInterrupt."""

    seen: list[int] = field(default_factory=list)
    armed: bool = False


@contextlib.contextmanager
def interrupt_signals() -> Iterator[Interrupts]:
    """While inside, Ctrl-C (SIGINT) and SIGTERM (a batch system's time limit, ``kill``)
    are recorded in the yielded ``Interrupts``; a second one raises KeyboardInterrupt
    while it is ``armed``.

    The first signal does not raise: an exception raised at an arbitrary point can land
    in library cleanup (a Dask future's ``__del__``), where Python prints it with a
    traceback and carries on. The sweep polls for it instead and stops in its own time.
    A second signal means the user will not wait, so it raises, but only while the sweep
    is armed (collecting results): raised while a cluster starts or closes, it leaves
    Dask a half-made cluster to close at exit, with a traceback. Only in the main thread
    (signal handlers cannot be set elsewhere); the previous handlers are restored on exit.
    """
    interrupts = Interrupts()
    if threading.current_thread() is not threading.main_thread():
        yield interrupts
        return

    def interrupt(signum: int, frame: Any) -> None:
        interrupts.seen.append(signum)
        if interrupts.armed and len(interrupts.seen) > 1:
            raise KeyboardInterrupt(f"signal {signum}")

    previous = {sig: signal.signal(sig, interrupt) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield interrupts
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)


@contextlib.contextmanager
def dask_client(scheduler: str | None, workers: int | None) -> Iterator[Client]:
    """A client on ``scheduler``, or on a new loopback LocalCluster of ``workers`` processes."""
    if scheduler is not None:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as err:
            raise EtswarmError(f"--scheduler {scheduler}: cannot connect ({err})") from err
        try:
            yield client
        finally:
            client.close()
        return
    n_workers = workers or os.cpu_count() or 1
    cluster = LocalCluster(
        n_workers=n_workers,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        dashboard_address=None,
        silence_logs=logging.CRITICAL,  # shutdown races log comm errors with tracebacks
    )
    try:
        client = Client(cluster)
        try:
            client.register_plugin(_IgnoreSigint(), name="etswarm-ignore-sigint")
            yield client
        finally:
            client.close()
    finally:
        cluster.close()


def run_sweep(
    spec: SweepSpec,
    out_dir: str | Path,
    *,
    scheduler: str | None = None,
    workers: int | None = None,
    retry_failed: bool = False,
    show_progress: bool = True,
    client: Client | None = None,
) -> SweepOutcome:
    """Execute the runs of ``spec`` that have no record in ``out_dir``; write the table.

    ``scheduler`` is a Dask scheduler address (``tcp://host:8786``); without it a local
    cluster of ``workers`` processes (default: every core) is started and closed here;
    with ``client`` (a connected distributed.Client) that client is used and left open.
    Returns the outcome; an interrupt (Ctrl-C) is caught and reported as
    ``interrupted=True`` after the table is written.
    """
    if workers is not None and workers < 1:
        raise EtswarmError(f"--workers {workers}: must be at least 1")
    if workers is not None and scheduler is not None:
        raise EtswarmError("--workers applies to the local cluster only, not with --scheduler")
    check_task(spec)
    store = RunStore(out_dir)
    store.create()
    if spec.path.is_file():
        atomic_write_bytes(store.spec_path, spec.path.read_bytes())
    todo, skipped = plan_runs(spec, store, retry_failed)
    ran = failed = 0
    interrupted = False
    if todo:
        search_dir = str(spec.path.parent.resolve())
        progress = SweepProgress(spec.name, len(todo), skipped, enabled=show_progress)
        try:
            session = (
                contextlib.nullcontext(client)
                if client is not None
                else dask_client(scheduler, workers)
            )
            with interrupt_signals() as interrupts, session as client, progress:
                by_key: dict[Any, Run] = {}
                pending: dict[Any, Any] = {}  # key -> future; dropped once stored
                for run in todo:
                    future = client.submit(
                        execute_run,
                        spec.task,
                        run.params,
                        run.run_id,
                        search_dir,
                        key=f"etswarm-run-{run.run_id}",
                        pure=False,
                    )
                    by_key[future.key] = run
                    pending[future.key] = future
                interrupts.armed = True
                try:
                    finished = as_completed(list(pending.values()))
                    while not finished.is_empty() and not interrupts.seen:
                        batch = finished.next_batch(block=False)
                        if not batch:
                            time.sleep(POLL_S)
                            continue
                        for future in batch:
                            pending.pop(future.key, None)  # frees the result on the cluster
                            record = _collect(future, by_key[future.key], spec.task)
                            if record is None:
                                continue
                            store.write(record)
                            ok = record["status"] == "ok"
                            ran += 1
                            failed += 0 if ok else 1
                            progress.advance(ok)
                except KeyboardInterrupt:
                    interrupted = True
                interrupts.armed = False
                if interrupts.seen or interrupted:
                    client.cancel(list(pending.values()))
                interrupted = interrupted or bool(interrupts.seen)
        except KeyboardInterrupt:
            interrupted = True
    table = write_results(spec, store)
    kept = sum(1 for run in spec.runs() if _status(store, run, spec.task) is not None)
    return SweepOutcome(
        out_dir=store.out_dir,
        total=len(spec.runs()),
        skipped=skipped,
        ran=ran,
        failed=failed,
        pending=len(todo) - ran,
        kept=kept,
        interrupted=interrupted,
        table=table,
    )


def _collect(future: Any, run: Run, task: str) -> dict[str, Any] | None:
    """The record of a finished future; None when it was cancelled (not a result)."""
    if future.status == "cancelled":
        return None
    try:
        record = future.result()
    except concurrent.futures.CancelledError:
        return None
    except Exception as err:  # the worker died or the future was lost: still a result
        return error_record(task, run.params, run.run_id, err, traceback.format_exc())
    return record


def write_results(spec: SweepSpec, store: RunStore) -> Path:
    """Write ``results.parquet`` from the records of the spec's runs; returns its path."""
    records = [
        r
        for run in spec.runs()
        if (r := store.read(run.run_id)) is not None and r.get("task", spec.task) == spec.task
    ]
    frame = build_table(records, spec.parameters)
    meta = {
        "sweep": spec.name,
        "task": spec.task,
        "parameters": list(spec.parameters),
        "swept": list(spec.swept),
        "spec": str(spec.path.resolve()),
    }
    return write_table(frame, store.table_path, meta)
