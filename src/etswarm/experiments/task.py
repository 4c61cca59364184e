"""The task side of a sweep: find the task function and run it once, recording the outcome.

A task is any importable function ``f(params: dict) -> dict`` whose result is JSON-able.
``execute_run`` is what a Dask worker runs: it never raises for a failing task; it returns a
record with ``status`` "ok" (and the summary) or "error" (and the one-line message and the
traceback), so a crash is data, not a lost sweep.
"""

from __future__ import annotations

import datetime as dt
import importlib
import json
import math
import socket
import sys
import time
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Any

import etswarm
from etswarm.errors import EtswarmError

TaskFunction = Callable[[dict[str, Any]], dict[str, Any]]


def resolve_task(ref: str, search_dir: str | Path | None = None) -> TaskFunction:
    """Import ``module:function`` and return the function.

    When the module cannot be imported and ``search_dir`` is given (the spec's folder), the
    folder is put on ``sys.path`` and the import tried again, so a task module may sit next
    to its spec. Raises EtswarmError naming ``ref`` when it cannot be found or called.
    """
    module_name, _, func_name = ref.partition(":")
    try:
        module = _import(module_name, search_dir)
    except ImportError as err:
        raise EtswarmError(f"task {ref!r}: cannot import {module_name} ({err})") from err
    func = getattr(module, func_name, None)
    if not callable(func):
        raise EtswarmError(f"task {ref!r}: {module_name} has no function {func_name}")
    return func


def _import(module_name: str, search_dir: str | Path | None) -> Any:
    try:
        return importlib.import_module(module_name)
    except ModuleNotFoundError as err:
        missing_is_ours = err.name is not None and module_name.split(".")[0] == err.name
        if search_dir is None or not missing_is_ours:
            raise
        folder = str(Path(search_dir).resolve())
        if folder not in sys.path:
            sys.path.append(folder)
        return importlib.import_module(module_name)


def execute_run(
    task_ref: str, params: dict[str, Any], run_id: str, search_dir: str | None = None
) -> dict[str, Any]:
    """Run one task and return its record (JSON-able); never raises for task errors.

    The record holds ``run_id``, ``status`` ("ok" or "error"), ``params``, ``summary`` (the
    task's dict, or None), ``error`` (one line, or None), ``traceback`` (text, or None),
    ``wall_time_s`` (task call, seconds), ``version`` (etswarm.__version__ on the worker),
    ``task``, ``host`` and ``finished_at`` (UTC ISO time).
    """
    start = time.perf_counter()
    summary: dict[str, Any] | None = None
    error: str | None = None
    trace: str | None = None
    try:
        func = resolve_task(task_ref, search_dir)
        result = func(dict(params))
        if not isinstance(result, dict):
            raise TypeError(f"task returned {type(result).__name__}, expected a dict")
        summary = json.loads(json.dumps(_jsonable(result), allow_nan=False))
    except (Exception, SystemExit) as err:  # a task calling sys.exit is a failed run too
        error = one_line(err)
        trace = traceback.format_exc()
    wall = time.perf_counter() - start
    return {
        "run_id": run_id,
        "status": "ok" if error is None else "error",
        "params": params,
        "summary": summary,
        "error": error,
        "traceback": trace,
        "wall_time_s": wall,
        "version": etswarm.__version__,
        "task": task_ref,
        "host": socket.gethostname(),
        "finished_at": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
    }


def error_record(
    task_ref: str, params: dict[str, Any], run_id: str, err: BaseException, trace: str
) -> dict[str, Any]:
    """The record of a run that failed outside the task (worker died, future lost...)."""
    return {
        "run_id": run_id,
        "status": "error",
        "params": params,
        "summary": None,
        "error": one_line(err),
        "traceback": trace,
        "wall_time_s": None,
        "version": etswarm.__version__,
        "task": task_ref,
        "host": None,
        "finished_at": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
    }


def one_line(err: BaseException) -> str:
    """``Type: message`` on one line, at most 300 characters."""
    message = " ".join(str(err).split())
    text = f"{type(err).__name__}: {message}" if message else type(err).__name__
    return text if len(text) <= 300 else text[:297] + "..."


def _jsonable(value: Any) -> Any:
    """Turn numpy scalars/arrays, tuples and non-finite floats into plain JSON values."""
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if hasattr(value, "tolist") and callable(value.tolist):  # numpy scalar or array
        return _jsonable(value.tolist())
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
