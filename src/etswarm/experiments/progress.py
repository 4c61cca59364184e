"""The sweep's progress display on stderr: a rich bar on a terminal, plain lines otherwise."""

from __future__ import annotations

import sys
import time
from types import TracebackType
from typing import Any

from rich.console import Console
from rich.progress import (
    BarColumn,
    Progress,
    TaskID,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)


class SweepProgress:
    """Counts of runs done, failed and remaining, with the time left.

    ``total`` is the number of runs this session executes (already finished runs are
    reported as ``skipped`` and not counted, so the time estimate reflects real work).
    With ``enabled=False`` nothing is shown. When stderr is not a terminal a plain line is
    printed at every tenth of the work instead of a live bar (readable in cluster logs).
    """

    def __init__(
        self,
        name: str,
        total: int,
        skipped: int = 0,
        enabled: bool = True,
        console: Console | None = None,
    ) -> None:
        self.name = name
        self.total = total
        self.skipped = skipped
        self.enabled = enabled and total > 0
        self.console = console or Console(stderr=True)
        self.done = 0
        self.failed = 0
        self._progress: Progress | None = None
        self._task: TaskID | None = None
        self._next_line = 0.1
        self._start = time.monotonic()

    @property
    def remaining(self) -> int:
        return self.total - self.done - self.failed

    def __enter__(self) -> SweepProgress:
        self._start = time.monotonic()
        if not self.enabled:
            return self
        if self.console.is_terminal:
            self._progress = Progress(
                TextColumn("[bold]{task.description}"),
                BarColumn(),
                TextColumn(
                    "[green]done {task.fields[done]}[/] · [red]failed {task.fields[failed]}[/]"
                    " · remaining {task.fields[remaining]}"
                ),
                TextColumn("· elapsed"),
                TimeElapsedColumn(),
                TextColumn("· left"),
                TimeRemainingColumn(),
                console=self.console,
                transient=False,
            )
            self._progress.start()
            self._task = self._progress.add_task(
                self._description(), total=self.total, **self._fields()
            )
        else:
            self._line("started")
        return self

    def advance(self, ok: bool) -> None:
        """Count one finished run (``ok`` False for a recorded error)."""
        if ok:
            self.done += 1
        else:
            self.failed += 1
        if not self.enabled:
            return
        if self._progress is not None and self._task is not None:
            self._progress.update(self._task, advance=1, **self._fields())
        elif (self.done + self.failed) / self.total >= self._next_line or self.remaining == 0:
            while self._next_line <= (self.done + self.failed) / self.total:
                self._next_line += 0.1
            self._line("progress")

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        if self._progress is not None:
            self._progress.stop()
            self._progress = None

    def _description(self) -> str:
        extra = f" ({self.skipped} kept from before)" if self.skipped else ""
        return f"sweep {self.name}{extra}"

    def _fields(self) -> dict[str, Any]:
        return {"done": self.done, "failed": self.failed, "remaining": self.remaining}

    def _line(self, what: str) -> None:
        elapsed = time.monotonic() - self._start
        finished = self.done + self.failed
        left = ""
        if finished and self.remaining:
            left = f", ~{elapsed / finished * self.remaining:.0f} s left"
        print(
            f"{self._description()}: {what}: done {self.done}, failed {self.failed},"
            f" remaining {self.remaining} of {self.total} ({elapsed:.0f} s{left})",
            file=sys.stderr,
            flush=True,
        )
