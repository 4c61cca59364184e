"""The tick loop's work without numba's reference counting frees all it allocates.

The controller's per-robot work and the simulator's phases are compiled with ``_nrt=False``
(no reference counting; see ``controller.busy_part``, ``radio.deliver``,
``motion.move_phase``, ``collide.resolve_overlaps``). A function compiled so that receives
an array a callee allocated would never free it, so the few functions that allocate, and
those that take an allocated array back, keep the counting (``_nrt=True``). This runs a
formation, a split and both censuses (the walk's count floods a grid per step) with numba's
allocation statistics on, and checks that every allocation the compiled code made was freed.
"""

from __future__ import annotations

import gc
import importlib
import inspect
import pkgutil
import re

import pytest
from numba.core.registry import CPUDispatcher as Dispatcher
from numba.core.runtime import _nrt_python, rtsys

import etswarm.algorithm
import etswarm.sim
from etswarm.algorithm.params import ETParams
from etswarm.algorithm.run import ETRun, RunConfig

from .traced import SESSION_34_FORMATION


@pytest.mark.parametrize("census", ["walk", "tree"])
def test_a_regeneration_frees_every_compiled_allocation(census: str) -> None:
    config = RunConfig(
        shape="triangle", seed=9, max_time_s=3 * 3600, damage=("split x=0 at=formed+30",),
        census=census, et=ETParams(**SESSION_34_FORMATION),
    )
    ETRun(config).run()  # compiled before the statistics start
    _nrt_python.memsys_enable_stats()
    try:
        gc.collect()
        before = rtsys.get_allocation_stats()
        run = ETRun(config)
        summary = run.run()
        del run
        gc.collect()
        after = rtsys.get_allocation_stats()
    finally:
        _nrt_python.memsys_disable_stats()
    censuses = [e for e in summary["events"] if e["kind"] == "census"]
    assert len(censuses) == 2 and all(e["method"] == census for e in censuses)
    # the loop allocated its scratch rows every tick and freed them all
    assert after.alloc - before.alloc > 10_000
    assert after.alloc - after.free == before.alloc - before.free


ALLOCATES = re.compile(r"np\.(empty|zeros|ones|full|array|arange|concatenate)\(|\.copy\(\)")


def compiled_functions() -> list[tuple[str, Dispatcher]]:
    """Every numba function defined in the simulator's and the algorithm's modules."""
    found = []
    for package in (etswarm.sim, etswarm.algorithm):
        for info in pkgutil.iter_modules(package.__path__):
            module = importlib.import_module(f"{package.__name__}.{info.name}")
            for name, value in vars(module).items():
                if isinstance(value, Dispatcher) and value.py_func.__module__ == module.__name__:
                    found.append((f"{module.__name__}.{name}", value))
    return found


def test_every_compiled_function_that_allocates_keeps_the_counting() -> None:
    # Reference counting is inherited from the caller unless a function sets it: one
    # that allocates inside a function compiled without it would not compile, or leak.
    functions = compiled_functions()
    assert len(functions) > 150
    allocating = [
        (name, f) for name, f in functions if ALLOCATES.search(inspect.getsource(f.py_func))
    ]
    assert {"etswarm.algorithm.controller.busy_robots", "etswarm.sim.radio.radio_phase"} <= {
        name for name, _ in allocating
    }
    unmarked = [name for name, f in allocating if f.targetoptions.get("_nrt") is not True]
    assert unmarked == []
    bare = {name for name, f in functions if f.targetoptions.get("_nrt") is False}
    assert bare == {
        "etswarm.algorithm.controller.busy_part",
        "etswarm.sim.radio.deliver",
        "etswarm.sim.motion.move_phase",
        "etswarm.sim.collide.resolve_overlaps",
    }
