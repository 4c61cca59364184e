"""Shared fixtures: one real Dask LocalCluster on loopback for the module, spec writers."""

from __future__ import annotations

import shutil
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

FAKE_TASK = Path(__file__).with_name("fake_task.py")


@pytest.fixture(scope="module")
def scheduler_address() -> Iterator[str]:
    """A real 2-worker LocalCluster (threads, loopback TCP); yields its scheduler address."""
    from distributed import LocalCluster

    cluster = LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=False,
        protocol="tcp://",
        host="127.0.0.1",
        dashboard_address=None,
    )
    try:
        yield cluster.scheduler_address
    finally:
        cluster.close()


def _write_spec(folder: Path, text: str, name: str = "spec.toml") -> Path:
    shutil.copy(FAKE_TASK, folder / "fake_task.py")
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture
def write_spec() -> Callable[..., Path]:
    """``write_spec(folder, text)``: write a spec with the fake task module beside it."""
    return _write_spec
