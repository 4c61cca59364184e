"""``kernel.compiling``: a kernel's first call runs under an exclusive lock on a file beside
its generated module, so two processes do not compile the same kernel side by side."""

from __future__ import annotations

import fcntl
import sys
import types
from pathlib import Path

import pytest

from etswarm.sim.kernel import compiling


def fake_kernel(folder: Path, name: str) -> types.SimpleNamespace:
    """A stand-in for a compiled ``run_ticks``: its ``py_func`` names a module whose file is
    ``folder/name.py``, registered in ``sys.modules`` as load_kernel registers its own."""
    source = folder / f"{name}.py"
    source.write_text("")
    module = types.ModuleType(name)
    module.__file__ = str(source)
    sys.modules[name] = module

    def run_ticks() -> None:
        return None

    run_ticks.__module__ = name
    return types.SimpleNamespace(py_func=run_ticks)


def locked_elsewhere(path: Path) -> bool:
    """True when another open file description holds an exclusive flock on ``path``."""
    with open(path, "a") as other:
        try:
            fcntl.flock(other, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            return True
        fcntl.flock(other, fcntl.LOCK_UN)
        return False


def test_the_lock_is_held_during_the_first_call_and_released_after(tmp_path: Path) -> None:
    kernel = fake_kernel(tmp_path, "_etswarm_kernel_lock_test")
    lock = tmp_path / "_etswarm_kernel_lock_test.lock"
    try:
        with compiling(kernel):
            assert lock.exists()
            assert locked_elsewhere(lock)
        assert not locked_elsewhere(lock)
    finally:
        del sys.modules["_etswarm_kernel_lock_test"]


def test_an_error_in_the_first_call_releases_the_lock(tmp_path: Path) -> None:
    kernel = fake_kernel(tmp_path, "_etswarm_kernel_lock_error")
    lock = tmp_path / "_etswarm_kernel_lock_error.lock"
    try:
        with pytest.raises(RuntimeError), compiling(kernel):
            raise RuntimeError("compile failed")
        assert not locked_elsewhere(lock)
    finally:
        del sys.modules["_etswarm_kernel_lock_error"]


def test_only_generated_kernel_modules_are_locked(tmp_path: Path) -> None:
    # a function of an ordinary module (this one) gets no lock file beside it
    here = Path(__file__)
    ran = []
    with compiling(types.SimpleNamespace(py_func=fake_kernel)):
        ran.append(True)
    assert ran == [True]
    assert not here.with_suffix(".lock").exists()
