"""A sweep's output folder: one JSON record per run, written atomically.

Layout of ``OUT``::

    OUT/spec.toml           the spec of the latest session (a copy)
    OUT/runs/<run_id>.json  one record per finished run (see task.execute_run)
    OUT/results.parquet     the tidy table (table.write_table)

A record file appears whole or not at all (written to a temporary file, then renamed), so
a sweep killed at any moment leaves only complete records, and a later session can trust
what it finds.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path
from typing import Any

from etswarm.errors import EtswarmError


def atomic_write_bytes(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` so readers see the old file or the new one, never half."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


class RunStore:
    """The records of one sweep output folder."""

    def __init__(self, out_dir: str | Path) -> None:
        self.out_dir = Path(out_dir)
        self.runs_dir = self.out_dir / "runs"
        self.table_path = self.out_dir / "results.parquet"
        self.spec_path = self.out_dir / "spec.toml"

    def create(self) -> None:
        """Make the folders; EtswarmError when OUT exists and is not a folder."""
        if self.out_dir.exists() and not self.out_dir.is_dir():
            raise EtswarmError(f"--out {self.out_dir}: exists and is not a folder")
        try:
            self.runs_dir.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise EtswarmError(f"--out {self.out_dir}: cannot create ({err.strerror})") from err

    def record_path(self, run_id: str) -> Path:
        return self.runs_dir / f"{run_id}.json"

    def write(self, record: dict[str, Any]) -> Path:
        """Store one run record atomically; returns its path."""
        path = self.record_path(record["run_id"])
        text = json.dumps(record, indent=1, allow_nan=False)
        atomic_write_bytes(path, (text + "\n").encode("utf-8"))
        return path

    def read(self, run_id: str) -> dict[str, Any] | None:
        """The record of ``run_id``, or None when absent or unreadable."""
        return self._load(self.record_path(run_id))

    def status(self, run_id: str) -> str | None:
        """"ok", "error", or None when the run has no (valid) record."""
        record = self.read(run_id)
        return None if record is None else record.get("status")

    def records(self) -> list[dict[str, Any]]:
        """Every valid record in the folder, ordered by file name."""
        if not self.runs_dir.is_dir():
            return []
        found = (self._load(p) for p in sorted(self.runs_dir.glob("*.json")))
        return [r for r in found if r is not None]

    @staticmethod
    def _load(path: Path) -> dict[str, Any] | None:
        try:
            record = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        if not isinstance(record, dict) or "run_id" not in record or "status" not in record:
            return None
        return record
