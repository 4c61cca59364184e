"""Test order for a cold start on two workers.

pytest-xdist's ``worksteal`` scheduler first hands each of its N workers one contiguous
slice of the collected tests (the first worker the first 1/N, and so on). From empty
caches, the first ET run a worker makes compiles the ET controller and its tick loop,
about two minutes on one core; if both workers start with ET runs, both compile the
same code side by side. So the tests that run no ET controller (shapes, measures, the
simulator's own tests, damage specs) are moved to the middle of the list: on two workers
the second one starts with them while the first compiles, and then loads the compiled
kernel from disk (:func:`etswarm.sim.kernel.compiling` makes a worker that asks while
another compiles wait for it instead). On one worker the order does not matter.
"""

from __future__ import annotations

from pathlib import Path

import pytest

#: Test folders and files (relative to ``tests/``) whose tests make no ET run.
NO_ET_RUN = ("shapes", "measures", "sim", "damage/test_spec.py", "test_compile_cache.py")


def _runs_no_et(item: pytest.Item, root: Path) -> bool:
    try:
        rel = Path(item.path).relative_to(root).as_posix()
    except ValueError:
        return False
    return any(rel == part or rel.startswith(part + "/") for part in NO_ET_RUN)


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Move the tests of :data:`NO_ET_RUN` to the middle of ``items``, in their order."""
    root = Path(__file__).parent
    light = [item for item in items if _runs_no_et(item, root)]
    if not light or len(light) == len(items):
        return
    rest = [item for item in items if not _runs_no_et(item, root)]
    middle = min(len(items) // 2, len(rest))
    items[:] = rest[:middle] + light + rest[middle:]
