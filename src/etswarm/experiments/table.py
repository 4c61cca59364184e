"""The tidy results table: one row per run, one column per parameter or scalar measure.

Columns, in order: ``run_id``, the parameters (``seed`` last), ``status``, ``error``, then
every scalar measure of the run summary, then ``wall_time_s`` (the task call, seconds),
``version`` (etswarm on the worker) and ``host``.

Nested summaries are flattened:

- a dict becomes ``key.sub`` columns (``states.Stable``);
- ``components`` (a list of per-remnant dicts) becomes ``n_components``,
  ``components_formed``, ``component_jaccard_min``/``_mean``, ``census_error_mean``
  (census count minus the remnant's robots, averaged), ``census_error_max_abs`` and
  ``reform_time_s`` (the slowest remnant's ``time_to_stable_s``; empty when one never
  stabilised) and ``stretched_links`` (summed over the remnants; empty for summaries
  older than the measure);
- ``events`` (a list of ``{t_s, kind, ...}``) becomes ``n_events`` and ``events.<kind>``
  counts; any other list becomes ``n_<key>``.

A measure whose name is already a parameter or a bookkeeping column (``robots`` when the
spec sets ``robots``) is stored as ``result.<name>``, and dropped when it equals that
column in every row. Which columns are parameters is kept in the Parquet metadata
(key ``etswarm``), so a report can tell parameters from measures.
"""

from __future__ import annotations

import io
import json
import math
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from etswarm.errors import EtswarmError
from etswarm.experiments.store import RunStore, atomic_write_bytes

BOOKKEEPING = ("run_id", "status", "error", "wall_time_s", "version", "host")
_META_KEY = b"etswarm"


def flatten_summary(summary: dict[str, Any] | None) -> dict[str, Any]:
    """The scalar measures of one run summary as a flat ``{column: value}`` dict."""
    flat: dict[str, Any] = {}
    if not summary:
        return flat
    for key, value in summary.items():
        if key == "components" and isinstance(value, list):
            flat.update(_component_measures(value))
        elif key == "events" and isinstance(value, list):
            flat.update(_event_measures(value))
        elif isinstance(value, dict):
            for sub, sub_value in _flatten_dict(value, key).items():
                flat[sub] = sub_value
        elif isinstance(value, list):
            flat[f"n_{key}"] = len(value)
        else:
            flat[key] = value
    return flat


def _flatten_dict(value: dict[str, Any], prefix: str) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, sub in value.items():
        name = f"{prefix}.{key}"
        if isinstance(sub, dict):
            out.update(_flatten_dict(sub, name))
        elif isinstance(sub, list):
            out[f"{name}.n"] = len(sub)
        else:
            out[name] = sub
    return out


def _number(value: Any) -> float | None:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    return float(value) if math.isfinite(value) else None


def _component_measures(components: list[Any]) -> dict[str, Any]:
    comps = [c for c in components if isinstance(c, dict)]
    jaccards = [j for c in comps if (j := _number(c.get("jaccard"))) is not None]
    census_errors = [
        float(c["census_count"]) - float(c["robots"])
        for c in comps
        if _number(c.get("census_count")) is not None and _number(c.get("robots")) is not None
    ]
    stable_times = [_number(c.get("time_to_stable_s")) for c in comps]
    links = [n for c in comps if (n := _number(c.get("stretched_links"))) is not None]
    out: dict[str, Any] = {
        "n_components": len(comps),
        "components_formed": sum(1 for c in comps if c.get("formed") is True),
        "component_jaccard_min": min(jaccards) if jaccards else None,
        "component_jaccard_mean": sum(jaccards) / len(jaccards) if jaccards else None,
        "census_error_mean": (
            sum(census_errors) / len(census_errors) if census_errors else None
        ),
        "census_error_max_abs": max(abs(e) for e in census_errors) if census_errors else None,
        "reform_time_s": (
            max(t for t in stable_times if t is not None)
            if stable_times and all(t is not None for t in stable_times)
            else None
        ),
        "stretched_links": int(sum(links)) if links else None,
    }
    return out


def _event_measures(events: list[Any]) -> dict[str, Any]:
    out: dict[str, Any] = {"n_events": len(events)}
    for event in events:
        if isinstance(event, dict) and isinstance(event.get("kind"), str):
            name = f"events.{event['kind']}"
            out[name] = out.get(name, 0) + 1
    return out


def record_row(record: dict[str, Any], parameters: Sequence[str]) -> dict[str, Any]:
    """One table row (a flat dict) from one run record."""
    params = record.get("params") or {}
    row: dict[str, Any] = {"run_id": record.get("run_id")}
    for name in parameters:
        row[name] = _cell(params.get(name))
    row["status"] = record.get("status")
    row["error"] = record.get("error")
    taken = set(row) | set(BOOKKEEPING)
    for name, value in flatten_summary(record.get("summary")).items():
        row[f"result.{name}" if name in taken else name] = _cell(value)
    for name in ("wall_time_s", "version", "host"):
        row[name] = record.get(name)
    return row


def _cell(value: Any) -> Any:
    """Lists (e.g. damage) become their JSON text so every cell is a scalar."""
    if isinstance(value, list | dict):
        return json.dumps(value, separators=(", ", ": "))
    return value


def build_table(
    records: Iterable[dict[str, Any]], parameters: Sequence[str] | None = None
) -> pd.DataFrame:
    """The tidy table of ``records``; ``parameters`` default to every params key seen."""
    records = list(records)
    if parameters is None:
        seen: dict[str, None] = {}
        for record in records:
            seen.update(dict.fromkeys(record.get("params") or {}))
        seen.pop("seed", None)
        parameters = [*seen, "seed"] if records else []
    rows = [record_row(r, parameters) for r in records]
    frame = pd.DataFrame.from_records(rows)
    if frame.empty:
        return pd.DataFrame(columns=["run_id", *parameters, "status", "error", *BOOKKEEPING[3:]])
    tail = [c for c in ("wall_time_s", "version", "host") if c in frame.columns]
    frame = frame[[c for c in frame.columns if c not in tail] + tail]
    for column in [c for c in frame.columns if c.startswith("result.")]:
        base = column.removeprefix("result.")
        if base in frame.columns and _same(frame[column], frame[base]):
            frame = frame.drop(columns=column)
    for column in frame.columns:
        frame[column] = _harmonize(frame[column])
    return frame.convert_dtypes()


def _harmonize(column: pd.Series) -> pd.Series:
    """A column mixing text with numbers (robots = 20 and "auto") becomes all text."""
    kinds = {
        "number" if isinstance(v, int | float) and not isinstance(v, bool) else type(v).__name__
        for v in column.dropna()
    }
    if len(kinds) <= 1:
        return column
    return column.map(lambda v: None if v is None or v is pd.NA else str(v))


def _same(measure: pd.Series, parameter: pd.Series) -> bool:
    """True when ``measure`` only repeats ``parameter`` (missing measures say nothing)."""
    equal = measure.isna() | (measure.astype(object) == parameter.astype(object))
    return bool(equal.fillna(False).all())


def write_table(frame: pd.DataFrame, path: str | Path, meta: dict[str, Any]) -> Path:
    """Write ``frame`` to Parquet atomically, with ``meta`` stored as JSON under 'etswarm'."""
    path = Path(path)
    table = pa.Table.from_pandas(frame, preserve_index=False)
    metadata = dict(table.schema.metadata or {})
    metadata[_META_KEY] = json.dumps(meta).encode("utf-8")
    table = table.replace_schema_metadata(metadata)
    buffer = io.BytesIO()
    pq.write_table(table, buffer)
    atomic_write_bytes(path, buffer.getvalue())
    return path


def read_table(results: str | Path) -> tuple[pd.DataFrame, dict[str, Any]]:
    """Load a results table and its metadata from a Parquet file or a sweep output folder.

    For a folder, the table is rebuilt from ``runs/*.json`` when there is no
    ``results.parquet`` or when records are newer than it (a sweep that was killed).
    """
    path = Path(results)
    if path.is_dir():
        store = RunStore(path)
        parquet = store.table_path
        newest = max((p.stat().st_mtime for p in store.runs_dir.glob("*.json")), default=None)
        if parquet.is_file() and (newest is None or parquet.stat().st_mtime >= newest):
            return _read_parquet(parquet)
        records = store.records()
        if not records:
            raise EtswarmError(f"{path}: no results.parquet and no run records in runs/")
        meta: dict[str, Any] = {}
        if parquet.is_file():
            meta = _read_parquet(parquet)[1]
        frame = build_table(records, meta.get("parameters"))
        return frame, meta
    if not path.is_file():
        raise EtswarmError(f"{path}: no such results file or sweep folder")
    return _read_parquet(path)


def _read_parquet(path: Path) -> tuple[pd.DataFrame, dict[str, Any]]:
    try:
        table = pq.read_table(path)
    except (OSError, pa.ArrowException) as err:
        raise EtswarmError(f"{path}: not a readable Parquet file ({err})") from err
    raw = (table.schema.metadata or {}).get(_META_KEY)
    meta = json.loads(raw) if raw else {}
    return table.to_pandas().convert_dtypes(), meta
